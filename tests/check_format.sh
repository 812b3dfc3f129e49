#!/usr/bin/env bash
# Fails when a C/C++ file of the project is not formatted with its .clang-format.
# Usage: check_format.sh ROOT
set -u
root=$1
command -v clang-format >/dev/null || { echo "FAIL: clang-format is not installed (scripts/install-deps.sh installs it)"; exit 1; }
cd "$root" || exit 1
if git rev-parse --is-inside-work-tree >/dev/null 2>&1; then
    files=$(git ls-files '*.c' '*.h' '*.cpp')
else
    files=$(find app bench editor io renderer tests tools ui view -name '*.c' -o -name '*.h' -o -name '*.cpp' 2>/dev/null)
fi
bad=0
for f in $files; do
    [ -f "$f" ] || continue
    if ! clang-format --dry-run -Werror "$f" >/dev/null 2>&1; then
        echo "not formatted: $f (clang-format -i $f)"
        bad=$((bad + 1))
    fi
done
echo "check_format: $(echo "$files" | wc -w) files, $bad not formatted"
[ $bad = 0 ]
