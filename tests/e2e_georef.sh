#!/usr/bin/env bash
# End-to-end: worlds made from georeferenced data keep their place and their shape,
# checked by GDAL (gdalinfo -json, and its Python bindings for every sample).
#  1. new flat from=DEM keeps the CRS and geotransform in the world file; float and
#     16-bit GeoTIFF exports (whole world and a sub-region) have the source's CRS and
#     corners, their sidecars too; a PNG's sidecar carries the place back in.
#  2. A non-square raster makes a world of its own shape, every row and column, and
#     exports back to the same dimensions and values.
#  3. A parameter file without the new keys loads as before (square, local metres).
#  4. Crash recovery of a world made from a file re-reads the file (checked).
# Usage: e2e_georef.sh OROGEN TESTS_DIR
set -u
orogen=$1
tests=$2
work=$(mktemp -d "${TMPDIR:-/tmp}/orogen-e2e-geo-XXXXXX")
trap '[ -n "${KEEP:-}" ] || rm -rf "$work"' EXIT
failures=0
passes=0
dem=$tests/data/dem/N44W072.hgt
py=/usr/bin/python3 # Debian's, with GDAL's bindings (gdal-bin depends on them)

check() { # name, condition already evaluated as $?
    if [ "$2" = 0 ]; then passes=$((passes + 1)); else echo "FAIL: $1"; failures=$((failures + 1)); fi
}
run() {
    "$orogen" "$@" >"$work/out" 2>"$work/err"
    status=$?
    [ $status = 0 ] || cat "$work/err"
}
for tool in gdalinfo gdal_translate; do
    command -v $tool >/dev/null || { echo "FAIL: $tool is missing (scripts/install-deps.sh)"; exit 1; }
done
$py -c "from osgeo import gdal; import numpy" || { echo "FAIL: $py lacks GDAL's bindings"; exit 1; }

# same_place SOURCE EXPORT COL ROW W H [TOLERANCE]: the export's CRS is the source's, its size W x H
# and its corners those of the source's samples COL .. COL+W-1, ROW .. ROW+H-1 (from
# gdalinfo -json), and every sample equal (16-bit: through its sidecar's mapping).
same_place() {
    gdalinfo -json "$1" >"$work/a.json" && gdalinfo -json "$2" >"$work/b.json" &&
        $py - "$work/a.json" "$work/b.json" "$1" "$2" "$3" "$4" "$5" "$6" "${7:-0}" <<'EOF'
import json, sys, os
from osgeo import gdal, osr
import numpy as np
a, b = json.load(open(sys.argv[1])), json.load(open(sys.argv[2]))
src, out = sys.argv[3], sys.argv[4]
c, r, w, h = map(int, sys.argv[5:9])
tolerance = float(sys.argv[9])
ok = True
def fail(msg):
    global ok
    ok = False
    print("  " + msg)
if b["size"] != [w, h]:
    fail("size %s, want %s" % (b["size"], [w, h]))
sa, sb = osr.SpatialReference(), osr.SpatialReference()
sa.ImportFromWkt(a["coordinateSystem"]["wkt"])
sb.ImportFromWkt(b["coordinateSystem"]["wkt"])
if not sa.IsSame(sb):
    fail("coordinate systems differ")
def corner(gt, col, row):
    return [gt[0] + col * gt[1] + row * gt[2], gt[3] + col * gt[4] + row * gt[5]]
# gdalinfo prints corners to 7 decimals; the geotransforms give them in full.
ga, gb = a["geoTransform"], b["geoTransform"]
for k, (col, row) in {"upperLeft": (0, 0), "lowerLeft": (0, h), "upperRight": (w, 0),
                      "lowerRight": (w, h)}.items():
    want, full = corner(ga, c + col, r + row), corner(gb, col, row)
    shown = b["cornerCoordinates"][k]
    if max(abs(full[0] - want[0]), abs(full[1] - want[1])) > 1e-9 or \
            max(abs(shown[0] - want[0]), abs(shown[1] - want[1])) > 1e-7:
        fail("%s corner %s (%s), want %s" % (k, shown, full, want))
ds_src, ds_out = gdal.Open(src), gdal.Open(out)
sv = ds_src.GetRasterBand(1).ReadAsArray(c, r, w, h).astype(np.float64)
ov = ds_out.GetRasterBand(1).ReadAsArray().astype(np.float64)
band = ds_out.GetRasterBand(1)
if out.endswith(".tif") and band.GetUnitType() != "m":
    fail("the band's unit is '%s', not metres" % band.GetUnitType())
if os.path.exists(out + ".json"):
    sc = json.load(open(out + ".json"))
    # A 16-bit GeoTIFF says its mapping itself, as GDAL readers apply it (gdalinfo: Offset, Scale).
    if out.endswith(".tif") and "16" in sc["format"] and \
            (band.GetScale() != sc["height_scale"] or band.GetOffset() != sc["height_offset"]):
        fail("band scale %s offset %s, the sidecar's %s %s" % (band.GetScale(), band.GetOffset(),
                                                           sc["height_scale"], sc["height_offset"]))
    ov = ov * sc["height_scale"] + sc["height_offset"]
    step = sc["height_scale"] if "16" in sc["format"] else 0
    if sc.get("geotransform") is None:
        fail("the sidecar has no geotransform")
    elif max(abs(x - y) for x, y in zip(sc["geotransform"], b["geoTransform"])) > 1e-12:
        fail("the sidecar's geotransform %s is not the file's %s" % (sc["geotransform"], b["geoTransform"]))
else:
    step = 0
d = np.abs(sv - ov).max() if sv.shape == ov.shape else float("inf")
if d > max(step / 2, tolerance) + 1e-9:
    fail("samples differ by up to %g (allowed %g)" % (d, max(step / 2, tolerance)))
sys.exit(0 if ok else 1)
EOF
}

