# SPDX-License-Identifier: GPL-3.0-or-later
"""The warnings tinlod gives on the tiles, shown to the user (a worker's own stderr goes
nowhere the user sees): each once, for the first tile that gives it. A warning on the whole
raster (the jitter against a small cell, a CRS that stretches distances) comes from every
tile alike, thousands of times in a national job, and from tinlod build -check before any
tile: it is said then, once; one the driver acts on itself is not shown.
"""
import sys

# Warnings addressed to someone building tiles by hand, whose work the driver does.
HANDLED = ("TINLOD_BORDER_REFUSED lists",)
# Warnings whose figures are each tile's own (a DEM in degrees has cells of another size in
# each tile; each tile's coarsest level bends by its own height): the first tile's stands for
# them all.
FIGURES_VARY = ("m is more than half the cell size", "triangles part by up to")


class TileWarnings:
    def __init__(self):
        self.shown = set()

    def show_job(self, warnings):
        """The job's own, which tinlod build -check gave before any tile (build_check): said
        now, and by no tile again."""
        for warning in self.new(warnings):
            print("Warning: %s" % warning, file=sys.stderr)

    def show(self, tile, warnings):
        for warning in self.new(warnings):
            print("Warning: tile %d,%d: %s" % (tile.col, tile.row, warning), file=sys.stderr)

    def new(self, warnings):
        """Those not shown yet nor handled by the driver, marked shown."""
        out = []
        for warning in dict.fromkeys(warnings):
            key = next((marker for marker in FIGURES_VARY if marker in warning), warning)
            if key in self.shown or any(marker in warning for marker in HANDLED):
                continue
            self.shown.add(key)
            out.append(warning)
        return out
