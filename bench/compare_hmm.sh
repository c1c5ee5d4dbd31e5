#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Compares 'tinlod insert' with hmm (fogleman/hmm: Garland and Heckbert's greedy insertion,
# 16-bit PNG in, binary STL out) as a user meets them: whole processes, from the DEM (for
# hmm, its PNG) to the mesh file, at the same tolerance in metres. Prints, per DEM and
# tolerance: each tool's whole-process wall time (median of RUNS runs, taken in turn so that
# drift of the machine's speed hits both), the ratio, each tool's own insertion-loop time,
# vertex and triangle counts, and hmm's maximum error measured in metres against the DEM.
# Times are printed, never asserted; the run fails only if a tool fails.
#
# Usage: bash bench/compare_hmm.sh [DEM:TOLERANCE ...]
#   Default: alps_2x2_N46E007_N47E008.tif:20 and gabilan_mesa_lidar1m.tif:0.5 from
#   ../shared/data (or $TINLOD_TEST_DATA), the targets of issue 17. DEMs must have no
#   nodata cells (hmm has no notion of them).
# Environment: HMM (hmm's binary), else HMM_SRC (a checkout of fogleman/hmm, built by its
#   Makefile in a copy under BUILD_DIR; needs libglm-dev); neither: skipped. RUNS (default
#   5), TINLOD (default build/core/tinlod), BUILD_DIR (default build/hmm-bench: the PNGs,
#   meshes and hmm's copy go there, never into the source tree).
#
# hmm's units (src/heightmap.cpp, src/triangulator.cpp): it reads a PNG's 16-bit values v as
# heights v / 65535 and compares errors in those units, so with the DEM scaled linearly from
# [min, max] to [0, 65535], -e is the tolerance divided by (max - min). -z (z scale in pixel
# widths) only scales the STL's z: it is set to (max - min) / cell size for a mesh of the
# right shape. hmm works on heights rounded to 1/65535 of the range (printed as 'quantum'),
# so its error measured against the DEM may pass the tolerance by up to one quantum. It
# keeps its TIN Delaunay on the square pixel grid, as 'tinlod insert -delaunay grid' does,
# unlike tinlod's default on a geographic DEM.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
tinlod=${TINLOD:-$root/build/core/tinlod}
build=${BUILD_DIR:-$root/build/hmm-bench}
data=${TINLOD_TEST_DATA:-$root/../shared/data}
runs=${RUNS:-5}

[[ -x $tinlod ]] || { echo "error: no tinlod binary at $tinlod (build first, or set TINLOD)" >&2; exit 1; }
mkdir -p "$build"

# hmm: the given binary, or built from the given checkout in a copy of its own.
locate_hmm() {
  if [[ -n ${HMM:-} ]]; then
    [[ -x $HMM ]] || { echo "error: HMM=$HMM is not an executable" >&2; exit 1; }
    echo "$HMM"; return
  fi
  [[ -n ${HMM_SRC:-} && -f ${HMM_SRC:-}/Makefile ]] || return 0
  rm -rf "$build/hmm-src"
  cp -r "$HMM_SRC" "$build/hmm-src"
  if ! make -C "$build/hmm-src" >"$build/hmm-make.log" 2>&1; then
    echo "skipped: building hmm failed (see $build/hmm-make.log; it needs libglm-dev)" >&2; return 0
  fi
  echo "$build/hmm-src/bin/release/hmm"
}
hmm=$(locate_hmm)
if [[ -z $hmm ]]; then
  echo "skipped: set HMM to hmm's binary or HMM_SRC to a checkout of github.com/fogleman/hmm"; exit 0
fi

