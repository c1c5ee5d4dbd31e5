#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""What tinlod-tiles' driver needs to set the thresholds of a job of many tiles: its surveys
read (as each survey task ends) and the thresholds set from them, with the histograms in a
SurveyStore (as the driver does) or held in memory (-in_memory, as before). The surveys
are a job's real ones (tinlod build -survey's JSON files), read again and again to make N.

Usage: driver_surveys.py TILES_SOURCE_DIR N SURVEY.json... [-in_memory]
Prints the time to read the N surveys, to set the thresholds, the peak memory and the
store's file size."""
import resource
import sys
import tempfile
import time

sys.path.insert(0, sys.argv[1])
from tinlodtiles import thresholds  # noqa: E402
from tinlodtiles.survey_reader import SurveyReader  # noqa: E402
from tinlodtiles.survey_store import SurveyStore  # noqa: E402

in_memory = "-in_memory" in sys.argv
args = [a for a in sys.argv[2:] if a != "-in_memory"]
n, paths = int(args[0]), args[1:]
with tempfile.TemporaryDirectory() as folder, SurveyStore(folder) as store:
    reader = SurveyReader(None if in_memory else store)
    start = time.monotonic()
    for i in range(n):
        reader.load(i, paths[i % len(paths)])
    read = time.monotonic() - start
    start = time.monotonic()
    values = thresholds.level_thresholds([reader.levels(i, None) for i in range(n)], 20, 5)
    set_time = time.monotonic() - start
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    print("%d surveys (%s): read in %.1f s (%.1f ms a survey), thresholds of %d levels set in %.1f s, peak %.0f MiB%s"
          % (n, "histograms in memory" if in_memory else "histograms in a SurveyStore", read, 1000 * read / n,
             len(values), set_time, peak, "" if in_memory else ", the store's file %.0f MB" % (store.size() / 1e6)))
    print(thresholds.as_option(values))
