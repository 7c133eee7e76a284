#!/usr/bin/env bash
# What each lens type costs: renders a model with no lens and with one full-frame lens of each
# type (default properties, except the few a lens needs to act on the model), alternating the
# runs, and prints the best render time of each and its ratio to the lens-free frame.
#   scripts/lens-cost.sh [model] [WxH] [repeats]     (needs a build in build/)
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
model=${1:-tests/data/models/HRA_Female_Body/HRA_Female_Body.glb}
size=${2:-640x480}
repeats=${3:-3}
render=build/bin/mvcl-render
full='shape=rectangle,center=[0.5,0.5],size=[1,1]'
declare -A lens=(
    [none]=''
    [layer]="layer:$full"
    [achromatic]="achromatic:$full"
    [shadow]="shadow:$full"
    [magnifier]="magnifier:$full"
    [clip]="clip:$full"
    [xray]="xray:$full"
    [peel]="peel:$full"
    [falsecolor]="falsecolor:$full"
    [edges]="edges:$full"
    [section]="section:$full"
)
order=(none layer achromatic shadow magnifier clip xray peel falsecolor edges section)
declare -A best
for ((r = 0; r < repeats; ++r)); do
    for name in "${order[@]}"; do
        args=()
        [[ -n ${lens[$name]} ]] && args=(--lens "${lens[$name]}")
        ms=$($render "$model" --size "$size" "${args[@]}" -o /tmp/mvcl-lens-cost.png |
             sed -n 's/^render .*: \([0-9.]*\) ms$/\1/p')
        if [[ -z ${best[$name]:-} ]] || awk "BEGIN{exit !($ms < ${best[$name]})}"; then best[$name]=$ms; fi
    done
done
printf '%-11s %10s %8s\n' lens 'best ms' ratio
for name in "${order[@]}"; do
    printf '%-11s %10.1f %8.2f\n' "$name" "${best[$name]}" "$(awk "BEGIN{print ${best[$name]} / ${best[none]}}")"
done
