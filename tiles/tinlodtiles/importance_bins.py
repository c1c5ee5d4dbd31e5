# SPDX-License-Identifier: GPL-3.0-or-later
"""The bins of importance a survey counts its candidates in (tinlod build -survey): 1/200 of
a decade each, from 1e-12, bin 0 holding everything below."""

BINS_PER_DECADE = 200
LOWEST = 1e-12


def bin_top(b):
    """The smallest importance above every importance in bin b."""
    return LOWEST if b == 0 else 10.0 ** (b / BINS_PER_DECADE - 12)
