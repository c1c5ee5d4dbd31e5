# SPDX-License-Identifier: GPL-3.0-or-later
"""One tile's task, run by a Dask worker: `tinlod build` on the tile, in a subprocess.

Only the standard library: the module is shipped to workers by value (cloudpickle), so a
worker on another host needs nothing of tinlod-tiles installed, only tinlod itself and the
same paths to the DEM and the tiles folder.
"""
import ctypes
import os
import signal
import socket
import subprocess
import time

EMPTY_EXIT_CODE = 3  # the core's "the tile holds no valid data: nothing written"
KILL_HOOK_VARIABLE = "TINLOD_TILES_TEST_KILL"  # "C,R:seconds", for the tests only
_PR_SET_PDEATHSIG = 1
ERROR_PREFIX = "ERROR: "  # how tinlod starts a failure's message on stderr
WARNING_PREFIX = "Warning: "  # and a warning's
WORKER_PREFIX = "worker "  # a failure of the worker's reach (unreachable), not of tinlod's


class TileFailed(Exception):
    """tinlod failed on the tile or was killed; Dask retries the task."""


def run_tile(job):
    """Build one tile. `job` is a dict: tinlod, dem, tiles_dir, name, col, row, tile_size,
    build_options, kill_hook. Returns the tile's status ('done' or 'empty'), seconds, peak MiB
    and tinlod's warnings; raises TileFailed otherwise."""
    final = os.path.join(job["tiles_dir"], job["name"])
    partial = partial_path(final)
    check_reach(job)
    try:
        attempt = count_attempt(final)
        remove_if_present(partial)
    except OSError as e:
        raise TileFailed(unreachable(job, "cannot write the tiles folder %s (%s)" % (job["tiles_dir"], e.strerror or e)))
    command = [job["tinlod"], "build", job["dem"], partial, "-tile_size", str(job["tile_size"]),
               "-tile", "%d,%d" % (job["col"], job["row"])] + list(job["build_options"]) + ["-q", "-overwrite"]
    if job.get("survey"):
        command.append("-survey")
    kill_after = kill_hook_seconds(job, attempt)
    try:
        code, seconds, peak_mib, message, warnings = run_measured(command, final + ".log", kill_after, job.get("threads"))
    except OSError as e:  # tinlod gone since check_reach, or the log not writable
        raise TileFailed(unreachable(job, "cannot run %s (%s)" % (job["tinlod"], e.strerror or e))) from None
    if code == EMPTY_EXIT_CODE:
        remove_if_present(partial)
        return {"status": "empty", "seconds": seconds, "peak_mib": peak_mib, "attempt": attempt, "warnings": []}
    if code != 0 or not os.path.isfile(partial):
        remove_if_present(partial)
        raise TileFailed("tile %d,%d (attempt %d): %s" % (job["col"], job["row"], attempt, message))
    publish(partial, final)
    return {"status": "done", "seconds": seconds, "peak_mib": peak_mib, "attempt": attempt, "warnings": warnings}


def check_reach(job):
    """What a worker on another machine may lack: the DEM (when the driver saw a file there;
    GDAL's virtual paths and connection strings are tinlod's to open), the tiles folder, or
    tinlod, at the driver's paths. Said as such, naming the worker, where tinlod's "cannot
    open the DEM" blamed the DEM the driver had just read."""
    dem, tinlod = job["dem"], job["tinlod"]
    if job.get("dem_is_file") and not os.path.exists(dem):
        raise TileFailed(unreachable(job, "cannot see the DEM %s" % dem))
    if not os.path.isdir(job["tiles_dir"]):
        raise TileFailed(unreachable(job, "cannot see the tiles folder %s" % job["tiles_dir"]))
    if not os.access(tinlod, os.X_OK):
        raise TileFailed(unreachable(job, "has no tinlod at %s" % tinlod))


def unreachable(job, what):
    """A task's failure for want of the driver's paths on its worker: on a remote scheduler's,
    most likely a machine without them; on the local cluster, a file moved during the run."""
    if job.get("remote"):
        return "%s %s: every worker must reach the DEM, the tiles folder and tinlod by the paths the driver gives " \
               "(a shared file system, tinlod installed alike)" % (worker_name(), what)
    return "%s %s (moved or removed during the run?)" % (WORKER_PREFIX.strip(), what)


def worker_name():
    """The worker running this task, "worker ADDRESS (host NAME)", as `dask worker` lists it."""
    host = socket.gethostname()
    try:
        from distributed import get_worker
        return "%s %s (host %s)" % (WORKER_PREFIX.strip(), get_worker().address, host)
    except (ImportError, ValueError):  # not on a Dask worker (a test calling run_tile)
        return "%s on host %s" % (WORKER_PREFIX.strip(), host)


def publish(partial, final):
    """Renames the finished file to its final name, so that the tile appears whole or not at
    all; its bytes on disk first (tinlod writes without syncing, for speed), then the rename:
    the catalogue then records a finished tile that a crash of the machine cannot leave
    truncated under its final name, which a rerun would take as finished."""
    sync_path(partial, os.O_RDONLY)
    os.replace(partial, final)
    sync_path(os.path.dirname(os.path.abspath(final)), os.O_RDONLY | os.O_DIRECTORY)


