#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The targets of issue 19, printed in one run (never asserted; the run fails only if a tool
# fails or a union is not conforming):
#  1. alps_2x2 cut into 4 and into 16 tiles, patagonia_coast into 16, built as tinlod tiles
#     does by default (a survey pass, one threshold per level, the build pass): whether every
#     level's union is conforming, and its accuracy (pooled RMSE and maximum error against
#     the DEM, from the tiles' levels tables) against a whole-raster run with the same
#     options, at the coarsest level and at equal vertex counts; then swiss_alps (voids) and
#     vancouver (sea) as 16 tiles, meghalaya_50m (clipped to a region) as 12 and mandakini_90m
#     (45 % nodata, tiles of no valid cell) as 20;
#  2. the peak memory of one tile of 4096 x 4096 cells (-tile_size 4095, tile 0,0 of a synthetic 8193 x 8193 DEM),
#     to build it and to measure it (tinlod accuracy on that DEM as 4 such tiles, with the raster);
#  3. tinlod accuracy on a catalogue (a tile at a time) against the same on the whole run's
#     hierarchy: time, peak memory, figures (alps_2x2 and patagonia_coast as 16 tiles);
#  4. with tinlod-tiles (Dask): cells per second on 1 and on 2 workers (alps_2x2, 16 tiles);
#  5. under -method error -max_error 25, the rounds that agree the border lines, and the
#     union against a whole run (alps_2x2 as 4 and 16 tiles, patagonia_coast as 16);
#  6. with tinlod tiles -exact_stop: the union's coarsest level against a whole run's count
#     (alps_2x2 as 4 and 16 tiles, patagonia_coast as 16);
#  7. (part driver) the driver's memory and time to set the thresholds of a national job:
#     alps_2x2's 16 surveys (tiles of 600) read again and again as DRIVER_TILES tiles' (default
#     5960), histograms in a SurveyStore as tinlod-tiles does, and held in memory as before.
# Usage: bash bench/tiles_bench.sh [parts...]
#   (parts: accuracy memory measure throughput throughput_large bounded exact_stop driver;
#   default all but throughput_large and driver)
# Environment: TINLOD (default build/core/tinlod), TINLOD_TILES (default build/tiles/tinlod-tiles),
#   WORK (default build/tiles-bench: outputs go there), TINLOD_TEST_DATA (default ../shared/data),
#   THROUGHPUT_ROUNDS (default 3: rounds of the three throughput runs, taken in turn),
#   DRIVER_TILES (default 5960: the tiles of part driver).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
tinlod=${TINLOD:-$root/build/core/tinlod}
tiles=${TINLOD_TILES:-$root/build/tiles/tinlod-tiles}
data=${TINLOD_TEST_DATA:-$root/../shared/data}
work=${WORK:-$root/build/tiles-bench}
parts=${*:-accuracy memory measure throughput bounded exact_stop}
mkdir -p "$work"

# tile_grid DEM SIZE: "across down"
tile_grid() {
  local w h
  read -r w h < <(gdalinfo "$1" | sed -n 's/^Size is \([0-9]*\), \([0-9]*\)/\1 \2/p')
  echo "$(( (w - 2) / $2 + 1 )) $(( (h - 2) / $2 + 1 ))"
}

