#!/usr/bin/env bash
# Runs issue #32's hostile and careless inputs against a built penumbra and prints a Markdown
# table: case, exit code, wall time, the last error or warning on stderr (what the user reads)
# and the test that asserts the case.
#   scripts/hostile_cases.sh [PENUMBRA]     (default build/penumbra)
# Each case has a test that asserts its outcome (tests/app/cli_*_test.cpp, tests/core/): this
# script is the record of what a user sees, kept in docs/reliability.md. About a minute.
# Exit codes: 0 success, 2 input, 3 setting or limit, 4 output, 130/143 SIGINT/SIGTERM.
set -uo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
penumbra=$(realpath "${1:-$root/build/penumbra}")
[[ -x $penumbra ]] || { echo "hostile_cases: no penumbra at $penumbra (build first)" >&2; exit 2; }
work=$(mktemp -d /tmp/penumbra-hostile.XXXXXX)
trap 'rm -rf "$work"' EXIT
cd "$work"
cp "$root/data/cornell/cornell.obj" "$root/data/cornell/cornell.mtl" .

# The Cornell box (millimetres) with one change: scene NAME 'JSON members'.
scene() {
    cat >"$1.json" <<EOF
{ "units": "mm", "up": [0, 1, 0], "geometry": "${3:-cornell.obj}",
  "materials": { "light": { "emission_two_sided": false } },
  "mesher": { "max_edge_length": 100 }${2:+, $2} }
EOF
}

seconds() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.1f", b - a }'; }

# row CASE TEST COMMAND...: runs COMMAND (at most $limit s, default 120) and prints its table
# row; TEST is the test that asserts the case.
row() {
    local name=$1 test=$2
    shift 2
    local start end rc message
    start=$(date +%s.%N)
    timeout "${limit:-120}" "$@" >stdout.txt 2>stderr.txt
    rc=$?
    end=$(date +%s.%N)
    # The last error or warning, else the last line (progress lines say what a long run does).
    message=$({ grep -E 'error:|warning:' stderr.txt || grep -v '^[[:space:]]*$' stderr.txt; } |
        tail -n 1 | cut -c 1-320 | sed 's/|/\\|/g')
    [[ $rc -eq 124 ]] && rc="(runs; stopped at ${limit:-120} s)"
    printf '| %s | %s | %s s | %s | `%s` |\n' "$name" "$rc" "$(seconds "$start" "$end")" "$message" \
        "$test"
}

bake() { "$penumbra" bake "$@"; }  # outside row, which needs a program

echo "| case | exit | time | message (stderr's last error or warning, else its last line) | test |"
echo "|---|---|---|---|---|"

scene box
row "--max-edge 1e-6" CliBudget.ElementSizeFarBelowTheBudgetIsRefusedBeforeMeshing "$penumbra" bake box.json -o out -q --max-edge 1e-6
limit=20 row "--max-edge 1e-3" Mesher.ElementBudgetCoarsensTheMesh "$penumbra" bake box.json -o out --no-render --max-edge 1e-3
scene eps '"solver": { "epsilon": 1e-12 }'
row "solver.epsilon 1e-12, --max-memory 200M" CliMemory.EpsilonGrowingLinksWithoutBoundIsStopped "$penumbra" bake eps.json -o out -q --max-memory 200M
scene area '"solver": { "min_area": 1e-30 }'
row "solver.min_area 1e-30" CliBudget.MinimumAreaFarBelowTheBudgetIsRefused "$penumbra" bake area.json -o out -q

{
    echo "v 0 0 0"; echo "v 1 0 0"; echo "v 0 1 0"; echo "v 0 0 1"; echo "v 1 0 1"; echo "v 0 1 1"
    printf 'f 4 5 6\nf'; for ((i = 0; i < 10000; ++i)); do printf ' 1 2 3'; done; echo
} >repeat.obj
cat >repeat.json <<EOF
{ "geometry": "repeat.obj", "materials": { "defaultobject": { "emission": [1, 1, 1] } } }
EOF
row "OBJ face of one triangle's indices × 10 000" SceneIo.FaceVisitingAPointTwiceIsAnError "$penumbra" bake repeat.json -o out -q

scene flux && sed -i 's/"emission_two_sided": false/&, "emission_flux_lm": 1e39/' flux.json
row "emission_flux_lm 1e39" SceneIo.FluxBeyondTheFloatRangeIsAnError "$penumbra" bake flux.json -o out -q
scene sensor '"sensors": [ { "position": [1e308, 0, 0], "normal": [0, 1, 0] } ]'
row "sensor at 1e308" SceneIo.PositionsAndToleranceOutOfRangeAreErrors "$penumbra" bake sensor.json -o out -q
scene contact && sed -i 's/"max_edge_length": 100/&, "contact_tolerance": 1e308/' contact.json
row "mesher.contact_tolerance 1e308" SceneIo.PositionsAndToleranceOutOfRangeAreErrors "$penumbra" bake contact.json -o out -q
for flag in "--max-edge nan" "--epsilon nan" "--residual nan" "--min-area nan" \
    "--max-edge 1e400" "--epsilon 5"; do
    # shellcheck disable=SC2086 # the flag and its value are two words
    row "$flag" CliBadInput.NonFiniteOrOutOfRangeFlagsAreOneLineErrors "$penumbra" bake box.json -o out -q $flag
