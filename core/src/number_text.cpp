// SPDX-License-Identifier: GPL-3.0-or-later
#include "number_text.h"

#include <algorithm>
#include <charconv>

namespace tinlod {
namespace {

// Large enough for any double in any of the formats below (fixed notation of 1e308
// with a few decimals included).
constexpr std::size_t kBuffer = 400;

}  // namespace

std::string roundTripNumber(double value) {
  char buffer[kBuffer];
  const std::to_chars_result end = std::to_chars(buffer, buffer + kBuffer, value);
  return std::string(buffer, end.ptr);
}

std::string fixedNumber(double value, int decimals) {
  char buffer[kBuffer];
  const std::to_chars_result end = std::to_chars(buffer, buffer + kBuffer, value, std::chars_format::fixed, decimals);
  return std::string(buffer, end.ptr);
}

std::string significantNumber(double value, int digits) {
  char buffer[kBuffer];
  const std::to_chars_result end = std::to_chars(buffer, buffer + kBuffer, value, std::chars_format::general, digits);
  return std::string(buffer, end.ptr);
}

std::string columnNumber(double value, int decimals, int width) {
  const std::size_t fits = static_cast<std::size_t>(std::max(width, 1));
  std::string text = fixedNumber(value, decimals);
  for (int digits = static_cast<int>(fits); text.size() > fits && digits >= 1; --digits) text = significantNumber(value, digits);
  return text;
}

std::string groupedCount(std::size_t count) {
  std::string digits = std::to_string(count);
  for (int at = static_cast<int>(digits.size()) - 3; at > 0; at -= 3) digits.insert(static_cast<std::size_t>(at), ",");
  return digits;
}

}  // namespace tinlod
