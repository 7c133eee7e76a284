#!/usr/bin/env bash
# Builds mvcl and its tests with AddressSanitizer + UndefinedBehaviorSanitizer (clang, -O1,
# assertions on) in build-asan/ (or $MVCL_ASAN_BUILD_DIR) and runs the whole ctest suite under
# them, leak checking included. Any sanitizer report aborts that test, so ctest fails. The viewer
# is left out: its window system and Mesa (not ours, not instrumented) report leaks of their own.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/ci-common.sh"

build_dir="${MVCL_ASAN_BUILD_DIR:-$repo/build-asan}"
compiler=clang++-14
# llvm-14 brings llvm-symbolizer, for stack traces with file:line.
ci_ensure_packages clang-14 llvm-14
export ASAN_SYMBOLIZER_PATH="$(command -v llvm-symbolizer-14 || true)"

ci_reset_if_compiler_differs "$build_dir" "$compiler"
# Debug keeps assertions; -O1 as the sanitizer docs recommend (fast enough, accurate stacks).
cmake -S "$repo" -B "$build_dir" -G Ninja -DCMAKE_CXX_COMPILER="$compiler" \
  -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-O1 -g" \
  -DMVCL_SANITIZE=ON -DMVCL_BUILD_TESTS=ON -DMVCL_BUILD_BENCH=OFF -DMVCL_BUILD_VIEWER=OFF >/dev/null
cmake --build "$build_dir" -- -j"$jobs"
ctest --test-dir "$build_dir" --output-on-failure -j"$jobs"
echo "ci-sanitizers: the whole suite passed under ASan+UBSan+LSan with no reports"
