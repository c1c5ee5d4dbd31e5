// SPDX-License-Identifier: GPL-3.0-or-later
#include "tinlod/accuracy_report.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "report_plots.h"
#include "tinlod/error.h"

namespace fs = std::filesystem;

namespace tinlod {
namespace {

const char* const kCsvHeader =
    "dem,method,delete_pct,stop_pct,level,vertices,triangles,select_s,delete_s,certified_error_m,test_points,"
    "rmse_m,mean_error_m,max_abs_error_m,max_error_x,max_error_y,morans_i,insert_rmse_m,rmse_ratio_to_insert,"
    "elevation_n,elevation_r,elevation_mean_ref,elevation_mean_simplified,elevation_std_ref,elevation_std_simplified,"
    "mean_curvature_n,mean_curvature_r,mean_curvature_mean_ref,mean_curvature_mean_simplified,"
    "mean_curvature_std_ref,mean_curvature_std_simplified";

// A folder of its own per test, so listing it shows exactly what the writer left.
struct TempFolder {
  fs::path path;
  TempFolder() {
    static int counter = 0;
    path = fs::temp_directory_path() /
           ("tinlod-report-test-" + std::to_string(getpid()) + "-" + std::to_string(++counter));
    fs::create_directories(path);
  }
  ~TempFolder() {
    std::error_code ignored;
    fs::remove_all(path, ignored);
  }
  std::string file(const std::string& name) const { return (path / name).string(); }
  std::vector<std::string> names() const {
    std::vector<std::string> out;
    for (const fs::directory_entry& e : fs::directory_iterator(path)) out.push_back(e.path().filename().string());
    return out;
  }
};

// A level whose accuracy falls with its number, as a real run's does.
LevelAccuracy level(const std::string& dem, const std::string& method, int number, std::size_t vertices) {
  LevelAccuracy l;
  l.dem = dem;
  l.method = method;
  l.deletePct = 20;
  l.stopPct = 5;
  l.level = number;
  l.vertices = vertices;
  l.triangles = 2 * vertices;
  l.selectSeconds = 0.5 + number;
  l.deleteSeconds = 1.25 + number;
  l.certifiedError = 2.0 * number;
  l.testPoints = 10000;
  l.rmse = 0.1 + number;
  l.meanError = -0.01;
  l.maxAbsError = 3.0 + 2 * number;
  l.maxErrorX = 500000.5;
  l.maxErrorY = 5100000.25;
  l.moransI = 0.4;
  l.variables = {{"elevation", 10000, 1 - std::pow(10.0, -5 + 0.3 * number), 800, 800.5, 120, 119},
                 {"mean_curvature", 9000, 0.95 - 0.05 * number, 0, 0.0001, 0.01, 0.008}};
  return l;
}

std::vector<LevelAccuracy> run(const std::string& dem, const std::string& method, int levels) {
  std::vector<LevelAccuracy> rows;
  for (int i = 0; i < levels; ++i)
    rows.push_back(level(dem, method, i, static_cast<std::size_t>(650000 * std::pow(0.7, i))));
  return rows;
}

AccuracyReport report(std::vector<LevelAccuracy> rows) {
  AccuracyReport r;
  r.title = "Accuracy test";
  r.reference = "tin";
  r.crsName = "WGS 84 / UTM zone 32N";
  r.generator = "tinlod test";
  r.rows = std::move(rows);
  return r;
}

std::string readText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

// RFC 4180 fields of one line (no line breaks inside quotes in these tests).
std::vector<std::string> csvFields(const std::string& line) {
  std::vector<std::string> out(1);
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted && c == '"' && i + 1 < line.size() && line[i + 1] == '"')
      out.back() += line[++i];
    else if (c == '"')
      quoted = !quoted;
    else if (c == ',' && !quoted)
      out.emplace_back();
    else
      out.back() += c;
  }
  return out;
}

std::string csvField(const std::vector<std::string>& header, const std::vector<std::string>& row,
                     const std::string& column) {
  for (std::size_t i = 0; i < header.size(); ++i)
    if (header[i] == column) return row.at(i);
  ADD_FAILURE() << "no column " << column;
  return {};
}

