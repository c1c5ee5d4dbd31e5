# SPDX-License-Identifier: GPL-3.0-or-later
"""Loads libtinlod_processing.so and lets it register its provider.

The algorithms are C++; qgis_process (3.22) loads only Python plugins, so this thin
plugin is what brings them into the toolbox, qgis_process and PyQGIS alike.
"""

import ctypes
import os

LIBRARY = "libtinlod_processing.so"


class TinlodPlugin:
    def __init__(self, iface):
        self.iface = iface
        self._library = None

    def initProcessing(self):  # noqa: N802 (QGIS's name)
        if self._library is None:
            path = os.path.join(os.path.dirname(__file__), LIBRARY)
            self._library = ctypes.CDLL(path)
        if not self._library.tinlod_register_provider():
            raise RuntimeError("tinlod: the 'tinlod' Processing provider could not be registered")

    def initGui(self):  # noqa: N802 (QGIS's name)
        self.initProcessing()

    def unload(self):
        if self._library is not None:
            self._library.tinlod_unregister_provider()
