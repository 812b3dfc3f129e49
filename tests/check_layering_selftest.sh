#!/usr/bin/env bash
# The layering check must catch what it is for: an upward include, a circle, an
# include of a missing file; and pass a clean tree. Usage: check_layering_selftest.sh TESTS_DIR
set -u
check_py="$1/check_layering.py"
work=$(mktemp -d "${TMPDIR:-/tmp}/orogen-layering-XXXXXX")
trap 'rm -rf "$work"' EXIT
failures=0
expect() { # name, expected exit status, text the output must contain
    out=$(python3 "$check_py" "$work/tree" 2>&1)
    status=$?
    if [ "$status" != "$2" ] || ! grep -qF -- "$3" <<<"$out"; then
        echo "FAIL: $1 (status $status, wanted $2 and '$3'): $out"
        failures=$((failures + 1))
    fi
}
clean_tree() {
    rm -rf "$work/tree"
    mkdir -p "$work/tree/io" "$work/tree/editor/world" "$work/tree/editor/cmd" "$work/tree/renderer"
    printf '#include "io/a.h"\n' >"$work/tree/io/a.c"
    printf '// a\n' >"$work/tree/io/a.h"
    printf '#include "editor/world/w.h"\n#include "io/a.h"\n' >"$work/tree/editor/world/w.c"
    printf '#include "io/a.h"\n' >"$work/tree/editor/world/w.h"
    printf '#include "editor/world/w.h"\n' >"$work/tree/renderer/r.c"
    printf '/*\n#include "renderer/r.h"\n*/\n// #include "x"\n' >"$work/tree/editor/cmd/c.c"
}
clean_tree
expect "a clean tree passes (includes in comments are not includes)" 0 "0 problems"
clean_tree
printf '#include "renderer/r.h"\n' >>"$work/tree/editor/world/w.c"
printf '// r\n' >"$work/tree/renderer/r.h"
expect "an upward include is refused" 1 "editor/world/w.c:3: includes \"renderer/r.h\" (folder editor/world may not use renderer)"
clean_tree
printf '#include "io/missing.h"\n' >>"$work/tree/io/a.c"
expect "an include of a missing file is refused" 1 "io/a.c:2: includes \"io/missing.h\", which is not a file"
clean_tree
printf '#include "io/b.h"\n' >"$work/tree/io/a.h"
printf '#include "io/a.h"\n' >"$work/tree/io/b.h"
expect "a circle between files is refused" 1 "circle: io/a -> io/b -> io/a"
clean_tree
printf 'const char *s = "/*"; // /* neither opens a comment\n#include "renderer/r.h"\n' >>"$work/tree/editor/world/w.c"
printf '// r\n' >"$work/tree/renderer/r.h"
expect "\"/*\" in a string or after // hides no include" 1 "folder editor/world may not use renderer"
clean_tree
printf '#include "editor/world/w.h"\n' >"$work/tree/io/a.c"
expect "io may not use the editor" 1 "folder io may not use editor/world"
clean_tree
printf '#include "editor/cmd/c.h"\n' >>"$work/tree/renderer/r.c"
printf '// c\n' >"$work/tree/editor/cmd/c.h"
expect "the renderer may not use the command language" 1 "folder renderer may not use editor/cmd"
echo "check_layering_selftest: $failures failed"
[ $failures = 0 ]
