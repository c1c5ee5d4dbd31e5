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
# pick goes through is blocked. 20 % of the 200 vertices is 40 deletions, 80 candidates
# gone through: all from the smooth tile, whose bin gives 0.8 of its candidates.
smooth = [level(100, 20, 40, {10: 100})]
rough = [level(100, 20, 40, {20: 100})]
(t, share), = thresholds.level_thresholds([smooth, rough], 20, 5)
check("the threshold is the top of the smooth tile's bin", abs(t - thresholds.bin_top(10)) < 1e-30, t)
check("... with 0.8 of that bin", abs(share - 0.8) < 1e-12, share)
check("as the option tinlod build takes", thresholds.as_option([(t, share)]) == "%.17g:0.800000" % t)

# Twice the deletions: the whole smooth bin (100 gone through) and 60 of the rough one's.
(t, share), = thresholds.level_thresholds([smooth, rough], 40, 5)
check("a larger delete percentage reaches the rough tile's bin, 0.6 of it",
      abs(t - thresholds.bin_top(20)) < 1e-30 and abs(share - 0.6) < 1e-12, (t, share))

# The stop: 5 % of 200 is 10; with 12 vertices left, only 2 may go (4 gone through).
late = [level(6, 1, 2, {10: 6})], [level(6, 1, 2, {20: 6})]
tiny = [[dict(late[0][0], vertices=6)], [dict(late[1][0], vertices=6)]]
for s in tiny:
    s.insert(0, level(100, 20, 40, {30: 100}))
levels = thresholds.level_thresholds(tiny, 20, 5)
check("at the stop, the last level deletes only what is left above it (2 of 6 in the first bin)",
      abs(levels[1][0] - thresholds.bin_top(10)) < 1e-30 and abs(levels[1][1] - 4 / 6) < 1e-12, levels)

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
