# SPDX-License-Identifier: GPL-3.0-or-later
"""Each level as one layer across tiles: an OGR VRT union of the tiles' `level_K` views,
written beside the catalogue, and the same union merged into one GeoPackage on demand."""
import os
import re
import sys
import tempfile
from xml.sax.saxutils import escape, quoteattr

from osgeo import gdal, ogr

from . import replace_guard
from .catalogue import Catalogue, levels_folder
from .errors import TilesError


def built_tile_files(catalogue, catalogue_path, extent=None):
    """The catalogue's done tiles' files, as absolute paths, row by row; with an extent
    (xmin, ymin, xmax, ymax), only those of the tiles meeting it."""
    base = os.path.dirname(os.path.abspath(catalogue_path))
    rows = catalogue.rows()
    meeting = catalogue.tiles_meeting(extent) if extent else set(rows)
    return [os.path.join(base, rows[key]["file"]) for key in sorted(rows, key=lambda k: (k[1], k[0]))
            if rows[key]["status"] == "done" and rows[key]["file"] and key in meeting]


def check_not_a_tile(out_path, files):
    """OUT may not be one of the catalogue's tile files: writing it would destroy the tile."""
    for path in files:
        if os.path.exists(out_path) and os.path.exists(path) and os.path.samefile(out_path, path):
            raise TilesError("OUT %s is a tile of the catalogue (%s): writing it would destroy the tile; name "
                             "another file" % (out_path, os.path.basename(path)))


def union_vrt(level, files, vrt_folder=None):
    """The VRT text of level `level` over the files: their paths relative to vrt_folder (so
    the catalogue's folder can move), or absolute without one."""
    layers = []
    for path in files:
        name = os.path.relpath(path, vrt_folder) if vrt_folder else os.path.abspath(path)
        layers.append('    <OGRVRTLayer name=%s>\n      <SrcDataSource relativeToVRT="%d">%s</SrcDataSource>\n'
                      '      <SrcLayer>level_%d</SrcLayer>\n    </OGRVRTLayer>'
                      % (quoteattr(os.path.splitext(os.path.basename(path))[0]), 1 if vrt_folder else 0,
                         escape(name), level))
    return ('<OGRVRTDataSource>\n  <OGRVRTUnionLayer name="level_%d">\n'
            '    <SourceLayerFieldName>tile</SourceLayerFieldName>\n%s\n'
            '  </OGRVRTUnionLayer>\n</OGRVRTDataSource>\n' % (level, "\n".join(layers)))


def check_exists(path):
    if not path.startswith("/vsi") and not os.path.exists(path):
        raise TilesError("the tile file %s does not exist: the catalogue names its tiles' files relative to itself, so "
                         "its tiles folder must stay beside it; move the folder back, or run tinlod-tiles on the "
                         "catalogue again to build the tile" % path)


def level_views(path):
    """The levels whose `level_K` view a tile has: all, or those its build's -levels asked for."""
    check_exists(path)
    dataset = ogr.Open(path)
    if dataset is None:
        raise TilesError("%s is not a GeoPackage GDAL can open" % path)
    names = (dataset.GetLayer(i).GetName() for i in range(dataset.GetLayerCount()))
    return {int(name[len("level_"):]) for name in names if re.fullmatch(r"level_\d+", name)}


def refuses_line_vertices(path):
    """Whether a tile built under -max_error refused line vertices (TINLOD_BORDER_REFUSED),
    which the tiles beside it must keep too: until they are built again, the two do not
    meet on that line."""
    dataset = gdal.OpenEx(path, gdal.OF_VECTOR)
    return bool(dataset is not None and dataset.GetMetadataItem("TINLOD_BORDER_REFUSED"))


def write_level_vrts(catalogue, catalogue_path, levels):
    """`<stem>_levels/level_K.vrt` for K in 0..levels-1 that the tiles have a view of; returns
    their paths."""
    files = built_tile_files(catalogue, catalogue_path)
    viewed = level_views(files[0]) if files else set()
    folder = levels_folder(catalogue_path)
    os.makedirs(folder, exist_ok=True)
    for stale in os.listdir(folder):
        if stale.startswith("level_") and stale.endswith(".vrt"):
            os.remove(os.path.join(folder, stale))
    paths = []
    for level in sorted(viewed & set(range(levels))):
        path = os.path.join(folder, "level_%d.vrt" % level)
        with open(path + ".partial", "w", encoding="utf-8") as f:
            f.write(union_vrt(level, files, folder))
        os.replace(path + ".partial", path)
        paths.append(path)
    return paths


def fewest_levels(rows):
    """The levels every done tile of the catalogue's rows has."""
    return min((r["levels"] for r in rows if r["status"] == "done" and r["levels"]), default=0)


def unfinished_warning(rows):
    """What a catalogue's unfinished tiles mean for a level read from it ("" when none), as
    tinlod's commands say it."""
    unfinished = {}
    for r in rows:
        if r["status"] not in ("done", "empty"):
            unfinished[r["status"]] = unfinished.get(r["status"], 0) + 1
    if not unfinished:
        return ""
    count = sum(unfinished.values())
    return ("%d of the catalogue's %d tiles %s not finished (%s): only the finished tiles are read; run tinlod-tiles "
            "again to finish them" % (count, len(rows), "is" if count == 1 else "are",
                                      ", ".join("%d %s" % (n, s) for s, n in sorted(unfinished.items()))))


