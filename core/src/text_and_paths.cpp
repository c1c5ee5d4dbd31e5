// SPDX-License-Identifier: GPL-3.0-or-later
#include "text_and_paths.h"

#include <cpl_string.h>
#include <cpl_vsi.h>

#include <cstdio>
#include <filesystem>
#include <sstream>

namespace tinlod {

std::string formatNumber(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

std::string jsonString(const std::string& text) {
  std::string out = "\"";
  for (unsigned char c : text) {
    if (c == '"' || c == '\\')
      out += {'\\', static_cast<char>(c)};
    else if (c == '\n')
      out += "\\n";
    else if (c == '\t')
      out += "\\t";
    else if (c == '\r')
      out += "\\r";
    else if (c < 0x20) {
      char escaped[8];
      std::snprintf(escaped, sizeof escaped, "\\u%04x", c);
      out += escaped;
    } else
      out += static_cast<char>(c);
  }
  return out + "\"";
}

namespace {

bool gdalName(const std::string& path) { return path.rfind("/vsi", 0) == 0 || path.find(':') != std::string::npos; }

}  // namespace

bool plainPathMissing(const std::string& path) {
  VSIStatBufL stat;
  return !gdalName(path) && VSIStatL(path.c_str(), &stat) != 0;
}

std::string tildeHint(const std::string& path) {
  return path.rfind('~', 0) == 0 ? " (~ is expanded by a shell only outside quotes: write the folder out, $HOME/...)" : "";
}

std::string recordedPath(const std::string& path) {
  std::error_code ec;
  std::string out = path;
  if (!gdalName(path) && std::filesystem::exists(path, ec)) {
    const std::filesystem::path absolute = std::filesystem::absolute(path, ec);
    if (!ec) out = absolute.lexically_normal().string();
  }
  // A GeoPackage's text is UTF-8: a name in another encoding (Latin-1's "d\xe9m.tif") is
  // recorded as Latin-1 read ("dém.tif"), for the eye.
  if (CPLIsUTF8(out.c_str(), int(out.size()))) return out;
  char* recoded = CPLRecode(out.c_str(), CPL_ENC_ISO8859_1, CPL_ENC_UTF8);
  out = recoded;
  CPLFree(recoded);
  return out;
}

}  // namespace tinlod