std::size_t occurrences(const std::string& text, const std::string& needle) {
  std::size_t n = 0;
  for (std::size_t at = text.find(needle); at != std::string::npos; at = text.find(needle, at + needle.size())) ++n;
  return n;
}

// A strict JSON syntax check (RFC 8259), enough to catch a missing comma, a bare NaN
// or an unescaped quote.
class JsonChecker {
 public:
  explicit JsonChecker(const std::string& text) : s_(text) {}
  bool valid() {
    const bool ok = value();
    space();
    return ok && at_ == s_.size();
  }

 private:
  void space() {
    while (at_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[at_]))) ++at_;
  }
  bool eat(char c) {
    space();
    if (at_ < s_.size() && s_[at_] == c) return ++at_, true;
    return false;
  }
  bool literal(const std::string& word) {
    if (s_.compare(at_, word.size(), word) != 0) return false;
    at_ += word.size();
    return true;
  }
  bool string() {
    if (!eat('"')) return false;
    while (at_ < s_.size() && s_[at_] != '"') {
      if (static_cast<unsigned char>(s_[at_]) < 0x20) return false;
      if (s_[at_] == '\\' && ++at_ < s_.size() && std::string("\"\\/bfnrtu").find(s_[at_]) == std::string::npos)
        return false;
      ++at_;
    }
    return eat('"');
  }
  bool number() {
    static const std::regex pattern(R"(-?(0|[1-9][0-9]*)(\.[0-9]+)?([eE][+-]?[0-9]+)?)");
    std::smatch m;
    const std::string rest = s_.substr(at_, 40);
    if (!std::regex_search(rest, m, pattern, std::regex_constants::match_continuous)) return false;
    at_ += static_cast<std::size_t>(m.length(0));
    return true;
  }
  template <typename Item>
  bool sequence(char close, Item item) {
    if (eat(close)) return true;
    do
      if (!item()) return false;
    while (eat(','));
    return eat(close);
  }
  bool value() {
    space();
    if (eat('{')) return sequence('}', [this] { return string() && eat(':') && value(); });
    if (eat('[')) return sequence(']', [this] { return value(); });
    if (at_ < s_.size() && s_[at_] == '"') return string();
    return literal("null") || literal("true") || literal("false") || number();
  }
  const std::string& s_;
  std::size_t at_ = 0;
};

std::vector<std::string> svgElements(const std::string& html) {
  std::vector<std::string> out;
  for (std::size_t at = html.find("<svg"); at != std::string::npos; at = html.find("<svg", at + 1))
    out.push_back(html.substr(at, html.find("</svg>", at) - at));
  return out;
}

TEST(AccuracyReport, CsvHasTheHeaderAndALinePerLevel) {
  TempFolder dir;
  std::vector<LevelAccuracy> rows = run("alps.tif", "degree", 3);
  const std::vector<LevelAccuracy> more = run("alps.tif", "volume", 2);
  rows.insert(rows.end(), more.begin(), more.end());
  writeAccuracyReport(report(rows), dir.file("r.csv"));
  const std::vector<std::string> text = lines(readText(dir.file("r.csv")));
  ASSERT_EQ(text.size(), 6u);
  EXPECT_EQ(text[0], kCsvHeader);
  for (const std::string& line : text) EXPECT_EQ(csvFields(line).size(), csvFields(text[0]).size()) << line;
  EXPECT_EQ(csvField(csvFields(text[0]), csvFields(text[4]), "method"), "volume");
}

TEST(AccuracyReport, CsvNumbersReadBackExactly) {
  TempFolder dir;
  std::vector<LevelAccuracy> rows = run("alps.tif", "degree", 2);
  rows[1].rmse = 1.0 / 3.0;  // needs 16 digits; %.10g would lose it
  rows[1].variables[0].correlation = 0.999991234567891;
  rows[1].maxErrorY = 5123456.789012345;
  writeAccuracyReport(report(rows), dir.file("r.csv"));
  const std::vector<std::string> text = lines(readText(dir.file("r.csv")));
  const std::vector<std::string> header = csvFields(text[0]), row = csvFields(text[2]);
  EXPECT_EQ(std::strtod(csvField(header, row, "rmse_m").c_str(), nullptr), 1.0 / 3.0);
  EXPECT_EQ(std::strtod(csvField(header, row, "elevation_r").c_str(), nullptr), 0.999991234567891);
  EXPECT_EQ(std::strtod(csvField(header, row, "max_error_y").c_str(), nullptr), 5123456.789012345);
  EXPECT_EQ(csvField(header, row, "vertices"), std::to_string(rows[1].vertices));
  EXPECT_EQ(csvField(header, row, "delete_s"), "2.25");
}

