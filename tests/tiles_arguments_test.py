#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""tiles/tinlodtiles/arguments.py: the build options tinlod-tiles passes to every task.

Usage: tiles_arguments_test.py TILES_SOURCE_DIR"""
import os
import sys

sys.path.insert(0, sys.argv[1])
from tinlodtiles.arguments import absolute_files  # noqa: E402
from script_checks import check, exit_code  # noqa: E402

here = os.getcwd()
given = ["-seed", "5", "-fixed", "sub/points.gpkg", "-delete_pct", "25"]
check("a -fixed file named from the current folder is passed as an absolute path, the rest as given",
      absolute_files(given) == ["-seed", "5", "-fixed", os.path.join(here, "sub/points.gpkg"), "-delete_pct", "25"],
      absolute_files(given))
check("a GDAL virtual path is passed as given",
      absolute_files(["-fixed", "/vsicurl/https://example.com/p.gpkg"]) == ["-fixed", "/vsicurl/https://example.com/p.gpkg"])
check("-fixed without its value is left for tinlod to refuse", absolute_files(["-fixed"]) == ["-fixed"])

sys.exit(exit_code("tiles arguments"))
