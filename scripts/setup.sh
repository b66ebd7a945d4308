#!/usr/bin/env bash
# Installs what Sylva needs on Debian 12 (with apt, as root or through sudo); only what is
# missing, so it is safe to run again.
#   scripts/setup.sh          building and running sylva (`make demo`, `make install`)
#   scripts/setup.sh --test   and everything the tests, the sanitizer and fuzz builds, the
#                             package checks and the farm test use (`make test`), including the
#                             Khronos glTF Validator from npm into tests/tools/node_modules
set -euo pipefail
cd "$(dirname "$0")/.."

# The compiler and build tools, and the libraries sylva links (GoogleTest and Google Benchmark
# too: the build's configure step finds them, so `make test` can reuse the demo's build). GL: EGL
# (libEGL with Mesa's EGL vendor library and its llvmpipe driver, GL/glcorearb.h from
# libgl-dev) and OSMesa; either alone builds (README "Building");
# pybind11, Python's headers and numpy for the sylva Python module (python/).
packages=(
  build-essential cmake ninja-build pkg-config
  libegl-dev libegl-mesa0 libgl1-mesa-dri libgl-dev libosmesa6-dev libopencv-dev libavutil-dev libglm-dev libtinygltf-dev nlohmann-json3-dev libstb-dev
  libopenmesh-dev libnanoflann-dev libembree-dev libtomlplusplus-dev libcli11-dev libxxhash-dev
  libpng-dev libjpeg-dev libgif-dev libcairo2-dev libglib2.0-dev libopenexr-dev libmurmurhash-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  pybind11-dev python3-dev python3-numpy
)
test_packages=(
  ccache clang-format clang libfuzzer-14-dev libclang-rt-14-dev libomp-14-dev ffmpeg nodejs
  librsvg2-bin poppler-utils libxml2-utils openexr openimageio-tools python3-openimageio python3-numpy python3-pytest
  slurm-wlm munge lintian man-db
)
test=0
if [ "${1:-}" = "--test" ]; then
  test=1
  packages+=("${test_packages[@]}")
elif [ $# -gt 0 ]; then
  echo "usage: scripts/setup.sh [--test]" >&2
  exit 2
fi

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ $test = 1 ]; then command -v npm >/dev/null 2>&1 || missing+=(npm); fi

if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}"
  sudo=""
  if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
  export DEBIAN_FRONTEND=noninteractive
  $sudo apt-get update -qq
  $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

if [ $test = 1 ] && [ "${SYLVA_SKIP_NPM:-0}" != "1" ] &&
  [ ! -f tests/tools/node_modules/gltf-validator/package.json ]; then
  echo "setup: installing gltf-validator (npm) for the tests"
  (cd tests/tools && npm ci --no-audit --no-fund --loglevel=error >/dev/null)
fi
