# SPDX-License-Identifier: GPL-3.0-or-later
"""The command line of tinlod-tiles, gdal-style: the options of a run and of `merge`, each
checked before any work with a message naming the option and the fix."""
import os
import re
import shlex
import shutil
import sys
from dataclasses import dataclass, field

from osgeo import gdal

from .errors import TilesError

HELP = """Builds a DEM of any size as tiles whose TIN hierarchies fit together exactly: Dask runs one
`tinlod build` per tile (on a local cluster, or on a running scheduler's workers), and a
catalogue GeoPackage lists the tiles and their status. A rerun resumes: finished tiles are
skipped. Each level across the tiles is one layer: <stem>_levels/level_K.vrt.

Usage: tinlod-tiles DEM CATALOGUE.gpkg -tile_size N [options] [-- build options]
       tinlod-tiles merge CATALOGUE.gpkg -level K OUT.gpkg [-te xmin ymin xmax ymax]
                          [-overwrite] [-q]
       tinlod-tiles --version

Tiles:
  -tile_size N     cell steps per tile side (a tile spans N + 1 cells), a multiple of the
                   build's -block (default 3); neighbouring tiles share that row or column
  -workers n       local cluster: workers, one tile each at a time
                   (default: the number of cores)
  -scheduler ADDR  a running Dask scheduler (tcp://host:8786) instead of a local cluster;
                   its workers must reach the DEM, the tiles folder and tinlod by the same paths
  -retries r       times a failed tile is tried again (default 2)
  -tinlod PATH     the tinlod program (default: the one beside tinlod-tiles, else on PATH)
  -selection global|tile
                   global (default): two passes; the first surveys every tile's levels,
                   from which one importance threshold per level is set for the whole
                   raster, and the second builds the tiles with them, so each level deletes
                   the raster's least important vertices, as a whole run does; tile: one
                   pass, each tile deleting -delete_pct of its own vertices per level
                   (faster, but a few per cent to 20 % less accurate at equal vertex counts)
  -exact_stop      with -selection global: a second survey pass, the tiles deleting as the
                   build pass will, sets the last level so that the coarsest level ends at
                   the stop percentage of the vertices (a quarter more time; without it the
                   coarsest level ends a few per cent above it)
  -- options       everything after -- goes to each tile's tinlod build, but for what belongs
                   to the run: the tile options -tile and -tile_size, the outputs -accuracy
                   and -report, and -overwrite and -q. With -method error -max_error E the
                   tiles agree their shared lines in rounds (a line vertex goes only where
                   both sides stay within E), building again the tiles a round changed

Merge:
  -level K         merge: the level to merge, 0 to the catalogue's TINLOD_LEVELS - 1; -1 the coarsest
  -te xmin ymin xmax ymax
                   merge: only the tiles whose extent meets this box (in the catalogue's
                   CRS), a region of a large job

General:
  -overwrite       start again: replace the catalogue, its tiles and level files
                   (merge: replace OUT.gpkg)
  -q               quiet: no progress, warnings and errors only
"""

REFUSED_BUILD_OPTIONS = {
    "-survey": "tinlod-tiles runs the survey pass itself (-selection global)",
    "-level_thresholds": "tinlod-tiles sets them from the survey pass (-selection global)",
    "-border_keep": "tinlod-tiles agrees the lines' kept cells itself (-method error -max_error)",
    "-line_outline": "tinlod-tiles gathers the lines' outline cells from the survey pass (-selection global)",
    "-tile": "tinlod-tiles gives each task its tile",
    "-check": "tinlod-tiles checks the build options itself before any tile runs",
    "-tile_size": "give -tile_size to tinlod-tiles itself, before --",
    "-accuracy": "one raster per run cannot hold every tile; once the tiles are built, "
                 "tinlod accuracy DEM CATALOGUE.gpkg -accuracy RASTER.tif measures them as one TIN",
    "-report": "one report per run cannot hold every tile; once the tiles are built, "
               "tinlod accuracy DEM CATALOGUE.gpkg -report REPORT.html measures them as one TIN",
    "-overwrite": "give -overwrite to tinlod-tiles itself, before --",
    "-q": "give -q to tinlod-tiles itself, before --",
}


@dataclass
class RunArguments:
    dem: str
    catalogue: str
    tile_size: int
    workers: int = field(default_factory=lambda: os.cpu_count() or 1)
    scheduler: str = None
    retries: int = 2
    tinlod: str = None
    selection: str = "global"
    exact_stop: bool = False
    overwrite: bool = False
    quiet: bool = False
    build_options: list = field(default_factory=list)


