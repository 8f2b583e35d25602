#!/usr/bin/env bash
# A generated office floor of about 32 k input triangles (bench/office_gen: 8 × 8 offices,
# window openings in the exterior walls) with a work-plane grid of about 2 000 sensors, through
# a year of Chicago weather with Tregenza's patches (issue #31): the whole `penumbra annual`
# command's wall time and peak memory, its stages (summary.json) and the machine's load.
#
#   bench/annual_floor.sh [BUILD_DIR] [EXTRA annual FLAGS...]   (docs/annual.md has the figures)
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-build}"
shift || true
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

"$build/bench/office_gen" -o "$work/floor" --triangles 32000
# A work plane over the whole floor plate (32 × 28 m): spacing 0.63 m gives about 2 000 points.
python3 - "$work/floor/scene.json" <<'PY'
import json, sys
path = sys.argv[1]
scene = json.load(open(path))
scene["grids"] = {"floor": {"floor": "floor", "height": 0.8, "spacing": 0.63, "wall_offset": 0.3}}
json.dump(scene, open(path, "w"), indent=1)
PY
echo "load before: $(cut -d' ' -f1-3 /proc/loadavg) on $(nproc) cores"
/usr/bin/time -f "%e %M %U %S" -o "$work/time" "$build/penumbra" annual "$work/floor/scene.json" \
    --weather data/weather/chicago_ohare_tmy3.epw -o "$work/out" -q "$@"
echo "load after:  $(cut -d' ' -f1-3 /proc/loadavg)"
python3 - "$work/time" "$work/out/summary.json" <<'PY'
import json, sys
timing, summary = sys.argv[1:3]
seconds, kb, user, system = open(timing).read().split()
s = json.load(open(summary))
grid = s["grids"][0]
print(f"{s['sensors']} sensors: {float(seconds):.1f} s wall ({float(user) + float(system):.1f} s "
      f"CPU), peak {int(kb) / 1024:.0f} MB; "
      f"stages {json.dumps(s['seconds'])}; coefficients' system {s['coefficients']}; "
      f"{s['sky_patches']['count']} patches, {s['sun_bins']['count']} sun bins; "
      f"sDA {grid['sda_pct']:.1f} %, ASE {grid['ase_pct']:.1f} %"
      + (f"; mesh {s['mesh']['elements']} elements" if "mesh" in s else ""))
PY
