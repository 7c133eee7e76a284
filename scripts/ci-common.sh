# Shared by the scripts/ci-*.sh robustness scripts; source it, do not run it.
# Expects the base packages of scripts/bootstrap.sh (compilers, cmake, ninja, the -dev packages);
# each script adds what only it needs (clang, libFuzzer) with ci_ensure_packages.

repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
jobs="$(nproc)"

# Installs the Debian packages that are missing (root or sudo); a no-op when all are there.
ci_ensure_packages() {
  local missing=() p
  for p in "$@"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  ((${#missing[@]})) || return 0
  echo "$(basename "$0"): installing ${missing[*]}" >&2
  local sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $sudo apt-get update -qq
  $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
}

# A build directory configured with another compiler cannot be reconfigured: start it afresh.
ci_reset_if_compiler_differs() {
  local build_dir="$1" compiler="$2"
  local cache="$build_dir/CMakeCache.txt" cached
  [ -f "$cache" ] || return 0
  cached="$(sed -n 's/^CMAKE_CXX_COMPILER:[A-Z]*=//p' "$cache")"
  if [ "$(command -v "$cached")" != "$(command -v "$compiler")" ]; then
    echo "$(basename "$0"): $build_dir was configured with another compiler; starting it afresh" >&2
    rm -rf "$build_dir"
  fi
}

# Sanitizer settings for every run: stop at the first report, with a stack and a non-zero exit.
# abort_on_error stays off so that the exit code (not a SIGABRT core) tells ctest it failed.
export ASAN_OPTIONS="halt_on_error=1:detect_leaks=1:detect_stack_use_after_return=1:check_initialization_order=1:strict_init_order=1:${ASAN_OPTIONS_EXTRA:-}"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1:${UBSAN_OPTIONS_EXTRA:-}"
export LSAN_OPTIONS="suppressions=$repo/tests/sanitizers/lsan.supp:print_suppressions=0"

ci_seconds_since() { echo $(($(date +%s) - $1)); }
