#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""tinlod-tiles as a user runs it, on a local Dask cluster of 2 workers: the catalogue ends
complete, a tile whose tinlod is killed mid-run is retried, a rerun builds no finished tile
again, each level across the tiles (VRT and merge) holds every tile's triangles, info describes
the catalogue, under -method error -max_error the tiles agree their lines in rounds, and Ctrl-C
stops a run at once.
Usage: tiles_test.py TINLOD_CLI TINLOD_TILES STANDIN
Skipped (exit 77) where python3-distributed is absent. A tinlod without -tile_size (the core
before tiles) is stood in for by STANDIN, which cuts the tile's window itself."""
import json
import math
import os
import pty
import re
import shutil
import signal
import socket
import sqlite3
import struct
import subprocess
import sys
import tempfile
import threading
import time
import zipfile

from osgeo import gdal, ogr, osr

from script_checks import check, exit_code, failures

SKIPPED = 77
TILE_SIZE = 150  # a 400 x 300 DEM: 3 x 2 tiles
# Killed this long after its tinlod starts: within the loader's and GDAL's start-up on a fast
# machine, where a whole 151 x 151 tile takes 0.15 s (0.3 s let it finish there).
KILLED_TILE, KILL_AFTER = (1, 0), 0.04
EMPTY_TILE = (2, 1)  # its whole window nodata
FIELDS = {"tile_col", "tile_row", "xoff", "yoff", "xsize", "ysize", "file", "status", "levels", "vertices",
          "triangles", "attempts", "seconds", "peak_mib", "error"}



def run(args, env=None):
    started = time.monotonic()
    result = subprocess.run(args, capture_output=True, text=True, env=env)
    print("$ %s  -> exit %d in %.1f s" % (" ".join(args[:3] + ["..."]), result.returncode, time.monotonic() - started))
    return result


def make_dem(tinlod, path):
    """The default terrain, 400 x 300, without the void; one tile's window made nodata."""
    subprocess.run([tinlod, "makedem", path, "-size", "400", "300", "-no_void", "-q"], check=True)
    dataset = gdal.Open(path, gdal.GA_Update)
    band = dataset.GetRasterBand(1)
    xoff, yoff = EMPTY_TILE[0] * TILE_SIZE, EMPTY_TILE[1] * TILE_SIZE
    xsize, ysize = dataset.RasterXSize - xoff, dataset.RasterYSize - yoff
    band.WriteRaster(xoff, yoff, xsize, ysize, struct.pack("%df" % (xsize * ysize), *([band.GetNoDataValue()] * (xsize * ysize))),
                     buf_type=gdal.GDT_Float32)
    dataset = None


def make_points(dem, path, beyond=0):
    """A GeoPackage of one point at the DEM's centre, in its CRS: points for -fixed; and
    `beyond` points beyond its extent."""
    raster = gdal.Open(dem)
    x0, dx, _, y0, _, dy = raster.GetGeoTransform()
    source = ogr.GetDriverByName("GPKG").CreateDataSource(path)
    layer = source.CreateLayer("points", raster.GetSpatialRef(), ogr.wkbPoint)
    places = [(x0 + dx * raster.RasterXSize / 2, y0 + dy * raster.RasterYSize / 2)]
    places += [(x0 - (k + 1) * 100 * dx, y0) for k in range(beyond)]
    for x, y in places:
        feature = ogr.Feature(layer.GetLayerDefn())
        feature.SetGeometry(ogr.CreateGeometryFromWkt("POINT (%r %r)" % (x, y)))
        layer.CreateFeature(feature)
    source = raster = None
    return path


def make_mosaic(dem, work):
    """The DEM cut into its left and right halves, put together again by a VRT."""
    halves = []
    for i, window in enumerate(([0, 0, 200, 300], [200, 0, 200, 300])):
        halves.append(os.path.join(work, "half_%d.tif" % i))
        gdal.Translate(halves[-1], dem, srcWin=window)
    path = os.path.join(work, "mosaic.vrt")
    gdal.BuildVRT(path, halves).FlushCache()
    return path


def write_points(path, points, like):
    """Points in the CRS of the catalogue's tiles layer."""
    source = ogr.Open(like)  # held: the layer and its CRS die with their dataset
    srs = source.GetLayerByName("tiles").GetSpatialRef()
    out = ogr.GetDriverByName("GPKG").CreateDataSource(path)
    layer = out.CreateLayer("points", srs, ogr.wkbPoint)
    for x, y in points:
        f = ogr.Feature(layer.GetLayerDefn())
        g = ogr.Geometry(ogr.wkbPoint)
        g.AddPoint_2D(x, y)
        f.SetGeometry(g)
        layer.CreateFeature(f)
    out = None


def point_values(path):
    """(elevation, tile or None) of each point, in order."""
    dataset = ogr.Open(path)
    layer = dataset.GetLayerByName("points")
    has_tile = layer.GetLayerDefn().GetFieldIndex("tile") >= 0
    return [(f["elevation"], f["tile"] if has_tile else None) for f in layer]


def rows(catalogue):
    dataset = ogr.Open(catalogue)
    layer = dataset.GetLayerByName("tiles")
    names = {layer.GetLayerDefn().GetFieldDefn(i).GetName() for i in range(layer.GetLayerDefn().GetFieldCount())}
    found = {(f["tile_col"], f["tile_row"]): {n: f.GetField(n) for n in names} for f in layer}
    return found, names, dict(dataset.GetMetadata_Dict())


def tile_box(catalogue, tile, inset):
    """The catalogue's extent of a tile, shrunk by `inset` on every side."""
    dataset = ogr.Open(catalogue)
    layer = dataset.GetLayerByName("tiles")
    layer.SetAttributeFilter("tile_col = %d AND tile_row = %d" % tile)
    feature = layer.GetNextFeature()  # held: the geometry dies with it
    minx, maxx, miny, maxy = feature.GetGeometryRef().GetEnvelope()
    return minx + inset, miny + inset, maxx - inset, maxy - inset


def level_count(path, layer_name):
    dataset = ogr.Open(path)
    return dataset.GetLayerByName(layer_name).GetFeatureCount()


def file_times(folder):
    return {name: os.stat(os.path.join(folder, name)).st_mtime_ns for name in sorted(os.listdir(folder))
            if name.endswith(".gpkg")}


def check_complete(catalogue, label):
    found, names, metadata = rows(catalogue)
    check("%s: the catalogue lists the 6 tiles" % label, len(found) == 6, len(found))
    check("%s: the tiles layer has every field" % label, FIELDS <= names, sorted(FIELDS - names))
    check("%s: the all-nodata tile is 'empty'" % label, found.get(EMPTY_TILE, {}).get("status") == "empty",
          found.get(EMPTY_TILE))
    done = {k: r for k, r in found.items() if k != EMPTY_TILE}
    check("%s: every other tile is 'done', with its file, levels and counts" % label,
          all(r["status"] == "done" and r["file"] and r["levels"] and r["vertices"] and r["triangles"]
              for r in done.values()), [(k, r["status"], r["error"]) for k, r in done.items()])
    base = os.path.dirname(catalogue)
    check("%s: every done tile's file exists" % label,
          all(os.path.isfile(os.path.join(base, r["file"] or "-")) for r in done.values()))
    check("%s: metadata (kind, tile size, raster size, levels)" % label,
          metadata.get("TINLOD_KIND") == "catalogue" and metadata.get("TINLOD_TILE_SIZE") == str(TILE_SIZE)
          and metadata.get("TINLOD_RASTER_SIZE") == "400,300" and int(metadata.get("TINLOD_LEVELS", 0)) > 1,
          metadata)
    return found, metadata


def info_of_catalogue(tinlod, catalogue):
    """(j) info describes the catalogue: its tiles by status, its done tiles' triangles added up."""
    tiles = rows(catalogue)[0].values()
    statuses = {}
    for tile in tiles:
        statuses[tile["status"]] = statuses.get(tile["status"], 0) + 1
    text = run([tinlod, "info", catalogue])
    counts = ", ".join("%d %s" % (statuses[s], s) for s in sorted(statuses))
    check("(j) info on the catalogue counts its tiles by status",
          text.returncode == 0 and (": tinlod catalogue, " in text.stdout)
          and ("; %d tiles (%s), " % (len(tiles), counts)) in text.stdout, (counts, text.stdout, text.stderr))
    described = run([tinlod, "info", "-json", catalogue])
    try:
        levels = json.loads(described.stdout)["levels"]
    except (ValueError, KeyError):
        levels = []
    done = [t for t in tiles if t["status"] == "done"]
    check("(j) info on the catalogue adds up its done tiles' level 0 triangles",
          len(levels) == done[0]["levels"] and levels[0]["triangles"] == sum(t["triangles"] for t in done),
          (levels[:1], [t["triangles"] for t in done], described.stderr))


def lod_and_accuracy(tinlod, catalogue, dem, work):
    """(g) lod and accuracy take the catalogue: its tiles as one hierarchy."""
    box = tile_box(catalogue, (0, 0), inset=0.0)
    out = os.path.join(work, "lod.gpkg")
    lod = run([tinlod, "lod", catalogue, out, "-center", str(box[2]), str(box[1]), "-dropoff", "40", "-q"])
    check("(g) lod on the catalogue succeeds", lod.returncode == 0, lod.stderr[-2000:])
    if lod.returncode != 0:
        return
    source = ogr.Open(out)
    places = [(f.GetGeometryRef().GetX(), f.GetGeometryRef().GetY()) for f in source.GetLayerByName("vertices")]
    check("(g) a vertex of a line two tiles share is one vertex of the output", len(places) == len(set(places)),
          len(places) - len(set(places)))
    raster = gdal.Open(dem)  # held: the band dies with its dataset
    band = raster.GetRasterBand(1).ReadAsArray()
    wrong = [f["id"] for f in source.GetLayerByName("vertices")
             if abs(band[f["row"], f["col"]] - f.GetGeometryRef().GetZ()) > 1e-3]
    check("(g) rows and columns are the whole raster's (each vertex has its cell's height)", not wrong, wrong[:5])
    levels = {f["first_level"] for f in source.GetLayerByName("triangles")}
    check("(g) fine near the centre, coarse far away", 0 in levels and max(levels) >= 8, sorted(levels))
    report = os.path.join(work, "accuracy.json")
    accuracy = run([tinlod, "accuracy", dem, catalogue, "-reference", "dem", "-report", report, "-q"])
    check("(g) accuracy on the catalogue succeeds", accuracy.returncode == 0, accuracy.stderr[-2000:])
    if accuracy.returncode == 0:
        with open(report) as f:
            rows = json.load(f)["runs"][0]["levels"]
        distinct = set()
        for name in os.listdir(os.path.join(work, "a_tiles")):
            if name.endswith(".gpkg"):
                tile = ogr.Open(os.path.join(work, "a_tiles", name))
                distinct |= {(f.GetGeometryRef().GetX(), f.GetGeometryRef().GetY()) for f in tile.GetLayerByName("vertices")}
        check("(g) accuracy reports every level, level 0 with the tiles' distinct vertices",
              len(rows) == 15 and rows[0]["vertices"] == len(distinct), (len(rows), rows[0].get("vertices"), len(distinct)))
        check("(g) ... each level's largest error at the cells is the build's certified one",
              all(abs(r["max_abs_error_m"] - r["certified_error_m"]) < 1e-6 for r in rows),
              [(r["max_abs_error_m"], r["certified_error_m"]) for r in rows])
        # -compare_insert reads the tiles as one hierarchy at once; without it they are
        # measured a tile at a time: the same points and values, summed in another order.
        whole_report = os.path.join(work, "accuracy_whole.json")
        whole = run([tinlod, "accuracy", dem, catalogue, "-reference", "dem", "-report", whole_report,
                     "-compare_insert", "-q"])
        check("(g) accuracy -compare_insert on the catalogue succeeds", whole.returncode == 0, whole.stderr[-2000:])
        if whole.returncode == 0:
            with open(whole_report) as f:
                as_one = json.load(f)["runs"][0]["levels"]
            check("(g) tile by tile, accuracy is that of the tiles read as one hierarchy",
                  len(as_one) == len(rows) and all(
                      a["test_points"] == b["test_points"] and a["vertices"] == b["vertices"]
                      and a["max_abs_error_m"] == b["max_abs_error_m"]
                      and abs(a["rmse_m"] - b["rmse_m"]) <= 1e-9 * b["rmse_m"]
                      and abs(a["morans_i"] - b["morans_i"]) <= 1e-9 for a, b in zip(rows, as_one)),
                  [(a["rmse_m"], b["rmse_m"], a["test_points"], b["test_points"]) for a, b in zip(rows, as_one)])


