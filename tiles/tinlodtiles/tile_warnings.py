# SPDX-License-Identifier: GPL-3.0-or-later
"""The warnings tinlod gives on the tiles, shown to the user (a worker's own stderr goes
nowhere the user sees): each once, for the first tile that gives it. A warning on the whole
raster (the jitter against a small cell, a CRS that stretches distances) comes from every
tile alike, thousands of times in a national job; one the driver acts on itself is not shown.
"""
import sys

# Warnings addressed to someone building tiles by hand, whose work the driver does.
HANDLED = ("TINLOD_BORDER_REFUSED lists",)


class TileWarnings:
    def __init__(self):
        self.shown = set()

    def show(self, tile, warnings):
        for warning in warnings:
            if warning in self.shown or any(marker in warning for marker in HANDLED):
                continue
            self.shown.add(warning)
            print("Warning: tile %d,%d: %s" % (tile.col, tile.row, warning), file=sys.stderr)