MERGED_KIND = "merged_level"  # a merge output's TINLOD_KIND


def hidden_partial(out_path):
    """A new hidden name beside OUT to write it under: no file of the user's is taken for it."""
    folder, name = os.path.split(os.path.abspath(out_path))
    short = os.fsencode(name)[:150].decode("utf-8", "ignore")  # the hidden name within 255 bytes
    try:
        handle, partial = tempfile.mkstemp(prefix=".%s." % short, suffix=".partial.gpkg", dir=folder)
    except OSError as e:
        raise TilesError("cannot write %s (%s): name an output where you can write" % (out_path, e.strerror)) from None
    os.close(handle)
    os.remove(partial)  # GDAL makes the file itself
    return partial


def merge_level(catalogue_path, level, out_path, overwrite, extent=None):
    """The tiles' level `level` (-1: the coarsest; of the tiles meeting `extent`, if given)
    merged into one layer `level_K` of a new GeoPackage; returns K and its triangle count."""
    catalogue = Catalogue.open(catalogue_path, update=False)
    rows = catalogue.rows().values()
    check_not_a_tile(out_path, built_tile_files(catalogue, catalogue_path))
    # A run stopped before its end has not recorded TINLOD_LEVELS: its finished tiles say.
    levels = int(catalogue.setting("TINLOD_LEVELS") or fewest_levels(rows))
    warning = unfinished_warning(rows)
    if warning:
        print("Warning: " + warning, file=sys.stderr)
    if level == -1 and levels:  # the coarsest, as tinlod's -level -1
        level = levels - 1
    if not 0 <= level < levels:
        raise TilesError("-level %d: the catalogue's tiles have levels 0 to %d" % (level, levels - 1)
                         if levels else "-level: %s has no finished tile yet; run tinlod-tiles on it first"
                         % catalogue_path)
    files = built_tile_files(catalogue, catalogue_path, extent)
    finished = catalogue.described_extent() if not files else None
    catalogue.close()
    if not files:
        raise TilesError("-te %s: no finished tile meets this box; the finished tiles cover %s"
                         % (" ".join("%.3f" % v for v in extent), finished))
    for path in files:
        check_exists(path)
    refusing = [path for path in files if refuses_line_vertices(path)]
    if refusing:
        raise TilesError("%s refuses line vertices its neighbours may have deleted: the catalogue's -max_error run "
                         "stopped before its tiles agreed their shared lines, so they do not meet there yet; run "
                         "tinlod-tiles on it again to finish them" % refusing[0])
    viewed = level_views(files[0])
    if level not in viewed:
        raise TilesError("-level %d: the tiles were built with -levels, and have a layer only for level %s"
                         % (level, ", ".join(str(k) for k in sorted(viewed))))
    replace_guard.refuse_dangling_link(out_path, "OUT")
    out_path = os.path.realpath(out_path) if os.path.islink(out_path) else out_path  # a link's file is replaced
    if os.path.exists(out_path) and not overwrite:
        raise TilesError("%s exists: add -overwrite to replace it" % out_path)
    old_stat = os.stat(out_path) if os.path.exists(out_path) else None
    if old_stat:
        replace_guard.check_replaceable(out_path, MERGED_KIND, "merged level of tinlod-tiles", "OUT")
    source = "/vsimem/tinlod_tiles_merge_%d.vrt" % os.getpid()
    gdal.FileFromMemBuffer(source, union_vrt(level, files).encode("utf-8"))
    partial, failure = hidden_partial(out_path), ""
    try:
        options = gdal.VectorTranslateOptions(format="GPKG", layerName="level_%d" % level)
        try:
            written = gdal.VectorTranslate(partial, source, options=options)
        except RuntimeError as e:  # a folder root may write but GDAL may not (/proc), a full disk
            written, failure = None, str(e).replace(partial, out_path)
        if written is None:
            raise TilesError("cannot write %s%s: name an output where you can write"
                             % (out_path, " (%s)" % failure if failure else ""))
        # tinlod's readers name what the file is, and the catalogue they take instead.
        written.SetMetadata({"TINLOD_KIND": MERGED_KIND, "TINLOD_LEVEL": str(level),
                             "TINLOD_CATALOGUE": os.path.abspath(catalogue_path)})
        written = None
        if os.path.exists(out_path):  # opened meanwhile: checked again
            replace_guard.refuse_in_use(out_path)
        if old_stat:
            replace_guard.keep_permissions(partial, old_stat)
        try:
            os.replace(partial, out_path)
        except OSError as e:
            raise TilesError("cannot put %s in place (%s): nothing was written" % (out_path, e.strerror)) from None
    finally:
        gdal.Unlink(source)
        if os.path.exists(partial):
            os.remove(partial)
    merged = ogr.Open(out_path)  # held: the layer dies with it
    return level, merged.GetLayer(0).GetFeatureCount()
