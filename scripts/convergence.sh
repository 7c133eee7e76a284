#!/usr/bin/env bash
# Error against run time on three scenes, for docs/benchmarks.md ("Error against run time"):
# `mvcl-bench convergence` on the cube in cube, the HRA body and the two-cylinder engine, each
# under its demo lens stack (assets/lenses/), CSVs and printed summaries into out/, plots into
# docs/images/convergence-<scene>.png. References are cached in out/convergence-cache/, so a
# second run only measures.
#   scripts/convergence.sh [extra mvcl-bench convergence options, e.g. --seeds 5]
# Sizes and budgets are chosen so that a first run (references included) takes about 10 minutes
# on a 2-core machine; see docs/benchmarks.md for what was measured with them.
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bench="${MVCL_BUILD_DIR:-$repo/build}/bin/mvcl-bench"
cd "$repo" # the lens files name their scenes relative to themselves, the cache is in out/
mkdir -p out
# The plots need Debian's matplotlib; say so before spending minutes on the measurements.
if ! /usr/bin/python3 -c "import matplotlib" 2>/dev/null; then
  echo "convergence.sh: needs python3-matplotlib (apt-get install python3-matplotlib)" >&2
  exit 1
fi

size="${MVCL_CONVERGENCE_SIZE:-320x240}"
max_spp="${MVCL_CONVERGENCE_MAX_SPP:-128}"
reference_spp="${MVCL_CONVERGENCE_REFERENCE_SPP:-1024}"
start=$(date +%s)
for scene in cube-in-cube HRA_Female_Body 2CylinderEngine; do
  echo "== $scene" >&2
  "$bench" convergence --lenses "assets/lenses/$scene.json" --size "$size" --max-spp "$max_spp" \
    --reference-spp "$reference_spp" --csv "out/convergence-$scene.csv" "$@" | tee "out/convergence-$scene.txt"
done
/usr/bin/python3 scripts/plot-convergence.py out/convergence-{cube-in-cube,HRA_Female_Body,2CylinderEngine}.csv \
  -o docs/images
echo
grep -h "adaptive reaches" out/convergence-{cube-in-cube,HRA_Female_Body,2CylinderEngine}.txt
echo "total $(($(date +%s) - start)) s"
