#!/usr/bin/env bash
# Whole frames against POV-Ray 3.7: the same scene, camera, lights, materials and trace depth in
# both renderers, one ray per pixel through its centre, the same thread count.
#   scripts/frame-vs-povray.sh [WxH] [threads]      (default: each scene's own size, 2 threads)
# Scenes: builtin:cube-in-cube at 500x500, HRA_Female_Body and 2CylinderEngine at 800x600 (WxH,
# when given, is used for all three). `mvcl-bench pov` writes each as a POV-Ray scene and prints the
# matching mvcl-render camera; then povray and mvcl-render run alternately, ROUNDS times (default
# 5; who goes first alternates), and the table gives for each:
#   - POV-Ray's render-only "Trace Time" and mvcl-render's "render ... ms" (median, min-max),
#     and their ratio POV/mvcl (ratio of the medians, then the range over the rounds' pairs);
#   - each whole process's user+sys CPU time (loading, parsing, BVH and tree builds included);
#   - how far apart the two images are (mvcl-bench image-diff: mean and largest difference in
#     8-bit levels, share of pixels more than 8 levels apart), to show that the scenes match.
# Needs povray (Debian: povray), /usr/bin/time (Debian: time) and a build in build/ (or
# MVCL_BUILD_DIR) with mvcl-bench and mvcl-render. Files go to out/frame-vs-povray/.
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bin="${MVCL_BUILD_DIR:-$repo/build}/bin"
size="${1:-}"
threads="${2:-2}"
rounds="${ROUNDS:-5}"
work="$repo/out/frame-vs-povray"
mkdir -p "$work"
for tool in povray /usr/bin/time "$bin/mvcl-bench" "$bin/mvcl-render"; do
  command -v "$tool" >/dev/null || { echo "frame-vs-povray: $tool not found" >&2; exit 1; }
done

models="$repo/tests/data/models"
scenes=(
  "cube-in-cube|builtin:cube-in-cube|${size:-500x500}"
  "HRA_Female_Body|$models/HRA_Female_Body/HRA_Female_Body.glb|${size:-800x600}"
  "2CylinderEngine|$models/2CylinderEngine/2CylinderEngine.glb|${size:-800x600}"
)

# One run of each renderer: appends "trace_seconds cpu_seconds" to $name.pov.runs or
# "render_milliseconds cpu_seconds" to $name.mvcl.runs.
run_pov() { # name width height
  local name=$1 w=$2 h=$3
  /usr/bin/time -f '%U %S' -o "$work/$name.pov.time" \
    povray "+I$work/$name.pov" "+O$work/$name-povray.png" "+W$w" "+H$h" -A -J0 "+WT$threads" +FN -D \
    -P File_Gamma=sRGB 2>"$work/$name.pov.log" >/dev/null
  local trace
  trace=$(sed -n 's/^ *Trace Time:.*(\([0-9.]*\) seconds).*/\1/p' "$work/$name.pov.log")
  [[ -n $trace ]] || { echo "frame-vs-povray: no Trace Time from povray ($work/$name.pov.log)" >&2; exit 1; }
  echo "$trace $(awk '{print $1 + $2}' "$work/$name.pov.time")" >>"$work/$name.pov.runs"
}
run_mvcl() { # name source size camera...
  local name=$1 source=$2 sz=$3
  shift 3
  local summary ms
  summary=$(/usr/bin/time -f '%U %S' -o "$work/$name.mvcl.time" \
    "$bin/mvcl-render" "$source" --size "$sz" --spp 1 --threads "$threads" --no-progress "$@" \
    -o "$work/$name-mvcl.png")
  ms=$(sed -n 's/^render .*: \([0-9.]*\) ms$/\1/p' <<<"$summary")
  [[ -n $ms ]] || { echo "frame-vs-povray: no render time from mvcl-render" >&2; exit 1; }
  echo "$ms $(awk '{print $1 + $2}' "$work/$name.mvcl.time")" >>"$work/$name.mvcl.runs"
}