@dataclass
class MergeArguments:
    catalogue: str
    level: int
    out: str
    extent: tuple = None  # (xmin, ymin, xmax, ymax): only the tiles meeting it
    overwrite: bool = False
    quiet: bool = False


def whole_number(text, option, least):
    if not re.fullmatch(r"[0-9]+", text or "") or int(text) < least:
        raise TilesError("%s %s: give a whole number of at least %d" % (option, text, least))
    return int(text)


TILE_SIZE_MOST = 2**31 - 1  # tinlod's whole numbers are C++ ints


def tile_size(text, block):
    if not re.fullmatch(r"-?[0-9]+(\.[0-9]*)?", text or ""):
        raise TilesError("-tile_size %s is not a number of cells: give a whole number, %d or more (thousands of cells "
                         "make fewer, larger tiles)" % (text, 2 * block))
    if not re.fullmatch(r"[0-9]+", text) or int(text) < 2 * block:
        raise TilesError("-tile_size %s: a tile is at least two blocks of -block %d: give a whole number, %d or more "
                         "(thousands of cells make fewer, larger tiles)" % (text, block, 2 * block))
    if int(text) > TILE_SIZE_MOST:
        raise TilesError("-tile_size %s: give at most %d (a tile as large as the DEM's longer side makes one tile of "
                         "the whole DEM)" % (text, TILE_SIZE_MOST))
    return int(text)


def split_options(args, valued, flags):
    """(positionals, {option: value, values or True}) of args, gdal-style; `valued` maps an
    option to the count of values it takes."""
    positionals, options = [], {}
    i = 0
    while i < len(args):
        arg = args[i]
        if arg in options and (arg in valued or arg in flags):
            raise TilesError("%s is given more than once" % arg)
        if arg in valued:
            count = valued[arg]
            if i + count >= len(args):
                raise TilesError("%s needs %d value%s" % (arg, count, "s" if count > 1 else ""))
            options[arg] = args[i + 1] if count == 1 else args[i + 1: i + 1 + count]
            i += 1 + count
            continue
        if arg in flags:
            options[arg] = True
        elif arg.startswith("-") and len(arg) > 1:
            raise TilesError("unknown option %s (tinlod-tiles --help lists them; build options go after --)" % arg)
        else:
            positionals.append(arg)
        i += 1
    return positionals, options


def check_text(args):
    """Every argument must be UTF-8 text: the catalogue records the DEM, the options and the
    -fixed file as GDAL metadata, which is UTF-8 (a name in another encoding reaches Python
    as undecodable bytes, which GDAL's bindings cannot take)."""
    for arg in args:
        try:
            arg.encode("utf-8")
        except UnicodeEncodeError:
            shown = arg.encode("utf-8", "surrogateescape").decode("utf-8", "backslashreplace")
            raise TilesError("%s is not UTF-8 text: tinlod-tiles records its arguments in the catalogue, which "
                             "holds UTF-8 text; give it in UTF-8 (a file: rename it, or give a link to it named in UTF-8)" % shown) from None


# A tcp:// (or scheme-less) scheduler address: host (a bracketed IPv6 one too), then port.
TCP_ADDRESS = re.compile(r"(?:tcp://)?\[?([^\]/]+?)\]?:(\d+)/?")


def check_scheduler_address(address):
    """tcp:// (Dask's default) or no scheme, with a port; another protocol (tls://, ucx://) is the
    client's to read. An empty address (-scheduler "$UNSET") must not fall back to a local cluster."""
    if address is None or re.match(r"(?!tcp://)\w+://", address):
        return
    match = TCP_ADDRESS.fullmatch(address)
    if not match:
        raise TilesError("-scheduler %s: give the scheduler's address, tcp://host:port or host:port (`dask scheduler` "
                         "prints it: tcp://host:8786 by default)" % shlex.quote(address))
    if not 1 <= int(match.group(2)) <= 65535:
        raise TilesError("-scheduler %s: port %s is out of range (1 to 65535); `dask scheduler` prints its address, "
                         "tcp://host:8786 by default" % (address, match.group(2)))


