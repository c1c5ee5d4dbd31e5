#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""tiles/tinlodtiles/agreement.py: which tiles hold a line cell (as the core's
cellsOnSharedLines, by brute force over every tile), the keep file, and the rounds' next
step from the tiles' recorded kept and refused cells.

Usage: agreement_test.py TILES_SOURCE_DIR"""
import os
import sys
import tempfile

sys.path.insert(0, sys.argv[1])
from osgeo import gdal, ogr  # noqa: E402

from tinlodtiles import agreement, cell_file  # noqa: E402
from tinlodtiles.grid import tile_grid  # noqa: E402
from script_checks import check, exit_code  # noqa: E402

gdal.UseExceptions()


def write_tile(path, agreed, kept=(), refused=()):
    """A GeoPackage with only the metadata a built tile records."""
    dataset = ogr.GetDriverByName("GPKG").CreateDataSource(path)
    dataset.CreateLayer("vertices", geom_type=ogr.wkbPoint)
    if agreed:
        dataset.SetMetadataItem("TINLOD_BORDER_AGREED", "yes")
        for key, cells in (("TINLOD_BORDER_KEPT", kept), ("TINLOD_BORDER_REFUSED", refused)):
            if cells:
                dataset.SetMetadataItem(key, ";".join("%d %d" % c for c in sorted(cells)))
    dataset = None


SIZE, WIDTH, HEIGHT = 150, 400, 300  # 3 x 2 tiles, the last column and row short
tiles = tile_grid(WIDTH, HEIGHT, SIZE)
lines = agreement.TileLines(tiles, SIZE)
by_name = {(t.col, t.row): t for t in tiles}

# Every cell of every line (and a few off them): the tiles found by place are those whose
# lines hold the cell, checked against every tile.
cells = [(r, c) for r in range(HEIGHT) for c in (0, 150, 300, 399)] + \
        [(r, c) for r in (0, 150, 299) for c in range(WIDTH)] + [(10, 10), (151, 151)]
wrong = [cell for cell in cells
         if sorted((t.col, t.row) for t in lines.tiles_holding(cell))
         != sorted((t.col, t.row) for t in tiles if lines.holds(t, cell))]
check("the tiles holding a cell are found by its place, as by every tile", not wrong, wrong[:5])
check("a cell of the vertical line 150 is held by both tiles beside it",
      sorted((t.col, t.row) for t in lines.tiles_holding((10, 150))) == [(0, 0), (1, 0)])
check("a cell where lines cross is held by the four tiles around it",
      len(lines.tiles_holding((150, 150))) == 4)
check("the raster's own edge is no shared line", lines.tiles_holding((10, 0)) == [] and lines.tiles_holding((0, 10)) == [])

check("needed: -method error with a finite -max_error only",
      agreement.needed(["-method", "error", "-max_error", "5"])
      and not agreement.needed(["-method", "error", "-max_error", "inf"])
      and not agreement.needed(["-method", "error"]) and not agreement.needed(["-max_error", "5"]))

work = tempfile.mkdtemp(prefix="tinlod_agreement_test_")
keep = agreement.keep_path(work)
cell_file.write_cells(keep, {(20, 150), (3, 150)})
with open(keep, "a") as f:
    f.write("# a comment\n\n7 300  # and one after a cell\n")
check("the keep file reads back, comments and blank lines skipped",
      cell_file.read_cells(keep) == {(3, 150), (20, 150), (7, 300)}, cell_file.read_cells(keep))
check("a missing keep file is no kept cell", cell_file.read_cells(os.path.join(work, "absent.txt")) == set())

# Tile 0,0 refused (40, 150) on the line it shares with 1,0; 1,0 was built with nothing
# kept; 2,0 was built with its own line's cell (7, 300) kept; 0,1 and 1,1 say nothing of
# agreement (built before); 2,1's file is unreadable.
paths = {name: os.path.join(work, "tile_%d_%d.gpkg" % name) for name in by_name}
write_tile(paths[(0, 0)], True, refused={(40, 150)})
write_tile(paths[(1, 0)], True)
write_tile(paths[(2, 0)], True, kept={(7, 300)})
write_tile(paths[(0, 1)], False)
write_tile(paths[(1, 1)], False)
with open(paths[(2, 1)], "w") as f:
    f.write("not a GeoPackage")
done = {by_name[name]: path for name, path in paths.items()}
kept, again = agreement.next_round(done, {(7, 300)}, lines)
check("the refused cell joins the kept ones", kept == {(7, 300), (40, 150)}, kept)
check("both tiles of its line, those built before agreement and the unreadable one are built again; "
      "the tile whose kept cells are unchanged is not",
      sorted((t.col, t.row) for t in again) == [(0, 0), (0, 1), (1, 0), (1, 1), (2, 1)],
      sorted((t.col, t.row) for t in again))
kept, _ = agreement.next_round({by_name[(2, 0)]: paths[(2, 0)]}, set(), lines)
check("with the keep file lost, the kept cells come back from what the tiles recorded", kept == {(7, 300)}, kept)

sys.exit(exit_code("agreement"))
