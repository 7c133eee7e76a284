#!/usr/bin/env bash
# Sets up a Debian 12 machine for mvcl and builds it: installs the Debian packages that are
# missing (needs root or sudo), then configures and builds into build/ (or $MVCL_BUILD_DIR).
#   scripts/bootstrap.sh                 everything (the apps, the tests, the benches)
#   scripts/bootstrap.sh TARGET...       only those targets and what they need (the README's
#                                        first command: mvcl-render, with the lens plugins)
# Used by both README commands and by .ci/run. Safe to run again: it only does what is missing.
set -euo pipefail

repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build_dir="${MVCL_BUILD_DIR:-$repo/build}"
build_type="${MVCL_BUILD_TYPE:-Release}"

packages=(
  g++ cmake ninja-build pkg-config
  libglm-dev libtinygltf-dev libtinyobjloader-dev nlohmann-json3-dev libstb-dev libtinyexr-dev libtbb-dev
  libcli11-dev libgtest-dev
  libglfw3-dev libimgui-dev libepoxy-dev   # mvcl-viewer
  xvfb xauth libgl1-mesa-dri              # the viewer's end-to-end test: a real window, Mesa llvmpipe
  libembree-dev libbenchmark-dev   # optional peers for mvcl-bench
  libopenimageio-dev               # mvcl-imageio-oiio, the optional module for .tif and other formats
  libavformat-dev libavcodec-dev libswscale-dev   # mvcl-video-ffmpeg, the optional module for H.264 videos
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "bootstrap: installing ${missing[*]}" >&2
  sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $sudo apt-get update -qq
  $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

cmake -S "$repo" -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE="$build_type" >/dev/null
targets=()
for target in "$@"; do targets+=(--target "$target"); done
cmake --build "$build_dir" "${targets[@]}" -- -j"$(nproc)"