def parse_run(args):
    check_text(args)
    ours, build_options = (args[: args.index("--")], args[args.index("--") + 1:]) if "--" in args else (args, [])
    positionals, options = split_options(ours, dict.fromkeys(("-tile_size", "-workers", "-scheduler", "-retries",
                                                              "-tinlod", "-selection"), 1), ("-exact_stop", "-overwrite", "-q"))
    if len(positionals) != 2:
        raise TilesError("give the DEM and the catalogue: tinlod-tiles DEM CATALOGUE.gpkg -tile_size N")
    if "-tile_size" not in options:
        raise TilesError("-tile_size is required: the cell steps per tile side, e.g. -tile_size 3000")
    if "-workers" in options and "-scheduler" in options:
        raise TilesError("-workers sizes the local cluster; a -scheduler's workers are started with it "
                         "(dask worker ADDRESS --nworkers n): give one of them")
    arguments = RunArguments(positionals[0], positionals[1], tile_size(options["-tile_size"], build_block(build_options)),
                             scheduler=options.get("-scheduler"), overwrite="-overwrite" in options,
                             quiet="-q" in options, build_options=absolute_files(build_options))
    check_scheduler_address(arguments.scheduler)
    if "-workers" in options:
        arguments.workers = whole_number(options["-workers"], "-workers", 1)
    if "-retries" in options:
        arguments.retries = whole_number(options["-retries"], "-retries", 0)
    arguments.selection = options.get("-selection", "global")
    if arguments.selection not in ("global", "tile"):
        raise TilesError("-selection %s: give global (one threshold per level for the whole raster) or tile"
                         % arguments.selection)
    arguments.exact_stop = "-exact_stop" in options
    if arguments.exact_stop and (arguments.selection != "global" or "-threshold" in build_options):
        raise TilesError("-exact_stop sets the last level from a second survey pass of -selection global: "
                         "it does nothing with -selection tile or -- -threshold; leave it out")
    # Recorded as absolute paths: a relative name from a folder whose name is not UTF-8 is not either.
    check_text([p if p.startswith("/vsi") else os.path.abspath(p) for p in positionals] + arguments.build_options)
    check_run(arguments)
    arguments.tinlod = find_tinlod(options.get("-tinlod"))
    return arguments


# Build options that name a file, which every task opens wherever it runs.
FILE_OPTIONS = ("-fixed",)


def absolute_files(build_options):
    """The build options with the files they name made absolute (GDAL's /vsi paths as
    given): a worker in another folder, or a rerun from one, then opens the same file, and a
    rerun naming another file by the same relative path is not taken for the same job."""
    out = list(build_options)
    for i in range(len(out) - 1):
        if out[i] in FILE_OPTIONS and out[i + 1] and not out[i + 1].startswith("/vsi"):
            out[i + 1] = os.path.abspath(out[i + 1])
    return out


def layer_spec(spec):
    """(file, layer name or None) of a layer named as QGIS names one: points.gpkg|layername=p."""
    path, _, layer = spec.partition("|")
    return path, (layer.split("=", 1)[1] if layer.startswith("layername=") else None)


def check_run(arguments):
    for option in arguments.build_options:
        if option in REFUSED_BUILD_OPTIONS:
            raise TilesError("%s after --: %s" % (option, REFUSED_BUILD_OPTIONS[option]))
    threads = os.environ.get("TINLOD_THREADS")  # empty is unset, as tinlod reads it
    if threads and (not re.fullmatch(r"[0-9]+", threads) or int(threads) < 1):
        raise TilesError("TINLOD_THREADS=%s: give each tile's tinlod a whole number of threads, 1 or more, or unset it "
                         "(each tinlod then gets its share of the cores)" % threads)
    block = build_block(arguments.build_options)
    if arguments.tile_size % block:
        lower = arguments.tile_size - arguments.tile_size % block
        raise TilesError("-tile_size %d is not a multiple of -block %d (so the tiles' samples would not meet): "
                         "use %s%d" % (arguments.tile_size, block, "%d or " % lower if lower else "", lower + block))
    check_dem(arguments.dem)
    check_output(arguments.catalogue, "CATALOGUE")


def build_option(build_options, name):
    """The value given to one of the build options: None when it is not there, "" when it
    ends them without a value."""
    for i, option in enumerate(build_options):
        if option == name:
            return build_options[i + 1] if i + 1 < len(build_options) else ""
    return None


def build_block(build_options):
    """The build's -block (default 3), which a tile side must be a multiple of."""
    value = build_option(build_options, "-block")
    return 3 if value is None else whole_number(value, "-block", 1)


