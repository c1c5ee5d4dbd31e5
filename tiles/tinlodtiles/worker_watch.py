# SPDX-License-Identifier: GPL-3.0-or-later
"""A running scheduler without workers: said, where the run would wait for one in silence.

A scheduler started before its workers, workers that failed to start on their machines, or
all of them lost mid-run leave the tasks queued and the driver waiting for ever with no word.
"""
import os
import sys
import threading
import time

# How long the scheduler may have no worker before the run says so: workers started with the
# scheduler take a few seconds to join.
QUIET_SECONDS = 30.0
QUIET_VARIABLE = "TINLOD_TILES_TEST_NO_WORKERS"  # seconds instead of 30, for the tests only
POLL_SECONDS = 1.0  # the client refreshes what it knows of the scheduler every 2 s


class WorkerWatch:
    """While the run lasts, warns each time the scheduler has had no worker for QUIET_SECONDS."""

    def __init__(self, client, address):
        self.client, self.address = client, address
        self.stopped = threading.Event()
        self.thread = threading.Thread(target=self.watch, name="worker watch", daemon=True)
        self.quiet = float(os.environ.get(QUIET_VARIABLE) or QUIET_SECONDS)

    def __enter__(self):
        self.thread.start()
        return self

    def __exit__(self, *_):
        self.stopped.set()
        self.thread.join()

    def watch(self):
        since, said = time.monotonic(), False  # since when there has been no worker
        while not self.stopped.wait(POLL_SECONDS):
            if self.workers():
                since, said = time.monotonic(), False
            elif not said and time.monotonic() - since >= self.quiet:
                said = True
                print("Warning: the Dask scheduler %s has had no worker for %.0f s: the tiles wait for one. Start "
                      "`dask worker %s` where the DEM, the tiles folder and tinlod are reachable by the same paths "
                      "(Ctrl-C stops the run; the same command resumes it)" % (self.address, self.quiet, self.address),
                      file=sys.stderr, flush=True)

    def workers(self):
        try:
            return len(self.client.scheduler_info().get("workers", {}))
        except Exception:  # the client closing meanwhile: nothing to say
            return 1
