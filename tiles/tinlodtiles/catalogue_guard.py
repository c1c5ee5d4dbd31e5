# SPDX-License-Identifier: GPL-3.0-or-later
"""What the catalogue's name may replace: never an input of the job, never a file that is
something else (a DEM, a GeoPackage of the user's), never a GeoPackage another program has
open. -overwrite removes the catalogue before the job writes a new one."""
import os
import sqlite3

from osgeo import gdal

from .arguments import build_option, layer_spec
from .errors import TilesError


def check(catalogue_path, dem, build_options, overwrite):
    """TilesError before anything is written, when the catalogue may not be written there."""
    refuse_input(catalogue_path, dem, build_options)
    if overwrite and os.path.exists(catalogue_path):
        refuse_in_use(catalogue_path)
        refuse_other_kind(catalogue_path)


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


def refuse_other_kind(catalogue_path):
    """A catalogue, or a file no GDAL driver opens (a damaged catalogue, which -overwrite is
    there to replace); a DEM or a GeoPackage of something else is someone's data."""
    dataset = open_any(catalogue_path, gdal.OF_VECTOR | gdal.OF_RASTER)
    if dataset is None or dataset.GetMetadataItem("TINLOD_KIND") == "catalogue":
        return
    raise TilesError("%s exists and is no tinlod-tiles catalogue (GDAL reads it as %s): -overwrite replaces only a "
                     "catalogue; name another file, or remove it first" % (catalogue_path, dataset.GetDriver().ShortName))


def open_any(path, flags):
    """The dataset at `path`, or None where GDAL opens none (its exceptions are on)."""
    try:
        return gdal.OpenEx(path, flags)
    except RuntimeError:
        return None


def refuse_in_use(catalogue_path):
    """SQLite's write-ahead log beside a GeoPackage belongs to it: a new file in its place
    would be read with the old log, corrupt. One left by a program that ended is played
    back by reading the file once; one still in use is another program's."""
    wal = catalogue_path + "-wal"
    if not os.path.exists(wal):
        return
    try:
        connection = sqlite3.connect(catalogue_path, timeout=0)
        try:
            connection.execute("SELECT count(*) FROM sqlite_master").fetchone()
        finally:
            connection.close()
    except sqlite3.Error:
        pass  # the test below says what matters
    if os.path.exists(wal):
        raise TilesError("%s is open in another program (QGIS, with its layers loaded for editing, or a script), its "
                         "write-ahead log %s in use (a file put in its place would be read with it, corrupt): close "
                         "it there, then run again" % (catalogue_path, os.path.basename(wal)))
