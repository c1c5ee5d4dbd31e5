#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Checks that the tiles of a tiled tinlod run fit together at every level.

    tile_union.py [--whole WHOLE.gpkg] [--json OUT.json] TILE.gpkg ...

For each level k, over the union of the tiles' level k:
- every triangle is counter-clockwise with a positive area;
- no directed edge is in two triangles (so no edge is in more than two, and no two
  triangles overlap along an edge);
- a vertex of one tile on a shared border line sits at exactly the same x and y in every
  tile that has it (the same cell of the whole raster);
- no crack: no edge on a shared border line has a vertex of the union strictly inside it
  (a T-junction, where one tile kept a vertex the other deleted).
With --whole (a run over the whole raster with the same options), each level's area and
its pooled RMSE and maximum error against the DEM are printed beside the whole run's; with
--max_area_change F too, a level whose area differs from the whole run's by more than F
(relative) fails. Exit status 1 when any tile union is not conforming, or its area is off.  Reads the GeoPackages with sqlite3
and osgeo (for the metadata), nothing else.
"""
import argparse
import bisect
import json
import math
import sqlite3
import struct
import sys

from osgeo import gdal


def metadata(path):
    ds = gdal.OpenEx(path, gdal.OF_VECTOR)
    if ds is None:
        raise SystemExit(f"cannot open {path}")
    return ds.GetMetadata()


def point_xy(blob):
    """x and y of a GeoPackage point blob (header, optional envelope, WKB point)."""
    flags = blob[3]
    envelope = {0: 0, 1: 32, 2: 48, 3: 48, 4: 64}[(flags >> 1) & 7]
    wkb = 8 + envelope
    order = "<" if blob[wkb] == 1 else ">"
    return struct.unpack_from(order + "dd", blob, wkb + 5)


def signed_area(p, q, r):
    return 0.5 * ((q[0] - p[0]) * (r[1] - p[1]) - (r[0] - p[0]) * (q[1] - p[1]))


class Hierarchy:
    """A hierarchy GeoPackage, read once: each vertex's cell and place, the triangles with
    their levels, the levels table. `offset` (column, row) turns its cells into the whole
    raster's."""

    def __init__(self, path, offset=(0, 0)):
        self.path = path
        db = sqlite3.connect(f"file:{path}?mode=ro", uri=True)
        self.key = {}  # vertex id -> whole-raster (row, col)
        self.xy = {}
        for vid, row, col, geom in db.execute("SELECT id, row, col, geom FROM vertices"):
            self.key[vid] = (row + offset[1], col + offset[0])
            self.xy[vid] = point_xy(geom)
        self.triangles = db.execute("SELECT v0, v1, v2, first_level, last_level FROM triangles").fetchall()
        self.levels = {r[0]: r[1:] for r in db.execute("SELECT level, vertices, triangles, max_error, rmse, cells FROM levels")}
        db.close()

    def area(self, k):
        return sum(signed_area(self.xy[a], self.xy[b], self.xy[c]) for a, b, c in level_triangles(self, k))


class Tile(Hierarchy):
    def __init__(self, path):
        xoff, yoff, xsize, ysize = (int(v) for v in metadata(path)["TINLOD_TILE_WINDOW"].split(","))
        self.window = (xoff, yoff, xsize, ysize)
        super().__init__(path, (xoff, yoff))


def level_triangles(tin, k):
    return [t[:3] for t in tin.triangles if t[3] <= k <= t[4]]


