# SPDX-License-Identifier: GPL-3.0-or-later
"""The run: the tile grid, the catalogue, and one Dask task per unfinished tile.

The driver (this process) alone writes the catalogue, as the tasks' futures complete; the
tasks only build tile files, which appear whole or not at all. Stopped anyhow (Ctrl-C, a
killed driver), the catalogue still says which tiles are finished, and a rerun does the rest.
"""
import fcntl
import logging
import os
import re
import shlex
import signal
import socket
import sys
import threading
import time

from osgeo import gdal

from . import (agreement, build_check, catalogue_guard, dask_import, fixed_points, line_outline, replace_guard, stop_check,
               task, thresholds)
from .cell_file import read_cells, write_cells
from .arguments import TCP_ADDRESS, build_option
from .catalogue import BUILD_SETTINGS, FIXED_STAMP, SOURCE_STAMP, Catalogue, file_stamp, levels_folder, tiles_folder
from .errors import TilesError
from .grid import tile_grid
from .levels import fewest_levels, write_level_vrts
from .progress import Progress, n_tiles
from .survey_reader import SurveyReader
from .survey_store import SurveyStore
from .tile_file import read_tile_summary
from .tile_warnings import TileWarnings
from .tin_crs import predicted_tin_srs
from .worker_watch import WorkerWatch


def run(arguments):
    """Runs the job; returns the exit code (0, or 1 when tiles failed for good)."""
    dask_import.begin()
    dem = gdal.Open(arguments.dem)
    catalogue_guard.check(arguments.catalogue, dem, arguments.build_options, arguments.overwrite)
    settings = job_settings(arguments, dem)
    tiles = tile_grid(dem.RasterXSize, dem.RasterYSize, arguments.tile_size)
    warn_of_small_tiles(tiles, arguments.tile_size)
    settings[BUILD_SETTINGS], job_warnings = build_check.check_job(
        arguments.tinlod, dem_path(arguments.dem), arguments.catalogue, arguments.tile_size, tiles, arguments.build_options)
    warnings = TileWarnings()  # what the checks and the tasks' tinlods said, over every pass
    warnings.show_job(job_warnings)
    fixed = build_option(arguments.build_options, "-fixed")  # there: -check opened it
    settings[FIXED_STAMP] = file_stamp(fixed) if fixed else ""
    if fixed and not build_option(arguments.build_options, "-s_srs"):  # else the DEM's own CRS is not the one
        warn_of_points_outside(fixed, dem)
    if os.path.exists(arguments.catalogue) and not arguments.overwrite:
        Catalogue.open(arguments.catalogue).close()  # refused before anything is written
    if arguments.scheduler:  # before the catalogue records the job's settings
        check_reachable(arguments.scheduler)
        check_scheduler_answers(arguments.scheduler)
    folder = tiles_folder(arguments.catalogue)
    if os.path.exists(folder) and not os.path.isdir(folder):
        raise TilesError("%s is in the way: the catalogue's tiles go into a folder of that name; move that file, or "
                         "name another catalogue" % folder)
    try:
        os.makedirs(folder, exist_ok=True)
    except OSError as e:
        raise TilesError("cannot make the tiles folder %s (%s): put the catalogue where you can write"
                         % (folder, e.strerror)) from None
    with DriverLock(folder, arguments.catalogue):
        replaced = os.stat(arguments.catalogue) if arguments.overwrite and os.path.exists(arguments.catalogue) else None
        if arguments.overwrite:
            remove_job(arguments.catalogue)
        catalogue = open_catalogue(arguments, settings, predicted_tin_srs(dem, arguments.build_options), tiles)
        if replaced:
            replace_guard.keep_permissions(arguments.catalogue, replaced)
        dem = None
        remove_leftovers(folder, catalogue)
        pending = pending_tiles(catalogue, tiles, arguments.catalogue)
        agreeing = agreement.needed(arguments.build_options)
        if agreeing:  # a run stopped between two rounds of agreement left tiles to build again
            listed = set(pending)
            pending += [t for t in tiles_to_agree(catalogue, tiles, arguments)[0] if t not in listed]
        if not pending:  # nothing to build: the thresholds stay as they were set
            warn_of_reused_thresholds(catalogue, arguments)
        started = set(pending)  # surveyed or built by this run (a survey may find a tile empty)
        try:
            outcome, built, rounds = build(catalogue, tiles, arguments, folder, pending, agreeing, warnings)
        except TilesStopped:
            if not agreeing:  # tiles built under a bound may not meet yet: no layer across them
                write_level_vrts(catalogue, arguments.catalogue, fewest_levels(catalogue.rows().values()))
            raise
        ran = len(started | built)
        return finish(catalogue, arguments, len(tiles) - ran, outcome, ran, rounds)


# A tile's fixed costs, measured on tiles of 30 cells: about 0.3 s of tinlod (both passes)
# and a 0.7 MB GeoPackage before its first triangle.
TILE_SECONDS, TILE_BYTES = 0.3, 0.7e6


