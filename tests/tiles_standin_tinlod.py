#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""A stand-in for `tinlod build -tile_size N -tile C,R`, for a tinlod built before the core
learnt tiles: it cuts the tile's window out of the DEM (gdal_translate -srcwin, the core's
grid), builds it with the real tinlod (TINLOD_STANDIN_REAL), and adds the core's TINLOD_TILE*
metadata. Exit 3 when the window holds no valid data, as the core does. Only the tests use it.
Usage: tiles_standin_tinlod.py build DEM OUT.gpkg -tile_size N -tile C,R [options]"""
import ctypes
import os
import signal
import subprocess
import sys
import tempfile

from osgeo import gdal, ogr

gdal.UseExceptions()


def window(width, height, tile_size, col, row):
    xoff, yoff = col * tile_size, row * tile_size
    return xoff, yoff, min(xoff + tile_size, width - 1) - xoff + 1, min(yoff + tile_size, height - 1) - yoff + 1


def take(args, name):
    i = args.index(name)
    value = args[i + 1]
    del args[i : i + 2]
    return value


def has_valid_data(path):
    dataset = gdal.Open(path)  # held: the band dies with it
    try:
        dataset.GetRasterBand(1).ComputeRasterMinMax(False)
        return True
    except RuntimeError:  # every cell nodata
        return False


def die_with_parent():
    """The real tinlod ends with the stand-in, as the core would when killed."""
    ctypes.CDLL(None).prctl(1, signal.SIGKILL)  # PR_SET_PDEATHSIG


def main(args):
    real = os.environ["TINLOD_STANDIN_REAL"]
    if args[:1] != ["build"] or "-tile" not in args:
        os.execv(real, [real] + args)
    args = args[1:]
    tile_size, tile = int(take(args, "-tile_size")), take(args, "-tile")
    dem, out, options = args[0], args[1], args[2:]
    col, row = (int(v) for v in tile.split(","))
    source = gdal.Open(dem)
    win = window(source.RasterXSize, source.RasterYSize, tile_size, col, row)
    with tempfile.TemporaryDirectory() as work:
        cut = os.path.join(work, "tile.tif")
        gdal.Translate(cut, source, srcWin=list(win))
        if not has_valid_data(cut):
            return 3
        code = subprocess.call([real, "build", cut, out] + options, preexec_fn=die_with_parent)
    if code != 0:
        return code
    target = ogr.Open(out, update=1)
    for key, value in (("TINLOD_TILE", tile), ("TINLOD_TILE_SIZE", str(tile_size)),
                       ("TINLOD_TILE_WINDOW", "%d,%d,%d,%d" % win),
                       ("TINLOD_RASTER_SIZE", "%d,%d" % (source.RasterXSize, source.RasterYSize))):
        target.SetMetadataItem(key, value)
    target = None
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
