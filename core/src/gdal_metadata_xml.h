// SPDX-License-Identifier: GPL-3.0-or-later
// Private: items added to the dataset metadata GDAL keeps in a GeoPackage (an XML
// document in gpkg_metadata), in the bulk writer's SQLite connection: a reopening of the
// file through GDAL only to add them cost a PROJ database start-up, a tenth of a small job.
#pragma once

#include <map>
#include <string>

#include "sqlite_database.h"

namespace tinlod {

// `xml` with each item set in its default domain (<Metadata> without a domain), replacing
// an item of the same key. Returns false when `xml` has no default domain to add to.
bool withGdalMetadataItems(std::string& xml, const std::map<std::string, std::string>& items);

// Sets the items in the file's dataset metadata; false when GDAL wrote none to set them in.
bool setGdalMetadataItems(SqliteDatabase& db, const std::map<std::string, std::string>& items);

}  // namespace tinlod
