#!/usr/bin/env bash
# Installs, builds with warnings as errors and runs the whole test suite.
#   scripts/test.sh              Release build
#   scripts/test.sh --sanitize   the same suite under ASan + UBSan
#   scripts/test.sh --thread     the threaded engine's tests (edits, the parallel pool,
#                                the tile cache, change notifications, the EXR writer,
#                                hydraulic erosion's bands)
#                                under TSan
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
case "${1:-}" in
--sanitize)
  "$root/scripts/build.sh" --sanitize -DOROGEN_WERROR=ON
  dir="$root/build-sanitize"
  # intercept_tls_get_addr=0: GCC 12's LeakSanitizer misreads the dynamic TLS of the
  # dlopen'ed image module (libpng under OpenImageIO) and its tracer crashes at exit
  # ("Tracer caught signal 11"); leaks are still checked everywhere else.
  export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:intercept_tls_get_addr=0
  export LSAN_OPTIONS=suppressions=$root/tests/lsan.supp:print_suppressions=0
  export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
  ;;
--thread)
  "$root/scripts/install-deps.sh"
  dir="$root/build-tsan"
  tsan_tests=(test_edit test_cache test_parallel test_world_events test_tokenize test_cmd_job test_sculpt_drag test_erosion
    test_history_squeeze
    test_exr_write)
  cmake -S "$root" -B "$dir" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DOROGEN_TSAN=ON \
    -DOROGEN_WERROR=ON >/dev/null
  targets=()
  for t in "${tsan_tests[@]}"; do
    [ -f "$root/tests/$t.c" ] && targets+=(--target "$t")
  done
  cmake --build "$dir" -j "$(nproc)" "${targets[@]}"
  export TSAN_OPTIONS=halt_on_error=1:second_deadlock_stack=1
  cd "$dir"
  ctest --output-on-failure -j 2 -R "^($(IFS='|'; echo "${tsan_tests[*]}"))\$"
  exit
  ;;
*)
  "$root/scripts/build.sh" -DOROGEN_WERROR=ON
  dir="$root/build"
  ;;
esac
cd "$dir"
ctest --output-on-failure -j 2