def border_agreement(base, options, work, env):
    """(h) Under -method error -max_error the tiles agree their lines in rounds: the run ends
    with no tile refusing a line vertex, the union conforming at every level, and a rerun
    after a kept cell was added to the keep file builds the two tiles of its line again."""
    catalogue = os.path.join(work, "e.gpkg")
    bounded = options + ["-method", "error", "-max_error", "2"]
    first = run(base + [catalogue] + bounded, env)
    check("(h) the bounded run succeeds", first.returncode == 0, first.stderr[-2000:])
    check("(h) its tiles agreed their lines in a second round", "border agreement, round 2" in first.stdout,
          first.stdout[-2000:])
    check("(h) the summary counts the 6 tiles once (the empty one run, not skipped), and the builds and rounds apart",
          re.search(r"^6 tiles run \(\d+ builds in \d rounds of border agreement\), 0 skipped", first.stdout, re.M),
          first.stdout[-2000:])
    folder = os.path.join(work, "e_tiles")
    found = rows(catalogue)[0]
    files = [os.path.join(work, r["file"]) for r in found.values() if r["status"] == "done"]
    metadata = [gdal.OpenEx(f).GetMetadata_Dict() for f in files]
    check("(h) every tile was built agreed, and none refuses a line vertex any more",
          len(files) == 5 and all(m.get("TINLOD_BORDER_AGREED") == "yes" and not m.get("TINLOD_BORDER_REFUSED")
                                  for m in metadata), [(m.get("TINLOD_BORDER_AGREED"), m.get("TINLOD_BORDER_REFUSED")) for m in metadata])
    with open(os.path.join(folder, "border_keep.txt")) as f:
        kept = [tuple(int(v) for v in line.split()) for line in f if line.strip()]
    check("(h) the keep file lists the refused cells, each on a shared line",
          kept and all(r % TILE_SIZE == 0 or c % TILE_SIZE == 0 for r, c in kept), kept[:10])
    union = subprocess.run(["/usr/bin/python3", os.path.join(os.path.dirname(os.path.abspath(__file__)), "tile_union.py")]
                           + files, capture_output=True, text=True)
    levels = union.stdout.count("conforming=yes")
    check("(h) the union of the tiles is conforming at every level",
          union.returncode == 0 and levels >= 10 and "conforming=no" not in union.stdout, union.stdout[-2000:])
    rerun = run(base + [catalogue] + bounded, env)
    check("(h) a rerun builds nothing", rerun.returncode == 0 and "0 tiles run" in rerun.stdout, rerun.stdout)
    # A run stopped before the rounds ended leaves a tile that refused line vertices its
    # neighbour deleted: the tiles do not meet there, and readers say so.
    tinlod = options[options.index("-tinlod") + 1]
    refusing = os.path.join(folder, "tile_1_0.gpkg")
    saved = open(refusing, "rb").read()
    dataset = gdal.OpenEx(refusing, gdal.OF_VECTOR | gdal.OF_UPDATE)
    dataset.SetMetadataItem("TINLOD_BORDER_REFUSED", "5 %d" % TILE_SIZE)
    dataset = None
    lod = run([tinlod, "lod", catalogue, os.path.join(work, "e_lod.gpkg"), "-max_error", "5"])
    merged = run([base[0], "merge", catalogue, "-level", "0", os.path.join(work, "e_merged.gpkg")])
    with open(refusing, "wb") as f:
        f.write(saved)
    check("(h) a catalogue whose tiles have not agreed their lines yet is refused by tinlod lod and merge, "
          "saying to run tinlod tiles again",
          all(r.returncode == 1 and "before its tiles agreed their shared lines" in r.stderr for r in (lod, merged)),
          (lod.stderr[-500:], merged.stderr[-500:]))
    # A driver stopped between two rounds left a keep file the tiles were not built with.
    cell = next((r, TILE_SIZE) for r in range(1, TILE_SIZE) if (r, TILE_SIZE) not in kept)
    with open(os.path.join(folder, "border_keep.txt"), "a") as f:
        f.write("%d %d\n" % cell)
    before = file_times(folder)
    resumed = run(base + [catalogue] + bounded, env)
    after = file_times(folder)
    changed = sorted(name for name in before if after.get(name) != before[name])
    check("(h) after a cell of the line between tiles 0,0 and 1,0 was kept, a rerun builds those two again",
          resumed.returncode == 0 and "4 skipped" in resumed.stdout
          and {"tile_0_0.gpkg", "tile_1_0.gpkg"} <= set(changed), (changed, resumed.stdout))
    metadata = gdal.OpenEx(os.path.join(folder, "tile_0_0.gpkg")).GetMetadata_Dict()
    check("(h) ... with that cell kept", "%d %d" % cell in (metadata.get("TINLOD_BORDER_KEPT") or "").split(";"),
          metadata.get("TINLOD_BORDER_KEPT"))


def ctrl_c(dem, tiles, work, env, stop=signal.SIGINT, started_ignoring=False):
    """(i) Ctrl-C while tiles are being built: the run stops at once (exit 130), the tiles'
    tinlods end with it, and the tiles stay pending. The tinlod here sleeps, so that only
    the stop can end the tasks. SIGTERM (a batch scheduler's) and SIGHUP (a closed
    terminal) stop it alike, and so does SIGINT where a script's shell started the run in
    the background, ignoring SIGINT (`started_ignoring`), as it stops tinlod."""
    name = signal.Signals(stop).name + ("_ignored" if started_ignoring else "")
    sleeper, pids = os.path.join(work, "sleeping_tinlod"), os.path.join(work, "sleeping_%s.pids" % name)
    with open(sleeper, "w") as f:
        # -check and --version (which the driver asks beside the checks) answer at once.
        f.write('#!/bin/sh\nfor a in "$@"; do case "$a" in -check|--version) exit 0;; esac; done\n'
                'echo $$ >> %s\nexec sleep 120\n' % pids)
    os.chmod(sleeper, 0o755)
    catalogue = os.path.join(work, "g_%s.gpkg" % name)
    driver = subprocess.Popen([tiles, dem, catalogue, "-tile_size", str(TILE_SIZE), "-workers", "2", "-selection", "tile",
                               "-tinlod", sleeper], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env,
                              preexec_fn=(lambda: signal.signal(signal.SIGINT, signal.SIG_IGN)) if started_ignoring else None)
    started = []
    deadline = time.monotonic() + 60
    while len(started) < 2 and time.monotonic() < deadline and driver.poll() is None:
        time.sleep(0.1)
        started = open(pids).read().split() if os.path.exists(pids) else []
    check("(i) both workers are building a tile (%s)" % name, len(started) == 2, started)
    driver.send_signal(stop)
    stopping = time.monotonic()
    try:
        out, err = driver.communicate(timeout=30)
    except subprocess.TimeoutExpired:
        driver.kill()
        out, err = driver.communicate()
    took = time.monotonic() - stopping
    check("(i) %s stops the run within 10 s with exit code 130" % name, driver.returncode == 130 and took < 10,
          (driver.returncode, took, err[-1000:]))
    time.sleep(0.5)  # the signal's delivery
    alive = [p for p in started if os.path.exists("/proc/%s" % p) and "Z" not in open("/proc/%s/stat" % p).read().split()[2]]
    check("(i) the tiles' tinlods ended with the run (%s)" % name, not alive, alive)
    pending = [r["status"] for r in rows(catalogue)[0].values()]
    check("(i) the tiles stay pending (the empty one found so) for a rerun (%s)" % name,
          pending.count("pending") >= 5 and "done" not in pending, pending)
    check("(i) the message counts the tiles the catalogue has pending (%s)" % name,
          ("%d tiles left pending in" % pending.count("pending")) in err, (pending, err[-500:]))


def hangup_under_nohup(dem, tiles, work, env):
    """(i) Under nohup (SIGHUP ignored) a closed terminal does not stop a run, which must
    outlive it: SIGHUP mid-run, and the run ends as without it."""
    catalogue = os.path.join(work, "nohup.gpkg")
    driver = subprocess.Popen([tiles, dem, catalogue, "-tile_size", str(TILE_SIZE), "-workers", "2", "-q"],
                              stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env,
                              preexec_fn=lambda: signal.signal(signal.SIGHUP, signal.SIG_IGN))
    deadline = time.monotonic() + 60
    while not os.path.exists(catalogue) and time.monotonic() < deadline and driver.poll() is None:
        time.sleep(0.05)
    driver.send_signal(signal.SIGHUP)
    out, err = driver.communicate(timeout=300)
    statuses = [r["status"] for r in rows(catalogue)[0].values()] if driver.returncode == 0 else []
    check("(i) under nohup, SIGHUP leaves the run to finish (exit 0, every tile built)",
          driver.returncode == 0 and statuses and "pending" not in statuses, (driver.returncode, statuses, err[-1000:]))


def hangup_of_the_terminal(dem, tiles, work, env):
    """(i) The terminal closing under a run (a dropped ssh session) stops it as Ctrl-C does:
    exit 130 and the level files over the tiles done, though writing to the terminal now
    fails (EIO), which could happen before the hangup's signal is handled."""
    catalogue = os.path.join(work, "hangup.gpkg")
    folder = os.path.join(work, "hangup_tiles")
    pid, terminal = pty.fork()
    if pid == 0:  # the run, on the terminal
        os.execve(tiles, [tiles, dem, catalogue, "-tile_size", str(TILE_SIZE), "-workers", "1", "-selection", "tile"], env)
    deadline = time.monotonic() + 60
    while time.monotonic() < deadline and not any(re.fullmatch(r"tile_\d+_\d+\.gpkg", n) for n in (
            os.listdir(folder) if os.path.isdir(folder) else [])):
        try:
            os.read(terminal, 65536)  # what it shows, read as a terminal would
        except OSError:
            break
    os.close(terminal)  # the terminal goes: the kernel hangs up its session
    _, status = os.waitpid(pid, 0)
    code = os.waitstatus_to_exitcode(status)
    levels = os.path.join(work, "hangup_levels")
    check("(i) a closed terminal stops the run as Ctrl-C does: exit 130, the level files over the tiles done",
          code == 130 and os.path.isfile(os.path.join(levels, "level_0.vrt")), (code, os.listdir(work)))


def slow_tinlod(tinlod, work, name, case):
    """A tinlod that sleeps in the runs matching a shell `case` pattern of its arguments."""
    path = os.path.join(work, name)
    with open(path, "w") as f:
        f.write('#!/bin/sh\ncase " $* " in %s esac\nexec "%s" "$@"\n' % (case, tinlod))
    os.chmod(path, 0o755)
    return path