if (($# == 0)); then
  for pair in alps_2x2_N46E007_N47E008.tif:20 gabilan_mesa_lidar1m.tif:0.5; do
    [[ -f $data/${pair%:*} ]] && set -- "$@" "$data/$pair"
  done
  (($# > 0)) || { echo "skipped: no DEMs given and none found in $data (set TINLOD_TEST_DATA)"; exit 0; }
fi

now() { date +%s.%N; }
# The median of the numbers on standard input.
median() { sort -g | awk '{v[NR] = $1} END {print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }

# Runs the two commands in turn, RUNS times each after one warm-up of each; wall seconds of
# each run go to $build/times.a and times.b, the last run's output to out.a and out.b.
time_pair() {
  local -n a=$1 b=$2
  "${a[@]}" >"$build/out.a" 2>&1 </dev/null || { cat "$build/out.a" >&2; echo "error: ${a[*]} failed" >&2; exit 1; }
  "${b[@]}" >"$build/out.b" 2>&1 </dev/null || { cat "$build/out.b" >&2; echo "error: ${b[*]} failed" >&2; exit 1; }
  : >"$build/times.a"; : >"$build/times.b"
  local i t0
  for ((i = 0; i < runs; ++i)); do
    t0=$(now); "${a[@]}" >"$build/out.a" 2>&1 </dev/null; awk -v s="$t0" -v e="$(now)" 'BEGIN {print e - s}' >>"$build/times.a"
    t0=$(now); "${b[@]}" >"$build/out.b" 2>&1 </dev/null; awk -v s="$t0" -v e="$(now)" 'BEGIN {print e - s}' >>"$build/times.b"
  done
}

# hmm's maximum error in metres at every cell: its STL read back, interpolated on the DEM's
# grid and compared with the DEM's own heights. Needs Python with numpy, matplotlib and GDAL's
# bindings; prints "n/a" without them.
measure_hmm() { # STL DEM
  /usr/bin/python3 - "$@" <<'EOF' 2>/dev/null || echo n/a
import sys
import numpy as np
from matplotlib.tri import Triangulation, LinearTriInterpolator
from osgeo import gdal
stl, dem = sys.argv[1], sys.argv[2]
ds = gdal.Open(dem)  # kept: a band outliving its dataset crashes
z = ds.GetRasterBand(1).ReadAsArray().astype(np.float64)
h, w = z.shape
tri = np.fromfile(stl, dtype=np.dtype([("n", "<f4", 3), ("v", "<f4", (3, 3)), ("a", "<u2")]), offset=84)["v"]
pts, idx = np.unique(tri.reshape(-1, 3), axis=0, return_inverse=True)
# hmm writes x = column, y = (height - 1) - row, z = normalised height * zscale.
heights = z[(h - 1) - pts[:, 1].astype(int), pts[:, 0].astype(int)]
mesh = LinearTriInterpolator(Triangulation(pts[:, 0], pts[:, 1], idx.reshape(-1, 3)), heights)
cols, rows = np.meshgrid(np.arange(w, dtype=float), np.arange(h, dtype=float))
est = mesh(cols, (h - 1) - rows)
print("%.4f" % np.nanmax(np.abs(est - z)))
EOF
}

fmt="%-26s %6s %9s %9s %7s %9s %9s %9s %9s %9s %9s %8s\n"
# shellcheck disable=SC2059 # the format is ours
printf "$fmt" DEM tol hmm_s tl_s ratio hmm_loop tl_loop hmm_verts tl_verts hmm_tris tl_tris hmm_err
for arg in "$@"; do
  dem=${arg%:*} tol=${arg##*:}
  [[ $arg == *:* && -f $dem ]] || { echo "error: give DEM:TOLERANCE, not '$arg'" >&2; exit 1; }
  name=$(basename "${dem%.*}")
  # A copy in the build folder: gdalinfo -stats writes its .aux.xml beside the file it reads.
  grid=$build/$name.tif
  rm -f "$grid.aux.xml"
  gdal_translate -q -ot Float32 "$dem" "$grid"
  info=$(gdalinfo -stats "$grid")
  valid=$(sed -nE 's/.*STATISTICS_VALID_PERCENT=([0-9.]+).*/\1/p' <<<"$info")
  if [[ -n $valid && $valid != 100 ]]; then
    echo "error: $dem has nodata cells ($valid% valid); hmm cannot be compared on it" >&2; exit 1
  fi
  lo=$(sed -nE 's/.*STATISTICS_MINIMUM=(.*)/\1/p' <<<"$info")
  hi=$(sed -nE 's/.*STATISTICS_MAXIMUM=(.*)/\1/p' <<<"$info")
  cell=$(sed -nE 's/^Pixel Size = \(([-0-9.e]+),.*/\1/p' <<<"$info")
  read -r range e z quantum < <(awk -v lo="$lo" -v hi="$hi" -v tol="$tol" -v cell="$cell" 'BEGIN {
    r = hi - lo; c = cell < 0 ? -cell : cell
    if (c < 0.1) c *= 111320  # degrees: metres at the equator, enough for the shape of the mesh
    printf "%.17g %.9g %.9g %.3g\n", r, tol / r, r / c, r / 65535 }')
  png=$build/$name.png
  t0=$(now)
  gdal_translate -q -of PNG -ot UInt16 -a_nodata none -scale "$lo" "$hi" 0 65535 "$grid" "$png"
  convert_s=$(awk -v s="$t0" -v e="$(now)" 'BEGIN {printf "%.3f", e - s}')

  # shellcheck disable=SC2034 # used through time_pair's namerefs
  tl_cmd=("$tinlod" insert "$dem" "$build/$name.gpkg" -max_error "$tol" -overwrite)
  # shellcheck disable=SC2034
  hmm_cmd=("$hmm" "$png" "$build/$name.stl" -z "$z" -e "$e")
  time_pair tl_cmd hmm_cmd
  tl_s=$(median <"$build/times.a") hmm_s=$(median <"$build/times.b")
  read -r tv tt < <(sed -nE 's/^Wrote ([0-9]+) vertices and ([0-9]+) triangles.*/\1 \2/p' "$build/out.a")
  tl_loop=$(sed -nE 's/^Wrote .* insertion ([0-9.eE+-]+) s\).*/\1/p' "$build/out.a")
  hv=$(sed -nE 's/^ +points = ([0-9]+)/\1/p' "$build/out.b")
  ht=$(sed -nE 's/^ +triangles = ([0-9]+)/\1/p' "$build/out.b")
  hmm_loop=$(sed -nE 's/^triangulating\.\.\. ([0-9.eE+-]+)s/\1/p' "$build/out.b")
  [[ -n $tv && -n $tl_loop && -n $hv && -n $hmm_loop ]] || { echo "error: cannot parse the tools' output" >&2; exit 1; }
  herr=$(measure_hmm "$build/$name.stl" "$grid")
  # shellcheck disable=SC2059
  printf "$fmt" "$name" "$tol" "$(printf %.3f "$hmm_s")" "$(printf %.3f "$tl_s")" \
    "$(awk -v a="$tl_s" -v b="$hmm_s" 'BEGIN {printf "%.2f", a / b}')" "$(printf %.3f "$hmm_loop")" \
    "$(printf %.3f "$tl_loop")" "$hv" "$tv" "$ht" "$tt" "$herr"
  echo "  hmm -z $z -e $e (height range $range m, quantum $quantum m); DEM to PNG took $convert_s s, not counted"
done
echo "(whole-process wall seconds are medians of $runs runs; loop times are each tool's own report:"
echo " hmm's 'triangulating', tinlod's 'insertion', both with their set-up scan)"
