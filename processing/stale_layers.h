// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

class QgsMapLayer;
class QgsProject;

namespace tinlod::qgis {

// A run written over a GeoPackage already on the map may leave it without tables an earlier
// run loaded: fewer levels, other level views, another kind of TIN. Their layers would stay
// in the project as broken layers ("level_5" of a file with 3 levels). This removes the
// layers a run loaded (not the user's own) from `layer`'s file whose table the file no longer
// has. If one of them was shown, the coarsest level of the file still on the map is shown
// instead, so that a level shows, as after a first run.
void removeLayersOfTablesGone(QgsMapLayer* layer, QgsProject* project);

}  // namespace tinlod::qgis