def interrupted_run(args, env, folder, files, wanted, settle):
    """Runs tinlod-tiles until `wanted` files of the tiles folder match `files`, waits
    `settle` seconds, then sends Ctrl-C (SIGINT); returns its exit code and stderr."""
    driver = subprocess.Popen(args, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env)
    deadline = time.monotonic() + 60
    while time.monotonic() < deadline and driver.poll() is None and len(
            [n for n in (os.listdir(folder) if os.path.isdir(folder) else []) if re.fullmatch(files, n)]) < wanted:
        time.sleep(0.1)
    time.sleep(settle)
    driver.send_signal(signal.SIGINT)
    try:
        _, err = driver.communicate(timeout=30)
    except subprocess.TimeoutExpired:
        driver.kill()
        _, err = driver.communicate()
    return driver.returncode, err


def ctrl_c_with_tiles_done(tinlod, dem, tiles, work, env):
    """(i) Ctrl-C once some tiles are done: their levels are there as one layer each
    (<stem>_levels/level_K.vrt) for QGIS and ogrinfo, as after a run that ends."""
    slow = slow_tinlod(tinlod, work, "slow_build_tinlod", '*" -check "*) ;; *" -tile 1,0 "*) exec sleep 120;;')
    catalogue = os.path.join(work, "k.gpkg")
    code, err = interrupted_run([tiles, dem, catalogue, "-tile_size", str(TILE_SIZE), "-workers", "2", "-selection", "tile",
                                 "-tinlod", slow], env, os.path.join(work, "k_tiles"), r"tile_\d+_\d+\.gpkg", 4, 1)
    done = [k for k, r in rows(catalogue)[0].items() if r["status"] == "done"]
    vrt = os.path.join(work, "k_levels", "level_0.vrt")
    layers = open(vrt).read().count("<OGRVRTLayer") if os.path.isfile(vrt) else -1
    check("(i) Ctrl-C with %d tiles done leaves their level layers (level_0.vrt over %d tiles)" % (len(done), layers),
          code == 130 and done and layers == len(done), (code, done, layers, err[-500:]))


def ctrl_c_in_survey(tinlod, dem, tiles, work, env):
    """(i) Ctrl-C in the survey pass, when every survey but one has ended: every tile is
    still to build, and the message says so (it once counted the one survey left)."""
    slow = slow_tinlod(tinlod, work, "slow_survey_tinlod", '*" -tile 1,0 "*" -survey "*) exec sleep 120;;')
    catalogue = os.path.join(work, "s.gpkg")
    code, err = interrupted_run([tiles, dem, catalogue, "-tile_size", str(TILE_SIZE), "-workers", "2", "-tinlod", slow],
                                env, os.path.join(work, "s_tiles"), r".*\.json", 4, 0.5)
    statuses = [r["status"] for r in rows(catalogue)[0].values()]
    left = statuses.count("pending")
    check("(i) Ctrl-C in the survey pass counts every tile still to build (%d), not the surveys left" % left,
          code == 130 and left >= 5 and ("%d tiles left pending in" % left) in err, (code, statuses, err[-500:]))
    # The rerun reuses the surveys that ended and counts them: a survey and a build each
    # (the stopped survey of tile 1,0 is not a try; it was 1 for the reused ones).
    rerun = run([tiles, dem, catalogue, "-tile_size", str(TILE_SIZE), "-workers", "2", "-tinlod", tinlod], env)
    attempts = {k: r["attempts"] for k, r in rows(catalogue)[0].items() if r["status"] == "done"}
    check("(i) after the rerun, every tile counts its survey and its build (%s)" % sorted(set(attempts.values())),
          rerun.returncode == 0 and len(attempts) >= 5 and set(attempts.values()) == {2}, (attempts, rerun.stderr[-500:]))


def holed_dem(path):
    """300 x 300 cells of 30 m with a one-cell hole every 10 cells each way: 900 holes, whose
    outlines' vertices stay, 20 % of the vertices."""
    size, values = 300, []
    for r in range(size):
        for c in range(size):
            hole = r % 10 == 5 and c % 10 == 5
            values.append(float("nan") if hole else 500 + 3 * r + 2 * c + 20 * math.sin(0.1 * r) * math.cos(0.07 * c))
    dataset = gdal.GetDriverByName("GTiff").Create(path, size, size, 1, gdal.GDT_Float32)
    dataset.SetGeoTransform([500000, 30, 0, 5000000, 0, -30])
    srs = osr.SpatialReference()
    srs.ImportFromEPSG(32632)
    dataset.SetProjection(srs.ExportToWkt())
    dataset.GetRasterBand(1).SetNoDataValue(float("nan"))
    dataset.GetRasterBand(1).WriteRaster(0, 0, size, size, struct.pack("%df" % len(values), *values),
                                         buf_type=gdal.GDT_Float32)
    dataset = None


def stop_warning(tiles, tinlod, work, env):
    """The union's coarsest level well above -stop_pct is said, as a whole run says it, with
    why; not when -max_levels stops the levels on purpose."""
    dem = os.path.join(work, "holed.tif")
    holed_dem(dem)
    held = run([tiles, dem, os.path.join(work, "holed.gpkg"), "-tile_size", str(TILE_SIZE), "-tinlod", tinlod], env)
    check("a tiled run whose outlines stay says its coarsest level keeps more than -stop_pct, and why",
          held.returncode == 0 and "the tiles' coarsest level (14) keeps about 20.7 % of level 0's vertices" in held.stderr
          and "the last levels deleted almost nothing" in held.stderr, held.stderr[-1000:])
    capped = run([tiles, dem, os.path.join(work, "capped.gpkg"), "-tile_size", str(TILE_SIZE), "-tinlod", tinlod,
                  "--", "-max_levels", "3"], env)
    check("with -max_levels the tiled run does not warn of the stop", capped.returncode == 0
          and "coarsest level" not in capped.stderr, capped.stderr[-1000:])


def union_counts(files):
    """Each level's vertex count of the tiles' union (tile_union.py)."""
    with tempfile.NamedTemporaryFile(suffix=".json", delete=False) as f:
        path = f.name
    subprocess.run(["/usr/bin/python3", os.path.join(os.path.dirname(os.path.abspath(__file__)), "tile_union.py"),
                    "--json", path] + files, capture_output=True, text=True, check=True)
    with open(path) as f:
        counts = [r["vertices"] for r in json.load(f)]
    os.remove(path)
    return counts


def exact_stop(base, options, work, env):
    """(l) -exact_stop: a second survey pass, made as the build pass deletes, sets the stop
    level: the union's coarsest level ends at -stop_pct (5 %) of its level 0's vertices; a run
    without it has the same levels above it."""
    def tile_files(stem):
        folder = os.path.join(work, stem + "_tiles")
        return folder, sorted(os.path.join(folder, n) for n in os.listdir(folder) if n.endswith(".gpkg"))

    first = run(base + [os.path.join(work, "exact.gpkg"), "-exact_stop"] + options, env)
    without = run(base + [os.path.join(work, "plain.gpkg")] + options, env)
    failed = [r for r in (first, without) if r.returncode != 0]
    if failed:  # say what the run said, where listing its missing tiles folder would hide it
        check("(l) -exact_stop: both runs succeed", False, failed[0].stderr[-2000:])
        return
    folder, files = tile_files("exact")
    exact, plain = union_counts(files), union_counts(tile_files("plain")[1])
    off = [abs(c[-1] - 0.05 * c[0]) / (0.05 * c[0]) for c in (exact, plain)]
    # The level that reaches the stop is the first that differs; the levels after it delete nothing.
    stop = next((k for k, (a, b) in enumerate(zip(exact, plain)) if a != b), len(exact))
    check("(l) -exact_stop sets the stop level alone and ends the union's coarsest level within 1 %% of -stop_pct "
          "(%d vertices, the stop %.0f)" % (exact[-1], 0.05 * exact[0]),
          first.returncode == 0 and without.returncode == 0 and "second survey pass (-exact_stop): 5 tiles" in first.stdout
          and off[0] < 0.01 and 0 < stop < len(exact) and set(exact[stop:]) == {exact[-1]},
          (exact, plain, first.stdout + first.stderr[-1000:]))
    # The surveys walk every candidate: the first pass's thresholds delete what they aim at.
    check("(l) without it the levels delete the delete percentage: within 2 %% of the stop too (%d)" % plain[-1],
          off[1] < 0.02 and all(abs(b / a - 0.8) < 0.01 for a, b in zip(plain[:8], plain[1:9])), plain)
    check("(l) ... and leaves no survey behind, the catalogue recording TINLOD_EXACT_STOP=yes",
          not [n for n in os.listdir(folder) if "survey" in n]
          and rows(os.path.join(work, "exact.gpkg"))[2].get("TINLOD_EXACT_STOP") == "yes"
          and not rows(os.path.join(work, "plain.gpkg"))[2].get("TINLOD_EXACT_STOP"), os.listdir(folder))
    finished = run(base + [os.path.join(work, "plain.gpkg"), "-exact_stop"] + options, env)
    check("(l) ... -exact_stop on a finished catalogue made without it says so too (nothing is built)",
          finished.returncode == 0 and "set without -exact_stop" in finished.stderr
          and "0 tiles run" in finished.stdout, finished.stdout + finished.stderr[-1000:])
    os.remove(os.path.join(work, "plain_tiles", "tile_0_0.gpkg"))
    late = run(base + [os.path.join(work, "plain.gpkg"), "-exact_stop"] + options, env)
    check("(l) -exact_stop on a catalogue whose thresholds were set without it says they are reused, naming -overwrite",
          late.returncode == 0 and "set without -exact_stop" in late.stderr and "-overwrite" in late.stderr
          and "second survey pass" not in late.stdout, late.stdout + late.stderr[-1000:])
    tile = run(base + [os.path.join(work, "x.gpkg"), "-exact_stop", "-selection", "tile"] + options, env)
    check("(l) -exact_stop with -selection tile is refused", tile.returncode == 1 and "-exact_stop" in tile.stderr
          and not os.path.exists(os.path.join(work, "x.gpkg")), tile.stderr)


class DaskProcess:
    """`dask scheduler` or `dask worker`, started as a user starts them, ended whatever happens."""

    def __init__(self, args, env=None):
        self.log = tempfile.TemporaryFile()
        self.process = subprocess.Popen(["dask"] + args, stdout=self.log, stderr=subprocess.STDOUT, env=env,
                                        start_new_session=True)

    def said(self, pattern, seconds=60):
        """The first match of `pattern` in what it printed, waited for; None after `seconds`."""
        deadline = time.monotonic() + seconds
        while time.monotonic() < deadline and self.process.poll() is None:
            self.log.seek(0)
            found = re.search(pattern, self.log.read().decode(errors="replace"))
            if found:
                return found
            time.sleep(0.2)
        return None

    def end(self, how=signal.SIGTERM):
        if self.process.poll() is None:
            os.killpg(self.process.pid, how)
        try:
            self.process.wait(timeout=20)
        except subprocess.TimeoutExpired:
            os.killpg(self.process.pid, signal.SIGKILL)
            self.process.wait()


def start_scheduler():
    """A scheduler on a free port of this machine; (process, its address) or (None, None)."""
    scheduler = DaskProcess(["scheduler", "--host", "127.0.0.1", "--port", "0", "--dashboard-address", ":0"])
    found = scheduler.said(r"Scheduler at:\s+(tcp://[\d.]+:\d+)")
    if not found:
        scheduler.end(signal.SIGKILL)
        return None, None
    return scheduler, found.group(1)


