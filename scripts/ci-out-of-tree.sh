#!/usr/bin/env bash
# Builds the out-of-tree lens example (examples/out-of-tree-lens) against an *installed* mvcl,
# tests it and renders with it: proves that find_package(mvcl COMPONENTS testing),
# mvcl_add_lens_plugin() and mvcl::testing are enough to write and test a lens without the mvcl
# source tree — its unit test (with the conformance suite linked in) and the installed
# mvcl-lens-conformance on the module both pass — and that the installed mvcl-render finds both
# its own plugins (<prefix>/lib/mvcl/plugins) and the new one (MVCL_PLUGIN_PATH).
#
#   scripts/ci-out-of-tree.sh [build dir]     (default: build/, configured and built if needed)
#
# Works in a scratch directory ($MVCL_OUT_OF_TREE_DIR or a mktemp one, removed afterwards).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/ci-common.sh"

build_dir="${1:-$repo/build}"
work="${MVCL_OUT_OF_TREE_DIR:-$(mktemp -d /tmp/mvcl-out-of-tree.XXXXXX)}"
[ -n "${MVCL_OUT_OF_TREE_DIR:-}" ] || trap 'rm -rf "$work"' EXIT
prefix="$work/prefix"
example_build="$work/example-build"
image="$work/invert.png"

step() { echo "ci-out-of-tree: $*" >&2; }

if [ ! -f "$build_dir/CMakeCache.txt" ]; then
  cmake -S "$repo" -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
fi
step "building mvcl in $build_dir"
cmake --build "$build_dir" --target mvcl mvcl-render mvcl-lens-plugins mvcl_testing mvcl-lens-conformance -- -j"$jobs"
step "installing to $prefix"
cmake --install "$build_dir" --prefix "$prefix" >/dev/null

step "building examples/out-of-tree-lens against the installed package"
cmake -S "$repo/examples/out-of-tree-lens" -B "$example_build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$prefix" >/dev/null
cmake --build "$example_build" -- -j"$jobs"
[ -f "$example_build/mvcl-lens-invert.so" ] || { step "FAIL: mvcl-lens-invert.so was not built"; exit 1; }

step "running the example's tests: its unit test (with the conformance suite) and mvcl-lens-conformance on the module"
env -u LD_LIBRARY_PATH ctest --test-dir "$example_build" --output-on-failure -j"$jobs"
listed="$("$example_build/invert-lens-test" --gtest_list_tests)"
grep -q "^LensConformance/invert\.$" <<<"$listed" \
  || { step "FAIL: the unit test has no LensConformance/invert suite"; echo "$listed" >&2; exit 1; }
# By name through MVCL_PLUGIN_PATH, as the docs show it.
env -u LD_LIBRARY_PATH MVCL_PLUGIN_PATH="$example_build" "$prefix/bin/mvcl-lens-conformance" invert \
  --gtest_filter='LensConformance/invert.*' --gtest_brief=1 \
  || { step "FAIL: mvcl-lens-conformance invert"; exit 1; }

# Nothing from the source or build tree may leak in: only the prefix and the example build.
render="$prefix/bin/mvcl-render"
listing="$(env -u LD_LIBRARY_PATH MVCL_PLUGIN_PATH="$example_build" "$render" --list-lenses)"
for type in invert layer achromatic shadow; do
  grep -q "^$type:" <<<"$listing" || { step "FAIL: the installed mvcl-render does not list lens '$type'"; echo "$listing" >&2; exit 1; }
done
grep -q "from $example_build/mvcl-lens-invert.so" <<<"$listing" \
  || { step "FAIL: 'invert' was not loaded from $example_build"; echo "$listing" >&2; exit 1; }

step "rendering builtin:cube-in-cube through the invert lens"
render_cube() {
  env -u LD_LIBRARY_PATH MVCL_PLUGIN_PATH="$example_build" "$render" builtin:cube-in-cube \
    --size 160x120 --spp 1 --no-progress --lens layer:layers=1-,center=[0.4,0.5],size=[0.4,0.6] "$@" >/dev/null
}
render_cube -o "$image" --lens invert:amount=1,shape=ellipse,center=[0.5,0.5],size=[0.5,0.5]
[ -s "$image" ] || { step "FAIL: $image was not written"; exit 1; }
# The same render without the invert lens must differ, or the plugin did nothing.
render_cube -o "$work/without-invert.png"
! cmp -s "$image" "$work/without-invert.png" || { step "FAIL: the invert lens changed no pixel"; exit 1; }
echo "ci-out-of-tree: the installed package built and tested the example lens, and the installed mvcl-render rendered with it"