def warn_of_small_tiles(tiles, tile_size):
    """Thousands of small tiles cost more in tasks and files than in triangles: said before
    they start (-tile_size 6 on a 1201 x 1201 DEM made 40,000 tasks without a word)."""
    if len(tiles) < 1000 or tile_size >= 256:
        return
    print("Warning: %d tiles of %d x %d cells: each is a task and a GeoPackage of its own (about %.2f s and %.1f MB "
          "before its first triangle: %.0f min of tasks and %.0f GB in all); tiles of 1024 to 4096 cells suit most "
          "DEMs (-tile_size)" % (len(tiles), tile_size, tile_size, TILE_SECONDS, TILE_BYTES / 1e6,
                                 len(tiles) * TILE_SECONDS / 60, len(tiles) * TILE_BYTES / 1e9), file=sys.stderr)


def warn_of_points_outside(fixed, dem):
    """A whole run says how many points to keep fall outside its data; no tile sees those
    beyond the DEM's extent."""
    try:
        outside, total = fixed_points.outside_count(fixed, dem)
    except RuntimeError:  # GDAL's: -check has said what it could of the file
        return
    if outside:
        print("Warning: %d of the %d points to keep (-fixed) lie beyond the DEM's extent and are ignored"
              % (outside, total), file=sys.stderr)


def build(catalogue, tiles, arguments, folder, pending, agreeing, warnings):
    """The passes over the pending tiles; (outcome by status, the tiles built, rounds of
    border agreement). `warnings` (TileWarnings) shows what the tiles' tinlods say."""
    outcome, built, rounds = {}, set(pending), 1
    if not pending:
        return outcome, built, rounds
    with Workers(arguments, warnings) as workers:  # one cluster for every pass
        extra = []
        if global_selection(arguments):
            extra = ["-level_thresholds", level_thresholds(catalogue, tiles, arguments, workers)]
            extra += line_outline.build_option(catalogue, folder)
            rows = catalogue.rows()  # the surveys found some tiles empty: those are not built
            pending = [t for t in pending if rows[(t.col, t.row)]["status"] != "empty"]
            built = set(pending)
        if agreeing:
            extra += ["-border_keep", os.path.abspath(agreement.keep_path(folder))]
        outcome = run_tiles(catalogue, pending, arguments, workers, extra) if pending else {}
        if agreeing:
            rounds = agree_lines(catalogue, tiles, arguments, workers, extra, outcome, built)
    return outcome, built, rounds


def tiles_to_agree(catalogue, tiles, arguments):
    """The finished tiles to build again so that their lines agree (agreement.next_round),
    marked pending, and how many line cells are kept; the keep file updated first."""
    rows = catalogue.rows()
    base = os.path.dirname(os.path.abspath(arguments.catalogue))
    done = {t: os.path.join(base, rows[(t.col, t.row)]["file"]) for t in tiles
            if rows[(t.col, t.row)]["status"] == "done" and rows[(t.col, t.row)]["file"]}
    path = agreement.keep_path(tiles_folder(arguments.catalogue))
    kept, again = agreement.next_round(done, read_cells(path), agreement.TileLines(tiles, arguments.tile_size))
    write_cells(path, kept)
    for t in again:
        catalogue.update(t.col, t.row, {"status": "pending", "file": None})
    return again, len(kept)


def agree_lines(catalogue, tiles, arguments, workers, extra, outcome, built):
    """Rounds of building again the tiles whose lines gained kept cells, until none does
    (or a tile fails for good: a rerun goes on from there). Adds to `outcome` and to the
    set of tiles `built`; returns the rounds, the first included."""
    rounds = 1
    while not outcome.get("failed"):
        again, kept = tiles_to_agree(catalogue, tiles, arguments)
        if not again:
            break
        rounds += 1
        if not arguments.quiet:
            print("border agreement, round %d: %s again (%d line cells kept under -max_error)"
                  % (rounds, n_tiles(len(again)), kept))
        built.update(again)
        for status, count in run_tiles(catalogue, again, arguments, workers, extra).items():
            outcome[status] = outcome.get(status, 0) + count
    return rounds


def job_settings(arguments, dem):
    """The catalogue's metadata: what a rerun must match."""
    return {"TINLOD_SOURCE": dem_path(arguments.dem), "TINLOD_TILE_SIZE": str(arguments.tile_size),
            "TINLOD_BUILD_OPTIONS": shlex.join(arguments.build_options),
            "TINLOD_RASTER_SIZE": "%d,%d" % (dem.RasterXSize, dem.RasterYSize),
            "TINLOD_SELECTION": "global" if global_selection(arguments) else "tile",
            SOURCE_STAMP: file_stamp(dem_path(arguments.dem))}


def check_reachable(address):
    """A TCP connection to the scheduler (tcp://host:port, or host:port), or TilesError."""
    match = TCP_ADDRESS.fullmatch(address)
    if not match:
        return  # another protocol: the client says what it finds
    try:
        socket.create_connection((match.group(1), int(match.group(2))), timeout=20).close()
    except OSError as e:
        raise TilesError("cannot reach the Dask scheduler %s (%s): is `dask scheduler` running there? "
                         "Nothing was written" % (address, e.strerror or e)) from None


