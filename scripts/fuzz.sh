#!/usr/bin/env bash
# Builds the libFuzzer targets of tests/fuzz (clang, ASan + UBSan) and runs each for a
# while on its seed corpus (tests/fuzz/corpus/NAME/, which also holds every input that
# ever crashed it: each run replays them first).
#   scripts/fuzz.sh [SECONDS] [TARGET...]   default 30 s each, every target
# New interesting inputs go to build-fuzz/corpus/NAME/; a crash leaves its input in
# build-fuzz/artifacts/ (copy it into tests/fuzz/corpus/NAME/ once fixed) and fails.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
seconds=${1:-30}
shift || true
"$root/scripts/install-deps.sh"
dir="$root/build-fuzz"
cmake -S "$root" -B "$dir" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_C_COMPILER=clang \
  -DCMAKE_CXX_COMPILER=clang++ -DOROGEN_FUZZ=ON >/dev/null
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
  for src in "$root"/tests/fuzz/fuzz_*.c; do
    name=$(basename "$src" .c)
    [ "$name" = fuzz_support ] || targets+=("$name")
  done
fi
cmake --build "$dir" -j "$(nproc)" --target "${targets[@]}"
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:allocator_may_return_null=1
export LSAN_OPTIONS=suppressions=$root/tests/lsan.supp:print_suppressions=0
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
mkdir -p "$dir/artifacts"
failed=0
for t in "${targets[@]}"; do
  name=${t#fuzz_}
  seeds="$root/tests/fuzz/corpus/$name"
  found="$dir/corpus/$name"
  mkdir -p "$found" "$seeds"
  dict=()
  [ -f "$root/tests/fuzz/$name.dict" ] && dict=(-dict="$root/tests/fuzz/$name.dict")
  log="$dir/$t.log"
  if "$dir/tests/fuzz/$t" -max_total_time="$seconds" -timeout=30 -rss_limit_mb=8192 -malloc_limit_mb=8192 \
    -max_len=65536 -artifact_prefix="$dir/artifacts/$t-" -print_final_stats=1 "${dict[@]}" \
    "$found" "$seeds" >"$log" 2>&1; then
    runs=$(grep -m 1 'stat::number_of_executed_units' "$log" | grep -oE '[0-9]+$' || echo '?')
    echo "fuzz: $t: $runs runs in ${seconds} s, no crash ($(ls "$found" | wc -l) corpus inputs found)"
  else
    echo "fuzz: $t FAILED (log: $log; input: $(ls -t "$dir/artifacts/$t-"* 2>/dev/null | head -n 1))"
    tail -n 40 "$log"
    failed=1
  fi
done
exit $failed
