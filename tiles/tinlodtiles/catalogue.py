# SPDX-License-Identifier: GPL-3.0-or-later
"""The catalogue GeoPackage: one `tiles` layer (a feature per tile: its extent, window,
file, status and what its build measured) and the job's settings as GDAL metadata.

Only the driver writes it, one tile at a time, each change committed on its own: a run
stopped anyhow leaves a catalogue that says which tiles are finished.
"""
import os
import shlex
import shutil
import time

from osgeo import ogr, osr

from .arguments import build_option, layer_spec
from .build_check import same_version
from .errors import TilesError

LAYER = "tiles"
STATUSES = ("pending", "done", "empty", "failed")
FIELDS = (  # (name, OGR type)
    ("tile_col", ogr.OFTInteger), ("tile_row", ogr.OFTInteger),
    ("xoff", ogr.OFTInteger), ("yoff", ogr.OFTInteger), ("xsize", ogr.OFTInteger), ("ysize", ogr.OFTInteger),
    ("file", ogr.OFTString), ("status", ogr.OFTString), ("levels", ogr.OFTInteger),
    ("vertices", ogr.OFTInteger64), ("triangles", ogr.OFTInteger64), ("attempts", ogr.OFTInteger),
    ("seconds", ogr.OFTReal), ("peak_mib", ogr.OFTReal), ("error", ogr.OFTString),
)
# The settings a rerun must share with the catalogue's first run.
JOB_KEYS = ("TINLOD_SOURCE", "TINLOD_TILE_SIZE", "TINLOD_BUILD_OPTIONS", "TINLOD_RASTER_SIZE", "TINLOD_SELECTION")
# The DEM file's and the -fixed file's size and time of change (file_stamp), which a rerun
# must find unchanged: the finished tiles were built from them.
SOURCE_STAMP = "TINLOD_SOURCE_STAMP"
FIXED_STAMP = "TINLOD_FIXED_STAMP"
STAMPS = ((SOURCE_STAMP, "the DEM"), (FIXED_STAMP, "the -fixed file"))

# The build options as tinlod build reads them ("VERSION: OPTIONS", see build_check):
# compared instead of TINLOD_BUILD_OPTIONS's text where both runs have it from one tinlod.
BUILD_SETTINGS = "TINLOD_BUILD_SETTINGS"


def options_part(settings):
    return settings.split(": ", 1)[-1]


