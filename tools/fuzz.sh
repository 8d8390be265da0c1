#!/usr/bin/env bash
# Builds the libFuzzer targets (tests/fuzz/fuzz_targets.hpp) with clang, the whole tree under
# -fsanitize=fuzzer-no-link,address,undefined, and runs each for a bounded time on a copy of its
# seed corpus (tests/fuzz/corpus/<target>/). A crash fails the script and leaves the input in
# build-fuzz/crashes/; add it to tests/fuzz/regressions/<target>/ with the fix.
#   tools/fuzz.sh [SECONDS_PER_TARGET]   (default 30)
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-30}
dir=${UAVMOT_FUZZ_BUILD_DIR:-build-fuzz}
export CCACHE_BASEDIR=${CCACHE_BASEDIR:-$(cd .. && pwd)}
targets=(mcap_reader sample_validators config eval_files recording motion_state segmentation_state)
cmake -S . -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ \
  -DUAVMOT_FUZZ=ON -DUAVMOT_BUILD_TESTS=OFF -DUAVMOT_BUILD_BENCHMARKS=OFF >/dev/null
echo "fuzz: building ${targets[*]/%/_fuzz} in $dir (log: $dir/build.log)"
cmake --build "$dir" -j "$(nproc)" --target "${targets[@]/%/_fuzz}" >"$dir/build.log" 2>&1 ||
  { tail -n 40 "$dir/build.log"; exit 1; }
mkdir -p "$dir/crashes"
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
# The config and eval targets write their input to a file: on tmpfs they run ~10x faster than on /tmp here.
if [[ -z ${TMPDIR:-} && -d /dev/shm && -w /dev/shm ]]; then export TMPDIR=/dev/shm; fi
total_runs=0
for t in "${targets[@]}"; do
  work="$dir/corpus/$t"
  mkdir -p "$work"
  cp -n tests/fuzz/corpus/"$t"/* "$work"/
  if [[ -d tests/fuzz/regressions/$t ]]; then cp -n tests/fuzz/regressions/"$t"/* "$work"/; fi
  echo "fuzz: $t for ${seconds} s"
  if ! "$dir/fuzz/${t}_fuzz" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
       -artifact_prefix="$dir/crashes/$t-" "$work" 2>"$dir/$t.log"; then
    tail -n 40 "$dir/$t.log"
    echo "fuzz: $t FAILED; the input is in $dir/crashes/" >&2
    exit 1
  fi
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$dir/$t.log")
  echo "fuzz: $t: $runs inputs, corpus $(ls "$work" | wc -l) files, no crash"
  total_runs=$((total_runs + runs))
done
echo "fuzz: no crash in ${#targets[@]} targets ($total_runs inputs)"
