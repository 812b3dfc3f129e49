#!/usr/bin/env bash
# End-to-end: import and export through the real orogen binary, proven by readers
# nobody here wrote: GDAL (gdalinfo, gdallocationinfo) and OpenImageIO (iinfo,
# oiiotool). Usage: e2e_interchange.sh OROGEN TESTS_DIR
set -u
orogen=$1
tests=$2
work=$(mktemp -d "${TMPDIR:-/tmp}/orogen-e2e-ix-XXXXXX")
trap '[ -n "${KEEP:-}" ] || rm -rf "$work"' EXIT
failures=0
passes=0
kauai=$tests/data/dem/N22W160.hgt
vermont=$tests/data/dem/N44W072.hgt

check() { # name, condition already evaluated as $?
    if [ "$2" = 0 ]; then passes=$((passes + 1)); else echo "FAIL: $1"; failures=$((failures + 1)); fi
}
run() { # captures stdout, stderr and status of orogen
    "$orogen" "$@" >"$work/out" 2>"$work/err"
    status=$?
}
same() { # two numbers equal within $3
    python3 -c "import sys; sys.exit(0 if abs(float('$1') - float('$2')) <= $3 else 1)"
}
pixel() { # FILE X Y: the value OpenImageIO reads at column X, row Y
    oiiotool "$1" --cut "1x1+$2+$3" -o "$work/pixel.tif" >/dev/null 2>&1 &&
        oiiotool --dumpdata "$work/pixel.tif" | sed -n 's/.*Pixel (0, 0): *\([-0-9.e+]*\).*/\1/p'
}

for tool in gdallocationinfo gdalinfo oiiotool iinfo python3 sqlite3; do
    command -v $tool >/dev/null || { echo "FAIL: $tool is missing (scripts/install-deps.sh)"; exit 1; }
done

# 1. SRTM at one world sample per raster sample: heights equal what GDAL reads.
points="0 0
17 5
600 600
1200 1200
250 911
1000 42
733 377"
cmds="new flat from=$vermont spacing=30"
while read -r c r; do cmds="$cmds; sample $((c * 30)) $((r * 30))"; done <<<"$points"
run -c "$cmds"
check "import the Vermont .hgt" $status
grep -q "imported $vermont: 3601 x 3601\|imported $vermont: 1201 x 1201" "$work/out"
check "import reports the source size" $?
i=0
ok=0
while read -r c r; do
    want=$(gdallocationinfo -valonly "$vermont" "$c" "$r")
    got=$(grep -E '^-?[0-9]+\.[0-9]+$' "$work/out" | sed -n "$((i + 1))p")
    if [ "$want" != -32768 ]; then same "$got" "$want" 0 || { ok=1; echo "  ($c, $r): got $got, GDAL $want"; }; fi
    i=$((i + 1))
done <<<"$points"
check "imported heights equal gdallocationinfo at sample points" $ok

