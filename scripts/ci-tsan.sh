#!/usr/bin/env bash
# ThreadSanitizer job: the concurrent parts of mvcl (render sessions, the controller, the worker
# pool, policy composition, picking, the edit storms) run under TSan (clang, -O1, assertions on)
# with no report, and a deliberate race is reported (tests/sanitizers/ThreadSanitizerProbe.cpp).
#
# The worker pool is oneTBB. Debian's libtbb is not instrumented: TSan cannot see its hand-offs
# and reports every chunk of every parallel loop as a race (about two thousand reports on these
# tests). Suppressing TBB would also hide real races in our loop bodies, whose stacks pass
# through it. So this script builds the same oneTBB from Debian's source package (the version of
# the installed libtbb-dev) with -fsanitize=thread into <build>/onetbb/ and links the
# tests to it; mvcl's code is the same as in every other build. It is built again only when the
# installed libtbb-dev changes version.
#
# Build directory: build-tsan/ (or $MVCL_TSAN_BUILD_DIR). Tests: $MVCL_TSAN_TESTS (a ctest -R
# regular expression; default below). Reports fail the test that made them: TSan exits 66.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/ci-common.sh"

build_dir="${MVCL_TSAN_BUILD_DIR:-$repo/build-tsan}"
compiler=clang++-14
tests="${MVCL_TSAN_TESTS:-^(ThreadSanitizer\.|WorkerPool\.|RenderSessionTest\.|EditStorm\.|Controller|ViewSetupTest\.|Picking\.|DepthHistogram\.|SceneLoadJob\.|QuickBvh\.|Document|RenderPriority|RefinementHold|CompareRender|LensStackCompose\.|PolicyMapDiff\.|Renderer\.)}"
# dpkg-dev unpacks the source package; llvm-14 brings llvm-symbolizer for stacks with file:line.
ci_ensure_packages clang-14 llvm-14 dpkg-dev libtbb-dev
export TSAN_OPTIONS="second_deadlock_stack=1:history_size=4:suppressions=$repo/tests/sanitizers/tsan.supp:external_symbolizer_path=$(command -v llvm-symbolizer-14 || true):${TSAN_OPTIONS_EXTRA:-}"

start=$(date +%s)
ci_reset_if_compiler_differs "$build_dir" "$compiler"
mkdir -p "$build_dir"

# --- oneTBB with -fsanitize=thread, from Debian's source package of the installed version.
tbb_version="$(dpkg-query -W -f='${Version}' libtbb-dev)"
tbb_root="$build_dir/onetbb"
tbb_prefix="$tbb_root/prefix"
if [ "$(cat "$tbb_root/version" 2>/dev/null)" != "$tbb_version" ]; then
  if ! grep -rqsE '^(Types: .*deb-src|deb-src )' /etc/apt/sources.list /etc/apt/sources.list.d/; then
    # Debian's images list binary packages only; the same archives serve the sources.
    echo "ci-tsan: enabling Debian's source packages (deb-src) for apt-get source" >&2
    if [ -f /etc/apt/sources.list.d/debian.sources ]; then
      sed 's/^Types: deb$/Types: deb-src/' /etc/apt/sources.list.d/debian.sources >/etc/apt/sources.list.d/mvcl-deb-src.sources
    else
      sed -n 's/^deb /deb-src /p' /etc/apt/sources.list >/etc/apt/sources.list.d/mvcl-deb-src.list
    fi
    apt-get update -qq
  fi
  rm -rf "$tbb_root"
  mkdir -p "$tbb_root"
  (cd "$tbb_root" && apt-get source -qq "onetbb=$tbb_version" >/dev/null 2>&1) ||
    { echo "ci-tsan: apt-get source onetbb=$tbb_version failed" >&2; exit 1; }
  tbb_source="$(find "$tbb_root" -maxdepth 1 -mindepth 1 -type d -name 'onetbb-*')"
  # TBB_SANITIZE=thread: oneTBB's own switch (-fsanitize=thread, and no IPO, which TSan breaks).
  cmake -S "$tbb_source" -B "$tbb_root/build" -G Ninja -DCMAKE_CXX_COMPILER="$compiler" \
    -DCMAKE_BUILD_TYPE=RelWithDebInfo -DTBB_SANITIZE=thread -DTBB_TEST=OFF -DTBB_STRICT=OFF \
    -DTBBMALLOC_BUILD=OFF -DTBB_DISABLE_HWLOC_AUTOMATIC_SEARCH=ON -DCMAKE_INSTALL_PREFIX="$tbb_prefix" >/dev/null
  cmake --build "$tbb_root/build" -- -j"$jobs" >"$tbb_root/build.log" 2>&1 ||
    { tail -30 "$tbb_root/build.log"; echo "ci-tsan: oneTBB $tbb_version does not build with TSan" >&2; exit 1; }
  cmake --install "$tbb_root/build" >/dev/null
  echo "$tbb_version" >"$tbb_root/version"
