#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Tiles built one by one with `tinlod build -tile` fit together at every level: on the
# project's synthetic DEM (a void and a flat lake) and, where ../shared/data is present, on
# a real geographic DEM with voids. tile_union.py checks each level's union (no overlap, no
# crack, border vertices at the same place in both tiles); it is shown to fail on tiles
# that do not belong together.
# Usage: tile_union_test.sh TINLOD
set -uo pipefail
here=$(cd "$(dirname "$0")" && pwd)
# shellcheck source=tests/script_support.sh
source "$here/script_support.sh"
tinlod=$1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
union() { /usr/bin/python3 "$here/tile_union.py" "$@" > "$work/union.log" 2>&1; }

# build_tiles DEM SIZE PREFIX [options]: every tile of DEM; echoes how many were written.
build_tiles() {
  local dem=$1 size=$2 prefix=$3; shift 3
  local dims across down written=0
  dims=$(gdalinfo "$dem" | sed -n 's/^Size is \([0-9]*\), \([0-9]*\)/\1 \2/p')
  read -r w h <<< "$dims"
  across=$(( w <= 1 ? 1 : (w - 2) / size + 1 )); down=$(( h <= 1 ? 1 : (h - 2) / size + 1 ))
  for ((c = 0; c < across; c++)); do
    for ((r = 0; r < down; r++)); do
      "$tinlod" build "$dem" "${prefix}_${c}_${r}.gpkg" -tile_size "$size" -tile "$c,$r" -q "$@" && written=$((written + 1))
    done
  done
  echo "$written"
}

"$tinlod" makedem "$work/dem.tif" -size 400 330 -q
check "12 tiles of the synthetic DEM are built" test "$(build_tiles "$work/dem.tif" 120 "$work/syn")" = 12
"$tinlod" build "$work/dem.tif" "$work/whole.gpkg" -q
# The tiles' lines hold unjittered vertices, so the areas differ a little (3e-5 measured).
check "their union is conforming at every level, with the whole run's area (to 1e-4)" \
  union --whole "$work/whole.gpkg" --max_area_change 1e-4 "$work"/syn_*.gpkg
check "... and has 15 levels (the defaults' 14 above level 0)" test "$(grep -c 'conforming=yes' "$work/union.log")" = 15
cp "$work/union.log" "$work/union_ok.log"

