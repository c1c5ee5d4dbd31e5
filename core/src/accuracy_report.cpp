// SPDX-License-Identifier: GPL-3.0-or-later
#include "tinlod/accuracy_report.h"

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <filesystem>
#include <fstream>

#include "accuracy_report_formats.h"
#include "tinlod/error.h"
#include "tinlod/output_files.h"

namespace fs = std::filesystem;

namespace tinlod {
namespace {

using Writer = void (*)(const AccuracyReport&, std::ostream&);

std::string lowerExtension(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

// nullptr for an extension no format has.
Writer writerFor(const std::string& path) {
  const std::string ext = lowerExtension(path);
  if (ext == ".csv") return writeCsvReport;
  if (ext == ".json") return writeJsonReport;
  if (ext == ".html" || ext == ".htm") return writeHtmlReport;
  return nullptr;
}

}  // namespace

// Said in the user's terms before the temporary sibling exists, whose name would
// otherwise turn up in the message of a failed open.
void checkAccuracyReportPath(const std::string& path) {
  const std::string ext = lowerExtension(path);
  if (ext.empty()) throw Error("-report: '" + path + "' has no extension: name the file .csv, .json or .html");
  if (!writerFor(path)) throw Error("-report: unknown report format '" + ext + "': name the file .csv, .json or .html");
  const fs::path dir = fs::path(path).parent_path().empty() ? fs::path(".") : fs::path(path).parent_path();
  if (!fs::is_directory(dir)) throw Error("-report: the folder of '" + path + "' does not exist");
  if (access(dir.c_str(), W_OK) != 0) throw Error("-report: the folder of '" + path + "' is not writable");
  if (fs::is_directory(path)) throw Error("-report: '" + path + "' is a folder: name a .csv, .json or .html file");
}

void writeAccuracyReport(const AccuracyReport& report, const std::string& path) {
  checkAccuracyReportPath(path);
  OutputFiles files(true);
  writeAccuracyReport(report, files.add(path, "-report"));
  files.commit();
}

void writeAccuracyReport(const AccuracyReport& report, const StagedFile& file) {
  errno = 0;
  std::ofstream out(file.staging, std::ios::binary);
  writerFor(file.path)(report, out);
  out.close();
  if (!out) throw Error(file.option + ": cannot write '" + file.path + "': " + whyWriteFailed(file.staging.parent_path()));
}

bool isAccuracyReportPath(const std::string& path) { return writerFor(path) != nullptr; }

}  // namespace tinlod
