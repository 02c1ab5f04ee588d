#!/usr/bin/env bash
# Runs each libFuzzer target (tests/fuzz/) for a given time with ASan and UBSan, on a corpus
# that grows across runs (build-sanitize/fuzz/corpus/<target>/, seeded from the reference scenes
# and the test meshes), and prints how many inputs each executed and what it found.
#
#   bash scripts/fuzz.sh                 # 60 s per target
#   bash scripts/fuzz.sh 600 scene obj   # 10 min for the scene and OBJ targets
#
# A finding (crash, sanitizer report, an input slower than 10 s, more than 2 GiB) stops its
# target; the input is kept in build-sanitize/fuzz/findings/<target>/ and the script exits 1.
# Replay one: build-sanitize/tests/fuzz/fuzz_<target> <file>.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="$root/build-sanitize"
seconds="${1:-60}"
shift || true
bash "$root/scripts/sanitize.sh" --build-only

targets=("$@")
if ((${#targets[@]} == 0)); then
  for program in "$build"/tests/fuzz/fuzz_*; do targets+=("${program##*/fuzz_}"); done
fi
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
status=0
printf '%-8s %10s %8s %s\n' target inputs seconds result
for target in "${targets[@]}"; do
  program="$build/tests/fuzz/fuzz_$target"
  [ -x "$program" ] || { echo "no fuzz target '$target' (expected $program)"; exit 2; }
  corpus="$build/fuzz/corpus/$target"
  findings="$build/fuzz/findings/$target"
  log="$build/fuzz/$target.log"
  mkdir -p "$corpus" "$findings"
  result=ok
  "$program" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -max_len=65536 -print_final_stats=1 \
    -artifact_prefix="$findings/" "$corpus" "$build/tests/fuzz/seeds/$target" >"$log" 2>&1 || result="FOUND (see $log)"
  inputs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  [ "$result" = ok ] || status=1
  printf '%-8s %10s %8s %s\n' "$target" "${inputs:-?}" "$seconds" "$result"
done
exit $status
