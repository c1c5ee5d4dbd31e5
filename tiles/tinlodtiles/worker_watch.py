# SPDX-License-Identifier: GPL-3.0-or-later
"""A running scheduler's workers, watched while the run lasts: none, or one that runs several
tiles at once, is said.

A scheduler started before its workers, workers that failed to start on their machines, or
all of them lost mid-run leave the tasks queued and the driver waiting for ever with no word.
A worker started with --nthreads N runs N tiles at once, each tinlod on every core its
machine's TINLOD_THREADS allows (all by default): N times the threads the machine has.
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
    """While the run lasts, warns each time the scheduler has had no worker for QUIET_SECONDS,
    and once of each worker that runs several tiles at once."""

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
        crowded = set()  # the workers said to run several tiles at once
        while True:  # looked at once at the start, then every POLL_SECONDS
            workers = self.workers()
            self.say_crowded(workers, crowded)
            if workers:
                since, said = time.monotonic(), False
            elif not said and time.monotonic() - since >= self.quiet:
                said = True
                print("Warning: the Dask scheduler %s has had no worker for %.0f s: the tiles wait for one. Start "
                      "`dask worker %s` where the DEM, the tiles folder and tinlod are reachable by the same paths "
                      "(Ctrl-C stops the run; the same command resumes it)" % (self.address, self.quiet, self.address),
                      file=sys.stderr, flush=True)
            if self.stopped.wait(POLL_SECONDS):
                return

    @staticmethod
    def say_crowded(workers, crowded):
        """Once for each worker with more than one thread (the addresses said go into `crowded`)."""
        for address, worker in workers.items():
            threads = worker.get("nthreads", 1)
            if threads > 1 and address not in crowded:
                crowded.add(address)
                print("Warning: the Dask worker %s runs %d tiles at once (--nthreads %d), each tinlod on the cores "
                      "its TINLOD_THREADS allows (every core by default): start workers with --nthreads 1 "
                      "(--nworkers for more on a machine) and TINLOD_THREADS set to the cores over them"
                      % (address, threads, threads), file=sys.stderr, flush=True)

    def workers(self):
        """The scheduler's workers as the client last heard of them: {address: info}."""
        try:
            return dict(self.client.scheduler_info().get("workers", {}))
        except Exception:  # the client closing meanwhile: nothing to say
            return {"": {}}
