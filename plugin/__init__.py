# SPDX-License-Identifier: GPL-3.0-or-later
"""tinlod QGIS plugin: registers the compiled "TIN hierarchy" Processing provider."""


def classFactory(iface):  # noqa: N802 (QGIS's name)
    from .tinlod_plugin import TinlodPlugin

    return TinlodPlugin(iface)
