# SPDX-License-Identifier: GPL-3.0-or-later
"""tinlod build -check, run by the driver before anything is written: what every tile would
refuse is said once, not by every task and retry; and the build options as that tinlod reads
them (its "options in effect"), which the catalogue records (TINLOD_BUILD_SETTINGS), so that
a rerun spelling the same job another way (a default given, another order, 20.0 for 20)
resumes it.
"""
import subprocess

from .errors import TilesError
from .task import tinlod_error, warning_lines

IN_EFFECT = "Options in effect: "


def check_job(tinlod, dem, catalogue, tile_size, tiles, build_options):
    """-check with the job's build options on the first and the last tile (the raster's two
    ends, where a geographic DEM's cells are widest and narrowest); TilesError with tinlod's
    message if it refuses them. Returns the settings to record ("" from a tinlod that prints
    none) and the checks' warnings (a CRS that stretches distances or cannot project the whole
    DEM), which every task would give again after its tile, hours into a national job."""
    # At once, with the version the settings name: the run's first task waits on them.
    checks = [(tile, start_check(tinlod, dem, catalogue, tile_size, tile, build_options))
              for tile in dict.fromkeys((tiles[0], tiles[-1]))]  # once for a single tile
    asked_version = start_version(tinlod)
    try:
        warnings = []
        for tile, check in checks:
            result = finished(check)
            warnings += warning_lines(result.stderr)
            if result.returncode != 0:
                message = tinlod_error(result.stderr) or result.stderr.strip() or "exit code %d" % result.returncode
                raise TilesError("tinlod build refuses the job (tile %d,%d): %s. Nothing was written"
                                 % (tile.col, tile.row, message))
        # The options read alike on every tile.
        return settings_of(version_of(finished(asked_version)), result), list(dict.fromkeys(warnings))
    finally:  # a refusal, or Ctrl-C
        for process in [process for _, process in checks] + [asked_version]:
            if process.poll() is None:
                process.kill()
                process.wait()


def recorded_settings(tinlod, dem, catalogue, tile_size, tile, build_options):
    """The settings of options an earlier run recorded only as given; "" if -check refuses
    them now."""
    result = finished(start_check(tinlod, dem, catalogue, tile_size, tile, build_options))
    return settings_of(version_of(finished(start_version(tinlod))), result) if result.returncode == 0 else ""


def start_check(tinlod, dem, catalogue, tile_size, tile, build_options):
    # Our options go first, so that a user's option without its value cannot take one.
    command = [tinlod, "build", dem, catalogue, "-check", "-tile_size", str(tile_size),
               "-tile", "%d,%d" % (tile.col, tile.row)]
    return start(command + list(build_options))


def start(command):
    return subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            errors="surrogateescape")


def finished(process):
    stdout, stderr = process.communicate()
    return subprocess.CompletedProcess(process.args, process.returncode, stdout, stderr)


def settings_of(version, result):
    """"VERSION: OPTIONS" (`version` as version_of gives it): a default means what that
    tinlod says it means, so settings recorded by another version are not compared
    (same_version)."""
    in_effect = next((line[len(IN_EFFECT):] for line in result.stdout.split("\n") if line.startswith(IN_EFFECT)), "")
    return "%s: %s" % (version, in_effect) if in_effect else ""


def start_version(tinlod):
    return start([tinlod, "--version"])


def version_of(result):
    """The first line of tinlod --version's answer (`result`, as finished gives it)."""
    return result.stdout.strip().split("\n")[0] or "tinlod of unknown version"


def same_version(a, b):
    return a.split(": ", 1)[0] == b.split(": ", 1)[0]