TEST(AccuracyReport, CsvQuotesTextAndLeavesMissingValuesEmpty) {
  TempFolder dir;
  std::vector<LevelAccuracy> rows = run("valley, \"north\".tif", "degree", 2);
  rows[0].moransI = NAN;
  rows[1].variables.pop_back();  // no mean curvature at this level
  writeAccuracyReport(report(rows), dir.file("r.csv"));
  const std::string text = readText(dir.file("r.csv"));
  EXPECT_NE(text.find("\"valley, \"\"north\"\".tif\""), std::string::npos);
  const std::vector<std::string> all = lines(text);
  const std::vector<std::string> header = csvFields(all[0]);
  EXPECT_EQ(csvField(header, csvFields(all[1]), "dem"), "valley, \"north\".tif");
  EXPECT_EQ(csvField(header, csvFields(all[1]), "morans_i"), "");
  EXPECT_EQ(csvField(header, csvFields(all[2]), "mean_curvature_r"), "");
  EXPECT_EQ(csvField(header, csvFields(all[2]), "mean_curvature_n"), "");
  EXPECT_EQ(text.find("nan"), std::string::npos);
}

TEST(AccuracyReport, JsonGroupsInterleavedRowsIntoRuns) {
  TempFolder dir;
  const std::vector<LevelAccuracy> a = run("alps.tif", "degree", 3), b = run("alps.tif", "volume", 2);
  writeAccuracyReport(report({a[0], b[0], a[1], b[1], a[2]}), dir.file("r.json"));
  const std::string json = readText(dir.file("r.json"));
  EXPECT_TRUE(JsonChecker(json).valid()) << json;
  EXPECT_EQ(occurrences(json, "\"dem\":"), 2u);
  const std::size_t degree = json.find("\"method\": \"degree\""), volume = json.find("\"method\": \"volume\"");
  ASSERT_NE(degree, std::string::npos);
  ASSERT_NE(volume, std::string::npos);
  ASSERT_LT(degree, volume);
  const std::string first = json.substr(degree, volume - degree), second = json.substr(volume);
  EXPECT_EQ(occurrences(first, "\"level\":"), 3u);
  EXPECT_NE(first.find("\"level\": 2"), std::string::npos);
  EXPECT_EQ(occurrences(second, "\"level\":"), 2u);
  for (const char* key : {"\"title\": \"Accuracy test\"", "\"reference\": \"tin\"", "\"step\": 1",
                          "\"control_spacing\": 3", "\"delete_pct\": 20", "\"mean_curvature\": {", "\"n\": 9000"})
    EXPECT_NE(json.find(key), std::string::npos) << key;
}

