#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""tiles/tinlodtiles/catalogue.py: a catalogue that cannot be written whole leaves nothing;
a rerun is refused when a file the finished tiles were built from (the DEM, the -fixed
points) has changed, and accepted by a catalogue that recorded no stamp for it.

Usage: catalogue_test.py TILES_SOURCE_DIR"""
import os
import sys
import tempfile

sys.path.insert(0, sys.argv[1])
from tinlodtiles import catalogue as catalogue_module  # noqa: E402
from tinlodtiles.catalogue import FIXED_STAMP, SOURCE_STAMP, Catalogue, file_stamp  # noqa: E402
from tinlodtiles.errors import TilesError  # noqa: E402
from tinlodtiles.grid import tile_grid  # noqa: E402
from script_checks import check, exit_code  # noqa: E402


def settings(folder, options, dem_stamp, fixed_stamp):
    return {"TINLOD_SOURCE": os.path.join(folder, "dem.tif"), "TINLOD_TILE_SIZE": "150",
            "TINLOD_BUILD_OPTIONS": options, "TINLOD_RASTER_SIZE": "400,300", "TINLOD_SELECTION": "global",
            SOURCE_STAMP: dem_stamp, FIXED_STAMP: fixed_stamp}


def refusal(catalogue, given, path):
    try:
        catalogue.check_same_job(given, path, None)
    except TilesError as e:
        return str(e)
    return None


with tempfile.TemporaryDirectory() as folder:
    points = os.path.join(folder, "points.csv")
    with open(points, "w") as f:
        f.write("x,y\n10,20\n")
    stamp = file_stamp(points)
    check("a file's stamp is its bytes and time of change", stamp.startswith("10 bytes, changed "), stamp)
    check("a GDAL virtual path has no stamp", file_stamp("/vsicurl/https://example.com/p.csv") == "")

    options = "-fixed " + points
    path = os.path.join(folder, "c.gpkg")
    tiles = tile_grid(400, 300, 150)
    made = Catalogue.create(path, settings(folder, options, "1 bytes", stamp), None, tiles)
    check("the catalogue records the -fixed file's stamp", made.setting(FIXED_STAMP) == stamp, made.setting(FIXED_STAMP))
    check("the same files: the rerun is accepted", refusal(made, settings(folder, options, "1 bytes", stamp), path) is None)
    with open(points, "a") as f:
        f.write("30,40\n")
    message = refusal(made, settings(folder, options, "1 bytes", file_stamp(points)), path)
    check("the -fixed file edited since: refused, naming it and -overwrite",
          message is not None and ("the -fixed file %s has changed since %s" % (points, path)) in message
          and "-overwrite" in message, message)
    message = refusal(made, settings(folder, options, "2 bytes", stamp), path)
    check("the DEM changed since: refused, naming it",
          message is not None and ("the DEM %s has changed" % os.path.join(folder, "dem.tif")) in message, message)
    made.close()

    earlier = os.path.join(folder, "earlier.gpkg")  # as an earlier tinlod-tiles made it: no stamp of -fixed
    made = Catalogue.create(earlier, settings(folder, options, "1 bytes", ""), None, tiles)
    check("a catalogue without a -fixed stamp accepts the rerun (it gets the stamp then)",
          made.setting(FIXED_STAMP) is None
          and refusal(made, settings(folder, options, "1 bytes", file_stamp(points)), earlier) is None)
    made.close()

    def failing_write(partial, *_):
        with open(partial, "w") as f:
            f.write("half")
        raise RuntimeError("the disk is full")

    real_write = catalogue_module.write_new
    catalogue_module.write_new = failing_write
    broken = os.path.join(folder, "broken.gpkg")
    try:
        Catalogue.create(broken, settings(folder, "", "1 bytes", ""), None, tiles)
        raised = False
    except RuntimeError:
        raised = True
    catalogue_module.write_new = real_write
    check("a catalogue that fails while being written leaves neither it nor its partial file",
          raised and not os.path.exists(broken) and not os.path.exists(broken + ".partial.gpkg"), os.listdir(folder))

    # A full disk at a tile's update: said as such, with what to do (SQLite said "database or
    # disk is full" of no file).
    real_usage = catalogue_module.shutil.disk_usage
    catalogue_module.shutil.disk_usage = lambda _: real_usage(folder)._replace(free=4096)
    said = catalogue_module.write_failure(path, RuntimeError("failed to execute update : database or disk is full"))
    catalogue_module.shutil.disk_usage = real_usage
    check("a full disk under the catalogue is said as such, with what to do",
          said == "the disk is full: make room and run tinlod-tiles again, which keeps the finished tiles", said)
    check("another failure keeps its own words",
          catalogue_module.write_failure(path, RuntimeError(" no such table \n")) == "no such table")

sys.exit(exit_code("catalogue"))
