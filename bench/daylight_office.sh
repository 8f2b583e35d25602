#!/usr/bin/env bash
# The side-lit office of issue #30 under skies A, A-open and B: the whole `penumbra daylight`
# command's wall time for the 77 work-plane sensors and the full mesh, and its sensors against
# Radiance's (data/reference/office/radiance_<case>.csv): the mean of the per-sensor relative
# differences, its mean magnitude and the largest, B also without its row y = 2 m (on the edge
# of the sun patch, where Radiance's point sun and Penumbra's 0.5° disc differ).
#
#   bench/daylight_office.sh [BUILD_DIR]        (docs/daylight.md has the figures)
set -euo pipefail
cd "$(dirname "$0")/.."
penumbra="${1:-build}/penumbra"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

for case in A A-open B; do
    start=$(date +%s.%N)
    "$penumbra" daylight "data/office/$case.json" -o "$work/$case" -q
    end=$(date +%s.%N)
    python3 - "$case" "$work/$case/sensors.csv" "data/reference/office/radiance_$case.csv" \
        "$start" "$end" <<'PY'
import csv, sys
case, ours, theirs = sys.argv[1:4]
seconds = float(sys.argv[5]) - float(sys.argv[4])
mine = list(csv.DictReader(open(ours)))
ref = list(csv.DictReader(line for line in open(theirs) if not line.startswith("#")))
def summary(pairs):
    d = [(float(m["illuminance_total_lx"]) - float(r["illuminance_lx"])) / float(r["illuminance_lx"])
         for m, r in pairs]
    return f"{len(d)} sensors: mean {sum(d) / len(d):+.2%}, mean |.| {sum(map(abs, d)) / len(d):.2%}, " \
           f"largest {max(d, key=abs):+.1%}"
pairs = list(zip(mine, ref))
print(f"{case:7s} {seconds:6.2f} s  {summary(pairs)}")
if case == "B":
    off_edge = [p for p in pairs if abs(float(p[1]["y"]) - 2.0) > 1e-6]
    print(f"{'':7s} {'':8s}  without row y = 2 m, {summary(off_edge)}")
PY
done
