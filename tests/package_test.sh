#!/usr/bin/env bash
# The Debian package as a user gets it: made by cpack from the build, its control data and
# contents inspected with dpkg-deb, unpacked into a scratch root, and its command line and
# QGIS plugin run from there (qgis_process with the unpacked plugin folder).
# Usage: package_test.sh BUILD_DIR
set -euo pipefail
build=$1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
for tool in cpack dpkg-deb dpkg-shlibdeps; do
  command -v "$tool" > /dev/null || { echo "skipped: $tool is not installed"; exit 77; }
done

# shellcheck source-path=SCRIPTDIR source=script_support.sh
source "$(dirname "$0")/script_support.sh"

(cd "$build" && cpack -G DEB -B "$work/out" > "$work/cpack.log" 2>&1) || { cat "$work/cpack.log"; exit 1; }
deb=$(ls "$work"/out/tinlod_*_amd64.deb)
dpkg-deb -I "$deb" > "$work/info.txt"
dpkg-deb -c "$deb" | awk '{print $6}' > "$work/contents.txt"
qgis_core=$(ldd "$build/plugin/tinlod/libtinlod_processing.so" | sed -nE 's/^\s*(libqgis_core\.so\.[0-9.]+) .*/\1/p')
qgis_package=$(dpkg -S "$qgis_core" 2>/dev/null | head -1 | cut -d: -f1)
check "the package depends on the package of $qgis_core ($qgis_package), from dpkg-shlibdeps" \
  grep -Eq "Depends:.*\\b$qgis_package\\b" "$work/info.txt"
check "the package depends on GDAL's library" grep -Eq "Depends:.*\blibgdal[0-9]+\b" "$work/info.txt"
check "the package depends on python3-qgis (the plugin's Python side)" grep -Eq "Depends:.*\bpython3-qgis\b" "$work/info.txt"
check "the package holds the command line" grep -qx "./usr/bin/tinlod" "$work/contents.txt"
check "the package holds tinlod-tiles, the Dask tile driver" grep -qx "./usr/bin/tinlod-tiles" "$work/contents.txt"
check "the package holds tinlod-tiles' modules" grep -qx "./usr/share/tinlod/tiles/tinlodtiles/driver.py" "$work/contents.txt"
check "the package recommends python3-distributed (for tinlod-tiles)" grep -Eq "Recommends:.*\bpython3-distributed\b" "$work/info.txt"
check "the package holds the docs the README links to" grep -qx "./usr/share/doc/tinlod/docs/cli/build.md" "$work/contents.txt"
for f in __init__.py tinlod_plugin.py metadata.txt icon.svg built_for_qgis.txt libtinlod_processing.so help/sampletin.md; do
  check "the package holds the plugin's $f where QGIS finds system plugins" \
    grep -qx "./usr/share/qgis/python/plugins/tinlod/$f" "$work/contents.txt"
done

root=$work/root
dpkg-deb -x "$deb" "$root"
check "the unpacked command line runs" bash -c "'$root/usr/bin/tinlod' --version | grep -q '^tinlod '"
check "the unpacked tinlod-tiles runs, finding its modules" bash -c "'$root/usr/bin/tinlod-tiles' --help | grep -q '^Usage: tinlod-tiles '"
check "the unpacked tinlod tiles forwards to tinlod-tiles" bash -c "'$root/usr/bin/tinlod' tiles --help | grep -q '^Usage: tinlod-tiles '"
"$root/usr/bin/tinlod" makedem "$work/dem.tif" > /dev/null
check "the unpacked command line samples a DEM" "$root/usr/bin/tinlod" sample "$work/dem.tif" "$work/tin.gpkg" -q

export QGIS_PLUGINPATH=$root/usr/share/qgis/python/plugins
isolated_qgis "$work"
"$qp" list > "$work/list.txt" 2>&1 || true
check "qgis_process with the unpacked plugin lists tinlod:sampletin" grep -q "tinlod:sampletin" "$work/list.txt"
"$qp" run tinlod:sampletin --INPUT="$work/dem.tif" --OUTPUT="$work/qp.gpkg" > "$work/run.txt" 2>&1 || true
check "qgis_process runs tinlod:sampletin from the unpacked plugin" test -s "$work/qp.gpkg"

finish_checks package