# 2. Geographic spacing: degrees become metres at the tile's centre latitude, and
# row 0 (north) samples land exactly on the world grid along x.
run -c "new flat from=$kauai; sample 0 0; sample $(python3 -c 'print(85.74684706448636*300)') 0"
check "import the Kauai .hgt at its own spacing" $status
grep -q "85.747 x 92.281 m at latitude 22.5000" "$work/out"; check "degree spacing converted at the centre latitude" $?
voids=$(python3 -c "
import struct
d = open('$kauai', 'rb').read()
print(sum(1 for (v,) in struct.iter_unpack('>h', d) if v == -32768))")
[ "$voids" -gt 0 ] && grep -q "; $voids voids filled;" "$work/out"
check "Kauai's $voids voids are filled and counted" $?
got=$(grep -E '^-?[0-9]+\.[0-9]+$' "$work/out" | sed -n 2p)
same "$got" "$(gdallocationinfo -valonly "$kauai" 300 0)" 0.001; check "geographic import: value at (300, 0)" $?

# 2b. An ESRI ASCII grid through GDAL: its cell size is the spacing, its nodata a void.
printf 'ncols 4\nnrows 3\nxllcorner 1000\nyllcorner 2000\ncellsize 10\nNODATA_value -9999\n1 2 3 4\n5 -9999 7 8\n9 10 11 12\n' >"$work/grid.asc"
run -c "new flat; set spacing 10; generate; import $work/grid.asc; sample 30 0; sample 0 20; sample 10 10"
check "import an ESRI ASCII grid" $status
grep -q "grid.asc: 4 x 3 samples (AAIGrid .*10 x 10 m per sample), 10 x 10 m apart.* 1 voids filled" "$work/out"
check "the grid's cell size is the spacing and its nodata cell a filled void" $?
vals=($(grep -E '^-?[0-9]+\.[0-9]+$' "$work/out"))
same "${vals[0]}" 4 0 && same "${vals[1]}" 9 0; check "ASCII grid values land row 0 first (4 at x=30, 9 at z=20)" $?
python3 -c "import sys; v=float('${vals[2]}'); sys.exit(0 if 1 < v < 12 else 1)"; check "the void is filled from its neighbours (${vals[2]})" $?

# 3. Export: every format, read back by GDAL and OpenImageIO at true scale.
run -c "new flat from=$vermont spacing=30; export $work/v.tif; export $work/v.exr; export $work/v.png; export $work/v16.tif bits=16; export $work/v.r16; sample 3000 6000"
check "export tif, exr, png, 16-bit tif and r16" $status
h=$(tail -n 1 "$work/out")
gdalinfo "$work/v.tif" >"$work/gdalinfo" 2>&1
grep -q "Size is 3601, 3601\|Size is 1201, 1201" "$work/gdalinfo"; check "gdalinfo: size" $?
# A world made from the DEM keeps its place: the GeoTIFF has the DEM's geotransform
# (e2e_georef.sh checks corners and coordinate systems in full).
grep -q "Pixel Size = (0.000833333333333,-0.000833333333333)" "$work/gdalinfo"; check "gdalinfo: the DEM's pixels" $?
grep -q "Origin = (-72.000416666666666,45.000416666666666)" "$work/gdalinfo"; check "gdalinfo: the DEM's origin" $?
# Without georeferencing: local metres, north-up, the origin half a sample out.
run -c "new flat; set generator flat; set size 300; set spacing 30; generate; export $work/local.tif region=0,0,3000,3000"
gdalinfo "$work/local.tif" >"$work/gdalinfo" 2>&1
grep -q "Pixel Size = (30.000000000000000,-30.000000000000000)" "$work/gdalinfo"; check "gdalinfo: 30 m pixels" $?
grep -q "Origin = (-15.000000000000000,15.000000000000000)" "$work/gdalinfo"; check "gdalinfo: origin half a sample out" $?
same "$(gdallocationinfo -valonly "$work/v.tif" 100 200)" "$h" 0; check "gdallocationinfo on the GeoTIFF equals sample" $?
iinfo "$work/v.exr" | grep -q "1 channel, float openexr"; check "iinfo: EXR is one float channel" $?
oiiotool --info -v "$work/v.exr" | grep -q "channel list: Y"; check "EXR channel is named Y" $?
same "$(pixel "$work/v.exr" 100 200)" "$h" 0; check "oiiotool reads the EXR height" $?
iinfo "$work/v.png" | grep -q "1 channel, uint16 png"; check "iinfo: PNG is 16-bit grey" $?
iinfo "$work/v16.tif" | grep -q "1 channel, uint16 tiff"; check "iinfo: 16-bit TIFF" $?
scale=$(python3 -c "import json; print(json.load(open('$work/v.png.json'))['height_scale'])")
offset=$(python3 -c "import json; print(json.load(open('$work/v.png.json'))['height_offset'])")
raw=$(pixel "$work/v.png" 100 200)
same "$(python3 -c "print($raw * $scale + $offset)")" "$h" "$(python3 -c "print($scale / 2 + 1e-9)")"
check "PNG16 x sidecar scale + offset gives the height" $?
[ "$(stat -c %s "$work/v.r16")" = $(($(python3 -c "import json; d=json.load(open('$work/v.r16.json')); print(d['width']*d['height'])") * 2)) ]
check "R16 is width x height x 2 bytes" $?

# 4. Round trips: 16-bit files come back to the same bytes, float ones bit-exactly.
for f in v.r16 v.png v16.tif; do
    ext=${f##*.}
    run -c "new flat from=$work/$f; export $work/again.$ext $( [ "$f" = v16.tif ] && echo bits=16 ) scale=$scale offset=$offset"
    check "re-import $f" $status
    grep -q "^new flat world of .* samples, 30 m apart" "$work/out"; check "$f: the sidecar's spacing comes back" $?
    cmp -s "$work/$f" "$work/again.$ext" || oiiotool --diff "$work/$f" "$work/again.$ext" >/dev/null 2>&1
    check "$f: import -> export is lossless" $?
done
for f in v.exr v.tif; do
    run -c "new flat from=$work/$f; export $work/again.${f##*.}"
    check "re-import $f" $status
    idiff -fail 0 -failpercent 0 "$work/$f" "$work/again.${f##*.}" >/dev/null 2>&1
    check "$f: float round trip is bit-exact" $?
done

# 5. Placement, blending and undo.
run -c "new flat; set generator flat; set base_height 10; set spacing 30; generate; import $work/v.exr x=900 z=1800; sample 900 1800; sample 899 1800; undo; sample 900 1800"
check "import onto a flat world at x, z" $status
first=$(gdallocationinfo -valonly "$work/v.tif" 0 0)
vals=($(grep -E '^-?[0-9]+\.[0-9]+$' "$work/out"))
same "${vals[0]}" "$first" 0.001; check "row 0, column 0 lands at x, z" $?
same "${vals[2]}" 10 0; check "undo removes the import" $?
run -c "new flat; set generator flat; set base_height 10; set spacing 30; generate; import $work/v.exr x=0 z=0 blend=add; sample 0 0"
same "$(tail -n 1 "$work/out")" "$(python3 -c "print($first + 10)")" 0.001; check "blend=add adds to the terrain" $?
# anchor=centre on an even size (403 x 344): the middle sample (201, 172) lands at x, z
# on whole samples, so export of the same place gives the same image back.
oiiotool --pattern noise:type=uniform:min=0:max=1 403x344 1 -d uint16 -o "$work/even.png"
run -c "import $work/even.png scale=1 offset=0 x=500 z=500 anchor=centre; export $work/even_back.png region=98,156,902,842 scale=1 offset=0"
grep -q "placed at 98, 156 .. 902, 842 m on the coarse layer (138632 samples)" "$work/out" && idiff "$work/even.png" "$work/even_back.png" >/dev/null
check "anchor=centre on a 403 x 344 raster: every row and column placed on whole samples and back unchanged" $?

# 6. RAW sizes: inferred squares, and a clear error naming sizes that fit.
head -c 20000 /dev/zero >"$work/odd.r16"
run -c "new flat; import $work/odd.r16 min=0 max=100"
[ $status = 0 ] && grep -q "odd.r16: 100 x 100 samples (RAW uint16 little-endian)" "$work/out"
check "a RAW of 10000 samples is read as 100 x 100" $?
head -c 20002 /dev/zero >"$work/odd.r16"
run -c "new flat; import $work/odd.r16"
[ $status = 1 ] && grep -q "odd.r16: 10001 uint16 samples is not a square; give width= and height= (sizes that fit: 137x73" "$work/err"
check "non-square RAW: error lists sizes that fit" $?
run -c "new flat; import $work/odd.r16 width=137"
check "width= reads a non-square RAW" $status

# 7. Bad input: a clear error naming the file, and the world unchanged.
area='hash 0 0 2000 2000'
run -c "$area"; before=$(cat "$work/out")
printf 'not an image at all\n' >"$work/junk.png"
head -c 3000 "$work/v.png" >"$work/truncated.png"
printf 'P5\n100000 100000\n65535\n' >"$work/huge.pgm"
head -c 100 "$work/v.tif" >"$work/truncated.tif"
mkdir -p "$work/folder.png"
for bad in junk.png truncated.png huge.pgm truncated.tif folder.png missing.exr; do
    run -c "import $work/$bad; $area"
    [ $status = 1 ] && grep -q "$work/$bad" "$work/err"; check "bad input $bad: error names the file" $?
    ! grep -qi "^libpng\|^TIFF" "$work/err"; check "bad input $bad: no library's own line before ours" $?
done
run -c "import $work/huge.pgm"
grep -q "larger than the 65536 x 65536 limit\|over the limit" "$work/err"; check "huge header refused against the limit" $?
grep -q "100000 x 100000" "$work/err"; check "and the error gives the header's size" $?
python3 -c "
import struct
w, h = 4, 4
vals = [1.0] * 16
vals[5] = float('nan'); vals[6] = float('inf')
open('$work/nan.pfm', 'wb').write(b'Pf\n4 4\n-1.0\n' + struct.pack('<16f', *vals))"
run -c "new flat; import $work/nan.pfm"
check "NaN / Inf samples are filled, not fatal" $status
grep -q "; 2 voids filled;" "$work/out"; check "NaN / Inf samples are counted as voids" $?
run -c "$area"; after=$(cat "$work/out")
[ "$before" = "$after" ]; check "failed imports leave the world unchanged" $?

run -c "new flat; import $vermont"
[ $status = 1 ] && grep -q "N44W072.hgt: it covers .* over the limit of 134217728 in one import: give a larger spacing=" "$work/err"
check "a DEM onto a 2 m world: refused before a 10^9-sample edit" $?

# 8. Bad exports: nothing written, old file untouched.
cp "$work/v.png" "$work/keep.png"
run -c "new flat; export $work/keep.png"
[ $status = 1 ] && grep -q "unbounded: give region=" "$work/err"; check "unbounded world needs a region" $?
run -c "new flat; export $work/keep.png region=0,0,0,0"
[ $status = 1 ] && grep -q "keep.png: the region holds" "$work/err"; check "zero-size region refused" $?
run -c "new flat; export $work/keep.png region=0,0,1e9,1e9"
[ $status = 1 ] && grep -q "over the limit" "$work/err"; check "gigantic region refused" $?
cmp -s "$work/v.png" "$work/keep.png"; check "refused exports leave the old file alone" $?
run -c "new flat; export /proc/orogen-nope/x.png region=0,0,100,100"
[ $status = 1 ] && grep -q "/proc/orogen-nope/x.png" "$work/err"; check "unwritable export path: clear error" $?
run -c "new flat; export $work/x.bmp region=0,0,100,100"
[ $status = 1 ] && grep -q "x.bmp: cannot tell the format" "$work/err"; check "unknown export extension" $?
! ls "$work" | grep tmp-; check "no temp files left behind" $?

# 9. Presets resample the region to the nearest size the engine imports (fit=crop crops
# instead), and say so.
run -c "new flat from=$vermont spacing=30; export $work/u.r16 preset=unreal; export $work/y.raw preset=unity; export $work/yc.raw preset=unity fit=crop; export $work/g.png preset=godot"
grep -q "preset unreal: resampled the region's 1201 x 1201 samples to 1009 x 1009" "$work/out" &&
    grep -q "Scale X = Y = 3571.42857" "$work/out"
check "unreal preset resamples 1201^2 to 1009^2 and prints its scale (30 m x 1200 / 1008)" $?
grep -q "Scale Z = " "$work/out"; check "unreal preset prints Scale Z" $?
grep -q "preset unity: resampled the region's 1201 x 1201 samples to 1025 x 1025" "$work/out" &&
    grep -q "resolution 1025; Terrain Width 36000, Length 36000" "$work/out" &&
    grep -q "preset unity: cropped 1201 x 1201 samples to 1025 x 1025" "$work/out" &&
    [ "$(stat -c %s "$work/yc.raw")" = $((1025 * 1025 * 2)) ]
check "unity preset resamples to 2^n+1 keeping the extent (36 km); fit=crop crops" $?
[ $status = 1 ] && grep -q "g.png: preset godot takes float heights" "$work/err"; check "godot preset refuses 16-bit PNG" $?

# 10. Tiled export: tiles share their edge samples, and 4 shards run by GNU parallel
# write the same bytes as one run.
world="new flat; set size 1025; set spacing 4; generate"
mkdir -p "$work/one" "$work/sharded"
run -c "$world; export $work/one/t.png tiles=4x4"
check "tiled export runs" $status
grep -q "exported 16 of 16 tiles of 257 x 257 samples" "$work/out"; check "16 tiles of 257 x 257 samples" $?
[ -s "$work/one/t_x0_y0.png" ] && [ -s "$work/one/t_x3_y3.png" ] && [ -s "$work/one/t_x3_y3.png.json" ] && [ -s "$work/one/t.png.json" ]
check "Unreal-style names _x0_y0, a sidecar per tile and one for the set" $?
[ "$(pixel "$work/one/t_x0_y0.png" 256 100)" = "$(pixel "$work/one/t_x1_y0.png" 0 100)" ]
check "neighbouring tiles share their edge samples" $?
if command -v parallel >/dev/null; then
    parallel --will-cite "$orogen" -c "'$world; export $work/sharded/t.png tiles=4x4 shard={}/4'" ::: 0 1 2 3 >/dev/null 2>&1
    check "4 shards under GNU parallel" $?
    diff -r "$work/one" "$work/sharded" >/dev/null; check "4 shards write the files of one run, byte for byte" $?
else
    echo "FAIL: GNU parallel is missing (scripts/install-deps.sh installs it)"; failures=$((failures + 1))
fi
# One 16-bit mapping for every tile: by default the union of the region's heights
# (stored 0 and 65535 both used somewhere in the set), said in the sidecars and printout.
mkdir -p "$work/union"
run -c "new flat from=$vermont; export $work/union/t.png tiles=2x2; sample 0 0"
grep -q "height mapping: one for every tile: the region's heights 115 .. 1908 m" "$work/out"
check "tiles: the printout says the union mapping" $?
/usr/bin/python3 - "$work/union" "$(tail -n 1 "$work/out")" <<'EOF'
import glob, json, sys
from osgeo import gdal
d, h00 = sys.argv[1], float(sys.argv[2])
sets = json.load(open(d + "/t.png.json"))
assert "the region's heights 115 .. 1908 m" in sets["height_mapping"]
lo, hi, maps = 65535, 0, set()
for f in sorted(glob.glob(d + "/t_x*_y*.png")):
    sc = json.load(open(f + ".json"))
    maps.add((sc["height_scale"], sc["height_offset"]))
    a = gdal.Open(f).ReadAsArray()
    lo, hi = min(lo, int(a.min())), max(hi, int(a.max()))
    if f.endswith("t_x0_y0.png"):
        assert abs(a[0, 0] * sc["height_scale"] + sc["height_offset"] - h00) <= sc["height_scale"] / 2 + 1e-9
assert len(maps) == 1 and maps == {(sets["height_scale"], sets["height_offset"])}, maps
assert (lo, hi) == (0, 65535), (lo, hi)
EOF
check "tiles: one mapping in every sidecar, spanning stored 0 .. 65535 over the set" $?
# The formats that carry a date (EXR, TIFF) too: a second apart, as one run and as two
# shards, every file the same bytes.
mkdir -p "$work/date1" "$work/date2"
small="new flat; set size 257; set spacing 4; generate"
run -c "$small; export $work/date1/d.exr tiles=2x2; export $work/date1/d16.tif tiles=2x2 bits=16; export $work/date1/d32.tif tiles=2x2"
sleep 1.1
for shard in 0/2 1/2; do
    "$orogen" -c "$small; export $work/date2/d.exr tiles=2x2 shard=$shard; export $work/date2/d16.tif tiles=2x2 bits=16 shard=$shard; export $work/date2/d32.tif tiles=2x2 shard=$shard" >/dev/null 2>&1
done
files=$(ls "$work/date1" | wc -l)
[ "$files" = 27 ] && diff -r "$work/date1" "$work/date2" >/dev/null
check "EXR and 16/32-bit TIFF tiles a second apart, one run and two shards: the same bytes ($files files)" $?
# A world made from a raster imports, in a script, only the parts a shard reads: the
# shards' files are still those of one run, and the world, once a later command needs
# all of it, is the one a whole import makes (heights, mip levels, saved tiles).
mkdir -p "$work/dem1" "$work/dem2"
run -c "new flat from=$vermont; export $work/dem1/v.exr tiles=3x3; export $work/dem1/v16.tif tiles=3x3 bits=16; save $work/dem1.world"
for shard in 0/2 1/2; do
    "$orogen" -c "new flat from=$vermont; export $work/dem2/v.exr tiles=3x3 shard=$shard; export $work/dem2/v16.tif tiles=3x3 bits=16 shard=$shard; save $work/dem2_${shard%/*}.world" >/dev/null 2>&1
done
[ "$(ls "$work/dem1" | wc -l)" = 38 ] && diff -r "$work/dem1" "$work/dem2" >/dev/null
check "a world from an SRTM tile: 2 shards write the tiles of one run, byte for byte (EXR, 16-bit TIFF)" $?
# Their shared 16-bit mapping comes from the raster, not from reading the whole region:
# the same as read from the world once it is all imported (sample needs all of it).
mkdir -p "$work/dem3"
run -c "new flat from=$vermont; sample 0 0; export $work/dem3/v16.tif tiles=3x3 bits=16"
differ=0
for f in "$work"/dem3/*; do cmp -s "$f" "$work/dem1/${f##*/}" || differ=1; done
[ "$(ls "$work/dem3" | wc -l)" = 19 ] && [ $differ = 0 ]
check "a world from an SRTM tile: the 16-bit tiles' shared range, from the raster, is the one read from the world" $?
dump() { sqlite3 "$1" "select layer, face, level, tx, ty, hex(data) from tiles order by 1, 2, 3, 4, 5" | md5sum; }
[ "$(dump "$work/dem1.tiles")" = "$(dump "$work/dem2_0.tiles")" ] && [ "$(dump "$work/dem1.tiles")" = "$(dump "$work/dem2_1.tiles")" ]
check "a world from an SRTM tile imported in parts saves the tiles (and mip levels) of a whole import" $?
run -c "$world; export $work/u.raw tiles=2x2 preset=unity"
[ -s "$work/u_0_0.raw" ] && [ -s "$work/u_1_1.raw" ]; check "Unity tiles are named NAME_X_Z" $?
# Presets size each tile as the engine imports one and print one tile's settings and
# the set's placement; godot refuses float TIFF.
[ "$(stat -c %s "$work/u_0_0.raw")" = $((513 * 513 * 2)) ] && grep -q "each tile (513 x 513 samples)" "$work/out" &&
    grep -q "resolution 513; Terrain Width 2048" "$work/out" && grep -q "tile (x, y) starts at X = 0 + x \* 2048 m" "$work/out"
check "Unity 2x2: 513 x 513 tiles, settings for one tile and the set's placement" $?
run -c "$world; export $work/ue.png tiles=4x4 preset=unreal; export $work/uc.png tiles=4x4 preset=unreal fit=crop"
size=$(iinfo "$work/ue_x3_y3.png" 2>/dev/null | sed -n 's/.*: *\([0-9]*\) x *\([0-9]*\),.*/\1x\2/p')
[ $status = 0 ] && [ "$size" = 253x253 ] && grep -q "resampled the region's 1025 x 1025 samples to 1009 x 1009 in all (253 x 253 per tile)" "$work/out" &&
    grep -q "cropped 257 x 257 samples to 253 x 253" "$work/out"
check "Unreal 4x4: each tile an Unreal size (253 x 253; got $size), resampled (or cropped with fit=crop)" $?
# A 1201^2 DEM as 2 x 2 Unity tiles: 513^2 each, sharing their edges, covering the
# region's corners, at the printed scale (Terrain Width = the region's extent / 2).
mkdir -p "$work/unity"
run -c "new flat from=$vermont; export $work/unity/v.raw tiles=2x2 preset=unity; export $work/unity/whole.exr"
check "Unity 2x2 tiles of a 1201^2 DEM" $status
cp "$work/out" "$work/unity.out"
# The world's extent: its 1201 samples at the spacing its own float export states.
e=$(/usr/bin/python3 -c "import json; print(repr(json.load(open('$work/unity/whole.exr.json'))['spacing'] * 1200 - 1e-6))")
run -c "new flat from=$vermont; sample 0 0; sample $e 0; sample 0 $e; sample $e $e"
tail -n 4 "$work/out" >>"$work/unity.out"
/usr/bin/python3 - "$work/unity" "$work/unity.out" <<'EOF'
import json, re, sys
import numpy as np
d, out = sys.argv[1], open(sys.argv[2]).read()
t = {(x, y): np.fromfile(f"{d}/v_{x}_{y}.raw", dtype="<u2").reshape(513, 513) for x in (0, 1) for y in (0, 1)}
assert (t[0, 0][:, 512] == t[1, 0][:, 0]).all() and (t[0, 1][:, 512] == t[1, 1][:, 0]).all(), "x seams"
assert (t[0, 0][512, :] == t[0, 1][0, :]).all() and (t[1, 0][512, :] == t[1, 1][0, :]).all(), "z seams"
sc = json.load(open(f"{d}/v_1_1.raw.json"))
scale, offset = sc["height_scale"], sc["height_offset"]
heights = [float(v) for v in out.split()[-4:]]
corners = [t[0, 0][0, 0], t[1, 0][0, 512], t[0, 1][512, 0], t[1, 1][512, 512]]
for want, stored in zip(heights, corners):
    assert abs(stored * scale + offset - want) <= scale / 2 + 1e-6, (want, stored * scale + offset)
extent = 1200 * json.load(open(f"{d}/whole.exr.json"))["spacing"]
width = float(re.search(r"resolution 513; Terrain Width ([0-9.]+), Length ([0-9.]+)", out).group(1))
assert abs(2 * width - extent) < 0.01, (width, extent)
assert abs(sc["spacing"] * 1024 - extent) < 0.01 and abs(sc["origin_x"] - width) < 1e-4
place = re.search(r"starts at X = 0 \+ x \* ([0-9.]+) m", out).group(1)
assert abs(float(place) - width) < 1e-6, place
EOF
check "Unity 2x2 of a 1201^2 DEM: 513^2 tiles, equal seams, corners at the world's corner heights, printed width x 2 = the extent" $?
run -c "$world; export $work/godot.tif preset=godot"
[ $status = 1 ] && grep -q "preset godot takes float heights in metres: name it .exr" "$work/err" && [ ! -e "$work/godot.tif" ]
check "preset godot refuses a float TIFF" $?
run -c "$world; export $work/g.png tiles=2x2 pattern={name}_y{y}_x{x}"
[ -s "$work/g_y1_x0.png" ]; check "pattern= names tiles (Gaea-style y before x)" $?
run -c "$world; export $work/s.png shard=1/2"
[ $status = 1 ] && grep -q "shard= splits a tiled export" "$work/err"; check "shard= without tiles= is refused" $?

# 11. Meshes: assimp loads OBJ, PLY and glb with the counts and bounds we report; the
# Khronos glTF validator finds nothing wrong; simplification keeps to its error;
# solid=1 closes the mesh.
command -v assimp >/dev/null || { echo "FAIL: assimp is missing (assimp-utils)"; failures=$((failures + 1)); }
run -c "new flat; set size 257; generate; export $work/m.obj; export $work/m.ply; export $work/m.glb; export $work/s.glb simplify=1; export $work/solid.ply solid=1; export $work/c.glb centred=1"
check "mesh exports run" $status
for f in m.obj m.ply m.glb; do
    assimp info "$work/$f" >"$work/assimp" 2>&1
    grep -q "Vertices: *66049" "$work/assimp" && grep -q "Faces: *131072" "$work/assimp"
    check "assimp: $f has 66049 vertices and 131072 triangles" $?
    lo=$(grep "exported $work/$f:" "$work/out" | sed -E 's/.*bounds ([-0-9.e+]+), ([-0-9.e+]+), ([-0-9.e+]+) \.\. .*/\1 \2 \3/')
    read -r ax ay az <<<"$(sed -nE 's/Minimum point *\(([-0-9.]+) ([-0-9.]+) ([-0-9.]+)\)/\1 \2 \3/p' "$work/assimp")"
    read -r lx ly lz <<<"$lo"
    same "$ax" "$lx" 0.01 && same "$ay" "$ly" 0.01 && same "$az" "$lz" 0.01
    check "assimp: $f's bounding box starts where the export says ($ax $ay $az vs $lo)" $?
done
for f in m.obj m.ply m.glb s.glb solid.ply c.glb; do
    python3 "$tests/mesh_check.py" "$work/$f" >"$work/manifold" 2>&1
    rc=$?
    check "manifold: $(cat "$work/manifold")" $rc
done
grep -q "Maximum point *(512.000000 " <(assimp info "$work/m.glb" 2>&1); check "the glb spans 512 m (256 samples x 2 m) in X" $?
validator_dir=$(cd "$tests/.." && pwd)/.cache/npm
for f in m.glb s.glb c.glb; do
    node "$tests/support/validate_gltf.js" "$validator_dir" "$work/$f" >"$work/validator" 2>&1
    rc=$?; check "glTF validator: $f has no errors and no warnings ($(head -n 1 "$work/validator"))" $rc
done
line=$(grep "exported $work/s.glb:" "$work/out")
tris=$(echo "$line" | sed -E 's/.* ([0-9]+) triangles.*/\1/')
error=$(echo "$line" | sed -E 's/.*height error ([-0-9.e+]+) m.*/\1/')
[ "$tris" -lt 131072 ] && python3 -c "import sys; sys.exit(0 if float('$error') <= 1.0 else 1)"
check "simplify=1 leaves fewer triangles ($tris) within 1 m ($error m)" $?
python3 - "$work/solid.ply" <<'PY'
import struct, sys
from collections import Counter
d = open(sys.argv[1], 'rb').read()
head, body = d.split(b'end_header\n', 1)
nv = int(head.split(b'element vertex ')[1].split(b'\n')[0])
nf = int(head.split(b'element face ')[1].split(b'\n')[0])
off = nv * 32
edges = Counter()
for k in range(nf):
    n, a, b, c = struct.unpack_from('<BIII', body, off + k * 13)
    for u, v in ((a, b), (b, c), (c, a)):
        edges[(u, v)] += 1
# Closed and consistently wound: every directed edge once, its reverse once.
sys.exit(0 if all(edges[(v, u)] == 1 for (u, v), n in edges.items() if n == 1) and max(edges.values()) == 1 else 1)
PY
check "solid=1 makes a closed, consistently wound mesh" $?
# Simplification judged by the reader: on a real DEM the vertical deviation at every
# sample of the whole mesh (border included) is within what the export reported, which
# is within simplify=; no triangle faces down or stands on edge.
run -c "new flat from=$vermont; export $work/rs.ply region=10000,20000,30000,40000 simplify=2; export $work/rf.ply region=10000,20000,30000,40000"
reported=$(sed -n 's/^exported .*rs.ply: .*height error \([-0-9.e+]*\) m.*/\1/p' "$work/out")
[ -n "$reported" ] && python3 -c "import sys; sys.exit(0 if float('$reported') <= 2 else 1)" &&
    python3 "$tests/simplify_check.py" "$work/rs.ply" "$work/rf.ply" "$reported" >"$work/simplify" 2>&1
rc=$?
check "simplify=2 on the Vermont DEM: $(cat "$work/simplify")" $rc
python3 "$tests/mesh_check.py" "$work/rs.ply" >"$work/manifold" 2>&1
rc=$?
check "manifold: $(cat "$work/manifold")" $rc
# Blender reads these meshes in tests/e2e_blender.sh.

# 12. The other layers: material weights exactly as stored, four per RGBA file, and a
# tangent-space normal map.
run -c "new flat; set size 257; set generator flat; generate; tool paint material=3 strength=1 radius=30; dab 100 100; export $work/w.png layer=materials; export $work/n.png layer=normals"
check "export layer=materials and layer=normals" $status
iinfo "$work/w_m0-3.png" | grep -q "257 x  257, 4 channel, uint8 png"; check "material weights: 8-bit RGBA, one pixel per sample" $?
oiiotool "$work/w_m0-3.png" --cut 1x1+50+50 -o "$work/px.tif" && oiiotool --dumpdata "$work/px.tif" | grep -q "Pixel (0, 0): 0 0 0 255 "
check "painted material 3 reads 255 in the alpha of _m0-3 at the dab" $?
oiiotool "$work/w_m4-7.png" --cut 1x1+50+50 -o "$work/px.tif" && oiiotool --dumpdata "$work/px.tif" | grep -q "Pixel (0, 0): 0 0 0 0 "
check "and 0 for materials 4-7" $?
oiiotool "$work/n.png" --cut 1x1+10+10 -o "$work/px.tif" && oiiotool --dumpdata "$work/px.tif" | grep -q "Pixel (0, 0): 128 128 255 "
check "a flat world's normal map is (128, 128, 255)" $?
# 16-bit normals: the same normals as the 8-bit map, 257 times finer.
run -c "new flat; set size 257; generate; export $work/n8.png layer=normals; export $work/n16.png layer=normals bits=16"
check "export layer=normals bits=16" $status
iinfo "$work/n16.png" | grep -q "257 x  257, 3 channel, uint16 png"; check "16-bit normal map: uint16 RGB" $?
rgb_at_80_90() { oiiotool "$1" --cut 1x1+80+90 -o "$work/px.tif" && oiiotool --dumpdata "$work/px.tif" | sed -n 's/.*Pixel (0, 0): \([0-9]*\) \([0-9]*\) \([0-9]*\) .*/\1 \2 \3/p'; }
p8=$(rgb_at_80_90 "$work/n8.png"); p16=$(rgb_at_80_90 "$work/n16.png")
echo "$p8 $p16" | awk '{ for (k = 1; k <= 3; k++) { d = $k - $(k + 3) * 255 / 65535; if (d > 0.5 || d < -0.5 || $(k + 3) == 0) exit 1 } }'
check "16-bit normals round to the 8-bit ones on relief ($p16 vs $p8)" $?
run -c "new flat; export $work/n.png layer=normals bits=32 region=0,0,10,10"
[ $status = 1 ] && grep -q "n.png: normal maps are 8 or 16 bits" "$work/err"
check "bits=32 normals are refused" $?
run -c "new flat; export $work/n.exr layer=normals region=0,0,10,10"
[ $status = 1 ] && grep -q "n.exr: normal maps and material weights are written as .png" "$work/err"
check "layer images other than .png are refused" $?

echo "e2e_interchange: $passes passed, $failures failed"
[ $failures = 0 ]
