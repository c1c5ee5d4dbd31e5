# SPDX-License-Identifier: GPL-3.0-or-later
"""A tile followed through the build pass's levels, read from its survey at its vertex count.

In the build pass a tile deletes what the raster's thresholds take, not a fifth of its own
vertices a level: a smooth tile ends a level with fewer vertices than its survey did, a
rough one with more. Both delete their least important vertices first, so a tile's state
in the build pass is much like its survey's state at the same vertex count, at whatever
level the survey reached it: its candidates by importance, and how many of those a pick
takes (independence blocks the others). The thresholds are set from those states.
"""
import math

import numpy as np

from .importance_bins import BINS_PER_DECADE, Bins, added

# A survey level that deleted less than this share of what the delete percentage asks
# (the tile's own stop level) walked only its least important candidates: its blocking is
# no guide beyond them.
FULL_LEVEL = 0.75


HISTOGRAMS = ("histogram", "picked_histogram", "walk_histogram")


def compact(row, store=None):
    """A survey level with its histograms as Bins (or, with a SurveyStore, as its handles);
    the tile's own picks only where the level has no walk through every candidate, which
    alone is read then. A compact row as it is."""
    if not any(isinstance(row[k], list) for k in HISTOGRAMS if k in row) and not (
            "walk_histogram" in row and "picked_histogram" in row):
        return row
    out = dict(row)
    if "walk_histogram" in out:
        out.pop("picked_histogram", None)
    for key in HISTOGRAMS:
        if key in out:
            out[key] = Bins.of(out[key]) if store is None else store.put(Bins.of(out[key]))
    return out


class SurveyedTile:
    def __init__(self, levels, delete_pct):
        levels = [compact(r) for r in levels]
        self.levels = levels
        self.vertices = float(levels[0]["vertices"])  # its own count, as the build pass goes
        self.union = float(levels[0].get("union_vertices", levels[0]["vertices"]))  # its part of the union's
        full = [r for r in levels if r["vertices"] > 0
                and r["picked"] + own_border(levels, r) >= FULL_LEVEL * delete_pct / 100.0 * r["vertices"]]
        self.full = full or levels

    def state(self):
        """(candidates, picks): Bins at the tile's current vertex count, from its survey's two
        levels around that count (log-interpolated, scaled to the count): the picks of its
        walk through every candidate. Below the survey's last count, its last level's,
        raised as its levels' importances rise with fewer vertices."""
        around = self.around()
        rows = [row for row, _ in around]
        weights = [weight for _, weight in around]
        vertices = sum(w * r["vertices"] for r, w in around)
        scale = self.vertices / vertices if vertices else 0.0
        counts = added([Bins.of(r.get("histogram", [])) for r in rows], [w * scale for w in weights])
        picks = added([self.walked(r) for r in rows], [w * scale for w in weights])
        shift = self.rise()
        return counts.shifted(shift), picks.shifted(shift)

    def walked(self, row):
        """The level's picks by bin: its walk's through every candidate. A survey of an
        earlier tinlod walked only up to the delete percentage: beyond its picks' bins, the
        nearest full level's share of what its pick went through."""
        if "walk_histogram" in row:
            return Bins.of(row["walk_histogram"])
        full = min(self.full, key=lambda r: abs(math.log(max(r["vertices"], 1) / max(row["vertices"], 1))))
        taken = full["picked"] / full["considered"] if full["considered"] else 1.0
        counts, own = Bins.of(row.get("histogram", [])), Bins.of(row.get("picked_histogram", []))
        top = own.hi - 1 if len(own.values) else (0 if own.zero else -1)
        picks = counts.values.astype(np.float64) * taken
        below = np.arange(counts.lo, counts.hi) < top
        picks[below] = own.on(counts.lo, counts.hi)[below]
        return Bins(own.zero if top > 0 else taken * counts.zero, counts.lo, picks)

    def around(self):
        """The survey's levels around the current count, with their weights."""
        counts = [max(r["vertices"], 1) for r in self.levels]
        if self.vertices >= counts[0]:
            return [(self.levels[0], 1.0)]
        if self.vertices <= counts[-1]:
            return [(self.levels[-1], 1.0)]
        j = next(i for i in range(len(counts) - 1) if counts[i] >= self.vertices >= counts[i + 1])
        if counts[j] == counts[j + 1]:
            return [(self.levels[j], 1.0)]
        weight = math.log(self.vertices / counts[j + 1]) / math.log(counts[j] / counts[j + 1])
        return [(self.levels[j], weight), (self.levels[j + 1], 1.0 - weight)]

    def rise(self):
        """Bins to raise the last level's importances by, below the survey's last count: as
        the importance of its last picks rose with fewer vertices over its last two full
        levels (a power law)."""
        last = self.levels[-1]["vertices"]
        if self.vertices >= last or self.vertices <= 0 or len(self.full) < 2:
            return 0
        a, b = self.full[-2], self.full[-1]
        if not (a["last"] > 0 and b["last"] > 0 and a["vertices"] > b["vertices"]):
            return 0
        slope = math.log(b["last"] / a["last"]) / math.log(b["vertices"] / a["vertices"])
        return max(0, int(round(BINS_PER_DECADE * slope * math.log10(self.vertices / last))))

    def delete(self, picked, row):
        """The level's deletions: `picked` of its own, and the border rule's as its survey's
        level made them (the border rule goes by level number)."""
        self.vertices = max(0.0, self.vertices - picked - (own_border(self.levels, row) if row else 0))
        self.union = max(0.0, self.union - picked - (row.get("border_picked", 0) if row else 0))


def own_border(levels, row):
    """The line vertices the survey's level deleted, as the tile counts them."""
    k = levels.index(row)
    return max(0, row["vertices"] - row["picked"] - levels[k + 1]["vertices"]) if k + 1 < len(levels) else 0

