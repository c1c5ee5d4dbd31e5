// SPDX-License-Identifier: GPL-3.0-or-later
#include "tinlod/dem.h"

#include <algorithm>

namespace tinlod {

std::size_t Dem::validCount() const {
  return static_cast<std::size_t>(
      std::count_if(z.begin(), z.end(), [](float v) { return !std::isnan(v); }));
}

}  // namespace tinlod
