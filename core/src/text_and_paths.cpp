// SPDX-License-Identifier: GPL-3.0-or-later
#include "text_and_paths.h"

#include <cpl_vsi.h>

#include <sstream>

namespace tinlod {

std::string formatNumber(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

bool plainPathMissing(const std::string& path) {
  const bool special = path.rfind("/vsi", 0) == 0 || path.find(':') != std::string::npos;
  VSIStatBufL stat;
  return !special && VSIStatL(path.c_str(), &stat) != 0;
}

}  // namespace tinlod
