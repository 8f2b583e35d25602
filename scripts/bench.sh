#!/usr/bin/env bash
# Bakes the Cornell box at three element sizes; prints elements, rays, seconds per stage and
# the power balance. Then meshes the Cornell box and generated office floors with and without
# discontinuity meshing, and office floors of 32k to 1M input triangles as input (mesh_bench:
# how meshing scales), and runs hierarchical radiosity on generated office
# floors of 1k to 32k input triangles (hr_bench; a size over 10 minutes is stopped and
# reported). Build first (scripts/setup.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs)"
if [ $# -eq 0 ]; then set -- 0.10 0.05 0.04; fi
build/bench/bake_sizes data/cornell/scene.json "$@"
build/bench/mesh_bench 0.25 1 2 4 8
build/bench/mesh_bench --as-input 32k,128k,512k,1M
build/bench/hr_bench --max-seconds 600
