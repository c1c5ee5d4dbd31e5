# SPDX-License-Identifier: GPL-3.0-or-later
"""Loads libtinlod_processing.so and lets it register its provider.

The algorithms are C++; qgis_process (3.22) loads only Python plugins, so this thin
plugin is what brings them into the toolbox, qgis_process and PyQGIS alike.

The library is linked against the exact QGIS it was built with (libqgis_core.so.3.22.16,
say). In any other QGIS it cannot load: the plugin then says so once, in words a user can
act on, and QGIS goes on without it instead of showing a traceback.
"""

import ctypes
import os
import sys

LIBRARY = "libtinlod_processing.so"
BUILT_FOR = "built_for_qgis.txt"  # written by the build: the QGIS version it compiled against
# Said once a process: qgis_process makes the plugin more than once.
_said = set()


def _here(name):
    return os.path.join(os.path.dirname(__file__), name)


def built_for():
    """The QGIS version the provider was built against, or None if unknown."""
    try:
        with open(_here(BUILT_FOR), encoding="utf-8") as f:
            return f.read().strip() or None
    except OSError:
        return None


def running_qgis():
    try:
        from qgis.core import Qgis

        return Qgis.QGIS_VERSION
    except Exception:  # noqa: BLE001 (outside QGIS: no version to name)
        return "unknown"


def mismatch_message(error):
    built = built_for() or "another QGIS"
    return (
        "tinlod: its Processing provider was built for QGIS {built} and cannot load in this "
        "QGIS {running} ({error}). The tinlod algorithms are not available; the rest of QGIS "
        "works as usual. To use them, rebuild tinlod on this machine (bash scripts/build.sh, "
        "then bash scripts/install-plugin.sh) or install the tinlod package built for this "
        "QGIS.".format(built=built, running=running_qgis(), error=error)
    )


class TinlodPlugin:
    def __init__(self, iface):
        self.iface = iface
        self._library = None
        self._registered = False
        self._failure = None  # the message, said once

    def initProcessing(self):  # noqa: N802 (QGIS's name)
        if self._registered or self._failure:
            return
        try:
            if self._library is None:
                self._library = ctypes.CDLL(_here(LIBRARY))
        except OSError as e:
            self._fail(mismatch_message(e))
            return
        if not self._library.tinlod_register_provider():
            self._fail("tinlod: the 'tinlod' Processing provider could not be registered")
            return
        self._registered = True

    def initGui(self):  # noqa: N802 (QGIS's name)
        self.initProcessing()

    def unload(self):
        if self._registered:
            self._library.tinlod_unregister_provider()
            self._registered = False

    def _fail(self, message):
        self._failure = message
        if message in _said:
            return
        _said.add(message)
        try:
            from qgis.core import Qgis, QgsMessageLog

            # The desktop's log panel; qgis_process prints it on the terminal.
            QgsMessageLog.logMessage(message, "tinlod", Qgis.Critical)
            if self.iface is not None and hasattr(self.iface, "messageBar"):
                self.iface.messageBar().pushMessage("tinlod", message, level=Qgis.Critical, duration=0)
        except Exception:  # noqa: BLE001 (the message must get out whatever QGIS offers)
            sys.stderr.write(message + "\n")
