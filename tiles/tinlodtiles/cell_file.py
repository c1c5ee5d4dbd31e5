# SPDX-License-Identifier: GPL-3.0-or-later
"""Files of raster cells, one "row col" of the whole raster per line ('#' starts a comment),
as tinlod build's -border_keep and -line_outline read them."""
from . import task


def read_cells(path):
    """The cells, as (row, col); none when the file is not there."""
    try:
        with open(path) as f:
            lines = [line.split("#", 1)[0].split() for line in f]
    except FileNotFoundError:
        return set()
    return {(int(fields[0]), int(fields[1])) for fields in lines if fields}


def write_cells(path, cells):
    """Whole or not at all (a task may read the file meanwhile), and on disk before the
    catalogue records what it holds."""
    partial = path + ".partial"
    with open(partial, "w") as f:
        for row, col in sorted(cells):
            f.write("%d %d\n" % (row, col))
    task.publish(partial, path)
