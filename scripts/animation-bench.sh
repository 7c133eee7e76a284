#!/usr/bin/env bash
# What an animation costs against single renders of its frames (docs/benchmarks.md, "Animations"):
# a 60-frame turntable and a 60-frame lens sweep with a fixed camera, HRA female body, 640x480,
# 1 spp. Each animation runs in one process (one scene load, one BVH, one render session); each
# single render is its own process that renders one frame of the same animation (--frames i-i:
# the same camera and lens values, one full pass), whose "render" line is its render time alone.
#
#   scripts/animation-bench.sh [frames]        (default 60; build first: build/bin/mvcl-render)
set -euo pipefail

repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
render="${MVCL_BUILD_DIR:-$repo/build}/bin/mvcl-render"
frames="${1:-60}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
cd "$repo"

common=(--no-progress --lenses assets/lenses/HRA_Female_Body.json --size 640x480 --spp 1)
now() { date +%s.%N; }
# "render     640x480, 1 spp: 1234.5 ms ..." → 1234.5
renderMilliseconds() { sed -n 's/^render  *[0-9]*x[0-9]*, [^:]*: \([0-9.]*\) ms.*/\1/p' "$1"; }

echo "cpu        $(lscpu | sed -n 's/^Model name: *//p'), $(nproc) cores"
measure() {
    local name="$1"
    shift
    local start end
    start=$(now)
    "$render" "${common[@]}" "$@" -o "$work/$name/%04d.png" > "$work/$name.log"
    end=$(now)
    local animationMs wallMs singlesMs=0 i ms
    animationMs=$(renderMilliseconds "$work/$name.log")
    wallMs=$(awk -v a="$start" -v b="$end" 'BEGIN { print (b - a) * 1000 }')
    for ((i = 0; i < frames; ++i)); do
        "$render" "${common[@]}" "$@" --frames "$i-$i" -o "$work/single/%04d.png" > "$work/single.log"
        ms=$(renderMilliseconds "$work/single.log")
        singlesMs=$(awk -v a="$singlesMs" -v b="$ms" 'BEGIN { print a + b }')
    done
    grep -E '^(render|wrote)' "$work/$name.log"
    printf '%-10s animation: %.0f ms rendering, %.0f ms for the whole process; %d single renders: %.0f ms rendering\n' \
        "$name" "$animationMs" "$wallMs" "$frames" "$singlesMs"
    printf '%-10s ratio      %.3f (rendering) / %.3f (whole animation process) x the single renders\n' "$name" \
        "$(awk -v a="$animationMs" -v b="$singlesMs" 'BEGIN { print a / b }')" \
        "$(awk -v a="$wallMs" -v b="$singlesMs" 'BEGIN { print a / b }')"
}
measure turntable --turntable "$frames"
measure sweep --sweep skeleton.distance=0:0.6 --frame-count "$frames"
