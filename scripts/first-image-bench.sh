#!/usr/bin/env bash
# From the file to the first image in the viewer, for docs/benchmarks.md ("From the file to the
# first image"): the HRA body three times side by side (1.18 million triangles, written by
# scripts/replicate-gltf.py) opened by a script in a running viewer under Xvfb (Mesa llvmpipe),
# 1280x720 view, the cube-in-cube scene with a lens on screen when `open` runs. Prints the
# viewer's own timings of each run: scene shown (with its BVH's build time), first image,
# layers inferred. Usage: scripts/first-image-bench.sh [rounds] [model.glb]
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
viewer="${MVCL_BUILD_DIR:-$repo/build}/bin/mvcl-viewer"
rounds="${1:-5}"
work="${TMPDIR:-/tmp}/mvcl-first-image"
mkdir -p "$work"
model="${2:-$work/HRA_Female_Body-x3.glb}"
if [ ! -f "$model" ]; then
  python3 "$repo/scripts/replicate-gltf.py" "$repo/tests/data/models/HRA_Female_Body/HRA_Female_Body.glb" "$model" 3
fi
cat >"$work/open.txt" <<SCRIPT
wait-converged
add-lens layer 0.5 0.5
open $model
wait-converged
quit
SCRIPT
echo "$(lscpu | sed -n 's/^Model name: *//p'), load average $(cut -d' ' -f1-3 /proc/loadavg)"
for ((round = 1; round <= rounds; ++round)); do
  rm -f "$work/recovery.json" # a copy left by an earlier run would be offered at the start (a modal)
  xvfb-run -a -s '-screen 0 1700x800x24' "$viewer" --size 1660x720 --recovery "$work/recovery.json" \
    --script "$work/open.txt" 2>&1 | grep -E "showing|first image|inferred|full BVH" | sed "s/^mvcl-viewer: /$round: /"
done
