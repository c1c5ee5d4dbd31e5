# SPDX-License-Identifier: GPL-3.0-or-later
"""tinlod-tiles' command line: parse, run, and report a failure once (exit 1, "ERROR: ...")."""
import sys

from osgeo import gdal, ogr

from .arguments import HELP, parse_merge, parse_run
from .errors import TilesError

STOPPED_EXIT_CODE = 130  # as a shell reports a run ended by Ctrl-C


def main(args):
    if not args or args[0] in ("--help", "-h"):
        sys.stdout.write(HELP)
        return 0 if args else 1
    gdal.UseExceptions()
    ogr.UseExceptions()
    try:
        if args[0] == "merge":
            return merge(parse_merge(args[1:]))
        return run(parse_run(args))
    except TilesError as e:
        print("ERROR: %s" % e, file=sys.stderr)
        return 1
    except KeyboardInterrupt:  # outside the tiles' loop: the catalogue holds what finished
        print("ERROR: stopped before the end; the catalogue keeps the tiles finished so far: run again to "
              "resume", file=sys.stderr)
        return STOPPED_EXIT_CODE
    except RuntimeError as e:  # GDAL's own errors
        print("ERROR: %s" % e, file=sys.stderr)
        return 1


def run(arguments):
    from .driver import TilesStopped, run as run_job

    try:
        return run_job(arguments)
    except TilesStopped as e:
        count = int(str(e))
        print("ERROR: stopped before the end; %d tile%s left pending in %s: run again to finish them"
              % (count, "" if count == 1 else "s", arguments.catalogue), file=sys.stderr)
        return STOPPED_EXIT_CODE


def merge(arguments):
    from .levels import merge_level

    level, count = merge_level(arguments.catalogue, arguments.level, arguments.out, arguments.overwrite,
                               arguments.extent)
    if not arguments.quiet:
        print("%s: level_%d, %d triangles from the catalogue's tiles" % (arguments.out, level, count))
    return 0
