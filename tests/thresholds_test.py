#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""tiles/tinlodtiles/thresholds.py against hand-computed thresholds: one per level for the
whole raster, from the tiles' surveys (tinlod build -survey).

Usage: thresholds_test.py TILES_SOURCE_DIR"""
import json
import os
import sys
import tempfile

sys.path.insert(0, sys.argv[1])
from tinlodtiles import thresholds  # noqa: E402
from script_checks import check, exit_code  # noqa: E402


def level(vertices, picked, considered, histogram):
    return {"level": 1, "vertices": vertices, "picked": picked, "considered": considered, "last": 0,
            "histogram": [[b, n] for b, n in histogram.items()]}


# A smooth tile (100 candidates in bin 10) and a rough one (100 in bin 20); half of what a
# pick goes through is blocked. 20 % of the 200 vertices is 40 deletions: all from the
# smooth tile's bin, 0.4 of its candidates (80 of them gone through).
smooth = [level(100, 20, 40, {10: 100})]
rough = [level(100, 20, 40, {20: 100})]
(t, share), = thresholds.level_thresholds([smooth, rough], 20, 5)
check("the threshold is the top of the smooth tile's bin", abs(t - thresholds.bin_top(10)) < 1e-30, t)
check("... with 0.4 of that bin", abs(share - 0.4) < 1e-12, share)
check("as the option tinlod build takes", thresholds.as_option([(t, share)]) == "%.17g:0.400000" % t)

# Twice the deletions (80): the whole smooth bin (100 gone through, 50 deleted) and 30 of
# the rough one's 100.
(t, share), = thresholds.level_thresholds([smooth, rough], 40, 5)
check("a larger delete percentage reaches the rough tile's bin, 0.3 of it",
      abs(t - thresholds.bin_top(20)) < 1e-30 and abs(share - 0.3) < 1e-12, (t, share))

# The stop, with -delete_pct 50 -stop_pct 30: 200 vertices, the stop 60. Level 1 deletes
# half, so level 2 finds 100 and deletes 0.4 of what it finds, down to 60; level 3 nothing.
# The surveys found 80 at level 2 (each tile deleted more of its own): 0.4 of 80 is 32
# (20 from the smooth bin, 12 of the rough one's 40, a share 0.3), not the 20 above the
# stop their own count would leave, which the build pass, finding about 100, would miss
# by 20.
def first(b):
    return level(100, 50, 100, {b: 100})


def later(b):
    return level(40, 10, 20, {b: 40})


tiles = [[first(5), later(10), later(10)], [first(5), later(20), later(20)]]
levels = thresholds.level_thresholds(tiles, 50, 30)
check("the last level deletes the share that takes the expected count to the stop",
      abs(levels[1][0] - thresholds.bin_top(20)) < 1e-30 and abs(levels[1][1] - 0.3) < 1e-12, levels)
check("a level after the stop deletes nothing", levels[2] == (0.0, 1.0), levels)

# A survey of another binning is refused.
with tempfile.NamedTemporaryFile("w", suffix=".json", delete=False) as f:
    json.dump({"bins_per_decade": 50, "lowest": 1e-12, "levels": []}, f)
try:
    thresholds.read_survey(f.name)
    check("a survey in other bins is refused", False)
except ValueError:
    check("a survey in other bins is refused", True)
os.remove(f.name)

sys.exit(exit_code("thresholds"))
