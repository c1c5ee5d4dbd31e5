#!/usr/bin/env bash
# Installs the built plugin into the default QGIS profile of the current user and enables
# it, for the desktop toolbox and qgis_process alike. Run scripts/build.sh first.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
src=$root/build/plugin/tinlod
[[ -f $src/libtinlod_processing.so ]] || { echo "ERROR: build first: bash scripts/build.sh" >&2; exit 1; }
profile=${QGIS_PROFILE_DIR:-$HOME/.local/share/QGIS/QGIS3/profiles/default}
mkdir -p "$profile/python/plugins"
rm -rf "$profile/python/plugins/tinlod"
cp -r "$src" "$profile/python/plugins/tinlod"
QT_QPA_PLATFORM=offscreen /usr/bin/qgis_process.bin plugins enable tinlod > /dev/null 2>&1 || true
echo "Installed the tinlod plugin into $profile/python/plugins/tinlod (enabled)"