def file_stamp(path):
    """A local file's bytes and time of change; "" for a GDAL virtual path (/vsi...). A
    VRT's stamp is its own, not its sources'; a shapefile's that of its .shp; a layer named
    as QGIS names one (points.gpkg|layername=p), its file's."""
    path = layer_spec(path)[0]
    if path.startswith("/vsi"):
        return ""
    status = os.stat(path)
    return "%d bytes, changed %s UTC" % (status.st_size, time.strftime("%Y-%m-%d %H:%M:%S", time.gmtime(status.st_mtime_ns // 10 ** 9))
                                         + ".%09d" % (status.st_mtime_ns % 1000000000))


def stamped_file(settings, key):
    """The file a stamp is of, as the job's settings name it (a layer's: its file)."""
    if key == SOURCE_STAMP:
        return settings["TINLOD_SOURCE"]
    return layer_spec(build_option(shlex.split(settings["TINLOD_BUILD_OPTIONS"]), "-fixed"))[0]


def same_file(recorded, given):
    """Whether two paths of the DEM name one file (a link to it, or the link's target)."""
    if recorded == given or recorded.startswith("/vsi") or given.startswith("/vsi"):
        return recorded == given
    return os.path.realpath(recorded) == os.path.realpath(given)


class Catalogue:
    def __init__(self, dataset):
        self.dataset = dataset
        self.layer = dataset.GetLayerByName(LAYER)
        self.srs = self.layer.GetSpatialRef()
        # Each tile's feature id, read once: a grid of thousands of tiles is updated by id.
        self.fids = {(f["tile_col"], f["tile_row"]): f.GetFID() for f in self.layer}

    @classmethod
    def create(cls, path, settings, srs, tiles):
        """A new catalogue of pending tiles, written under a temporary name and renamed: a
        run stopped meanwhile leaves no catalogue rather than half of one."""
        partial = path + ".partial.gpkg"
        if os.path.exists(partial):
            os.remove(partial)
        try:
            write_new(partial, settings, srs, tiles)
        except BaseException:
            if os.path.exists(partial):
                os.remove(partial)
            raise
        os.replace(partial, path)
        return cls.open(path)

    @classmethod
    def open(cls, path, update=True):
        """The catalogue at `path`, for its driver to write (`update`) or for a reader (merge),
        which needs only read access; TilesError naming the file when it is not one."""
        if update and not os.access(path, os.W_OK):
            raise TilesError("cannot write the catalogue %s: run tinlod-tiles as a user who may, or copy the catalogue "
                             "and its tiles folder where you can write" % path)
        try:
            dataset = ogr.Open(path, update=1 if update else 0)
            catalogue = dataset is not None and dataset.GetMetadataItem("TINLOD_KIND") == "catalogue" \
                and dataset.GetLayerByName(LAYER) is not None
            if catalogue:
                dataset.GetLayerByName(LAYER).GetFeatureCount()  # a damaged file fails here, not later
        except RuntimeError as e:
            raise TilesError("%s cannot be read (%s): it is damaged; build it again with tinlod-tiles -overwrite"
                             % (path, str(e).strip())) from None
        if not catalogue:
            if not update:
                raise TilesError("CATALOGUE %s is not a tinlod-tiles catalogue: give the GeoPackage tinlod-tiles "
                                 "wrote (its tiles layer lists the tiles)" % path)
            raise TilesError("%s exists and is no tinlod-tiles catalogue; name another file or add "
                             "-overwrite to replace it" % path)
        return cls(dataset)

    def setting(self, key):
        return self.dataset.GetMetadataItem(key)

    def set_setting(self, key, value):
        self.dataset.SetMetadataItem(key, value)
        self.dataset.FlushCache()

    def check_same_job(self, settings, path, recorded_settings):
        """A rerun resumes the catalogue's own job only: the same DEM, unchanged, tile size and
        options. The DEM by another path to the same file (a link) is the same DEM; the build
        options are compared as the same tinlod reads them (`recorded_settings`, see
        build_check), else as given."""
        given_settings = settings.get(BUILD_SETTINGS)
        for key in JOB_KEYS:
            if key == "TINLOD_SOURCE" and same_file(self.setting(key) or "", settings[key]):
                continue
            if key == "TINLOD_BUILD_OPTIONS" and recorded_settings and given_settings \
                    and same_version(recorded_settings, given_settings):
                if recorded_settings != given_settings:
                    raise TilesError("%s was made with the build options %s (in effect: %s), not %s (in effect: %s): "
                                     "run with the same options to resume it, or add -overwrite to start again"
                                     % (path, self.setting(key) or "(none)", options_part(recorded_settings),
                                        settings[key] or "(none)", options_part(given_settings)))
                continue
            if (self.setting(key) or "") != settings[key]:
                raise TilesError("%s was made with %s=%s, not %s: run with the same settings to resume it, "
                                 "or add -overwrite to start again"
                                 % (path, key, self.setting(key) or "(none)", settings[key] or "(none)"))
        for key, what in STAMPS:
            recorded = self.setting(key)  # absent in a catalogue of an earlier tinlod-tiles
            if recorded and settings.get(key) and recorded != settings[key]:
                raise TilesError("%s %s has changed since %s was made (it was %s, it is %s): its finished tiles "
                                 "were built from it as it was; add -overwrite to build every tile again"
                                 % (what, stamped_file(settings, key), path, recorded, settings[key]))

    def rows(self):
        """Each tile's (col, row) -> its fields, as a dict."""
        self.layer.ResetReading()
        return {(f["tile_col"], f["tile_row"]): feature_values(f) for f in self.layer}

    def update(self, col, row, values, extent=None):
        """Sets some fields of one tile (and its extent, an OGR polygon), committed at once."""
        feature = self.feature(col, row)
        for name, value in values.items():
            if value is None:
                feature.SetFieldNull(name)
            else:
                feature.SetField(name, value)
        if extent is not None:
            feature.SetGeometry(extent)
        try:
            self.dataset.StartTransaction()
            self.layer.SetFeature(feature)
            self.dataset.CommitTransaction()
        except RuntimeError as e:
            raise TilesError("cannot update the catalogue %s (tile %d,%d): %s" % (
                self.dataset.GetDescription(), col, row, write_failure(self.dataset.GetDescription(), e))) from None

    def feature(self, col, row):
        if (col, row) not in self.fids:
            raise TilesError("the catalogue has no tile %d,%d" % (col, row))
        return self.layer.GetFeature(self.fids[(col, row)])

    def value(self, col, row, name):
        """One field of one tile (None when null)."""
        return feature_values(self.feature(col, row))[name]

    def tiles_meeting(self, extent):
        """(col, row) of the tiles whose extent meets (xmin, ymin, xmax, ymax)."""
        self.layer.SetSpatialFilterRect(*extent)
        found = {(f["tile_col"], f["tile_row"]) for f in self.layer}
        self.layer.SetSpatialFilter(None)
        return found

    def described_extent(self):
        """The done tiles' extent and the CRS, as a message names them."""
        # The features' own envelopes: a GeoPackage's GetExtent is the whole layer's, filter or not.
        self.layer.SetAttributeFilter("status = 'done'")
        boxes = [f.GetGeometryRef().GetEnvelope() for f in self.layer if f.GetGeometryRef() is not None]
        self.layer.SetAttributeFilter(None)
        if not boxes:
            return "nothing (no tile is finished)"
        xmin, xmax = min(b[0] for b in boxes), max(b[1] for b in boxes)
        ymin, ymax = min(b[2] for b in boxes), max(b[3] for b in boxes)
        crs = self.srs.GetName() if self.srs is not None else "no CRS"
        return "%.3f %.3f %.3f %.3f (xmin ymin xmax ymax, in %s)" % (xmin, ymin, xmax, ymax, crs)

    def extent_in_layer_srs(self, polygon, srs):
        """A tile's extent in the catalogue's CRS (the same, unless the core chose another)."""
        polygon = polygon.Clone()
        if srs is not None and self.srs is not None and not srs.IsSame(self.srs):
            srs = srs.Clone()
            srs.SetAxisMappingStrategy(osr.OAMS_TRADITIONAL_GIS_ORDER)
            polygon.Transform(osr.CoordinateTransformation(srs, self.srs))
        return polygon

    def close(self):
        self.dataset.FlushCache()
        self.dataset = self.layer = None


def write_failure(path, error):
    """Why a write to `path` failed: SQLite's "database or disk is full" names no file and
    leaves the user guessing which; a full disk is said as such, with what to do."""
    try:
        full = shutil.disk_usage(os.path.dirname(os.path.abspath(path)) or ".").free < 1 << 20
    except OSError:
        full = False
    if full:
        return "the disk is full: make room and run tinlod-tiles again, which keeps the finished tiles"
    return str(error).strip()


def write_new(path, settings, srs, tiles):
    dataset = ogr.GetDriverByName("GPKG").CreateDataSource(path)
    if dataset is None:
        raise TilesError("cannot create the catalogue %s: is its folder writable?" % path)
    layer = dataset.CreateLayer(LAYER, srs, ogr.wkbPolygon, ["FID=fid", "GEOMETRY_NAME=geom"])
    for name, kind in FIELDS:
        layer.CreateField(ogr.FieldDefn(name, kind))
    dataset.StartTransaction()
    for tile in tiles:
        layer.CreateFeature(pending_feature(layer, tile))
    dataset.CommitTransaction()
    for key, value in dict(settings, TINLOD_KIND="catalogue").items():
        dataset.SetMetadataItem(key, value)
    dataset = None  # closed: written whole


def pending_feature(layer, tile):
    feature = ogr.Feature(layer.GetLayerDefn())
    for name in ("xoff", "yoff", "xsize", "ysize"):
        feature.SetField(name, getattr(tile, name))
    feature.SetField("tile_col", tile.col)
    feature.SetField("tile_row", tile.row)
    feature.SetField("status", "pending")
    feature.SetField("attempts", 0)
    return feature


def feature_values(feature):
    return {name: (feature.GetField(name) if feature.IsFieldSetAndNotNull(name) else None) for name, _ in FIELDS}


def tiles_folder(catalogue_path):
    """`<catalogue stem>_tiles` beside the catalogue."""
    return os.path.splitext(catalogue_path)[0] + "_tiles"


def levels_folder(catalogue_path):
    """`<catalogue stem>_levels` beside the catalogue: a VRT per level."""
    return os.path.splitext(catalogue_path)[0] + "_levels"
