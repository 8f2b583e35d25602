#!/usr/bin/env bash
# Radiance reference illuminances for the side-lit office of issue #30: for each daylight case
# it builds the octree with oconv, runs rtrace -I on the work-plane sensors and writes
# OUT/radiance_<case>.csv (x,y,z,illuminance_lx in the .pts order). Radiance is a tool for
# making references, not a build or test dependency (scripts/reference/README.md).
#
#   scripts/reference/radiance_office.sh [--scene DIR] [--out DIR] [--ad N] [--cases "A A-open B"]
#   scripts/reference/radiance_office.sh --compare REF.csv OTHER.csv
#
# --scene: the office's Radiance files (default: data/office/ if it exists, else
# ../shared/scenes/office/, both from the repository's root). --out: default
# data/reference/office/. --ad: ambient divisions (default AD below). --compare prints the mean
# and largest |other − ref| / ref over the sensors of two such CSVs.
# Environment: RADIANCE, an install prefix holding bin/ (oconv, rtrace) and lib/ (rayinit.cal,
# skybright.cal); without it the tools come from PATH and the .cal files from RAYPATH.
# RADIANCE_COMMIT is printed with the log (the commit the tools were built from).
set -euo pipefail

# The issue's high-accuracy settings: 16 ambient bounces, no ambient cache (-aa 0: every
# ambient value is sampled, none interpolated), no super-sampling, and a weight limit so low
# that only the depth limits (-ab, -lr) end a path.
AB=16
AD=65536
AS=0
AA=0
LR=40
LW=1e-10
# Radiance's luminous efficacy and RGB luminance weights (rlux / pcomb's convention).
EFFICACY=179
WEIGHTS="0.265 0.670 0.065"

repo=$(cd "$(dirname "$0")/../.." && pwd)

die() {
    echo "radiance_office: $*" >&2
    exit 1
}

# Mean and largest relative difference of column 4 of two CSVs with the same sensors.
compare_csv() {
    [ -f "$1" ] || die "no file $1"
    [ -f "$2" ] || die "no file $2"
    paste -d, "$1" "$2" | awk -F, 'NR > 1 {
            if ($1 != $5 || $2 != $6 || $3 != $7) { print "sensor " NR - 1 " differs" > "/dev/stderr"; exit 1 }
            d = ($8 - $4) / $4; if (d < 0) d = -d
            sum += d; if (d > big) big = d; n++
        }
        END { printf "sensors %d  mean |diff|/ref %.4f  max %.4f\n", n, sum / n, big }'
}

default_scene() {
    for dir in "$repo/data/office" "$repo/../shared/scenes/office"; do
        if [ -d "$dir" ]; then
            (cd "$dir" && pwd)
            return
        fi
    done
    die "no data/office/ nor ../shared/scenes/office/ beside $repo; pass --scene DIR"
}

scene=""
out="$repo/data/reference/office"
cases="A A-open B"
while [ $# -gt 0 ]; do
    case "$1" in
    --scene) scene=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    --ad) AD=$2; shift 2 ;;
    --cases) cases=$2; shift 2 ;;
    --compare)
        [ $# -eq 3 ] || die "--compare takes two CSV files"
        compare_csv "$2" "$3"
        exit 0
        ;;
    *) die "unknown argument '$1' (see the comment at the top of $0)" ;;
    esac
done
[ -n "$scene" ] || scene=$(default_scene)

if [ -n "${RADIANCE:-}" ]; then
    PATH="$RADIANCE/bin:$PATH"
    RAYPATH=".:$RADIANCE/lib"
fi
export PATH RAYPATH="${RAYPATH:-.}"
for tool in oconv rtrace; do
    command -v "$tool" >/dev/null || die "$tool not found (set RADIANCE to Radiance's install prefix)"
done

# The scene files of each case, in oconv's order: materials before the surfaces that use
# them, and each gensky sky before skyglow.rad whose glow hemispheres its skyfunc drives.
# oconv -f freezes the objects into the octree, which rtrace would otherwise re-read by
# file name from its own directory.
# Sets the array files.
set_case_files() {
    case "$1" in
    A) files=(materials.rad office.rad window_glazed.rad sky_A_overcast.rad skyglow.rad) ;;
    A-open) files=(materials.rad office.rad sky_A_overcast.rad skyglow.rad) ;;
    B) files=(materials.rad office.rad window_glazed.rad sky_B_clear_sun.rad skyglow.rad) ;;
    *) die "unknown case '$1' (A, A-open or B)" ;;
    esac
    for f in "${files[@]}"; do [ -f "$scene/$f" ] || die "no $scene/$f (case $1)"; done
}
for name in $cases; do set_case_files "$name"; done

sensors="$scene/sensors_workplane.pts"
[ -f "$sensors" ] || die "no $sensors"
mkdir -p "$out"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
rtrace_options=(-I -h -ab "$AB" -ad "$AD" -as "$AS" -aa "$AA" -lr "$LR" -lw "$LW")

echo "radiance_office: $(rtrace -version 2>&1 | head -1), commit ${RADIANCE_COMMIT:-unknown}"
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs)"
echo "scene: $scene"
for name in $cases; do
    set_case_files "$name"
    (cd "$scene" && oconv -f "${files[@]}") >"$work/$name.oct"
    echo "case $name"
    echo "  (cd $scene && oconv -f ${files[*]}) > $name.oct"
    echo "  rtrace ${rtrace_options[*]} $name.oct < sensors_workplane.pts"
    TIMEFORMAT="  rtrace wall %R s, user %U s, system %S s"
    time rtrace "${rtrace_options[@]}" "$work/$name.oct" <"$sensors" >"$work/$name.rgb"
    # Illuminance = efficacy × (weights · RGB irradiance); x, y, z as the .pts file gives them.
    awk -v k="$EFFICACY" -v w="$WEIGHTS" '
        BEGIN { split(w, c, " ") }
        NF >= 3 { printf "%.6g\n", k * (c[1] * $1 + c[2] * $2 + c[3] * $3) }' \
        "$work/$name.rgb" >"$work/$name.lx"
    awk 'NF >= 6 { print $1 "," $2 "," $3 }' "$sensors" >"$work/$name.xyz"
    [ "$(wc -l <"$work/$name.xyz")" -eq "$(wc -l <"$work/$name.lx")" ] ||
        die "rtrace gave $(wc -l <"$work/$name.lx") values for $(wc -l <"$work/$name.xyz") sensors"
    {
        echo "x,y,z,illuminance_lx"
        paste -d, "$work/$name.xyz" "$work/$name.lx"
    } >"$out/radiance_$name.csv"
    awk -F, 'NR > 1 { s += $4; n++ } END { printf "  %d sensors, mean %.1f lx -> %s\n", n, s / n, FILENAME }' \
        "$out/radiance_$name.csv"
done