echo "CPU: $(lscpu | sed -n 's/^Model name: *//p'), $(nproc) cores; load $(cut -d' ' -f1-3 /proc/loadavg)"
echo "$(povray --version 2>&1 | grep -m1 '^POV-Ray'); $threads threads; $rounds alternating rounds per scene"
echo
rows=()
for entry in "${scenes[@]}"; do
  IFS='|' read -r name source sz <<<"$entry"
  w=${sz%x*}
  h=${sz#*x}
  options=$("$bin/mvcl-bench" pov "$source" --size "$sz" -o "$work/$name.pov" 2>"$work/$name.export.log") || {
    cat "$work/$name.export.log" >&2
    exit 1
  }
  read -r -a camera <<<"$options"
  rm -f "$work/$name.pov.runs" "$work/$name.mvcl.runs"
  for ((r = 0; r < rounds; ++r)); do
    if ((r % 2 == 0)); then
      run_pov "$name" "$w" "$h"
      run_mvcl "$name" "$source" "$sz" "${camera[@]}"
    else
      run_mvcl "$name" "$source" "$sz" "${camera[@]}"
      run_pov "$name" "$w" "$h"
    fi
  done
  diff=$("$bin/mvcl-bench" image-diff "$work/$name-mvcl.png" "$work/$name-povray.png" \
    --write-diff "$work/$name-diff.png")
  rows+=("$name|$sz|$work/$name.pov.runs|$work/$name.mvcl.runs|$diff")
done

python3 - "${rows[@]}" <<'EOF'
import re, statistics, sys

def spread(values, scale=1.0, digits=0):
    values = [v * scale for v in values]
    return f"{statistics.median(values):.{digits}f} ({min(values):.{digits}f}–{max(values):.{digits}f})"

print("| scene | size | POV-Ray trace ms | mvcl-render ms | ratio POV/mvcl | POV-Ray CPU s | mvcl-render CPU s "
      "| CPU ratio | image difference (8-bit levels) |")
print("|---|---|---|---|---|---|---|---|---|")
for row in sys.argv[1:]:
    name, size, pov_runs, mvcl_runs, diff = row.split("|", 4)
    pov = [tuple(map(float, line.split())) for line in open(pov_runs)]
    mvcl = [tuple(map(float, line.split())) for line in open(mvcl_runs)]
    pov_ms = [p[0] * 1000 for p in pov]
    mvcl_ms = [m[0] for m in mvcl]
    pairs = [p / m for p, m in zip(pov_ms, mvcl_ms)]
    pov_cpu = [p[1] for p in pov]
    mvcl_cpu = [m[1] for m in mvcl]
    match = re.match(r"mean ([0-9.]+) levels, max ([0-9]+) levels, ([0-9.]+) % of pixels more than ([0-9]+)", diff)
    mean, largest, share, threshold = match.groups()
    print(f"| {name} | {size} | {spread(pov_ms)} | {spread(mvcl_ms, digits=1)} "
          f"| {statistics.median(pov_ms) / statistics.median(mvcl_ms):.2f} ({min(pairs):.2f}–{max(pairs):.2f}) "
          f"| {spread(pov_cpu, digits=2)} | {spread(mvcl_cpu, digits=2)} "
          f"| {statistics.median(pov_cpu) / statistics.median(mvcl_cpu):.2f} "
          f"| mean {float(mean):.3f}, max {largest}, {float(share):.3f} % over {threshold} |")
EOF
echo
echo "Medians with min–max over the rounds; ratio POV/mvcl > 1: mvcl-render is faster. Trace and render"
echo "times leave out loading (POV-Ray's parse builds its mesh2 trees; mvcl-render loads, infers layers"
echo "and builds its BVH); the CPU columns are whole processes. Images and differences: $work/"