def check_scheduler_answers(address):
    """Dask's own handshake, or TilesError: what takes a TCP connection may be no scheduler
    (another server, a proxy that takes them all), which left a catalogue and a lock behind
    when only the run's client found out."""
    distributed = dask_import.distributed()
    started = time.monotonic()
    try:
        distributed.Client(address, timeout="20s").close()
    except (OSError, ValueError) as e:  # Dask's timeout says 20 s, however long it tried
        why = "tried for %.1f s" % (time.monotonic() - started) if isinstance(e, OSError) else str(e)
        raise TilesError("no Dask scheduler answers at %s (%s): is `dask scheduler` running there, on that port? "
                         "Nothing was written" % (address, why)) from None


def dem_path(path):
    """The DEM as every worker opens it: a file's absolute path; a GDAL virtual path
    (/vsizip/, /vsis3/, /vsicurl/...) as given, which making it absolute would break
    (/vsizip//abs/path.zip/x.tif needs its two slashes)."""
    return path if path.startswith("/vsi") else os.path.abspath(path)


def global_selection(arguments):
    """The study's -threshold mode already deletes alike everywhere: no survey needed."""
    return arguments.selection == "global" and "-threshold" not in arguments.build_options


def level_thresholds(catalogue, tiles, arguments, workers):
    """The job's thresholds, one per level: recorded in the catalogue once the survey pass
    has run over every tile (a rerun reuses them), as text for -level_thresholds."""
    recorded = catalogue.setting("TINLOD_LEVEL_THRESHOLDS")
    if recorded:
        warn_of_reused_thresholds(catalogue, arguments)
        if not arguments.quiet:  # a log of a resumed run says which pass it is in, as the first run's does
            print("build pass: one importance threshold per level for the whole raster, as the catalogue recorded them")
        return recorded
    folder = tiles_folder(arguments.catalogue)
    rows = catalogue.rows()
    surveyed = [t for t in tiles if rows[(t.col, t.row)]["status"] != "empty"]
    missing = [t for t in surveyed if not os.path.isfile(survey_path(folder, t))]
    with SurveyStore(folder) as store:
        # Read as the tasks end, while the others still run: thousands of them.
        surveys = SurveyReader(store)
        if missing:
            if not arguments.quiet:
                print("survey pass: %s" % n_tiles(len(missing)))
            outcome = run_tiles(catalogue, missing, arguments, workers, ["-survey"], survey="survey", loaded=surveys)
            if outcome.get("failed"):
                raise TilesError("%s failed in the survey pass; %s"
                                 % (n_tiles(outcome["failed"]), failure_summary(catalogue.rows().values())))
        rows = catalogue.rows()
        surveyed = [t for t in surveyed if rows[(t.col, t.row)]["status"] != "empty"]
        levels = [surveys.levels(t, survey_path(folder, t)) for t in surveyed]
        percents = percent(arguments, "-delete_pct", 20), percent(arguments, "-stop_pct", 5)
        values = thresholds.level_thresholds(levels, *percents)
        write_cells(line_outline.path(folder), surveys.cells)  # before the thresholds are recorded: a rerun has both
        catalogue.set_setting(line_outline.DIGEST, line_outline.digest(line_outline.path(folder)))
        catalogue.set_setting(line_outline.SETTING, line_outline.NAME)
        if arguments.exact_stop:
            values = exact_stop(catalogue, surveyed, arguments, workers, values, levels, percents, store)
            catalogue.set_setting(EXACT_STOP, "yes")
    text = thresholds.as_option(values)
    catalogue.set_setting(thresholds.SHARES_SETTING, thresholds.SHARES_DELETED)
    catalogue.set_setting("TINLOD_LEVEL_THRESHOLDS", text)
    for t in surveyed:
        task.remove_if_present(survey_path(folder, t))
        task.remove_if_present(survey_path(folder, t, SECOND_SURVEY))
    if not arguments.quiet:
        print("build pass: one importance threshold per level for the whole raster")
    return text


def warn_of_reused_thresholds(catalogue, arguments):
    """A rerun reuses the thresholds recorded: say where they differ from what it was asked."""
    recorded = catalogue.setting("TINLOD_LEVEL_THRESHOLDS")
    if not recorded:
        return
    if ":" in recorded and catalogue.setting(thresholds.SHARES_SETTING) != thresholds.SHARES_DELETED:
        print("Warning: %s's thresholds were set by an earlier tinlod-tiles, whose share of a bin's flat ties "
              "counted the ties gone through, not those deleted: the tiles built now delete more of their flat "
              "ties at those levels (the union still fits together); add -overwrite to build every tile alike"
              % arguments.catalogue, file=sys.stderr)
    if arguments.exact_stop and catalogue.setting(EXACT_STOP) != "yes":
        print("Warning: %s's thresholds were set without -exact_stop, and a rerun reuses them: add -overwrite "
              "to set them again with it" % arguments.catalogue, file=sys.stderr)


