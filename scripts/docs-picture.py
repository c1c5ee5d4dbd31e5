#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Draws docs/images/result.png, the README's picture, from a real run on the default DEM.

Usage: /usr/bin/python3 scripts/docs-picture.py [TINLOD [OUT.png]]
       (defaults: build/core/tinlod and docs/images/result.png)

Needs Debian's python3-matplotlib and python3-gdal (hence /usr/bin/python3, not a pyenv one).
Everything it runs is tinlod's own default DEM, so the picture never depends on outside data.
"""
import os
import subprocess
import sys
import tempfile

import matplotlib

matplotlib.use("Agg")  # no display on a build machine
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.collections import PolyCollection  # noqa: E402
from osgeo import gdal, ogr  # noqa: E402

gdal.UseExceptions()
ogr.UseExceptions()

root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
tinlod = sys.argv[1] if len(sys.argv) > 1 else os.path.join(root, "build", "core", "tinlod")
out_png = sys.argv[2] if len(sys.argv) > 2 else os.path.join(root, "docs", "images", "result.png")

# A centre south-west of the middle, so the detailed patch sits on hills rather than the lake.
CENTER = (410000.0, 5208000.0)
DROPOFF = 400.0


def run(*args):
    subprocess.run([tinlod, *args, "-q"], check=True)


def hillshade(path):
    ds = gdal.Open(path)
    band = ds.GetRasterBand(1)
    z = band.ReadAsArray().astype(float)
    nodata = band.GetNoDataValue()
    valid = np.isfinite(z) if nodata is None else (z != nodata) & np.isfinite(z)
    gt = ds.GetGeoTransform()
    zf = np.where(valid, z, np.nanmean(np.where(valid, z, np.nan)))
    # Heights exaggerated twice: the default DEM's hills are gentle at this scale.
    dy, dx = np.gradient(2.0 * zf, -gt[5], gt[1])
    # Light from the north-west, 45 degrees up, as GIS hillshades usually are.
    az, alt = np.radians(315.0), np.radians(45.0)
    slope = np.arctan(np.hypot(dx, dy))
    aspect = np.arctan2(-dx, dy)
    shade = np.sin(alt) * np.cos(slope) + np.cos(alt) * np.sin(slope) * np.cos(az - aspect)
    shade = np.ma.masked_where(~valid, np.clip(shade, 0, 1))
    extent = (gt[0], gt[0] + gt[1] * ds.RasterXSize, gt[3] + gt[5] * ds.RasterYSize, gt[3])
    return shade, extent


def triangles(path, layer_name, level_field=None):
    ds = ogr.Open(path)
    layer = ds.GetLayerByName(layer_name)
    polys, levels = [], []
    for feature in layer:
        ring = feature.GetGeometryRef().GetGeometryRef(0)
        polys.append([(ring.GetX(i), ring.GetY(i)) for i in range(3)])
        if level_field:
            levels.append(feature.GetField(level_field))
    return polys, levels


def coarsest_level(path):
    ds = ogr.Open(path)
    names = [ds.GetLayer(i).GetName() for i in range(ds.GetLayerCount())]
    return max(int(n[len("level_"):]) for n in names if n.startswith("level_"))


def main():
    with tempfile.TemporaryDirectory() as work:
        dem = os.path.join(work, "default_dem.tif")
        hier = os.path.join(work, "default_hierarchy.gpkg")
        lod = os.path.join(work, "lod.gpkg")
        run("makedem", dem)
        run("build", dem, hier)
        run("lod", hier, lod, "-center", str(CENTER[0]), str(CENTER[1]), "-dropoff", str(DROPOFF))

        shade, extent = hillshade(dem)
        top = coarsest_level(hier)
        coarse, _ = triangles(hier, "level_%d" % top)
        hier_ds = ogr.Open(hier)  # held: a layer outlives no dataset in GDAL's Python
        level0_count = hier_ds.GetLayerByName("level_0").GetFeatureCount()
        hier_ds = None
        varying, first_levels = triangles(lod, "triangles", "first_level")

    fig, axes = plt.subplots(1, 2, figsize=(11, 4.7), dpi=100)
    for ax in axes:
        ax.imshow(shade, extent=extent, cmap="gray", vmin=0, vmax=1, interpolation="bilinear")
        ax.set_xlim(extent[0], extent[1])
        ax.set_ylim(extent[2], extent[3])
        ax.set_xticks([])
        ax.set_yticks([])

    axes[0].add_collection(PolyCollection(coarse, facecolors="none", edgecolors="#b2182b", linewidths=0.2))
    axes[0].set_title("Level %d of the hierarchy: %d of level 0's %d triangles"
                      % (top, len(coarse), level0_count), fontsize=10)

    cmap = plt.get_cmap("plasma", top + 1)
    axes[1].add_collection(PolyCollection(varying, facecolors=[cmap(lv) for lv in first_levels],
                                          edgecolors="black", linewidths=0.12, alpha=0.45))
    bar = fig.colorbar(matplotlib.cm.ScalarMappable(matplotlib.colors.Normalize(-0.5, top + 0.5), cmap),
                       ax=axes[1], fraction=0.04, pad=0.02)
    bar.set_label("level", fontsize=9)
    axes[1].plot([CENTER[0]], [CENTER[1]], marker="+", color="white", markersize=12, mew=2)
    axes[1].set_title("Varying level of detail (tinlod lod): %d triangles, coloured by level"
                      % len(varying), fontsize=10)

    fig.suptitle("tinlod on its default DEM (1200 x 1000 cells of 20 m, a flat lake and a nodata void)",
                 fontsize=11)
    fig.tight_layout()
    os.makedirs(os.path.dirname(os.path.abspath(out_png)), exist_ok=True)
    fig.savefig(out_png)
    # Quantised to a palette: the picture is a line drawing over a grey shade, and a
    # full-colour PNG of it is several times larger for no visible gain.
    from PIL import Image
    Image.open(out_png).convert("RGB").quantize(colors=64, method=Image.Quantize.MEDIANCUT).save(
        out_png, optimize=True)
    print("wrote %s (%d bytes)" % (out_png, os.path.getsize(out_png)))


if __name__ == "__main__":
    main()
