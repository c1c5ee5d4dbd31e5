# SPDX-License-Identifier: GPL-3.0-or-later
"""Whether the tiles' coarsest level ended well above -stop_pct: each tile makes as many
levels as -delete_pct takes to -stop_pct, and where its levels delete less (the outlines of
voids, which stay), a whole run goes on to more levels by itself but the tiles do not."""
import os
import sys

from .arguments import build_option
from .errors import TilesError
from .tile_file import level_vertices

# Above the stop by a fifth of it: not the few per cent that the lines' vertices add (their
# rows added up count a line's vertices in both tiles: 5.6 % for 6 tiles of 150 cells of a
# DEM a whole run takes to 5.0 %), nor the surveys' last level's miss (patagonia_coast +7.5 %).
SLACK = 1.2


def warn_if_above_stop(rows, catalogue_path, build_options, stop, levels):
    """Says so on stderr when the done tiles' coarsest level holds more than SLACK times the
    `stop` per cent (-stop_pct) of their level 0 (their rows added up, as tinlod info does). Not under a
    bound, a threshold or -max_levels, which stop the levels on purpose."""
    if levels < 2 or any(build_option(build_options, o) is not None for o in ("-max_error", "-threshold", "-max_levels")):
        return
    base = os.path.dirname(os.path.abspath(catalogue_path))
    first = before = last = 0
    for row in rows:
        if row["status"] == "done" and row["file"]:
            try:
                counts = level_vertices(os.path.join(base, row["file"]))
            except (TilesError, RuntimeError):  # moved or damaged since: a warning's figures need not stop the run
                continue
            if len(counts) >= levels:
                first, before, last = first + counts[0], before + counts[levels - 2], last + counts[levels - 1]
    if not first or last <= SLACK * stop / 100.0 * first:
        return
    # A last level that still deleted 1 % is one a whole run would follow with more.
    why = ("a tiled run makes as many levels as -delete_pct takes to -stop_pct, where a whole run goes on: give "
           "-- -max_levels N for more" if before - last >= 0.01 * before else
           "the last levels deleted almost nothing: the rest is fixed, or on outlines, whose vertices go only while "
           "the outline moves less than -outline_tolerance")
    print("Warning: the tiles' coarsest level (%d) keeps about %.1f %% of level 0's vertices (the tiles' rows added up), "
          "above the %g %% asked for (-stop_pct): %s" % (levels - 1, 100.0 * last / first, stop, why), file=sys.stderr)
