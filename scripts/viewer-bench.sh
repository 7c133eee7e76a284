#!/usr/bin/env bash
# UI frame times of mvcl-viewer under Xvfb (Mesa llvmpipe), for docs/benchmarks.md ("The viewer's
# frame times"): the HRA body under its demo lens stack plus one lens, a 1280x720 view, the
# scripted lens drag and orbit of scripts/viewer-bench.txt. Extra arguments go to the viewer
# (e.g. --sampling progressive --max-spp 64).
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
viewer="${MVCL_BUILD_DIR:-$repo/build}/bin/mvcl-viewer"
cd "$repo"
# A copy left by an earlier run would be offered at the start (a modal): each run starts clean.
rm -f "${TMPDIR:-/tmp}/mvcl-viewer-bench.recovery.json"
xvfb-run -a -s '-screen 0 1700x800x24' "$viewer" --size 1660x720 \
  --lenses assets/lenses/HRA_Female_Body.json --recovery "${TMPDIR:-/tmp}/mvcl-viewer-bench.recovery.json" \
  --script scripts/viewer-bench.txt "$@"
