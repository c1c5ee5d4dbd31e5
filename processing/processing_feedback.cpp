// SPDX-License-Identifier: GPL-3.0-or-later
#include "processing_feedback.h"

#include <QRegularExpression>

#include <qgsapplication.h>
#include <qgsprocessingutils.h>

#include <memory>

#include "tinlod/stop_signals.h"

namespace tinlod::qgis {

namespace {

// qgis_process leaves Ctrl-C to Python's handler, which only notes it while C++ runs: the
// run went on and replaced its outputs. While a tinlod job's feedback lives, the job's own
// handlers stop it as on the command line. The QGIS desktop has its Cancel button.
std::shared_ptr<void> stopSignalsWhileRunning() {
  if (QgsApplication::platform() != QLatin1String("qgis_process")) return nullptr;
  catchStopSignals();
  return std::shared_ptr<void>(nullptr, [](void*) { releaseStopSignals(); });
}

// The fixes the core's messages give as commands, as a QGIS user makes them: with an
// algorithm, or in QGIS itself. tinlod tiles has no algorithm: it stays a command.
const ParameterNames& desktopTerms() {
  static const ParameterNames terms{
      {QStringLiteral("tinlod build"), QStringLiteral("Build TIN hierarchy from DEM")},
      {QStringLiteral("tinlod sample"), QStringLiteral("Sample TIN from DEM")},
      {QStringLiteral("(of tinlod lines or locate)"),
       QStringLiteral("(of Douglas-Peucker simplification values, Polyline concavity or TIN elevation at points)")},
      {QStringLiteral("its layers and metadata are shown by ogrinfo -so, and it opens in QGIS as it is"),
       QStringLiteral("add it to the map as it is (Layer > Add Layer > Add Vector Layer)")},
      {QStringLiteral("-overwrite replaces the layers of the same kind"),
       QStringLiteral("writing into an existing GeoPackage replaces the layers of the same kind")},
      // The DEM's CRS is the layer's (DemAlgorithm passes a CRS assigned in QGIS on).
      {QStringLiteral("name its CRS with -s_srs EPSG:4326 (QGIS: assign the layer's CRS)"),
       QStringLiteral("assign the layer's CRS, EPSG:4326 (Layer Properties > Source)")},
      {QStringLiteral("name its CRS with -s_srs, e.g. -s_srs EPSG:4326 (QGIS: assign the layer's CRS)"),
       QStringLiteral("assign the layer's CRS (Layer Properties > Source), e.g. EPSG:4326")},
      {QStringLiteral("CRS with -s_srs (e.g. -s_srs EPSG:4326 for degrees; QGIS: assign the layer's CRS), or a projected one with -t_srs"),
       QStringLiteral("CRS: assign the layer's CRS (Layer Properties > Source; EPSG:4326 for degrees), or choose a projected TARGET_CRS")},
      {QStringLiteral("name the right one with -s_srs"), QStringLiteral("assign the right one to the layer (Layer Properties > Source)")},
      {QStringLiteral("leave -s_srs out to use the DEM's own CRS"),
       QStringLiteral("assign the layer the CRS of its file (Layer Properties > Source)")},
      // -t_srs is TARGET_CRS by now: the warp is QGIS's.
      {QStringLiteral("(gdalwarp TARGET_CRS)"), QStringLiteral("(Raster > Projections > Warp (Reproject))")},
      {QStringLiteral("cut it into regions (gdal_translate -projwin)"),
       QStringLiteral("cut it into regions (Raster > Extraction > Clip Raster by Extent)")},
      {QStringLiteral("-s_srs "), QStringLiteral("the layer's CRS ")},
      {QStringLiteral("target CRS "), QStringLiteral("TARGET_CRS ")}};
  return terms;
}

}  // namespace

Feedback processingFeedback(QgsProcessingFeedback* feedback, const ParameterNames& names) {
  Feedback out;
  if (!feedback) return out;
  auto lastPhase = std::make_shared<std::string>();
  out.progress = [feedback, lastPhase, stopGuard = stopSignalsWhileRunning()](double fraction, const std::string& phase) {
    if (stopRequested()) feedback->cancel();
    if (phase != *lastPhase) {
      feedback->setProgressText(QString::fromStdString(phase));
      *lastPhase = phase;
    }
    feedback->setProgress(100.0 * fraction);
    return !feedback->isCanceled();
  };
  out.warning = [feedback, names](const std::string& m) {
    feedback->pushWarning(withParameterNames(QString::fromStdString(m), names));
  };
  // Notes name options too ("-block 1 samples every cell"): the dialog's names, as in warnings.
  out.info = [feedback, names](const std::string& m) {
    feedback->pushInfo(withParameterNames(QString::fromStdString(m), names));
  };
  return out;
}

QString withParameterNames(const QString& message, const ParameterNames& names) {
  QString out = message;
  static const QRegularExpression named(QStringLiteral("^[A-Z_]+: "));
  // The core calls the file it writes "output": every algorithm that has one names it OUTPUT.
  static const QRegularExpression output(QStringLiteral("^output:? '"));
  out.replace(output, QStringLiteral("OUTPUT: '"));
  static const QRegularExpression outputFolder(QStringLiteral("^the folder of output '"));
  out.replace(outputFolder, QStringLiteral("OUTPUT: the folder of '"));
  for (const auto& [option, parameter] : names) {
    if (option.startsWith(kFileOf)) {
      if (!named.match(out).hasMatch() && out.contains(QLatin1Char('\'') + option.mid(kFileOf.size()) + QLatin1Char('\'')))
        out.prepend(parameter + QStringLiteral(": "));
    } else if (option.endsWith(QLatin1Char(':'))) {
      out.replace(QRegularExpression(QLatin1Char('^') + QRegularExpression::escape(option)), parameter + QLatin1Char(':'));
    } else {
      out.replace(QRegularExpression(QStringLiteral("(^|[\\s'(])") + QRegularExpression::escape(option) + QStringLiteral("\\b")),
                  QStringLiteral("\\1") + parameter);
    }
  }
  // A layer QGIS wrote to a file for the run (sourceFile) is named after its parameter there.
  out.replace(QRegularExpression(QLatin1Char('\'') + QRegularExpression::escape(QgsProcessingUtils::tempFolder()) +
                                 QStringLiteral("/[^']*/([A-Z_]+)\\.gpkg(\\|layername=[^']*)?'")),
              QStringLiteral("\\1"));
  for (const auto& [command, desktop] : desktopTerms()) out.replace(command, desktop);
  return out;
}

}  // namespace tinlod::qgis