# The two passes of -selection global: every tile's survey, one threshold per level for the
# whole raster, then the tiles built with them fit together as well.
failed=0
for f in "$work"/syn_*.gpkg; do
  t=$(basename "$f" .gpkg); t=${t#syn_}
  "$tinlod" build "$work/dem.tif" "$work/survey_$t.json" -tile_size 120 -tile "${t/_/,}" -q -survey || failed=$((failed + 1))
done
check "the 12 tiles are surveyed" test "$failed" = 0
thresholds=$(cd "$here/../tiles" && /usr/bin/python3 -c "
import glob
from tinlodtiles.thresholds import read_survey, level_thresholds, as_option
print(as_option(level_thresholds([read_survey(p) for p in sorted(glob.glob('$work/survey_*.json'))], 20, 5)))")
check "the surveys give 14 thresholds" test "$(tr ',' '\n' <<< "$thresholds" | wc -l)" = 14
# line_outline_union PATTERN OUT: the line cells on the outline the surveys list, in one file.
line_outline_union() {
  (cd "$here/../tiles" && /usr/bin/python3 -c "
import glob, sys
from tinlodtiles import cell_file, line_outline
cell_file.write_cells(sys.argv[2], line_outline.gather(glob.glob(sys.argv[1])))" "$1" "$2")
}
line_outline_union "$work/survey_*.json" "$work/line_outline.txt"
check "the surveys list line cells on the outline (the void reaches a line)" test -s "$work/line_outline.txt"
failed=0
for f in "$work"/syn_*.gpkg; do
  t=$(basename "$f" .gpkg); t=${t#syn_}
  "$tinlod" build "$work/dem.tif" "$work/glob_$t.gpkg" -tile_size 120 -tile "${t/_/,}" -q -level_thresholds "$thresholds" \
    -line_outline "$work/line_outline.txt" || failed=$((failed + 1))
done
check "the 12 tiles are built with the thresholds" test "$failed" = 0
check "tiles built with the thresholds and the line outline fit together at every level, with the whole run's area" \
  union --whole "$work/whole.gpkg" --max_area_change 1e-4 "$work"/glob_*.gpkg
level_counts() { /usr/bin/python3 -c "import sqlite3,sys; print([r[0] for r in sqlite3.connect(sys.argv[1]).execute('select vertices from levels')])" "$1"; }
check "... and the thresholds changed what they deleted" test "$(level_counts "$work/glob_1_1.gpkg")" != "$(level_counts "$work/syn_1_1.gpkg")"
err=$("$tinlod" build "$work/dem.tif" "$work/x.gpkg" -tile_size 120 -tile 0,0 -level_thresholds 1,2 2>&1)
check "too few thresholds are refused" grep -q "gives 2 thresholds for 14 levels" <<< "$err"

# Tiles that do not belong together are caught: another seed moves the border vertices,
# another delete percentage thins the border lines otherwise.
cp "$work/syn_1_1.gpkg" "$work/keep.gpkg"
"$tinlod" build "$work/dem.tif" "$work/syn_1_1.gpkg" -tile_size 120 -tile 1,1 -q -overwrite -seed 2
/usr/bin/python3 "$here/tile_union.py" "$work"/syn_*.gpkg > "$work/apart.log" 2>&1
check "a tile with another seed is refused (vertices apart)" test $? = 1
check "... naming a vertex at two places" grep -q "elsewhere$" "$work/apart.log"
"$tinlod" build "$work/dem.tif" "$work/syn_1_1.gpkg" -tile_size 120 -tile 1,1 -q -overwrite -delete_pct 5 -max_levels 14
/usr/bin/python3 "$here/tile_union.py" "$work"/syn_*.gpkg > "$work/crack.log" 2>&1
check "a tile thinned otherwise is refused (a crack)" grep -q "(a crack)" "$work/crack.log"
cp "$work/keep.gpkg" "$work/syn_1_1.gpkg"

# Option errors name the option.
err=$("$tinlod" build "$work/dem.tif" "$work/x.gpkg" -tile_size 100 -tile 0,0 2>&1)
check "-tile_size not a multiple of -block is refused" grep -q -- "-tile_size 100 must be a multiple of -block" <<< "$err"
err=$("$tinlod" build "$work/dem.tif" "$work/x.gpkg" -tile_size 120 -tile 4,0 2>&1)
check "-tile outside the grid is refused and the grid is named" grep -q "make 4 x 3 tiles" <<< "$err"

# A tile with no data: exit code 3, nothing written.
/usr/bin/python3 - "$work/dem.tif" "$work/holed.tif" << 'PY'
import sys
from osgeo import gdal
src = gdal.Open(sys.argv[1])
dst = gdal.GetDriverByName("GTiff").CreateCopy(sys.argv[2], src)
band = dst.GetRasterBand(1)
a = band.ReadAsArray()
a[0:150, 0:150] = band.GetNoDataValue()
band.WriteArray(a)
dst = None
PY
"$tinlod" build "$work/holed.tif" "$work/empty.gpkg" -tile_size 120 -tile 0,0 -q 2> "$work/empty.err"
check "a tile without data exits with 3" test $? = 3
check "... and writes nothing" test ! -e "$work/empty.gpkg"

data=${TINLOD_TEST_DATA:-$here/../../shared/data}
if [[ -f $data/swiss_alps_N46E008.tif ]]; then
  dem=$data/swiss_alps_N46E008.tif  # degrees, 7 % voids
  check "4 tiles of swiss_alps are built" test "$(build_tiles "$dem" 600 "$work/alps")" = 4
  "$tinlod" build "$dem" "$work/alps_whole.gpkg" -q
  # The outline moves within -outline_tolerance, a little otherwise than in the whole run
  # where the tiles keep the lines' outline cells (1.9e-4 measured at level 14).
  check "their union is conforming at every level, with the whole run's area (to 1e-3)" \
    union --whole "$work/alps_whole.gpkg" --max_area_change 1e-3 "$work"/alps_*_*.gpkg
  check "... 15 levels" test "$(grep -c 'conforming=yes' "$work/union.log")" = 15
  check "... level 0's area is the whole run's (to 1e-4)" /usr/bin/python3 -c "
import re,sys
line=[l for l in open('$work/union.log') if l.startswith('level  0')][0]
sys.exit(abs(float(re.search(r'area ratio ([0-9.]+)', line).group(1)) - 1) > 1e-4)"
  tail -3 "$work/union.log"
  # The two passes of tinlod tiles: the surveys' thresholds and line outline. Only the line
  # cells on a tile's outline stay, of those near the voids; the union is still conforming.
  failed=0
  for t in 0_0 0_1 1_0 1_1; do
    "$tinlod" build "$dem" "$work/alps_survey_$t.json" -tile_size 600 -tile "${t/_/,}" -q -survey || failed=$((failed + 1))
  done
  check "the 4 swiss_alps tiles are surveyed" test "$failed" = 0
  thresholds=$(cd "$here/../tiles" && /usr/bin/python3 -c "
import glob
from tinlodtiles.thresholds import read_survey, level_thresholds, as_option
print(as_option(level_thresholds([read_survey(p) for p in sorted(glob.glob('$work/alps_survey_*.json'))], 20, 5)))")
  line_outline_union "$work/alps_survey_*.json" "$work/alps_line_outline.txt"
  check "the swiss_alps surveys list line cells on the outline" test -s "$work/alps_line_outline.txt"
  failed=0
  for t in 0_0 0_1 1_0 1_1; do
    "$tinlod" build "$dem" "$work/alpsglob_$t.gpkg" -tile_size 600 -tile "${t/_/,}" -q -level_thresholds "$thresholds" \
      -line_outline "$work/alps_line_outline.txt" || failed=$((failed + 1))
  done
  check "the 4 swiss_alps tiles are built with the thresholds" test "$failed" = 0
  check "tiles of swiss_alps built so are conforming at every level, with the whole run's area (to 1e-3)" \
    union --whole "$work/alps_whole.gpkg" --max_area_change 1e-3 "$work"/alpsglob_*.gpkg
  check "... 15 levels" test "$(grep -c 'conforming=yes' "$work/union.log")" = 15
  tail -1 "$work/union.log"
else
  echo "SKIPPED (real DEM): $data/swiss_alps_N46E008.tif is absent; set TINLOD_TEST_DATA to run it"
fi
finish_checks tile_union
