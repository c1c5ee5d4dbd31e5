// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace tinlod::cli {

// gdal-style arguments: "-name value" options, "-flag" switches and positional
// operands. Each accessor consumes what it reads; finish() rejects what is left.
class Arguments {
 public:
  // After "--" every argument is a file name, one starting with a dash included.
  explicit Arguments(std::vector<std::string> args);

  bool flag(const std::string& name);
  // Whether an option is there, without consuming it.
  bool given(const std::string& name) const;
  std::string text(const std::string& name, const std::string& fallback);
  // Every value of an option that may be given several times (-co A=1 -co B=2).
  std::vector<std::string> repeated(const std::string& name);
  int integer(const std::string& name, int fallback);
  // An option with several whole-number values, "-size 360 300"; fallback when absent.
  std::vector<int> integers(const std::string& name, std::size_t count, std::vector<int> fallback);
  double number(const std::string& name, double fallback);
  // An option with several numbers, "-valid_range -500 9000"; fallback when absent.
  std::vector<double> numbers(const std::string& name, std::size_t count, std::vector<double> fallback);
  // Every occurrence of an option of `count` numbers: "-center 1 2 -center 3 4".
  std::vector<std::vector<double>> repeatedNumbers(const std::string& name, std::size_t count);
  std::uint64_t unsignedInteger(const std::string& name, std::uint64_t fallback);
  // The remaining operands; throws Error for an unknown option or a wrong count.
  std::vector<std::string> operands(std::size_t count, const std::string& usage);
  // One or more operands.
  std::vector<std::string> someOperands(const std::string& usage);
  // The options read so far whose values differ from their defaults, as "-name value" by
  // name (numbers as read, not as typed), `leaveOut` aside; "" when there are none. Two
  // spellings of one job ("-delete_pct 20.0 -seed 5" and "-seed 5") give the same text.
  std::string inEffect(const std::set<std::string>& leaveOut) const;
  // Records an option read as text as the command understood it, where one meaning has
  // several spellings the text alone cannot tell alike ("-levels last,0" and "0,last").
  void restate(const std::string& name, const std::string& value, bool isDefault);

 private:
  bool take(const std::string& name, std::vector<std::string>& values, std::size_t count);
  bool take(const std::string& name, std::string& value);
  void rejectOptions(const std::string& usage) const;
  static int parseInteger(const std::string& name, const std::string& value);
  static double parseNumber(const std::string& name, const std::string& value);
  // Records a value read unless it is the default.
  void note(const std::string& name, const std::string& value, bool isDefault);
  std::vector<std::string> args_;
  std::vector<std::string> afterDashes_;  // the file names after "--"
  std::map<std::string, std::string> read_;  // by name: the value read, when not the default
};

}  // namespace tinlod::cli
