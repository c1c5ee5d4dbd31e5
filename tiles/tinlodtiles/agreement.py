# SPDX-License-Identifier: GPL-3.0-or-later
"""Agreeing the border lines of a job under an error bound (-method error -max_error).

A line vertex's deletion changes the triangles on both sides of the line, and each tile sees
only its own side's cells. So each tile deletes the line vertices the border rule takes
where its own cells stay within the bound, and refuses the others (TINLOD_BORDER_REFUSED in
its file). The refused cells join the job's keep file (-border_keep), which both tiles of
the line then keep, and every tile whose lines gained a kept cell is built again. The kept
set only grows, so the rounds end; when none refuses a vertex, the two tiles of every line
made the same deletions, each within the bound on its side: the bound holds everywhere.
"""
import math
import os

from osgeo import gdal

from .arguments import build_option

KEEP_NAME = "border_keep.txt"


def needed(build_options):
    """Only a bounded error job needs agreeing: other methods thin a line by its own data."""
    if build_option(build_options, "-method") != "error":
        return False
    try:
        return math.isfinite(float(build_option(build_options, "-max_error")))
    except (TypeError, ValueError):  # absent, or not a number (tinlod says so)
        return False


def keep_path(folder):
    return os.path.join(folder, KEEP_NAME)


def cells_of(text):
    """TINLOD_BORDER_KEPT or _REFUSED ("row col;row col"; GDAL drops an empty one)."""
    return {tuple(int(v) for v in part.split()) for part in (text or "").split(";") if part.strip()}


class TileLines:
    """Which cells lie on a tile's shared lines, as the core finds them (cellsOnSharedLines)."""

    def __init__(self, tiles, tile_size):
        self.width = max(t.xoff + t.xsize for t in tiles)
        self.height = max(t.yoff + t.ysize for t in tiles)
        self.size = tile_size
        self.at = {(t.col, t.row): t for t in tiles}

    def holds(self, tile, cell):
        row, col = cell
        if not (tile.yoff <= row < tile.yoff + tile.ysize and tile.xoff <= col < tile.xoff + tile.xsize):
            return False
        last_col, last_row = tile.xoff + tile.xsize - 1, tile.yoff + tile.ysize - 1
        return ((tile.xoff > 0 and col == tile.xoff) or (last_col < self.width - 1 and col == last_col)
                or (tile.yoff > 0 and row == tile.yoff) or (last_row < self.height - 1 and row == last_row))

    def tiles_holding(self, cell):
        """The tiles whose lines hold the cell: those whose windows do (at most 4)."""
        row, col = cell
        cols = {col // self.size, col // self.size - 1} if col % self.size == 0 else {col // self.size}
        rows = {row // self.size, row // self.size - 1} if row % self.size == 0 else {row // self.size}
        found = (self.at.get((c, r)) for c in cols for r in rows)
        return [t for t in found if t is not None and self.holds(t, cell)]

    def kept_by_tile(self, kept):
        """{tile: the kept cells on its lines}, a cell looked up once (a job has many tiles)."""
        by_tile = {}
        for cell in kept:
            for tile in self.tiles_holding(cell):
                by_tile.setdefault(tile, set()).add(cell)
        return by_tile


def tile_record(path):
    """(the kept cells a built tile was given, the cells it refused); None for either when
    its file does not say (built without agreement)."""
    try:
        dataset = gdal.OpenEx(path)
    except RuntimeError:  # unreadable: built again
        return None, None
    if dataset is None or dataset.GetMetadataItem("TINLOD_BORDER_AGREED") != "yes":
        return None, None
    return cells_of(dataset.GetMetadataItem("TINLOD_BORDER_KEPT")), cells_of(dataset.GetMetadataItem("TINLOD_BORDER_REFUSED"))


def next_round(done, kept, lines):
    """From the built tiles ({tile: its file}) and the kept cells so far: the kept cells with
    every refusal added, and the tiles to build again (those whose lines' kept cells are not
    those they were built with, or whose file does not say)."""
    records = {tile: tile_record(path) for tile, path in done.items()}
    kept = set(kept)
    for given, refused in records.values():  # what the tiles recorded, should the keep file be lost
        kept |= (given or set()) | (refused or set())
    by_tile = lines.kept_by_tile(kept)
    again = [tile for tile, (given, _) in records.items() if given is None or given != by_tile.get(tile, set())]
    return kept, again
