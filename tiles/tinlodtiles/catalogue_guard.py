# SPDX-License-Identifier: GPL-3.0-or-later
"""What the catalogue's name may replace: never an input of the job, and with -overwrite,
which removes the catalogue before the job writes a new one, only what replace_guard allows."""
import os

from osgeo import gdal

from .arguments import build_option, layer_spec
from .errors import TilesError
from .replace_guard import check_replaceable, open_any, refuse_dangling_link


def check(catalogue_path, dem, build_options, overwrite):
    """TilesError before anything is written, when the catalogue may not be written there."""
    refuse_dangling_link(catalogue_path, "CATALOGUE")
    refuse_input(catalogue_path, dem, build_options)
    if overwrite and os.path.exists(catalogue_path):
        check_replaceable(catalogue_path, "catalogue", "tinlod-tiles catalogue", "CATALOGUE")


def input_files(dem, build_options):
    """Every file the job reads: the DEM's (its sidecars and a VRT's sources included) and
    the -fixed layer's."""
    files = list(dem.GetFileList() or [])
    fixed = build_option(build_options, "-fixed")
    if fixed:
        dataset = open_any(layer_spec(fixed)[0], gdal.OF_VECTOR)
        files += list(dataset.GetFileList() or []) if dataset else []
    return files


def refuse_input(catalogue_path, dem, build_options):
    if not os.path.exists(catalogue_path):
        return
    for name in input_files(dem, build_options):
        if os.path.exists(name) and os.path.samefile(name, catalogue_path):
            raise TilesError("%s is an input of this job (%s): the catalogue written there would destroy it; name "
                             "another catalogue" % (catalogue_path, name))