def thread_logging_tinlod(tinlod, work, log):
    """A tinlod that notes the TINLOD_THREADS a task gave it (not the driver's -check runs),
    then runs as tinlod."""
    path = os.path.join(work, "noting_tinlod")
    with open(path, "w") as f:
        f.write('#!/bin/sh\ncase " $* " in *" -check "*) ;; *" -tile "*) echo "threads=${TINLOD_THREADS:-unset}" >> "%s";; '
                'esac\nexec "%s" "$@"\n' % (log, tinlod))
    os.chmod(path, 0o755)
    return path


def remote_cluster(tinlod, tiles, dem, work, env):
    """(j) -scheduler on a scheduler and a worker started as docs/cli/tiles.md says: a scheduler
    without workers is said, not waited on in silence; the workers keep their own TINLOD_THREADS;
    a scheduler killed mid-run leaves the unfinished tiles pending (not failed with no message)
    in one line, and the same command finishes them on a new scheduler."""
    if shutil.which("dask") is None:
        print("(j) SKIPPED: no `dask` command (python3-distributed's)")
        return
    scheduler, address = start_scheduler()
    workers = []
    try:
        check("(j) `dask scheduler` starts and says its address", address is not None)
        if address is None:
            return
        catalogue = os.path.join(work, "remote.gpkg")
        args = [tiles, dem, catalogue, "-tile_size", str(TILE_SIZE), "-scheduler", address]
        quiet = dict(env, TINLOD_TILES_TEST_NO_WORKERS="1")
        driver = subprocess.Popen(args + ["-tinlod", tinlod], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                                  env=quiet)
        said = []
        reader = threading.Thread(target=lambda: said.extend(driver.stderr), daemon=True)
        reader.start()
        deadline = time.monotonic() + 60
        while time.monotonic() < deadline and not any("has had no worker for" in line for line in said):
            time.sleep(0.2)
        driver.send_signal(signal.SIGINT)
        driver.wait(timeout=30)
        reader.join(timeout=5)
        check("(j) a scheduler without workers is said (%s), and Ctrl-C then stops the run (exit %s)"
              % ("".join(said)[:80], driver.returncode),
              any(("the Dask scheduler %s has had no worker for 1 s" % address) in line and ("dask worker %s" % address)
                  in line for line in said) and driver.returncode == 130, "".join(said)[-1500:])

        log = os.path.join(work, "remote_threads.txt")
        noting = thread_logging_tinlod(tinlod, work, log)
        workers.append(DaskProcess(["worker", address, "--nthreads", "1", "--no-dashboard"], dict(env, TINLOD_THREADS="1")))
        workers.append(DaskProcess(["worker", address, "--nthreads", "2", "--no-dashboard"], dict(env, TINLOD_THREADS="1")))
        for worker in workers:
            worker.said(r"Registered to:")
        finished = run(args + ["-tinlod", noting], dict(env, TINLOD_THREADS="7"))
        check_complete(catalogue, "(j) -scheduler")
        threads = set(open(log).read().split()) if os.path.isfile(log) else set()
        check("(j) the tiles' tinlods keep their worker's TINLOD_THREADS, not the driver's (%s)" % sorted(threads),
              finished.returncode == 0 and threads == {"threads=1"}, (threads, finished.stderr[-1000:]))
        check("(j) a worker that runs 2 tiles at once (--nthreads 2) is said, once; the other is not",
              finished.stderr.count("runs 2 tiles at once (--nthreads 2)") == 1
              and "runs 1 tiles" not in finished.stderr, finished.stderr[-1500:])

        lost = os.path.join(work, "lost.gpkg")
        slow = slow_tinlod(tinlod, work, "slow_remote_tinlod", '*" -check "*) ;; *" -tile 0,1 "*) sleep 30;;')
        driver = subprocess.Popen([tiles, dem, lost, "-tile_size", str(TILE_SIZE), "-scheduler", address, "-tinlod", slow, "-q"],
                                  stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env)
        folder = os.path.join(work, "lost_tiles")
        deadline = time.monotonic() + 60
        while time.monotonic() < deadline and not (os.path.isdir(folder) and any(
                re.fullmatch(r"tile_\d+_\d+\.survey\.json", n) for n in os.listdir(folder))):
            time.sleep(0.1)
        scheduler.end(signal.SIGKILL)
        _, err = driver.communicate(timeout=60)
        statuses = sorted(r["status"] for r in rows(lost)[0].values())
        check("(j) a scheduler killed mid-run: one line, the tiles left pending, none failed (%s)" % statuses,
              driver.returncode == 1 and ("the Dask scheduler %s stopped running the tiles (its connection was lost)"
                                          % address) in err and "Traceback" not in err and "failed" not in statuses
              and "pending" in statuses and len([line for line in err.strip().split("\n")
                                                 if not line.startswith("Warning: the Dask worker")]) == 1,
              (statuses, err[-2000:]))
        for worker in workers:
            worker.end()
        scheduler, address = start_scheduler()
        workers = [DaskProcess(["worker", address, "--nthreads", "1", "--no-dashboard"], env)]
        again = run([tiles, dem, lost, "-tile_size", str(TILE_SIZE), "-scheduler", address, "-tinlod", tinlod], env)
        check("(j) the same command on a new scheduler finishes the catalogue", again.returncode == 0, again.stderr[-1500:])
        check_complete(lost, "(j) after the scheduler was lost")
    finally:
        for worker in workers:
            worker.end()
        if scheduler:
            scheduler.end()


def point_count(path):
    dataset = ogr.Open(path)  # held: a layer dies with its dataset
    return dataset.GetLayerByName("points").GetFeatureCount()


def catalogue_guard_cases(tiles, dem, work, program):
    """-overwrite removes the catalogue before a new one is written: never an input's file,
    never someone's other data, never a GeoPackage another program has open."""
    options = ["-tile_size", str(TILE_SIZE), "-tinlod", program, "-overwrite"]
    raster = os.path.join(work, "dem_in.gpkg")
    gdal.Translate(raster, dem, format="GPKG")
    before = os.path.getsize(raster)
    itself = run([tiles, raster, raster] + options)
    check("-overwrite with the catalogue named as the DEM is refused, and the DEM is left as it was",
          itself.returncode == 1 and ("%s is an input of this job" % raster) in itself.stderr
          and os.path.getsize(raster) == before and gdal.Open(raster) is not None, itself.stderr[-1500:])
    points = make_points(dem, os.path.join(work, "keep.gpkg"))
    fixed = run([tiles, dem, points] + options + ["--", "-fixed", points])
    check("... as is the catalogue named as the -fixed points, which are kept",
          fixed.returncode == 1 and "is an input of this job" in fixed.stderr
          and point_count(points) == 1, fixed.stderr[-1500:])
    other = make_points(dem, os.path.join(work, "someones.gpkg"))
    others = run([tiles, dem, other] + options)
    check("-overwrite on a GeoPackage that is no catalogue is refused, naming what it is",
          others.returncode == 1 and "exists and is no tinlod-tiles catalogue (GDAL reads it as GPKG)" in others.stderr
          and point_count(other) == 1, others.stderr[-1500:])
    held = make_points(dem, os.path.join(work, "held.gpkg"))
    connection = sqlite3.connect(held)
    connection.execute("PRAGMA journal_mode=WAL")
    connection.execute("CREATE TABLE notes(a)")
    connection.commit()
    try:
        in_use = run([tiles, dem, held] + options)
    finally:
        connection.close()
    check("-overwrite on a GeoPackage another program has open (its write-ahead log in use) is refused",
          in_use.returncode == 1 and "is open in another program" in in_use.stderr
          and "close it there, then run again" in in_use.stderr, in_use.stderr[-1500:])
    writing = make_points(dem, os.path.join(work, "writing.gpkg"))
    connection = sqlite3.connect(writing, isolation_level=None)
    connection.execute("BEGIN EXCLUSIVE")
    connection.execute("CREATE TABLE notes(a)")
    try:
        locked = run([tiles, dem, writing] + options)
    finally:
        connection.execute("ROLLBACK")
        connection.close()
    check("-overwrite on a GeoPackage another program is writing (locked) is refused, not taken for a damaged one",
          locked.returncode == 1 and "is being written by another program" in locked.stderr
          and point_count(writing) == 1, locked.stderr[-1500:])