accuracy_case() {  # NAME DEM SIZE
  local name=$1 dem=$2 size=$3 across down
  read -r across down < <(tile_grid "$dem" "$size")
  echo "== $name: $((across * down)) tiles of $size cells"
  [[ -f $work/$name.whole.gpkg ]] || /usr/bin/time -f "whole run: %e s, peak %M KB" "$tinlod" build "$dem" "$work/$name.whole.gpkg" -q
  local start=$SECONDS peak=0 thresholds status
  rm -f "$work/$name".survey_*.json "$work/$name".tile_*.gpkg
  # The two passes of tinlod tiles' default -selection global, one tile after another. A
  # tile without valid cells writes nothing (exit 3), as tinlod tiles records it empty.
  for ((c = 0; c < across; c++)); do
    for ((r = 0; r < down; r++)); do
      status=0
      "$tinlod" build "$dem" "$work/$name.survey_${c}_${r}.json" -tile_size "$size" -tile "$c,$r" -q -overwrite -survey \
        2> /dev/null || status=$?
      (( status == 0 || status == 3 )) || { echo "tile $c,$r: the survey failed (exit $status)"; return 1; }
    done
  done
  thresholds=$(cd "$root/tiles" && /usr/bin/python3 -c "
import glob
from tinlodtiles.thresholds import read_survey, level_thresholds, as_option
print(as_option(level_thresholds([read_survey(p) for p in sorted(glob.glob('$work/$name.survey_*.json'))], 20, 5)))")
  # The lines' outline cells the tiles' surveys list: only these of the line cells near nodata stay.
  (cd "$root/tiles" && /usr/bin/python3 -c "
import glob
from tinlodtiles import cell_file, line_outline
cell_file.write_cells('$work/$name.line_outline.txt', line_outline.gather(glob.glob('$work/$name.survey_*.json')))")
  echo "survey pass: $((SECONDS - start)) s, $(wc -l < "$work/$name.line_outline.txt") line cells on the outline"
  for ((c = 0; c < across; c++)); do
    for ((r = 0; r < down; r++)); do
      [[ -f $work/$name.survey_${c}_${r}.json ]] || continue  # empty
      /usr/bin/time -o "$work/time.txt" -f "%M" "$tinlod" build "$dem" "$work/$name.tile_${c}_${r}.gpkg" \
        -tile_size "$size" -tile "$c,$r" -q -overwrite -level_thresholds "$thresholds" -line_outline "$work/$name.line_outline.txt"
      peak=$(( $(cat "$work/time.txt") > peak ? $(cat "$work/time.txt") : peak ))
    done
  done
  echo "both passes, tiles one after another: $((SECONDS - start)) s, largest peak $((peak / 1024)) MiB"
  /usr/bin/python3 "$root/tests/tile_union.py" --whole "$work/$name.whole.gpkg" --json "$work/$name.json" \
    "$work/$name".tile_*.gpkg > "$work/$name.union.txt" || { cat "$work/$name.union.txt"; return 1; }
  tail -1 "$work/$name.union.txt"
  /usr/bin/python3 - "$work/$name.json" << 'PY'
import json, sys
rows = json.load(open(sys.argv[1]))
last = rows[-1]
def ratio(a, b): return a / b if b else float("nan")
print(f"coarsest level {last['level']}: tiles {last['vertices']} vertices, RMSE {last['rmse']:.3f} m, max {last['max_error']:.2f} m;"
      f" whole {last['whole_vertices']} vertices, RMSE {last['whole_rmse']:.3f} m, max {last['whole_max_error']:.2f} m;"
      f" RMSE ratio {ratio(last['rmse'], last['whole_rmse']):.4f}, max ratio {ratio(last['max_error'], last['whole_max_error']):.4f}")
# At equal vertex counts: the whole run's RMSE interpolated (log-log) at each tile level's count.
import math
whole = sorted((r['whole_vertices'], r['whole_rmse'], r['whole_max_error']) for r in rows)
worst = 0
for r in rows:
    v = r['vertices']
    for (v0, e0, m0), (v1, e1, m1) in zip(whole, whole[1:]):
        if v0 <= v <= v1 and v1 > v0 and e0 > 0 and e1 > 0:
            t = (math.log(v) - math.log(v0)) / (math.log(v1) - math.log(v0))
            e = math.exp(math.log(e0) + t * (math.log(e1) - math.log(e0)))
            worst = max(worst, r['rmse'] / e)
            print(f"  level {r['level']:2d}: {v} vertices, RMSE {r['rmse']:.3f} m; whole at that count {e:.3f} m (ratio {r['rmse'] / e:.4f})")
            break
print(f"largest RMSE ratio at equal vertex counts: {worst:.4f} (target 1.02)")
PY
}

memory_case() {
  local dem=$work/synthetic_8193.tif
  [[ -f $dem ]] || "$tinlod" makedem "$dem" -size 8193 8193 -cell 10 -q
  echo "== one tile of 4096 x 4096 cells (-tile_size 4095 and the shared line) of a synthetic 8193 x 8193 DEM"
  /usr/bin/time -f "tile 0,0: %e s, peak %M KB (target: 1 GB)" "$tinlod" build "$dem" "$work/big_tile.gpkg" \
    -tile_size 4095 -tile 0,0 -q -overwrite
  # As each of 2 Dask workers runs it: one thread.
  TINLOD_THREADS=1 /usr/bin/time -f "tile 0,0 with one thread: %e s, peak %M KB (target: 1 GB)" "$tinlod" build "$dem" \
    "$work/big_tile.gpkg" -tile_size 4095 -tile 0,0 -q -overwrite
  TINLOD_THREADS=1 /usr/bin/time -f "its survey with one thread: %e s, peak %M KB (target: 1 GB)" "$tinlod" build "$dem" \
    "$work/big_tile.json" -tile_size 4095 -tile 0,0 -survey -q -overwrite
  if ! /usr/bin/python3 -c "import distributed" 2> /dev/null || [[ ! -x $tiles ]]; then
    echo "== measuring 4096 x 4096 tiles: SKIPPED (python3-distributed or $tiles absent)"
    return 0
  fi
  echo "== tinlod accuracy -reference dem on the synthetic 8193 x 8193 DEM as 4 tiles of 4096 x 4096 cells, a tile at a time"
  [[ -f $work/syn4.gpkg ]] || "$tiles" "$dem" "$work/syn4.gpkg" -tile_size 4095 -workers 2 -tinlod "$tinlod" -q
  /usr/bin/time -f "with the raster: %e s, peak %M KB (target: 1 GB)" "$tinlod" accuracy "$dem" "$work/syn4.gpkg" \
    -reference dem -report "$work/syn4.json" -accuracy "$work/syn4.tif" -overwrite -q
}

# tinlod accuracy on a catalogue, a tile at a time, against the same on the whole run's
# hierarchy (one file, all in memory): time and peak memory, and the report's figures.
measure_case() {  # NAME DEM SIZE
  local name=$1 dem=$2 size=$3
  if ! /usr/bin/python3 -c "import distributed" 2> /dev/null || [[ ! -x $tiles ]]; then
    echo "== measure $name: SKIPPED (python3-distributed or $tiles absent)"
    return 0
  fi
  echo "== tinlod accuracy -reference dem on $name: a catalogue of tiles of $size cells against the whole run"
  [[ -f $work/$name.measure.gpkg ]] || "$tiles" "$dem" "$work/$name.measure.gpkg" -tile_size "$size" -workers 2 -tinlod "$tinlod" -q
  [[ -f $work/$name.whole.gpkg ]] || "$tinlod" build "$dem" "$work/$name.whole.gpkg" -q
  /usr/bin/time -f "catalogue, tile by tile: %e s, peak %M KB" "$tinlod" accuracy "$dem" "$work/$name.measure.gpkg" \
    -reference dem -report "$work/$name.measure.json" -accuracy "$work/$name.measure.tif" -overwrite -q
  /usr/bin/time -f "whole run's hierarchy: %e s, peak %M KB" "$tinlod" accuracy "$dem" "$work/$name.whole.gpkg" \
    -reference dem -report "$work/$name.whole_measure.json" -accuracy "$work/$name.whole_measure.tif" -overwrite -q
  /usr/bin/python3 - "$work/$name.measure.json" "$work/$name.whole_measure.json" << 'PY'
import json, sys
tiles, whole = (json.load(open(p))["runs"][0]["levels"] for p in sys.argv[1:])
for a, b in ((tiles[0], whole[0]), (tiles[-1], whole[-1])):
    print(f"  level {a['level']}: catalogue {a['test_points']} points, RMSE {a['rmse_m']:.4f} m, "
          f"mean curvature r {a['variables']['mean_curvature']['r']:.4f}; "
          f"whole run {b['test_points']} points, RMSE {b['rmse_m']:.4f} m, r {b['variables']['mean_curvature']['r']:.4f}")
PY
}

# Under -method error -max_error 25, tinlod-tiles (Dask, 2 workers) agrees the border lines
# in rounds: the rounds, time, kept line cells, whether every level's union is conforming,
# and the coarsest level against a whole-raster run with the same options.
bounded_case() {  # NAME DEM SIZE
  local name=$1 dem=$2 size=$3
  if ! /usr/bin/python3 -c "import distributed" 2> /dev/null || [[ ! -x $tiles ]]; then
    echo "== bounded $name: SKIPPED (python3-distributed or $tiles absent)"
    return 0
  fi
  local options=(-method error -max_error 25)
  echo "== $name under ${options[*]}: tiles of $size cells, border lines agreed in rounds"
  [[ -f $work/$name.bounded_whole.gpkg ]] || /usr/bin/time -f "whole run: %e s, peak %M KB" \
    "$tinlod" build "$dem" "$work/$name.bounded_whole.gpkg" -q "${options[@]}"
  rm -rf "$work/$name.bounded.gpkg" "$work/$name.bounded_tiles" "$work/$name.bounded_levels"
  local start=$SECONDS
  "$tiles" "$dem" "$work/$name.bounded.gpkg" -tile_size "$size" -workers 2 -tinlod "$tinlod" -- "${options[@]}" \
    > "$work/$name.bounded.log"
  echo "tinlod-tiles: $((SECONDS - start)) s, $(grep -c '^border agreement' "$work/$name.bounded.log" | \
    awk '{print $1 + 1}') rounds, $(wc -l < "$work/$name.bounded_tiles/border_keep.txt") line cells kept"
  /usr/bin/python3 "$root/tests/tile_union.py" --whole "$work/$name.bounded_whole.gpkg" --json "$work/$name.bounded.json" \
    "$work/$name.bounded_tiles"/tile_*.gpkg > "$work/$name.bounded.union.txt" || { cat "$work/$name.bounded.union.txt"; return 1; }
  tail -1 "$work/$name.bounded.union.txt"
  /usr/bin/python3 - "$work/$name.bounded.json" << 'PY'
import json, sys
rows = json.load(open(sys.argv[1]))
both = [r for r in rows if "whole_vertices" in r]  # a bounded whole run may stop before the tiles' last level
for r in (both[-1], rows[-1]):
    whole = (f"; whole run {r['whole_vertices']} vertices, RMSE {r['whole_rmse']:.3f} m, max {r['whole_max_error']:.2f} m"
             if "whole_vertices" in r else " (the whole run stopped before)")
    print(f"level {r['level']}: tiles {r['vertices']} vertices, RMSE {r['rmse']:.3f} m, max {r['max_error']:.2f} m{whole}")
PY
}

throughput_case() {  # [DEM TILE_SIZE LABEL]: by default alps_2x2 as 16 tiles of 600 cells
  if ! /usr/bin/python3 -c "import distributed" 2> /dev/null || [[ ! -x $tiles ]]; then
    echo "== throughput: SKIPPED (python3-distributed or $tiles absent)"
    return 0
  fi
  local dem=${1:-$data/alps_2x2_N46E007_N47E008.tif} size=${2:-600} label=${3:-alps_2x2} rounds=${THROUGHPUT_ROUNDS:-3}
  local w h cells
  read -r w h < <(gdalinfo "$dem" | sed -n 's/^Size is \([0-9]*\), \([0-9]*\)/\1 \2/p')
  cells=$((w * h))
  echo "== throughput: $label ($cells cells) as $(tile_grid "$dem" "$size" | awk '{print $1 * $2}') tiles of $size cells with tinlod-tiles, $rounds rounds"
  run_workers() {  # N [TINLOD_THREADS]: seconds of a whole run (both passes)
    rm -rf "$work/cat.gpkg" "$work/cat_tiles" "$work/cat_levels"
    local start
    start=$(date +%s.%N)
    TINLOD_THREADS=${2:-} "$tiles" "$dem" "$work/cat.gpkg" -tile_size "$size" -workers "$1" -tinlod "$tinlod" -q
    echo "$(date +%s.%N) - $start" | bc
  }
  # What the machine itself gives: two CPU-bound processes at once against one (shared
  # virtual cores may give far less than 2x, whatever the program).
  local spin='s = 0
for i in range(20_000_000): s += i * i'
  # The three runs of a round are taken in turn, so that the machine's drift over minutes
  # falls on all three; the medians over the rounds are compared.
  local t1=() t1single=() t2=() one two round
  for ((round = 1; round <= rounds; ++round)); do
    one=$( { /usr/bin/time -f "%e" /usr/bin/python3 -c "$spin"; } 2>&1 )
    two=$( { /usr/bin/time -f "%e" bash -c "/usr/bin/python3 -c '$spin' & /usr/bin/python3 -c '$spin'; wait"; } 2>&1 )
    t1+=("$(run_workers 1)") t1single+=("$(run_workers 1 1)") t2+=("$(run_workers 2)")
    printf "round %d: the machine %sx (two CPU-bound processes against one); 1 worker (tinlod on both cores) %.2f s, " \
      "$round" "$(echo "scale=3; 2 * $one / $two" | bc)" "${t1[-1]}"
    printf "1 worker of 1 thread (TINLOD_THREADS=1) %.2f s, 2 workers (1 thread each) %.2f s\n" "${t1single[-1]}" "${t2[-1]}"
  done
  /usr/bin/python3 - "${t1[*]}" "${t1single[*]}" "${t2[*]}" "$cells" << 'PY'
import statistics, sys
t1, t1single, t2 = (statistics.median(map(float, a.split())) for a in sys.argv[1:4])
cells = int(sys.argv[4])
print(f"medians: 1 worker {t1:.2f} s ({cells / t1:.0f} cells/s), 1 single-threaded worker {t1single:.2f} s "
      f"({cells / t1single:.0f} cells/s), 2 workers {t2:.2f} s ({cells / t2:.0f} cells/s)")
print(f"speed-up of 2 workers over 1: {t1 / t2:.3f}x; over 1 single-threaded worker: {t1single / t2:.3f}x (target 1.7x)")
PY
}

driver_case() {
  local dem=$data/alps_2x2_N46E007_N47E008.tif status across down c r
  read -r across down < <(tile_grid "$dem" 600)
  for ((c = 0; c < across; c++)); do
    for ((r = 0; r < down; r++)); do
      [[ -f $work/driver.survey_${c}_${r}.json ]] && continue
      status=0
      "$tinlod" build "$dem" "$work/driver.survey_${c}_${r}.json" -tile_size 600 -tile "$c,$r" -q -survey 2> /dev/null || status=$?
      (( status == 0 || status == 3 )) || { echo "tile $c,$r: the survey failed (exit $status)"; return 1; }
    done
  done
  echo "== the driver's thresholds for ${DRIVER_TILES:-5960} tiles (alps_2x2's 16 surveys of 600-cell tiles, again and again)"
  for mode in "" -in_memory; do
    /usr/bin/python3 "$root/bench/driver_surveys.py" "$root/tiles" "${DRIVER_TILES:-5960}" "$work"/driver.survey_*.json $mode | head -1
  done
}

# tinlod tiles -exact_stop (a second survey pass sets the level that reaches the stop): the
# union's coarsest level against a whole run's count, and the accuracy at equal counts.
exact_stop_case() {  # NAME DEM SIZE
  local name=$1 dem=$2 size=$3
  if ! /usr/bin/python3 -c "import distributed" 2> /dev/null || [[ ! -x $tiles ]]; then
    echo "== $name with -exact_stop: SKIPPED (python3-distributed or $tiles absent)"
    return 0
  fi
  [[ -f $work/$name.whole.gpkg ]] || "$tinlod" build "$dem" "$work/$name.whole.gpkg" -q
  rm -rf "$work/$name.exact.gpkg" "$work/$name.exact_tiles" "$work/$name.exact_levels"
  local start=$SECONDS
  "$tiles" "$dem" "$work/$name.exact.gpkg" -tile_size "$size" -exact_stop -tinlod "$tinlod" -q
  echo "== $name with -exact_stop: $((SECONDS - start)) s on $(nproc) workers"
  /usr/bin/python3 "$root/tests/tile_union.py" --whole "$work/$name.whole.gpkg" --json "$work/$name.exact.json" \
    "$work/$name.exact_tiles"/tile_*.gpkg > "$work/$name.exact.union.txt" || { cat "$work/$name.exact.union.txt"; return 1; }
  tail -1 "$work/$name.exact.union.txt"
  /usr/bin/python3 - "$work/$name.exact.json" << 'PY'
import json, math, sys
rows = json.load(open(sys.argv[1]))
whole = sorted((r['whole_vertices'], r['whole_rmse']) for r in rows)
worst = 0
for r in rows:
    for (v0, e0), (v1, e1) in zip(whole, whole[1:]):
        if v0 <= r['vertices'] <= v1 and v1 > v0:
            t = (math.log(r['vertices']) - math.log(v0)) / (math.log(v1) - math.log(v0))
            worst = max(worst, r['rmse'] / math.exp(math.log(e0) + t * (math.log(e1) - math.log(e0))))
            break
last = rows[-1]
print(f"coarsest level {last['level']}: {last['vertices']} vertices against a whole run's {last['whole_vertices']}"
      f" ({100 * (last['vertices'] / last['whole_vertices'] - 1):+.1f} %); largest RMSE ratio at equal vertex counts {worst:.4f}")
PY
}

for part in $parts; do
  case $part in
    accuracy)
      accuracy_case alps4 "$data/alps_2x2_N46E007_N47E008.tif" 1200
      accuracy_case alps16 "$data/alps_2x2_N46E007_N47E008.tif" 600
      accuracy_case patagonia16 "$data/patagonia_coast_S46W066.tif" 900
      # Beyond the issue's cases: voids (swiss_alps, 7 % nodata), sea (vancouver), a DEM
      # clipped to a region (meghalaya_50m, 9 % nodata round it; mandakini_90m, 45 %, with
      # tiles of no valid cell).
      accuracy_case swiss16 "$data/swiss_alps_N46E008.tif" 300
      accuracy_case vancouver16 "$data/vancouver_N49W123.tif" 300
      accuracy_case meghalaya12 "$data/meghalaya_50m.tif" 450
      accuracy_case mandakini20 "$data/mandakini_90m.tif" 150
      ;;
    memory) memory_case ;;
    measure)
      measure_case alps16 "$data/alps_2x2_N46E007_N47E008.tif" 600
      measure_case patagonia16 "$data/patagonia_coast_S46W066.tif" 900
      ;;
    throughput) throughput_case ;;
    throughput_large)
      # A job 4 times alps_2x2's, in tiles 4 times as large: the driver's fixed costs (Dask's
      # start, the catalogue) weigh less, as they would in a national job.
      [[ -f $work/synthetic_4800.tif ]] || "$tinlod" makedem "$work/synthetic_4800.tif" -size 4800 4800 -q
      throughput_case "$work/synthetic_4800.tif" 1200 "makedem 4800 x 4800"
      ;;
    exact_stop)
      exact_stop_case alps4 "$data/alps_2x2_N46E007_N47E008.tif" 1200
      exact_stop_case alps16 "$data/alps_2x2_N46E007_N47E008.tif" 600
      exact_stop_case patagonia16 "$data/patagonia_coast_S46W066.tif" 900
      ;;
    bounded)
      bounded_case alps4 "$data/alps_2x2_N46E007_N47E008.tif" 1200
      bounded_case alps16 "$data/alps_2x2_N46E007_N47E008.tif" 600
      bounded_case patagonia16 "$data/patagonia_coast_S46W066.tif" 900
      ;;
    driver) driver_case ;;
    *) echo "unknown part $part" >&2; exit 2 ;;
  esac
done
