#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The cost of writing a hierarchy GeoPackage, against the targets of issue 17, in one run:
#   - the whole `tinlod build` (defaults) against `ogr2ogr -f GPKG -lco SPATIAL_INDEX=NO`
#     copying just the triangles layer it wrote to a new file;
#   - bytes per stored triangle in the hierarchy file, indexes included (target <= 250),
#     and what each table and index pays, from SQLite's dbstat;
#   - peak memory of the build (GNU time's maximum resident set size);
#   - with HMM or HMM_SRC set, `tinlod insert` against hmm (bench/compare_hmm.sh).
# Times are printed, never asserted. Each command runs RUNS times (default 3) and the
# median is printed beside the minimum and maximum.
#
# Usage: bash bench/bench_gpkg_write.sh [DEM]   (default ../shared/data/alps_2x2_N46E007_N47E008.tif)
# Environment: TINLOD (binary, default build/core/tinlod), RUNS, TINLOD_ARGS (more build options).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
tinlod=${TINLOD:-$root/build/core/tinlod}
dem=${1:-${TINLOD_TEST_DATA:-$root/../shared/data}/alps_2x2_N46E007_N47E008.tif}
runs=${RUNS:-3}
[[ -f $dem ]] || { echo "skipped: no DEM at $dem"; exit 0; }
command -v /usr/bin/time >/dev/null || { echo "skipped: GNU time (/usr/bin/time) is needed"; exit 0; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# One run: prints "seconds peak_MB".
timed() {
  /usr/bin/time -f '%e %M' -o "$work/time" "$@" >/dev/null 2>"$work/err" || { cat "$work/err"; exit 1; }
  awk '{printf "%s %.0f\n", $1, $2 / 1024}' "$work/time"
}

# Median, minimum and maximum of column $1 of stdin.
summary() {
  sort -n -k"$1","$1" | awk -v c="$1" '{v[NR] = $c} END {printf "median %s (min %s, max %s)", v[int((NR + 1) / 2)], v[1], v[NR]}'
}

build_runs=$work/build.txt copy_runs=$work/copy.txt
for ((r = 0; r < runs; r++)); do
  rm -f "$work/h.gpkg" "$work/copy.gpkg"
  timed "$tinlod" build "$dem" "$work/h.gpkg" -q ${TINLOD_ARGS:-} >>"$build_runs"
  timed ogr2ogr -f GPKG -lco SPATIAL_INDEX=NO "$work/copy.gpkg" "$work/h.gpkg" triangles >>"$copy_runs"
done

triangles=$(sqlite3 "$work/h.gpkg" "SELECT count(*) FROM triangles")
bytes=$(stat -c %s "$work/h.gpkg")
echo "DEM: $dem ($triangles stored triangles, $((bytes / 1000000)) MB)"
echo "tinlod build, whole process, s:      $(summary 1 <"$build_runs")"
echo "ogr2ogr copy of its triangles, s:    $(summary 1 <"$copy_runs")"
echo "tinlod build peak memory, MB:        $(summary 2 <"$build_runs")"
echo "bytes per stored triangle:           $(awk -v b="$bytes" -v t="$triangles" 'BEGIN {printf "%.1f", b / t}') (target <= 250)"
echo "bytes per stored triangle, by table and index:"
sqlite3 "$work/h.gpkg" "SELECT printf('  %-32s %6.1f', name, sum(pgsize) * 1.0 / $triangles) FROM dbstat
                        GROUP BY name HAVING sum(pgsize) * 1.0 / $triangles >= 0.1 ORDER BY sum(pgsize) DESC"

# The insertion targets of the same issue, when hmm is at hand (see compare_hmm.sh).
if [[ -n ${HMM:-} || -n ${HMM_SRC:-} ]]; then
  echo
  bash "$root/bench/compare_hmm.sh"
fi
