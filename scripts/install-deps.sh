#!/usr/bin/env bash
# Installs the Debian 12 packages polydual needs; skips what is already there
# (idempotent). Needs root (or sudo) and Debian's package mirrors only.
set -euo pipefail
PKGS=(build-essential cmake ccache pkg-config
      libcgal-dev libgmp-dev libmpfr-dev libboost-dev libeigen3-dev libtbb-dev
      libceres-dev zlib1g-dev libgtest-dev libgmock-dev libbenchmark-dev
      gmsh libgmsh-dev
      clang-14 libclang-rt-14-dev
      python3 python3-vtk9 python3-matplotlib python3-numpy python3-meshio xvfb xauth time
      openfoam
      tetgen python3-netgen)  # mesh producers of the tests' corpus (tests/corpus)
missing=()
for p in "${PKGS[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#PKGS[@]} packages present"
  exit 0
fi
echo "install-deps: installing ${missing[*]}"
SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO="sudo"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -q
$SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
