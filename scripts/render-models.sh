#!/usr/bin/env bash
# Renders every model of tests/data/models with mvcl-render and prints one Markdown table row per
# model: triangles, BVH build, render time, rays and Mrays/s. Used for docs/benchmarks.md.
#   scripts/render-models.sh [WxH] [spp]      (default 800x600, 4 spp; images go to out/models/)
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
render="${MVCL_BUILD_DIR:-$repo/build}/bin/mvcl-render"
size="${1:-800x600}"
spp="${2:-4}"
mkdir -p "$repo/out/models"
echo "| model | triangles | layers | BVH build ms | render ms | Mrays | Mrays/s |"
echo "|---|---|---|---|---|---|---|"
for model in "$repo"/tests/data/models/*/*.glb; do
  name="$(basename "$model" .glb)"
  summary="$("$render" "$model" --no-progress --size "$size" --spp "$spp" -o "$repo/out/models/$name.png")"
  triangles="$(sed -n 's/^geometry *\([0-9]*\) triangles.*/\1/p' <<<"$summary")"
  layers="$(sed -n 's/.* \([0-9]*\) layers.*/\1/p' <<<"$summary")"
  build="$(sed -n 's/^bvh *\([0-9.]*\) ms.*/\1/p' <<<"$summary")"
  ms="$(sed -n 's/^render .*: \([0-9.]*\) ms/\1/p' <<<"$summary")"
  mrays="$(sed -n 's/^rays *\([0-9.]*\) M.*/\1/p' <<<"$summary")"
  rate="$(sed -n 's/.*, \([0-9.]*\) Mrays\/s/\1/p' <<<"$summary")"
  echo "| $name | $triangles | $layers | $build | $ms | $mrays | $rate |"
done
