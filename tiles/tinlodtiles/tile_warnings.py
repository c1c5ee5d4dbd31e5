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
        out = [w for w in dict.fromkeys(warnings) if w not in self.shown and not any(m in w for m in HANDLED)]
        self.shown.update(out)
        return out
