# SPDX-License-Identifier: GPL-3.0-or-later
"""The checks of the Python test scripts: each prints `ok: ...` or `FAILED: ...`, and the
script's exit code says whether any failed (ctest reads it)."""

failures = []


def check(what, ok, detail=""):
    print(("ok: " if ok else "FAILED: ") + what + ("" if ok else "  (%s)" % (detail,)))
    if not ok:
        failures.append(what)


def exit_code(script):
    """Prints how many checks of `script` failed; 1 if any did, else 0."""
    print("%s: %d failed" % (script, len(failures)))
    return 1 if failures else 0
