#!/usr/bin/env bash
# Builds filum with AddressSanitizer and UndefinedBehaviorSanitizer (clang) in build-sanitize/
# and runs the test suite there; any sanitizer report fails the test that triggered it.
#
#   bash scripts/sanitize.sh                # every test but the stress suite (about 1 hour)
#   bash scripts/sanitize.sh --ci           # what CI runs (scripts/test.sh): builds only the core
#                                           # tests and the fuzz targets, runs labels core and fuzz
#   bash scripts/sanitize.sh --build-only   # configure and build everything, no test (scripts/fuzz.sh)
#   bash scripts/sanitize.sh --tsan         # ThreadSanitizer on the haptics tests (build-tsan/): the
#                                           # servo thread, the triple buffer (--ci runs it too)
#   bash scripts/sanitize.sh -L visual      # other arguments go to ctest The same build holds the libFuzzer targets (scripts/fuzz.sh).
# ThreadSanitizer: the only threads filum starts are haptics/'s servo loops (rendering runs Xvfb
# as a separate process): --tsan builds the haptics tests alone with it, in build-tsan/.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="$root/build-sanitize"

if ! command -v clang++ >/dev/null; then
  sudo=""
  [ "$(id -u)" -ne 0 ] && sudo="sudo"
  echo "installing: clang (sanitizers and libFuzzer)"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends clang
fi

# ThreadSanitizer cannot share a build with ASan: its own tree, only what the haptics tests need.
tsan() {
  cmake -S "$root" -B "$root/build-tsan" -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=Debug \
    -DCMAKE_CXX_FLAGS_DEBUG="-O1 -g" -DFILUM_SANITIZE=thread -DFILUM_BUILD_BENCHMARKS=OFF >/dev/null
  cmake --build "$root/build-tsan" -j"$(nproc)" --target test_haptics test_haptics_openhaptics
  TSAN_OPTIONS="halt_on_error=1:second_deadlock_stack=1" ctest --test-dir "$root/build-tsan" -j"$(nproc)" \
    --output-on-failure -L haptics
}
if [ "${1:-}" = "--tsan" ]; then
  tsan
  echo "sanitize.sh: the haptics tests passed under ThreadSanitizer"
  exit 0
fi

# RelWithDebInfo-like: -O1 keeps the sanitized suite fast enough and the reports readable.
cmake -S "$root" -B "$build" -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-O1 -g" \
  -DFILUM_SANITIZE=address,undefined -DFILUM_BUILD_FUZZERS=ON -DFILUM_BUILD_BENCHMARKS=OFF >/dev/null
targets=()
ctest_arguments=("$@")
((${#ctest_arguments[@]})) || ctest_arguments=(-LE stress)
case "${1:-}" in
  --build-only) ctest_arguments=() ;;
  --ci)
    targets=(--target test_core fuzz_scene fuzz_obj fuzz_off fuzz_ply fuzz_stl fuzz_vtp)
    ctest_arguments=(-L 'core|fuzz') ;;
esac
cmake --build "$build" -j"$(nproc)" "${targets[@]}"
[ "${1:-}" = "--build-only" ] && exit 0
# Leaks are findings too; a report aborts so the test fails; UBSan prints the stack.
asan="abort_on_error=1:strict_string_checks=1:detect_stack_use_after_return=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
# The tests that render load Mesa's GL driver through VTK, which leaks 112 bytes in 2 blocks
# from inside the driver, unloaded before the leak check can name it: they run with every check
# but the leak check.
rendering='OffscreenRenderer|FrameRecorder|RunVisual|ViewCommand'
status=0
ASAN_OPTIONS="detect_leaks=1:$asan" ctest --test-dir "$build" -j"$(nproc)" --output-on-failure -E "$rendering" \
  "${ctest_arguments[@]}" || status=1
# --ci selects labels core and fuzz, which hold no rendering test: no second pass then.
if [ "${1:-}" != "--ci" ]; then
  ASAN_OPTIONS="detect_leaks=0:$asan" ctest --test-dir "$build" -j"$(nproc)" --output-on-failure -R "$rendering" \
    "${ctest_arguments[@]}" || status=1
fi
also=""
if [ "${1:-}" = "--ci" ]; then
  tsan || status=1
  also=" (and the haptics tests under TSan)"
fi
if ((status)); then echo "sanitize.sh: some tests failed under the sanitizers (above)"; else echo "sanitize.sh: every selected test passed under ASan and UBSan$also"; fi
exit $status
