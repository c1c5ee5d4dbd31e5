# SPDX-License-Identifier: GPL-3.0-or-later
"""tinlod-tiles: a DEM of any size built as tiles by Dask, listed in a catalogue GeoPackage."""
