// SPDX-License-Identifier: GPL-3.0-or-later
#include "arguments.h"

#include <algorithm>
#include <charconv>
#include <climits>
#include <cmath>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include <cpl_string.h>

#include "tinlod/error.h"

namespace tinlod::cli {
namespace {

std::string numberText(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", v);
  return text;
}

template <typename T, typename F>
std::string joined(const std::vector<T>& values, F text) {
  std::string out;
  for (const T& v : values) out += (out.empty() ? "" : " ") + text(v);
  return out;
}

bool plain(unsigned char c) { return c && (std::isalnum(c) || std::strchr("_@%+=:,./-", c)); }

// A value as a shell would read it back: bare when it is plain (and no option's name),
// else quoted, and bytes that are not printable ASCII (a WKT's line breaks) as $'\xHH'; so
// that two different sets of values never read alike, and the text stays one line.
std::string quoted(const std::string& value) {
  if (!value.empty() && value[0] != '-' && std::all_of(value.begin(), value.end(), [](char c) { return plain(c); }))
    return value;
  // Letters beyond ASCII (a file name's é, 日本) are printable as they are, in UTF-8.
  const bool printable = CPLIsUTF8(value.c_str(), int(value.size())) && std::all_of(value.begin(), value.end(), [](char c) {
    return static_cast<unsigned char>(c) >= 0x20 && c != 0x7f;
  });
  std::string out = printable ? "'" : "$'";
  for (const char c : value) {
    if (!printable && (c < 0x20 || c >= 0x7f || c == '\\' || c == '\'')) {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02x", static_cast<unsigned char>(c));
      out += hex;
    } else {
      out += printable && c == '\'' ? std::string("'\\''") : std::string(1, c);
    }
  }
  return out + "'";
}

}  // namespace

Arguments::Arguments(std::vector<std::string> args) {
  const auto dashes = std::find(args.begin(), args.end(), "--");
  afterDashes_.assign(dashes == args.end() ? dashes : dashes + 1, args.end());
  args_.assign(args.begin(), dashes);
}

void Arguments::note(const std::string& name, const std::string& value, bool isDefault) {
  if (!isDefault) read_[name] = value;
}

void Arguments::restate(const std::string& name, const std::string& value, bool isDefault) {
  read_.erase(name);
  note(name, quoted(value), isDefault);
}

std::string Arguments::inEffect(const std::set<std::string>& leaveOut) const {
  std::string out;
  for (const auto& [name, value] : read_)
    if (!leaveOut.count(name)) out += (out.empty() ? "" : " ") + name + (value.empty() ? "" : " " + value);
  return out;
}

bool Arguments::flag(const std::string& name) {
  auto it = std::find(args_.begin(), args_.end(), name);
  if (it == args_.end()) return false;
  args_.erase(std::remove(it, args_.end(), name), args_.end());  // -q -q is -q
  note(name, "", false);
  return true;
}

bool Arguments::given(const std::string& name) const { return std::find(args_.begin(), args_.end(), name) != args_.end(); }

bool Arguments::take(const std::string& name, std::vector<std::string>& values, std::size_t count) {
  auto it = std::find(args_.begin(), args_.end(), name);
  if (it == args_.end()) return false;
  if (std::size_t(args_.end() - it) <= count)
    throw Error(name + " needs " + std::to_string(count) + (count == 1 ? " value" : " values"));
  values.assign(it + 1, it + 1 + count);
  args_.erase(it, it + 1 + count);
  if (std::find(args_.begin(), args_.end(), name) != args_.end()) throw Error(name + " is given more than once");
  return true;
}

bool Arguments::take(const std::string& name, std::string& value) {
  std::vector<std::string> values;
  if (!take(name, values, 1)) return false;
  value = values[0];
  return true;
}

// from_chars, unlike strtol, takes no leading space or '+' and reports overflow instead
// of clamping: "12abc", "1e3", "" and 2^64 are refused, not read as something else.
int Arguments::parseInteger(const std::string& name, const std::string& value) {
  int parsed = 0;
  const auto [end, error] = std::from_chars(value.data(), value.data() + value.size(), parsed);
  if (error == std::errc::result_out_of_range)
    throw Error(name + " expects a whole number from " + std::to_string(INT_MIN) + " to " + std::to_string(INT_MAX) +
                ", got '" + value + "'");
  if (value.empty() || error != std::errc() || end != value.data() + value.size())
    throw Error(name + " expects a whole number, got '" + value + "'");
  return parsed;
}

std::vector<int> Arguments::integers(const std::string& name, std::size_t count, std::vector<int> fallback) {
  std::vector<std::string> values;
  if (!take(name, values, count)) return fallback;
  std::vector<int> parsed;
  for (const std::string& v : values) parsed.push_back(parseInteger(name, v));
  note(name, joined(parsed, [](int v) { return std::to_string(v); }), parsed == fallback);
  return parsed;
}

std::vector<std::string> Arguments::repeated(const std::string& name) {
  std::vector<std::string> values;
  for (auto it = std::find(args_.begin(), args_.end(), name); it != args_.end(); it = std::find(args_.begin(), args_.end(), name)) {
    if (it + 1 == args_.end()) throw Error(name + " needs 1 value");
    values.push_back(*(it + 1));
    args_.erase(it, it + 2);
  }
  note(name, joined(values, quoted), values.empty());
  return values;
}

std::string Arguments::text(const std::string& name, const std::string& fallback) {
  std::string value;
  if (!take(name, value)) return fallback;
  note(name, quoted(value), value == fallback);
  return value;
}

int Arguments::integer(const std::string& name, int fallback) {
  std::string value;
  if (!take(name, value)) return fallback;
  const int parsed = parseInteger(name, value);
  note(name, std::to_string(parsed), parsed == fallback);
  return parsed;
}

double Arguments::parseNumber(const std::string& name, const std::string& value) {
  // Decimal only: strtod also reads hexadecimal ("0x14") and leading spaces, which the
  // scripts that read tinlod's options (tinlod tiles) would read otherwise or not at all.
  const bool decimal = value.find_first_not_of("0123456789+-.eE") == std::string::npos;
  char* end = nullptr;
  const double parsed = std::strtod(value.c_str(), &end);
  if (value.empty() || !decimal || *end != '\0' || !std::isfinite(parsed))
    throw Error(name + " expects a number, got '" + value + "'");
  return parsed;
}

double Arguments::number(const std::string& name, double fallback) {
  std::string value;
  if (!take(name, value)) return fallback;
  const double parsed = parseNumber(name, value);
  note(name, numberText(parsed), parsed == fallback);
  return parsed;
}

std::vector<std::vector<double>> Arguments::repeatedNumbers(const std::string& name, std::size_t count) {
  std::vector<std::vector<double>> out;
  for (auto it = std::find(args_.begin(), args_.end(), name); it != args_.end(); it = std::find(args_.begin(), args_.end(), name)) {
    if (std::size_t(args_.end() - it) <= count) throw Error(name + " needs " + std::to_string(count) + " numbers");
    std::vector<double> values;
    for (std::size_t k = 1; k <= count; ++k) values.push_back(parseNumber(name, *(it + k)));
    out.push_back(values);
    args_.erase(it, it + 1 + count);
  }
  note(name, joined(out, [](const std::vector<double>& v) { return joined(v, numberText); }), out.empty());
  return out;
}

std::uint64_t Arguments::unsignedInteger(const std::string& name, std::uint64_t fallback) {
  std::string value;
  if (!take(name, value)) return fallback;
  std::uint64_t parsed = 0;
  const auto [end, error] = std::from_chars(value.data(), value.data() + value.size(), parsed);
  if (value.empty() || error != std::errc() || end != value.data() + value.size())
    throw Error(name + " expects a whole number from 0 to " + std::to_string(UINT64_MAX) + ", got '" + value + "'");
  note(name, std::to_string(parsed), parsed == fallback);
  return parsed;
}

std::vector<double> Arguments::numbers(const std::string& name, std::size_t count, std::vector<double> fallback) {
  std::vector<std::string> values;
  if (!take(name, values, count)) return fallback;
  std::vector<double> parsed;
  for (const std::string& v : values) parsed.push_back(parseNumber(name, v));
  note(name, joined(parsed, numberText), parsed == fallback);
  return parsed;
}

std::vector<std::string> Arguments::someOperands(const std::string& usage) {
  rejectOptions(usage);
  args_.insert(args_.end(), afterDashes_.begin(), afterDashes_.end());
  afterDashes_.clear();
  if (args_.empty()) throw Error("expected one or more file names\nUsage: " + usage);
  return args_;
}

void Arguments::rejectOptions(const std::string& usage) const {
  for (const std::string& a : args_)
    if (a.size() > 1 && a[0] == '-' && !std::isdigit(static_cast<unsigned char>(a[1])))
      throw Error("unknown option '" + a + "'" +
                  (a.find_first_of("./") != std::string::npos  // a file's name, it seems
                       ? " (a file name starting with a dash goes after --, or as ./" + a + ")"
                       : std::string()) +
                  "\nUsage: " + usage);
}

std::vector<std::string> Arguments::operands(std::size_t count, const std::string& usage) {
  rejectOptions(usage);
  args_.insert(args_.end(), afterDashes_.begin(), afterDashes_.end());
  afterDashes_.clear();
  if (args_.size() != count)
    throw Error("expected " + std::to_string(count) + (count == 1 ? " file name, got " : " file names, got ") + std::to_string(args_.size()) +
                "\nUsage: " + usage);
  return args_;
}

}  // namespace tinlod::cli
