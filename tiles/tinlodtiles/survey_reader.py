# SPDX-License-Identifier: GPL-3.0-or-later
"""The driver's surveys: each read once, as its task ends, into what setting the thresholds
needs (the levels' figures, their histograms in a SurveyStore) and the line cells it lists."""
from . import line_outline, thresholds


class SurveyReader:
    """The surveys' levels, read once each (their histograms into a SurveyStore), and the
    line cells they list."""

    def __init__(self, store):
        self.store, self.read, self.cells = store, {}, set()

    def load(self, tile, path):
        survey = thresholds.load_survey(path, self.store)
        self.cells |= line_outline.survey_cells(survey, path)
        self.read[tile] = survey["levels"]

    def levels(self, tile, path):
        if tile not in self.read:
            self.load(tile, path)
        return self.read[tile]
