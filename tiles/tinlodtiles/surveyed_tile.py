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

from .importance_bins import BINS_PER_DECADE, bin_top

# A survey level that deleted less than this share of what the delete percentage asks
# (the tile's own stop level) walked only its least important candidates: its blocking is
# no guide beyond them.
FULL_LEVEL = 0.75


class SurveyedTile:
    def __init__(self, levels, delete_pct):
        self.levels = levels
        self.vertices = float(levels[0]["vertices"])  # its own count, as the build pass goes
        self.union = float(levels[0].get("union_vertices", levels[0]["vertices"]))  # its part of the union's
        full = [r for r in levels if r["vertices"] > 0
                and r["picked"] + own_border(levels, r) >= FULL_LEVEL * delete_pct / 100.0 * r["vertices"]]
        self.full = full or levels

    def state(self):
        """(candidates, picks): bin -> count at the tile's current vertex count, from its
        survey's two levels around that count (log-interpolated, scaled to the count): the
        picks of its walk through every candidate. Below the survey's last count, its last
        level's, raised as its levels' importances rise with fewer vertices."""
        counts, picks, vertices = {}, {}, 0.0
        for row, weight in self.around():
            walked = self.walked(row)
            for b, n in row.get("histogram", []):
                counts[b] = counts.get(b, 0.0) + weight * n
                picks[b] = picks.get(b, 0.0) + weight * walked(b, n)
            vertices += weight * row["vertices"]
        scale = self.vertices / vertices if vertices else 0.0
        shift = self.rise()
        # Bin 0 holds the ties of no importance (a flat sea's), which stay so.
        return ({b + shift if b else 0: n * scale for b, n in counts.items()},
                {b + shift if b else 0: n * scale for b, n in picks.items()})

    def walked(self, row):
        """The level's picks of a bin of n candidates: its walk's through every candidate.
        A survey of an earlier tinlod walked only up to the delete percentage: beyond its
        picks' bins, the nearest full level's share of what its pick went through."""
        if "walk_histogram" in row:
            walk = dict(row["walk_histogram"])
            return lambda b, n: walk.get(b, 0)
        full = min(self.full, key=lambda r: abs(math.log(max(r["vertices"], 1) / max(row["vertices"], 1))))
        taken = full["picked"] / full["considered"] if full["considered"] else 1.0
        own = dict(row.get("picked_histogram", []))
        top = max(own) if own else -1
        return lambda b, n: own.get(b, 0) if b < top else taken * n

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


def picks_below(counts, picks, threshold, share):
    """A state's picks under (threshold, share): every bin below the threshold's, and in
    that bin the share of its candidates, as far as its picks go (a blocked candidate does
    not count against the share)."""
    total = 0.0
    for b, n in counts.items():
        if bin_top(b) < threshold:
            total += picks.get(b, 0.0)
        elif bin_top(b) == threshold:
            total += min(picks.get(b, 0.0), share * n)
    return total
