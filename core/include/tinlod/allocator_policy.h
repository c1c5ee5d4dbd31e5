// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

namespace tinlod {

// For a process that builds large TINs and ends (the command line, qgis_process): every
// array of 4 MB or more gets a memory mapping of its own, given back when it is freed.
// glibc otherwise raises its mmap threshold to the largest block freed (up to 32 MB), and
// arrays below it then come from the heap, where what is freed between trims stays
// resident. A threshold the user sets (MALLOC_MMAP_THRESHOLD_) stands. Not for a
// long-lived host such as the QGIS desktop, whose own allocations it would change too.
void mapLargeArraysApart();

}  // namespace tinlod
