# SPDX-License-Identifier: GPL-3.0-or-later
"""The one way tinlod-tiles reports a failure: a message naming the input and the fix."""


class TilesError(Exception):
    """Reported once by the command line as "ERROR: message", exit code 1."""
