// SPDX-License-Identifier: GPL-3.0-or-later
#include "tinlod/hierarchy_layers.h"

#include <algorithm>
#include <cctype>
#include <charconv>

#include "tinlod/error.h"

namespace tinlod {

std::vector<std::int32_t> HierarchyLayers::views(std::int32_t coarsest) const {
  std::vector<std::int32_t> out;
  if (levelViews.empty()) {
    for (std::int32_t L = 0; L <= coarsest; ++L) out.push_back(L);
    return out;
  }
  for (std::int32_t L : levelViews) {
    const std::int32_t level = L == kCoarsest ? coarsest : L;
    if (level <= coarsest) out.push_back(level);
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

std::vector<std::int32_t> HierarchyLayers::missingLevels(std::int32_t coarsest) const {
  std::vector<std::int32_t> out;
  for (std::int32_t L : levelViews)
    if (L > coarsest) out.push_back(L);
  return out;
}

namespace {

std::string trimmedLower(std::string text) {
  const auto space = [](unsigned char c) { return std::isspace(c) != 0; };
  while (!text.empty() && space(text.back())) text.pop_back();
  std::size_t first = 0;
  while (first < text.size() && space(text[first])) ++first;
  text.erase(0, first);
  for (char& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return text;
}

}  // namespace

// "0, 5, Last" as people type lists is taken too.
std::vector<std::int32_t> parseLevelList(const std::string& text, const std::string& option) {
  if (trimmedLower(text) == "all") return {};
  std::vector<std::int32_t> levels;
  std::size_t begin = 0;
  while (begin <= text.size()) {
    const std::size_t end = std::min(text.find(',', begin), text.size());
    const std::string item = trimmedLower(text.substr(begin, end - begin));
    std::int32_t level = -1;
    const auto [at, ec] = std::from_chars(item.data(), item.data() + item.size(), level);
    if (item == "last") level = HierarchyLayers::kCoarsest;
    else if (item.empty() || ec != std::errc() || at != item.data() + item.size() || level < 0)
      throw Error(option + " '" + text + "': give 'all' or levels separated by commas, such as 0,5,last ('" + item +
                  "' is not a level number)");
    levels.push_back(level);
    begin = end + 1;
  }
  return levels;
}

std::string levelListText(const std::vector<std::int32_t>& levels) {
  if (levels.empty()) return "all";
  std::string out;
  for (std::int32_t L : levels) out += (out.empty() ? "" : ",") + (L == HierarchyLayers::kCoarsest ? std::string("last") : std::to_string(L));
  return out;
}

}  // namespace tinlod
