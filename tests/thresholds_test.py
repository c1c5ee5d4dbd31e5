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
from tinlodtiles.importance_bins import Bins, added  # noqa: E402
from tinlodtiles.survey_reader import SurveyReader  # noqa: E402
from tinlodtiles.survey_store import SurveyStore  # noqa: E402
from tinlodtiles.surveyed_tile import SurveyedTile  # noqa: E402
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

# Each tile is followed through the levels at the count the thresholds leave it, its state
# read from its survey at that count, whatever level the survey reached it at. With
# -delete_pct 25: level 1 deletes 50 of the 200 vertices, all from the smooth tile's bin 10
# (half of its 100 candidates: the other half blocked). The smooth tile has 50 left, which
# its survey reached at its level 3 (bin 12, 25 picks); the rough one keeps its 100, its
# survey's level 1 (bin 20, 50 picks). Level 2 deletes 37.5 of 150: the smooth tile's 25,
# and 12.5 of the rough tile's 100 candidates in bin 20. Read at level 2 of each survey
# (75 vertices each, bins 11 and 21) it was half of the smooth tile's bin 11.
def row(vertices, b):
    return level(vertices, vertices // 2, vertices, {b: vertices})


smooth_tile = [row(100, 10), row(75, 11), row(50, 12)]
rough_tile = [row(100, 20), row(75, 21), row(50, 22)]
levels = thresholds.level_thresholds([smooth_tile, rough_tile], 25, 5)
check("level 1 takes half of the smooth tile's bin", levels[0] == (thresholds.bin_top(10), 0.5), levels)
check("level 2 reads each tile's survey at the count level 1 left it: the rough tile's first level",
      levels[1][0] == thresholds.bin_top(20) and abs(levels[1][1] - 0.125) < 1e-12, levels)

# The stop, with -delete_pct 50 -stop_pct 30: 200 vertices, the stop 60. Level 1 deletes
# 100 (50 a tile, half of each bin 5), level 2 finds the 100 left and deletes 0.4 of them,
# 40: 0.4 of the 100 candidates of bin 10, 20 of each tile's 25 picks. Level 3 nothing.
tiles = [[row(100, 5), row(50, 10), row(30, 20)], [row(100, 5), row(50, 10), row(30, 20)]]
levels = thresholds.level_thresholds(tiles, 50, 30)
check("the last level deletes the share that takes the followed count to the stop",
      levels[1][0] == thresholds.bin_top(10) and abs(levels[1][1] - 0.4) < 1e-12, levels)
check("a level after the stop deletes nothing", levels[2] == (0.0, 1.0), levels)
check("... and it is the stop level -exact_stop walks", thresholds.stop_level(tiles, 50, 30) == 1)

# A survey of an earlier tinlod (no walk_histogram): a bin its pick walked gives its own
# picks (picked_histogram), 30 of bin 3's 40 (the first candidates are seldom blocked);
# beyond, the level's share of what its pick went through (0.5).
walked = dict(level(100, 40, 80, {3: 40, 4: 40, 5: 20}), picked_histogram=[[3, 30], [4, 10]])
counts, picks = (b.as_dict() for b in SurveyedTile([walked], 20).state())
check("a walked bin's picks are the survey's, beyond the walk the level's share",
      counts == {3: 40, 4: 40, 5: 20} and picks == {3: 30, 4: 20, 5: 10}, (counts, picks))

# A survey that walked on through every candidate (walk_histogram) gives its walk's picks in
# every bin: bin 4's 12 and bin 5's 3, where the share gave 20 and 10.
walked_on = dict(walked, walk_histogram=[[3, 30], [4, 12], [5, 3]])
counts, picks = (b.as_dict() for b in SurveyedTile([walked_on], 20).state())
check("a survey's walk through every candidate gives its picks in every bin",
      counts == {3: 40, 4: 40, 5: 20} and picks == {3: 30, 4: 12, 5: 3}, (counts, picks))

# Below its survey's last count a tile reads its last level with the importances raised as
# they rose over its last two full levels: 4 times the importance for half the vertices,
# so at half the last count again 120 bins up (a factor 3.98), the candidates halved.
rising = [dict(row(100, 10), last=1e6), dict(row(50, 40), last=4e6)]
tile = SurveyedTile(rising, 50)
tile.vertices = 25
counts, picks = (b.as_dict() for b in tile.state())
check("below the survey's last count: its last level, importances raised",
      tile.rise() == 120 and counts == {160: 25.0} and picks == {160: 12.5}, (tile.rise(), counts, picks))

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
# Never more than the delete percentage of the level's vertices, as a whole run's levels:
# with -delete_pct 20, 16 of the 80 (the smooth tile's 12, 4 of the rough tile's 30).
exact = thresholds.exact_stop_thresholds(first_values, second, 30, 2, 20)
check("-exact_stop: the walked level deletes at most the delete percentage of its vertices",
      exact[2][0] == thresholds.bin_top(20) and abs(exact[2][1] - 4 / 30) < 1e-12, exact)
# With the border rule's 8 picks there, they count toward the 16: 8 of the level's own.
capped_border = [[dict(r) for r in s] for s in second]
capped_border[0][2]["border_picked"] = capped_border[1][2]["border_picked"] = 4
exact = thresholds.exact_stop_thresholds(first_values, capped_border, 30, 2, 20)
check("-exact_stop: the border rule's picks count toward the delete percentage",
      exact[2][0] == thresholds.bin_top(10) and abs(exact[2][1] - 8 / 30) < 1e-12, exact)
# The border rule's picks at the walked level (4 of the union's in each tile, at most: there
# they passed no threshold) go beside its own: 12 of them, the smooth tile's 12 picks.
with_border = [[dict(r) for r in s] for s in second]
with_border[0][2]["border_picked"] = with_border[1][2]["border_picked"] = 4
exact = thresholds.exact_stop_thresholds(first_values, with_border, 30, 2)
check("-exact_stop: the walked level leaves room for the border rule's picks there",
      exact[2][0] == thresholds.bin_top(10) and abs(exact[2][1] - 0.4) < 1e-12, exact)
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

# A bin two tiles hold, whose picks differ (tile A can take 5 of its 100, B 90 of its 100):
# each tile deletes at most its own picks, so the share that deletes 50 is 0.45 (A's 5, B's
# 45), not the pooled 0.25 (A's 5 and B's 25: 30).
check("a bin's share counts each tile's picks as its cap", abs(thresholds.share_reaching([(100, 5), (100, 90)], 50) - 0.45) < 1e-12,
      thresholds.share_reaching([(100, 5), (100, 90)], 50))
check("... 0.9 when every pick is needed (B's 90 are 0.9 of its candidates)",
      abs(thresholds.share_reaching([(100, 5), (100, 90)], 95) - 0.9) < 1e-12)


def survey_row(vertices, picked, considered, histogram, last, walked=None):
    return dict(level(vertices, picked, considered, histogram), last=last,
                **({"picked_histogram": [[b, n] for b, n in walked.items()]} if walked else {}))


# A small tile whose survey's line deletions outrun its count (it reaches no vertex left)
# is followed to 0 without failing.
small = [survey_row(100, 20, 40, {1: 20, 2: 20, 3: 20, 4: 20}, 1e-9, {1: 10, 2: 10}),
         survey_row(50, 10, 20, {2: 10, 3: 10, 4: 10, 5: 10}, 2e-9, {2: 5, 3: 5}),
         survey_row(25, 5, 10, {3: 5, 4: 5, 5: 5}, 4e-9), survey_row(15, 3, 6, {6: 6}, 8e-9)]
large = [survey_row(1000, 200, 400, {400: 400}, 1e-6), survey_row(800, 160, 320, {410: 320}, 2e-6),
         survey_row(640, 128, 256, {420: 256}, 4e-6), survey_row(512, 100, 200, {430: 200}, 8e-6)]
check("a tile followed down to no vertex does not stop the thresholds",
      len(thresholds.level_thresholds([small, large], 20, 5)) == 4)

# Bins: a survey's histogram as one array from its lowest bin above 0, bin 0's ties apart;
# in 16 bits where every count fits, else 32-bit floats (which hold any count exactly).
bins = Bins.of([[0, 7], [40, 3], [42, 5]])
check("Bins keep bin 0 apart and the others from their lowest",
      (bins.zero, bins.lo, bins.hi, list(bins.values), bins.values.dtype.name) == (7.0, 40, 43, [3, 0, 5], "uint16")
      and bins.as_dict() == {0: 7, 40: 3, 42: 5}, (bins.zero, bins.lo, list(bins.values)))
check("... a count beyond 16 bits in 32-bit floats, exactly",
      Bins.of([[5, 70000], [6, 1]]).values.dtype.name == "float32" and Bins.of([[5, 70000]]).get(5) == 70000)
check("... read over any run of bins, 0 outside theirs", list(bins.on(-1, 44)[[1, 41, 42, 43, 44]]) == [7, 3, 0, 5, 0])
check("... raised by a shift, bin 0 staying", bins.shifted(10).as_dict() == {0: 7, 50: 3, 52: 5})
total = added([bins, Bins.of([[0, 1], [39, 2], [42, 1]])], [2.0, 0.5])
check("... added up with weights over the bins they span",
      total.as_dict() == {0: 14.5, 39: 1.0, 40: 6.0, 42: 10.5}, total.as_dict())

# Added one at a time (a generator, the run of bins growing both ways), the same sums.
streamed = added(h for h in [Bins.of([[50, 1]]), bins, Bins.of([[0, 1], [39, 2], [60, 4]])])
check("... added one at a time as they come, the run growing on both sides",
      streamed.as_dict() == {0: 8, 39: 2, 40: 3, 42: 5, 50: 1, 60: 4}, streamed.as_dict())

# The driver's surveys with their histograms in a SurveyStore (an unnamed file: the folder
# stays empty) set the very thresholds of those held in memory, and hold no histogram.
with tempfile.TemporaryDirectory() as folder:
    paths = []
    for i, tile in enumerate([smooth_tile, rough_tile, small, large]):
        paths.append(os.path.join(folder, "survey_%d.json" % i))
        with open(paths[-1], "w") as f:
            json.dump({"bins_per_decade": 200, "lowest": 1e-12, "levels": tile, "line_outline": [[i, 2 * i]]}, f)
    in_memory = [thresholds.read_survey(p) for p in paths]
    with SurveyStore(folder) as store:
        reader = SurveyReader(store)
        stored = [reader.levels(i, p) for i, p in enumerate(paths)]
        check("a SurveyStore leaves no file in the tiles' folder", sorted(os.listdir(folder)) == sorted(
            os.path.basename(p) for p in paths), os.listdir(folder))
        check("... the levels hold handles, not histograms", all(
            not isinstance(r[k], (Bins, list)) for s in stored for r in s for k in ("histogram", "walk_histogram") if k in r))
        check("... and read back every histogram as it was", all(
            Bins.of(a[k]).as_dict() == Bins.of(b[k]).as_dict() for s, t in zip(in_memory, stored) for a, b in zip(s, t)
            for k in ("histogram", "picked_histogram") if k in a))
        for pcts in [(20, 5), (25, 5), (50, 30)]:
            check("... the same thresholds with -delete_pct %d -stop_pct %d" % pcts,
                  thresholds.level_thresholds(stored, *pcts) == thresholds.level_thresholds(in_memory, *pcts),
                  (thresholds.level_thresholds(stored, *pcts), thresholds.level_thresholds(in_memory, *pcts)))
        check("... and -exact_stop's", thresholds.exact_stop_thresholds(first_values, stored, 30, 2) ==
              thresholds.exact_stop_thresholds(first_values, in_memory, 30, 2))
        check("... the surveys' line cells gathered as they are read", reader.cells == {(0, 0), (1, 2), (2, 4), (3, 6)},
              reader.cells)

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
