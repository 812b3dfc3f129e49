#!/usr/bin/env bash
# The size check must catch what it is for: a file in app/ over 700 lines and a
# function over 120 (braces in comments and strings not counted); and pass sizes at
# the limits. Usage: check_sizes_selftest.sh TESTS_DIR
set -u
check_py="$1/check_sizes.py"
work=$(mktemp -d "${TMPDIR:-/tmp}/orogen-sizes-XXXXXX")
trap 'rm -rf "$work"' EXIT
failures=0
expect() { # name, expected exit status, text the output must contain ("" for none)
    out=$(python3 "$check_py" "$work/tree" 2>&1)
    status=$?
    if [ "$status" != "$2" ] || { [ -n "$3" ] && ! grep -qF -- "$3" <<<"$out"; }; then
        echo "FAIL: $1 (status $status, wanted $2 and '$3'): $out"
        failures=$((failures + 1))
    fi
}
# A function of n lines from its signature to its closing brace, in app/f.c; a
# struct, an array and braces in a comment and a string around it.
function_of() {
    rm -rf "$work/tree"
    mkdir -p "$work/tree/app"
    {
        printf 'typedef struct s {\n    int a;\n} s;\nstatic const int t[] = {1, 2};\n'
        printf '// a comment with a { brace\n'
        printf 'static int long_one(int x,\n                    int y) {\n'
        for ((i = 0; i < $1 - 4; i++)); do printf '    x += y; /* } */ (void)"{";\n'; done
        printf '    return x;\n}\n'
    } >"$work/tree/app/f.c"
}
function_of 120
expect "a function of 120 lines passes" 0 ""
function_of 121
expect "a function of 121 lines is refused, at its signature's line" 1 "app/f.c:6: long_one is 121 lines"
rm -rf "$work/tree"
mkdir -p "$work/tree/app"
for ((i = 0; i < 700; i++)); do echo "int v$i;"; done >"$work/tree/app/g.h"
expect "a file of 700 lines passes" 0 ""
echo "int v700;" >>"$work/tree/app/g.h"
expect "a file of 701 lines is refused" 1 "app/g.h:1: 701 lines"
if [ "$failures" -ne 0 ]; then
    echo "check_sizes_selftest: $failures failed"
    exit 1
fi
echo "check_sizes_selftest: every case as expected"
