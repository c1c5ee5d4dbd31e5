# SPDX-License-Identifier: GPL-3.0-or-later
"""What the catalogue records of a built tile, read from its GeoPackage."""
from dataclasses import dataclass

from osgeo import ogr, osr

from .errors import TilesError


@dataclass
class TileSummary:
    levels: int  # levels of the hierarchy, level 0 included
    vertices: int  # level 0's
    triangles: int  # level 0's
    extent: ogr.Geometry  # the triangles' bounding box, in `srs`
    srs: osr.SpatialReference


def read_tile_summary(path, expected_tile):
    try:
        return summary_of(path, expected_tile)
    except RuntimeError as e:  # GDAL's exceptions: a damaged file
        raise TilesError("%s cannot be read (%s)" % (path, str(e).strip())) from None


def summary_of(path, expected_tile):
    dataset = ogr.Open(path)
    if dataset is None:
        raise TilesError("%s is not a GeoPackage GDAL can open" % path)
    tile = dataset.GetMetadataItem("TINLOD_TILE")
    if tile is not None and tile != expected_tile:
        raise TilesError("%s holds tile %s, not %s" % (path, tile, expected_tile))
    levels = dataset.GetLayerByName("levels")
    triangles = dataset.GetLayerByName("triangles")
    if levels is None or triangles is None:
        raise TilesError("%s is no tinlod hierarchy (no levels or triangles layer)" % path)
    counts = level_rows(levels)
    vertices, triangle_count = counts.get(0, (0, 0))
    srs = triangles.GetSpatialRef()
    return TileSummary(len(counts), vertices, triangle_count, extent_polygon(triangles.GetExtent()),
                       srs.Clone() if srs is not None else None)


def level_rows(levels):
    """A tile's levels table (its layer): {level: (vertices, triangles)}."""
    return {f.GetField("level"): (f.GetField("vertices"), f.GetField("triangles")) for f in levels}


def level_vertices(path):
    """A tile's vertices per level, level 0 first; TilesError when its file holds no levels
    table (GDAL's RuntimeError when it is damaged)."""
    dataset = ogr.Open(path)
    levels = dataset.GetLayerByName("levels") if dataset is not None else None
    if levels is None:
        raise TilesError("%s holds no levels table" % path)
    rows = level_rows(levels)
    return [rows[k][0] for k in sorted(rows)]


def extent_polygon(extent):
    minx, maxx, miny, maxy = extent
    ring = ogr.Geometry(ogr.wkbLinearRing)
    for x, y in ((minx, miny), (maxx, miny), (maxx, maxy), (minx, maxy), (minx, miny)):
        ring.AddPoint_2D(x, y)
    polygon = ogr.Geometry(ogr.wkbPolygon)
    polygon.AddGeometry(ring)
    return polygon