def check_dem(path):
    if not os.path.exists(path) and not path.startswith("/vsi"):
        raise TilesError("DEM %s does not exist" % path)
    with gdal.quiet_errors() if hasattr(gdal, "quiet_errors") else _Quiet():
        try:
            dataset = gdal.OpenEx(path, gdal.OF_RASTER)
        except RuntimeError:
            dataset = None
    if dataset is None:
        raise TilesError("DEM %s is not a raster GDAL can open" % path)
    if dataset.RasterXSize < 2 or dataset.RasterYSize < 2:
        raise TilesError("DEM %s has %d x %d cells: a TIN needs cells in two rows and two columns at least"
                         % (path, dataset.RasterXSize, dataset.RasterYSize))


class _Quiet:
    def __enter__(self):
        gdal.PushErrorHandler("CPLQuietErrorHandler")

    def __exit__(self, *_):
        gdal.PopErrorHandler()


def check_output(path, what):
    if not path.lower().endswith(".gpkg"):
        raise TilesError("%s %s: name a GeoPackage, ending in .gpkg" % (what, path))
    folder = os.path.dirname(os.path.abspath(path))
    if not os.path.isdir(folder) or not os.access(folder, os.W_OK):
        raise TilesError("%s %s: its folder %s does not exist or is not writable" % (what, path, folder))
    if os.path.isdir(path):
        raise TilesError("%s %s is a folder" % (what, path))


def find_tinlod(given):
    """-tinlod, else tinlod beside this program (installed: bin/; build tree: core/), else PATH."""
    if given is not None:
        if os.sep not in given and not os.path.exists(given):  # a name, as a shell takes it: on PATH
            found = shutil.which(given)
            if found is None:
                raise TilesError("-tinlod %s: no program of that name on PATH; give its path" % given)
            given = found
        if not (os.path.isfile(given) and os.access(given, os.X_OK)):
            raise TilesError("-tinlod %s is not an executable file" % given)
        return os.path.abspath(given)
    here = os.path.dirname(os.path.realpath(sys.argv[0]))
    for candidate in (os.path.join(here, "tinlod"), os.path.join(here, "..", "core", "tinlod")):
        if os.path.isfile(candidate) and os.access(candidate, os.X_OK):
            return os.path.abspath(candidate)
    found = shutil.which("tinlod")
    if found is None:
        raise TilesError("tinlod is neither beside tinlod-tiles nor on PATH: give -tinlod PATH")
    return os.path.abspath(found)


def parse_merge(args):
    check_text(args)
    positionals, options = split_options(args, {"-level": 1, "-te": 4}, ("-overwrite", "-q"))
    if len(positionals) != 2:
        raise TilesError("usage: tinlod-tiles merge CATALOGUE.gpkg -level K OUT.gpkg [-te xmin ymin xmax ymax]")
    if "-level" not in options:
        raise TilesError("merge needs -level K: the level to merge, 0 to the catalogue's TINLOD_LEVELS - 1, or -1 "
                         "for the coarsest")
    catalogue, out = positionals
    if not os.path.isfile(catalogue):
        raise TilesError("CATALOGUE %s does not exist" % catalogue)
    check_output(out, "OUT")
    if os.path.abspath(out) == os.path.abspath(catalogue):
        raise TilesError("OUT %s is the catalogue itself: name another file" % out)
    # As tinlod reads a whole number (-0 is 0), so that a script's level goes to both alike.
    if not re.fullmatch(r"-?[0-9]+", options["-level"]) or int(options["-level"]) < -1:
        raise TilesError("-level %s: give a level number, 0 or more, or -1 for the coarsest" % options["-level"])
    level = int(options["-level"])
    return MergeArguments(catalogue, level, out,
                          extent(options["-te"]) if "-te" in options else None,
                          "-overwrite" in options, "-q" in options)


def extent(values):
    """-te xmin ymin xmax ymax, in the catalogue's CRS."""
    try:
        xmin, ymin, xmax, ymax = (float(v) for v in values)
    except ValueError:
        raise TilesError("-te %s: give four numbers, xmin ymin xmax ymax in the catalogue's CRS"
                         % " ".join(values)) from None
    if not (xmin < xmax and ymin < ymax):
        raise TilesError("-te %s: xmin must be below xmax and ymin below ymax" % " ".join(values))
    return xmin, ymin, xmax, ymax
