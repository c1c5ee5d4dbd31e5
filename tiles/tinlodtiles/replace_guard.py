# SPDX-License-Identifier: GPL-3.0-or-later
"""What -overwrite may replace, as tinlod's own outputs are guarded: a file of the kind it
writes (or a damaged one), that no other program has open, that its owner has not
write-protected, and that this user may remove; the new file keeps the old one's mode and
group."""
import os
import sqlite3
import stat

from osgeo import gdal

from .errors import TilesError

SQLITE_HEADER = b"SQLite format 3\0"
# As tinlod says it (core/src/sqlite_in_use.cpp).
IN_USE_BY = ("QGIS, which holds a GeoPackage so once one of its layers has been edited, until all of them are removed; "
             "or a script")


def refuse_dangling_link(path, what):
    if os.path.islink(path) and not os.path.exists(path):
        raise TilesError("%s %s is a symbolic link to %s, which does not exist: remove the link or name another file"
                         % (what, path, os.readlink(path)))


def check_replaceable(path, kind, kind_words, what):
    """TilesError unless the existing `path` may be replaced by a new file of TINLOD_KIND
    `kind` (`kind_words` for messages, `what` names the argument)."""
    refuse_in_use(path)
    refuse_other_kind(path, kind, kind_words, what)
    refuse_protected(path, what)


def refuse_in_use(path):
    """SQLite's journal or write-ahead log beside a GeoPackage belongs to it: a new file in
    its place would be read with the old log, corrupt. A write lock is asked for and given
    back: refused while another program writes. A log left by a program that ended is played
    back so; one still in use is another program's."""
    if not is_sqlite(path):
        return
    wal = path + "-wal"
    try:
        connection = sqlite3.connect(path, timeout=0, isolation_level=None)
        try:
            connection.execute("BEGIN IMMEDIATE")
            connection.execute("ROLLBACK")
        finally:
            connection.close()
    except sqlite3.OperationalError as e:
        if "locked" in str(e) or "busy" in str(e):
            raise TilesError("%s is being written by another program (%s), locked: close it there, then run again"
                             % (path, IN_USE_BY)) from None
    except sqlite3.Error:
        pass  # a damaged file: refuse_other_kind says what it is
    if os.path.exists(wal):
        raise TilesError("%s is open in another program (%s), its write-ahead log %s in use (a file put in its place "
                         "would be read with it, corrupt): close it there, then run again"
                         % (path, IN_USE_BY, os.path.basename(wal)))


def refuse_other_kind(path, kind, kind_words, what):
    """One of `kind`, or an SQLite file no GDAL driver opens (a damaged one, which -overwrite
    is there to replace); a DEM, a GeoPackage of other layers or a text file is someone's."""
    dataset = open_any(path, gdal.OF_VECTOR | gdal.OF_RASTER)
    if dataset is not None and dataset.GetMetadataItem("TINLOD_KIND") == kind:
        return
    if dataset is None and is_sqlite(path):
        return
    reads = "GDAL reads it as %s" % dataset.GetDriver().ShortName if dataset is not None else "not a GeoPackage"
    raise TilesError("%s %s exists and is no %s (%s): -overwrite replaces only one; name another file, or remove it "
                     "first" % (what, path, kind_words, reads))


def refuse_protected(path, what):
    """As cp would not write it: write-protected (even to root, a deliverable so marked), not
    this user's to write, or another user's in a sticky folder (as /tmp)."""
    mode = os.stat(path).st_mode
    folder = os.path.dirname(os.path.abspath(path))
    if mode & 0o222 == 0:
        why = "is write-protected (mode %04o): make it writable (chmod u+w) to replace it" % stat.S_IMODE(mode)
    elif not os.access(path, os.W_OK):
        why = "is not yours to write (mode %04o)" % stat.S_IMODE(mode)
    elif not os.access(folder, os.W_OK | os.X_OK):
        why = "is in a folder you may not write"
    elif os.geteuid() != 0 and os.stat(folder).st_mode & stat.S_ISVTX and os.stat(path).st_uid != os.geteuid() \
            and os.stat(folder).st_uid != os.geteuid():
        why = "belongs to another user, in a folder where only a file's owner may replace it (sticky, as /tmp)"
    else:
        return
    raise TilesError("%s %s %s, or choose another name" % (what, path, why))


def keep_permissions(new_path, old_stat):
    """The new file keeps the old one's mode, group and (for root) owner, where the file
    system keeps them (vfat, CIFS may not)."""
    try:
        os.chown(new_path, old_stat.st_uid if os.geteuid() == 0 else -1, old_stat.st_gid)
    except OSError:
        pass  # not in its group: the new file keeps this user's
    try:
        os.chmod(new_path, stat.S_IMODE(old_stat.st_mode))
    except OSError:
        pass


def is_sqlite(path):
    try:
        with open(path, "rb") as f:
            return f.read(len(SQLITE_HEADER)) == SQLITE_HEADER
    except OSError:
        return False


def open_any(path, flags):
    """The dataset at `path`, or None where GDAL opens none (its exceptions are on)."""
    try:
        return gdal.OpenEx(path, flags)
    except RuntimeError:
        return None