def percent(arguments, name, default):
    return float(build_option(arguments.build_options, name) or default)


# -exact_stop's second survey pass, as the build pass deletes: its surveys' file kind, and
# the catalogue's record that the thresholds were so set.
SECOND_SURVEY = "survey2"
EXACT_STOP = "TINLOD_EXACT_STOP"


def exact_stop(catalogue, surveyed, arguments, workers, values, first, percents, store):
    """-exact_stop: the first round's thresholds with the level that reaches the stop set
    from a second survey pass, which makes the levels below the stop level they aim at with
    them (the build pass's very state) and walks every candidate at it."""
    if not values:  # no tile with data was surveyed
        return values
    level = thresholds.stop_level(first, *percents)
    if level is None:  # no level is expected to reach the stop: the last comes nearest
        level = len(values) - 1
    folder = tiles_folder(arguments.catalogue)
    missing = [t for t in surveyed if not os.path.isfile(survey_path(folder, t, SECOND_SURVEY))]
    if missing:
        if not arguments.quiet:
            print("second survey pass (-exact_stop): %s" % n_tiles(len(missing)))
        walked = values[:level] + [(1e308, 1.0)] + values[level + 1:]
        extra = ["-survey", "-level_thresholds", thresholds.as_option(walked)] + line_outline.build_option(catalogue, folder)
        outcome = run_tiles(catalogue, missing, arguments, workers, extra, survey=SECOND_SURVEY)
        if outcome.get("failed"):
            raise TilesError("%s failed in the second survey pass; %s"
                             % (n_tiles(outcome["failed"]), failure_summary(catalogue.rows().values())))
    second = [thresholds.load_survey(survey_path(folder, t, SECOND_SURVEY), store)["levels"] for t in surveyed]
    return thresholds.exact_stop_thresholds(values, second, percents[1], level, percents[0])


def survey_path(folder, tile, kind="survey"):
    return os.path.join(folder, survey_name(tile, kind))


def survey_name(tile, kind="survey"):
    return tile.name[: -len(".gpkg")] + "." + kind + ".json"


# The tiles folder's files, by what leaves them: a finished run, and a run killed outright
# (half-written files, logs, attempt counts). Nothing else there is ours to remove.
CELL_FILES = "|".join(re.escape(name) for name in (agreement.KEEP_NAME, line_outline.NAME))
RUN_FILES = re.compile(r"tile_\d+_\d+\.(gpkg|survey2?\.json)|(%s)" % CELL_FILES)
LEFTOVER_FILES = re.compile(r"tile_\d+_\d+\.(partial\.gpkg|gpkg\.log|gpkg\.attempts|survey2?\.partial\.json(\.partial)?"
                            r"|survey2?\.json\.log|survey2?\.json\.attempts)|(%s)\.partial" % CELL_FILES)


def remove_job(catalogue_path):
    """-overwrite: the catalogue, its tiles and its level files go; only files tinlod-tiles
    names, so that nothing else a user keeps in those folders is lost. The catalogue first:
    replace_guard has said it may go, and without it the rest is no job."""
    try:
        if os.path.exists(catalogue_path):
            os.remove(catalogue_path)
        remove_matching(tiles_folder(catalogue_path),
                        lambda name: RUN_FILES.fullmatch(name) or LEFTOVER_FILES.fullmatch(name))
        remove_matching(levels_folder(catalogue_path), re.compile(r"level_\d+\.vrt").fullmatch)
    except OSError as e:
        raise TilesError("-overwrite cannot remove %s (%s): make the job's files yours to remove, or name another "
                         "catalogue" % (e.filename, e.strerror)) from None


def remove_matching(folder, names):
    """The files of `folder` whose name `names` accepts."""
    if os.path.isdir(folder):
        for name in os.listdir(folder):
            if names(name):
                os.remove(os.path.join(folder, name))


