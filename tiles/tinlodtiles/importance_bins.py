# SPDX-License-Identifier: GPL-3.0-or-later
"""The bins of importance a survey counts its candidates in (tinlod build -survey): 1/200 of
a decade each, from 1e-12, bin 0 holding everything below."""
import itertools
import math

import numpy as np

BINS_PER_DECADE = 200
LOWEST = 1e-12


def bin_top(b):
    """The smallest importance above every importance in bin b."""
    return LOWEST if b == 0 else 10.0 ** (b / BINS_PER_DECADE - 12)


class Bins:
    """Counts by bin: bin 0's (the ties of no importance) apart, the others over a run of
    bins from `lo` (1 or more) in one array. A driver holds every tile's survey, thousands of
    them, each level's histograms a thousand bins or more, which as Python dicts took 2.7 MB
    a tile; bin 0 apart, no array spans the empty bins between it and the others."""

    __slots__ = ("zero", "lo", "values")

    def __init__(self, zero, lo, values):
        self.zero, self.lo, self.values = zero, lo, values

    @staticmethod
    def of(pairs):
        """From a survey's [[bin, count], ...], in 16 bits where every count fits (float32
        holds any count a tile can have exactly); Bins as they are, and stored ones read back."""
        if isinstance(pairs, Bins):
            return pairs
        if hasattr(pairs, "load"):  # a SurveyStore's StoredBins
            return pairs.load()
        flat = np.fromiter(itertools.chain.from_iterable(pairs), np.float64, 2 * len(pairs))
        bins, counts = flat[0::2].astype(np.int64), flat[1::2]
        zero = float(counts[bins == 0].sum())
        bins, counts = bins[bins > 0], counts[bins > 0]
        if not len(bins):
            return Bins(zero, 1, np.zeros(0, np.uint16))
        lo = int(bins.min())
        whole = np.all(counts == np.floor(counts)) and counts.max() < 2 ** 16
        values = np.zeros(int(bins.max()) - lo + 1, np.uint16 if whole else np.float32)
        values[bins - lo] = counts
        return Bins(zero, lo, values)

    @property
    def hi(self):
        """One past the last bin."""
        return self.lo + len(self.values)

    def get(self, b):
        if b == 0:
            return self.zero
        return float(self.values[b - self.lo]) if self.lo <= b < self.hi else 0.0

    def on(self, lo, hi):
        """The counts over bins lo to hi - 1 (0 where there are none), as float64."""
        out = np.zeros(max(0, hi - lo))
        if lo <= 0 < hi:
            out[-lo] = self.zero
        a, b = max(lo, self.lo), min(hi, self.hi)
        if a < b:
            out[a - lo:b - lo] = self.values[a - self.lo:b - self.lo]
        return out

    def shifted(self, shift):
        """The bins raised by `shift`, bin 0 staying."""
        return Bins(self.zero, self.lo + shift, self.values) if shift else self

    def as_dict(self):
        """{bin: count} of the bins with a count."""
        out = {0: self.zero} if self.zero else {}
        out.update({self.lo + int(i): float(self.values[i]) for i in np.flatnonzero(self.values)})
        return out


def added(histograms, weights=None):
    """Bins added up (each times its weight, when given), over the run of bins they span;
    `histograms` may be a generator, read once (a driver's thousands of tiles' states need
    not be held at once)."""
    total = BinsSum()
    for i, h in enumerate(histograms):
        total.add(h, 1.0 if weights is None else weights[i])
    return total.bins()


class BinsSum:
    """Bins added one at a time: the run of bins grows to span them."""

    def __init__(self):
        self.zero, self.lo, self.total = 0, 1, None

    def add(self, h, weight=1.0):
        self.zero += weight * h.zero
        if not len(h.values):
            return
        if self.total is None:
            self.lo, self.total = h.lo, np.zeros(len(h.values))
        elif h.lo < self.lo or h.hi > self.lo + len(self.total):
            lo, hi = min(h.lo, self.lo), max(h.hi, self.lo + len(self.total))
            grown = np.zeros(hi - lo)
            grown[self.lo - lo:self.lo - lo + len(self.total)] = self.total
            self.lo, self.total = lo, grown
        self.total[h.lo - self.lo:h.hi - self.lo] += weight * h.values.astype(np.float64)  # as stored, w x values stays 32 bits

    def bins(self):
        return Bins(self.zero, self.lo, self.total if self.total is not None else np.zeros(0))
