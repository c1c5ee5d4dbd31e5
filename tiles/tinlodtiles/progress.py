# SPDX-License-Identifier: GPL-3.0-or-later
"""Progress of a run on stderr: tiles finished / total, one updated line on a terminal, a
line per tile elsewhere (a log keeps each tile's outcome)."""
import sys


def n_tiles(count):
    """"1 tile", "2 tiles"."""
    return "%d tile%s" % (count, "" if count == 1 else "s")


class Progress:
    def __init__(self, total, quiet):
        self.total, self.quiet, self.finished = total, quiet, 0
        self.terminal = sys.stderr.isatty()

    def tile(self, col, row, status):
        self.finished += 1
        if self.quiet:
            return
        text = "%d/%d tiles (tile %d,%d %s)" % (self.finished, self.total, col, row, status)
        if self.terminal:
            sys.stderr.write("\r" + text + " " * 8)
        else:
            sys.stderr.write(text + "\n")
        sys.stderr.flush()

    def end(self):
        if self.terminal and not self.quiet and self.finished:
            sys.stderr.write("\n")
            sys.stderr.flush()
