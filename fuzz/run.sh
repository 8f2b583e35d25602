#!/usr/bin/env bash
# Fuzzes one target for a while: fuzz/run.sh TARGET SECONDS [libFuzzer options...]
# TARGET is scene_json, pts, rad, solver_state or epw. Builds the libFuzzer binaries with clang
# (not installed by scripts/setup.sh: apt-get install clang libclang-rt-14-dev) in build-fuzz/,
# then fuzzes from a copy of the checked-in corpus, fuzz/corpus/TARGET/, in
# build-fuzz/corpus/TARGET/. A finding is written to build-fuzz/findings/; fix it, then add it
# to fuzz/corpus/TARGET/ so that the replay test of the default build
# (ctest --test-dir build -L fuzz) guards it.
set -euo pipefail

if [[ $# -lt 2 ]]; then
    echo "usage: $0 TARGET SECONDS [libFuzzer options...]" >&2
    exit 2
fi
target=$1
seconds=$2
shift 2
root=$(cd "$(dirname "$0")/.." && pwd)
build=$root/build-fuzz

if [[ ! -f $build/CMakeCache.txt ]]; then
    CC=clang CXX=clang++ cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
        -DPENUMBRA_FUZZ=ON -DPENUMBRA_BUILD_TESTS=OFF -DPENUMBRA_BUILD_BENCH=OFF \
        -DPENUMBRA_BUILD_VIEWER_WINDOW=OFF >/dev/null
fi
cmake --build "$build" -j 2 --target "fuzz_$target"

# The fuzzer adds what it finds to its first folder: a scratch copy, not the checked-in seeds.
mkdir -p "$build/corpus/$target" "$build/findings"
cp -n "$root/fuzz/corpus/$target/"* "$build/corpus/$target/" 2>/dev/null || true
"$build/fuzz/fuzz_$target" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
    -artifact_prefix="$build/findings/$target-" "$@" "$build/corpus/$target"
