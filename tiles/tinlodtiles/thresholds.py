# SPDX-License-Identifier: GPL-3.0-or-later
"""One importance threshold per level for the whole raster, from every tile's survey.

A tile alone deletes at each level a share of its own vertices: smooth tiles keep vertices a
run over the whole raster would delete, rough tiles lose vertices it would keep. The surveys
(`tinlod build -survey`) say how many candidates of each importance every tile had at each
level and how many of those it could take (independence blocks the others); the threshold
of a level is the importance below which the tiles' candidates, so thinned, make the delete
percentage of all the raster's vertices, as a whole run's best-first selection would. Each
tile is followed through the levels at the count the thresholds leave it, its state read
from its survey at that count (SurveyedTile). In the threshold's own bin (a flat area's
ties), a share of its candidates may go.
"""
import json

import numpy as np

from .importance_bins import BINS_PER_DECADE, LOWEST, Bins, BinsSum, added, bin_top
from .surveyed_tile import SurveyedTile, compact

# The catalogue's record that a threshold's share (t:s) is the share of its bin's candidates
# deleted (tinlod build since 2026-11-28), not of those the pick went through.
SHARES_SETTING = "TINLOD_THRESHOLD_SHARES"
SHARES_DELETED = "deleted"


def load_survey(path, store=None):
    """A tile's survey (tinlod build -survey's JSON), checked to have this tinlod's bins, its
    levels' histograms held as Bins, or put in `store` (a SurveyStore: a driver holds
    thousands of surveys)."""
    with open(path) as f:
        survey = json.load(f)
    if survey.get("bins_per_decade") != BINS_PER_DECADE or survey.get("lowest") != LOWEST:
        raise ValueError("%s was written by another tinlod (bins %s): survey again" % (path, survey.get("bins_per_decade")))
    survey["levels"] = [compact(r, store) for r in survey.get("levels", [])]
    return survey


def read_survey(path):
    """A survey's levels."""
    return load_survey(path)["levels"]


def level_thresholds(surveys, delete_pct, stop_pct):
    """The (threshold, share) of levels 1, 2, ... from the tiles' surveys (lists of levels):
    the level deletes the independent candidates below the threshold's bin and at most that
    share of those in it."""
    return [threshold for threshold, _ in followed_levels(surveys, delete_pct, stop_pct)]


def stop_level(surveys, delete_pct, stop_pct):
    """The level that reaches the stop (the first to delete less than the delete
    percentage), or None."""
    fractions = [fraction for _, fraction in followed_levels(surveys, delete_pct, stop_pct)]
    return next((k for k, f in enumerate(fractions) if f < delete_pct / 100.0), None)


def followed_levels(surveys, delete_pct, stop_pct):
    """Each level's (threshold, share) and the share of the union's vertices it aims at:
    the delete percentage, and at the stop level what takes the count down to the stop.
    The tiles are followed through the levels: each level aims at its share of the union's
    vertices (a line vertex two tiles hold counted once) as the thresholds before it leave
    them, less what the border rule deletes, and takes from each tile what its state there
    gives under the threshold."""
    tiles = [SurveyedTile(s, delete_pct) for s in surveys if s]
    stop = stop_pct / 100.0 * sum(t.union for t in tiles)
    out = []
    for k in range(max((len(s) for s in surveys), default=0)):
        union = sum(t.union for t in tiles)
        fraction = max(0.0, min(delete_pct / 100.0, 1 - stop / union)) if union > 0 else 0.0
        rows = [t.levels[k] if len(t.levels) > k else None for t in tiles]
        target = fraction * union - border_picked([r for r in rows if r])
        threshold, deleted = tiles_threshold(tiles, target)
        for t, picked, row in zip(tiles, deleted, rows):
            t.delete(picked, row)
        out.append((threshold, fraction))
    return out


def tiles_threshold(tiles, target):
    """The (threshold, share) of a level whose deletions from the tiles (SurveyedTile) reach
    `target`, and each tile's deletions under it. A tile's state is read twice, added up
    and then in the threshold's bin, not held: a driver follows tens of thousands."""
    counts, picks = BinsSum(), BinsSum()
    for t in tiles:
        c, p = t.state()
        counts.add(c)
        picks.add(p)
    top, needed = bin_reaching(counts.bins(), picks.bins(), target)
    # Per tile: its picks below the threshold's bin, and its picks and candidates in it.
    figures = [in_bin(*t.state(), top) for t in tiles]
    share = 1.0 if needed is None else share_reaching([(n, p) for _, p, n in figures], needed)
    threshold = (bin_top(top), share) if top >= 0 else (0.0, 1.0)
    return threshold, [below + min(p, share * n) for below, p, n in figures]


