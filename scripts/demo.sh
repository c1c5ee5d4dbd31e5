#!/usr/bin/env bash
# The main job on the project's own default DEM: build, generate the DEM, sample it into
# a TIN, and say where the outputs are.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bash "$root/scripts/build.sh"
out=$root/build/demo
mkdir -p "$out"
tinlod=$root/build/core/tinlod
"$tinlod" makedem -overwrite "$out/default_dem.tif"
"$tinlod" sample -overwrite "$out/default_dem.tif" "$out/default_tin.gpkg"
cat <<MSG

Outputs:
  DEM:  $out/default_dem.tif
  TIN:  $out/default_tin.gpkg  (layers 'vertices' and 'triangles'; open it in QGIS or with ogrinfo)
  QGIS plugin: $root/build/plugin/tinlod  (zip: $(ls "$root"/build/tinlod-plugin-*.zip))
MSG
