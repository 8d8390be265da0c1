#!/usr/bin/env bash
# The README's test command (and CI's, via .ci/run): installs dependencies, builds, runs the whole
# test suite, the README's demo from a bare clone in an empty folder (fresh-clone), the whole suite
# again under ASan + UBSan, the DDS tests under TSan, then every fuzz target for a bounded time
# (docs/developing.md has each stage and its time).
# Locally, UAVMOT_SKIP_STAGES="asan tsan fuzz" (any stage names) skips stages;
# UAVMOT_SANITIZER_STAGES=0 skips both sanitizer stages.
set -euo pipefail
cd "$(dirname "$0")/.."
skip=" ${UAVMOT_SKIP_STAGES:-} "
if [[ ${UAVMOT_SANITIZER_STAGES:-1} == 0 ]]; then skip+=" asan tsan "; fi
fuzz_seconds=${UAVMOT_FUZZ_SECONDS:-20}
# A disk that fills half-way fails tests with misleading errors ("No space left on device" in a
# recorder, an unwritable frame), so the run first checks that what its stages write fits: a clean
# clone grew by 10.2 GiB over a full run (2026-11-27: build and tests 2.2, ASan 6.8, TSan and
# fuzzing 1.2); the estimates below (GiB, rounded up) add a margin. UAVMOT_MIN_FREE_GIB overrides.
declare -A stage_gib=([deps]=0 [build]=2 [tests]=1 [fresh-clone]=1 [asan]=8 [tsan]=1 [fuzz]=1)
timings=()
free_gib() { df -Pk . | awk 'NR == 2 { printf "%d", $4 / 1048576 }'; }
need_gib=0
for name in "${!stage_gib[@]}"; do
  [[ $skip == *" $name "* ]] || need_gib=$((need_gib + stage_gib[$name]))
done
need_gib=${UAVMOT_MIN_FREE_GIB:-$need_gib}
if [[ ! $need_gib =~ ^[0-9]+$ ]]; then
  echo "test.sh: UAVMOT_MIN_FREE_GIB='$need_gib': expected a whole number of GiB" >&2
  exit 2
fi
if (($(free_gib) < need_gib)); then
  echo "test.sh: $(free_gib) GiB free on $(df -P . | awk 'NR == 2 { print $6 }'), the stages to run need about $need_gib GiB (UAVMOT_MIN_FREE_GIB to override); free some space and run again" >&2
  exit 1
fi
stage() {  # name command...
  local name=$1 start=$SECONDS
  shift
  # A stage without a disk estimate would count 0 GiB in the check above: name it in stage_gib.
  [[ -v "stage_gib[$name]" ]] || { echo "test.sh: stage $name has no disk estimate in stage_gib" >&2; exit 2; }
  if [[ $skip == *" $name "* ]]; then
    echo "test.sh: stage $name skipped (UAVMOT_SKIP_STAGES or UAVMOT_SANITIZER_STAGES=0)"
    timings+=("$name: skipped")
    return
  fi
  echo "test.sh: stage $name ($(free_gib) GiB free)"
  "$@"
  timings+=("$name: $((SECONDS - start)) s")
}

tests() {
  local build_dir=${UAVMOT_BUILD_DIR:-build} failed=0
  # Each gtest binary writes its report here (what it skipped, and why), ctest its own beside it:
  # tools/check_skips.py fails the stage for a skip tools/expected_skips.txt does not list.
  local reports
  reports=$(realpath -m "$build_dir/test_reports")
  rm -rf "$reports"
  mkdir -p "$reports/gtest"
  export GTEST_OUTPUT="xml:$reports/gtest/"
  # Integration tests start real Fast DDS processes; run them one at a time so they
  # do not compete for the two cores and shared-memory segments. Every test runs before the stage
  # fails, also when the first half failed.
  ctest --test-dir "$build_dir" --output-on-failure -j 2 -LE serial --output-junit "$reports/ctest_parallel.xml" || failed=1
  # Shared-memory segments left by killed Fast DDS processes of earlier runs on this machine.
  fastdds shm clean >/dev/null 2>&1 || true
  ctest --test-dir "$build_dir" --output-on-failure -L serial --output-junit "$reports/ctest_serial.xml" || failed=1
  unset GTEST_OUTPUT
  python3 tools/check_skips.py tools/expected_skips.txt "$reports/gtest" "$reports/ctest_parallel.xml" \
    "$reports/ctest_serial.xml" || failed=1
  # Last, so that the tail CI keeps says why each failed test failed, not only which.
  python3 tools/report_failures.py "$reports/gtest" "$reports/ctest_parallel.xml" "$reports/ctest_serial.xml" || true
  return "$failed"
}

stage deps bash tools/install_deps.sh
stage build bash tools/build.sh
stage tests tests
stage fresh-clone bash tools/fresh_clone_demo.sh
stage asan bash tools/sanitize.sh address
stage tsan bash tools/sanitize.sh thread
stage fuzz bash tools/fuzz.sh "$fuzz_seconds"
printf 'test.sh: %s\n' "${timings[@]}"