def sync_path(path, flags):
    descriptor = os.open(path, flags)
    try:
        os.fsync(descriptor)
    finally:
        os.close(descriptor)


def partial_path(final):
    """Where tinlod writes the tile (or its survey) until it is complete, with the final name's
    extension, so tinlod knows the format."""
    stem, ext = os.path.splitext(final)
    return stem + ".partial" + ext


def attempts_path(final):
    return final + ".attempts"


def count_attempt(final):
    """This attempt's number for the tile, kept in a marker file beside it: a retry may run
    on another worker, and the driver reads the count when the tile fails for good."""
    path = attempts_path(final)
    try:
        with open(path) as f:
            attempt = int(f.read().strip() or 0) + 1
    except (OSError, ValueError):
        attempt = 1
    with open(path, "w") as f:
        f.write("%d\n" % attempt)
    return attempt


def kill_hook_seconds(job, attempt):
    """The test hook: TINLOD_TILES_TEST_KILL="C,R:seconds" (the driver's, passed in the job,
    so that it reaches remote workers too) kills this tile's tinlod after that many seconds
    on its first attempt, so that the task fails mid-run."""
    hook = job.get("kill_hook") or ""
    if attempt != 1 or ":" not in hook:
        return None
    tile, seconds = hook.split(":", 1)
    return float(seconds) if tile == "%d,%d" % (job["col"], job["row"]) else None


def run_measured(command, log_path, kill_after=None, threads=None):
    """Runs the command; returns (exit code, wall seconds, peak RSS in MiB, last stderr
    line, its warnings). A signal gives a negative code, as in subprocess."""
    start = time.monotonic()
    with open(log_path, "wb") as log:
        # A session of its own: the terminal's Ctrl-C reaches the driver, which stops the
        # run; the parent-death signal ends tinlod if its worker dies.
        env = dict(os.environ, TINLOD_THREADS=str(threads)) if threads else None
        process = subprocess.Popen(command, stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                                   stderr=log, start_new_session=True, preexec_fn=_dying_with_parent(), env=env)
        status, usage = wait_or_kill(process.pid, start, kill_after)
    process.returncode = os.waitstatus_to_exitcode(status)  # reaped here, not by Popen
    seconds = time.monotonic() - start
    text = read_log(log_path)
    remove_if_present(log_path)
    message, warnings = last_error_line(text, process.returncode), warning_lines(text)
    return process.returncode, seconds, usage.ru_maxrss / 1024.0, message, warnings


def wait_or_kill(pid, start, kill_after):
    """os.wait4 (for the child's ru_maxrss), polling while a kill is due, so the pid is
    never signalled once reaped."""
    while kill_after is not None:
        reaped, status, usage = os.wait4(pid, os.WNOHANG)
        if reaped == pid:
            return status, usage
        if time.monotonic() - start >= kill_after:
            os.kill(pid, signal.SIGKILL)
            break
        time.sleep(0.05)
    _, status, usage = os.wait4(pid, 0)
    return status, usage


def read_log(log_path):
    """What tinlod wrote to stderr ("" when there is no log)."""
    try:
        with open(log_path, errors="replace") as f:
            return f.read()
    except OSError:
        return ""


def last_error_line(text, code):
    """The message to record from tinlod's stderr: its last error (its lines after ERROR
    too), else the last other ERROR line, else its last line, else the code."""
    error = tinlod_error(text)
    if error is not None:
        return ERROR_PREFIX + error
    lines = [line.strip() for line in text.split("\n") if line.strip()]
    others = [line for line in lines if line.startswith("ERROR")]  # GDAL's, before a crash
    if others:
        return others[-1]
    if code < 0:
        return "tinlod was killed by signal %d" % -code
    return lines[-1] if lines else "tinlod exited with code %d" % code


def warning_lines(text):
    """tinlod's warnings in its stderr ("Warning: ..."), each once, in order, without the prefix."""
    lines = [line.strip() for line in text.split("\n") if line.startswith(WARNING_PREFIX)]
    return list(dict.fromkeys(line[len(WARNING_PREFIX):] for line in lines))


def tinlod_error(stderr_text):
    """tinlod's last error message in what it wrote to stderr, None when there is none.
    The lines after the ERROR line continue it (a value it quotes, such as a WKT, may span
    lines, and the advice comes after it), up to the usage tinlod adds after a misspelt
    option, or a message of its own (GDAL's "ERROR 1: ...", a warning)."""
    lines = stderr_text.split("\n")
    starts = [i for i, line in enumerate(lines) if line.startswith(ERROR_PREFIX)]
    if not starts:
        return None
    message = [lines[starts[-1]][len(ERROR_PREFIX):]]
    for line in lines[starts[-1] + 1:]:
        if line.startswith(("Usage:", "ERROR", "WARNING", "Warning")):
            break
        message.append(line)
    return "\n".join(message).rstrip()


def _dying_with_parent():
    """For the child: SIGTERM when the worker thread that started it ends (prctl), prctl
    looked up here, so that the forked child of a threaded process only calls it."""
    prctl = ctypes.CDLL(None, use_errno=True).prctl
    return lambda: prctl(_PR_SET_PDEATHSIG, signal.SIGTERM)


def remove_if_present(path):
    try:
        os.remove(path)
    except FileNotFoundError:
        pass
