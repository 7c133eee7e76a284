#!/usr/bin/env bash
# Catalogue case 27: intersection results must not depend on the compiler or its flags.
# Builds mvcl-robustness-digest (the framework and that one target only) with GCC and clang at
# -O0 and -O3, plus GCC -O3 -march=native with the mvcl library built -ffp-contract=fast, placed
# *after* mvcl's own -ffp-contract=off (MVCL_FRAMEWORK_COMPILE_OPTIONS), as a project compiling
# mvcl's sources or headers with its own flags might. The digest program itself keeps
# contraction off there: it generates the rays, and those must stay the same rays.
# Runs each and diffs the outputs (counts and a hash of every hit): they must be identical, and
# each run must pass (no leak, no self-hit, the layer-gap map complete).
# Build directories: build-flags-<variant>/ (or under $MVCL_FLAGS_BUILD_ROOT).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/ci-common.sh"

root="${MVCL_FLAGS_BUILD_ROOT:-$repo}"
target="${MVCL_DIGEST_TARGET:-mvcl-robustness-digest}"
# Smaller than the tool's defaults: the aim is bitwise agreement between builds, not statistics,
# and five -O0/-O3 builds have to fit the CI budget.
digest_args=(${MVCL_DIGEST_ARGS:---rays 50000 --triangles 300 --spawned 200})
ci_ensure_packages clang-14

# name | compiler | options for every target | options for the mvcl library only
variants=(
  "gcc-O0|g++|-O0|"
  "gcc-O3|g++|-O3|"
  "clang-O0|clang++-14|-O0|"
  "clang-O3|clang++-14|-O3|"
  "gcc-O3-native-fpcontract-fast|g++|-O3;-march=native|-ffp-contract=fast"
)

outputs=()
status=0
for v in "${variants[@]}"; do
  IFS='|' read -r name compiler options framework_options <<<"$v"
  build_dir="$root/build-flags-$name"
  start=$(date +%s)
  ci_reset_if_compiler_differs "$build_dir" "$compiler"
  # Build type None: only the options above, no -O2/-DNDEBUG from a CMake build type.
  cmake -S "$repo" -B "$build_dir" -G Ninja -DCMAKE_CXX_COMPILER="$compiler" -DCMAKE_BUILD_TYPE=None \
    -DMVCL_EXTRA_COMPILE_OPTIONS="$options" -DMVCL_FRAMEWORK_COMPILE_OPTIONS="$framework_options" \
    -DMVCL_BUILD_TESTS=ON -DMVCL_BUILD_BENCH=OFF >/dev/null
  cmake --build "$build_dir" --target "$target" -- -j"$jobs" >"$build_dir/build.log" 2>&1 ||
    { tail -30 "$build_dir/build.log"; echo "ci-flag-invariance: $name does not build" >&2; exit 1; }
  out="$build_dir/digest.txt"
  if ! "$build_dir/bin/$target" "${digest_args[@]}" >"$out"; then
    echo "ci-flag-invariance: $name: a robustness case failed:" >&2
    cat "$out" >&2
    status=1
  fi
  echo "ci-flag-invariance: $name ($(ci_seconds_since "$start") s): $(md5sum <"$out" | cut -c1-12)"
  outputs+=("$out")
done

reference="${outputs[0]}"
for out in "${outputs[@]:1}"; do
  if ! diff -u "$reference" "$out"; then
    echo "ci-flag-invariance: $out differs from $reference" >&2
    status=1
  fi
done
((status == 0)) && echo "ci-flag-invariance: all ${#outputs[@]} builds print identical digests"
exit "$status"
