#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Compares 'tinlod insert' with delatin (Mapbox's greedy insertion, npm delatin@0.2.0) on
# the same DEMs and tolerances: vertex counts, insertion times, and each tool's maximum
# error measured independently at every cell. Fails if tinlod needs more than 1% more
# vertices than delatin or misses the tolerance; times are printed, never asserted.
#
# Usage: bash bench/compare_delatin.sh [DEM ...]
#   DEMs must have no nodata cells (delatin has no notion of them). Default: three of
#   ../shared/data (or $TINLOD_TEST_DATA) with none: alps_2x2_N46E007_N47E008.tif (5.8 M
#   cells, geographic), big_tujunga_30m.tif (0.8 M, UTM), dead_sea_N31E035.tif (1.4 M,
#   geographic). Environment: TOLERANCES="m ..." (metres, for every DEM; default per DEM
#   below), TINLOD (binary, default build/core/tinlod), TINLOD_ARGS (more options of
#   tinlod insert, e.g. "-delaunay grid" for delatin's criterion), BUILD_DIR (default
#   build/delatin-bench: delatin is installed, and the DEMs converted, there).
#
# On a geographic DEM the two TINs differ by more than tie-breaking: tinlod keeps its TIN
# Delaunay in metres (UTM) by default, delatin in pixel units, and the pixels are not
# square there; TINLOD_ARGS="-delaunay grid" compares like with like.
# Times: delatin's is run(tol) alone; tinlod's also covers its inserter's set-up (the
# first scan of the starting triangles, which delatin does in its constructor).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
tinlod=${TINLOD:-$root/build/core/tinlod}
build=${BUILD_DIR:-$root/build/delatin-bench}
data=${TINLOD_TEST_DATA:-$root/../shared/data}

if ! command -v node >/dev/null || ! command -v npm >/dev/null; then
  echo "skipped: node and npm are needed to run delatin"; exit 0
fi
[[ -x $tinlod ]] || { echo "error: no tinlod binary at $tinlod (build first, or set TINLOD)" >&2; exit 1; }

if (($# == 0)); then
  for f in alps_2x2_N46E007_N47E008.tif big_tujunga_30m.tif dead_sea_N31E035.tif; do
    [[ -f $data/$f ]] && set -- "$@" "$data/$f"
  done
  (($# > 0)) || { echo "skipped: no DEMs given and none found in $data (set TINLOD_TEST_DATA)"; exit 0; }
fi

# Default tolerances per DEM: delatin's vertices are about 1%, 0.5% and 0.1% of the cells.
default_tolerances() {
  case $1 in
    alps_2x2_N46E007_N47E008) echo "100 150 400" ;;
    big_tujunga_30m) echo "40 65 160" ;;
    dead_sea_N31E035) echo "65 90 190" ;;
    *) echo "10 20 50" ;;
  esac
}

# delatin goes into the build folder, never the source tree.
mkdir -p "$build"
cp "$root/bench/delatin/package.json" "$root/bench/delatin/run.mjs" "$build/"
if ! (cd "$build" && npm install --no-audit --no-fund >"$build/npm.log" 2>&1); then
  echo "skipped: 'npm install' of delatin failed in $build (see $build/npm.log)"; exit 0
fi

