#!/usr/bin/env bash
# qgis_process.bin with the assembled plugin, as a batch user runs it: list, help, run
# with --json on a real DEM (the default DEM when ../shared/data is absent), and an error.
# Usage: qgis_process_test.sh PLUGIN_DIR TINLOD_CLI
set -euo pipefail
plugin_dir=$1
tinlod_cli=$2
here=$(cd "$(dirname "$0")" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# shellcheck source-path=SCRIPTDIR source=script_support.sh
source "$here/script_support.sh"
# No .aux.xml statistics beside the DEMs of ../shared/data.
export GDAL_PAM_ENABLED=NO
# An isolated QGIS profile holding the plugin, as `plugins enable` would leave it.
isolated_qgis "$work" "$plugin_dir"

"$qp" list > "$work/list.txt" 2>/dev/null
check "qgis_process list shows tinlod:sampletin" grep -q "tinlod:sampletin" "$work/list.txt"
check "qgis_process list shows tinlod:buildhierarchy" grep -q "tinlod:buildhierarchy" "$work/list.txt"
check "qgis_process list shows tinlod:accuracy" grep -q "tinlod:accuracy" "$work/list.txt"
check "qgis_process list shows tinlod:greedyinsertion" grep -q "tinlod:greedyinsertion" "$work/list.txt"
check "qgis_process list shows tinlod:extractlod" grep -q "tinlod:extractlod" "$work/list.txt"
check "qgis_process list shows tinlod:locate" grep -q "tinlod:locate" "$work/list.txt"
check "qgis_process list shows tinlod:dpvalues" grep -q "tinlod:dpvalues" "$work/list.txt"
check "qgis_process list shows tinlod:concavity" grep -q "tinlod:concavity" "$work/list.txt"

"$qp" help tinlod:sampletin > "$work/help.txt" 2>/dev/null
check "qgis_process help describes the parameters" grep -q "TARGET_CRS" "$work/help.txt"

data=${TINLOD_TEST_DATA:-$here/../../shared/data}
if [[ -f $data/dead_sea_N31E035.tif ]]; then
  dem=$data/dead_sea_N31E035.tif
  crs=EPSG:32636
else
  echo "note: ../shared/data is absent: qgis_process runs on the default DEM instead of a real one"
  dem=$work/default_dem.tif
  "$tinlod_cli" makedem "$dem" > /dev/null
  crs=EPSG:32632
fi
out=$work/out.gpkg
"$qp" --json run tinlod:sampletin --INPUT="$dem" --BLOCK=3 --OUTPUT="$out" > "$work/run.json" 2> "$work/run.err" || true
check "qgis_process --json run succeeds and reports the counts" /usr/bin/python3 - "$work/run.json" "$out" "$crs" <<'PY'
import json, sys
from osgeo import ogr
result = json.load(open(sys.argv[1]))
outputs = result["results"]
ds = ogr.Open(sys.argv[2])
triangles = ds.GetLayerByName("triangles")
assert outputs["OUTPUT"] == sys.argv[2], outputs
assert int(outputs["TRIANGLES"]) == triangles.GetFeatureCount() > 1000, (outputs, triangles.GetFeatureCount())
assert int(outputs["VERTICES"]) == ds.GetLayerByName("vertices").GetFeatureCount()
srs = triangles.GetSpatialRef()
assert "%s:%s" % (srs.GetAuthorityName(None), srs.GetAuthorityCode(None)) == sys.argv[3], srs.GetName()
print("  %s triangles in %s" % (outputs["TRIANGLES"], srs.GetName()))
PY

hier=$work/hier.gpkg
"$qp" --json run tinlod:buildhierarchy --INPUT="$dem" --METHOD=1 --DELETE_PCT=20 --STOP_PCT=5 --OUTPUT="$hier" > "$work/hier.json" 2> "$work/hier.err" || true
check "qgis_process --json run tinlod:buildhierarchy writes every level" /usr/bin/python3 - "$work/hier.json" "$hier" <<'PY'
import json, sys
from osgeo import ogr
outputs = json.load(open(sys.argv[1]))["results"]
ds = ogr.Open(sys.argv[2])
levels = int(outputs["COARSEST_LEVEL"])
assert levels >= 5 and int(outputs["LEVELS"]) == levels + 1, outputs
rows = {f.GetField("level"): f for f in ds.GetLayerByName("levels")}
for level in range(levels + 1):
    layer = ds.GetLayerByName("level_%d" % level)
    assert layer is not None and layer.GetFeatureCount() == rows[level].GetField("triangles"), level
assert rows[levels].GetField("vertices") == int(outputs["COARSEST_VERTICES"])
print("  %d levels, %d -> %d vertices" % (levels + 1, rows[0].GetField("vertices"), rows[levels].GetField("vertices")))
PY

# QGIS reads the bulk-loaded spatial index: a native algorithm with an extent filter takes
# exactly the triangles that meet the extent, from a level view and from the triangles table.
/usr/bin/python3 - "$hier" > "$work/extent.txt" <<'PY'
import sys
from osgeo import ogr
ds = ogr.Open(sys.argv[1])
minx, maxx, miny, maxy = ds.GetLayerByName("triangles").GetExtent()
w, h = maxx - minx, maxy - miny
print("%.6f,%.6f,%.6f,%.6f" % (minx + 0.3 * w, minx + 0.45 * w, miny + 0.5 * h, miny + 0.6 * h))
PY
for layer in level_3 triangles; do
  "$qp" run native:extractbyextent --INPUT="$hier|layername=$layer" --EXTENT="$(cat "$work/extent.txt")" --CLIP=false \
    --OUTPUT="$work/extent_$layer.gpkg" > "$work/extent_$layer.log" 2>&1 || true
  check "QGIS extracts by extent from $layer through its spatial index" /usr/bin/python3 - "$hier" "$layer" "$work/extent.txt" "$work/extent_$layer.gpkg" <<'PY'
import sys
from osgeo import ogr
hier, name, extent, out = sys.argv[1:]
x0, x1, y0, y1 = map(float, open(extent).read().split(","))
box = ogr.CreateGeometryFromWkt("POLYGON((%r %r,%r %r,%r %r,%r %r,%r %r))" % (x0, y0, x1, y0, x1, y1, x0, y1, x0, y0))
ds = ogr.Open(hier)
layer = ds.GetLayerByName(name)
expected = sum(1 for f in layer if f.GetGeometryRef().Intersects(box))
extracted = ogr.Open(out)  # a layer lives only as long as its dataset
got = extracted.GetLayer(0).GetFeatureCount()
assert expected > 0 and got == expected, (got, expected)
print("  %d of %d triangles" % (got, layer.GetFeatureCount()))
PY
done

lod=$work/lod.gpkg
"$qp" --json run tinlod:extractlod --HIERARCHY="$hier" --MAX_ERROR=20 --OUTPUT="$lod" > "$work/lod.json" 2> "$work/lod.err" || true
check "qgis_process --json run tinlod:extractlod writes a TIN coarser than level 0" /usr/bin/python3 - "$work/lod.json" "$lod" "$hier" <<'PY'
import json, sys
from osgeo import ogr
outputs = json.load(open(sys.argv[1]))["results"]
lod, hierarchy = ogr.Open(sys.argv[2]), ogr.Open(sys.argv[3])  # a layer lives only as long as its dataset
triangles = lod.GetLayerByName("triangles")
level0 = hierarchy.GetLayerByName("level_0").GetFeatureCount()
assert int(outputs["TRIANGLES"]) == triangles.GetFeatureCount(), outputs
assert 0 < triangles.GetFeatureCount() < level0, (triangles.GetFeatureCount(), level0)
print("  %d triangles where level 0 has %d" % (triangles.GetFeatureCount(), level0))
PY

"$qp" --json run tinlod:locate --INPUT="$hier|layername=vertices" --HIERARCHY="$hier" --LEVEL=0 --OUTPUT="$work/located.gpkg" > "$work/loc.json" 2> "$work/loc.err" || true
check "qgis_process --json run tinlod:locate gives every vertex an elevation on level 0" /usr/bin/python3 - "$work/loc.json" "$work/located.gpkg" <<'PY'
import json, sys
from osgeo import ogr
outputs = json.load(open(sys.argv[1]))["results"]
ds = ogr.Open(sys.argv[2])  # a layer lives only as long as its dataset
points = ds.GetLayerByName("points")
assert int(outputs["POINTS"]) == int(outputs["LOCATED"]) == points.GetFeatureCount() > 1000, outputs
# Each point is a vertex of level 0: its elevation is the vertex's own height.
wrong = [f.GetFID() for f in points if f.GetField("elevation") is None or abs(f.GetField("elevation") - f.GetGeometryRef().GetZ()) > 1e-6]
assert not wrong, wrong[:5]
print("  %s points located on level 0" % outputs["LOCATED"])
PY

# The catalogue of a tiled run as the hierarchy: 2 x 2 tiles of a small DEM built one by one
# and listed as tinlod-tiles lists them (its own catalogue module, without Dask).
"$tinlod_cli" makedem "$work/small.tif" -size 200 150 -q
mkdir -p "$work/cat_tiles"
for tile in 0,0 1,0 0,1 1,1; do
  "$tinlod_cli" build "$work/small.tif" "$work/cat_tiles/tile_${tile/,/_}.gpkg" -tile_size 102 -tile "$tile" -q
done
PYTHONPATH=$here/../tiles /usr/bin/python3 - "$work/small.tif" "$work/cat.gpkg" <<'PY'
import sys
from osgeo import gdal, ogr
from tinlodtiles.catalogue import Catalogue
from tinlodtiles.grid import tile_grid
dem, path = gdal.Open(sys.argv[1]), sys.argv[2]
tiles = tile_grid(dem.RasterXSize, dem.RasterYSize, 102)
catalogue = Catalogue.create(path, {"TINLOD_TILE_SIZE": "102"}, None, tiles)
for t in tiles:
    source = ogr.Open("%s/cat_tiles/%s" % (path.rsplit("/", 1)[0], t.name))
    minx, maxx, miny, maxy = source.GetLayerByName("triangles").GetExtent()
    box = ogr.CreateGeometryFromWkt("POLYGON((%r %r,%r %r,%r %r,%r %r,%r %r))" % (minx, miny, maxx, miny, maxx, maxy, minx, maxy, minx, miny))
    catalogue.update(t.col, t.row, {"file": "cat_tiles/" + t.name, "status": "done"}, box)
catalogue.close()
PY
"$qp" --json run tinlod:extractlod --HIERARCHY="$work/cat.gpkg" --MAX_ERROR=5 --OUTPUT="$work/cat_lod.gpkg" > "$work/cat_lod.json" 2> "$work/cat_lod.err" || true
check "qgis_process --json run tinlod:extractlod takes a catalogue: one TIN across its tiles" /usr/bin/python3 - "$work/cat_lod.json" "$work/cat_lod.gpkg" <<'PY'
import json, sys
from osgeo import ogr
outputs = json.load(open(sys.argv[1]))["results"]
ds = ogr.Open(sys.argv[2])  # a layer lives only as long as its dataset
places = [(f.GetGeometryRef().GetX(), f.GetGeometryRef().GetY()) for f in ds.GetLayerByName("vertices")]
assert int(outputs["TRIANGLES"]) == ds.GetLayerByName("triangles").GetFeatureCount() > 100, outputs
assert len(places) == len(set(places)), "a vertex of a shared line twice"
print("  %s triangles over 4 tiles" % outputs["TRIANGLES"])
PY
# A centre of detail picked in another CRS (the canvas's) is taken to the tiles' CRS.
read -r utm_centre lonlat_centre < <(/usr/bin/python3 - "$work/small.tif" <<'PY'
import sys
from osgeo import gdal, osr
dem = gdal.Open(sys.argv[1])
x0, dx, _, y0, _, dy = dem.GetGeoTransform()
x, y = x0 + dx * dem.RasterXSize * 0.3, y0 + dy * dem.RasterYSize * 0.6
wgs84 = osr.SpatialReference()
wgs84.ImportFromEPSG(4326)
wgs84.SetAxisMappingStrategy(osr.OAMS_TRADITIONAL_GIS_ORDER)
to_wgs84 = osr.CoordinateTransformation(dem.GetSpatialRef(), wgs84)
lon, lat, _ = to_wgs84.TransformPoint(x, y)
print("%.6f,%.6f %.9f,%.9f" % (x, y, lon, lat))
PY
)
"$qp" --json run tinlod:extractlod --HIERARCHY="$work/cat.gpkg" "--CENTER=$utm_centre [EPSG:32632]" --DROPOFF=20 --OUTPUT="$work/cat_utm.gpkg" > "$work/cat_utm.json" 2> "$work/cat_utm.err" || true
"$qp" --json run tinlod:extractlod --HIERARCHY="$work/cat.gpkg" "--CENTER=$lonlat_centre [EPSG:4326]" --DROPOFF=20 --OUTPUT="$work/cat_ll.gpkg" > "$work/cat_ll.json" 2> "$work/cat_ll.err" || true
# Without a CRS (no project here): in the hierarchy's, as docs/qgis/extractlod.md says.
"$qp" --json run tinlod:extractlod --HIERARCHY="$work/cat.gpkg" "--CENTER=$utm_centre" --DROPOFF=20 --OUTPUT="$work/cat_bare.gpkg" > "$work/cat_bare.json" 2> "$work/cat_bare.err" || true
"$tinlod_cli" lod "$work/cat.gpkg" "$work/cat_coarsest.gpkg" -center 0 0 -dropoff 0 -q
check "qgis_process --json run tinlod:extractlod on a catalogue: a CENTER in EPSG:4326, or with no CRS, gives the TIN of the same centre in the tiles' CRS" /usr/bin/python3 - "$work/cat_utm.json" "$work/cat_ll.json" "$work/cat_bare.json" "$work/cat_coarsest.gpkg" <<'PY'
import json, sys
from osgeo import ogr
utm, lonlat, bare = (int(json.load(open(p))["results"]["TRIANGLES"]) for p in sys.argv[1:4])
ds = ogr.Open(sys.argv[4])
coarsest = ds.GetLayerByName("triangles").GetFeatureCount()
assert utm == lonlat == bare > coarsest, (utm, lonlat, bare, coarsest)  # finer near the centre either way
print("  %d triangles each way (the coarsest level: %d)" % (utm, coarsest))
PY
"$qp" --json run tinlod:locate --INPUT="$work/cat_lod.gpkg|layername=vertices" --HIERARCHY="$work/cat.gpkg" --LEVEL=0 --OUTPUT="$work/cat_loc.gpkg" > "$work/cat_loc.json" 2> "$work/cat_loc.err" || true
check "qgis_process --json run tinlod:locate takes a catalogue: each vertex its own height on level 0" /usr/bin/python3 - "$work/cat_loc.gpkg" <<'PY'
import sys
from osgeo import ogr
ds = ogr.Open(sys.argv[1])  # a layer lives only as long as its dataset
points = list(ds.GetLayerByName("points"))
assert len(points) > 100 and all(p["tile"] for p in points), len(points)
wrong = [p.GetFID() for p in points if p["elevation"] is None or abs(p["elevation"] - p.GetGeometryRef().GetZ()) > 1e-6]
assert not wrong, wrong[:5]
PY
"$qp" --json run tinlod:accuracy --INPUT="$work/small.tif" --HIERARCHY="$work/cat.gpkg" --REFERENCE=1 --REPORT="$work/cat.json" > "$work/cat_acc.json" 2> "$work/cat_acc.err" || true
check "qgis_process --json run tinlod:accuracy takes a catalogue: every level of its tiles" /usr/bin/python3 - "$work/cat.json" <<'PY'
import json, sys
rows = json.load(open(sys.argv[1]))["runs"][0]["levels"]
assert len(rows) == 15 and rows[-1]["vertices"] < rows[0]["vertices"] / 10, [r["vertices"] for r in rows]
assert all(abs(r["max_abs_error_m"] - r["certified_error_m"]) < 1e-6 for r in rows)
print("  levels 0-14, %d to %d vertices" % (rows[0]["vertices"], rows[-1]["vertices"]))
PY

gdal_contour -q -a elev -i 100 "$dem" "$work/contours.gpkg"
"$qp" --json run tinlod:dpvalues --INPUT="$work/contours.gpkg" --THRESHOLD=50 --OUTPUT="$work/dp.gpkg" > "$work/dp.json" 2> "$work/dp.err" || true
check "qgis_process --json run tinlod:dpvalues on contours of the DEM" /usr/bin/python3 - "$work/dp.json" "$work/dp.gpkg" <<'PY'
import json, sys
from osgeo import ogr
outputs = json.load(open(sys.argv[1]))["results"]
ds = ogr.Open(sys.argv[2])  # a layer lives only as long as its dataset
lines = ds.GetLayerByName("lines")
assert int(outputs["LINES"]) == lines.GetFeatureCount() > 10, outputs
assert ds.GetLayerByName("simplified").GetFeatureCount() == lines.GetFeatureCount()
f = lines.GetNextFeature()
assert f.GetGeometryRef().GetM(0) == 1e300, f.GetGeometryRef().GetM(0)
print("  %s lines, %s crossings at 50 m" % (outputs["LINES"], outputs["CROSSINGS"]))
PY

"$qp" --json run tinlod:concavity --INPUT="$work/contours.gpkg" --WINDOW=300 --OUTPUT="$work/cc.gpkg" > "$work/cc.json" 2> "$work/cc.err" || true
check "qgis_process --json run tinlod:concavity on contours of the DEM" /usr/bin/python3 - "$work/cc.json" "$work/cc.gpkg" <<'PY'
import json, sys
from osgeo import ogr
outputs = json.load(open(sys.argv[1]))["results"]
ds = ogr.Open(sys.argv[2])  # a layer lives only as long as its dataset
parts = ds.GetLayerByName("parts").GetFeatureCount()
assert parts == int(outputs["CONVEX"]) + int(outputs["STRAIGHT"]) + int(outputs["CONCAVE"]) > 10, outputs
assert ds.GetLayerByName("vertices").GetFeatureCount() == int(outputs["VERTICES"])
print("  %d parts: %s convex, %s concave" % (parts, outputs["CONVEX"], outputs["CONCAVE"]))
PY

# An input is never an output, even where QGIS would replace a destination.
dem_sum=$(md5sum < "$dem")
"$qp" run tinlod:accuracy --INPUT="$dem" --HIERARCHY="$hier" --ACCURACY="$dem" > "$work/same.out" 2>&1 || true
check "qgis_process run tinlod:accuracy refuses to write over its DEM" \
  bash -c '[[ $(md5sum < "$1") == "$2" ]] && grep -q "is an input of this run" "$3"' _ "$dem" "$dem_sum" "$work/same.out"

# Ctrl-C reaches a tinlod algorithm under qgis_process (Python's handler would only note it):
# the run stops within seconds, and the old output stays as it was.
cp "$hier" "$work/kept.gpkg"
kept_sum=$(md5sum < "$work/kept.gpkg")
"$tinlod_cli" makedem -q -size 1500 1200 -cell 10 "$work/medium.tif"
"$qp" run tinlod:sampletin --INPUT="$work/medium.tif" --BLOCK=1 --OUTPUT="$work/kept.gpkg" > "$work/int.out" 2>&1 &
pid=$!
for _ in $(seq 600); do grep -q "10" "$work/int.out" 2>/dev/null && break; kill -0 $pid 2>/dev/null || break; sleep 0.05; done
kill -INT $pid
start=$(date +%s%N)
wait $pid && int_rc=0 || int_rc=$?
int_ms=$(( ($(date +%s%N) - start) / 1000000 ))
echo "  qgis_process stopped ${int_ms} ms after Ctrl-C (exit $int_rc)"
check "qgis_process stops a tinlod run at Ctrl-C within 2.5 s, the old output kept" \
  bash -c '(( $1 != 0 && $2 < 2500 )) && [[ $(md5sum < "$3") == "$4" ]] && ! ls -A "$5" | grep -q "^\.kept"' _ "$int_rc" "$int_ms" "$work/kept.gpkg" "$kept_sum" "$work"

# ... and so does one before the algorithm has started, from the moment the plugin has
# loaded: in a script's background job, where the shell has SIGINT ignored, the run
# stopped nowhere and replaced its output. Without the mend SIGINT is caught only once the
# algorithm has started, half a second after the library is loaded: sent before, it is lost.
"$qp" run tinlod:sampletin --INPUT="$work/medium.tif" --BLOCK=1 --OUTPUT="$work/kept.gpkg" > "$work/early.out" 2>&1 &
pid=$!
for _ in $(seq 600); do  # until the plugin has loaded the provider's library
  grep -q libtinlod_processing /proc/$pid/maps 2>/dev/null && break
  kill -0 $pid 2>/dev/null || break
  sleep 0.01
done
for _ in $(seq 30); do  # then until SIGINT is caught, 0.3 s at most: the provider is registered at once
  caught=$(sed -n 's/^SigCgt:\t//p' /proc/$pid/status 2>/dev/null || true)
  [[ -n $caught ]] && (( (0x$caught & 2) != 0 )) && break
  sleep 0.01
done
started=$(grep -c "^Inputs" "$work/early.out" || true)
kill -INT $pid
wait $pid && early_rc=0 || early_rc=$?
echo "  Ctrl-C when the plugin had loaded (the algorithm started: $started): exit $early_rc"
check "qgis_process stops a tinlod run at a Ctrl-C before the algorithm starts, the old output kept" \
  bash -c '(( $1 != 0 )) && [[ $(md5sum < "$2") == "$3" ]]' _ "$early_rc" "$work/kept.gpkg" "$kept_sum"

"$qp" --json run tinlod:accuracy --INPUT="$dem" --HIERARCHY="$hier" --ACCURACY="$work/acc.tif" --REPORT="$work/acc.json" > "$work/acc.out.json" 2> "$work/acc.err" || true
check "qgis_process --json run tinlod:accuracy writes the raster and the report" /usr/bin/python3 - "$work/acc.out.json" "$work/acc.tif" "$work/acc.json" <<'PY'
import json, sys
from osgeo import gdal
outputs = json.load(open(sys.argv[1]))["results"]
raster = gdal.Open(sys.argv[2])
assert raster.RasterCount == 4, raster.RasterCount
report = json.load(open(sys.argv[3]))
levels = report["runs"][0]["levels"]
assert levels[0]["rmse_m"] == 0 and abs(levels[-1]["rmse_m"] - float(outputs["RMSE"])) < 1e-6, (levels[-1], outputs)
assert 0.9 < float(outputs["R_ELEVATION"]) <= 1, outputs
print("  coarsest level: RMSE %.2f m, r elevation %.6f, r mean curvature %.4f" % (
    float(outputs["RMSE"]), float(outputs["R_ELEVATION"]), float(outputs["R_MEAN_CURVATURE"])))
PY

ins=$work/insert.gpkg
"$qp" --json run tinlod:greedyinsertion --INPUT="$dem" --MAX_ERROR=5 --OUTPUT="$ins" > "$work/ins.json" 2> "$work/ins.err" || true
check "qgis_process --json run tinlod:greedyinsertion keeps every cell within the tolerance" /usr/bin/python3 - "$work/ins.json" "$ins" <<'PY'
import json, sys
from osgeo import ogr
outputs = json.load(open(sys.argv[1]))["results"]
ds = ogr.Open(sys.argv[2])
vertices = ds.GetLayerByName("vertices")
assert int(outputs["VERTICES"]) == vertices.GetFeatureCount() > 100, outputs
assert int(outputs["TRIANGLES"]) == ds.GetLayerByName("triangles").GetFeatureCount()
assert float(outputs["MAX_ERROR"]) <= 5 + 1e-9 and 0 < float(outputs["RMSE"]) < 5, outputs
orders = sorted(f.GetField("insertion") for f in vertices)
assert orders[0] == 1 and len(set(orders)) == len(orders), orders[:5]
print("  %s vertices, maximum error %.3f m, RMSE %.3f m" % (outputs["VERTICES"], float(outputs["MAX_ERROR"]), float(outputs["RMSE"])))
PY

if "$qp" run tinlod:sampletin --INPUT="$dem" --BAND=9 --OUTPUT="$work/bad.gpkg" > "$work/bad.out" 2> "$work/bad.err"; then
  bad_rc=0
else
  bad_rc=$?
fi
check "a bad band exits 1" test "$bad_rc" -eq 1
check "a bad band names BAND on stderr" grep -q "Invalid band number for BAND (9)" "$work/bad.err"
check "a bad band writes nothing" test ! -e "$work/bad.gpkg"

# scripts/install-plugin.sh into a profile folder of one's choosing: installed and enabled
# there, so qgis_process on that configuration lists the algorithms.
chosen=$work/chosen_config
TINLOD_PLUGIN_DIR=$plugin_dir QGIS_PROFILE_DIR=$chosen/profiles/default bash "$here/../scripts/install-plugin.sh" > "$work/install.out"
check "install-plugin.sh says it enabled the plugin in the chosen profile" grep -q "enabled it in $chosen/profiles/default" "$work/install.out"
QGIS_CUSTOM_CONFIG_PATH=$chosen "$qp" list > "$work/chosen.txt" 2>/dev/null || true
check "install-plugin.sh: qgis_process on that profile lists tinlod:sampletin" grep -q "tinlod:sampletin" "$work/chosen.txt"

# A provider built for another QGIS, simulated as the issue says: a copy of the plugin whose
# library needs a libqgis_core of another version (its name changed, same length, in the
# copy). QGIS must say so once, in words, and go on: no traceback, native algorithms there.
other=$work/other_config
mkdir -p "$other/profiles/default/python/plugins"
cp -r "$plugin_dir" "$other/profiles/default/python/plugins/tinlod"
/usr/bin/python3 - "$other/profiles/default/python/plugins/tinlod/libtinlod_processing.so" <<'PY'
import re, sys
path = sys.argv[1]
data = open(path, "rb").read()
needed = re.search(rb"libqgis_core\.so\.3\.\d+\.\d+", data).group(0)
other = needed[:-2] + (b"98" if needed.endswith(b"99") else b"99")
open(path, "wb").write(data.replace(needed, other))
PY
QGIS_CUSTOM_CONFIG_PATH=$other "$qp" plugins enable tinlod > /dev/null 2>&1 || true
QGIS_CUSTOM_CONFIG_PATH=$other "$qp" list > "$work/other.out" 2> "$work/other.err" && other_rc=0 || other_rc=$?
cat "$work/other.out" "$work/other.err" > "$work/other.all"
check "another QGIS: qgis_process still works (exit 0, native algorithms listed)" \
  bash -c "test $other_rc -eq 0 && grep -q 'native:buffer' '$work/other.out'"
check "another QGIS: no traceback" bash -c "! grep -q Traceback '$work/other.all'"
check "another QGIS: one clear message naming the QGIS it was built for and what to do" \
  bash -c "test \$(grep -c 'tinlod: its Processing provider was built for QGIS $(cat "$plugin_dir/built_for_qgis.txt") and cannot load' '$work/other.all') -eq 1 && grep -q 'rebuild tinlod on this machine' '$work/other.all'"
check "another QGIS: no tinlod algorithm is listed" bash -c "! grep -q 'tinlod:' '$work/other.out'"

finish_checks qgis_process
