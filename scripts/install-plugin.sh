#!/usr/bin/env bash
# Installs the built plugin into the default QGIS profile of the current user (or the
# profile folder QGIS_PROFILE_DIR names) and enables it there, for the desktop toolbox and
# qgis_process alike. Run scripts/build.sh first.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
src=${TINLOD_PLUGIN_DIR:-$root/build/plugin/tinlod}
[[ -f $src/libtinlod_processing.so ]] || { echo "ERROR: build first: bash scripts/build.sh" >&2; exit 1; }
profile=${QGIS_PROFILE_DIR:-$HOME/.local/share/QGIS/QGIS3/profiles/default}
mkdir -p "$profile/python/plugins"
rm -rf "$profile/python/plugins/tinlod"
cp -r "$src" "$profile/python/plugins/tinlod"
# Enabled in that profile's own settings, whichever profile it is (qgis_process's
# `plugins enable` only reaches the default one), with Qt's own INI writer.
settings=$profile/QGIS/QGIS3.ini
mkdir -p "$profile/QGIS"
if /usr/bin/python3 - "$settings" <<'PY'
import sys
from PyQt5.QtCore import QSettings
s = QSettings(sys.argv[1], QSettings.IniFormat)
s.setValue("PythonPlugins/tinlod", True)
s.sync()
sys.exit(0 if s.status() == QSettings.NoError and str(s.value("PythonPlugins/tinlod")).lower() == "true" else 1)
PY
then
  echo "Installed the tinlod plugin into $profile/python/plugins/tinlod and enabled it in $settings"
else
  echo "Installed the tinlod plugin into $profile/python/plugins/tinlod; enable it in QGIS: Plugins > Manage and Install Plugins > Installed > tinlod" >&2
fi
