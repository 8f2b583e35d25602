#!/usr/bin/env bash
# Lightmap benchmarks of issue #29 (docs/lightmaps.md has the figures):
#  1. the Cornell box into one 512² atlas at 200 texels/m: the whole `penumbra lightmap`
#     command's wall time and peak memory, and the RMSE of its preview.exr against the Cycles
#     reference (data/reference/cornell/, pixels of the light excluded; also split into the
#     light's edge pixels and the rest). Default settings: no extra flag is needed;
#  2. a generated office floor of about 32 000 input triangles at 20 texels/m (1024² atlases):
#     charts, atlases, coverage, stage times, wall time and peak memory.
#
#   bench/lightmap.sh [BUILD_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-build}"
penumbra="$build/penumbra"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

# Prints the run's figures from its manifest and /usr/bin/time's "%e %M".
report() {
    python3 - "$@" <<'PY'
import json, sys
name, timing, manifest = sys.argv[1:4]
seconds, kb = open(timing).read().split()
m = json.load(open(manifest))
stages = ", ".join(f"{k} {v:.2f}" for k, v in m["times_s"].items())
coverage = ", ".join(f"{a['coverage']:.3f}" for a in m["atlases"])
print(f"{name}: {float(seconds):.2f} s, peak {int(kb) / 1024:.0f} MB; {len(m['charts'])} charts, "
      f"{len(m['atlases'])} atlas(es) of {m['atlas_size']}², coverage {coverage}; "
      f"{m['texels']['covered']} texels; stages (s): {stages}")
PY
}

/usr/bin/time -f "%e %M" -o "$work/cornell.time" "$penumbra" lightmap data/cornell/scene.json \
    -o "$work/cornell" --atlas 512 --texels-per-metre 200 -q
report "Cornell box" "$work/cornell.time" "$work/cornell/lightmaps.json"
# The light (17, 12, 4 W/(sr·m²)) has luminance 0.265 × 17 + 0.670 × 12 + 0.065 × 4 = 12.81.
echo "Cornell preview RMSE against Cycles (light excluded): $("$build/bench/exr_rmse" \
    "$work/cornell/preview.exr" data/reference/cornell/cycles_4096spp.exr 12.805 --split)"

"$build/bench/office_gen" -o "$work/office" --triangles 32000 >/dev/null
/usr/bin/time -f "%e %M" -o "$work/office.time" "$penumbra" lightmap "$work/office/scene.json" \
    -o "$work/office-out" --atlas 1024 --texels-per-metre 20 -q
report "Office floor (32 k triangles)" "$work/office.time" "$work/office-out/lightmaps.json"
