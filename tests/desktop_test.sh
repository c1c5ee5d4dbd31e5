#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The real QGIS desktop under Xvfb, with a fresh profile: the plugin zip installed by
# QGIS's own plugin installer, every tinlod algorithm run from the Processing toolbox
# through its dialog, and each output checked on the map with its style
# (tests/desktop_driver.py does the clicking and checking inside QGIS).
# Kept in ARTEFACT_DIR: map.png (the map canvas; map.pgw, its world file), window.png
# (the whole window), result.json (the checks, the desktop's log messages, the layer
# tree), driver.log, qgis.log and each dialog's log.
# Usage: desktop_test.sh PLUGIN_ZIP TINLOD_CLI ARTEFACT_DIR
set -euo pipefail
plugin_zip=$(realpath "$1")
tinlod_cli=$2
artefacts=$3
here=$(cd "$(dirname "$0")" && pwd)

for tool in xvfb-run xauth; do
  if ! command -v "$tool" > /dev/null; then
    echo "skipped: $tool is absent (Debian: apt-get install xvfb xauth); the desktop test needs a virtual X server"
    exit 77
  fi
done
if [[ ! -x /usr/bin/qgis ]]; then
  echo "skipped: /usr/bin/qgis (the QGIS desktop) is absent"
  exit 77
fi
[[ -f $plugin_zip ]] || { echo "FAILED: no plugin zip at $plugin_zip"; exit 1; }

mkdir -p "$artefacts"
artefacts=$(realpath "$artefacts")
# Last run's artefacts would pass for this run's if QGIS wrote none.
rm -f "$artefacts"/{map.png,map.pgw,window.png,result.json,driver.log,qgis.log} "$artefacts"/dialog_*.log

# Everything QGIS, Xvfb and Processing write goes under $work: a fresh home, profile,
# runtime and temporary folder, removed at the end whatever happens.
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/home" "$work/tmp" "$work/data" "$work/profiles"
mkdir -m 700 "$work/xdg"
export HOME=$work/home XDG_RUNTIME_DIR=$work/xdg TMPDIR=$work/tmp
export QGIS_CUSTOM_CONFIG_PATH=$work/profiles
unset QGIS_PLUGINPATH DISPLAY WAYLAND_DISPLAY

# A small DEM keeps each run to seconds; contours of it are the line input.
"$tinlod_cli" makedem -q -size 400 300 -cell 30 "$work/data/dem.tif"
gdal_contour -q -a elev -i 25 "$work/data/dem.tif" "$work/data/contours.gpkg"
# A build long enough to cancel from its dialog (about 10 s here).
"$tinlod_cli" makedem -q -size 2000 2000 -cell 10 "$work/data/big.tif"

export TINLOD_DESKTOP_ZIP=$plugin_zip TINLOD_DESKTOP_WORK=$work/data TINLOD_DESKTOP_ARTEFACTS=$artefacts
export TINLOD_DESKTOP_RESULT=$artefacts/result.json
start=$(date +%s)
# Debian's /usr/bin/qgis wrapper adds --noversioncheck itself.
if timeout -k 20 600 xvfb-run -a -s "-screen 0 1600x1000x24" /usr/bin/qgis --nologo \
    --profiles-path "$work/profiles" --code "$here/desktop_driver.py" > "$artefacts/qgis.log" 2>&1; then
  qgis_rc=0
else
  qgis_rc=$?
fi
echo "  QGIS ran for $(($(date +%s) - start)) s (exit $qgis_rc); artefacts in $artefacts"

if [[ ! -s $TINLOD_DESKTOP_RESULT ]]; then
  echo "FAILED: the desktop driver wrote no result (QGIS exit $qgis_rc$( ((qgis_rc == 124)) && echo ': timed out')); see $artefacts/qgis.log and driver.log"
  tail -n 20 "$artefacts/qgis.log" | sed 's/^/  | /'
  exit 1
fi

/usr/bin/python3 - "$TINLOD_DESKTOP_RESULT" "$qgis_rc" "$artefacts/map.png" <<'PY'
import json, sys
result = json.load(open(sys.argv[1]))
qgis_rc = int(sys.argv[2])
failures = 0
for c in result["checks"]:
    if c["ok"]:
        print("ok: " + c["what"])
    else:
        failures += 1
        print("FAILED: " + c["what"])
        for line in c["detail"].splitlines():
            print("  | " + line)
clean = qgis_rc == 0
print(("ok: " if clean else "FAILED: ") + "QGIS quits cleanly (exit %d)" % qgis_rc)
failures += not clean
times = result["seconds"]
print("  seconds: " + ", ".join("%s %s" % (k, v) for k, v in times.items()))
print("  screenshot: " + sys.argv[3])
print("desktop: %d passed, %d failed" % (sum(c["ok"] for c in result["checks"]) + clean, failures))
sys.exit(1 if failures else 0)
PY
