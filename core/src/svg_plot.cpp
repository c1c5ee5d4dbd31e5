// SPDX-License-Identifier: GPL-3.0-or-later
#include "svg_plot.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <utility>

#include "number_text.h"

namespace tinlod {
namespace {

// The layout in SVG pixels; the page scales the whole drawing to its column.
constexpr double kWidth = 640, kLeft = 64, kPlotHeight = 280;
constexpr double kLegendGap = 60;  // from the bottom of the frame to the first legend row: tick labels, axis label
constexpr double kRow = 18;        // a legend row
// Okabe-Ito, yellow last: it is faint on white.
const char* const kPalette[] = {"#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9", "#000000", "#F0E442"};
const char* const kMuted = "#57606a";
const char* const kGrid = "#e3e6ea";
const char* const kFont = "system-ui,-apple-system,'Segoe UI',Roboto,'Helvetica Neue',Arial,sans-serif";

// Pixels, to a tenth: enough for any screen, and short.
std::string px(double value) { return fixedNumber(value, 1); }

// The plotting area, and the scales that map values into it.
struct Frame {
  double left = kLeft, right = 0, top = 0, bottom = 0;
  AxisScale x, y;
};

std::string typographicMinus(std::string text) {
  if (!text.empty() && text[0] == '-') text.replace(0, 1, "\u2212");
  return text;
}

std::string tickLabel(double value, TickStyle style) {
  if (style == TickStyle::Count && std::fabs(value) >= 1e6) return significantNumber(value / 1e6, 3) + "M";
  if (style == TickStyle::Count && std::fabs(value) >= 1e3) return significantNumber(value / 1e3, 3) + "k";
  return typographicMinus(significantNumber(value, 6));
}

// The r whose log10(1 - r) is `tick`, with digits enough to tell neighbouring ticks
// apart: -5 -> 0.99999, -2.5 -> 0.9968.
std::string rAtTick(double tick) {
  const int digits = std::clamp(static_cast<int>(std::ceil(-tick)) + 1, 2, 12);
  return typographicMinus(significantNumber(1 - std::pow(10.0, tick), digits));
}

// Cut to `limit` bytes without splitting a UTF-8 character; "…" marks the cut.
std::string shortened(const std::string& text, std::size_t limit) {
  if (text.size() <= limit) return text;
  std::size_t cut = limit - 1;
  while (cut > 0 && (static_cast<unsigned char>(text[cut]) & 0xC0) == 0x80) --cut;
  return text.substr(0, cut) + "\u2026";
}

std::string text(double x, double y, const std::string& content, const std::string& attributes = "") {
  return "<text x=\"" + px(x) + "\" y=\"" + px(y) + "\"" + attributes + ">" + escapeMarkup(content) + "</text>\n";
}

std::string line(double x1, double y1, double x2, double y2, const std::string& attributes) {
  return "<line x1=\"" + px(x1) + "\" y1=\"" + px(y1) + "\" x2=\"" + px(x2) + "\" y2=\"" + px(y2) + "\"" + attributes +
         "/>\n";
}

// A marker shape per run (circle, square, triangle, diamond), shifted after each round
// of the palette so run 8 does not look like run 0; hollow for a run's second quantity.
std::string marker(int run, double cx, double cy, bool hollow, const std::string& note) {
  const std::string colour = runColour(run);
  const std::string paint = " fill=\"" + (hollow ? std::string("#fff") : colour) + "\" stroke=\"" + colour +
                            "\" stroke-width=\"1.5\"><title>" + escapeMarkup(note) + "</title>";
  const std::string x = px(cx), y = px(cy);
  switch ((run + run / 8) % 4) {
    case 0:
      return "<circle cx=\"" + x + "\" cy=\"" + y + "\" r=\"4\"" + paint + "</circle>";
    case 1:
      return "<rect x=\"" + px(cx - 3.5) + "\" y=\"" + px(cy - 3.5) + "\" width=\"7\" height=\"7\"" + paint + "</rect>";
    case 2:
      return "<path d=\"M" + x + " " + px(cy - 5) + "L" + px(cx + 4.5) + " " + px(cy + 3.5) + "L" + px(cx - 4.5) + " " +
             px(cy + 3.5) + "Z\"" + paint + "</path>";
    default:
      return "<path d=\"M" + x + " " + px(cy - 5) + "L" + px(cx + 5) + " " + y + "L" + x + " " + px(cy + 5) + "L" +
             px(cx - 5) + " " + y + "Z\"" + paint + "</path>";
  }
}

std::string dash(bool dashed) { return dashed ? " stroke-dasharray=\"6 4\"" : ""; }

std::string drawLine(const PlotLine& l, const Frame& f) {
  std::string points, markers;
  for (const PlotPoint& p : l.points) {
    if (!f.x.plottable(p.x) || !f.y.plottable(p.y)) continue;
    points += (points.empty() ? "" : " ") + px(f.x.pixel(p.x)) + "," + px(f.y.pixel(p.y));
    markers += marker(l.run, f.x.pixel(p.x), f.y.pixel(p.y), l.dashed, p.note) + "\n";
  }
  if (points.empty()) return {};
  return "<polyline points=\"" + points + "\" fill=\"none\" stroke=\"" + runColour(l.run) +
         "\" stroke-width=\"2\" stroke-linejoin=\"round\"" + dash(l.dashed) + "/>\n" + markers;
}

bool anyPlottable(const LinePlot& plot, const Frame& f) {
  for (const PlotLine& l : plot.lines)
    for (const PlotPoint& p : l.points)
      if (f.x.plottable(p.x) && f.y.plottable(p.y)) return true;
  return false;
}

std::string yAxis(const LinePlot& plot, const Frame& f) {
  std::string out;
  for (double tick : f.y.ticks) {
    const double y = f.y.pixel(tick);
    out += line(f.left, y, f.right, y, " stroke=\"" + std::string(kGrid) + "\"");
    out += text(f.left - 6, y, tickLabel(tick, plot.y.ticks), " dy=\"0.32em\" text-anchor=\"end\"");
    if (plot.yIsLogOneMinusR)
      out += text(f.right + 6, y, rAtTick(tick), " dy=\"0.32em\" fill=\"" + std::string(kMuted) + "\"");
  }
  if (plot.yIsLogOneMinusR)
    out += text(f.right + 6, f.top - 8, "r", " font-style=\"italic\" fill=\"" + std::string(kMuted) + "\"");
  const double middle = (f.top + f.bottom) / 2;
  return out +
         text(0, 0, plot.y.label, " transform=\"translate(16," + px(middle) + ") rotate(-90)\" text-anchor=\"middle\"");
}

std::string xAxis(const LinePlot& plot, const Frame& f) {
  std::string out;
  for (double tick : f.x.ticks) {
    const double x = f.x.pixel(tick);
    out += line(x, f.top, x, f.bottom, " stroke=\"" + std::string(kGrid) + "\"");
    out += text(x, f.bottom + 16, tickLabel(tick, plot.x.ticks), " text-anchor=\"middle\"");
  }
  const std::string label = plot.x.label + (f.x.log ? " (log scale)" : "");
  return out + text((f.left + f.right) / 2, f.bottom + 36, label, " text-anchor=\"middle\"");
}

// Two columns when every run's label fits in half the width, so short legends stay short.
int legendColumns(const LinePlot& plot) {
  const bool allShort =
      std::all_of(plot.runLabels.begin(), plot.runLabels.end(), [](const std::string& l) { return l.size() <= 36; });
  return allShort && plot.runLabels.size() > 1 ? 2 : 1;
}

int legendRows(const LinePlot& plot) {
  const int columns = legendColumns(plot);
  const int runs = static_cast<int>(plot.runLabels.size());
  return (runs + columns - 1) / columns + (plot.solidKey.empty() ? 0 : 1);
}

// A run's colour, marker and label; `run` -1 is a key to the line styles, in grey.
std::string legendEntry(double x, double y, int run, bool dashed, const std::string& label, std::size_t limit) {
  const std::string colour = run < 0 ? kMuted : runColour(run);
  std::string out = line(x, y, x + 28, y, " stroke=\"" + colour + "\" stroke-width=\"2\"" + dash(dashed));
  if (run >= 0) out += marker(run, x + 14, y, false, label) + "\n";
  return out + text(x + 36, y, shortened(label, limit), " dy=\"0.32em\"");
}

std::string legend(const LinePlot& plot, const Frame& f) {
  std::string out;
  double y = f.bottom + kLegendGap;
  if (!plot.solidKey.empty()) {
    out += legendEntry(f.left, y, -1, false, plot.solidKey, 40);
    out += legendEntry(f.left + (f.right - f.left) / 2, y, -1, true, plot.dashedKey, 40);
    y += kRow;
  }
  const int columns = legendColumns(plot);
  const double columnWidth = (f.right - f.left) / columns;
  for (std::size_t i = 0; i < plot.runLabels.size(); ++i) {
    const double x = f.left + columnWidth * static_cast<double>(i % columns);
    out += legendEntry(x, y + kRow * static_cast<double>(i / columns), static_cast<int>(i), false, plot.runLabels[i],
                       columns == 2 ? 40 : 76);
  }
  return out;
}

Frame frameFor(const LinePlot& plot) {
  Frame f;
  f.right = kWidth - (plot.yIsLogOneMinusR ? 72 : 24);
  f.top = plot.subtitle.empty() ? 44 : 60;
  f.bottom = f.top + kPlotHeight;
  std::vector<double> xs, ys;
  for (const PlotLine& l : plot.lines)
    for (const PlotPoint& p : l.points) {
      xs.push_back(p.x);
      ys.push_back(p.y);
    }
  f.x = makeScale(xs, plot.x.kind, plot.x.fromZero, f.left, f.right);
  f.y = makeScale(ys, plot.y.kind, plot.y.fromZero, f.bottom, f.top);
  return f;
}

std::string heading(const LinePlot& plot, const Frame& f) {
  std::string out = text(f.left, 20, plot.title, " font-size=\"15\" font-weight=\"600\"");
  if (!plot.subtitle.empty()) out += text(f.left, 38, plot.subtitle, " fill=\"" + std::string(kMuted) + "\"");
  if (!plot.note.empty())
    out += text(kWidth - 8, 20, plot.note,
                " text-anchor=\"end\" font-style=\"italic\" fill=\"" + std::string(kMuted) + "\"");
  return out;
}

// Without a point to show, ticks would label a made-up range: the frame says so instead.
std::string body(const LinePlot& plot, const Frame& f) {
  const std::string frame = "<rect x=\"" + px(f.left) + "\" y=\"" + px(f.top) + "\" width=\"" + px(f.right - f.left) +
                            "\" height=\"" + px(f.bottom - f.top) + "\" fill=\"none\" stroke=\"#8c959f\"/>\n";
  if (!anyPlottable(plot, f))
    return frame + text((f.left + f.right) / 2, (f.top + f.bottom) / 2, "Nothing to plot",
                        " text-anchor=\"middle\" fill=\"" + std::string(kMuted) + "\"");
  std::string out = yAxis(plot, f) + xAxis(plot, f) + frame;
  for (const PlotLine& l : plot.lines) out += drawLine(l, f);
  return out;
}

}  // namespace

std::string escapeMarkup(const std::string& text) {
  static const std::pair<char, const char*> kEntities[] = {
      {'&', "&amp;"}, {'<', "&lt;"}, {'>', "&gt;"}, {'"', "&quot;"}, {'\'', "&#39;"}};
  std::string out;
  for (char c : text) {
    const auto* e =
        std::find_if(std::begin(kEntities), std::end(kEntities), [c](const auto& p) { return p.first == c; });
    out += e == std::end(kEntities) ? std::string(1, c) : std::string(e->second);
  }
  return out;
}

std::string runColour(int run) { return kPalette[run % 8]; }

std::string renderSvg(const LinePlot& plot) {
  const Frame f = frameFor(plot);
  const double height = f.bottom + kLegendGap + kRow * legendRows(plot);
  std::string out = "<svg viewBox=\"0 0 " + px(kWidth) + " " + px(height) + "\" width=\"" + px(kWidth) +
                    "\" height=\"" + px(height) + "\" role=\"img\" font-family=\"" + kFont +
                    "\" font-size=\"12\" fill=\"#24292f\">\n<title>" + escapeMarkup(plot.title) + "</title>\n";
  out += "<rect width=\"100%\" height=\"100%\" fill=\"#fff\"/>\n";
  return out + heading(plot, f) + body(plot, f) + legend(plot, f) + "</svg>\n";
}

}  // namespace tinlod
