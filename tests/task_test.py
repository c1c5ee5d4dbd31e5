#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""tiles/tinlodtiles/task.py with a stand-in tinlod: a finished tile is synced to disk before
it takes its final name, and the folder after, so that a crash of the machine cannot leave a
truncated file under the name the catalogue calls finished; a failed tile leaves nothing.

Usage: task_test.py TILES_SOURCE_DIR"""
import os
import stat
import sys
import tempfile

sys.path.insert(0, sys.argv[1])
from tinlodtiles import task  # noqa: E402
from script_checks import check, exit_code  # noqa: E402


def stand_in(folder, code):
    """A tinlod that writes its output file (its 4th argument) and exits with `code`."""
    path = os.path.join(folder, "tinlod_%d" % code)
    with open(path, "w") as f:
        f.write("#!/bin/sh\nprintf 'tile bytes' > \"$3\"\nexit %d\n" % code)
    os.chmod(path, os.stat(path).st_mode | stat.S_IXUSR)
    return path


def job(tinlod, folder):
    dem = os.path.join(folder, "dem.tif")
    open(dem, "a").close()
    return {"tinlod": tinlod, "dem": dem, "dem_is_file": True, "tiles_dir": folder, "name": "tile_0_0.gpkg", "col": 0,
            "row": 0, "tile_size": 100, "build_options": []}


synced = []  # (the path synced, whether the final file existed then)
real_fsync = os.fsync


def recording_fsync(descriptor):
    synced.append((os.readlink("/proc/self/fd/%d" % descriptor), os.path.exists(final)))
    real_fsync(descriptor)


task.os.fsync = recording_fsync
with tempfile.TemporaryDirectory() as folder:
    final = os.path.join(folder, "tile_0_0.gpkg")
    result = task.run_tile(job(stand_in(folder, 0), folder))
    partial = task.partial_path(final)
    check("the tile is done", result["status"] == "done", result)
    check("its file has its final name and its bytes, and no partial file is left",
          open(final).read() == "tile bytes" and not os.path.exists(partial), os.listdir(folder))
    check("the file was synced under its partial name, then the folder once it had its final name",
          synced == [(os.path.realpath(partial), False), (os.path.realpath(folder), True)], synced)

    synced.clear()
    os.remove(final)
    try:
        task.run_tile(job(stand_in(folder, 1), folder))
        failed = False
    except task.TileFailed:
        failed = True
    check("a failed tinlod fails the task, leaving no file and syncing nothing",
          failed and not os.path.exists(final) and not os.path.exists(partial) and not synced, (os.listdir(folder), synced))

# What a failed tinlod said, as the catalogue and the refusals record it.
wkt_error = "0..\nERROR: target CRS 'PROJCS[\"a\",\nGEOGCS[\"b\"]]' is not a CRS GDAL understands: use e.g. EPSG:32632\n"
check("an error quoting a value of two lines keeps its lines after the ERROR line (the advice comes there)",
      task.tinlod_error(wkt_error) == "target CRS 'PROJCS[\"a\",\nGEOGCS[\"b\"]]' is not a CRS GDAL understands: "
      "use e.g. EPSG:32632", task.tinlod_error(wkt_error))
check("the usage after a misspelt option is left out",
      task.tinlod_error("ERROR: unknown option '-bogus'\nUsage: tinlod build DEM OUT.gpkg [-method m]\n")
      == "unknown option '-bogus'", task.tinlod_error("ERROR: unknown option '-bogus'\nUsage: tinlod build\n"))
check("a GDAL error or a warning after it is not part of it",
      task.tinlod_error("ERROR: no room\nERROR 1: sqlite3_exec failed\n") == "no room"
      and task.tinlod_error("ERROR: no room\nWarning 1: closing\n") == "no room")
check("the last of two errors is taken", task.tinlod_error("ERROR: first\nERROR: second\n") == "second")
check("no ERROR line: None", task.tinlod_error("0...10...20\nKilled\n") is None)
with tempfile.TemporaryDirectory() as folder:
    log = os.path.join(folder, "tile.log")
    with open(log, "w") as f:
        f.write("0...10..\nERROR 1: TIFFReadEncodedTile() failed\n")
    check("a crash after GDAL's error records GDAL's line; a kill without one, the signal",
          task.last_error_line(task.read_log(log), -11) == "ERROR 1: TIFFReadEncodedTile() failed"
          and task.last_error_line(task.read_log(os.path.join(folder, "none.log")), -9) == "tinlod was killed by signal 9",
          task.last_error_line(task.read_log(log), -11))

# A worker on another machine without the driver's paths: said, naming the worker and the
# rule, where tinlod's own error blamed the DEM the driver had just read.
with tempfile.TemporaryDirectory() as folder:
    lacking = dict(job(stand_in(folder, 0), folder), remote=True)
    said = {}
    for case, change in (("DEM", {"dem": os.path.join(folder, "not_here.tif")}),
                         ("tinlod", {"tinlod": os.path.join(folder, "no_tinlod")}),
                         ("tiles folder", {"tiles_dir": os.path.join(folder, "gone")}),
                         ("local", {"dem": os.path.join(folder, "not_here.tif"), "remote": False})):
        try:
            task.run_tile(dict(lacking, **change))
        except task.TileFailed as e:
            said[case] = str(e)
    rule = "every worker must reach the DEM, the tiles folder and tinlod by the paths the driver gives"
    check("a remote worker without the DEM, tinlod or the tiles folder at the driver's paths says which, who, and the rule",
          said.get("DEM", "").startswith("worker on host ") and "cannot see the DEM" in said["DEM"]
          and all(rule in said.get(c, "") for c in ("DEM", "tinlod", "tiles folder"))
          and "has no tinlod at" in said.get("tinlod", "") and "cannot see the tiles folder" in said.get("tiles folder", ""),
          said)
    check("on the local cluster, a DEM gone is said as moved during the run",
          said.get("local", "").startswith("worker cannot see the DEM") and "(moved or removed during the run?)"
          in said["local"] and rule not in said["local"], said)
    check("each is a worker's failure to the driver (task.WORKER_PREFIX), not tinlod's",
          len(said) == 4 and all(m.startswith(task.WORKER_PREFIX) for m in said.values()), said)
    # A DEM the driver did not see as a file (a GDAL connection string, NETCDF:file.nc:var) is
    # tinlod's to open: not looked for as a file.
    virtual = task.run_tile(dict(lacking, dem="NETCDF:%s:z" % os.path.join(folder, "not_here.nc"), dem_is_file=False))
    check("a DEM the driver saw as no file is left to tinlod", virtual["status"] == "done", virtual)

sys.exit(exit_code("task"))