def check_level(tiles, k, lines_col, lines_row):
    problems = []
    directed = set()
    xy_of = {}
    area = 0.0
    used = set()
    line_edges = []
    for tile in tiles:
        for v0, v1, v2 in level_triangles(tile, k):
            ids = (v0, v1, v2)
            keys = [tile.key[v] for v in ids]
            pts = [tile.xy[v] for v in ids]
            a = signed_area(*pts)
            if not a > 0:
                problems.append(f"level {k}: triangle {keys} in {tile.path} is not counter-clockwise (area {a})")
            area += a
            for i in range(3):
                key, p = keys[i], pts[i]
                used.add(key)
                if xy_of.setdefault(key, p) != p:
                    problems.append(f"level {k}: the vertex of cell {key} lies at {p} in {tile.path} and at {xy_of[key]} elsewhere")
                e = (keys[i], keys[(i + 1) % 3])
                if e in directed:
                    problems.append(f"level {k}: edge {e} is in two triangles of the same orientation (an overlap)")
                directed.add(e)
    # Edges on a shared border line: none may pass over another vertex of the union.
    on_col = {}
    on_row = {}
    for key in used:
        if key[1] in lines_col:
            on_col.setdefault(key[1], []).append(key[0])
        if key[0] in lines_row:
            on_row.setdefault(key[0], []).append(key[1])
    for d in (on_col, on_row):
        for v in d.values():
            v.sort()
    for a, b in directed:
        for line, idx, other, d in ((a[1], 0, 1, on_col), (a[0], 1, 0, on_row)):
            if a[other] == b[other] and a[other] == line and line in d:
                lo, hi = sorted((a[idx], b[idx]))
                cells = d[line]
                i = bisect.bisect_right(cells, lo)
                if i < len(cells) and cells[i] < hi:
                    problems.append(f"level {k}: edge {a}-{b} on a tile border passes over the vertex at {(cells[i], line) if idx == 0 else (line, cells[i])} (a crack)")
    return problems, area, len(used)


def pooled(tiles, k):
    cells = sum(t.levels[k][4] for t in tiles)
    ss = sum(t.levels[k][3] ** 2 * t.levels[k][4] for t in tiles)
    return math.sqrt(ss / cells) if cells else 0.0, max(t.levels[k][2] for t in tiles)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--whole")
    ap.add_argument("--json")
    ap.add_argument("--levels", help="comma-separated levels to check (default: all)")
    ap.add_argument("--max_area_change", type=float,
                    help="with --whole: the largest relative change of a level's area from the whole run's")
    ap.add_argument("tiles", nargs="+")
    args = ap.parse_args()
    tiles = [Tile(p) for p in args.tiles]
    counts = {len(t.levels) for t in tiles}
    if len(counts) != 1:
        print(f"FAILED: the tiles have different numbers of levels: {sorted(counts)}")
        return 1
    nlevels = counts.pop()
    lines_col = {t.window[0] for t in tiles if t.window[0] > 0}
    lines_row = {t.window[1] for t in tiles if t.window[1] > 0}
    wanted = range(nlevels) if not args.levels else [int(x) for x in args.levels.split(",")]
    whole = Hierarchy(args.whole) if args.whole else None
    report = []
    failed = False
    for k in wanted:
        problems, area, vertices = check_level(tiles, k, lines_col, lines_row)
        rmse, maxe = pooled(tiles, k)
        row = {"level": k, "vertices": vertices, "triangles": sum(len(level_triangles(t, k)) for t in tiles),
               "area": area, "rmse": rmse, "max_error": maxe, "problems": len(problems)}
        if whole and k in whole.levels:
            wl = whole.levels[k]
            row.update({"whole_vertices": wl[0], "whole_area": whole.area(k), "whole_rmse": wl[3], "whole_max_error": wl[2]})
        report.append(row)
        if args.max_area_change is not None:
            if "whole_area" not in row:
                problems.append(f"level {k}: no area to compare with (--max_area_change needs --whole with this level)")
            elif abs(area / row["whole_area"] - 1) > args.max_area_change:
                problems.append(f"level {k}: area {area:.1f} is {area / row['whole_area']:.6f} of the whole run's "
                                f"{row['whole_area']:.1f} (more than {args.max_area_change} apart)")
            row["problems"] = len(problems)
        for p in problems[:10]:
            print("  " + p)
        failed |= bool(problems)
        line = f"level {k:2d}: {vertices} vertices, {row['triangles']} triangles, conforming={'no' if problems else 'yes'}, rmse {rmse:.3f} m, max {maxe:.2f} m"
        if "whole_rmse" in row:
            line += (f" | whole: {row['whole_vertices']} vertices, rmse {row['whole_rmse']:.3f} m, max {row['whole_max_error']:.2f} m,"
                     f" area ratio {area / row['whole_area']:.6f}")
        print(line, flush=True)
    if args.json:
        with open(args.json, "w") as f:
            json.dump(report, f, indent=1)
    print("FAILED: the tiles do not fit together" if failed else "OK: every level checked is conforming")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