field() { sed -E "s/.*\"$1\":([^,}]*).*/\1/" <<<"$2"; } # a number from a flat JSON line
failed=()
fmt="%-24s %6s %9s %9s %7s %8s %8s %7s %10s %10s %8s\n"
# shellcheck disable=SC2059 # the format is ours, shared with awk below
printf "$fmt" DEM tol dl_verts tl_verts v_ratio dl_s tl_s t_ratio dl_maxerr tl_maxerr tl_rmse
for dem in "$@"; do
  name=$(basename "${dem%.*}")
  grid=$build/$name.f32
  rm -f "$grid.aux.xml" # stale statistics would be trusted by gdalinfo -stats
  gdal_translate -q -of ENVI -ot Float32 "$dem" "$grid"
  # The ENVI header holds the size; -stats reads every cell (its .aux.xml stays in $build).
  w=$(awk '$1 == "samples" {print $3}' "$build/$name.hdr")
  h=$(awk '$1 == "lines" {print $3}' "$build/$name.hdr")
  valid=$(gdalinfo -stats "$grid" | sed -nE 's/.*STATISTICS_VALID_PERCENT=([0-9.]+).*/\1/p')
  if [[ -n $valid && $valid != 100 ]]; then
    echo "error: $dem has nodata cells ($valid% valid); delatin cannot be compared on it" >&2; exit 1
  fi
  read -r -a tolerances <<<"${TOLERANCES:-$(default_tolerances "$name")}"
  mapfile -t results < <(node "$build/run.mjs" "$grid" "$w" "$h" "${tolerances[@]}")
  ((${#results[@]} == ${#tolerances[@]})) || { echo "error: delatin failed on $dem" >&2; exit 1; }
  for line in "${results[@]}"; do
    tol=$(field tol "$line")
    (($(field uncovered "$line") == 0)) || echo "warning: delatin's TIN misses cells of $name" >&2
    gpkg=$build/$name.gpkg
    rm -f "$gpkg"
    # Without -q: the two summary lines on stdout are what is parsed; progress goes to stderr.
    # shellcheck disable=SC2086 # TINLOD_ARGS is a list of options
    if ! out=$("$tinlod" insert "$dem" "$gpkg" -max_error "$tol" -overwrite ${TINLOD_ARGS:-} 2>"$build/tinlod.log" </dev/null); then
      cat "$build/tinlod.log" >&2; echo "error: tinlod insert failed on $dem at $tol m" >&2; exit 1
    fi
    tv=$(sed -nE 's/^Wrote ([0-9]+) vertices .*/\1/p' <<<"$out")
    ts=$(sed -nE 's/^Wrote .* insertion ([0-9.eE+-]+) s\).*/\1/p' <<<"$out")
    read -r te tr cells < <(sed -nE 's/^Maximum error ([0-9.eE+-]+) m, RMSE ([0-9.eE+-]+) m over ([0-9]+) cells.*/\1 \2 \3/p' <<<"$out") || true
    [[ -n $tv && -n $ts && -n $cells ]] || { echo "error: cannot parse tinlod's output: $out" >&2; exit 1; }
    # awk does the floating-point work: one table row, then the checks, whose failures
    # are printed under the row; the exit status says whether any failed.
    if ! awk -v dem="$name" -v tol="$tol" -v dv="$(field vertices "$line")" -v tv="$tv" \
        -v ds="$(field seconds "$line")" -v ts="$ts" -v de="$(field measuredMaxError "$line")" \
        -v te="$te" -v tr="$tr" -v cells="$cells" -v n=$((w * h)) -v fmt="$fmt" 'BEGIN {
      printf fmt, dem, tol, dv, tv, sprintf("%.4f", tv / dv), sprintf("%.3f", ds),
        sprintf("%.3f", ts), sprintf("%.3f", ts / ds), sprintf("%.6g", de), sprintf("%.6g", te),
        sprintf("%.4g", tr)
      if (tv > 1.01 * dv) { printf "  FAIL: tinlod has %.2f%% more vertices than delatin (limit 1%%)\n", 100 * (tv / dv - 1); bad = 1 }
      if (te > tol + 1e-6) { printf "  FAIL: tinlod measured max error %s m > tolerance %s m\n", te, tol; bad = 1 }
      # Catches the few nodata cells a rounded VALID_PERCENT of 100 hides.
      if (cells != n) { printf "  FAIL: tinlod measured %d cells, the grid has %d\n", cells, n; bad = 1 }
      exit bad
    }'; then
      failed+=("$name at $tol m")
    fi
  done
done
if ((${#failed[@]})); then
  printf "FAILED: %s\n" "${failed[@]}"; exit 1
fi
echo "OK: tinlod within 1% of delatin's vertex count and within the tolerance on every row"
