#!/usr/bin/env bash
# The glazed side-lit office (data/office/A.json, its 77 sensors and 77-point grid) through a
# year of Chicago weather (issue #31): the whole `penumbra annual` command's wall time and
# peak memory, the coefficients' and the hours' shares, for Tregenza's patches and MF 4.
#
#   bench/annual_office.sh [BUILD_DIR]        (docs/annual.md has the figures)
set -euo pipefail
cd "$(dirname "$0")/.."
penumbra="${1:-build}/penumbra"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

for mf in 1 4; do
    /usr/bin/time -f "%e %M" -o "$work/time" "$penumbra" annual data/office/A.json \
        --weather data/weather/chicago_ohare_tmy3.epw --patches "$mf" -o "$work/mf$mf" -q
    python3 - "$mf" "$work/time" "$work/mf$mf/summary.json" <<'PY'
import json, sys
mf, timing, summary = sys.argv[1:4]
seconds, kb = open(timing).read().split()
s = json.load(open(summary))
grid = s["grids"][0]
print(f"MF {mf}: {float(seconds):6.2f} s, peak {int(kb) / 1024:.0f} MB; coefficients "
      f"{s['seconds']['coefficients']:.2f} s ({s['sky_patches']['count']} patches, "
      f"{s['sun_bins']['count']} sun bins), hours {s['seconds']['hours']:.2f} s; "
      f"sDA {grid['sda_pct']:.1f} %, ASE {grid['ase_pct']:.1f} %")
PY
done
