#!/usr/bin/env bash
# Builds everything, then the Debian package of the command line and the QGIS plugin
# (build/tinlod_<version>_amd64.deb). Install it with: apt install ./build/tinlod_*.deb
# Its dependencies come from dpkg-shlibdeps: it installs only beside the QGIS it was built for.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bash "$root/scripts/build.sh"
cd "$root/build"
rm -f tinlod_*.deb
cpack -G DEB > /dev/null
ls "$root"/build/tinlod_*.deb