# 1. A world from an SRTM tile keeps its place.
run -c "new flat from=$dem; save $work/w.world; export $work/a.tif; export $work/b.tif bits=16; export $work/sub.tif region=6000,9250,20000,30000; export $work/sub16.tif bits=16 region=6000,9250,20000,30000; export $work/p.png"
check "new flat from=DEM and the exports" $status
grep -q "new flat world of 1201 x 1201 samples.*georeferenced" "$work/out"; check "the world keeps every sample and says it is georeferenced" $?
grep -q '^geo_crs = GEOGCS\["WGS 84".*AUTHORITY\["EPSG","4326"\]\];$' "$work/w.world"; check "the world file keeps the CRS" $?
grep -q '^geo_transform = -72.00041666666667, 0.0008333333333333334, 0, 45.000416666666666, 0, -0.0008333333333333334;$' "$work/w.world"
check "the world file keeps the geotransform" $?
same_place "$dem" "$work/a.tif" 0 0 1201 1201; check "float GeoTIFF: the DEM's CRS, corners and samples" $?
same_place "$dem" "$work/b.tif" 0 0 1201 1201; check "16-bit GeoTIFF: the DEM's CRS, corners and samples" $?
# Without its sidecar the 16-bit GeoTIFF still gives metres (GDAL's band scale and offset).
cp "$work/b.tif" "$work/bare16.tif"
run -c "new flat from=$work/bare16.tif; export $work/from_bare16.tif"
grep -q "GTiff UInt16, x [0-9.]* + 115 (the band's scale and offset)" "$work/out"
check "new flat from a 16-bit GeoTIFF without its sidecar" $?
half_step16=$($py -c "import json; print(json.load(open('$work/b.tif.json'))['height_scale'] / 2)")
same_place "$dem" "$work/from_bare16.tif" 0 0 1201 1201 "$half_step16"; check "its heights are the DEM's to half a 16-bit step" $?
# region 6000,9250 .. 20000,30000 m at the world's spacing: its first and last samples.
read -r c0 r0 w h <<<"$($py -c "
import math
s = float([l.split('=')[1].strip(' ;\n') for l in open('$work/w.world') if l.startswith('spacing =')][0])
c0, r0 = math.ceil(6000 / s - 1e-9), math.ceil(9250 / s - 1e-9)
print(c0, r0, math.floor(20000 / s + 1e-9) + 1 - c0, math.floor(30000 / s + 1e-9) + 1 - r0)")"
same_place "$dem" "$work/sub.tif" "$c0" "$r0" "$w" "$h"; check "a sub-region's corners are its samples' ($c0, $r0, $w x $h)" $?
same_place "$dem" "$work/sub16.tif" "$c0" "$r0" "$w" "$h"; check "and as 16-bit" $?
# Saved and loaded, the world still knows its place.
run -c "load $work/w.world; export $work/again.tif"
same_place "$dem" "$work/again.tif" 0 0 1201 1201; check "a loaded world exports to the same place" $?
# A PNG has no room for a place: its sidecar brings it back in.
grep -q '"crs": "GEOGCS\[\\"WGS 84\\"' "$work/p.png.json"; check "the PNG's sidecar names the CRS" $?
run -c "new flat from=$work/p.png; export $work/from_png.tif"
check "new flat from the PNG" $status
half_step=$($py -c "import json; print(json.load(open('$work/p.png.json'))['height_scale'] / 2)")
same_place "$dem" "$work/from_png.tif" 0 0 1201 1201 "$half_step"; check "a world from the exported PNG has the DEM's place (16-bit steps)" $?

