# SPDX-License-Identifier: GPL-3.0-or-later
"""The CRS the core gives a DEM's TIN, known before any tile is built, for the catalogue's
`tiles` layer: -t_srs if given, else the DEM's CRS (or -s_srs) if it is in metres, else the
UTM zone of the DEM's centre (docs/cli/sample.md). A tile built in another CRS after all
has its extent transformed to this one."""
import math

from osgeo import osr

from .errors import TilesError


def user_srs(text, option):
    srs = osr.SpatialReference()
    try:
        srs.SetFromUserInput(text)
    except RuntimeError as e:
        raise TilesError("%s %s is not a CRS GDAL knows (%s); give EPSG:code, WKT or a PROJ string"
                         % (option, text, e)) from None
    srs.SetAxisMappingStrategy(osr.OAMS_TRADITIONAL_GIS_ORDER)
    return srs


def option_value(build_options, name):
    """The value after `name` in the build options, or None."""
    for i, option in enumerate(build_options[:-1]):
        if option == name:
            return build_options[i + 1]
    return None


def predicted_tin_srs(dataset, build_options):
    """The TIN's CRS, or None when the DEM has none (the core then says so per tile)."""
    target = option_value(build_options, "-t_srs")
    if target is not None:
        return user_srs(target, "-t_srs")
    source = option_value(build_options, "-s_srs")
    srs = user_srs(source, "-s_srs") if source is not None else dataset.GetSpatialRef()
    if srs is None:
        return None
    if srs.IsProjected() and abs(srs.GetLinearUnits() - 1.0) < 1e-9:
        return srs
    return utm_zone_of_centre(dataset, srs)


def utm_zone_of_centre(dataset, srs):
    gt = dataset.GetGeoTransform()
    x = gt[0] + gt[1] * dataset.RasterXSize / 2 + gt[2] * dataset.RasterYSize / 2
    y = gt[3] + gt[4] * dataset.RasterXSize / 2 + gt[5] * dataset.RasterYSize / 2
    wgs84 = osr.SpatialReference()
    wgs84.ImportFromEPSG(4326)
    wgs84.SetAxisMappingStrategy(osr.OAMS_TRADITIONAL_GIS_ORDER)
    srs = srs.Clone()
    srs.SetAxisMappingStrategy(osr.OAMS_TRADITIONAL_GIS_ORDER)
    lon, lat, _ = osr.CoordinateTransformation(srs, wgs84).TransformPoint(x, y)
    zone = min(60, max(1, int(math.floor((lon + 180) / 6)) + 1))
    utm = osr.SpatialReference()
    utm.ImportFromEPSG((32600 if lat >= 0 else 32700) + zone)
    utm.SetAxisMappingStrategy(osr.OAMS_TRADITIONAL_GIS_ORDER)
    return utm
