# SPDX-License-Identifier: GPL-3.0-or-later
"""The -fixed points beyond the DEM's extent: no tile reads them, so none warns of them, where
a whole run says how many points fall outside its data. A tile warns of those inside its
extent that fall on nodata (the driver shows its warnings)."""
from osgeo import gdal, ogr, osr

from .arguments import layer_spec


def outside_count(spec, dem):
    """(points beyond the DEM's extent, points) of a -fixed layer (file, or file|layername=x);
    (0, 0) when the layer or a CRS cannot be read (tinlod's -check has said what it could)."""
    path, name = layer_spec(spec)
    dataset = gdal.OpenEx(path, gdal.OF_VECTOR)
    layer = dataset.GetLayerByName(name) if name else dataset.GetLayer(0)
    source, target = layer.GetSpatialRef(), dem.GetSpatialRef()
    if source is None or target is None:
        return 0, 0
    for srs in (source, target):
        srs.SetAxisMappingStrategy(osr.OAMS_TRADITIONAL_GIS_ORDER)
    transform = osr.CoordinateTransformation(source, target)
    x0, dx, _, y0, _, dy = dem.GetGeoTransform()
    xs = sorted((x0, x0 + dx * dem.RasterXSize))
    ys = sorted((y0, y0 + dy * dem.RasterYSize))
    outside = total = 0
    for feature in layer:
        geometry = feature.GetGeometryRef()
        if geometry is None:
            continue
        geometry = geometry.Clone()
        geometry.Transform(transform)
        for point in points_of(geometry):
            total += 1
            outside += not (xs[0] <= point[0] <= xs[1] and ys[0] <= point[1] <= ys[1])
    return outside, total


def points_of(geometry):
    """The (x, y) of a point or of each point of a multipoint."""
    if geometry.GetGeometryType() in (ogr.wkbPoint, ogr.wkbPoint25D, ogr.wkbPointM, ogr.wkbPointZM):
        return [(geometry.GetX(), geometry.GetY())]
    return [(geometry.GetGeometryRef(i).GetX(), geometry.GetGeometryRef(i).GetY())
            for i in range(geometry.GetGeometryCount())]