# An import onto a world with no place gives it the file's (one undo step with the
# samples); a world that has a place keeps it.
run -c "new flat; set size 1300; set spacing 30; generate; import $dem spacing=30 x=300 z=600; export $work/adopt.tif region=300,600,36300,36600; import $dem spacing=30 x=0 z=0; undo; undo; export $work/undone.tif"
check "import onto a world without a place" $status
[ "$(grep -c "the world takes the file's place" "$work/out")" = 1 ]; check "it takes the first file's place only" $?
same_place "$dem" "$work/adopt.tif" 0 0 1201 1201; check "the world's export there has the DEM's CRS, corners and samples" $?
gdalinfo -json "$work/undone.tif" | $py -c "import json, sys; sys.exit(0 if not json.load(sys.stdin).get('coordinateSystem', {}).get('wkt') else 1)"
check "undone, the world has no place again" $?

# 2. Worlds of the data's own shape: a 1201 x 800 crop and a 403 x 344 one (even sides).
for win in "0 0 1201 800" "100 50 403 344"; do
    read -r c r w h <<<"$win"
    gdal_translate -q -srcwin $win "$dem" "$work/crop.tif"
    run -c "new flat from=$work/crop.tif; info; export $work/whole.tif; export $work/whole.exr; save $work/crop.world"
    check "new flat from a ${w} x ${h} raster" $status
    grep -q "^size=$w$" "$work/out" && grep -q "^size_z=$h$" "$work/out"; check "info: $w x $h samples" $?
    grep -q "^size_z = $h;" "$work/crop.world"; check "the world file keeps its rows (size_z = $h)" $?
    same_place "$work/crop.tif" "$work/whole.tif" 0 0 "$w" "$h"; check "$w x $h: export of the whole world is the raster" $?
    same_place "$dem" "$work/whole.tif" "$c" "$r" "$w" "$h"; check "$w x $h: and lies where the DEM's samples do" $?
    idiff -fail 0 -failpercent 0 "$work/whole.tif" "$work/whole.exr" >/dev/null 2>&1
    check "$w x $h: the EXR of the whole world has the raster's samples" $?
done
# The last row and column are the raster's (no row lost, no filler).
gdal_translate -q -srcwin 0 0 1201 800 "$dem" "$work/crop.tif"
run -c "new flat from=$work/crop.tif; spacing"
spacing=$(tail -n 1 "$work/out")
run -c "new flat from=$work/crop.tif; sample $($py -c "print(1200 * $spacing)") $($py -c "print(799 * $spacing)"); sample 0 $($py -c "print(800 * $spacing)")"
got=$(sed -n 's/^\(-\{0,1\}[0-9.]*\)$/\1/p' "$work/out" | tail -n 1)
want=$(gdallocationinfo -valonly "$dem" 1200 799)
$py -c "import sys; sys.exit(0 if abs(float('$got') - float('$want')) < 1e-9 else 1)"; check "the last sample is the raster's ($got, GDAL $want)" $?
grep -q "lies outside the world" "$work/err"; check "nothing past the last row" $?

# 3. A parameter file from before these keys: square, local metres, as before.
printf 'kind = flat;\ngenerator = flat;\nsize = 300;\nspacing = 30;\n' >"$work/old.world"
run -c "load $work/old.world; info; export $work/old.tif"
check "an old parameter file loads" $status
grep -q "^size_z=300$" "$work/out"; check "it is square" $?
gdalinfo "$work/old.tif" | grep -q "Origin = (-15.000000000000000,15.000000000000000)"; check "its export is in local metres" $?
gdalinfo "$work/old.tif" | grep -q "Size is 300, 300"; check "of the whole world" $?

# 4. A world made from a file is journaled by the file's name, not a copy of its
# samples: a crash after edits recovers the same terrain from it, and a file changed
# since is refused (the journal kept).
export OROGEN_RECOVER_DIR=$work/recover
mkdir -p "$OROGEN_RECOVER_DIR"
cp "$work/crop.tif" "$work/base.tif"
# (--batch - keeps a never-saved world's journal at its end, as a person typing would.)
printf 'new flat from=%s\ntool raise radius=2000 strength=1\nstroke 5000 5000 20000 9000\nhash 0 0 90000 60000\n' "$work/base.tif" |
    "$orogen" --batch - >"$work/out" 2>"$work/err"
edited=$(tail -n 1 "$work/out")
journal=$(ls "$OROGEN_RECOVER_DIR"/*.recover 2>/dev/null | head -n 1)
[ -n "$journal" ] && [ "$(stat -c %s "$journal")" -lt 1000000 ]
ok=$?; check "the journal names the raster instead of holding its $(stat -c %s "$work/base.tif" 2>/dev/null)-byte samples ($(stat -c %s "$journal" 2>/dev/null) bytes)" $ok
cp "$journal" "$work/journal.copy"
run -c "recover $journal; hash 0 0 90000 60000; undo; hash 0 0 90000 60000"
vals=($(grep -E '^[0-9a-f]{16}$' "$work/out"))
[ "${vals[0]:-}" = "$edited" ]; check "recovered from the raster and the journal: the same terrain" $?
run -c "new flat from=$work/base.tif; hash 0 0 90000 60000"
[ "${vals[1]:-}" = "$(tail -n 1 "$work/out")" ]; check "and the steps undo back to the raster" $?
rm -f "$OROGEN_RECOVER_DIR"/*.recover
cp "$work/journal.copy" "$OROGEN_RECOVER_DIR/again.recover"
gdal_translate -q -srcwin 1 0 1201 800 "$dem" "$work/base.tif"
run -c "recover $OROGEN_RECOVER_DIR/again.recover"
[ $status = 1 ] && grep -q "was made from $work/base.tif, which has changed since.*the journal is kept" "$work/err" &&
    [ -s "$OROGEN_RECOVER_DIR/again.recover" ]
check "a raster changed since: recovery refused, naming it, the journal kept" $?

echo "e2e_georef: $passes passed, $failures failed"
[ $failures = 0 ]