done
scene light '"point_lights": [ { "name": "bulb", "position": [278, 0, 279.6], "intensity_cd": 100 } ]'
row "point light on the floor" CliBadInput.PointLightOnASurface "$penumbra" bake light.json -o out -q

sed 's/cornell.mtl/missing.mtl/' cornell.obj >nomtl.obj
scene nomtl "" nomtl.obj
row "missing mtllib" SceneIo.MissingMaterialLibraryFolderAndLongLinesAreClearErrors "$penumbra" bake nomtl.json -o out -q

bake box.json -o good --no-render -q
cp -r good corrupt
printf '\x5a\x5a\x5a' | dd of=corrupt/solver_state.bin bs=1 seek=4096 conv=notrunc status=none
row "--reuse of a state file with 3 corrupted bytes" Reuse.StateFileRefusesEveryCorruptedByte "$penumbra" bake box.json -o out -q --reuse corrupt

scene sensors '"sensors": [ { "position": [278, 0, 279.6], "normal": [0, 1, 0] } ]'
bake sensors.json -o rebake --no-render -q
before=$([[ -e rebake/sensors.csv ]] && echo present || echo absent)
row "re-bake into an old folder, no sensors now" CliOutputs.RebakeRemovesTheEarlierBakesOtherFiles "$penumbra" bake box.json -o rebake --no-render -q
echo "|   (the old folder's sensors.csv) | | | before: $before; after: $([[ -e rebake/sensors.csv ]] && echo left || echo removed) | |"

mkdir adir
row "view --png /dev/full" CliOutputs.NeverReplacesWhatIsNotARegularFile "$penumbra" view good --png /dev/full
row "view --png onto a folder" CliOutputs.NeverReplacesWhatIsNotARegularFile "$penumbra" view good --png adir

# A signal while the bake runs (its state file and mesh.vtu are written at the end: the signal
# lands in the solve or the writing); no temporary file may be left.
for sig in INT TERM; do
    start=$(date +%s.%N)
    "$penumbra" bake box.json -o "sig$sig" -q --max-edge 0.02 2>stderr.txt &
    pid=$!
    sleep 3
    kill -s "$sig" "$pid"
    wait "$pid"
    rc=$?
    end=$(date +%s.%N)
    left=$(find . -name '*.tmp*' | wc -l)
    printf '| SIG%s 3 s into a bake | %s | %s s | temporary files left: %s | `%s` |\n' "$sig" "$rc" \
        "$(seconds "$start" "$end")" "$left" CliOutputs.SignalWhileWritingLeavesNoTemporaryFile
done

# A full disk, as a file size limit (SIGXFSZ ignored, so the write fails with EFBIG).
row "full disk (ulimit -f 64, SIGXFSZ ignored)" CliFullDisk.CornellBakeStopsAtTheFileTooLarge \
    bash -c "ulimit -f 64; trap '' XFSZ; exec '$penumbra' bake box.json -o full -q --no-render"
echo "|   (what the full disk's bake left) | | | full/: $(ls -A full 2>/dev/null | tr '\n' ' ')| |"

scene eye '"camera": { "eye": [1e308, 0, 0], "look_at": [278, 273, 0], "up": [0, 1, 0], "fov_deg": 40 }'
row "camera eye at 1e308" SceneIo.PositionsAndToleranceOutOfRangeAreErrors "$penumbra" bake eye.json -o out -q
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n' >bad.gltf # OBJ's text: assimp took it for OBJ
scene gltf "" bad.gltf
row "garbage .gltf as geometry" SceneIo.BrokenGltfIsAGltfError "$penumbra" bake gltf.json -o out -q
mkdir geodir
scene dir "" geodir
row "a folder as geometry" SceneIo.MissingMaterialLibraryFolderAndLongLinesAreClearErrors "$penumbra" bake dir.json -o out -q
{ echo "0 0 0 0 1 0"; head -c 10000000 /dev/zero | tr '\0' '9'; echo; } >long.pts
scene pts '"sensors": { "file": "long.pts" }'
row "10 MB bad line in a .pts file" SceneIo.MissingMaterialLibraryFolderAndLongLinesAreClearErrors "$penumbra" bake pts.json -o out -q
[[ ! -e out ]] || echo "hostile_cases: a refused case left out/ behind" >&2