def main(tinlod, tiles):
    try:
        import distributed  # noqa: F401
    except ImportError:
        print("SKIPPED: python3-distributed is absent (apt install python3-distributed)")
        return SKIPPED
    work = tempfile.mkdtemp(prefix="tinlod_tiles_test_")
    env = dict(os.environ)
    env.pop("TINLOD_TILES_TEST_KILL", None)
    program = tinlod
    dem = os.path.join(work, "dem.tif")
    make_dem(tinlod, dem)
    base = [tiles, dem]
    options = ["-tile_size", str(TILE_SIZE), "-workers", "2", "-tinlod", program, "--", "-seed", "5"]

    check("tinlod tiles --help is tinlod-tiles --help, and so is tinlod-tiles merge --help",
          run([tinlod, "tiles", "--help"]).stdout == run([tiles, "--help"]).stdout == run([tiles, "merge", "--help"]).stdout)
    version = run([tiles, "--version"])
    check("tinlod-tiles --version names the tinlod it runs", version.returncode == 0
          and version.stdout.startswith("tinlod-tiles, running tinlod ") and "GDAL" in version.stdout, version.stdout)
    bad = run(base + [os.path.join(work, "x.gpkg"), "-tile_size", "100", "-tinlod", program])
    check("-tile_size not a multiple of -block is refused, naming both",
          bad.returncode == 1 and "-tile_size 100" in bad.stderr and "-block 3" in bad.stderr, bad.stderr)
    levelless = run(base + [os.path.join(work, "t1.gpkg"), "-tile_size", str(TILE_SIZE), "-tinlod", program,
                            "--", "-threshold", "1e6"])
    check("-threshold without -max_levels is refused before any tile runs",
          levelless.returncode == 1 and "-threshold in a tiled run needs -max_levels" in levelless.stderr
          and not os.path.exists(os.path.join(work, "t1.gpkg")), levelless.stderr)
    away = run(base + [os.path.join(work, "away.gpkg"), "-tile_size", str(TILE_SIZE), "-scheduler", "tcp://127.0.0.1:9",
                       "-tinlod", program])
    check("an unreachable -scheduler is an error, and no catalogue is made",
          away.returncode == 1 and "cannot reach the Dask scheduler tcp://127.0.0.1:9" in away.stderr
          and not os.path.exists(os.path.join(work, "away.gpkg")), away.stderr[-1500:])
    for address, said in (("", "-scheduler '': give the scheduler's address"),  # -scheduler "$UNSET"
                          ("127.0.0.1:99999", "port 99999 is out of range (1 to 65535)"),
                          ("http://127.0.0.1:9", "unknown address scheme 'http'")):
        wrong = run(base + [os.path.join(work, "wrong.gpkg"), "-tile_size", str(TILE_SIZE), "-scheduler", address,
                            "-tinlod", program])
        check("-scheduler %r is refused with its reason (%s), and nothing is written" % (address, said),
              wrong.returncode == 1 and said in wrong.stderr and not os.path.exists(os.path.join(work, "wrong.gpkg")),
              wrong.stderr[-1500:])
    on_path = dict(env, PATH=os.path.dirname(os.path.abspath(program)) + os.pathsep + env.get("PATH", ""))
    named = run(base + [os.path.join(work, "named.gpkg"), "-tile_size", str(TILE_SIZE), "-tinlod", "nosuchtinlod"], on_path)
    check("-tinlod NAME not on PATH says so", named.returncode == 1
          and "-tinlod nosuchtinlod: no program of that name on PATH; give its path" in named.stderr, named.stderr[-1000:])
    named = run(base + [os.path.join(work, "named.gpkg"), "-tile_size", str(TILE_SIZE), "-tinlod",
                        os.path.basename(program), "--", "-threshold", "1e6"], on_path)
    check("-tinlod NAME is found on PATH, as a shell finds it (the job's own check then runs it)", named.returncode == 1
          and "-threshold in a tiled run needs -max_levels" in named.stderr, named.stderr[-1000:])
    # A port that takes connections but is no scheduler (another server; a proxy taking them all).
    impostor = socket.socket()
    impostor.bind(("127.0.0.1", 0))
    impostor.listen(8)

    def hang_up():
        while True:
            try:
                impostor.accept()[0].close()
            except OSError:  # closed below
                return
    threading.Thread(target=hang_up, daemon=True).start()
    address = "tcp://127.0.0.1:%d" % impostor.getsockname()[1]
    silent = run(base + [os.path.join(work, "silent.gpkg"), "-tile_size", str(TILE_SIZE), "-scheduler", address,
                         "-tinlod", program])
    impostor.close()
    mute = socket.socket()  # takes connections and holds them, never answering: Dask waits 20 s
    mute.bind(("127.0.0.1", 0))
    mute.listen(8)
    held = []

    def hold():
        while True:
            try:
                held.append(mute.accept()[0])
            except OSError:  # closed below
                return
    threading.Thread(target=hold, daemon=True).start()
    waiting = subprocess.Popen(base + [os.path.join(work, "silent.gpkg"), "-tile_size", str(TILE_SIZE), "-scheduler",
                                       "tcp://127.0.0.1:%d" % mute.getsockname()[1], "-tinlod", program],
                               stderr=subprocess.PIPE, text=True)
    time.sleep(3)  # past the checks, waiting on the port
    waiting.send_signal(signal.SIGINT)
    _, said = waiting.communicate(timeout=30)
    for connection in held:
        connection.close()
    mute.close()
    check("Ctrl-C while a silent -scheduler port is waited on says nothing was written (no catalogue to resume)",
          waiting.returncode == 130 and "stopped before the end; nothing was written" in said
          and not os.path.exists(os.path.join(work, "silent.gpkg")), said[-1000:])
    check("a -scheduler port that answers but not as Dask is an error before anything is written",
          silent.returncode == 1 and ("no Dask scheduler answers at %s" % address) in silent.stderr
          and "Nothing was written" in silent.stderr and not os.path.exists(os.path.join(work, "silent.gpkg"))
          and not os.path.exists(os.path.join(work, "silent_tiles")), silent.stderr[-1500:])
    blocked = os.path.join(work, "blocked.gpkg")
    open(os.path.join(work, "blocked_tiles"), "w").close()  # a file where the tiles folder goes
    refused = run(base[:1] + [dem, blocked, "-tile_size", str(TILE_SIZE), "-tinlod", program])
    check("a file where the tiles folder goes is an error naming it as in the way, not a traceback",
          refused.returncode == 1 and ("%s is in the way" % os.path.join(work, "blocked_tiles")) in refused.stderr
          and "Traceback" not in refused.stderr and not os.path.exists(blocked), refused.stderr[-1500:])
    catalogue_guard_cases(tiles, dem, work, program)
    tiny = os.path.join(work, "tiny.tif")
    gdal.Translate(tiny, dem, srcWin=[0, 0, 1, 1])
    one_cell = run(base[:1] + [tiny, os.path.join(work, "tiny.gpkg"), "-tile_size", str(TILE_SIZE), "-tinlod", program])
    check("a DEM of one cell is refused before a catalogue is made, naming the cause",
          one_cell.returncode == 1 and "has 1 x 1 cells: a TIN needs cells in two rows and two columns" in one_cell.stderr
          and not os.path.exists(os.path.join(work, "tiny.gpkg")), one_cell.stderr[-1500:])
    zipped = os.path.join(work, "dem.zip")
    with zipfile.ZipFile(zipped, "w") as archive:
        archive.write(dem, "dem.tif")
    taken = socket.socket()  # as another run's dashboard would: no warning that the port is in use
    try:
        taken.bind(("", 8787))
        taken.listen()
    except OSError:
        pass  # already taken
    virtual = run(base[:1] + ["/vsizip/" + zipped + "/dem.tif", os.path.join(work, "z.gpkg"), "-tile_size", str(TILE_SIZE),
                              "-workers", "2", "-tinlod", program, "--", "-seed", "5"], env)
    taken.close()
    check("a run beside another (port 8787 taken) says nothing of Dask's ports", "8787" not in virtual.stderr,
          virtual.stderr[-1500:])
    statuses = sorted(r["status"] for r in rows(os.path.join(work, "z.gpkg"))[0].values()) if virtual.returncode == 0 else []
    check("a DEM given by a GDAL virtual path (/vsizip//absolute/path.zip/dem.tif) is built",
          virtual.returncode == 0 and statuses == ["done"] * 5 + ["empty"], (statuses, virtual.stderr[-1500:]))
    wrong = run(base + [os.path.join(work, "w.gpkg"), "-tile_size", str(TILE_SIZE), "-workers", "2",
                        "-tinlod", program, "--", "-delete_pct", "200"], env)
    check("build options every tile would refuse are refused once, with tinlod's message, before anything is written",
          wrong.returncode == 1 and "tinlod build refuses the job (tile 0,0): -delete_pct must be from 1 to 100 (got 200)"
          in wrong.stderr and "Nothing was written" in wrong.stderr and "tiles failed" not in wrong.stderr
          and not os.path.exists(os.path.join(work, "w.gpkg")) and not os.path.exists(os.path.join(work, "w_tiles")),
          wrong.stderr[-2000:])
    tiny = run(base + [os.path.join(work, "w.gpkg"), "-tile_size", "6", "-tinlod", program, "--", "-delete_pct", "200"],
               env)
    check("thousands of tiny tiles are warned of with their fixed costs (here before the options are refused)",
          tiny.returncode == 1 and "Warning: 3350 tiles of 6 x 6 cells: each is a task and a GeoPackage of its own"
          in tiny.stderr and "(-tile_size)" in tiny.stderr and "tiles of" not in wrong.stderr, tiny.stderr[-2000:])
    wkt = run(base + [os.path.join(work, "w.gpkg"), "-tile_size", str(TILE_SIZE), "-tinlod", program,
                      "--", "-t_srs", 'PROJCS["a",\nGEOGCS["b"]]'], env)
    check("a refusal whose message spans lines (a WKT quoted) keeps tinlod's advice after the line break",
          wkt.returncode == 1 and "GEOGCS[\"b\"]]' is not a CRS GDAL understands: use e.g." in wkt.stderr
          and not os.path.exists(os.path.join(work, "w.gpkg")), wkt.stderr[-1000:])
    beyond = run(base + [os.path.join(work, "v.gpkg"), "-tile_size", str(TILE_SIZE), "-tinlod", program,
                         "--", "-levels", "0,99"], env)
    check("-levels beyond the tiles' levels is refused before anything is written (no tile would have level 99)",
          beyond.returncode == 1 and "every tile makes levels 0 to 14" in beyond.stderr
          and not os.path.exists(os.path.join(work, "v.gpkg")), beyond.stderr[-1000:])
    failing = os.path.join(work, "failing_tinlod")  # checks as tinlod does, then fails every tile
    with open(failing, "w") as f:
        f.write('#!/bin/sh\nfor a in "$@"; do [ "$a" = -check ] && exec "%s" "$@"; done\n'
                'echo "ERROR: the worker\'s disk is full" >&2\nexit 1\n' % program)
    os.chmod(failing, 0o755)
    alike = run(base + [os.path.join(work, "f.gpkg"), "-tile_size", str(TILE_SIZE), "-workers", "2", "-retries", "0",
                        "-tinlod", failing], env)
    check("tiles that all fail alike: the error says what the tiles said, and to correct the cause with -overwrite",
          alike.returncode == 1 and "tiles failed in the survey pass; they say:" in alike.stderr
          and "the worker's disk is full" in alike.stderr and " and 5 more)" in alike.stderr
          and "every tile failed alike" in alike.stderr and "-overwrite" in alike.stderr, alike.stderr[-2000:])
    check("what the tiles said is listed without tinlod's ERROR prefix, under the run's own ERROR line",
          "\n  the worker's disk is full (tile" in alike.stderr and "ERROR: ERROR" not in alike.stderr
          and "\n  ERROR: " not in alike.stderr, alike.stderr[-2000:])
    with open(failing, "w") as f:  # the same, but the empty tile found empty (tinlod's exit 3)
        f.write('#!/bin/sh\nfor a in "$@"; do [ "$a" = -check ] && exec "%s" "$@"; [ "$a" = %d,%d ] && exit 3; done\n'
                'echo "ERROR: the worker\'s disk is full" >&2\nexit 1\n' % ((program,) + EMPTY_TILE))
    alike = run(base + [os.path.join(work, "f2.gpkg"), "-tile_size", str(TILE_SIZE), "-workers", "2", "-retries", "0",
                        "-tinlod", failing], env)
    check("... and so is it when one tile is empty and all the others fail alike",
          alike.returncode == 1 and " and 4 more)" in alike.stderr and "every tile failed alike" in alike.stderr,
          alike.stderr[-2000:])
    for retries, said in (("0", "5 tiles failed, not retried (-retries 0); they say:"),
                          ("2", "5 tiles failed after their 2 retries; they say:")):
        built = run(base + [os.path.join(work, "built_f%s.gpkg" % retries), "-tile_size", str(TILE_SIZE), "-workers", "2",
                            "-selection", "tile", "-retries", retries, "-tinlod", failing], env)
        check("tiles that fail in the build pass: the error counts them and their retries (-retries %s)" % retries,
              built.returncode == 1 and said in built.stderr, built.stderr[-2000:])
    warning = os.path.join(work, "warning_tinlod")  # tinlod with a warning of its own
    with open(warning, "w") as f:
        # The whole raster's warning, which -check gives too; the tile's own, which it does not.
        f.write('#!/bin/sh\nt=; p=; c=\nfor a in "$@"; do [ "$p" = -tile ] && t=$a; [ "$a" = -check ] && c=1; p=$a; done\n'
                'echo "Warning: 2 of the 3 points to keep fall outside" >&2\n'
                '[ -z "$c" ] && echo "Warning: tile $t has a warning of its own" >&2\n'
                'echo "Warning: 3 border vertices would take cells ...: TINLOD_BORDER_REFUSED lists them" >&2\n'
                '[ -z "$c" ] && echo "Warning: read in its CRS (UTM), level 9\'s triangles part by up to $t m" >&2\n'
                'exec "%s" "$@"\n' % program)
    os.chmod(warning, 0o755)
    warned = run(base + [os.path.join(work, "wn.gpkg"), "-tile_size", str(TILE_SIZE), "-workers", "2", "-tinlod", warning],
                 env)
    own = re.findall(r"Warning: tile (\d+,\d+): tile (\d+,\d+) has a warning of its own", warned.stderr)
    check("a warning tinlod gives on a tile is shown, naming the tile (a worker's stderr goes nowhere): each tile's own",
          warned.returncode == 0 and len(own) == 5 and all(a == b for a, b in own), warned.stderr[-2000:])
    check("... one every tile gives alike, as -check does, once, before the tiles (thousands of times in a national "
          "job, hours into it)",
          warned.stderr.count("2 of the 3 points to keep fall outside") == 1
          and warned.stderr.startswith("Warning: 2 of the 3 points to keep fall outside\n"), warned.stderr[-2000:])
    check("... one whose figures are each tile's own (the coarsest level's bend), once, for the first tile",
          warned.stderr.count("triangles part by up to") == 1, warned.stderr[-2000:])
    check("... and none the driver acts on itself (the border rule's refused cells)",
          "TINLOD_BORDER_REFUSED" not in warned.stderr, warned.stderr[-2000:])
    empty = run(base + [os.path.join(work, "e0.gpkg")] + options + ["-valid_range", "50000", "90000"], env)
    check("a job whose every tile is empty (no valid cell) is an error naming the fix, not a success",
          empty.returncode == 1 and "none of the 6 tiles has a valid cell" in empty.stderr
          and "-overwrite" in empty.stderr, empty.stdout[-500:] + empty.stderr[-1000:])

    # (a) A run: the catalogue ends complete.
    catalogue = os.path.join(work, "a.gpkg")
    first = run(base + [catalogue] + options, env)
    check("(a) the run succeeds", first.returncode == 0, first.stderr[-2000:])
    check("(a) its coarsest level is near -stop_pct: no warning of it", "coarsest level" not in first.stderr,
          first.stderr[-2000:])
    check("(a) its summary counts every tile run, none skipped (the one its survey found empty included)",
          "6 tiles run, 0 skipped" in first.stdout, first.stdout)
    found, metadata = check_complete(catalogue, "(a)")
    check("(a) the build options are recorded exactly", metadata.get("TINLOD_BUILD_OPTIONS") == "-seed 5", metadata)

    # Any GDAL raster: the same DEM as a VRT mosaic of two files gives the same tiles.
    mosaic = make_mosaic(dem, work)
    from_mosaic = run([tiles, mosaic, os.path.join(work, "m.gpkg")] + options, env)
    check("a VRT mosaic of two files runs", from_mosaic.returncode == 0, from_mosaic.stderr[-2000:])
    same = ("status", "levels", "vertices", "triangles")
    mosaic_rows = rows(os.path.join(work, "m.gpkg"))[0]
    check("a VRT mosaic of two files gives the same tiles as the DEM itself",
          {k: [r[n] for n in same] for k, r in mosaic_rows.items()} == {k: [r[n] for n in same] for k, r in found.items()},
          mosaic_rows)

    # (b) The kill hook: tile 1,0's tinlod killed mid-run on its first attempt, retried.
    killed = os.path.join(work, "b.gpkg")
    env_kill = dict(env, TINLOD_TILES_TEST_KILL="%d,%d:%g" % (KILLED_TILE + (KILL_AFTER,)))
    second = run(base + [killed] + options, env_kill)
    check("(b) the run with a killed tile succeeds", second.returncode == 0, second.stderr[-2000:])
    found_b, _ = check_complete(killed, "(b)")
    tile = found_b.get(KILLED_TILE, {})
    # attempts counts a tile's tasks, its survey's and its build's: 1 each, and 1 more for the killed try.
    check("(b) the killed tile took 4 attempts (its survey and its build each killed on their first try)",
          tile.get("attempts") == 4, tile)
    check("(b) it was killed mid-run (a whole attempt takes longer than the kill delay)",
          (tile.get("seconds") or 0) > KILL_AFTER, tile.get("seconds"))
    check("(b) the other tiles took 2 attempts, a survey and a build",
          all(r["attempts"] == 2 for k, r in found_b.items() if k != KILLED_TILE and r["status"] == "done"), found_b)
    leftovers = [n for n in os.listdir(os.path.join(work, "b_tiles")) if not re.fullmatch(r"tile_\d+_\d+\.gpkg|\.driver\.lock|line_outline\.txt", n)]
    check("(b) nothing half-written is left in the tiles folder", not leftovers, leftovers)

    # (c) A rerun does no finished tile again.
    folder = os.path.join(work, "a_tiles")
    before = file_times(folder)
    rerun = run(base + [catalogue] + options, env)
    check("(c) the rerun succeeds", rerun.returncode == 0, rerun.stderr[-2000:])
    check("(c) the rerun reports 0 run, 6 skipped", "0 tiles run, 6 skipped" in rerun.stdout, rerun.stdout)
    check("(c) no tile file was written again", file_times(folder) == before)
    os.remove(os.path.join(folder, "tile_0_1.gpkg"))
    before.pop("tile_0_1.gpkg")
    again = run(base + [catalogue] + options, env)
    check("(c) a tile whose file is gone is built again, alone", "1 tile run, 5 skipped" in again.stdout
          and os.path.isfile(os.path.join(folder, "tile_0_1.gpkg")), again.stdout + again.stderr[-1000:])
    check("(c) the resumed run's log says it is in the build pass, with the thresholds recorded",
          "build pass: one importance threshold per level for the whole raster, as the catalogue recorded them"
          in again.stdout, again.stdout)
    after = file_times(folder)
    after.pop("tile_0_1.gpkg", None)
    check("(c) ... and the others are left as they were", after == before)
    original = open(os.path.join(folder, "tile_1_0.gpkg"), "rb").read()
    copied = open(os.path.join(folder, "tile_0_0.gpkg"), "rb").read()
    for damage, content in (("another tile's file copied over it", copied), ("a truncated file", original[:100])):
        with open(os.path.join(folder, "tile_1_0.gpkg"), "wb") as f:
            f.write(content)
        repaired = run(base + [catalogue] + options, env)
        check("(c) a tile whose file is %s is said and built again, alone" % damage,
              "Warning: tile 1,0 is built again: " in repaired.stderr and "1 tile run, 5 skipped" in repaired.stdout
              and open(os.path.join(folder, "tile_1_0.gpkg"), "rb").read()[:100] == original[:100],
              repaired.stdout + repaired.stderr[-1000:])
    link = os.path.join(work, "dem_link.tif")
    os.symlink(dem, link)
    linked = run([tiles, link, catalogue] + options, env)
    check("(c) the DEM named by a link to it resumes the job", linked.returncode == 0
          and "0 tiles run, 6 skipped" in linked.stdout, linked.stdout + linked.stderr[-1000:])
    stat = os.stat(dem)
    os.utime(dem, ns=(stat.st_atime_ns, stat.st_mtime_ns + 10 ** 9))
    changed = run(base + [catalogue] + options, env)
    os.utime(dem, ns=(stat.st_atime_ns, stat.st_mtime_ns))
    check("(c) a DEM changed since the catalogue was made is refused, suggesting -overwrite",
          changed.returncode == 1 and "has changed since" in changed.stderr and "-overwrite" in changed.stderr,
          changed.stderr[-1000:])
    check("(c) ... and the catalogue records the DEM's bytes and time of change",
          ("%d bytes, changed " % stat.st_size) in (rows(catalogue)[2].get("TINLOD_SOURCE_STAMP") or ""), rows(catalogue)[2])
    other = run(base + [catalogue] + options[:-1] + ["6"], env)
    check("(c) a rerun with other build options is refused, suggesting -overwrite",
          other.returncode == 1 and "-overwrite" in other.stderr and "(in effect: -seed 5)" in other.stderr
          and "(in effect: -seed 6)" in other.stderr, other.stderr)
    version = subprocess.run([program, "--version"], capture_output=True, text=True).stdout.strip()
    check("(c) the catalogue records the build options in effect, and the tinlod that read them",
          rows(catalogue)[2].get("TINLOD_BUILD_SETTINGS") == version + ": -seed 5", (version, rows(catalogue)[2]))
    spelled = run(base + [catalogue] + options[:-2] + ["-delete_pct", "20.0", "-seed", "5", "-method", "volume", "-block", "3"], env)
    check("(c) a rerun spelling the same options another way (defaults given, 20.0, another order) resumes the job",
          spelled.returncode == 0 and "0 tiles run, 6 skipped" in spelled.stdout, spelled.stdout + spelled.stderr[-1000:])
    # A catalogue an earlier tinlod-tiles made has no such record: its recorded options are read
    # as tinlod build reads them, recorded, and compared.
    dataset = gdal.OpenEx(catalogue, gdal.OF_VECTOR | gdal.OF_UPDATE)
    metadata = dataset.GetMetadata()
    metadata.pop("TINLOD_BUILD_SETTINGS")
    dataset.SetMetadata(metadata)
    dataset = None
    earlier = run(base + [catalogue] + options[:-2] + ["-seed", "5", "-delete_pct", "20"], env)
    check("(c) ... as does one of an earlier catalogue, which gets the record",
          earlier.returncode == 0 and "0 tiles run, 6 skipped" in earlier.stdout
          and rows(catalogue)[2].get("TINLOD_BUILD_SETTINGS") == version + ": -seed 5", earlier.stdout + earlier.stderr[-1000:])
    # Recorded by another tinlod, whose defaults may differ: the options are compared as given.
    dataset = gdal.OpenEx(catalogue, gdal.OF_VECTOR | gdal.OF_UPDATE)
    dataset.SetMetadataItem("TINLOD_BUILD_SETTINGS", "tinlod 0.0.1 (GDAL 3.6.2): -seed 5")
    dataset = None
    other_version = run(base + [catalogue] + options[:-2] + ["-seed", "5", "-delete_pct", "20"], env)
    check("(c) settings another tinlod recorded are not compared: options spelled otherwise are refused",
          other_version.returncode == 1 and "was made with TINLOD_BUILD_OPTIONS=-seed 5" in other_version.stderr,
          other_version.stderr[-1000:])
    again_as_given = run(base + [catalogue] + options, env)
    check("(c) ... and the options as given resume it", again_as_given.returncode == 0
          and "0 tiles run, 6 skipped" in again_as_given.stdout, again_as_given.stdout + again_as_given.stderr[-1000:])

    # A -fixed file edited in place after the job: the finished tiles kept the old points.
    points = make_points(dem, os.path.join(work, "points.gpkg"), beyond=2)
    pinned = os.path.join(work, "p.gpkg")
    with_points = run(base + [pinned] + options + ["-fixed", points + "|layername=points"], env)
    check("(c) -fixed points beyond the DEM's extent are said to be ignored, as a whole run says",
          "Warning: 2 of the 3 points to keep (-fixed) lie beyond the DEM's extent and are ignored" in with_points.stderr,
          with_points.stderr[-1000:])
    check("(c) a job with -fixed points (a layer named as QGIS names one) runs, and records the points file's "
          "bytes and time of change",
          with_points.returncode == 0 and "bytes, changed " in (rows(pinned)[2].get("TINLOD_FIXED_STAMP") or ""),
          with_points.stderr[-1000:])
    stat = os.stat(points)
    os.utime(points, ns=(stat.st_atime_ns, stat.st_mtime_ns + 10 ** 9))
    edited = run(base + [pinned] + options + ["-fixed", points + "|layername=points"], env)
    check("(c) ... and a rerun after the points file changed is refused, naming it and -overwrite",
          edited.returncode == 1 and ("the -fixed file %s has changed since" % points) in edited.stderr
          and "-overwrite" in edited.stderr, edited.stderr[-1000:])

    # (d) Each level across the tiles: the VRT and merge hold the sum of the tiles' triangles.
    found, metadata = rows(catalogue)[0], rows(catalogue)[2]
    levels = int(metadata.get("TINLOD_LEVELS", 0))
    files = [os.path.join(work, r["file"]) for r in found.values() if r["status"] == "done"]
    for level in sorted({0, 1, levels - 1}):
        expected = sum(level_count(f, "level_%d" % level) for f in files)
        vrt = os.path.join(work, "a_levels", "level_%d.vrt" % level)
        info = run(["ogrinfo", "-so", vrt, "level_%d" % level])
        counted = re.search(r"Feature Count: (\d+)", info.stdout)
        check("(d) level_%d.vrt opens as one layer of the %d triangles of the tiles" % (level, expected),
              counted is not None and int(counted.group(1)) == expected and expected > 0, info.stdout + info.stderr)
        out = os.path.join(work, "merged_%d.gpkg" % level)
        merged = run([tiles, "merge", catalogue, "-level", str(level), out])
        check("(d) merge -level %d gives one layer of the %d triangles" % (level, expected),
              merged.returncode == 0 and level_count(out, "level_%d" % level) == expected, merged.stderr)
    held = os.path.join(work, "merged_0.gpkg")
    connection = sqlite3.connect(held)
    connection.execute("PRAGMA journal_mode=WAL")
    connection.execute("CREATE TABLE notes(a)")
    connection.commit()
    try:
        again = run([tiles, "merge", catalogue, "-level", "0", held, "-overwrite"])
    finally:
        connection.close()
    check("(d) merge -overwrite of an output another program has open (its write-ahead log in use) is refused",
          again.returncode == 1 and "is open in another program" in again.stderr, again.stderr)
    someones = make_points(dem, os.path.join(work, "someones_merge.gpkg"))
    other = run([tiles, "merge", catalogue, "-level", "0", someones, "-overwrite"])
    check("(d) merge -overwrite of a GeoPackage that is no merged level (the user's layers) is refused, the file kept",
          other.returncode == 1 and "exists and is no merged level of tinlod-tiles (GDAL reads it as GPKG)" in other.stderr
          and point_count(someones) == 1, other.stderr)
    os.chmod(held, 0o444)
    protected = run([tiles, "merge", catalogue, "-level", "0", held, "-overwrite"])
    check("(d) merge -overwrite of a write-protected output is refused, as cp would refuse it",
          protected.returncode == 1 and "is write-protected (mode 0444)" in protected.stderr, protected.stderr)
    os.chmod(held, 0o640)
    kept = run([tiles, "merge", catalogue, "-level", "0", held, "-overwrite"])
    check("(d) a replaced merge output keeps its mode",
          kept.returncode == 0 and os.stat(held).st_mode & 0o777 == 0o640, (kept.stderr, oct(os.stat(held).st_mode)))
    dangling = os.path.join(work, "dangling.gpkg")
    os.symlink("nowhere/x.gpkg", dangling)
    mine = os.path.join(work, "mine.gpkg")
    with open(mine + ".partial.gpkg", "w") as f:
        f.write("the user's")
    linked = run([tiles, "merge", catalogue, "-level", "0", dangling])
    unclobbered = run([tiles, "merge", catalogue, "-level", "0", mine])
    check("(d) merge to a dangling link is refused; one to a new name leaves the user's NAME.partial.gpkg alone",
          linked.returncode == 1 and "is a symbolic link to nowhere/x.gpkg, which does not exist" in linked.stderr
          and unclobbered.returncode == 0 and open(mine + ".partial.gpkg").read() == "the user's",
          (linked.stderr, unclobbered.stderr))
    # /proc: root may write its folder, but GDAL cannot make a file there.
    unwritable = run([tiles, "merge", catalogue, "-level", "0", "/proc/merged.gpkg"])
    check("(d) merge to where no file can be made names the output, not its staging file, and the fix",
          unwritable.returncode == 1 and "/proc/merged.gpkg" in unwritable.stderr and ".partial" not in unwritable.stderr
          and ("name an output where you can write" in unwritable.stderr or "not writable" in unwritable.stderr),
          unwritable.stderr)
    some = os.path.join(work, "some.gpkg")
    only = run(base + [some] + options + ["-levels", "0,last"], env)
    written = sorted(os.listdir(os.path.join(work, "some_levels"))) if only.returncode == 0 else []
    check("(d) with -levels 0,last the level files are those two levels, and the summary says so",
          written == ["level_0.vrt", "level_%d.vrt" % (levels - 1)]
          and ("levels 0, %d across the tiles" % (levels - 1)) in only.stdout, (written, only.stdout, only.stderr))
    missing = run([tiles, "merge", some, "-level", "1", os.path.join(work, "some_1.gpkg")])
    check("(d) merge of a level the tiles have no layer for is refused, naming those they have",
          missing.returncode == 1 and ("have a layer only for level 0, %d" % (levels - 1)) in missing.stderr,
          missing.stderr)
    box = tile_box(catalogue, (0, 0), inset=1.0)
    corner = os.path.join(work, "corner.gpkg")
    region = run([tiles, "merge", catalogue, "-level", "1", corner, "-te"] + ["%.3f" % v for v in box])
    expected = level_count(os.path.join(work, "a_tiles", "tile_0_0.gpkg"), "level_1")
    check("(d) merge -te of a box inside tile 0,0 holds that tile's %d triangles only" % expected,
          region.returncode == 0 and level_count(corner, "level_1") == expected, region.stderr)
    coarsest = run([tiles, "merge", catalogue, "-level", "-1", os.path.join(work, "coarsest.gpkg")])
    check("(d) merge -level -1 merges the coarsest level, as tinlod's -level -1",
          coarsest.returncode == 0 and ("level_%d," % (levels - 1)) in coarsest.stdout
          and level_count(os.path.join(work, "coarsest.gpkg"), "level_%d" % (levels - 1))
          == sum(level_count(f, "level_%d" % (levels - 1)) for f in files), coarsest.stdout + coarsest.stderr)
    merged_0 = os.path.join(work, "merged_0.gpkg")
    told = [run([tinlod] + args) for args in (["info", merged_0], ["lod", merged_0, os.path.join(work, "ml.gpkg"),
                                                                  "-max_error", "5", "-q"])]
    check("(d) tinlod info and lod on a merged level name it and the catalogue to give instead",
          all(t.returncode == 1 and ("is level 0 of the tiles catalogue %s, merged by tinlod-tiles merge"
                                     % os.path.abspath(catalogue)) in t.stderr for t in told),
          [t.stderr for t in told])
    away = run([tiles, "merge", catalogue, "-level", "1", os.path.join(work, "away.gpkg"), "-te", "0", "0", "1", "1"])
    done_boxes = [tile_box(catalogue, key, 0.0) for key, r in found.items() if r["status"] == "done"]
    cover = "%.3f %.3f %.3f %.3f" % (min(b[0] for b in done_boxes), min(b[1] for b in done_boxes),
                                     max(b[2] for b in done_boxes), max(b[3] for b in done_boxes))
    check("(d) merge -te of a box no tile meets names where the finished tiles are (%s), and the CRS" % cover,
          away.returncode == 1 and ("no finished tile meets this box; the finished tiles cover %s (xmin ymin xmax ymax, in "
                                    % cover) in away.stderr, away.stderr)
    beyond = run([tiles, "merge", catalogue, "-level", str(levels), os.path.join(work, "m.gpkg")])
    check("(d) merge refuses a level the tiles do not have", beyond.returncode == 1 and "-level" in beyond.stderr,
          beyond.stderr)
    # A run stopped before its end (Ctrl-C) has recorded no TINLOD_LEVELS, and some tiles are
    # still pending: merge reads the finished ones, and says how many are not.
    stopped = os.path.join(work, "stopped.gpkg")
    shutil.copy(catalogue, stopped)
    dataset = gdal.OpenEx(stopped, gdal.OF_VECTOR | gdal.OF_UPDATE)
    dataset.SetMetadata({k: v for k, v in dataset.GetMetadata().items() if k != "TINLOD_LEVELS"})
    dataset.ExecuteSQL("UPDATE tiles SET status = 'pending', file = NULL WHERE tile_col = 0 AND tile_row = 0")
    dataset = None
    # The catalogue moved without its tiles folder: the readers say where the folder must be.
    os.makedirs(os.path.join(work, "moved"))
    moved = os.path.join(work, "moved", "a.gpkg")
    shutil.copy(catalogue, moved)
    lost = [run([tiles, "merge", moved, "-level", "1", os.path.join(work, "lost.gpkg")]),
            run([options[options.index("-tinlod") + 1], "lod", moved, os.path.join(work, "lost_lod.gpkg"), "-max_error", "5"]),
            run([options[options.index("-tinlod") + 1], "info", moved])]
    check("(d) a catalogue moved without its tiles folder: merge, tinlod lod and info say the folder must stay beside it",
          all(r.returncode == 1 and "tiles folder must stay beside it" in r.stderr for r in lost),
          [r.stderr[-400:] for r in lost])
    finished = len(files)
    check("(d) ... info still describes the catalogue, each finished tile named unreadable",
          "tiles (" in lost[2].stdout and lost[2].stdout.count("  unreadable: tile ") == finished
          and ("%d of the catalogue's finished tiles cannot be read" % finished) in lost[2].stderr,
          lost[2].stdout[-600:] + lost[2].stderr[-300:])
    # No output replaces a tile of the catalogue it reads (tinlod lod once did from the
    # command line, where GDAL was not yet set up when it listed its inputs).
    tile_file = files[0]
    before = open(tile_file, "rb").read()
    over = [run([options[options.index("-tinlod") + 1], "lod", catalogue, tile_file, "-max_error", "5", "-overwrite", "-q"]),
            run([tiles, "merge", catalogue, "-level", "1", tile_file, "-overwrite"])]
    check("(d) tinlod lod and merge refuse to write over a tile of the catalogue they read",
          all(r.returncode == 1 for r in over) and "is an input of this run" in over[0].stderr
          and "is a tile of the catalogue" in over[1].stderr and open(tile_file, "rb").read() == before,
          [r.stderr[-300:] for r in over])
    not_one = run([tiles, "merge", tile_file, "-level", "1", os.path.join(work, "n.gpkg")])
    damaged = os.path.join(work, "damaged.gpkg")
    with open(catalogue, "rb") as f, open(damaged, "wb") as g:
        g.write(f.read()[:50000])
    broken = [run([tiles, "merge", damaged, "-level", "1", os.path.join(work, "n.gpkg")]),
              run(base + [damaged] + options, env)]
    check("(d) merge of a GeoPackage that is no catalogue says so, without -overwrite advice",
          not_one.returncode == 1 and "is not a tinlod-tiles catalogue" in not_one.stderr
          and "-overwrite" not in not_one.stderr, not_one.stderr)
    check("(d) a damaged catalogue is named as damaged, by merge and by a rerun",
          all(r.returncode == 1 and "damaged.gpkg cannot be read" in r.stderr and "Traceback" not in r.stderr
              for r in broken), [r.stderr[-300:] for r in broken])
    if os.geteuid() == 0:  # another user, who may read the catalogue but not write it, merges it
        shared = tempfile.mkdtemp(prefix="tinlod_tiles_shared_")
        os.chmod(shared, 0o777)
        shutil.copy(catalogue, shared)
        shutil.copytree(os.path.join(work, "a_tiles"), os.path.join(shared, "a_tiles"))
        for place, _, names in os.walk(shared):
            os.chmod(place, 0o777 if place == shared else 0o755)
            for name in names:
                os.chmod(os.path.join(place, name), 0o644)
        reader = run(["setpriv", "--reuid=65534", "--regid=65534", "--clear-groups", tiles, "merge",
                      os.path.join(shared, "a.gpkg"), "-level", "1", os.path.join(shared, "m.gpkg"), "-q"])
        check("(d) merge needs only read access to the catalogue", reader.returncode == 0
              and level_count(os.path.join(shared, "m.gpkg"), "level_1") == sum(level_count(f, "level_1") for f in files),
              reader.stderr)
        shutil.rmtree(shared)
    partly = run([tiles, "merge", stopped, "-level", "1", os.path.join(work, "partly.gpkg")])
    check("(d) merge of a catalogue stopped before its end: the finished tiles' level, and a warning of the others",
          partly.returncode == 0 and "1 of the catalogue's 6 tiles is not finished (1 pending)" in partly.stderr
          and level_count(os.path.join(work, "partly.gpkg"), "level_1")
          == sum(level_count(f, "level_1") for f in files if not f.endswith("tile_0_0.gpkg")), partly.stderr)

    # (f) -selection global (the default) recorded one threshold per level and left no
    # survey behind; -selection tile makes one pass without them.
    thresholds = (metadata.get("TINLOD_LEVEL_THRESHOLDS") or "").split(",")
    check("(f) the catalogue holds one threshold per level above 0",
          metadata.get("TINLOD_SELECTION") == "global" and len(thresholds) == levels - 1
          and all(float(t.split(":")[0]) >= 0 for t in thresholds), metadata)
    check("(f) no survey file is left", not [n for n in os.listdir(folder) if "survey" in n], os.listdir(folder))
    own = gdal.OpenEx(os.path.join(folder, "tile_1_1.gpkg"), gdal.OF_VECTOR).GetMetadata()
    check("(f) a tile opened alone says its job's levels and the raster's thresholds it was built with",
          own.get("TINLOD_TILE_LEVELS", "").startswith("%d (levels 0 to %d" % (levels, levels - 1))
          and len(own.get("TINLOD_LEVEL_THRESHOLDS", "").split(" (")[0].split(",")) == levels - 1, own)
    # (k) The line cells on a tile's outline, which the surveys list: the build pass keeps
    # these, not every line cell near nodata (the empty corner's lines).
    outline_file = os.path.join(folder, "line_outline.txt")
    listed = [line.split() for line in open(outline_file)] if os.path.isfile(outline_file) else []
    tile_listed = gdal.OpenEx(os.path.join(folder, "tile_1_1.gpkg"), gdal.OF_VECTOR).GetMetadataItem("TINLOD_LINE_OUTLINE_CELLS")
    check("(k) the surveys' line outline is in the tiles folder, recorded by the catalogue and read by the tiles",
          metadata.get("TINLOD_LINE_OUTLINE") == "line_outline.txt" and len(listed) > 0
          and all(len(cell) == 2 for cell in listed) and int(tile_listed or 0) > 0, (metadata, listed, tile_listed))
    os.rename(outline_file, outline_file + ".moved")
    os.remove(os.path.join(folder, "tile_0_1.gpkg"))
    lost = run(base + [catalogue] + options, env)
    check("(k) a rerun with tiles to build whose line outline file is gone is refused, naming it and -overwrite",
          lost.returncode == 1 and "line_outline.txt is gone" in lost.stderr and "-overwrite" in lost.stderr
          and "Traceback" not in lost.stderr, lost.stderr[-1500:])
    os.rename(outline_file + ".moved", outline_file)
    whole_list = open(outline_file).read()
    with open(outline_file, "w") as f:
        f.write(whole_list[: len(whole_list) // 2])
    cut = run(base + [catalogue] + options, env)
    check("(k) ... and so is one whose line outline file was cut short",
          cut.returncode == 1 and "line_outline.txt has changed since" in cut.stderr and "-overwrite" in cut.stderr,
          cut.stderr[-1500:])
    with open(outline_file, "w") as f:
        f.write(whole_list)
    back = run(base + [catalogue] + options, env)
    check("(k) with the file back the tile is built again", back.returncode == 0 and "1 tile run, 5 skipped" in back.stdout,
          back.stdout + back.stderr[-1000:])
    # (f) A threshold's share (t:s) is the share of its bin's ties deleted, as the catalogue
    # records; one whose thresholds an earlier tinlod-tiles set (shares of the ties gone
    # through) is resumed with a warning that its tiles built now delete more of them.
    check("(f) the catalogue records that its shares are of the ties deleted",
          metadata.get("TINLOD_THRESHOLD_SHARES") == "deleted", metadata)
    edit = gdal.OpenEx(catalogue, gdal.OF_VECTOR | gdal.OF_UPDATE)
    first, rest = edit.GetMetadataItem("TINLOD_LEVEL_THRESHOLDS").split(",", 1)
    edit.SetMetadataItem("TINLOD_LEVEL_THRESHOLDS", first.split(":")[0] + ":0.500000," + rest)  # a share, at level 1
    edit = None
    os.remove(os.path.join(folder, "tile_0_1.gpkg"))
    ours = run(base + [catalogue] + options, env)
    check("(f) a rerun of this tinlod-tiles' catalogue with a share says nothing of it",
          ours.returncode == 0 and "1 tile run, 5 skipped" in ours.stdout and "earlier tinlod-tiles" not in ours.stderr,
          ours.stdout + ours.stderr[-1000:])
    edit = gdal.OpenEx(catalogue, gdal.OF_VECTOR | gdal.OF_UPDATE)
    edit.SetMetadataItem("TINLOD_THRESHOLD_SHARES", None)
    edit = None
    os.remove(os.path.join(folder, "tile_0_1.gpkg"))
    earlier = run(base + [catalogue] + options, env)
    check("(f) a catalogue an earlier tinlod-tiles set the thresholds of is resumed, with a warning",
          earlier.returncode == 0 and "1 tile run, 5 skipped" in earlier.stdout
          and "set by an earlier tinlod-tiles" in earlier.stderr and "-overwrite" in earlier.stderr,
          earlier.stdout + earlier.stderr[-1000:])
    by_tile = os.path.join(work, "t.gpkg")
    one_pass = run(base + [by_tile, "-selection", "tile"] + options, env)
    tile_metadata = rows(by_tile)[2]
    check("(f) -selection tile runs one pass, without thresholds",
          one_pass.returncode == 0 and tile_metadata.get("TINLOD_SELECTION") == "tile"
          and not tile_metadata.get("TINLOD_LEVEL_THRESHOLDS") and "survey pass" not in one_pass.stdout,
          one_pass.stdout + one_pass.stderr[-1000:])

    # (e) locate takes the catalogue: a point inside a tile gets that tile's height.
    points = os.path.join(work, "points.gpkg")
    box00 = tile_box(catalogue, (0, 0), inset=1.0)
    box10 = tile_box(catalogue, (1, 0), inset=1.0)
    centres = [((b[0] + b[2]) / 2, (b[1] + b[3]) / 2) for b in (box00, box10)]
    write_points(points, centres, catalogue)
    via_catalogue = run([tinlod, "locate", catalogue, points, os.path.join(work, "at_cat.gpkg"), "-level", "1", "-q"])
    via_tiles = [run([tinlod, "locate", os.path.join(work, "a_tiles", "tile_%d_0.gpkg" % c), points,
                      os.path.join(work, "at_%d.gpkg" % c), "-level", "1", "-q"]) for c in (0, 1)]
    heights = point_values(os.path.join(work, "at_cat.gpkg"))
    one = [point_values(os.path.join(work, "at_%d.gpkg" % c)) for c in (0, 1)]
    check("(e) locate on the catalogue gives each point its tile's height and names the tile",
          via_catalogue.returncode == 0 and all(r.returncode == 0 for r in via_tiles)
          and heights[0] == (one[0][0][0], "0,0") and heights[1] == (one[1][1][0], "1,0")
          and heights[0][0] is not None, (heights, one, via_catalogue.stderr))
    # A point in a tile not finished is not called outside the TIN: the summary says whose.
    partial = run([tinlod, "locate", stopped, points, os.path.join(work, "at_stopped.gpkg")])
    check("(e) locate on a catalogue with a pending tile counts its point outside the finished tiles' TIN",
          partial.returncode == 0 and "Located 1 of 2 points on level 0 (1 outside the finished tiles' TIN or in holes;"
          in partial.stdout and "1 of the catalogue's 6 tiles is not finished (1 pending)" in partial.stderr
          and point_values(os.path.join(work, "at_stopped.gpkg"))[0][0] is None,
          partial.stdout + partial.stderr[-500:])
    whole_points = run([tinlod, "locate", catalogue, points, os.path.join(work, "at_whole.gpkg")])
    check("(e) ... and with every tile finished, outside the TIN",
          whole_points.returncode == 0 and "(0 outside the TIN or in holes;" in whole_points.stdout, whole_points.stdout)

    # A point a few ULP either side of a shared line is in one tile or the other, never
    # between: the catalogue's boxes are the tiles' extents rounded to 15 digits (a DEM whose
    # lines fall on no round number).
    odd_dem = os.path.join(work, "odd.tif")
    gdal.Translate(odd_dem, dem)
    odd = gdal.Open(odd_dem, gdal.GA_Update)
    x0, dx, _, y0, _, dy = odd.GetGeoTransform()
    odd.SetGeoTransform((x0 + 0.123456789, dx * 1.0123456789, 0, y0 + 0.987654321, 0, dy * 1.0123456789))
    odd = None
    odd_catalogue = os.path.join(work, "odd.gpkg")
    check("(e) a DEM whose lines fall on no round number is built",
          run(base[:1] + [odd_dem, odd_catalogue] + options, env).returncode == 0)
    tile00 = ogr.Open(os.path.join(work, "odd_tiles", "tile_0_0.gpkg"))  # held: its layer dies with it
    line = [(f.GetGeometryRef().GetX(), f.GetGeometryRef().GetY()) for f in tile00.GetLayerByName("vertices")]
    tile00 = None
    y_line = min(y for _, y in line)  # its line with tile 0,1 (5202953.827160832, its box's 5202953.82716083)
    xs = sorted(x for x, y in line if y == y_line)
    x_mid = (xs[len(xs) // 2] + xs[len(xs) // 2 + 1]) / 2
    beside = []
    for direction in (-math.inf, math.inf):
        y = y_line
        for _ in range(3):
            y = math.nextafter(y, direction)
            beside.append((x_mid, y))
    beside_points = os.path.join(work, "beside_points.gpkg")
    write_points(beside_points, beside, odd_catalogue)
    located = run([tinlod, "locate", odd_catalogue, beside_points, os.path.join(work, "beside.gpkg"), "-q"])
    check("(e) locate finds points 1 to 3 ULP either side of a shared line", located.returncode == 0
          and len(point_values(os.path.join(work, "beside.gpkg"))) == len(beside)
          and all(h is not None for h, _ in point_values(os.path.join(work, "beside.gpkg"))),
          point_values(os.path.join(work, "beside.gpkg")))

    exact_stop(base, options, work, env)
    info_of_catalogue(tinlod, catalogue)
    lod_and_accuracy(tinlod, catalogue, dem, work)
    border_agreement(base, options, work, env)
    for stop in (signal.SIGINT, signal.SIGTERM, signal.SIGHUP):
        ctrl_c(dem, tiles, work, env, stop)
    ctrl_c(dem, tiles, work, env, signal.SIGINT, started_ignoring=True)
    hangup_under_nohup(dem, tiles, work, env)
    hangup_of_the_terminal(dem, tiles, work, env)
    ctrl_c_in_survey(tinlod, dem, tiles, work, env)
    ctrl_c_with_tiles_done(tinlod, dem, tiles, work, env)
    stop_warning(tiles, program, work, env)
    remote_cluster(tinlod, tiles, dem, work, env)

    if not failures:
        subprocess.run(["rm", "-rf", work])
    else:
        print("the files are left in " + work)
    return exit_code("tiles")


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:3]))
