#!/usr/bin/env bash
# Builds the libFuzzer targets with clang (AddressSanitizer + UndefinedBehaviorSanitizer) and runs
# each for a bounded time on a copy of its corpus. A crash fails the script and leaves the input
# in build-fuzz/crashes/. Usage: tools/fuzz.sh [SECONDS_PER_TARGET]   (default 30)
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-30}
dir=build-fuzz
cmake -S . -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ \
  -DUAVMOT_FUZZ=ON -DUAVMOT_SANITIZE=fuzzer-no-link,address,undefined -DUAVMOT_BUILD_TESTS=OFF \
  -DUAVMOT_BUILD_BENCHMARKS=OFF >/dev/null
targets=(sample_validators config eval_files)
cmake --build "$dir" -j "$(nproc)" --target mcap_reader_fuzz "${targets[@]/%/_fuzz}"
mkdir -p "$dir/crashes"
run() {  # name binary seed-corpus
  local work="$dir/corpus/$1"
  mkdir -p "$work"
  cp -n "$3"/* "$work"/ 2>/dev/null || true
  echo "fuzz: $1 for ${seconds} s"
  "$2" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
       -artifact_prefix="$dir/crashes/$1-" "$work" 2>"$dir/$1.log" || { tail -n 30 "$dir/$1.log"; exit 1; }
  grep -E "stat::number_of_executed_units|Done" "$dir/$1.log" | tail -n 1
}
run mcap_reader "$dir/tests/mcap_reader_fuzz" components/mcap/fuzz/corpus
for t in "${targets[@]}"; do run "$t" "$dir/fuzz/${t}_fuzz" "tests/fuzz/corpus/$t"; done
echo "fuzz: no crash in ${#targets[@]}+1 targets"
