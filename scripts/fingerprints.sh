#!/usr/bin/env bash
# Prints a fingerprint of every result of a set of bakes: the sha256 of each output file and
# the link, ray and shot counts of summary.json. Two builds that print the same lines give
# bitwise the same results; refactors are checked with it (docs/architecture.md).
#
#   scripts/fingerprints.sh [BUILD_DIR] > fingerprints.txt
#
# Scenes: the Cornell box (hierarchical, re-solved from its own state, Gauss–Seidel sweeps,
# shooting, Jacobi on fixed elements), the CIE 171 5.8 cube, a room with a
# sun, a spot and an area light through a roof opening, and a generated 2x2 office floor.
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-build}"
penumbra="$build/penumbra"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

fingerprint() { # name, then bake arguments
    local name="$1"
    shift
    "$penumbra" bake "$@" -o "$work/$name" -q >/dev/null
    (cd "$work/$name" && find . -type f ! -name summary.json | LC_ALL=C sort | xargs sha256sum) |
        sed "s|  \./|  $name/|"
    python3 - "$work/$name/summary.json" "$name" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
def walk(d, path=""):
    for k, v in sorted(d.items()):
        p = f"{path}.{k}" if path else k
        if isinstance(v, dict):
            walk(v, p)
        elif "second" not in p and "time" not in p and k != "scene_file":
            print(f"{sys.argv[2]}/summary {p} = {json.dumps(v)}")
walk(s)
PY
}

fingerprint cornell data/cornell/scene.json
fingerprint cornell-reuse data/cornell/scene.json --reuse "$work/cornell" --no-render
fingerprint cornell-gauss-seidel data/cornell/scene.json --iteration gauss_seidel --no-render
fingerprint cornell-shooting data/cornell/scene.json --method shooting
fingerprint cornell-jacobi data/cornell/scene.json --method jacobi --max-edge 0.1 --no-render
fingerprint cie-cube data/tests/fingerprint/cie_cube.json
fingerprint sun-spot data/tests/fingerprint/sun_spot.json
if [ -x "$build/bench/office_gen" ]; then
    "$build/bench/office_gen" -o "$work/office-scene" --rooms-x 2 --rooms-y 2 >/dev/null
    fingerprint office-2x2 "$work/office-scene/scene.json" --no-render
fi
