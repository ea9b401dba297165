#!/bin/sh
# Installs the Debian 12 packages aalab needs to build, test and run (docs/architecture.md, "Build and tests"); clang
# and its runtime (libFuzzer, the sanitizers) build the fuzz targets of tests/fuzz; slurm-wlm and munge run
# the throwaway cluster of tests/integration/slurm_farm.py (docs/farm.md).
set -e
packages="build-essential autoconf automake pkg-config
  libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers glslang-tools
  libopenimageio-dev openimageio-tools libpng-dev zlib1g-dev libjansson-dev libassimp-dev libcmocka-dev
  python3 python3-numpy python3-skimage python3-lxml
  chromium systemd
  clang libclang-rt-14-dev
  slurm-wlm munge"
missing=""
for p in $packages; do
	dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing="$missing $p"
done
if [ -z "$missing" ]; then
	echo "install-deps: all packages present"
	exit 0
fi
echo "install-deps: installing$missing"
SUDO=""
[ "$(id -u)" -ne 0 ] && SUDO="sudo"
$SUDO apt-get update -q
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -q --no-install-recommends $missing
