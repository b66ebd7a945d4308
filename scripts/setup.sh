#!/usr/bin/env bash
# Installs what building and testing Sylva needs on Debian 12: the Debian packages (with apt,
# as root or through sudo) and, for the tests, the Khronos glTF Validator from npm into
# tests/tools/node_modules. Installs only what is missing; safe to run again.
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(
  build-essential cmake ninja-build pkg-config clang-format clang libfuzzer-14-dev libclang-rt-14-dev libomp-14-dev
  libosmesa6-dev libopencv-dev libavutil-dev libglm-dev libtinygltf-dev nlohmann-json3-dev libstb-dev
  libopenmesh-dev libnanoflann-dev libembree-dev libtomlplusplus-dev libcli11-dev libxxhash-dev
  libpng-dev libjpeg-dev libgif-dev libcairo2-dev libgtest-dev libgmock-dev libbenchmark-dev ffmpeg nodejs
  libopenexr-dev libmurmurhash-dev librsvg2-bin poppler-utils libxml2-utils openexr openimageio-tools
  python3-openimageio python3-numpy slurm-wlm munge
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
command -v npm >/dev/null 2>&1 || missing+=(npm)

if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}"
  sudo=""
  if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
  export DEBIAN_FRONTEND=noninteractive
  $sudo apt-get update -qq
  $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

if [ "${SYLVA_SKIP_NPM:-0}" != "1" ] && [ ! -f tests/tools/node_modules/gltf-validator/package.json ]; then
  echo "setup: installing gltf-validator (npm) for the tests"
  (cd tests/tools && npm ci --no-audit --no-fund --loglevel=error >/dev/null)
fi
