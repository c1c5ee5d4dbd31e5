# SPDX-License-Identifier: GPL-3.0-or-later
"""The border lines' cells on the outline of a tile's level 0, gathered for the build pass.

A line cell near nodata may sit where one tile's level 0 meets the line through a hole, which
the tile beyond cannot see: such a cell stays at every level in both tiles. Each tile's
survey lists its own (line_outline); the union goes into one file that every tile of the
build pass reads (tinlod build -line_outline), so the two tiles of a line keep the same
cells. Without it a tile keeps every line cell within 3 blocks of a missing cell, which
costs accuracy on DEMs with voids or sea (a tiled run's coarse levels were up to 22 % worse
than a whole run's on swiss_alps as 16 tiles, 4 % with the list).
"""
import hashlib
import os

from .errors import TilesError
from .thresholds import load_survey

NAME = "line_outline.txt"
SETTING = "TINLOD_LINE_OUTLINE"  # the catalogue's record that the tiles are built with the file
DIGEST = "TINLOD_LINE_OUTLINE_SHA256"  # and of what it held


def digest(file_path):
    with open(file_path, "rb") as f:
        return hashlib.sha256(f.read()).hexdigest()


def path(folder):
    return os.path.join(folder, NAME)


def survey_cells(survey, survey_path):
    """The line cells one survey (its JSON, loaded from `survey_path`) lists, as (row, col) of
    the whole raster."""
    if "line_outline" not in survey:
        raise TilesError("%s was written by an older tinlod (no line_outline): run again with -overwrite" % survey_path)
    return {(int(row), int(col)) for row, col in survey["line_outline"]}


def gather(survey_paths):
    """The line cells the surveys at these paths list."""
    cells = set()
    for survey_path in survey_paths:
        cells |= survey_cells(load_survey(survey_path), survey_path)
    return cells


def build_option(catalogue, folder):
    """The build pass's -line_outline, when the job's surveys listed the cells; none for a job
    begun by a tinlod-tiles that did not (its tiles keep every line cell near nodata, and the
    rest must do the same). A lost file cannot be made again without the surveys."""
    if not catalogue.setting(SETTING):
        return []
    if not os.path.isfile(path(folder)):
        raise TilesError("%s is gone: the job's tiles were built with it (the line cells they keep) and it cannot be "
                         "made again; run again with -overwrite to build every tile anew" % path(folder))
    recorded = catalogue.setting(DIGEST)  # absent in a catalogue of an earlier tinlod-tiles
    if recorded and digest(path(folder)) != recorded:
        raise TilesError("%s has changed since the job's tiles were built with it (the line cells they keep), and the "
                         "job's list cannot be made again; run again with -overwrite to build every tile anew"
                         % path(folder))
    return ["-line_outline", os.path.abspath(path(folder))]
