// SPDX-License-Identifier: GPL-3.0-or-later
// Private: numbers as text for files other programs read (CSV, JSON, SVG). std::to_chars
// ignores the C locale, which QGIS may have set to one with a decimal comma.
#pragma once

#include <cstddef>
#include <string>

namespace tinlod {

// The shortest text that reads back as exactly `value`: 0.1, 650000, 1e-05.
std::string roundTripNumber(double value);

// `value` with `decimals` digits after the point: 12.5 -> "12.50" for 2.
std::string fixedNumber(double value, int decimals);

// `value` to `digits` significant digits, trailing zeros dropped: 0.0123456 -> "0.0123" for 3.
std::string significantNumber(double value, int digits);

// `value` for a table column of `width` characters: with `decimals` digits after the point
// where that fits, else with as many significant digits as fit (1e30 -> "1e+30"), so that a
// huge value never runs into the next column.
std::string columnNumber(double value, int decimals, int width);

// 650000 -> "650,000".
std::string groupedCount(std::size_t count);

}  // namespace tinlod
