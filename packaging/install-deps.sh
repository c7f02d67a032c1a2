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
  ca-certificates
)
# Components add their own lists: packaging/deps/<component>.txt (one package per line, '#'
# comments) for build/test/demo, packaging/deps/<component>.bench.txt for `make bench` only.
here=$(cd "$(dirname "$0")" && pwd)
for f in "$here"/deps/*.txt; do
  [[ -e "$f" ]] || continue
  [[ "$f" == *.bench.txt ]] && continue
  while read -r p _; do [[ -n "$p" && "$p" != \#* ]] && pkgs+=("$p"); done < "$f"
done
if [[ "${1:-}" == "--bench" ]]; then
  pkgs+=(python3 python3-numpy python3-open3d time)
  for f in "$here"/deps/*.bench.txt; do
    [[ -e "$f" ]] || continue
    while read -r p _; do [[ -n "$p" && "$p" != \#* ]] && pkgs+=("$p"); done < "$f"
  done
fi

# `npm pack` fetches the sample scan (make demo). Machines may carry their own Node.js whose npm
# conflicts with Debian's npm package: only install Debian's when there is no npm at all.
if ! command -v npm > /dev/null 2>&1; then
  pkgs+=(nodejs npm)
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
