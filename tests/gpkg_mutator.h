// SPDX-License-Identifier: GPL-3.0-or-later
// Random damage to a tinlod hierarchy GeoPackage, for the readers' fuzz test: hostile
// field values (huge, negative, NULL, text, other rows' ids), broken geometries, dropped
// rows, tables and columns, changed metadata and feature counts, truncated and scribbled
// files. The same seed gives the same damage.
#pragma once

#include <cstdint>
#include <map>
#include <random>
#include <string>

namespace tinlod::test {

class GpkgMutator {
 public:
  // `source`: the hierarchy every copy is made from.
  GpkgMutator(const std::string& source, std::uint64_t seed);

  // A fresh copy of the source with one to three random changes; `what` says which, for a
  // failure message (a change SQLite refused is listed as such, and the copy stays valid).
  std::string mutatedCopy(std::string& what);

 private:
  std::string change(const std::string& copy);
  std::string changeField(const std::string& copy);
  std::string changeGeometry(const std::string& copy);
  std::string dropRows(const std::string& copy);
  std::string dropSchema(const std::string& copy);
  std::string changeMetadata(const std::string& copy);
  std::string changeFeatureCount(const std::string& copy);
  std::string damageBytes(const std::string& copy);

  std::string hostileValue(const std::string& table, const std::string& column);
  std::string hostileText();
  long long anyRow(const std::string& table);
  std::string sql(const std::string& copy, const std::string& statement);
  int below(int n) { return static_cast<int>(random_() % static_cast<std::uint64_t>(n)); }

  std::string source_;
  std::mt19937_64 random_;
  std::map<std::string, long long> rows_;  // by table, in the source
};

}  // namespace tinlod::test
