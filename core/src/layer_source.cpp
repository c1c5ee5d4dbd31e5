// SPDX-License-Identifier: GPL-3.0-or-later
#include "layer_source.h"

#include <algorithm>
#include <cctype>
#include <string>

#include "text_and_paths.h"
#include "tinlod/error.h"

namespace tinlod {

namespace {

// QGIS's layerid=N: digits only ("abc" and "" were read as the first layer).
int layerId(const std::string& text, const std::string& spec, const std::string& what) {
  if (text.empty() || text.size() > 6 || !std::all_of(text.begin(), text.end(), [](unsigned char c) { return std::isdigit(c); }))
    throw Error(what + ": '" + spec + "': layerid must be a layer's number, 0 for the first");
  return std::stoi(text);
}

}  // namespace

LayerSource parseLayerSource(const std::string& spec, const std::string& what) {
  LayerSource s;
  std::size_t bar = spec.find('|');
  s.path = spec.substr(0, bar);
  while (bar != std::string::npos) {
    const std::size_t next = spec.find('|', bar + 1);
    const std::string part = spec.substr(bar + 1, next == std::string::npos ? std::string::npos : next - bar - 1);
    if (part.rfind("layername=", 0) == 0)
      s.layer = part.substr(10);
    else if (part.rfind("layerid=", 0) == 0)
      s.layerIndex = layerId(part.substr(8), spec, what);
    else if (part.rfind("geometrytype=", 0) != 0)  // QGIS names the type of a layer it split: same features
      throw Error(what + ": '" + spec + "' has a filter or option tinlod cannot apply (" + part +
                  "): save the features as a file of their own first");
    bar = next;
  }
  return s;
}

OpenLayer openLayer(const std::string& spec, const std::string& what) {
  const LayerSource source = parseLayerSource(spec, what);
  if (plainPathMissing(source.path)) throw Error(what + ": '" + source.path + "' does not exist" + tildeHint(source.path));
  OpenLayer out;
  out.path = source.path;
  out.dataset = openReadOnly(source.path, GDAL_OF_VECTOR);
  if (!out.dataset) throw Error(what + ": '" + source.path + "' is not a vector file GDAL can read");
  GDALDataset& ds = *out.dataset;
  out.layer = !source.layer.empty()                 ? ds.GetLayerByName(source.layer.c_str())
              : source.layerIndex < ds.GetLayerCount() ? ds.GetLayer(source.layerIndex)
                                                        : nullptr;
  if (!out.layer && ds.GetLayerCount() == 0) throw Error(what + ": '" + source.path + "' has no layer");
  if (!out.layer)
    throw Error(what + ": '" + source.path + "' has no " +
                (source.layer.empty() ? "layer of id " + std::to_string(source.layerIndex) + " (ids count from 0)"
                                      : "layer '" + source.layer + "'") +
                " (its layers: " + layerNames(ds) + ")");
  return out;
}

}  // namespace tinlod