def in_bin(counts, picks, top):
    """A state's (picks below bin `top`, picks in it, candidates in it); none below bin -1."""
    if top < 0:
        return 0.0, 0.0, 0.0
    return float(picks.on(0, top).sum()), picks.get(top), counts.get(top)


def union_vertices(rows):
    """The levels' vertices as their union counts them (a vertex two tiles share once); the
    tiles' own counts where a survey has no union count (an earlier tinlod's)."""
    return sum(r.get("union_vertices", r["vertices"]) for r in rows)


def border_picked(rows):
    """The border rule's picks as the union counts them. They go beside the tiles' own picks,
    which the threshold sets: aimed at the whole share, a level deleted them on top of it."""
    return sum(r.get("border_picked", 0) for r in rows)


def exact_stop_thresholds(values, second, stop_pct, walked, delete_pct=100.0):
    """-exact_stop: `values` with the level that reaches the stop set from a second round of
    surveys, made with `values` below the stop level they aim at (the build pass's very
    state there) and every candidate walked at it (level index `walked`): the first level
    whose picks would take the union below the stop deletes only what is above it (its
    picks' bins, best first; at most the delete percentage of its vertices, as a whole
    run's levels), and the levels after it nothing."""
    stop = stop_pct / 100.0 * union_vertices([s[0] for s in second if s])
    for k in range(walked + 1):
        rows = [s[k] for s in second if len(s) > k]
        # The border rule's picks below the walked level are the build pass's; at it, they
        # passed an infinite threshold, not the one set here: at most those go beside the
        # level's own, which then end at the stop or a little above it.
        vertices = union_vertices(rows) - border_picked(rows)
        if not rows or vertices - sum(r["picked"] for r in rows) <= stop or k == walked:
            break
    # The border rule's picks count toward the delete percentage, as in a level of followed_levels.
    target = max(0.0, min(vertices - stop, delete_pct / 100.0 * union_vertices(rows) - border_picked(rows)))
    def per_tile():  # each tile's (candidates, picks), read as they are needed, not held
        return ((Bins.of(r.get("histogram", [])), Bins.of(r.get("picked_histogram", []))) for r in rows)
    stop_threshold = threshold_reaching(added(c for c, _ in per_tile()), added(p for _, p in per_tile()), target,
                                        per_tile())
    return values[:k] + [stop_threshold] + [(0.0, 1.0)] * (len(values) - k - 1)


def threshold_reaching(counts, picks, target, tiles=None):
    """The (threshold, share) whose deletions reach `target`: the bin where the picks of the
    bins up to it (`picks`, Bins) do, and the share of that bin's candidates (`counts`)
    still needed (a flat area's ties share the rest). Each tile deletes at most its own
    picks of the bin, so with `tiles` (each tile's (counts, picks)) the share is the one
    whose deletions, so capped tile by tile, add up to what is needed."""
    top, needed = bin_reaching(counts, picks, target)
    if top < 0:
        return 0.0, 1.0
    if needed is None:
        return bin_top(top), 1.0
    if tiles is None:
        return bin_top(top), min(1.0, max(0.0, needed / counts.get(top)))
    return bin_top(top), share_reaching([(c.get(top), p.get(top)) for c, p in tiles], needed)


def bin_reaching(counts, picks, target):
    """The bin where the picks of the bins up to it reach `target` (-1: no bin needed, or
    none has candidates), and what is still needed from its candidates (None: all of them,
    the picks of every bin falling short)."""
    if target <= 0:
        return -1, None
    lo, hi = 0 if counts.zero else counts.lo, counts.hi
    candidates = counts.on(lo, hi)
    held = np.flatnonzero(candidates)  # the bins with candidates, in order
    if not len(held):
        return -1, None
    taken = picks.on(lo, hi)[held]
    reached = np.flatnonzero(np.cumsum(taken) >= target)
    if not len(reached):
        return lo + int(held[-1]), None
    k = int(reached[0])
    return lo + int(held[k]), target - float(taken[:k].sum())


def share_reaching(bins, needed):
    """The share s of a bin's candidates with sum over tiles of min(picks, s x candidates)
    = needed (bins: each tile's (candidates, picks) in it): the tiles whose picks run out
    first stop adding."""
    bins = sorted((p / n, n, p) for n, p in bins if n > 0 and p > 0)
    capped, open_candidates = 0.0, sum(n for _, n, _ in bins)
    for ratio, n, p in bins:
        # Below this ratio every tile still open deletes s x its candidates.
        if capped + ratio * open_candidates >= needed:
            break
        capped += p
        open_candidates -= n
    if open_candidates <= 0:
        return 1.0
    return min(1.0, max(0.0, (needed - capped) / open_candidates))


def as_option(thresholds):
    """The value of tinlod build's -level_thresholds."""
    return ",".join("%.17g" % t if share >= 1 else "%.17g:%.6f" % (t, share) for t, share in thresholds)
