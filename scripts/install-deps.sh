#!/usr/bin/env bash
# Installs every Debian 12 package tinlod needs to build, test and run in QGIS.
# Idempotent: packages already present are skipped, so a ready machine costs nothing.
set -euo pipefail

# `file`: CPack's .deb generator needs it to run dpkg-shlibdeps; a minimal Debian 12 lacks it
# (found by running .ci/run in a debootstrapped bookworm).
packages=(
  build-essential cmake pkg-config git zip ca-certificates file
  libcgal-dev libgmp-dev libmpfr-dev
  libgdal-dev gdal-bin libproj-dev libgeos-dev libsqlite3-dev
  qtbase5-dev libqgis-dev qgis qgis-providers python3-qgis python3-gdal python3-numpy
  libgtest-dev
  xvfb xauth
  python3-distributed
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if ((${#missing[@]} == 0)); then
  echo "tinlod: all build dependencies are installed"
  exit 0
fi

echo "tinlod: installing ${missing[*]}"
if [[ $(id -u) -ne 0 ]]; then sudo=sudo; else sudo=; fi
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -q
$sudo apt-get install -y -q --no-install-recommends "${missing[@]}"
