#!/usr/bin/env bash
# Builds the libFuzzer harnesses of tests/fuzz (clang, ASan+UBSan) in build-fuzz/ (or
# $MVCL_FUZZ_BUILD_DIR) and runs them:
#   mvcl-fuzz-gltf, mvcl-fuzz-glb   the glTF loader, $MVCL_FUZZ_SECONDS (default 120) seconds each,
#                                   seeded with every .gltf/.glb of tests/data/models (external
#                                   buffers inlined) and tests/data/fuzz-regressions;
#   mvcl-fuzz-obj, -stl, -ply       the OBJ, STL and PLY readers, half that each, seeded with the
#                                   files of tests/data/meshes that have their extension;
#   mvcl-fuzz-session               session files (lens-stack files and sessions of several views),
#                                   half that, seeded with assets/lenses/*.json,
#                                   tests/data/fuzz-seeds/session/ and tests/data/fuzz-regressions/*.json;
#   mvcl-fuzz-viewer-script         the viewer's scripts, half that, seeded with
#                                   tests/data/fuzz-seeds/viewer-script/ and scripts/viewer-bench.txt.
# The corpus grows in the build directory and is reused by the next run.
# A crash fails the script; the input is left in <build>/artifacts/: fix the bug, then copy the
# input into tests/data/fuzz-regressions/, where GltfFuzzRegressions loads it in every test run.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/ci-common.sh"

build_dir="${MVCL_FUZZ_BUILD_DIR:-$repo/build-fuzz}"
seconds="${MVCL_FUZZ_SECONDS:-120}"
compiler=clang++-14
# libclang-rt-14-dev holds libclang_rt.fuzzer; python3 prepares the seed corpus.
ci_ensure_packages clang-14 libclang-rt-14-dev llvm-14 python3
export ASAN_SYMBOLIZER_PATH="$(command -v llvm-symbolizer-14 || true)"

ci_reset_if_compiler_differs "$build_dir" "$compiler"
cmake -S "$repo" -B "$build_dir" -G Ninja -DCMAKE_CXX_COMPILER="$compiler" \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g" \
  -DMVCL_BUILD_FUZZERS=ON -DMVCL_BUILD_TESTS=OFF -DMVCL_BUILD_BENCH=OFF >/dev/null
cmake --build "$build_dir" --target mvcl-fuzz-gltf mvcl-fuzz-glb mvcl-fuzz-obj mvcl-fuzz-stl mvcl-fuzz-ply \
  mvcl-fuzz-session mvcl-fuzz-viewer-script -- -j"$jobs"

# Seeds: .glb as they are; .gltf with their external buffers inlined as data URIs, because the
# harness gives no asset folder (it never reads the disk). Images are dropped: they are not decoded.
# Files above 128 KiB are left out: they slow every execution and add no new structure.
max_len=131072
seeds="$build_dir/fuzz-seeds"
rm -rf "$seeds"
mkdir -p "$seeds/gltf" "$seeds/glb" "$seeds/obj" "$seeds/stl" "$seeds/ply"
for format in obj stl ply; do
  find "$repo/tests/data/meshes" -type f -iname "*.$format" -size -128k -exec cp {} "$seeds/$format/" \;
done
python3 - "$repo" "$seeds" "$max_len" <<'PY'
import base64, hashlib, json, os, pathlib, sys
repo, seeds, max_len = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2]), int(sys.argv[3])
sources = list((repo / "tests/data/models").rglob("*.gl*")) + list((repo / "tests/data/fuzz-regressions").glob("*"))
for path in (p for p in sources if p.name != "README.md"):
    data = path.read_bytes()
    kind = "glb" if data[:4] == b"glTF" else "gltf"
    if kind == "gltf" and path.suffix == ".gltf":
        try:
            doc = json.loads(data)
            for buffer in doc.get("buffers", []):
                uri = buffer.get("uri", "")
                if uri and not uri.startswith("data:") and (path.parent / uri).is_file():
                    buffer["uri"] = "data:application/octet-stream;base64," + base64.b64encode((path.parent / uri).read_bytes()).decode()
            doc.pop("images", None)
            data = json.dumps(doc).encode()
        except (ValueError, AttributeError, TypeError):
            pass  # hostile on purpose: keep it as it is
    if len(data) <= max_len:
        (seeds / kind / hashlib.sha1(data).hexdigest()).write_bytes(data)
PY

mkdir -p "$seeds/session" "$seeds/viewer-script"
cp "$repo"/assets/lenses/*.json "$seeds/session/"
find "$repo/tests/data/fuzz-regressions" -name '*.json' -exec cp {} "$seeds/session/" \;
cp "$repo"/tests/data/fuzz-seeds/session/*.json "$seeds/session/" # sessions of several views (version 2)
cp "$repo"/tests/data/fuzz-seeds/viewer-script/* "$repo/scripts/viewer-bench.txt" "$seeds/viewer-script/"

total=0
# fuzz TARGET SECONDS [libFuzzer options]: runs mvcl-fuzz-TARGET on its corpus and seeds.
fuzz() {
  local entry="$1" time="$2"
  shift 2
  local corpus="$build_dir/fuzz-corpus/$entry" artifacts="$build_dir/artifacts/$entry" log="$build_dir/fuzz-$entry.log"
  mkdir -p "$corpus" "$artifacts"
  echo "ci-fuzz: mvcl-fuzz-$entry for ${time}s ($(ls "$seeds/$entry" | wc -l) seeds, $(ls "$corpus" | wc -l) corpus inputs)"
  if ! "$build_dir/bin/mvcl-fuzz-$entry" "$corpus" "$seeds/$entry" "$@" \
      -max_total_time="$time" -max_len="$max_len" -timeout=10 -rss_limit_mb=2048 \
      -artifact_prefix="$artifacts/" -print_final_stats=1 >"$log" 2>&1; then
    tail -60 "$log"
    echo "ci-fuzz: mvcl-fuzz-$entry found a crash; the input is in $artifacts/ (see above)" >&2
    exit 1
  fi
  local runs
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log")
  echo "ci-fuzz: mvcl-fuzz-$entry: $runs executions, no crash ($(grep -c . <<<"$(ls "$corpus")") corpus inputs)"
  total=$((total + runs))
}
fuzz gltf "$seconds" -dict="$repo/tests/fuzz/gltf.dict"
fuzz glb "$seconds" -dict="$repo/tests/fuzz/gltf.dict"
for format in obj stl ply; do fuzz "$format" $((seconds / 2)); done
fuzz session $((seconds / 2))
fuzz viewer-script $((seconds / 2))
echo "ci-fuzz: $total executions in total, no crash"
