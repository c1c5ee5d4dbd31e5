#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""tinlod-tiles: a DEM of any size built as tiles by Dask, listed in a catalogue GeoPackage.

Debian's Python on purpose: it has GDAL's bindings (python3-gdal) and Dask
(python3-distributed). The modules are beside this script (source and build trees) or in
share/tinlod/tiles of the install prefix.
"""
import os
import sys


def module_folder():
    here = os.path.dirname(os.path.realpath(__file__))
    for folder in (here, os.path.join(here, "..", "share", "tinlod", "tiles")):
        if os.path.isdir(os.path.join(folder, "tinlodtiles")):
            return os.path.normpath(folder)
    sys.exit("ERROR: the tinlodtiles modules are neither beside %s nor in ../share/tinlod/tiles" % __file__)


if __name__ == "__main__":
    sys.path.insert(0, module_folder())
    from tinlodtiles.cli import main

    sys.exit(main(sys.argv[1:]))
