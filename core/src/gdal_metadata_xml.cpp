// SPDX-License-Identifier: GPL-3.0-or-later
#include "gdal_metadata_xml.h"

namespace tinlod {
namespace {

std::string escaped(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

// The item's line as GDAL writes it (CPLSerializeXMLTree: two spaces an indent level).
std::string itemLine(const std::string& key, const std::string& value) {
  return "    <MDI key=\"" + escaped(key) + "\">" + escaped(value) + "</MDI>\n";
}

void removeItem(std::string& xml, std::size_t begin, std::size_t& end, const std::string& key) {
  const std::string open = "<MDI key=\"" + escaped(key) + "\">";
  const std::size_t at = xml.find(open, begin);
  if (at == std::string::npos || at >= end) return;
  const std::size_t close = xml.find("</MDI>", at);
  if (close == std::string::npos || close >= end) return;
  std::size_t lineBegin = xml.rfind('\n', at);
  lineBegin = lineBegin == std::string::npos ? at : lineBegin + 1;
  std::size_t lineEnd = close + 6;
  if (lineEnd < xml.size() && xml[lineEnd] == '\n') ++lineEnd;
  xml.erase(lineBegin, lineEnd - lineBegin);
  end -= lineEnd - lineBegin;
}

}  // namespace

bool withGdalMetadataItems(std::string& xml, const std::map<std::string, std::string>& items) {
  const std::size_t open = xml.find("<Metadata>");
  if (open == std::string::npos) return false;
  std::size_t close = xml.find("</Metadata>", open);
  if (close == std::string::npos) return false;
  for (const auto& [key, value] : items) removeItem(xml, open, close, key);
  std::size_t lineBegin = xml.rfind('\n', close);
  lineBegin = lineBegin == std::string::npos || lineBegin < open ? close : lineBegin + 1;
  std::string lines;
  for (const auto& [key, value] : items) lines += itemLine(key, value);
  xml.insert(lineBegin, lines);
  return true;
}

bool setGdalMetadataItems(SqliteDatabase& db, const std::map<std::string, std::string>& items) {
  const char* const where =
      " FROM gpkg_metadata WHERE md_scope = 'dataset' AND md_standard_uri = 'http://gdal.org' AND mime_type = 'text/xml'"
      " AND id IN (SELECT md_file_id FROM gpkg_metadata_reference WHERE reference_scope = 'geopackage')";
  if (!db.hasSchemaObject("gpkg_metadata") || !db.hasSchemaObject("gpkg_metadata_reference")) return false;
  SqliteStatement read = db.prepare(std::string("SELECT id, metadata") + where + " ORDER BY id LIMIT 1");
  if (!read.step()) return false;
  const std::int64_t id = read.integerColumn(0);
  std::string xml = read.textColumn(1);
  read.reset();
  if (!withGdalMetadataItems(xml, items)) return false;
  SqliteStatement write = db.prepare("UPDATE gpkg_metadata SET metadata = ? WHERE id = ?");
  write.bindText(1, xml);
  write.bind(2, id);
  write.step();
  return true;
}

}  // namespace tinlod
