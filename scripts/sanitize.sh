#!/usr/bin/env bash
# Builds the tests with AddressSanitizer and UndefinedBehaviorSanitizer (gcc) in build-asan/
# and runs the unit and stat labels under them: scripts/sanitize.sh [ctest options...]
# Any report fails its test: UBSan does not recover, ASan stops at the first error, and leaks
# are reported at exit. Suppressions: a leak inside VTK 9.1 on an error path (scripts/lsan.supp).
# Environment: BUILD_DIR (default build-asan), JOBS (default 2).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${BUILD_DIR:-$root/build-asan}
jobs=${JOBS:-2}
flags="-fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer -O1 -g"

# Set before the build too: test discovery runs the sanitized test binaries.
export ASAN_OPTIONS="detect_leaks=1:strict_string_checks=1:detect_stack_use_after_return=1${ASAN_OPTIONS:+:$ASAN_OPTIONS}"
export LSAN_OPTIONS="suppressions=$root/scripts/lsan.supp:print_suppressions=0${LSAN_OPTIONS:+:$LSAN_OPTIONS}"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1${UBSAN_OPTIONS:+:$UBSAN_OPTIONS}"
# The CLI memory tests bound the CPU time of a refused run (a few seconds in Release).
export PENUMBRA_TEST_CPU_SCALE=${PENUMBRA_TEST_CPU_SCALE:-10}

# The build type's flags replace RelWithDebInfo's -O2 -DNDEBUG: assertions are checked too.
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DPENUMBRA_BUILD_BENCH=OFF \
    -DCMAKE_C_FLAGS_RELWITHDEBINFO="$flags" -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="$flags" \
    -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" >/dev/null
cmake --build "$build" -j "$jobs"

# Sanitized code runs several times slower than Release: the tests' time limits scale with it.
# The longest test takes 16–20 min sanitized on 2 shared cores, near 1800 s: an hour each.
ctest --test-dir "$build" -L 'unit|stat' --output-on-failure -j "$jobs" --timeout 3600 "$@"