fi
echo "ci-tsan: oneTBB $tbb_version with -fsanitize=thread in $tbb_prefix ($(ci_seconds_since "$start") s)"

# --- mvcl's tests with -fsanitize=thread, linked to that oneTBB. The viewer and the benches are
# left out: only the tests are built.
cmake -S "$repo" -B "$build_dir" -G Ninja -DCMAKE_CXX_COMPILER="$compiler" \
  -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-O1 -g" -DMVCL_SANITIZE_THREAD=ON \
  -DTBB_DIR="$tbb_prefix/lib/cmake/TBB" \
  -DMVCL_BUILD_TESTS=ON -DMVCL_BUILD_BENCH=OFF -DMVCL_BUILD_VIEWER=OFF >/dev/null
cmake --build "$build_dir" --target mvcl_tests -- -j"$jobs" >"$build_dir/build.log" 2>&1 ||
  { tail -40 "$build_dir/build.log"; echo "ci-tsan: the TSan build failed" >&2; exit 1; }
# The tests must run against the instrumented oneTBB, not Debian's (the probe checks it too).
# grep reads all of ldd's output (no -q): under pipefail, ldd killed by SIGPIPE after an early
# match would fail the check at random.
if ! ldd "$build_dir/bin/mvcl_tests" | grep "$tbb_prefix/lib/libtbb" >/dev/null; then
  ldd "$build_dir/bin/mvcl_tests" | grep tbb >&2
  echo "ci-tsan: mvcl_tests does not load the instrumented oneTBB" >&2
  exit 1
fi
echo "ci-tsan: built after $(ci_seconds_since "$start") s"

log="$build_dir/ctest.log"
status=0
# -V: every test's output goes to the log, so that reports are counted in passing tests too.
ctest --test-dir "$build_dir" -R "$tests" -j"$jobs" -V >"$log" 2>&1 || status=1
count="$(sed -n 's/^.*tests passed, [0-9]* tests failed out of \([0-9]*\)$/\1/p' "$log" | tail -1)"
failed="$(sed -n 's/^.*tests passed, \([0-9]*\) tests failed out of [0-9]*$/\1/p' "$log" | tail -1)"
# The probe's deliberate race is the one report expected; every other one is a finding.
reports="$(grep -c 'WARNING: ThreadSanitizer:' "$log" || true)"
if ((status || reports != 1)); then
  sed -n '/The following tests FAILED/,$p' "$log"
  grep -B2 -A40 'WARNING: ThreadSanitizer:' "$log" | head -200
fi
echo "ci-tsan: ${count:-0} tests under ThreadSanitizer, ${failed:-?} failed, $reports report(s) in all (1 expected: the deliberate race), $(ci_seconds_since "$start") s"
((status == 0 && reports == 1)) || { echo "ci-tsan: FAILED" >&2; exit 1; }
echo "ci-tsan: no report but the deliberate race"
