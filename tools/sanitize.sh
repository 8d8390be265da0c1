#!/usr/bin/env bash
# Builds uavmot with sanitizers (GCC, RelWithDebInfo, separate build folder) and runs tests under them.
#   tools/sanitize.sh address   ASan + UBSan in build-asan: the whole ctest suite
#   tools/sanitize.sh thread    TSan in build-tsan: the tests of the threaded and DDS code
# Extra arguments go to every ctest call (e.g. -R dds_tests); --build-only builds and stops. Findings fail the run: ASan and
# TSan exit non-zero at the first report, UBSan aborts (-fno-sanitize-recover, cmake/UavmotHelpers.cmake).
# Fast DDS, OpenCV, Ceres and the other system libraries are not instrumented; what they do is
# suppressed narrowly in tools/sanitizers/*.supp, each entry with its reason. Never uavmot code.
set -euo pipefail
cd "$(dirname "$0")/.."
kind=${1:?usage: tools/sanitize.sh address|thread [ctest args]}
shift
root=$(pwd)
supp=$root/tools/sanitizers
export CCACHE_BASEDIR=${CCACHE_BASEDIR:-$(cd .. && pwd)}
# These builds have -g, for which ccache also hashes the build folder's absolute path: without this,
# a clone in another folder (CI's) finds nothing in the cache and rebuilds for 18 + 8 min.
export CCACHE_NOHASHDIR=${CCACHE_NOHASHDIR:-1}
# -O1 as the sanitizers' documentation suggests: faster to build than -O2/-O3, still fast enough to run.
# -g1 (line tables, no variables): reports keep file:line, while the build is cheaper than with -g, which
# counts when CI, limited to 90 minutes, finds these objects missing from its cache.
common=(-G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1 -DNDEBUG" -DUAVMOT_WERROR=ON
        -DUAVMOT_BUILD_BENCHMARKS=OFF)

# compose_integration_test builds container images from the Release binaries' runtime packages:
# it tests the packaging, and the instrumented binaries would lack their sanitizer runtime in there.
# fault_injection and watchdog assert recovery times and health silence in seconds, which the
# instrumented processes (2-5x slower) do not keep; the restart paths they drive run under ASan in
# tracker_restart, tracker_resume and sink_faults.
# The four long accuracy tests (150-250 frames of 1-3 chains each, 19 min of test time under ASan) run the same code
# as the shorter scenario, unit and integration tests that do run here; left out so the whole CI run
# fits its 90 minutes (docs/developing.md, "CI stages").
not_here='^(compose_integration_test|fault_injection_integration_test|watchdog_integration_test'
not_here+='|chain_paper_scenario_test|scripted_flights_scenario_test|chain_structure_scenario_test|real_video_scenario_test)$'

case $kind in
  address)
    dir=${UAVMOT_ASAN_BUILD_DIR:-build-asan}
    cmake -S . -B "$dir" "${common[@]}" -DUAVMOT_SANITIZE=address,undefined >/dev/null
    targets=(all)
    # new_delete_type_mismatch=0: Fast DDS 2.9 deletes every DataReader's StatisticsReaderImpl (64 bytes)
    # through RTPSReader's sized delete (56 bytes) inside libfastrtps; ASan has no suppression by
    # stack for this check, so it is off. -Wnon-virtual-dtor (errors) covers the usual cause in our code.
    export ASAN_OPTIONS=halt_on_error=1:detect_leaks=1:detect_stack_use_after_return=1:strict_string_checks=1:check_initialization_order=1:strict_init_order=1:new_delete_type_mismatch=0
    export LSAN_OPTIONS=suppressions=$supp/lsan.supp:print_suppressions=0
    export UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1:suppressions=$supp/ubsan.supp
    ;;
  thread)
    dir=${UAVMOT_TSAN_BUILD_DIR:-build-tsan}
    cmake -S . -B "$dir" "${common[@]}" -DUAVMOT_SANITIZE=thread >/dev/null
    # Verified clean: mcap_tests (QueuedWriter's thread), dds_tests, record_tests and rogue_writer (four
    # instrumented nodes over DDS). Not yet: the tests that run the whole chain (chain_launch,
    # tracker_restart, live_status, record_replay) still report hand-overs inside uninstrumented
    # OpenCV/TBB and FFmpeg (libavutil) threads; frame_transport asserts millisecond pacing TSan breaks.
    targets=(mcap_tests dds_tests record_tests rogue_writer_integration_test)
    export TSAN_OPTIONS="halt_on_error=1:second_deadlock_stack=1:history_size=4:suppressions=$supp/tsan.supp"
    ;;
  *) echo "tools/sanitize.sh: unknown kind '$kind' (address or thread)" >&2; exit 2 ;;
esac

echo "sanitize $kind: building ${targets[*]} in $dir (log: $dir/build.log)"
start=$SECONDS
cmake --build "$dir" -j "$(nproc)" --target "${targets[@]}" >"$dir/build.log" 2>&1 || { tail -n 60 "$dir/build.log"; exit 1; }
echo "sanitize $kind: built in $((SECONDS - start)) s"
if [[ ${1:-} == --build-only ]]; then exit 0; fi

start=$SECONDS
if [[ $kind == address ]]; then
  ctest --test-dir "$dir" --output-on-failure -j 2 -LE serial -E "$not_here" "$@"
  ctest --test-dir "$dir" --output-on-failure -L serial -E "$not_here" "$@"
else
  ctest --test-dir "$dir" --output-on-failure -R "^($(IFS='|'; echo "${targets[*]}"))\$" "$@"
fi
echo "sanitize $kind: tests passed in $((SECONDS - start)) s"
