#!/usr/bin/env bash
# The main job on the project's own default DEM: build, generate the DEM, simplify it
# into a TIN hierarchy, describe the result, and say where the outputs are.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bash "$root/scripts/build.sh"
out=$root/build/demo
mkdir -p "$out"
tinlod=$root/build/core/tinlod
"$tinlod" makedem -overwrite "$out/default_dem.tif"
"$tinlod" build -overwrite -accuracy "$out/default_accuracy.tif" -report "$out/default_report.html" \
  "$out/default_dem.tif" "$out/default_hierarchy.gpkg"
"$tinlod" info "$out/default_hierarchy.gpkg"
cat <<MSG

Outputs:
  DEM:        $out/default_dem.tif
  Hierarchy:  $out/default_hierarchy.gpkg
              layers level_0 ... level_N (one TIN per level), vertices, triangles, groups, levels;
              open it in QGIS (Layer > Add Layer > Add Vector Layer) or with ogrinfo
  Accuracy:   $out/default_accuracy.tif (coarsest level: elevation and mean curvature differences)
              $out/default_report.html (every level, with plots; open it in a browser)
  QGIS plugin: $root/build/plugin/tinlod  (zip: $(ls "$root"/build/tinlod-plugin-*.zip))
MSG
