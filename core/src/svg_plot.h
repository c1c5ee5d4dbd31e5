// SPDX-License-Identifier: GPL-3.0-or-later
// Private: line plots as inline SVG, written by hand so that a report page needs no
// script, font or image from anywhere (it opens offline and in QGIS's browser).
#pragma once

#include <string>
#include <vector>

#include "plot_scale.h"

namespace tinlod {

// Text for HTML and SVG, safe in element content and in quoted attributes alike.
std::string escapeMarkup(const std::string& text);

// The colour of run `run`: the Okabe-Ito palette, which stays distinguishable with the
// common colour-vision deficiencies; after eight runs the colours repeat.
std::string runColour(int run);

struct PlotPoint {
  double x = 0, y = 0;
  std::string note;  // the marker's tooltip
};

// One quantity of one run. Colour and marker shape follow the run; a run's second
// quantity (max error beside RMSE) is dashed with hollow markers.
struct PlotLine {
  int run = 0;
  bool dashed = false;
  std::vector<PlotPoint> points;  // drawn in this order; NaN or, on a log axis, values <= 0 are left out
};

enum class TickStyle { Plain, Count };  // Count: 50k, 1M, for numbers of vertices

struct PlotAxis {
  std::string label;
  TickStyle ticks = TickStyle::Plain;
  AxisKind kind = AxisKind::Auto;  // Auto: logarithmic when the values span more than a factor of 20
  bool fromZero = false;           // a linear axis of magnitudes (metres, seconds) starts at 0
};

struct LinePlot {
  std::string title, subtitle;
  std::string note;  // top right, e.g. "lower is better"
  PlotAxis x, y;
  std::vector<PlotLine> lines;
  std::vector<std::string> runLabels;  // the legend: run i's colour and marker, and its name
  std::string solidKey, dashedKey;     // the legend for line styles, when runs have two quantities
  bool yIsLogOneMinusR = false;        // y is log10(1 - r): the right side says which r each tick is
};

// A complete <svg> element (no XML declaration), with its title for screen readers.
std::string renderSvg(const LinePlot& plot);

}  // namespace tinlod
