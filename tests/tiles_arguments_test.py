#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""tiles/tinlodtiles/arguments.py: the build options tinlod-tiles passes to every task; an
argument that is not UTF-8 text, which the catalogue's metadata cannot hold, refused.

Usage: tiles_arguments_test.py TILES_SOURCE_DIR"""
import os
import re
import sys
import tempfile

sys.path.insert(0, sys.argv[1])
from tinlodtiles.arguments import absolute_files, parse_merge, parse_run  # noqa: E402
from tinlodtiles.errors import TilesError  # noqa: E402
from script_checks import check, exit_code  # noqa: E402

here = os.getcwd()
given = ["-seed", "5", "-fixed", "sub/points.gpkg", "-delete_pct", "25"]
check("a -fixed file named from the current folder is passed as an absolute path, the rest as given",
      absolute_files(given) == ["-seed", "5", "-fixed", os.path.join(here, "sub/points.gpkg"), "-delete_pct", "25"],
      absolute_files(given))
check("a GDAL virtual path is passed as given",
      absolute_files(["-fixed", "/vsicurl/https://example.com/p.gpkg"]) == ["-fixed", "/vsicurl/https://example.com/p.gpkg"])
check("-fixed without its value is left for tinlod to refuse", absolute_files(["-fixed"]) == ["-fixed"])


def refusal(parse, args):
    try:
        parse(args)
    except TilesError as e:
        return str(e)
    return None


latin1 = os.fsdecode(b"d\xe9m.tif")  # a name in Latin-1, as Python reads it from the command line
for parse, args in ((parse_run, [latin1, "c.gpkg", "-tile_size", "300"]),
                    (parse_run, ["dem.tif", "c.gpkg", "-tile_size", "300", "--", "-fixed", latin1]),
                    (parse_merge, [latin1, "-level", "0", "out.gpkg"])):
    message = refusal(parse, args)
    check("%s: a name that is not UTF-8 is refused, shown with its byte escaped, before anything else"
          % " ".join(a if a != latin1 else "d\\xe9m.tif" for a in args),
          message is not None and message.startswith("d\\xe9m.tif is not UTF-8 text") and "rename it" in message,
          message)

# Run from a folder whose name is not UTF-8: the relative names are recorded as absolute paths.
with tempfile.TemporaryDirectory() as folder:
    latin1_folder = os.path.join(folder, latin1[:-len(".tif")])
    os.mkdir(latin1_folder)
    os.chdir(latin1_folder)
    message = refusal(parse_run, ["dem.tif", "c.gpkg", "-tile_size", "300"])
    os.chdir(here)
check("a relative name in a folder whose name is not UTF-8 is refused too",
      message is not None and "d\\xe9m/dem.tif is not UTF-8 text" in message, message)

for address in ("foo", "tcp://", "host:port", "10.0.0.1"):
    message = refusal(parse_run, ["dem.tif", "c.gpkg", "-tile_size", "300", "-scheduler", address])
    check("-scheduler %s is refused before anything is written, saying what an address is" % address,
          message is not None and message.startswith("-scheduler %s: give the scheduler's address, tcp://host:port"
                                                     % address), message)
for address in ("tcp://10.0.0.1:8786", "node7:8786", "[::1]:8786", "tls://node7:8786"):
    message = refusal(parse_run, ["dem.tif", "c.gpkg", "-tile_size", "300", "-scheduler", address])
    check("-scheduler %s is an address" % address, message is None or not message.startswith("-scheduler"), message)

for size, block, least in (("0", None, 6), ("3", None, 6), ("8", "4", 8), ("5", "5", 10), ("-300", None, 6),
                           ("300.0", None, 6)):
    extra = ["--", "-block", block] if block else []
    message = refusal(parse_run, ["dem.tif", "c.gpkg", "-tile_size", size] + extra)
    refused = not re.fullmatch("[0-9]+", size) or int(size) < least
    check("-tile_size %s with -block %s is refused below two blocks or not a whole number, naming the least"
          % (size, block or 3), message is not None and (message.startswith("-tile_size %s: a tile is at least two blocks"
                                                                            % size)
                                                         and ("give a whole number, %d or more" % least) in message) == refused,
          message)
message = refusal(parse_run, ["dem.tif", "c.gpkg", "-tile_size", "abc"])
check("-tile_size abc is said to be no number", message == "-tile_size abc is not a number of cells: give a whole number, "
      "6 or more (thousands of cells make fewer, larger tiles)", message)

for option, values in (("-tile_size", ["300", "600"]), ("-workers", ["2", "1"]), ("-overwrite", [])):
    given = [option] + values[:1] + [option] + values[1:]
    message = refusal(parse_run, ["dem.tif", "c.gpkg"] + (["-tile_size", "300"] if option != "-tile_size" else []) + given)
    check("%s given twice is refused (it took the last before)" % option,
          message == "%s is given more than once" % option, message)

for threads, refused in (("abc", True), ("0", True), ("-2", True), ("", False), ("3", False)):
    os.environ["TINLOD_THREADS"] = threads
    message = refusal(parse_run, ["dem.tif", "c.gpkg", "-tile_size", "300"])
    check("TINLOD_THREADS=%s is %s before any work" % (threads, "refused" if refused else "taken"),
          (message is not None and message.startswith("TINLOD_THREADS=%s: give each tile's tinlod a whole number of "
                                                      "threads" % threads)) == refused, message)
del os.environ["TINLOD_THREADS"]

message = refusal(parse_run, ["dem.tif", "c.gpkg", "-tile_size", "300", "--", "-accuracy", "a.tif"])
check("-accuracy after -- names the fix, tinlod accuracy on the catalogue",
      message is not None and "tinlod accuracy DEM CATALOGUE.gpkg -accuracy RASTER.tif" in message, message)

with tempfile.TemporaryDirectory() as folder:
    catalogue = os.path.join(folder, "c.gpkg")
    open(catalogue, "w").close()
    message = refusal(parse_merge, [catalogue, os.path.join(folder, "out.gpkg")])
    check("merge without -level names it", message is not None and message.startswith("merge needs -level K"), message)
    for level in ("-2", "x", "1.5", "+1", " 1"):
        message = refusal(parse_merge, [catalogue, "-level", level, os.path.join(folder, "out.gpkg")])
        check("merge -level %s is refused, naming -1 for the coarsest" % level,
              message == "-level %s: give a level number, 0 or more, or -1 for the coarsest" % level, message)
    message = refusal(parse_run, [catalogue, os.path.join(folder, "c2.gpkg"), "-tile_size", "3000000000"])
    check("-tile_size beyond tinlod's whole numbers is refused by tinlod-tiles, naming the most",
          message is not None and message.startswith("-tile_size 3000000000: give at most 2147483647"), message)
    # As tinlod reads -level (std::from_chars): -0 is level 0, as locate, lod and accuracy take it.
    check("merge -level -0 is level 0, as tinlod's commands read it",
          parse_merge([catalogue, "-level", "-0", os.path.join(folder, "out.gpkg")]).level == 0)

sys.exit(exit_code("tiles arguments"))
