# SPDX-License-Identifier: GPL-3.0-or-later
"""One importance threshold per level for the whole raster, from every tile's survey.

A tile alone deletes at each level a share of its own vertices: smooth tiles keep vertices a
run over the whole raster would delete, rough tiles lose vertices it would keep. The surveys
(`tinlod build -survey`) say how many candidates of each importance every tile had at each
level and how many of those it could take (independence blocks the others); the threshold of
a level is the importance below which the tiles' candidates, so thinned, make the delete
percentage of all the raster's vertices, as a whole run's best-first selection would.
"""
import json

BINS_PER_DECADE = 200
LOWEST = 1e-12


def bin_top(b):
    """The smallest importance above every importance in bin b."""
    return LOWEST if b == 0 else 10.0 ** (b / BINS_PER_DECADE - 12)


def load_survey(path):
    """A tile's survey (tinlod build -survey's JSON), checked to have this tinlod's bins."""
    with open(path) as f:
        survey = json.load(f)
    if survey.get("bins_per_decade") != BINS_PER_DECADE or survey.get("lowest") != LOWEST:
        raise ValueError("%s was written by another tinlod (bins %s): survey again" % (path, survey.get("bins_per_decade")))
    return survey


def read_survey(path):
    """A survey's levels."""
    return load_survey(path)["levels"]


def level_thresholds(surveys, delete_pct, stop_pct):
    """The (threshold, share) of levels 1, 2, ... from the tiles' surveys (lists of levels):
    the level deletes the candidates below the threshold's bin and that share of those in
    it."""
    levels = max(len(s) for s in surveys)
    original = sum(s[0]["vertices"] for s in surveys if s)
    stop = stop_pct / 100.0 * original
    thresholds = []
    for k in range(levels):
        rows = [s[k] for s in surveys if len(s) > k]
        counts = {}
        for r in rows:
            for b, n in r["histogram"]:
                counts[b] = counts.get(b, 0) + n
        vertices = sum(r["vertices"] for r in rows)
        picked, considered = sum(r["picked"] for r in rows), sum(r["considered"] for r in rows)
        taken = picked / considered if considered else 1.0  # the share of candidates independence lets through
        target = max(0.0, min(delete_pct / 100.0 * vertices, vertices - stop))
        threshold, share, seen = 0.0, 1.0, 0
        if target > 0:
            for b in sorted(counts):
                threshold = bin_top(b)
                if taken * (seen + counts[b]) >= target:
                    # Only part of this bin's candidates: a flat area's ties share the rest.
                    share = min(1.0, max(0.0, (target / taken - seen) / counts[b]))
                    break
                seen += counts[b]
        thresholds.append((threshold, share))
    return thresholds


def as_option(thresholds):
    """The value of tinlod build's -level_thresholds."""
    return ",".join("%.17g" % t if share >= 1 else "%.17g:%.6f" % (t, share) for t, share in thresholds)