class DriverLock:
    """One driver per catalogue: a second one would write it too. The lock file stays in the
    tiles folder (removing it would let a second driver lock another file)."""

    def __init__(self, folder, catalogue_path):
        self.path, self.catalogue_path = os.path.join(folder, ".driver.lock"), catalogue_path

    def __enter__(self):
        try:
            self.file = open(self.path, "w")
        except OSError as e:
            raise TilesError("cannot write in the tiles folder %s (%s): make it writable, or put the catalogue "
                             "where you can write" % (os.path.dirname(self.path), e.strerror)) from None
        try:
            fcntl.flock(self.file, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            self.file.close()
            raise TilesError("another tinlod-tiles is running on %s: wait for it, or stop it first"
                             % self.catalogue_path) from None

    def __exit__(self, *_):
        self.file.close()


def open_catalogue(arguments, settings, srs, tiles):
    if not os.path.exists(arguments.catalogue):
        return Catalogue.create(arguments.catalogue, settings, srs, tiles)
    catalogue = Catalogue.open(arguments.catalogue)
    recorded = catalogue.setting(BUILD_SETTINGS)
    if settings[BUILD_SETTINGS] and not recorded:  # made by an earlier tinlod-tiles: read its options now
        recorded = build_check.recorded_settings(arguments.tinlod, dem_path(arguments.dem), arguments.catalogue,
                                                 arguments.tile_size, tiles[0],
                                                 shlex.split(catalogue.setting("TINLOD_BUILD_OPTIONS") or ""))
    catalogue.check_same_job(settings, arguments.catalogue, recorded)
    for key, value in ((SOURCE_STAMP, settings[SOURCE_STAMP]), (FIXED_STAMP, settings[FIXED_STAMP]),
                       (BUILD_SETTINGS, recorded)):
        if value and not catalogue.setting(key):  # made by an earlier tinlod-tiles, and now checked
            catalogue.set_setting(key, value)
    return catalogue


FINISHED_SURVEY_ATTEMPTS = re.compile(r"tile_(\d+)_(\d+)\.survey2?\.json\.attempts")


def remove_leftovers(folder, catalogue):
    """What a run killed outright left: half-written tiles, logs, attempt counts. A survey
    that ended as the run stopped is reused: its attempts go into the catalogue first (the
    stopped driver had not recorded them)."""
    for name in os.listdir(folder):
        match = FINISHED_SURVEY_ATTEMPTS.fullmatch(name)
        survey = os.path.join(folder, name[: -len(".attempts")])
        if match and os.path.isfile(survey):
            col, row = int(match.group(1)), int(match.group(2))
            catalogue.update(col, row, {"attempts": (catalogue.value(col, row, "attempts") or 0) + read_attempts(survey)})
    remove_matching(folder, LEFTOVER_FILES.fullmatch)


def pending_tiles(catalogue, tiles, catalogue_path):
    """The tiles to build: all but those finished whose file is there, readable and theirs."""
    rows = catalogue.rows()
    base = os.path.dirname(os.path.abspath(catalogue_path))
    pending = []
    for tile in tiles:
        row = rows[(tile.col, tile.row)]
        if row["status"] == "empty" or (row["status"] == "done" and row["file"]
                                        and finished_file(os.path.join(base, row["file"]), tile)):
            continue
        if row["status"] != "pending":
            catalogue.update(tile.col, tile.row, {"status": "pending", "file": None})
        pending.append(tile)
    return pending


def finished_file(path, tile):
    """Whether a done tile's file is there and holds that tile; a damaged one or another
    tile's (copied or renamed over it) is said and built again."""
    if not os.path.isfile(path):
        return False
    try:
        read_tile_summary(path, "%d,%d" % (tile.col, tile.row))
        return True
    except TilesError as e:
        print("Warning: tile %d,%d is built again: %s" % (tile.col, tile.row, e), file=sys.stderr)
        return False


class Workers:
    """The Dask client (and local cluster) of a run, started once for both passes and closed
    however the run ends."""

    def __init__(self, arguments, warnings):
        self.arguments = arguments
        self.warnings = warnings  # a TileWarnings, over every pass

    def __enter__(self):
        self.distributed = dask_import.distributed()  # only a run with tiles to build needs Dask
        self.client, self.cluster = start_client(self.distributed, self.arguments)
        self.watch = WorkerWatch(self.client, self.arguments.scheduler).__enter__() if self.arguments.scheduler else None
        return self

    def __exit__(self, *_):
        if self.watch:
            self.watch.__exit__()
        stop(self.client, self.cluster)


def run_tiles(catalogue, pending, arguments, workers, extra_options=(), survey=None, loaded=None):
    """One task per pending tile; the catalogue follows their futures. Returns the count of
    tiles per status. With `survey` (the surveys' kind, as survey_name takes it), the tasks
    write each tile's survey, and the catalogue records only the tiles found empty (or
    failed); `loaded`, when given (a SurveyReader), reads each survey as its task ends."""
    distributed, client = workers.distributed, workers.client
    outcome = {}
    progress = Progress(len(pending), arguments.quiet)
    futures = {}  # filled as they are submitted, so that a stop cancels every one
    try:
        submit(client, pending, arguments, extra_options, survey, futures)
        for future in distributed.as_completed(list(futures)):
            if future.status == "cancelled":  # not by this run: its scheduler went away
                raise scheduler_lost(client, arguments, catalogue)
            tile = futures.pop(future)
            path = survey_path(tiles_folder(arguments.catalogue), tile, survey) if survey else None
            status = (record_survey(catalogue, tile, future, path) if survey
                      else record(catalogue, tile, future, arguments.catalogue, workers.warnings))
            if loaded is not None and status == "surveyed":
                loaded.load(tile, path)
            outcome[status] = outcome.get(status, 0) + 1
            progress.tile(tile.col, tile.row, status)
    except KeyboardInterrupt:
        cancel(client, futures)
        # The catalogue's count: a stop in a survey pass leaves every unbuilt tile pending.
        raise TilesStopped(sum(1 for r in catalogue.rows().values() if r["status"] == "pending")) from None
    except (OSError, distributed.utils.CancelledError) as e:
        # The scheduler lost as a result was fetched (Dask's CommClosedError), or the task
        # cancelled between its status and its result.
        cancel(client, futures)
        comm_lost = isinstance(e, distributed.comm.CommClosedError)
        if comm_lost or client.status != "running" or isinstance(e, distributed.utils.CancelledError):
            raise scheduler_lost(client, arguments, catalogue, lost=comm_lost) from None
        raise  # our own file's error
    except BaseException:  # not retried while the run stops
        cancel(client, futures)
        raise
    finally:
        progress.end()
    return outcome


def cancel(client, futures):
    """The run's tasks cancelled, unless the scheduler is gone: Dask would try to reach it for
    20 s and raise, hiding why the run stops."""
    if client.status == "running":
        try:
            client.cancel(list(futures))
        except OSError:  # lost meanwhile
            pass


class TilesStopped(Exception):
    """Ctrl-C: the tiles not yet finished stay pending in the catalogue."""


def start_client(distributed, arguments):
    # Dask keeps the source of the code that submits tasks, for its dashboard: not ours, whose
    # reading (inspect.getsource) took 1.6 ms of the driver's core a submit (19 s for the
    # 11,920 tasks of a 10^11-cell DEM).
    import dask
    ignored = "distributed.diagnostics.computations.ignore-modules"
    dask.config.set({ignored: list(dask.config.get(ignored, [])) + ["tinlodtiles", "__main__"]})
    # Dask's client logs a lost scheduler as tracebacks, about 100 lines, under its own name
    # and (log_errors) under its caller's module's, asyncio's event loop: the run says it in
    # one line (scheduler_lost).
    for name in ("distributed.client", "distributed.utils", "asyncio.events"):
        logging.getLogger(name).setLevel(logging.CRITICAL)
    if arguments.scheduler:
        try:
            return distributed.Client(arguments.scheduler, timeout="20s"), None
        except (OSError, ValueError) as e:  # ValueError: an address Dask cannot read
            raise TilesError("cannot reach the Dask scheduler %s (%s): is `dask scheduler` running there?"
                             % (arguments.scheduler, e)) from None
    # Threads, not processes: a task only waits on its tinlod (the GIL is free meanwhile),
    # and worker processes would each start Python and Dask again, seconds of a short run.
    # The tasks' tinlods are then this process's children (end_tile_processes).
    # The scheduler's HTTP server on a port of its own: with None it still takes 8787, and a
    # second run at once warns that the port is in use.
    # Without memory_limit, each worker would watch this process's memory (the tasks' is their
    # tinlods'); the LOCAL_CLUSTER settings quiet the rest.
    # For the rest of the run: some are read as the cluster runs, not as it starts.
    dask.config.set(LOCAL_CLUSTER)
    cluster = distributed.LocalCluster(n_workers=arguments.workers, threads_per_worker=1, processes=False,
                                       dashboard_address=":0", silence_logs=logging.ERROR, memory_limit=0)
    return distributed.Client(cluster), cluster


# A local cluster's scheduler and workers run on this process's event loop, beside the tasks'
# tinlods on the same cores: by default its profiler samples the worker threads every 10 ms,
# a tick checks the loop every 20 ms and monitors read the system every 0.1-0.5 s, 1.3 s of
# a core in a 16-tile run on 2 workers (0.4 s without them). A remote cluster keeps its own.
LOCAL_CLUSTER = {
    "distributed.worker.profile.enabled": False,
    "distributed.admin.tick.interval": "1s",
    "distributed.admin.system-monitor.interval": "5s",
    "distributed.worker.memory.monitor-interval": "5s",
}


def worker_threads(arguments):
    """A local cluster's workers share this machine: each tinlod gets its share of the cores,
    unless TINLOD_THREADS says otherwise; a remote scheduler's workers keep their own (their
    machines' TINLOD_THREADS, not the driver's: a batch script's export reached every worker)."""
    if arguments.scheduler:
        return None
    if os.environ.get("TINLOD_THREADS"):
        return int(os.environ["TINLOD_THREADS"])
    return max(1, (os.cpu_count() or 1) // arguments.workers)


def record_survey(catalogue, tile, future, path):
    """A survey task's end (its survey at `path`): the tile's attempts, and the status of a
    tile found empty or failed."""
    attempts = (catalogue.value(tile.col, tile.row, "attempts") or 0) + read_attempts(path)  # a tile's tasks, every pass
    task.remove_if_present(task.attempts_path(path))
    if future.status != "finished":
        catalogue.update(tile.col, tile.row, {"status": "failed", "error": failure_message(future), "attempts": attempts})
        return "failed"
    status = future.result()["status"]
    if status == "empty":  # found by its survey: it is never built
        catalogue.update(tile.col, tile.row, {"status": "empty", "attempts": attempts})
    else:
        catalogue.update(tile.col, tile.row, {"attempts": attempts})
    return "surveyed" if status == "done" else status


def scheduler_lost(client, arguments, catalogue, lost=False):
    """TilesError for the tasks Dask cancelled under the run, or whose results it could not
    fetch (`lost`: the scheduler killed or its connection lost, which Dask says in tracebacks):
    their tiles stay pending, not failed, and the same command finishes them once the
    scheduler is back."""
    where = arguments.scheduler or "of the local cluster"
    lost = lost or client.status != "running"
    why = "its connection was lost" if lost else "it cancelled the tasks (restarted?)"
    pending = sum(1 for r in catalogue.rows().values() if r["status"] == "pending")
    again = ("start the scheduler and its workers again, then run the same command" if arguments.scheduler
             else "run the same command again")
    return TilesError("the Dask scheduler %s stopped running the tiles (%s): %s stay pending in the catalogue, the "
                      "finished ones are kept; %s to finish them" % (where, why, n_tiles(pending), again))


def submit(client, pending, arguments, extra_options, survey, futures):
    """The tasks, their code shipped by value so that a remote worker needs only tinlod;
    their futures go into `futures` (future: tile)."""
    import cloudpickle

    cloudpickle.register_pickle_by_value(task)
    folder = os.path.abspath(tiles_folder(arguments.catalogue))
    dem_is_file = os.path.isfile(dem_path(arguments.dem))  # what a worker must see too (task.check_reach)
    jobs = [{"tinlod": arguments.tinlod, "dem": dem_path(arguments.dem), "dem_is_file": dem_is_file, "tiles_dir": folder,
             "name": survey_name(tile, survey) if survey else tile.name, "col": tile.col, "row": tile.row,
             "tile_size": arguments.tile_size,
             "build_options": list(arguments.build_options) + [o for o in extra_options if o != "-survey"],
             "survey": survey,
             "kill_hook": os.environ.get(task.KILL_HOOK_VARIABLE),
             "threads": worker_threads(arguments), "remote": bool(arguments.scheduler)} for tile in pending]
    keys = ["%s-%d-%d-%s" % (survey or "tile", tile.col, tile.row, os.urandom(4).hex()) for tile in pending]
    # One call for all: Dask's bookkeeping is per call (start_client).
    futures.update(zip(client.map(task.run_tile, jobs, key=keys, retries=arguments.retries, pure=False), pending))


def record(catalogue, tile, future, catalogue_path, warnings):
    """The catalogue row of a tile whose task has ended; returns its status. Its tinlod's
    warnings go to `warnings` (TileWarnings)."""
    folder = tiles_folder(catalogue_path)
    final = os.path.join(folder, tile.name)
    attempts = read_attempts(final)
    previous = catalogue.value(tile.col, tile.row, "attempts") or 0
    values = {"attempts": previous + attempts}
    extent = None
    if future.status == "finished":
        result = future.result()
        values.update(status=result["status"], seconds=round(result["seconds"], 3),
                      peak_mib=round(result["peak_mib"], 1), error=None)
        warnings.show(tile, result.get("warnings", []))
        if result["status"] == "done":
            try:
                summary = read_tile_summary(final, "%d,%d" % (tile.col, tile.row))
            except (TilesError, RuntimeError) as e:  # tinlod said done, but the file is not right
                values.update(status="failed", file=None, error=str(e))
            else:
                values.update(file=os.path.relpath(final, os.path.dirname(os.path.abspath(catalogue_path))),
                              levels=summary.levels, vertices=summary.vertices, triangles=summary.triangles)
                extent = catalogue.extent_in_layer_srs(summary.extent, summary.srs)
    else:
        values.update(status="failed", file=None, error=failure_message(future))
    catalogue.update(tile.col, tile.row, values, extent)
    task.remove_if_present(task.attempts_path(final))
    return values["status"]


def read_attempts(final):
    try:
        with open(task.attempts_path(final)) as f:
            return int(f.read().strip() or 0)
    except (OSError, ValueError):
        return 0


def failure_message(future):
    """Why a task failed, for the catalogue's error field."""
    try:
        return without_task_prefix(str(future.exception()))
    except Exception as e:  # a cancelled or lost future has no exception to give
        return "the task ended without a result (%s)" % type(e).__name__


def without_task_prefix(message):
    """A task's failure without its "tile C,R (attempt N): ": the catalogue's row names the
    tile and counts the attempts (an earlier tinlod-tiles recorded it with it)."""
    return re.sub(r"^tile \d+,\d+ \(attempt \d+\): ", "", message)


def stop(client, cluster):
    """Closes the client and the local cluster, whose tasks' tinlods are ended meanwhile: a
    worker thread cannot be stopped, only what it waits on (Ctrl-C would otherwise wait for
    the tiles being built), and closing waits for the tasks. A tinlod a worker starts while
    the cluster closes (its next task, before it hears of the cancel) is ended too. A remote
    scheduler's workers finish the tasks already running."""
    if cluster is None:
        client.close()
        return
    closed = threading.Event()
    ender = threading.Thread(target=end_tile_processes_until, args=(closed,), daemon=True)
    try:
        end_tile_processes()
        ender.start()
        client.close()
        cluster.close()
    finally:
        closed.set()
        end_tile_processes(signal.SIGKILL)


def end_tile_processes_until(closed):
    while not closed.wait(0.2):
        end_tile_processes()


def end_tile_processes(how=signal.SIGTERM):
    """Signals this process's children that lead a session of their own: the local cluster's
    tinlods (task.run_measured starts them so, out of the terminal's Ctrl-C). Their worker
    threads reap them."""
    import psutil  # Dask's own dependency

    for child in psutil.Process().children():
        try:
            if os.getsid(child.pid) == child.pid:
                child.send_signal(how)
        except (psutil.NoSuchProcess, ProcessLookupError):
            pass


def finish(catalogue, arguments, skipped, outcome, ran, rounds=1):
    """TINLOD_LEVELS, the level files and the summary (`ran` tiles built, in `rounds` of
    border agreement); 1 when tiles failed."""
    rows = catalogue.rows().values()
    counts = sorted({row["levels"] for row in rows if row["status"] == "done"})
    if len(counts) > 1:
        print("Warning: the tiles have from %d to %d levels; the level files stop at the fewest"
              % (counts[0], counts[-1]), file=sys.stderr)
    levels = counts[0] if counts else 0
    stop_check.warn_if_above_stop(rows, arguments.catalogue, arguments.build_options,
                                  percent(arguments, "-stop_pct", 5), levels)
    catalogue.set_setting("TINLOD_LEVELS", str(levels))
    vrts = write_level_vrts(catalogue, arguments.catalogue, levels)
    states = {}
    for row in rows:
        states[row["status"]] = states.get(row["status"], 0) + 1
    catalogue.close()
    if not arguments.quiet:
        print_summary(arguments.catalogue, ran, sum(outcome.values()), rounds, skipped, states, levels, vrts)
    if states.get("failed"):
        print("ERROR: %s failed%s; %s" % (n_tiles(states["failed"]), after_retries(states["failed"], arguments.retries),
                                           failure_summary(rows)), file=sys.stderr)
        return 1
    if rows and states.get("empty") == len(rows):  # a script must not take it for a result
        print("ERROR: none of the %d tiles has a valid cell of %s as tinlod build reads it (its band, -valid_range, "
              "the band's nodata), so nothing was built: correct the options and run again with -overwrite"
              % (len(rows), arguments.dem), file=sys.stderr)
        return 1
    return 0


def after_retries(failed, retries):
    if not retries:
        return ", not retried (-retries 0)"
    return " after %s %s" % ("its" if failed == 1 else "their", "retry" if retries == 1 else "%d retries" % retries)


def failure_summary(rows):
    """What the failed tiles' errors say, most common first (the catalogue's error field has
    each), and what to do: a run whose every tile failed alike most likely has wrong options."""
    rows = list(rows)
    messages = {}
    for row in rows:
        if row["status"] == "failed":
            message = without_task_prefix(row["error"] or "no message")
            if message.startswith(task.ERROR_PREFIX):  # printed after the run's own ERROR line
                message = message[len(task.ERROR_PREFIX):]
            messages.setdefault(message, []).append("%d,%d" % (row["tile_col"], row["tile_row"]))
    ranked = sorted(messages.items(), key=lambda item: -len(item[1]))
    lines = ["%s (tile %s%s)" % (message, tiles[0], " and %d more" % (len(tiles) - 1) if len(tiles) > 1 else "")
             for message, tiles in ranked[:3]]
    if len(ranked) > 3:
        lines.append("%d other messages (the catalogue's error field has each)" % (len(ranked) - 3))
    alike = len(ranked) == 1 and all(row["status"] in ("failed", "empty") for row in rows)
    if all(message.startswith(task.WORKER_PREFIX) for message in messages):  # the workers' paths, not the job
        advice = "run again to retry them once every worker reaches those paths"
    elif alike:
        advice = ("every tile failed alike: if the DEM or the options are wrong, correct them and run again with "
                  "-overwrite (the catalogue keeps the options it was made with)")
    else:
        advice = "run again to retry them"
    failed = sum(len(tiles) for tiles in messages.values())
    return "\n  ".join(["it says:" if failed == 1 else "they say:"] + lines) + "\n" + advice


def print_summary(catalogue_path, ran, builds, rounds, skipped, states, levels, vrts):
    agreed = " (%d builds in %d rounds of border agreement)" % (builds, rounds) if rounds > 1 else ""
    print("%s run%s, %d skipped (already finished); the catalogue %s has %s"
          % (n_tiles(ran), agreed, skipped, catalogue_path,
             ", ".join("%d %s" % (states[s], s) for s in ("done", "empty", "failed", "pending") if s in states)))
    pattern = os.path.join(levels_folder(catalogue_path), "level_K.vrt")
    if vrts and len(vrts) == levels:
        print("levels 0 to %d across the tiles: %s" % (levels - 1, pattern))
    elif vrts:  # the tiles were built with -levels
        written = [re.search(r"level_(\d+)\.vrt$", path).group(1) for path in vrts]
        print("levels %s across the tiles (of 0 to %d: the others have no layer, -levels): %s"
              % (", ".join(written), levels - 1, pattern))