TEST(AccuracyReport, JsonWritesNullForNanAndEscapesText) {
  TempFolder dir;
  std::vector<LevelAccuracy> rows = run("say \"hi\"\\\n\t\x01.tif", "degree", 2);
  rows[1].moransI = NAN;
  rows[1].variables[1].correlation = NAN;
  rows[1].rmse = INFINITY;
  writeAccuracyReport(report(rows), dir.file("r.json"));
  const std::string json = readText(dir.file("r.json"));
  EXPECT_TRUE(JsonChecker(json).valid()) << json;
  EXPECT_NE(json.find("\"morans_i\": null"), std::string::npos);
  EXPECT_NE(json.find("\"r\": null"), std::string::npos);
  EXPECT_NE(json.find("\"rmse_m\": null"), std::string::npos);
  EXPECT_NE(json.find(R"("dem": "say \"hi\"\\\n\t\u0001.tif")"), std::string::npos) << json;
  EXPECT_EQ(json.find("nan"), std::string::npos);
  EXPECT_EQ(json.find("inf"), std::string::npos);
}

TEST(AccuracyReport, HtmlHasOneSvgPerPlotWithTheRunsInTheLegend) {
  TempFolder dir;
  std::vector<LevelAccuracy> rows = run("alps.tif", "degree", 10);
  const std::vector<LevelAccuracy> more = run("alps.tif", "volume", 10);
  rows.insert(rows.end(), more.begin(), more.end());
  writeAccuracyReport(report(rows), dir.file("r.html"));
  const std::string html = readText(dir.file("r.html"));
  const std::vector<std::string> svgs = svgElements(html);
  ASSERT_EQ(svgs.size(), 4u);
  EXPECT_EQ(occurrences(html, "</svg>"), 4u);
  for (const std::string& svg : svgs) {
    EXPECT_NE(svg.find(">degree</text>"), std::string::npos);
    EXPECT_NE(svg.find(">volume</text>"), std::string::npos);
    EXPECT_NE(svg.find("<polyline"), std::string::npos);
  }
  EXPECT_NE(svgs[0].find("log10(1 - r)"), std::string::npos);
  EXPECT_NE(svgs[0].find("lower is better"), std::string::npos);
  EXPECT_NE(html.find("alps.tif, degree, delete 20 %, stop 5 %"), std::string::npos);  // the table's heading
}

TEST(AccuracyReport, TheReferenceAgainstItselfIsNotPlottedAtTheRoundingOfR) {
  std::vector<LevelAccuracy> rows = run("alps.tif", "degree", 5);
  rows[0].variables[0].correlation = 0.9999999999999999;  // level 0 against itself, as sums round it
  const std::vector<ReportPlot> plots = reportPlots(groupRuns(rows));
  ASSERT_FALSE(plots.empty());
  ASSERT_EQ(plots[0].plot.lines.size(), 1u);
  const std::vector<PlotPoint>& points = plots[0].plot.lines[0].points;
  // Levels 1 to 4 alone; level 0 would have been at -16.
  ASSERT_EQ(points.size(), 4u) << "first point at " << points[0].y;
  for (std::size_t i = 0; i < points.size(); ++i) EXPECT_NEAR(points[i].y, -5 + 0.3 * double(i + 1), 1e-6);
}

// The level tables may be wider than any cap on the page: nothing holds the page narrower
// than the window (a cap of 1420 px cut them).
TEST(AccuracyReport, HtmlPageTakesTheWindowsWidth) {
  TempFolder dir;
  writeAccuracyReport(report(run("alps.tif", "degree", 4)), dir.file("w.html"));
  const std::string html = readText(dir.file("w.html"));
  const std::string style = html.substr(0, html.find("</style>"));
  EXPECT_EQ(style.find("main{max-width"), std::string::npos);
  EXPECT_EQ(std::regex_search(style, std::regex(R"((main|body|section|\.card|\.scroll)\{[^}]*max-width)")), false);
  EXPECT_NE(html.find("<div class=\"scroll\"><table>"), std::string::npos);  // and scrolls where the window is narrower
}

TEST(AccuracyReport, HtmlEscapesTextAndNeedsNothingFromElsewhere) {
  TempFolder dir;
  AccuracyReport r = report(run("a<b & c>.tif", "degree", 3));
  r.title = "<script>alert(1)</script>";
  writeAccuracyReport(r, dir.file("r.html"));
  const std::string html = readText(dir.file("r.html"));
  EXPECT_NE(html.find("a&lt;b &amp; c&gt;.tif"), std::string::npos);
  EXPECT_EQ(html.find("a<b"), std::string::npos);
  EXPECT_NE(html.find("&lt;script&gt;alert(1)"), std::string::npos);
  for (const char* outside : {"<script", "http", "src=", "href", "url(", "@import", "<link", "<img", "<iframe"})
    EXPECT_EQ(html.find(outside), std::string::npos) << outside;
}

TEST(AccuracyReport, HtmlVertexAxisIsLogarithmicOnlyWhenWide) {
  TempFolder dir;
  writeAccuracyReport(report(run("alps.tif", "degree", 10)), dir.file("wide.html"));  // 650k to 26k
  const std::string wide = readText(dir.file("wide.html"));
  EXPECT_NE(wide.find("Vertices (log scale)"), std::string::npos);
  for (const char* tick : {">50k<", ">100k<", ">200k<", ">500k<"})
    EXPECT_NE(wide.find(tick), std::string::npos) << tick;
  EXPECT_NE(wide.find(">0.999<"), std::string::npos);                                  // r beside log10(1 - r) = -3
  writeAccuracyReport(report(run("alps.tif", "degree", 3)), dir.file("narrow.html"));  // 650k to 318k
  EXPECT_EQ(readText(dir.file("narrow.html")).find("(log scale)"), std::string::npos);
}

TEST(AccuracyReport, HtmlCopesWithEmptyReportsAndSingleLevels) {
  TempFolder dir;
  writeAccuracyReport(report({}), dir.file("empty.html"));
  const std::string empty = readText(dir.file("empty.html"));
  EXPECT_EQ(empty.find("<svg"), std::string::npos);
  EXPECT_NE(empty.find("no levels"), std::string::npos);
  EXPECT_NE(empty.find("</html>"), std::string::npos);

  std::vector<LevelAccuracy> rows = run("alps.tif", "degree", 1);
  rows[0].variables[0].correlation = 1;  // the reference itself: log10(0) must not be drawn
  rows[0].variables[1].correlation = NAN;
  writeAccuracyReport(report(rows), dir.file("one.html"));
  const std::string one = readText(dir.file("one.html"));
  EXPECT_EQ(svgElements(one).size(), 4u);
  EXPECT_GE(occurrences(one, "Nothing to plot"), 3u);  // both r plots, and level 0 has no times
  static const std::regex badNumber("=\"[^\"]*(nan|inf)", std::regex::icase);
  EXPECT_FALSE(std::regex_search(one, badNumber));
}

TEST(AccuracyReport, UnknownExtensionIsRefusedAndWritesNothing) {
  TempFolder dir;
  for (const char* name : {"r.txt", "r"}) {
    try {
      writeAccuracyReport(report(run("alps.tif", "degree", 2)), dir.file(name));
      ADD_FAILURE() << "no error for " << name;
    } catch (const Error& e) {
      const std::string message = e.what();
      for (const char* ext : {".csv", ".json", ".html"}) EXPECT_NE(message.find(ext), std::string::npos) << message;
    }
  }
  EXPECT_TRUE(dir.names().empty());
}

TEST(AccuracyReport, MissingFolderIsSaidPlainly) {
  TempFolder dir;
  try {
    writeAccuracyReport(report({}), dir.file("no/such/r.csv"));
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("folder"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(dir.names().empty());
}

TEST(AccuracyReport, ReplacesAnExistingFileAtomically) {
  TempFolder dir;
  const std::string path = dir.file("r.csv");
  std::ofstream(path) << "old report\n";
  std::ifstream reader(path);  // a reader of the old file must keep seeing it whole
  writeAccuracyReport(report(run("alps.tif", "degree", 2)), path);
  std::string old;
  std::getline(reader, old);
  EXPECT_EQ(old, "old report");
  EXPECT_EQ(readText(path).rfind(std::string(kCsvHeader) + "\n", 0), 0u);
  EXPECT_EQ(dir.names(), std::vector<std::string>{"r.csv"});  // no temporary sibling left
}

// Levels compared with greedy insertion at their sizes, and the insertion's own rows.
std::vector<LevelAccuracy> comparedWithInsertion() {
  std::vector<LevelAccuracy> rows = run("alps.tif", "volume", 3);
  std::vector<LevelAccuracy> inserted = run("alps.tif", "insert", 3);
  inserted.erase(inserted.begin());  // insertion has no level 0
  for (std::size_t k = 0; k < inserted.size(); ++k) {
    inserted[k].deletePct = NAN;
    inserted[k].rmse = 0.5 + k;
    rows[k + 1].insertRmse = inserted[k].rmse;
    rows[k + 1].insertRatio = rows[k + 1].rmse / inserted[k].rmse;
  }
  rows.insert(rows.end(), inserted.begin(), inserted.end());
  return rows;
}

TEST(AccuracyReport, CsvHasTheInsertRmseAndRatioWhereKnown) {
  TempFolder dir;
  const std::vector<LevelAccuracy> rows = comparedWithInsertion();
  writeAccuracyReport(report(rows), dir.file("r.csv"));
  const std::vector<std::string> text = lines(readText(dir.file("r.csv")));
  ASSERT_EQ(text.size(), rows.size() + 1);
  const std::vector<std::string> header = csvFields(text[0]);
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const std::vector<std::string> row = csvFields(text[k + 1]);
    ASSERT_EQ(row.size(), header.size());
    if (std::isnan(rows[k].insertRatio)) {
      EXPECT_EQ(csvField(header, row, "insert_rmse_m"), "") << k;
      EXPECT_EQ(csvField(header, row, "rmse_ratio_to_insert"), "") << k;
      continue;
    }
    EXPECT_EQ(std::strtod(csvField(header, row, "insert_rmse_m").c_str(), nullptr), rows[k].insertRmse);
    EXPECT_EQ(std::strtod(csvField(header, row, "rmse_ratio_to_insert").c_str(), nullptr), rows[k].insertRatio);
  }
  // Greedy insertion deletes nothing: its delete percentage is missing, not 0.
  EXPECT_EQ(csvField(header, csvFields(text.back()), "method"), "insert");
  EXPECT_EQ(csvField(header, csvFields(text.back()), "delete_pct"), "");
}

TEST(AccuracyReport, JsonHasTheInsertRmseAndRatioOrNull) {
  TempFolder dir;
  writeAccuracyReport(report(comparedWithInsertion()), dir.file("r.json"));
  const std::string json = readText(dir.file("r.json"));
  EXPECT_TRUE(JsonChecker(json).valid()) << json;
  EXPECT_EQ(occurrences(json, "\"rmse_ratio_to_insert\": "), 5u);  // every level of both runs
  EXPECT_EQ(occurrences(json, "\"insert_rmse_m\": "), 5u);
  EXPECT_NE(json.find("\"rmse_ratio_to_insert\": 2.2"), std::string::npos) << json;  // level 1: 1.1 / 0.5
  EXPECT_NE(json.find("\"insert_rmse_m\": 1.5"), std::string::npos);
  EXPECT_EQ(occurrences(json, "\"rmse_ratio_to_insert\": null"), 3u);  // level 0 and the insertion's rows
  EXPECT_NE(json.find("\"delete_pct\": null"), std::string::npos);
}

TEST(AccuracyReport, HtmlShowsTheRatioColumnAndPlotOnlyWhenKnown) {
  TempFolder dir;
  writeAccuracyReport(report(comparedWithInsertion()), dir.file("with.html"));
  const std::string with = readText(dir.file("with.html"));
  EXPECT_EQ(occurrences(with, ">RMSE / insert</th>"), 2u);  // in both runs' tables
  EXPECT_EQ(svgElements(with).size(), 5u);
  EXPECT_NE(with.find("RMSE / insert RMSE"), std::string::npos);
  EXPECT_NE(with.find("<td>2.20</td>"), std::string::npos);  // level 1's ratio
  EXPECT_NE(with.find("alps.tif, insert, stop 5 %"), std::string::npos);  // no delete percentage in its name
  writeAccuracyReport(report(run("alps.tif", "volume", 3)), dir.file("without.html"));
  const std::string without = readText(dir.file("without.html"));
  EXPECT_EQ(without.find("RMSE / insert"), std::string::npos);
  EXPECT_EQ(svgElements(without).size(), 4u);
}

TEST(AccuracyReport, KnowsItsExtensionsInAnyCase) {
  for (const char* yes : {"a.csv", "a.CSV", "dir.x/a.Json", "a.html", "a.HTM"})
    EXPECT_TRUE(isAccuracyReportPath(yes)) << yes;
  for (const char* no : {"a.txt", "a", "a.csv.gz", "csv", "a.gpkg"}) EXPECT_FALSE(isAccuracyReportPath(no)) << no;
}

}  // namespace
}  // namespace tinlod
