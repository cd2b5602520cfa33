#!/usr/bin/env bash
# Installs the Debian packages rastercmp needs (Debian 12, 13 and unstable: unversioned names only,
# so each release brings its own default LLVM and clang); does nothing when all are present.
# Runs as root, or through sudo when not root. Exit 3 when packages are missing and cannot be installed.
set -euo pipefail

packages=(
  cmake make g++ clang libclang-rt-dev llvm pkg-config
  libgtest-dev libgmock-dev libbenchmark-dev librapidcheck-dev
  libvulkan-dev mesa-vulkan-drivers vulkan-tools vulkan-validationlayers
  glslang-dev glslang-tools spirv-tools libglm-dev
  libopenimageio-dev openimageio-tools
  nlohmann-json3-dev libcli11-dev libfmt-dev
  libkainjow-mustache-dev gnuplot-nox
  libassimp-dev assimp-testmodels
  chromium fonts-dejavu-core
)

missing=()
for p in "${packages[@]}"; do
  status=$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null || true)
  [[ "$status" == "install ok installed" ]] || missing+=("$p")
done

if [[ ${#missing[@]} -eq 0 ]]; then
  exit 0
fi

echo "setup: installing ${#missing[@]} missing Debian packages: ${missing[*]}"
sudo_cmd=()
if [[ $(id -u) -ne 0 ]]; then
  if command -v sudo >/dev/null 2>&1; then
    sudo_cmd=(sudo)
  else
    echo "setup: not root and no sudo; install these packages: ${missing[*]}" >&2
    exit 3
  fi
fi
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -q
"${sudo_cmd[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}"
