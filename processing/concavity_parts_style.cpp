// SPDX-License-Identifier: GPL-3.0-or-later
#include "concavity_parts_style.h"

#include <qgscategorizedsymbolrenderer.h>
#include <qgslinesymbol.h>
#include <qgsvectorlayer.h>

#include "layer_placement.h"

namespace tinlod::qgis {

void ConcavityPartsStyle::postProcessLayer(QgsMapLayer* layer, QgsProcessingContext& context, QgsProcessingFeedback*) {
  if (reloadedIfLoadedBefore(layer)) return;
  if (auto* vector = qobject_cast<QgsVectorLayer*>(layer)) {
    QgsCategoryList categories;
    // ColorBrewer RdBu's ends, as the accuracy raster's: red bulges out, blue bends in.
    for (const auto& [value, colour] : {std::pair{"convex", "202,0,32"}, {"straight", "150,150,150"}, {"concave", "5,113,176"}})
      categories << QgsRendererCategory(QString::fromUtf8(value),
                                        QgsLineSymbol::createSimple({{"line_color", colour}, {"line_width", "0.5"}}),
                                        QString::fromUtf8(value));
    vector->setRenderer(new QgsCategorizedSymbolRenderer(QStringLiteral("class"), categories));
    vector->triggerRepaint();
  }
  placeLayer(layer, context.project());
}

}  // namespace tinlod::qgis
