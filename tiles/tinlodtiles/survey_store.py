# SPDX-License-Identifier: GPL-3.0-or-later
"""The surveys' histograms kept on disk while the driver sets the thresholds.

A driver follows every tile through the levels, one level at a time, and reads each tile's
state from the two survey levels around its count: it needs all the tiles' small figures
(counts, picks) at once, but a tile's histograms only while it reads that tile. Held in
memory, 60,000 tiles' surveys took about 8 GB; here the histograms go into one unnamed
temporary file beside the tiles (117 KB a tile; gone when the driver ends, however it ends),
a level keeping a handle to each: 0.9 GB in all (docs/scale.md).
"""
import os
import tempfile

import numpy as np

from .errors import TilesError
from .importance_bins import Bins


class StoredBins:
    """A histogram in a SurveyStore: Bins.of reads it back."""

    __slots__ = ("store", "zero", "lo", "length", "dtype", "offset")

    def __init__(self, store, zero, lo, length, dtype, offset):
        self.store, self.zero, self.lo, self.length, self.dtype, self.offset = store, zero, lo, length, dtype, offset

    def load(self):
        return Bins(self.zero, self.lo, self.store.read(self.offset, self.length, self.dtype))


class SurveyStore:
    def __init__(self, folder):
        self.folder = folder
        self._file = tempfile.TemporaryFile(dir=folder, prefix=".tinlod-surveys-")
        self._end = 0

    def close(self):
        self._file.close()

    def __enter__(self):
        return self

    def __exit__(self, *_):
        self.close()

    def size(self):
        """The bytes written to the file."""
        return self._end

    def put(self, bins):
        """The handle of `bins` (Bins), written to the store."""
        data = np.ascontiguousarray(bins.values).tobytes()
        offset = self._end
        try:
            written = os.pwrite(self._file.fileno(), data, offset)
        except OSError as e:
            written = e
        if written != len(data):  # a full disk: 117 KB a tile, 7 GB for 60,000 tiles
            raise TilesError("cannot keep the surveys in %s (%s): the driver needs about 120 KB there a tile"
                             % (self.folder, written.strerror if isinstance(written, OSError) else "a short write"))
        self._end += len(data)
        return StoredBins(self, bins.zero, bins.lo, len(bins.values), bins.values.dtype.str, offset)

    def read(self, offset, length, dtype):
        dtype = np.dtype(dtype)
        data = os.pread(self._file.fileno(), length * dtype.itemsize, offset)
        if len(data) != length * dtype.itemsize:
            raise TilesError("the surveys kept in %s were cut short: run again" % self.folder)
        return np.frombuffer(data, dtype)  # read-only: no Bins is changed in place
