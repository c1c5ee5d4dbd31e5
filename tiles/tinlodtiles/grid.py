# SPDX-License-Identifier: GPL-3.0-or-later
"""The tile grid of a raster, as the core (`tinlod build -tile_size N -tile C,R`) cuts it.

Neighbouring tiles share one row or column of cells, so that their TINs meet on it and fit
together exactly: tile C covers columns C*N .. min(C*N + N, W - 1), inclusive.
"""
import math
from dataclasses import dataclass


@dataclass(frozen=True)
class Tile:
    col: int
    row: int
    xoff: int
    yoff: int
    xsize: int
    ysize: int

    @property
    def name(self):
        """The tile's file name in the tiles folder."""
        return "tile_%d_%d.gpkg" % (self.col, self.row)


def tile_count(cells, tile_size):
    """Tiles along one axis of `cells` cells: each spans tile_size cell steps."""
    return max(1, math.ceil((cells - 1) / tile_size))


def tile_span(index, cells, tile_size):
    """(offset, size) of tile `index` along an axis, its last cell shared with the next."""
    offset = index * tile_size
    last = min(offset + tile_size, cells - 1)
    return offset, max(last - offset + 1, 1)


def tile_grid(width, height, tile_size):
    """Every tile of a width x height raster, row by row."""
    tiles = []
    for row in range(tile_count(height, tile_size)):
        yoff, ysize = tile_span(row, height, tile_size)
        for col in range(tile_count(width, tile_size)):
            xoff, xsize = tile_span(col, width, tile_size)
            tiles.append(Tile(col, row, xoff, yoff, xsize, ysize))
    return tiles
