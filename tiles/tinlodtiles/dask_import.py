# SPDX-License-Identifier: GPL-3.0-or-later
"""Dask, imported on a thread of its own while the run checks its job.

Importing distributed takes about 0.6 s of one core, as long as the checks before the first
task (GDAL, two tinlod -check runs, the catalogue) and in series with them: about a tenth of
a 16-tile run on 2 workers, with the second core idle. Begun at the start, it is done by the
time the first task is submitted; a run that needs no Dask (nothing pending) or fails its
checks does not wait for it (the thread is a daemon).
"""
import threading

from .errors import TilesError

_imported = {}
_thread = None


def _import():
    try:
        import distributed
        _imported["module"] = distributed
    except ImportError:
        _imported["error"] = TilesError("Dask is not installed: apt install python3-distributed")
    except BaseException as e:  # anything else is raised where the run asks for Dask
        _imported["error"] = e


def begin():
    """Starts the import, once."""
    global _thread
    if _thread is None:
        _thread = threading.Thread(target=_import, name="import distributed", daemon=True)
        _thread.start()


def distributed():
    """The distributed module, once imported (begun here if not before)."""
    begin()
    _thread.join()
    if "error" in _imported:
        raise _imported["error"]
    return _imported["module"]
