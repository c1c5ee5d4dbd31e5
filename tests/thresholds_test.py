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

# The two tiles share a line of 10 vertices (a half each in the union: 190 vertices, not
# 200), and the border rule deletes 4 of them (a half each: 2 in each tile's survey). 20 %
# of the union is 38 deletions, 34 of them the tiles' own: 0.34 of the smooth bin. Counted
# as before, the tiles' 200 vertices and no room for the line's picks, it was 40 (0.4).
def shared(row):
    return dict(row, union_vertices=95, border_picked=2)


(t, share), = thresholds.level_thresholds([[shared(smooth[0])], [shared(rough[0])]], 20, 5)
check("a level's own picks leave room for the border rule's, of the union's vertices",
      abs(t - thresholds.bin_top(10)) < 1e-30 and abs(share - 0.34) < 1e-12, (t, share))

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

# -exact_stop: a second round of surveys, made with the first round's thresholds (the build
# pass's state) and every candidate walked at the stop level (index 2), counts the union's
# vertices and each level's picks by bin. With -stop_pct 30 the stop is 60 of the union's
# 200. Levels 1 and 2 leave 160 and 128: above it. At index 2 the union has 80: 20 must go,
# the smooth tile's 12 picks and 8 of the rough tile's 10, whose bin has 30 candidates.
def walked(union, picked, counts, picks):
    return dict(level(2 * union, picked, 2 * picked, counts), union_vertices=union, picked_histogram=list(picks.items()))


first_values = [(1.0, 1.0), (2.0, 1.0), (3.0, 1.0), (4.0, 1.0)]
second = [[walked(100, 20, {}, {}), walked(80, 16, {}, {}), walked(40, 12, {10: 30}, {10: 12})],
          [walked(100, 20, {}, {}), walked(80, 16, {}, {}), walked(40, 10, {20: 30}, {20: 10})]]
exact = thresholds.exact_stop_thresholds(first_values, second, 30, 2)
check("-exact_stop: the walked level deletes what is above the stop, best first, and the next nothing",
      exact[:2] == first_values[:2] and abs(exact[2][0] - thresholds.bin_top(20)) < 1e-30
      and abs(exact[2][1] - 8 / 30) < 1e-12 and exact[3] == (0.0, 1.0), exact)
# When the first round's picks at index 1 (60 a tile) would already go below the stop, that
# level deletes only the 100 above it: the smooth tile's 60 and 40 of the rough one's 80.
second[0][1], second[1][1] = walked(80, 60, {10: 80}, {10: 60}), walked(80, 60, {20: 80}, {20: 60})
exact = thresholds.exact_stop_thresholds(first_values, second, 30, 2)
check("-exact_stop: an earlier level that reaches the stop deletes only down to it",
      exact[0] == first_values[0] and abs(exact[1][0] - thresholds.bin_top(20)) < 1e-30
      and abs(exact[1][1] - 0.5) < 1e-12 and exact[2:] == [(0.0, 1.0), (0.0, 1.0)], exact)

# The border rule's picks at that level (10 of the union's in each tile) go too: it deletes
# only 80 of its own, the smooth tile's 60 and 20 of the rough one's 80 (0.25).
second[0][1]["border_picked"] = second[1][1]["border_picked"] = 10
exact = thresholds.exact_stop_thresholds(first_values, second, 30, 2)
check("-exact_stop: the border rule's picks below the walked level count toward the stop",
      abs(exact[1][0] - thresholds.bin_top(20)) < 1e-30 and abs(exact[1][1] - 0.25) < 1e-12, exact)

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
