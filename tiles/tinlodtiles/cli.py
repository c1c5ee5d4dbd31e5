# SPDX-License-Identifier: GPL-3.0-or-later
"""tinlod-tiles' command line: parse, run, and report a failure once (exit 1, "ERROR: ...")."""
import os
import signal
import subprocess
import sys

from osgeo import gdal, ogr

from .arguments import HELP, find_tinlod, parse_merge, parse_run
from .errors import TilesError
from .terminal_stream import guard_terminal_streams

STOPPED_EXIT_CODE = 130  # as a shell reports a run ended by Ctrl-C


def main(args):
    if not args or args[0] in ("--help", "-h") or args[:2] in (["merge", "--help"], ["merge", "-h"]):
        sys.stdout.write(HELP)
        return 0 if args else 1
    if args == ["--version"]:
        return version()
    gdal.UseExceptions()
    ogr.UseExceptions()
    guard_terminal_streams(sys)
    stop_as_ctrl_c(signal.SIGTERM, signal.SIGHUP)
    # A shell starts a script's background job with SIGINT ignored, and Python then raises no
    # KeyboardInterrupt: caught as tinlod catches it, so that `kill -INT` stops both alike.
    if signal.getsignal(signal.SIGINT) == signal.SIG_IGN:
        signal.signal(signal.SIGINT, signal.default_int_handler)
    merging, arguments = args[0] == "merge", None
    try:
        if merging:
            return merge(parse_merge(args[1:]))
        arguments = parse_run(args)
        return run(arguments)
    except TilesError as e:
        print("ERROR: %s" % e, file=sys.stderr)
        return 1
    except KeyboardInterrupt:  # outside the tiles' loop: a catalogue holds what finished
        print("ERROR: stopped before the end; %s" % what_stays(merging, arguments), file=sys.stderr)
        return STOPPED_EXIT_CODE
    except RuntimeError as e:  # GDAL's own errors
        print("ERROR: %s" % e, file=sys.stderr)
        return 1


def what_stays(merging, arguments):
    """After a stop outside the tiles' loop: a stop during the checks (a -scheduler that does
    not answer takes 20 s) made no catalogue to resume from."""
    if merging:
        return "nothing was written (OUT is as it was)"
    if arguments is None or not os.path.exists(arguments.catalogue):
        return "nothing was written"
    return "run again to resume: the catalogue keeps the tiles finished"


def stop_as_ctrl_c(*signals):
    """A batch scheduler's stop (SIGTERM) and a closed terminal (SIGHUP) stop a run as Ctrl-C
    does, as they stop tinlod: the tiles' tinlods ended, the catalogue's level files written,
    exit 130. By default they would end the driver alone, its tasks' tinlods left running.
    nohup's SIGHUP stays ignored: the run must outlive its terminal."""
    def stop(signum, frame):
        for s in signals:  # one stop: a second signal (a hangup comes twice) must not cut the cleanup short
            signal.signal(s, signal.SIG_IGN)
        raise KeyboardInterrupt
    for s in signals:
        if not (s == signal.SIGHUP and signal.getsignal(s) == signal.SIG_IGN):
            signal.signal(s, stop)


def version():
    """tinlod-tiles runs the tinlod it finds: its version is that tinlod's."""
    try:
        tinlod = find_tinlod(None)
    except TilesError as e:
        print("tinlod-tiles (%s)" % e)
        return 1
    found = subprocess.run([tinlod, "--version"], capture_output=True, text=True)
    print("tinlod-tiles, running %s (%s)" % (found.stdout.strip() or "an unknown tinlod", tinlod))
    return found.returncode


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
