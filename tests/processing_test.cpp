// SPDX-License-Identifier: GPL-3.0-or-later
// The Processing algorithms in a headless QgsApplication, registered through the same
// C entry point the plugin calls.
#include <gdal_priv.h>
#include <ogr_spatialref.h>
#include <gtest/gtest.h>
#include <ogrsf_frmts.h>
#include <qgscategorizedsymbolrenderer.h>
#include <qgssinglesymbolrenderer.h>
#include <qgssymbol.h>
#include <qgsrasterlayer.h>
#include <qgssinglebandpseudocolorrenderer.h>
#include <qgsrasterdataprovider.h>
#include <qgsprocessingparameters.h>
#include <qgsapplication.h>
#include <qgsnativealgorithms.h>
#include <qgsprocessingalgorithm.h>
#include <qgsprocessingcontext.h>
#include <qgsprocessingmodelalgorithm.h>
#include <qgsprocessingfeedback.h>
#include <qgsprocessingregistry.h>
#include <qgsprocessingutils.h>
#include <qgslayertree.h>
#include <qgsproject.h>
#include <qgsvectorlayer.h>
#include <qgsgeometry.h>
#include <qgspoint.h>
#include <qgsfeatureiterator.h>
#include <qgsvectordataprovider.h>

#include <QFile>
#include <QImage>
#include <QPixmap>
#include <QSet>
#include <QUrl>
#include <QFileInfo>
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <thread>

#include "test_support.h"
#include "tinlod/dem_reader.h"
#include "tinlod/insert_job.h"
#include "tinlod/line_layers.h"
#include "tinlod/lod_job.h"
#include "tinlod/sample_job.h"
#include "tinlod/synthetic_dem.h"

extern "C" int tinlod_register_provider();
extern "C" void tinlod_unregister_provider();

namespace fs = std::filesystem;

namespace tinlod {
namespace {

std::string defaultDem() { return test::smallSyntheticDemFile(); }

// QgsProcessingAlgorithm::run catches the algorithm's exception and reports it here.
class RecordingFeedback : public QgsProcessingFeedback {
 public:
  void reportError(const QString& error, bool fatal) override {
    errors += error;
    QgsProcessingFeedback::reportError(error, fatal);
  }
  void pushInfo(const QString& info) override {
    infos += info;
    QgsProcessingFeedback::pushInfo(info);
  }
  void pushWarning(const QString& warning) override {
    warnings += warning;
    QgsProcessingFeedback::pushWarning(warning);
  }
  QString errors;
  QStringList infos;
  QStringList warnings;
};

struct Result {
  bool ok = false;
  QVariantMap outputs;
  QString error;
  std::shared_ptr<QgsProcessingContext> context;  // what the run asked QGIS to load
};

// With a project, the run sees its layers (ids as parameter values) and loads into it.
Result runAlgorithm(const QString& id, const QVariantMap& parameters, RecordingFeedback* feedback = nullptr,
                    QgsProject* project = nullptr) {
  std::unique_ptr<QgsProcessingAlgorithm> alg(QgsApplication::processingRegistry()->createAlgorithmById(id));
  EXPECT_NE(alg, nullptr) << id.toStdString();
  if (!alg) return {};
  Result r;
  r.context = std::make_shared<QgsProcessingContext>();
  QgsProcessingContext& context = *r.context;
  if (project) context.setProject(project);
  RecordingFeedback defaultFeedback;
  RecordingFeedback* f = feedback ? feedback : &defaultFeedback;
  try {
    r.outputs = alg->run(parameters, context, f, &r.ok);
  } catch (const QgsProcessingException& e) {
    r.error = e.what();
  }
  r.error += f->errors;
  return r;
}

// A hierarchy of the default DEM at `out`, its levels not loaded.
bool builtDefaultHierarchy(const QString& out) {
  return runAlgorithm(QStringLiteral("tinlod:buildhierarchy"),
                      {{"INPUT", QString::fromStdString(defaultDem())}, {"LOAD_LEVELS", false}, {"OUTPUT", out}}).ok;
}

long long featureCount(const QString& gpkg, const QString& layer) {
  QgsVectorLayer l(gpkg + "|layername=" + layer, layer, QStringLiteral("ogr"));
  return l.isValid() ? l.featureCount() : -1;
}

TEST(Processing, ProviderListsTheAlgorithm) {
  QgsProcessingProvider* provider = QgsApplication::processingRegistry()->providerById(QStringLiteral("tinlod"));
  ASSERT_NE(provider, nullptr);
  EXPECT_EQ(provider->name(), QStringLiteral("TIN hierarchy"));
  const QgsProcessingAlgorithm* alg = QgsApplication::processingRegistry()->algorithmById(QStringLiteral("tinlod:sampletin"));
  ASSERT_NE(alg, nullptr);
  EXPECT_EQ(alg->displayName(), QStringLiteral("Sample TIN from DEM"));
  EXPECT_TRUE(alg->shortHelpString().contains(QStringLiteral("geographic CRS")));
  for (const char* key : {"INPUT", "BAND", "BLOCK", "JITTER", "SEED", "TARGET_CRS", "OUTPUT"})
    EXPECT_NE(alg->parameterDefinition(QString(key)), nullptr) << key;
  EXPECT_EQ(tinlod_register_provider(), 1);  // a second call is harmless
}

// Decimal parameters say how many decimals the dialog shows (QGIS's default is six:
// "20.000000" for a percentage).
TEST(Processing, EveryDecimalParameterShowsAFewDecimals) {
  const QgsProcessingProvider* provider = QgsApplication::processingRegistry()->providerById(QStringLiteral("tinlod"));
  ASSERT_NE(provider, nullptr);
  int checked = 0;
  for (const QgsProcessingAlgorithm* alg : provider->algorithms())
    for (const QgsProcessingParameterDefinition* p : alg->parameterDefinitions()) {
      const auto* number = dynamic_cast<const QgsProcessingParameterNumber*>(p);
      if (!number || number->dataType() != QgsProcessingParameterNumber::Double) continue;
      const QVariant places = p->metadata().value(QStringLiteral("widget_wrapper")).toMap().value(QStringLiteral("decimals"));
      EXPECT_TRUE(places.isValid() && places.toInt() >= 1 && places.toInt() <= 4)
          << alg->id().toStdString() << " " << p->name().toStdString();
      ++checked;
    }
  EXPECT_GE(checked, 16);
  // A distance in the hierarchy's CRS shows its unit, taken from HIERARCHY.
  const QgsProcessingAlgorithm* lod = QgsApplication::processingRegistry()->algorithmById(QStringLiteral("tinlod:extractlod"));
  const auto* dropoff = dynamic_cast<const QgsProcessingParameterDistance*>(lod->parameterDefinition(QStringLiteral("DROPOFF")));
  ASSERT_NE(dropoff, nullptr);
  EXPECT_EQ(dropoff->parentParameterName(), QStringLiteral("HIERARCHY"));
  EXPECT_EQ(dropoff->defaultUnit(), QgsUnitTypes::DistanceMeters);
}

// Each algorithm has a one-line description for the toolbox and its group's icon; the
// provider its own: SVGs that draw.
TEST(Processing, AlgorithmsHaveShortDescriptionsAndDrawnIcons) {
  const QgsProcessingProvider* provider = QgsApplication::processingRegistry()->providerById(QStringLiteral("tinlod"));
  ASSERT_NE(provider, nullptr);
  EXPECT_FALSE(provider->icon().pixmap(32).isNull());
  const QImage providerImage = provider->icon().pixmap(32).toImage();
  QSet<QString> groups;
  for (const QgsProcessingAlgorithm* alg : provider->algorithms()) {
    const std::string id = alg->id().toStdString();
    EXPECT_GT(alg->shortDescription().size(), 30) << id;
    EXPECT_TRUE(alg->shortDescription().endsWith('.')) << id;
    // Help opens the algorithm's reference page, shipped beside the library as HTML whose
    // links lead to the other pages, which are there too.
    const QUrl help(alg->helpUrl());
    EXPECT_TRUE(help.isLocalFile() && help.toLocalFile().endsWith("/help/html/qgis/" + alg->name() + ".html") &&
                QFileInfo::exists(help.toLocalFile()))
        << id << ": " << alg->helpUrl().toStdString();
    QFile html(help.toLocalFile());
    ASSERT_TRUE(html.open(QIODevice::ReadOnly)) << id;
    const QString text = QString::fromUtf8(html.readAll());
    EXPECT_TRUE(text.contains("<table")) << id << ": no parameter table";
    static const QRegularExpression link(QStringLiteral("href=\"([^\"#:]+)(#[^\"]*)?\""));
    int links = 0;
    for (auto m = link.globalMatch(text); m.hasNext(); ++links) {
      const QString target = m.next().captured(1);
      EXPECT_TRUE(target.endsWith(".html") || target.endsWith(".png")) << id << ": " << target.toStdString();
      EXPECT_TRUE(QFileInfo::exists(QFileInfo(help.toLocalFile()).absolutePath() + "/" + target)) << id << ": " << target.toStdString();
    }
    EXPECT_GT(links, 0) << id;
    EXPECT_TRUE(QFile::exists(QStringLiteral(":/tinlod/%1.svg").arg(alg->groupId()))) << id;
    const QPixmap pixmap = alg->icon().pixmap(32);
    ASSERT_FALSE(pixmap.isNull()) << id;
    EXPECT_NE(pixmap.toImage(), providerImage) << id;
    groups << alg->groupId();
  }
  EXPECT_EQ(groups.size(), 4);
}

// Every parameter's tooltip is its row of the reference page, as plain text (a user trial
// found all 86 empty).
TEST(Processing, EveryParameterHasItsPagesDescriptionAsHelp) {
  const QgsProcessingProvider* provider = QgsApplication::processingRegistry()->providerById(QStringLiteral("tinlod"));
  ASSERT_NE(provider, nullptr);
  std::size_t parameters = 0;
  for (const QgsProcessingAlgorithm* listed : provider->algorithms()) {
    std::unique_ptr<QgsProcessingAlgorithm> alg(listed->create());  // as the dialog makes it
    for (const QgsProcessingParameterDefinition* p : alg->parameterDefinitions()) {
      ++parameters;
      const std::string where = alg->id().toStdString() + " " + p->name().toStdString();
      EXPECT_GT(p->help().size(), 20) << where;
      EXPECT_FALSE(p->help().contains('`') || p->help().contains("](")) << where << ": " << p->help().toStdString();
    }
  }
  EXPECT_GT(parameters, 80u);
  std::unique_ptr<QgsProcessingAlgorithm> build(
      QgsApplication::processingRegistry()->createAlgorithmById(QStringLiteral("tinlod:buildhierarchy")));
  EXPECT_TRUE(build->parameterDefinition(QStringLiteral("LOAD_LEVELS"))->help().startsWith("Open the level layers in the map"))
      << build->parameterDefinition(QStringLiteral("LOAD_LEVELS"))->help().toStdString();
}

TEST(Processing, SampleTinMatchesTheCore) {
  const QString out = QString::fromStdString(test::tempDir() + "/tin.gpkg");
  const Result r = runAlgorithm(QStringLiteral("tinlod:sampletin"),
                                {{"INPUT", QString::fromStdString(defaultDem())}, {"OUTPUT", out}});
  ASSERT_TRUE(r.ok) << r.error.toStdString();
  const Tin core = sampleTin(readDem(defaultDem(), 1, ProgressRange(Feedback{}, 0, 1)), {}, ProgressRange(Feedback{}, 0, 1));
  EXPECT_EQ(r.outputs.value("VERTICES").toLongLong(), (long long)core.vertices.size());
  EXPECT_EQ(r.outputs.value("TRIANGLES").toLongLong(), (long long)core.triangles.size());
  EXPECT_EQ(featureCount(out, "triangles"), (long long)core.triangles.size());
  EXPECT_EQ(r.outputs.value("OUTPUT").toString(), out);
}

// The help panel renders the help as HTML: a bare "<" (as in "<= k") hid the rest of a
// paragraph there.
TEST(Processing, HelpTextsHoldNoBareAngleBracket) {
  const QgsProcessingProvider* provider = QgsApplication::processingRegistry()->providerById(QStringLiteral("tinlod"));
  ASSERT_NE(provider, nullptr);
  ASSERT_GE(provider->algorithms().size(), 8);
  for (const QgsProcessingAlgorithm* alg : provider->algorithms())
    EXPECT_FALSE(alg->shortHelpString().contains(QRegularExpression(QStringLiteral("<(?![a-zA-Z/!])"))))
        << alg->id().toStdString();
}

TEST(Processing, ParametersReachTheCore) {
  const QString out = QString::fromStdString(test::tempDir() + "/tin.gpkg");
  const Result r = runAlgorithm(QStringLiteral("tinlod:sampletin"),
                                {{"INPUT", QString::fromStdString(defaultDem())},
                                 {"BAND", 1},
                                 {"BLOCK", 5},
                                 {"JITTER", 0.2},
                                 {"SEED", 3},
                                 {"TARGET_CRS", "EPSG:32633"},
                                 {"OUTPUT", out}});
  ASSERT_TRUE(r.ok) << r.error.toStdString();
  SampleOptions o;
  o.block = 5, o.jitter = 0.2, o.seed = 3, o.targetSrs = "EPSG:32633";
  const Tin core = sampleTin(readDem(defaultDem(), 1, ProgressRange(Feedback{}, 0, 1)), o, ProgressRange(Feedback{}, 0, 1));
  EXPECT_EQ(r.outputs.value("TRIANGLES").toLongLong(), (long long)core.triangles.size());
  QgsVectorLayer layer(out + "|layername=triangles", "t", QStringLiteral("ogr"));
  EXPECT_EQ(layer.crs().authid(), QStringLiteral("EPSG:32633"));
}

// The core's messages name the command line's options; in QGIS they name the parameters.
TEST(Processing, SamplingErrorsNameTheParameters) {
  const Result r = runAlgorithm(QStringLiteral("tinlod:sampletin"),
                                {{"INPUT", QString::fromStdString(defaultDem())},
                                 {"JITTER", 25},  // the default DEM's cells are 20 m
                                 {"OUTPUT", QString::fromStdString(test::tempDir() + "/tin.gpkg")}});
  ASSERT_FALSE(r.ok);
  EXPECT_TRUE(r.error.contains(QStringLiteral("use e.g. JITTER 2"))) << r.error.toStdString();
  EXPECT_FALSE(r.error.contains(QStringLiteral("-jitter"))) << r.error.toStdString();
}

TEST(Processing, ValidRangeReachesTheCoreAndABadOneNamesTheParameter) {
  const ProgressRange quiet(Feedback{}, 0, 1);
  std::vector<float> heights;
  for (float z : readDem(defaultDem(), 1, quiet).z)
    if (!std::isnan(z)) heights.push_back(z);
  std::nth_element(heights.begin(), heights.begin() + heights.size() / 2, heights.end());
  const double median = std::floor(heights[heights.size() / 2]);  // a whole number: the same as text
  const QString out = QString::fromStdString(test::tempDir() + "/tin.gpkg");
  const Result r = runAlgorithm(QStringLiteral("tinlod:sampletin"), {{"INPUT", QString::fromStdString(defaultDem())},
                                                                     {"VALID_RANGE", QStringLiteral("-100,%1").arg(median)},
                                                                     {"OUTPUT", out}});
  ASSERT_TRUE(r.ok) << r.error.toStdString();
  SampleOptions o;
  o.validHeights = {-100, median};
  const Tin core = sampleTin(readDem(defaultDem(), 1, quiet, o.validHeights), o, quiet);
  EXPECT_EQ(r.outputs.value("TRIANGLES").toLongLong(), (long long)core.triangles.size());
  EXPECT_LT(core.triangles.size(), sampleTin(readDem(defaultDem(), 1, quiet), {}, quiet).triangles.size() * 3 / 4);
  const Result bad = runAlgorithm(QStringLiteral("tinlod:sampletin"), {{"INPUT", QString::fromStdString(defaultDem())},
                                                                       {"VALID_RANGE", QStringLiteral("9000,-12000")},
                                                                       {"OUTPUT", out + "2"}});
  EXPECT_FALSE(bad.ok);
  EXPECT_TRUE(bad.error.contains("VALID_RANGE (9000,-12000)")) << bad.error.toStdString();
  // Accuracy takes the range the GeoPackage was made with unless one is given.
  const QgsProcessingAlgorithm* accuracy = QgsApplication::processingRegistry()->algorithmById(QStringLiteral("tinlod:accuracy"));
  ASSERT_NE(accuracy, nullptr);
  ASSERT_NE(accuracy->parameterDefinition(QStringLiteral("VALID_RANGE")), nullptr);
  EXPECT_FALSE(accuracy->parameterDefinition(QStringLiteral("VALID_RANGE"))->defaultValue().isValid());
}

TEST(Processing, BadBandIsAProcessingErrorNamingTheParameter) {
  const QString out = QString::fromStdString(test::tempDir() + "/tin.gpkg");
  const Result r = runAlgorithm(QStringLiteral("tinlod:sampletin"),
                                {{"INPUT", QString::fromStdString(defaultDem())}, {"BAND", 2}, {"OUTPUT", out}});
  EXPECT_FALSE(r.ok);
  EXPECT_TRUE(r.error.contains("BAND")) << r.error.toStdString();
  EXPECT_FALSE(fs::exists(out.toStdString()));
}

TEST(Processing, CoreErrorsBecomeProcessingExceptions) {
  const QString out = QString::fromStdString(test::tempDir() + "/tin.gpkg");
  const Result r = runAlgorithm(QStringLiteral("tinlod:sampletin"), {{"INPUT", QString::fromStdString(defaultDem())},
                                                                     {"TARGET_CRS", "EPSG:4326"},
                                                                     {"OUTPUT", out}});
  EXPECT_FALSE(r.ok);
  EXPECT_TRUE(r.error.contains("TARGET_CRS must be a projected CRS in metres")) << r.error.toStdString();
  EXPECT_TRUE(r.error.contains("EPSG:4326")) << r.error.toStdString();
  EXPECT_LT(r.error.size(), 200) << "no WKT dump: " << r.error.toStdString();
  EXPECT_FALSE(fs::exists(out.toStdString()));
}

// 60 x 10 cells of a degree from 20 W, 40 N: wider than a UTM zone reaches.
std::string wideDegreeDem() {
  const std::string path = test::tempDir() + "/wide_degrees.tif";
  GDALDatasetUniquePtr ds(GetGDALDriverManager()->GetDriverByName("GTiff")->Create(path.c_str(), 60, 10, 1, GDT_Float32, nullptr));
  double gt[6] = {-20, 1, 0, 40, 0, -1};
  ds->SetGeoTransform(gt);
  OGRSpatialReference srs;
  srs.importFromEPSG(4326);
  ds->SetSpatialRef(&srs);
  std::vector<float> z(600);
  for (std::size_t i = 0; i < z.size(); ++i) z[i] = 100.0f + static_cast<float>((i % 7) * 10 + (i / 60) * 3);
  EXPECT_EQ(ds->GetRasterBand(1)->RasterIO(GF_Write, 0, 0, 60, 10, z.data(), 60, 10, GDT_Float32, 0, 0), CE_None);
  return path;
}

// The PROJ string a warning advises is taken as TARGET_CRS as it is written: QGIS reads a
// PROJ string only after "PROJ:", and took anything it could not read as no CRS at all.
TEST(Processing, TargetCrsTakesThePROJStringAWarningAdvisesAndRefusesWhatNoOneReads) {
  const QString dem = QString::fromStdString(wideDegreeDem());
  const QString out = QString::fromStdString(test::tempDir() + "/wide.gpkg");
  RecordingFeedback warned;
  ASSERT_TRUE(runAlgorithm(QStringLiteral("tinlod:sampletin"), {{"INPUT", dem}, {"OUTPUT", out}}, &warned).ok);
  const QString warning = warned.warnings.filter(QStringLiteral("stretches distances")).value(0);
  const QRegularExpressionMatch advised = QRegularExpression(QStringLiteral("use TARGET_CRS '([^']+)'")).match(warning);
  ASSERT_TRUE(advised.hasMatch()) << warning.toStdString();
  RecordingFeedback taken;
  const Result r = runAlgorithm(QStringLiteral("tinlod:sampletin"),
                                {{"INPUT", dem}, {"TARGET_CRS", advised.captured(1)}, {"OUTPUT", out}}, &taken);
  ASSERT_TRUE(r.ok) << r.error.toStdString();
  EXPECT_TRUE(taken.warnings.filter(QStringLiteral("stretches distances")).isEmpty()) << taken.warnings.join('\n').toStdString();
  QgsVectorLayer layer(out + "|layername=triangles", "t", QStringLiteral("ogr"));
  EXPECT_TRUE(layer.crs().toProj().contains(QStringLiteral("+proj=lcc"))) << layer.crs().toProj().toStdString();
  const QString none = QString::fromStdString(test::tempDir() + "/none.gpkg");
  const Result bad = runAlgorithm(QStringLiteral("tinlod:sampletin"), {{"INPUT", dem}, {"TARGET_CRS", "nonsense"}, {"OUTPUT", none}});
  EXPECT_FALSE(bad.ok);
  EXPECT_TRUE(bad.error.contains("TARGET_CRS 'nonsense' is not a CRS GDAL understands")) << bad.error.toStdString();
  EXPECT_FALSE(fs::exists(none.toStdString()));
}

// The whole world, 36 x 18 cells of 10 degrees: no projected CRS holds it.
TEST(Processing, TheWholeWorldIsToldToBeClippedAsQgisDoesIt) {
  const std::string path = test::tempDir() + "/world.tif";
  ASSERT_EQ(std::system(("gdal_translate -q -outsize 36 18 -a_srs EPSG:4326 -a_ullr -180 90 180 -90 " + defaultDem() + " " + path)
                            .c_str()),
            0);
  RecordingFeedback warned;
  const QString out = QString::fromStdString(test::tempDir() + "/world.gpkg");
  const Result r = runAlgorithm(QStringLiteral("tinlod:sampletin"), {{"INPUT", QString::fromStdString(path)}, {"OUTPUT", out}}, &warned);
  EXPECT_FALSE(r.ok);
  EXPECT_TRUE(r.error.contains(QStringLiteral("cut it into regions (Raster > Extraction > Clip Raster by Extent)"))) << r.error.toStdString();
  EXPECT_TRUE(warned.warnings.filter(QStringLiteral("cannot project the whole DEM")).size() == 1) << warned.warnings.join('\n').toStdString();
  EXPECT_FALSE(r.error.contains(QStringLiteral("gdal_translate"))) << r.error.toStdString();
  EXPECT_FALSE(fs::exists(out.toStdString()));
}

TEST(Processing, OutputLayersAreLoadedNamedAndStyled) {
  const QString out = QString::fromStdString(test::tempDir() + "/my_tin.gpkg");
  std::unique_ptr<QgsProcessingAlgorithm> alg(QgsApplication::processingRegistry()->createAlgorithmById("tinlod:sampletin"));
  QgsProcessingContext context;
  QgsProject project;
  context.setProject(&project);
  RecordingFeedback feedback;
  bool ok = false;
  alg->run({{"INPUT", QString::fromStdString(defaultDem())}, {"OUTPUT", out}}, context, &feedback, &ok);
  ASSERT_TRUE(ok) << feedback.errors.toStdString();
  const auto layers = context.layersToLoadOnCompletion();
  ASSERT_EQ(layers.size(), 2);
  QStringList names;
  for (auto it = layers.constBegin(); it != layers.constEnd(); ++it) {
    names << it.value().name;
    EXPECT_NE(it.value().postProcessor(), nullptr);
  }
  names.sort();
  EXPECT_EQ(names, QStringList({"my_tin triangles", "my_tin vertices"}));
}

// What QGIS does when the run ends: each registered layer is loaded into the project
// (where the current layer is: `into`, or the root) and handed to its post-processor.
void loadAsQgisDoes(QgsProcessingContext& context, QgsProject& project, QgsLayerTreeGroup* into = nullptr) {
  const auto layers = context.layersToLoadOnCompletion();
  RecordingFeedback feedback;
  for (auto it = layers.constBegin(); it != layers.constEnd(); ++it) {
    auto* layer = new QgsVectorLayer(it.key(), it.value().name, QStringLiteral("ogr"));
    project.addMapLayer(layer, into == nullptr);
    if (into) into->insertLayer(0, layer);  // above the current layer, as QGIS adds it
    QgsProcessingContext loading;
    loading.setProject(&project);
    it.value().postProcessor()->postProcessLayer(layer, loading, &feedback);
  }
}

TEST(Processing, TemporaryOutputsAreNamedAfterTheToolVerticesHiddenAndOutOfAHierarchysGroup) {
  QgsProject project;
  // A hierarchy first: its levels make a group, and a level is the current layer.
  QgsProcessingContext first;
  first.setProject(&project);
  RecordingFeedback feedback;
  bool ok = false;
  std::unique_ptr<QgsProcessingAlgorithm> build(QgsApplication::processingRegistry()->createAlgorithmById("tinlod:buildhierarchy"));
  const QString hier = QString::fromStdString(test::tempDir() + "/peaks.gpkg");
  build->run({{"INPUT", QString::fromStdString(defaultDem())}, {"MAX_LEVELS", 2}, {"OUTPUT", hier}}, first, &feedback, &ok);
  ASSERT_TRUE(ok) << feedback.errors.toStdString();
  loadAsQgisDoes(first, project);
  QgsLayerTreeGroup* levels = project.layerTreeRoot()->findGroup(QStringLiteral("peaks levels"));
  ASSERT_NE(levels, nullptr);
  // Then a sample to a temporary output, loaded where QGIS would put it: in that group.
  QgsProcessingContext second;
  second.setProject(&project);
  std::unique_ptr<QgsProcessingAlgorithm> sample(QgsApplication::processingRegistry()->createAlgorithmById("tinlod:sampletin"));
  const QString temporary = QgsProcessingUtils::generateTempFilename(QStringLiteral("OUTPUT.gpkg"));
  sample->run({{"INPUT", QString::fromStdString(defaultDem())}, {"OUTPUT", temporary}}, second, &feedback, &ok);
  ASSERT_TRUE(ok) << feedback.errors.toStdString();
  loadAsQgisDoes(second, project, levels);
  QgsLayerTreeLayer* triangles = nullptr;
  QgsLayerTreeLayer* vertices = nullptr;
  for (QgsLayerTreeLayer* node : project.layerTreeRoot()->findLayers()) {
    if (node->name() == QStringLiteral("sampled TIN triangles")) triangles = node;
    if (node->name() == QStringLiteral("sampled TIN vertices")) vertices = node;
  }
  ASSERT_NE(triangles, nullptr) << "a temporary output's layers are named after the tool, not 'OUTPUT'";
  ASSERT_NE(vertices, nullptr);
  EXPECT_EQ(triangles->parent(), project.layerTreeRoot());
  EXPECT_EQ(vertices->parent(), project.layerTreeRoot());
  EXPECT_TRUE(triangles->itemVisibilityChecked());
  EXPECT_FALSE(vertices->itemVisibilityChecked());
  EXPECT_EQ(levels->findLayers().size(), 3);  // the levels alone
  // A locate afterwards, which QGIS would also put among the levels: at the top as well.
  QgsProcessingContext third;
  third.setProject(&project);
  std::unique_ptr<QgsProcessingAlgorithm> locate(QgsApplication::processingRegistry()->createAlgorithmById("tinlod:locate"));
  locate->run({{"INPUT", hier + "|layername=vertices"}, {"HIERARCHY", hier},
               {"OUTPUT", QString::fromStdString(test::tempDir() + "/peaks_located.gpkg")}}, third, &feedback, &ok);
  ASSERT_TRUE(ok) << feedback.errors.toStdString();
  loadAsQgisDoes(third, project, levels);
  EXPECT_EQ(levels->findLayers().size(), 3);
  bool locatedAtTop = false;
  for (QgsLayerTreeNode* child : project.layerTreeRoot()->children())
    locatedAtTop |= child->name() == QStringLiteral("peaks_located points");  // named after its file
  EXPECT_TRUE(locatedAtTop);
}

// Running again onto a file already on the map: QGIS hands the post-processors the layers
// already there (mapLayerFromString finds them by source), not new ones. They show the new
// file (they read the one it replaced until reloaded) and keep the user's style and place.
TEST(Processing, RunningAgainOntoALoadedFileShowsTheNewFileAndKeepsTheUsersStyle) {
  QgsProject project;
  const QString out = QString::fromStdString(test::tempDir() + "/again.gpkg");
  auto run = [&](const QString& algorithm, const QVariantMap& parameters) {
    Result r = runAlgorithm(algorithm, parameters, nullptr, &project);
    EXPECT_TRUE(r.ok) << r.error.toStdString();
    // As QGIS's handleAlgorithmResults: the layer on the map for the same source, or a new one.
    const auto layers = r.context->layersToLoadOnCompletion();
    for (auto it = layers.constBegin(); it != layers.constEnd(); ++it) {
      QgsProcessingContext loading;
      loading.setProject(&project);
      QgsMapLayer* layer = QgsProcessingUtils::mapLayerFromString(it.key(), loading);
      QgsProcessingContext::LayerDetails details = it.value();
      details.setOutputLayerName(layer);
      if (QgsMapLayer* taken = loading.temporaryLayerStore()->takeMapLayer(layer)) project.addMapLayer(taken);
      it.value().postProcessor()->postProcessLayer(layer, loading, nullptr);
    }
    return r;
  };
  auto build = [&](int deletePct, int levels = 3) {
    return run(QStringLiteral("tinlod:buildhierarchy"), {{"INPUT", QString::fromStdString(defaultDem())},
                                                         {"MAX_LEVELS", levels}, {"DELETE_PCT", deletePct}, {"OUTPUT", out}});
  };
  auto layerNames = [&](bool shownOnly) {
    QStringList names;
    for (QgsLayerTreeLayer* node : project.layerTreeRoot()->findLayers())
      if (!shownOnly || node->itemVisibilityChecked()) names << node->name();
    names.sort();
    return names.join(QStringLiteral(", ")).toStdString();
  };
  build(20);
  const QList<QgsMapLayer*> found = project.mapLayersByName(QStringLiteral("level_3"));
  ASSERT_EQ(found.size(), 1);
  auto* level3 = qobject_cast<QgsVectorLayer*>(found[0]);
  QgsSymbol* mine = QgsSymbol::defaultSymbol(QgsWkbTypes::PolygonGeometry);
  mine->setColor(QColor(1, 2, 3));
  level3->setRenderer(new QgsSingleSymbolRenderer(mine));
  project.layerTreeRoot()->findLayer(level3)->setItemVisibilityChecked(true);
  const long long before = level3->featureCount();

  build(40);
  EXPECT_EQ(project.mapLayersByName(QStringLiteral("level_3")).size(), 1) << "the same layer, not a second";
  const long long written = featureCount(out, QStringLiteral("level_3"));
  EXPECT_LT(written, before);  // 40 % a level deletes more than 20 %
  EXPECT_EQ(level3->featureCount(), written) << "the layer still reads the file the run replaced";
  auto* kept = dynamic_cast<QgsSingleSymbolRenderer*>(level3->renderer());
  ASSERT_NE(kept, nullptr);
  EXPECT_EQ(kept->symbol()->color(), QColor(1, 2, 3)) << "the user's style was replaced";
  EXPECT_TRUE(project.layerTreeRoot()->findLayer(level3)->itemVisibilityChecked());

  // With more levels, the new coarsest shows, alone, as after a first run.
  build(40, 5);
  QStringList shown;
  for (QgsLayerTreeLayer* node : project.layerTreeRoot()->findLayers())
    if (node->itemVisibilityChecked() && node->name().startsWith("level_")) shown << node->name();
  EXPECT_EQ(shown, QStringList({"level_5"}));

  // With fewer, the levels the file no longer has go (they would be broken layers), and the
  // new coarsest shows in place of the one shown; a layer the user loaded stays theirs.
  auto* own = new QgsVectorLayer(out + QStringLiteral("|layername=level_4"), QStringLiteral("my level 4"), QStringLiteral("ogr"));
  ASSERT_TRUE(own->isValid());
  project.addMapLayer(own);
  project.layerTreeRoot()->findLayer(own)->setItemVisibilityChecked(false);
  build(40, 2);
  EXPECT_EQ(layerNames(false), "level_0, level_1, level_2, my level 4");
  EXPECT_EQ(layerNames(true), "level_2");
  EXPECT_EQ(project.mapLayers().size(), 4);

  // A TIN of another kind written over the hierarchy: its levels go too.
  run(QStringLiteral("tinlod:sampletin"), {{"INPUT", QString::fromStdString(defaultDem())}, {"OUTPUT", out}});
  EXPECT_EQ(layerNames(false), "again triangles, again vertices, my level 4");
  EXPECT_EQ(layerNames(true), "again triangles");
}

// QGIS adds each loaded layer where the current one is: inside the group of levels once
// the first level is in it. The levels must still end in level order.
TEST(Processing, LevelsKeepTheirOrderWhenQgisAddsThemInsideTheGroup) {
  QgsProject project;
  const Result built = runAlgorithm(QStringLiteral("tinlod:buildhierarchy"),
                                    {{"INPUT", QString::fromStdString(defaultDem())}, {"MAX_LEVELS", 4},
                                     {"OUTPUT", QString::fromStdString(test::tempDir() + "/ordered.gpkg")}},
                                    nullptr, &project);
  ASSERT_TRUE(built.ok) << built.error.toStdString();
  QgsLayerTreeGroup* group = project.layerTreeRoot()->insertGroup(0, QStringLiteral("ordered levels"));
  group->setCustomProperty(QStringLiteral("tinlod/group"), true);
  loadAsQgisDoes(*built.context, project, group);
  QStringList order;
  for (QgsLayerTreeLayer* node : group->findLayers()) order << node->name();
  EXPECT_EQ(order, QStringList({"level_0", "level_1", "level_2", "level_3", "level_4"}));
}

TEST(Processing, CancelStopsAndLeavesNoFile) {
  const QString out = QString::fromStdString(test::tempDir() + "/tin.gpkg");
  RecordingFeedback feedback;
  QObject::connect(&feedback, &QgsFeedback::progressChanged, [&feedback](double p) {
    if (p > 30) feedback.cancel();
  });
  const Result r = runAlgorithm(QStringLiteral("tinlod:sampletin"),
                                {{"INPUT", QString::fromStdString(defaultDem())}, {"OUTPUT", out}}, &feedback);
  EXPECT_FALSE(r.ok);
  EXPECT_TRUE(r.error.contains("cancel")) << r.error.toStdString();
  EXPECT_FALSE(fs::exists(out.toStdString()));
}

TEST(Processing, ExistingGeoPackageKeepsItsOtherLayers) {
  const std::string dir = test::tempDir();
  const QString out = QString::fromStdString(dir + "/tin.gpkg");
  ASSERT_TRUE(runAlgorithm(QStringLiteral("tinlod:sampletin"), {{"INPUT", QString::fromStdString(defaultDem())}, {"OUTPUT", out}}).ok);
  // Another tool adds a layer to the same file.
  const Result copy = runAlgorithm(QStringLiteral("native:centroids"),
                                   {{"INPUT", out + "|layername=triangles"},
                                    {"ALL_PARTS", false},
                                    {"OUTPUT", QStringLiteral("ogr:dbname='%1' table=\"centroids\" (geom)").arg(out)}});
  ASSERT_TRUE(copy.ok) << copy.error.toStdString();
  ASSERT_GT(featureCount(out, "centroids"), 0);
  const Result again = runAlgorithm(QStringLiteral("tinlod:sampletin"),
                                    {{"INPUT", QString::fromStdString(defaultDem())}, {"BLOCK", 4}, {"OUTPUT", out}});
  ASSERT_TRUE(again.ok) << again.error.toStdString();
  EXPECT_GT(featureCount(out, "centroids"), 0);
  EXPECT_EQ(featureCount(out, "triangles"), again.outputs.value("TRIANGLES").toLongLong());
}

long long sqlCount(const std::string& gpkg, const std::string& sql);

// A model: build (an intermediate step), its coarsest level to native:centroids, and
// extractlod, whose TIN is the model's output "lod:tin".
void makeLodModel(QgsProcessingModelAlgorithm& model) {
  using Source = QgsProcessingModelChildParameterSource;
  QgsProcessingModelChildAlgorithm build(QStringLiteral("tinlod:buildhierarchy"));
  build.setChildId(QStringLiteral("build"));
  build.addParameterSources(QStringLiteral("INPUT"), {Source::fromStaticValue(QString::fromStdString(defaultDem()))});
  build.addParameterSources(QStringLiteral("MAX_LEVELS"), {Source::fromStaticValue(3)});
  model.addChildAlgorithm(build);
  QgsProcessingModelChildAlgorithm lod(QStringLiteral("tinlod:extractlod"));
  lod.setChildId(QStringLiteral("lod"));
  lod.addParameterSources(QStringLiteral("HIERARCHY"), {Source::fromChildOutput(QStringLiteral("build"), QStringLiteral("OUTPUT"))});
  lod.addParameterSources(QStringLiteral("MAX_ERROR"), {Source::fromStaticValue(5)});
  QgsProcessingModelOutput tin(QStringLiteral("tin"), QStringLiteral("tin"));
  tin.setChildId(QStringLiteral("lod"));
  tin.setChildOutputName(QStringLiteral("OUTPUT"));
  lod.setModelOutputs({{QStringLiteral("tin"), tin}});
  model.addChildAlgorithm(lod);
  QgsProcessingModelChildAlgorithm centroids(QStringLiteral("native:centroids"));
  centroids.setChildId(QStringLiteral("centroids"));
  centroids.addParameterSources(QStringLiteral("INPUT"),
                                {Source::fromChildOutput(QStringLiteral("build"), QStringLiteral("COARSEST_LAYER"))});
  QgsProcessingModelOutput points(QStringLiteral("points"), QStringLiteral("points"));
  points.setChildId(QStringLiteral("centroids"));
  points.setChildOutputName(QStringLiteral("OUTPUT"));
  centroids.setModelOutputs({{QStringLiteral("points"), points}});
  model.addChildAlgorithm(centroids);
  model.updateDestinationParameters();
}

// Only the model's output comes to the map, as QGIS loads no intermediate layer of a model;
// and the centroids are the coarsest level's triangles', where the GeoPackage alone gave
// native algorithms its first layer, the vertices.
TEST(Processing, AModelLoadsOnlyItsOwnOutputsAndItsStepsPassTriangles) {
  QgsProcessingModelAlgorithm model(QStringLiteral("m"), QStringLiteral("g"));
  makeLodModel(model);
  const QString dir = QString::fromStdString(test::tempDir());
  QgsProcessingContext context;
  QgsProject project;
  context.setProject(&project);
  RecordingFeedback feedback;
  bool ok = false;
  const QVariantMap results = model.run({{QStringLiteral("lod:tin"), dir + "/lod.gpkg"},
                                         {QStringLiteral("centroids:points"), dir + "/points.gpkg"}},
                                        context, &feedback, &ok);
  ASSERT_TRUE(ok) << feedback.errors.toStdString();
  const QStringList loaded = context.layersToLoadOnCompletion().keys();
  EXPECT_TRUE(loaded.contains(dir + "/lod.gpkg|layername=triangles")) << loaded.join(' ').toStdString();
  for (const QString& layer : loaded)
    EXPECT_FALSE(layer.startsWith(QgsProcessingUtils::tempFolder())) << "an intermediate layer: " << layer.toStdString();
  const QVariantMap built = results.value(QStringLiteral("CHILD_RESULTS")).toMap().value(QStringLiteral("build")).toMap();
  const QString coarsest = built.value(QStringLiteral("COARSEST_LAYER")).toString();
  EXPECT_TRUE(coarsest.endsWith(QStringLiteral("|layername=level_3"))) << coarsest.toStdString();
  QgsVectorLayer level(coarsest, QStringLiteral("level"), QStringLiteral("ogr"));
  ASSERT_TRUE(level.isValid());
  QgsVectorLayer centres(dir + "/points.gpkg", QStringLiteral("points"), QStringLiteral("ogr"));
  EXPECT_EQ(centres.featureCount(), level.featureCount());
  EXPECT_GT(level.featureCount(), 0);
}

// A model output left temporary is loaded, as native algorithms' are; and a context a model
// ran in (its variables stay in it) loads an algorithm's layers run after it.
TEST(Processing, AModelsTemporaryOutputAndALaterRunInItsContextAreLoaded) {
  QgsProcessingModelAlgorithm model(QStringLiteral("m"), QStringLiteral("g"));
  makeLodModel(model);
  QgsProcessingContext context;
  QgsProject project;
  context.setProject(&project);
  RecordingFeedback feedback;
  bool ok = false;
  model.run({{QStringLiteral("lod:tin"), QgsProcessing::TEMPORARY_OUTPUT},
             {QStringLiteral("centroids:points"), QgsProcessing::TEMPORARY_OUTPUT}},
            context, &feedback, &ok);
  ASSERT_TRUE(ok) << feedback.errors.toStdString();
  const QStringList loaded = context.layersToLoadOnCompletion().keys();
  EXPECT_EQ(loaded.filter(QStringLiteral("|layername=triangles")).size(), 1) << loaded.join(' ').toStdString();
  EXPECT_TRUE(loaded.filter(QStringLiteral("|layername=level_")).isEmpty()) << loaded.join(' ').toStdString();
  context.setLayersToLoadOnCompletion({});
  std::unique_ptr<QgsProcessingAlgorithm> sample(QgsApplication::processingRegistry()->createAlgorithmById("tinlod:sampletin"));
  sample->run({{"INPUT", QString::fromStdString(defaultDem())}, {"OUTPUT", QgsProcessing::TEMPORARY_OUTPUT}}, context, &feedback, &ok);
  ASSERT_TRUE(ok) << feedback.errors.toStdString();
  EXPECT_EQ(context.layersToLoadOnCompletion().size(), 2);
}

// Where LEVEL_VIEWS wrote no view of the coarsest level, its layer is the triangles cut to it.
TEST(Processing, TheCoarsestLayerWithoutItsViewIsTheTrianglesCutToIt) {
  const QString out = QString::fromStdString(test::tempDir() + "/hier.gpkg");
  const Result r = runAlgorithm(QStringLiteral("tinlod:buildhierarchy"), {{"INPUT", QString::fromStdString(defaultDem())},
                                                                          {"MAX_LEVELS", 3},
                                                                          {"LEVEL_VIEWS", "0"},
                                                                          {"OUTPUT", out}});
  ASSERT_TRUE(r.ok) << r.error.toStdString();
  QgsVectorLayer cut(r.outputs.value("COARSEST_LAYER").toString(), QStringLiteral("cut"), QStringLiteral("ogr"));
  ASSERT_TRUE(cut.isValid()) << r.outputs.value("COARSEST_LAYER").toString().toStdString();
  EXPECT_EQ(cut.featureCount(), sqlCount(out.toStdString(), "SELECT count(*) FROM triangles WHERE first_level <= 3 AND last_level >= 3"));
  const Result sampled = runAlgorithm(QStringLiteral("tinlod:sampletin"),
                                      {{"INPUT", QString::fromStdString(defaultDem())}, {"OUTPUT", out + "2.gpkg"}});
  ASSERT_TRUE(sampled.ok);
  EXPECT_EQ(featureCount(out + "2.gpkg", "triangles"),
            QgsVectorLayer(sampled.outputs.value("TRIANGLES_LAYER").toString(), "t", "ogr").featureCount());
}

// As tinlod accuracy: with neither output the figures still come (a model's step gets no file
// for an optional output no later step takes).
TEST(Processing, AccuracyWithNoFileToWriteStillMeasures) {
  const QString hierarchy = QString::fromStdString(test::tempDir() + "/hier.gpkg");
  ASSERT_TRUE(runAlgorithm(QStringLiteral("tinlod:buildhierarchy"),
                           {{"INPUT", QString::fromStdString(defaultDem())}, {"MAX_LEVELS", 2}, {"OUTPUT", hierarchy}})
                  .ok);
  const Result r = runAlgorithm(QStringLiteral("tinlod:accuracy"),
                                {{"INPUT", QString::fromStdString(defaultDem())}, {"HIERARCHY", hierarchy}});
  ASSERT_TRUE(r.ok) << r.error.toStdString();
  EXPECT_GT(r.outputs.value("RMSE").toDouble(), 0);
  EXPECT_GE(r.outputs.value("MAX_ERROR").toDouble(), r.outputs.value("RMSE").toDouble());
  EXPECT_FALSE(r.outputs.contains("REPORT"));
}

// A HIERARCHY that is no GeoPackage is refused by checkParameterValues, before the run: its
// message is then what processing.run raises, where a run's own error said only "There were
// errors executing the algorithm."
TEST(Processing, AHierarchyInNoGeoPackageIsRefusedBeforeTheRun) {
  QgsVectorLayer memory(QStringLiteral("Polygon?crs=EPSG:32632"), QStringLiteral("l2"), QStringLiteral("memory"));
  QgsVectorLayer points(QStringLiteral("Point?crs=EPSG:32632"), QStringLiteral("points"), QStringLiteral("memory"));
  QgsProject project;
  project.addMapLayer(&memory, false, false);
  project.addMapLayer(&points, false, false);
  QgsProcessingContext context;
  context.setProject(&project);
  for (const char* id : {"tinlod:accuracy", "tinlod:extractlod", "tinlod:locate"}) {
    std::unique_ptr<QgsProcessingAlgorithm> alg(QgsApplication::processingRegistry()->createAlgorithmById(id));
    ASSERT_NE(alg, nullptr) << id;
    QString message;
    const QVariant input = std::string(id) == "tinlod:locate" ? QVariant(points.id()) : QVariant(QString::fromStdString(defaultDem()));
    EXPECT_FALSE(alg->checkParameterValues({{"INPUT", input},
                                            {"HIERARCHY", memory.id()},
                                            {"OUTPUT", QString::fromStdString(test::tempDir() + "/o.gpkg")}},
                                           context, &message))
        << id;
    EXPECT_TRUE(message.contains("HIERARCHY: 'l2' is not stored in a GeoPackage")) << id << ": " << message.toStdString();
  }
  project.removeMapLayer(memory.id());
  project.removeMapLayer(points.id());
}

TEST(Processing, BuildHierarchyWritesLevelsQgisCanOpen) {
  const QString out = QString::fromStdString(test::tempDir() + "/hier.gpkg");
  std::unique_ptr<QgsProcessingAlgorithm> alg(QgsApplication::processingRegistry()->createAlgorithmById("tinlod:buildhierarchy"));
  ASSERT_NE(alg, nullptr);
  QgsProcessingContext context;
  QgsProject project;
  context.setProject(&project);
  RecordingFeedback feedback;
  bool ok = false;
  const QVariantMap outputs = alg->run({{"INPUT", QString::fromStdString(defaultDem())},
                                        {"METHOD", 3},  // error
                                        {"DELETE_PCT", 10},
                                        {"MAX_LEVELS", 4},
                                        {"OUTPUT", out}},
                                       context, &feedback, &ok);
  ASSERT_TRUE(ok) << feedback.errors.toStdString();
  EXPECT_EQ(outputs.value("LEVELS").toInt(), 5);
  EXPECT_EQ(outputs.value("COARSEST_LEVEL").toInt(), 4);
  for (int level = 0; level <= 4; ++level) {
    QgsVectorLayer layer(out + QStringLiteral("|layername=level_%1").arg(level), "l", QStringLiteral("ogr"));
    ASSERT_TRUE(layer.isValid()) << "level_" << level;
    EXPECT_GT(layer.featureCount(), 0);
    EXPECT_EQ(layer.crs().authid(), QStringLiteral("EPSG:32632"));
  }
  QgsVectorLayer top(out + "|layername=vertices", "v", QStringLiteral("ogr"));
  QgsFeatureRequest coarsest;
  coarsest.setFilterExpression(QStringLiteral("\"level\" = 4"));
  long long vertices = 0;
  QgsFeature f;
  for (QgsFeatureIterator it = top.getFeatures(coarsest); it.nextFeature(f);) ++vertices;
  EXPECT_EQ(vertices, outputs.value("COARSEST_VERTICES").toLongLong());
  // The levels load as one group named after the file, in level order, the coarsest visible.
  const auto layers = context.layersToLoadOnCompletion();
  ASSERT_EQ(layers.size(), 5);
  QgsProject target;
  for (auto it = layers.constBegin(); it != layers.constEnd(); ++it) {  // what QGIS does on completion
    auto* layer = new QgsVectorLayer(it.key(), it.value().name, QStringLiteral("ogr"));
    target.addMapLayer(layer);
    QgsProcessingContext loading;
    loading.setProject(&target);
    it.value().postProcessor()->postProcessLayer(layer, loading, &feedback);
  }
  QgsLayerTreeGroup* group = target.layerTreeRoot()->findGroup(QStringLiteral("hier levels"));
  ASSERT_NE(group, nullptr);
  QStringList order;
  for (QgsLayerTreeLayer* node : group->findLayers()) {
    order << node->name();
    EXPECT_EQ(node->isVisible(), node->name() == QStringLiteral("level_4")) << node->name().toStdString();
  }
  EXPECT_EQ(order, QStringList({"level_0", "level_1", "level_2", "level_3", "level_4"}));
  EXPECT_TRUE(target.layerTreeRoot()->findLayers().size() == 5);
}

TEST(Processing, BuildHierarchyRefusesMaxErrorWithAnotherMethod) {
  const QString out = QString::fromStdString(test::tempDir() + "/hier.gpkg");
  const Result r = runAlgorithm(QStringLiteral("tinlod:buildhierarchy"),
                                {{"INPUT", QString::fromStdString(defaultDem())}, {"METHOD", 1}, {"MAX_ERROR", 3}, {"OUTPUT", out}});
  EXPECT_FALSE(r.ok);
  EXPECT_TRUE(r.error.contains("MAX_ERROR applies to the error method only")) << r.error.toStdString();
  EXPECT_FALSE(fs::exists(out.toStdString()));
}

// The core's notes name options as warnings do: the dialog's parameters, not -max_error.
TEST(Processing, BuildHierarchyNotesNameTheParameters) {
  const QString out = QString::fromStdString(test::tempDir() + "/hier.gpkg");
  RecordingFeedback feedback;
  const Result r = runAlgorithm(QStringLiteral("tinlod:buildhierarchy"),
                                {{"INPUT", QString::fromStdString(defaultDem())}, {"METHOD", 3}, {"MAX_ERROR", 1},
                                 {"MAX_LEVELS", 1}, {"OUTPUT", out}},
                                &feedback);
  ASSERT_TRUE(r.ok) << r.error.toStdString();
  const QString all = feedback.infos.join('\n');
  EXPECT_TRUE(all.contains("more than MAX_ERROR 1 m: there the bound is level 0's own distance; BLOCK 1 samples every cell"))
      << all.toStdString();
  EXPECT_FALSE(all.contains("-max_error")) << all.toStdString();
}

// The first value of `sql`, run by SQLite on the GeoPackage (through GDAL).
long long sqlCount(const std::string& gpkg, const std::string& sql) {
  GDALDatasetUniquePtr ds(GDALDataset::Open(gpkg.c_str(), GDAL_OF_VECTOR));
  if (!ds) return -1;
  OGRLayer* result = ds->ExecuteSQL(sql.c_str(), nullptr, nullptr);
  if (!result) return -1;
  OGRFeatureUniquePtr f(result->GetNextFeature());
  const long long n = f ? f->GetFieldAsInteger64(0) : -1;
  ds->ReleaseResultSet(result);
  return n;
}

TEST(Processing, BuildHierarchyWritesTheChosenLayers) {
  const QString out = QString::fromStdString(test::tempDir() + "/chosen.gpkg");
  const Result r = runAlgorithm(QStringLiteral("tinlod:buildhierarchy"),
                                {{"INPUT", QString::fromStdString(defaultDem())}, {"LEVEL_VIEWS", "0, last"},
                                 {"GROUP_OUTLINES", false}, {"VERTEX_INDEX", true}, {"OUTPUT", out}});
  ASSERT_TRUE(r.ok) << r.error.toStdString();
  const std::string path = out.toStdString();
  EXPECT_EQ(sqlCount(path, "SELECT count(*) FROM sqlite_master WHERE type = 'view'"), 2);
  EXPECT_EQ(sqlCount(path, "SELECT count(*) FROM sqlite_master WHERE name = 'level_0'"), 1);
  EXPECT_EQ(sqlCount(path, "SELECT count(*) FROM gpkg_contents WHERE table_name = 'groups' AND data_type = 'attributes'"), 1);
  EXPECT_EQ(sqlCount(path, "SELECT count(*) FROM sqlite_master WHERE name = 'rtree_vertices_geom'"), 1);
  const Result bad = runAlgorithm(QStringLiteral("tinlod:buildhierarchy"),
                                  {{"INPUT", QString::fromStdString(defaultDem())}, {"LEVEL_VIEWS", "0,coarse"},
                                   {"OUTPUT", QString::fromStdString(test::tempDir() + "/bad.gpkg")}});
  EXPECT_FALSE(bad.ok);
  EXPECT_TRUE(bad.error.contains("LEVEL_VIEWS '0,coarse'")) << bad.error.toStdString();
}

TEST(Processing, BuildHierarchyKeepsPointsOfALayer) {
  const std::string dir = test::tempDir();
  const Tin tin = sampleTin(readDem(defaultDem(), 1, ProgressRange(Feedback{}, 0, 1)), {}, ProgressRange(Feedback{}, 0, 1));
  // A point layer on three interior vertices of the TIN.
  const QString points = QString::fromStdString(dir + "/keep.geojson");
  QFile file(points);
  ASSERT_TRUE(file.open(QIODevice::WriteOnly));
  QString json = "{\"type\":\"FeatureCollection\",\"crs\":{\"type\":\"name\",\"properties\":{\"name\":\"EPSG:32632\"}},\"features\":[";
  std::vector<std::size_t> picked;
  for (std::size_t i = tin.vertices.size() / 2; picked.size() < 3; ++i)
    if (!tin.vertices[i].outline) picked.push_back(i);
  for (std::size_t k = 0; k < picked.size(); ++k)
    json += QStringLiteral("%1{\"type\":\"Feature\",\"properties\":{},\"geometry\":{\"type\":\"Point\",\"coordinates\":[%2,%3]}}")
                .arg(k ? "," : "").arg(tin.vertices[picked[k]].x, 0, 'f', 3).arg(tin.vertices[picked[k]].y, 0, 'f', 3);
  file.write((json + "]}").toUtf8());
  file.close();
  const QString out = QString::fromStdString(dir + "/hier.gpkg");
  const Result r = runAlgorithm(QStringLiteral("tinlod:buildhierarchy"), {{"INPUT", QString::fromStdString(defaultDem())},
                                                                          {"FIXED_POINTS", points},
                                                                          {"LOAD_LEVELS", false},
                                                                          {"OUTPUT", out}});
  ASSERT_TRUE(r.ok) << r.error.toStdString();
  QgsVectorLayer vertices(out + "|layername=vertices", "v", QStringLiteral("ogr"));
  for (std::size_t id : picked) {
    const QgsFeature f = vertices.getFeature(static_cast<QgsFeatureId>(id) + 1);
    EXPECT_EQ(f.attribute("fixed").toInt(), 1) << id;
    EXPECT_EQ(f.attribute("level").toInt(), r.outputs.value("COARSEST_LEVEL").toInt()) << id;
  }
}

// A memory layer with a selection, "Selected features only": exactly the selected points
// are kept (QGIS hands them over as a temporary file); the others are not.
TEST(Processing, FixedPointsFromASelectionOfAMemoryLayer) {
  const std::string dir = test::tempDir();
  const Tin tin = sampleTin(readDem(defaultDem(), 1, ProgressRange(Feedback{}, 0, 1)), {}, ProgressRange(Feedback{}, 0, 1));
  QgsProject project;
  auto* layer = new QgsVectorLayer(QStringLiteral("Point?crs=EPSG:32632"), QStringLiteral("picked"), QStringLiteral("memory"));
  project.addMapLayer(layer);
  std::vector<std::size_t> picked;
  for (std::size_t i = tin.vertices.size() / 3; picked.size() < 5; i += 7)
    if (!tin.vertices[i].outline) picked.push_back(i);
  QgsFeatureList features;
  for (std::size_t id : picked) {
    QgsFeature f(layer->fields());
    f.setGeometry(QgsGeometry::fromPointXY(QgsPointXY(tin.vertices[id].x, tin.vertices[id].y)));
    features << f;
  }
  ASSERT_TRUE(layer->dataProvider()->addFeatures(features));
  QgsFeatureIds selected;
  QgsFeature f;
  int n = 0;
  for (QgsFeatureIterator it = layer->getFeatures(); it.nextFeature(f); ++n)
    if (n < 3) selected.insert(f.id());
  layer->selectByIds(selected);
  const QString out = QString::fromStdString(dir + "/selected.gpkg");
  std::unique_ptr<QgsProcessingAlgorithm> alg(QgsApplication::processingRegistry()->createAlgorithmById("tinlod:buildhierarchy"));
  QgsProcessingContext context;
  context.setProject(&project);
  RecordingFeedback feedback;
  bool ok = false;
  const QVariantMap outputs = alg->run({{"INPUT", QString::fromStdString(defaultDem())},
                                        {"FIXED_POINTS", QVariant::fromValue(QgsProcessingFeatureSourceDefinition(layer->id(), true))},
                                        {"LOAD_LEVELS", false},
                                        {"OUTPUT", out}},
                                       context, &feedback, &ok);
  ASSERT_TRUE(ok) << feedback.errors.toStdString();
  QgsVectorLayer vertices(out + "|layername=vertices", "v", QStringLiteral("ogr"));
  for (std::size_t k = 0; k < picked.size(); ++k) {
    const QgsFeature v = vertices.getFeature(static_cast<QgsFeatureId>(picked[k]) + 1);
    EXPECT_EQ(v.attribute("fixed").toInt(), k < 3 ? 1 : 0) << "point " << k;
  }
}

TEST(Processing, BuildHierarchyWritesTheAccuracyRasterAndReportWhenAsked) {
  const std::string dir = test::tempDir();
  const QString out = QString::fromStdString(dir + "/hier.gpkg"), raster = QString::fromStdString(dir + "/acc.tif"),
                report = QString::fromStdString(dir + "/acc.html");
  const Result r = runAlgorithm(QStringLiteral("tinlod:buildhierarchy"), {{"INPUT", QString::fromStdString(defaultDem())},
                                                                          {"LOAD_LEVELS", false},
                                                                          {"ACCURACY", raster},
                                                                          {"REPORT", report},
                                                                          {"OUTPUT", out}});
  ASSERT_TRUE(r.ok) << r.error.toStdString();
  EXPECT_EQ(r.outputs.value("ACCURACY").toString(), raster);
  EXPECT_EQ(r.outputs.value("REPORT").toString(), report);
  QgsRasterLayer layer(raster, "acc", QStringLiteral("gdal"));
  ASSERT_TRUE(layer.isValid());
  EXPECT_EQ(layer.bandCount(), 4);
  EXPECT_TRUE(fs::exists(report.toStdString()));
  // Without them, no accuracy file is made.
  const QString plain = QString::fromStdString(dir + "/plain.gpkg");
  ASSERT_TRUE(builtDefaultHierarchy(plain));
  int files = 0;
  for (const auto& entry : fs::directory_iterator(dir)) files += entry.path().extension() != ".gpkg";
  EXPECT_EQ(files, 2);
}

TEST(Processing, AccuracyMeasuresAHierarchyAndNamesBadParameters) {
  const std::string dir = test::tempDir();
  const QString hier = QString::fromStdString(dir + "/hier.gpkg");
  ASSERT_TRUE(builtDefaultHierarchy(hier));
  const QString raster = QString::fromStdString(dir + "/acc.tif"), report = QString::fromStdString(dir + "/acc.csv");
  const Result r = runAlgorithm(QStringLiteral("tinlod:accuracy"), {{"INPUT", QString::fromStdString(defaultDem())},
                                                                    {"HIERARCHY", hier},
                                                                    {"LEVEL", 0},
                                                                    {"VALID_RANGE", "None,None"},  // the dialog's "Not set"
                                                                    {"ACCURACY", raster},
                                                                    {"REPORT", report}});
  ASSERT_TRUE(r.ok) << r.error.toStdString();
  EXPECT_EQ(r.outputs.value("RMSE").toDouble(), 0.0);  // level 0 against itself
  EXPECT_NEAR(r.outputs.value("R_ELEVATION").toDouble(), 1.0, 1e-12);
  EXPECT_TRUE(fs::exists(raster.toStdString()));
  // A test grid too small for the surfaces is said in the dialog's names.
  RecordingFeedback small;
  const Result coarse = runAlgorithm(QStringLiteral("tinlod:accuracy"), {{"INPUT", QString::fromStdString(defaultDem())},
                                                                         {"HIERARCHY", hier},
                                                                         {"LEVEL", 0},
                                                                         {"STEP", 200}},
                                     &small);
  ASSERT_TRUE(coarse.ok) << coarse.error.toStdString();
  const QString warned = small.warnings.filter(QStringLiteral("too small for B-spline surfaces")).value(0);
  EXPECT_TRUE(warned.endsWith(QStringLiteral("give a smaller STEP or CONTROL_SPACING"))) << small.warnings.join('\n').toStdString();
  // COMPARE_INSERT: greedy insertion at each level's size fills the report's ratio column.
  const QString compared = QString::fromStdString(dir + "/compared.csv");
  const Result c = runAlgorithm(QStringLiteral("tinlod:accuracy"), {{"INPUT", QString::fromStdString(defaultDem())},
                                                                    {"HIERARCHY", hier},
                                                                    {"STEP", 3},
                                                                    {"COMPARE_INSERT", true},
                                                                    {"REPORT", compared}});
  ASSERT_TRUE(c.ok) << c.error.toStdString();
  std::istringstream csv(test::readFile(compared.toStdString()));
  std::string header, level0, level1;
  std::getline(csv, header), std::getline(csv, level0), std::getline(csv, level1);
  const auto field = [&](const std::string& line, const std::string& column) {
    std::vector<std::string> names, values;
    std::istringstream a(header), b(line + ",");
    for (std::string f; std::getline(a, f, ',');) names.push_back(f);
    for (std::string f; std::getline(b, f, ',');) values.push_back(f);
    const auto at = std::find(names.begin(), names.end(), column);
    return at == names.end() ? std::string("no such column") : values.at(static_cast<std::size_t>(at - names.begin()));
  };
  EXPECT_EQ(field(level0, "rmse_ratio_to_insert"), "");
  EXPECT_GT(std::stod(field(level1, "rmse_ratio_to_insert")), 0);
  const Result bad = runAlgorithm(QStringLiteral("tinlod:accuracy"), {{"INPUT", QString::fromStdString(defaultDem())},
                                                                      {"HIERARCHY", hier},
                                                                      {"REPORT", QString::fromStdString(dir + "/r.txt")},
                                                                      {"ACCURACY", QString::fromStdString(dir + "/b.tif")}});
  EXPECT_FALSE(bad.ok);
  EXPECT_TRUE(bad.error.contains("REPORT: unknown report format '.txt'")) << bad.error.toStdString();
  EXPECT_FALSE(fs::exists(dir + "/b.tif"));
}

// A batch row that leaves the optional accuracy raster empty gives it as an output definition
// of no path, "to load" when "Load layers on completion" is ticked: nothing to load, so
// nothing that QGIS would report as "not correctly generated".
TEST(Processing, AnAccuracyRasterLeftEmptyInABatchRowIsNotToLoad) {
  const std::string dir = test::tempDir();
  const QString hier = QString::fromStdString(dir + "/hier.gpkg");
  ASSERT_TRUE(builtDefaultHierarchy(hier));
  QgsProject project;
  const QVariant none = QVariant::fromValue(QgsProcessingOutputLayerDefinition(QString(), &project));
  const Result measured = runAlgorithm(QStringLiteral("tinlod:accuracy"),
                                       {{"INPUT", QString::fromStdString(defaultDem())}, {"HIERARCHY", hier}, {"ACCURACY", none},
                                        {"REPORT", QString::fromStdString(dir + "/batch.csv")}}, nullptr, &project);
  ASSERT_TRUE(measured.ok) << measured.error.toStdString();
  const Result built = runAlgorithm(QStringLiteral("tinlod:buildhierarchy"),
                                    {{"INPUT", QString::fromStdString(defaultDem())}, {"ACCURACY", none},
                                     {"OUTPUT", QString::fromStdString(dir + "/batch.gpkg")}}, nullptr, &project);
  ASSERT_TRUE(built.ok) << built.error.toStdString();
  for (const Result* r : {&measured, &built}) {
    const QStringList toLoad = r->context->layersToLoadOnCompletion().keys();
    for (const QString& path : toLoad) EXPECT_FALSE(path.isEmpty() || path.endsWith(".tif")) << path.toStdString();
  }
}

// QGIS asks before replacing a destination, but an input is never one: the DEM and the
// hierarchy stay as they were.
// As the dialog runs an algorithm with "Open output file after running": parameters read
// on the main thread (prepare), the work on another (QgsProcessingAlgRunnerTask), whose
// context's list of layers to load replaces the caller's. The accuracy raster must still
// load, on a single-band diverging ramp centred on zero.
TEST(Processing, AccuracyRasterLoadsStyledFromABackgroundRun) {
  const std::string dir = test::tempDir();
  const QString hier = QString::fromStdString(dir + "/bg_hier.gpkg");
  ASSERT_TRUE(builtDefaultHierarchy(hier));
  for (const QString id : {QStringLiteral("tinlod:accuracy"), QStringLiteral("tinlod:buildhierarchy")}) {
    const QString raster = QString::fromStdString(dir + "/bg_" + id.mid(7).toStdString() + ".tif");
    QgsProject project;
    QgsProcessingContext context;
    context.setProject(&project);
    QVariantMap parameters{{"INPUT", QString::fromStdString(defaultDem())},
                           {"ACCURACY", QVariant::fromValue(QgsProcessingOutputLayerDefinition(raster, &project))}};
    if (id == QStringLiteral("tinlod:accuracy")) parameters.insert("HIERARCHY", hier);
    else parameters.insert("OUTPUT", QString::fromStdString(dir + "/bg_built.gpkg")), parameters.insert("LOAD_LEVELS", false);
    std::unique_ptr<QgsProcessingAlgorithm> alg(QgsApplication::processingRegistry()->createAlgorithmById(id));
    RecordingFeedback feedback;
    ASSERT_TRUE(alg->prepare(parameters, context, &feedback)) << feedback.errors.toStdString();
    bool ok = false;
    std::thread worker([&] {
      try {
        alg->runPrepared(parameters, context, &feedback);
        ok = true;
      } catch (const QgsProcessingException& e) {
        feedback.errors += e.what();
      }
    });
    worker.join();
    ASSERT_TRUE(ok) << feedback.errors.toStdString();
    alg->postProcess(context, &feedback);  // the task's end, on the main thread: the lists are swapped here
    ASSERT_TRUE(context.willLoadLayerOnCompletion(raster)) << id.toStdString() << ": the raster would not be loaded";
    QgsProcessingContext::LayerDetails& details = context.layerToLoadOnCompletionDetails(raster);
    ASSERT_NE(details.postProcessor(), nullptr);
    EXPECT_EQ(details.name, QFileInfo(raster).completeBaseName());  // named after its file, as the TINs are
    auto* layer = new QgsRasterLayer(raster, details.name, QStringLiteral("gdal"));
    ASSERT_TRUE(layer->isValid());
    project.addMapLayer(layer);
    details.postProcessor()->postProcessLayer(layer, context, &feedback);
    auto* renderer = dynamic_cast<QgsSingleBandPseudoColorRenderer*>(layer->renderer());
    ASSERT_NE(renderer, nullptr) << id.toStdString() << ": " << layer->renderer()->type().toStdString();
    EXPECT_EQ(renderer->band(), 1);
    EXPECT_GT(renderer->classificationMax(), 0);
    EXPECT_EQ(renderer->classificationMin(), -renderer->classificationMax());
    EXPECT_EQ(layer->dataProvider()->generateBandName(1).isEmpty(), false);
    EXPECT_EQ(layer->bandName(1).contains(QStringLiteral("elevation difference")), true) << layer->bandName(1).toStdString();
  }
}

TEST(Processing, AccuracyNeverReplacesItsInputs) {
  const std::string dir = test::tempDir();
  const std::string dem = dir + "/dem.tif";
  fs::copy_file(defaultDem(), dem);
  const QString hier = QString::fromStdString(dir + "/hier.gpkg");
  ASSERT_TRUE(runAlgorithm(QStringLiteral("tinlod:buildhierarchy"),
                           {{"INPUT", QString::fromStdString(dem)}, {"LOAD_LEVELS", false}, {"OUTPUT", hier}}).ok);
  const std::string demBytes = test::readFile(dem), hierBytes = test::readFile(hier.toStdString());
  for (const QString& target : {QString::fromStdString(dem), hier}) {
    const Result r = runAlgorithm(QStringLiteral("tinlod:accuracy"),
                                  {{"INPUT", QString::fromStdString(dem)}, {"HIERARCHY", hier}, {"ACCURACY", target}});
    EXPECT_FALSE(r.ok);
    EXPECT_TRUE(r.error.contains("is an input of this run")) << r.error.toStdString();
  }
  EXPECT_EQ(test::readFile(dem), demBytes);
  EXPECT_EQ(test::readFile(hier.toStdString()), hierBytes);
}

TEST(Processing, GreedyInsertionMatchesTheCoreAndNamesBadParameters) {
  const QString out = QString::fromStdString(test::tempDir() + "/insert.gpkg");
  const Result r = runAlgorithm(QStringLiteral("tinlod:greedyinsertion"),
                                {{"INPUT", QString::fromStdString(defaultDem())}, {"MAX_ERROR", 2.5}, {"OUTPUT", out}});
  ASSERT_TRUE(r.ok) << r.error.toStdString();
  InsertOptions o;
  o.maxError = 2.5;
  const InsertedTin core = greedyInsertionTin(readDem(defaultDem(), 1, ProgressRange(Feedback{}, 0, 1)), o,
                                              ProgressRange(Feedback{}, 0, 1));
  EXPECT_EQ(r.outputs.value("VERTICES").toLongLong(), static_cast<long long>(core.tin.vertices.size()));
  EXPECT_EQ(featureCount(out, "triangles"), static_cast<long long>(core.tin.triangles.size()));
  EXPECT_DOUBLE_EQ(r.outputs.value("MAX_ERROR").toDouble(), core.summary.measuredMaxError);
  EXPECT_LE(r.outputs.value("MAX_ERROR").toDouble(), 2.5);
  EXPECT_GT(r.outputs.value("RMSE").toDouble(), 0);

  // A vertex count alone stops at exactly that count; an empty MAX_ERROR sets no tolerance then.
  const QString counted = QString::fromStdString(test::tempDir() + "/counted.gpkg");
  const Result c = runAlgorithm(QStringLiteral("tinlod:greedyinsertion"), {{"INPUT", QString::fromStdString(defaultDem())},
                                                                            {"MAX_VERTICES", 777},
                                                                            {"CANDIDATES", 1},
                                                                            {"OUTPUT", counted}});
  ASSERT_TRUE(c.ok) << c.error.toStdString();
  EXPECT_EQ(c.outputs.value("VERTICES").toLongLong(), 777);
  // The vertices' spatial index only when VERTEX_INDEX asks for it.
  const std::string indexQuery = "SELECT count(*) FROM sqlite_master WHERE name = 'rtree_vertices_geom'";
  EXPECT_EQ(sqlCount(out.toStdString(), indexQuery), 0);
  const QString indexed = QString::fromStdString(test::tempDir() + "/indexed.gpkg");
  ASSERT_TRUE(runAlgorithm(QStringLiteral("tinlod:greedyinsertion"), {{"INPUT", QString::fromStdString(defaultDem())},
                                                                       {"MAX_ERROR", 2.5},
                                                                       {"VERTEX_INDEX", true},
                                                                       {"OUTPUT", indexed}})
                  .ok);
  EXPECT_EQ(sqlCount(indexed.toStdString(), indexQuery), 1);

  const Result text = runAlgorithm(QStringLiteral("tinlod:greedyinsertion"), {{"INPUT", QString::fromStdString(defaultDem())},
                                                                               {"MAX_ERROR", QStringLiteral("abc")},
                                                                               {"OUTPUT", out + "y"}});
  EXPECT_FALSE(text.ok);  // not read as 0, an exact TIN
  EXPECT_TRUE(text.error.contains("MAX_ERROR")) << text.error.toStdString();
  const Result bad = runAlgorithm(QStringLiteral("tinlod:greedyinsertion"), {{"INPUT", QString::fromStdString(defaultDem())},
                                                                              {"MAX_VERTICES", 2},
                                                                              {"OUTPUT", out + "x"}});
  EXPECT_FALSE(bad.ok);
  EXPECT_TRUE(bad.error.contains("MAX_VERTICES")) << bad.error.toStdString();
}

TEST(Processing, ExtractLodMatchesTheCommandLineCoreAndNamesMissingTests) {
  const std::string dir = test::tempDir();
  ASSERT_TRUE(runAlgorithm(QStringLiteral("tinlod:buildhierarchy"),
                           {{"INPUT", QString::fromStdString(defaultDem())}, {"OUTPUT", QString::fromStdString(dir + "/h.gpkg")}})
                  .ok);
  const QString out = QString::fromStdString(dir + "/lod.gpkg");
  const Result r = runAlgorithm(QStringLiteral("tinlod:extractlod"),
                                {{"HIERARCHY", QString::fromStdString(dir + "/h.gpkg")},
                                 {"CENTER", QStringLiteral("404500,5203750 [EPSG:32632]")},
                                 {"DROPOFF", 200},
                                 {"OUTPUT", out}});
  ASSERT_TRUE(r.ok) << r.error.toStdString();
  LodJobOptions o;
  o.lod.centres = {{404500, 5203750}};
  o.lod.dropoff = 200;
  const LodSummary core = runLodJob(dir + "/h.gpkg", dir + "/core.gpkg", o, false, Feedback{});
  EXPECT_EQ(r.outputs.value("TRIANGLES").toLongLong(), static_cast<long long>(core.triangles));
  EXPECT_EQ(featureCount(out, "triangles"), static_cast<long long>(core.triangles));
  EXPECT_LT(core.triangles, core.levelZeroTriangles);
  const Result none = runAlgorithm(QStringLiteral("tinlod:extractlod"),
                                   {{"HIERARCHY", QString::fromStdString(dir + "/h.gpkg")}, {"OUTPUT", out + "x"}});
  EXPECT_FALSE(none.ok);
  EXPECT_TRUE(none.error.contains("DROPOFF")) << none.error.toStdString();
  // The core's option names come out as the parameters the user set.
  const Result growth = runAlgorithm(QStringLiteral("tinlod:extractlod"),
                                     {{"HIERARCHY", QString::fromStdString(dir + "/h.gpkg")},
                                      {"CENTER", QStringLiteral("404500,5203750 [EPSG:32632]")},
                                      {"DROPOFF", 200},
                                      {"ERROR_GROWTH", 0.01},
                                      {"OUTPUT", out + "y"}});
  EXPECT_FALSE(growth.ok);
  EXPECT_TRUE(growth.error.contains("ERROR_GROWTH needs MAX_ERROR")) << growth.error.toStdString();
}

// HIERARCHY as a level layer already on the map (by its id, as the dialog's layer list
// gives it) works as the file does; a layer not in a GeoPackage is refused by name.
TEST(Processing, HierarchyIsAFileOrALoadedLayerOfIt) {
  const std::string dir = test::tempDir();
  const QString hier = QString::fromStdString(dir + "/layer_h.gpkg");
  ASSERT_TRUE(builtDefaultHierarchy(hier));
  QgsProject project;
  auto* level = new QgsVectorLayer(hier + QStringLiteral("|layername=level_2"), QStringLiteral("level_2"), QStringLiteral("ogr"));
  auto* scratch = new QgsVectorLayer(QStringLiteral("Point?crs=EPSG:32632"), QStringLiteral("scratch"), QStringLiteral("memory"));
  ASSERT_TRUE(level->isValid());
  project.addMapLayers({level, scratch});
  const QString points = hier + QStringLiteral("|layername=vertices");
  auto locate = [&](const QVariant& hierarchy, const QString& out) {
    return runAlgorithm(QStringLiteral("tinlod:locate"),
                        {{"INPUT", points}, {"HIERARCHY", hierarchy}, {"LEVEL", 0}, {"OUTPUT", out}}, nullptr, &project);
  };
  const Result byFile = locate(hier, QString::fromStdString(dir + "/by_file.gpkg"));
  const Result byLayer = locate(level->id(), QString::fromStdString(dir + "/by_layer.gpkg"));
  ASSERT_TRUE(byFile.ok) << byFile.error.toStdString();
  ASSERT_TRUE(byLayer.ok) << byLayer.error.toStdString();
  EXPECT_GT(byLayer.outputs.value("LOCATED").toLongLong(), 1000);
  EXPECT_EQ(byLayer.outputs.value("LOCATED"), byFile.outputs.value("LOCATED"));
  const Result bad = locate(scratch->id(), QString::fromStdString(dir + "/bad_layer.gpkg"));
  EXPECT_FALSE(bad.ok);
  EXPECT_TRUE(bad.error.contains("HIERARCHY: 'scratch' is not stored in a GeoPackage")) << bad.error.toStdString();
  // A level file of a tinlod tiles catalogue (<stem>_levels/level_K.vrt): the catalogue is named.
  std::filesystem::create_directories(dir + "/job_levels");
  std::ofstream(dir + "/job_levels/level_2.vrt")
      << "<OGRVRTDataSource><OGRVRTLayer name=\"level_2\"><SrcDataSource>" << hier.toStdString()
      << "</SrcDataSource><SrcLayer>level_2</SrcLayer></OGRVRTLayer></OGRVRTDataSource>";
  const Result ofCatalogue = locate(QString::fromStdString(dir + "/job_levels/level_2.vrt"),
                                    QString::fromStdString(dir + "/by_vrt.gpkg"));
  EXPECT_FALSE(ofCatalogue.ok);
  EXPECT_TRUE(ofCatalogue.error.contains("is one level of a tinlod tiles catalogue: choose the catalogue itself, " +
                                         QString::fromStdString(dir) + "/job.gpkg"))
      << ofCatalogue.error.toStdString();
}

TEST(Processing, LocateAddsElevationsAsTheCoreDoes) {
  const std::string dir = test::tempDir();
  ASSERT_TRUE(runAlgorithm(QStringLiteral("tinlod:buildhierarchy"),
                           {{"INPUT", QString::fromStdString(defaultDem())}, {"OUTPUT", QString::fromStdString(dir + "/h.gpkg")}})
                  .ok);
  // Points stored in a file: the vertices of the hierarchy itself, each on level 0's TIN.
  const QString points = QString::fromStdString(dir + "/h.gpkg|layername=vertices");
  const QString out = QString::fromStdString(dir + "/located.gpkg");
  const Result r = runAlgorithm(QStringLiteral("tinlod:locate"), {{"INPUT", points},
                                                                  {"HIERARCHY", QString::fromStdString(dir + "/h.gpkg")},
                                                                  {"LEVEL", 0},
                                                                  {"OUTPUT", out}});
  ASSERT_TRUE(r.ok) << r.error.toStdString();
  EXPECT_GT(r.outputs.value("POINTS").toLongLong(), 1000);
  EXPECT_EQ(r.outputs.value("LOCATED").toLongLong(), r.outputs.value("POINTS").toLongLong());
  EXPECT_EQ(featureCount(out, "points"), r.outputs.value("POINTS").toLongLong());
  // Each point is a vertex of level 0: its elevation is the vertex's own height.
  QgsVectorLayer located(out + "|layername=points", QStringLiteral("points"), QStringLiteral("ogr"));
  ASSERT_TRUE(located.isValid());
  QgsFeature f;
  std::size_t checked = 0, wrong = 0;
  for (QgsFeatureIterator it = located.getFeatures(); it.nextFeature(f); ++checked) {
    const QgsPoint* p = qgsgeometry_cast<const QgsPoint*>(f.geometry().constGet());
    wrong += !p || f.attribute(QStringLiteral("elevation")).isNull() ||
             std::fabs(f.attribute(QStringLiteral("elevation")).toDouble() - p->z()) > 1e-6;
  }
  EXPECT_EQ(checked, std::size_t(r.outputs.value("POINTS").toLongLong()));
  EXPECT_EQ(wrong, 0u);
  const Result bad = runAlgorithm(QStringLiteral("tinlod:locate"), {{"INPUT", points},
                                                                    {"HIERARCHY", QString::fromStdString(dir + "/h.gpkg")},
                                                                    {"LEVEL", 99},
                                                                    {"OUTPUT", QString::fromStdString(dir + "/bad.gpkg")}});
  EXPECT_FALSE(bad.ok);
  EXPECT_TRUE(bad.error.contains("LEVEL 99 does not exist") && !bad.error.contains("-level")) << bad.error.toStdString();
}

// The core names the lines by the command line's operand (LINES); QGIS by its parameter.
TEST(Processing, LinesErrorsNameTheInputParameter) {
  const std::string dir = test::tempDir();
  std::ofstream(dir + "/p.geojson") << R"({"type": "FeatureCollection", "crs": {"type": "name", "properties": {"name": "urn:ogc:def:crs:EPSG::32632"}},
 "features": [{"type": "Feature", "properties": {}, "geometry": {"type": "Point", "coordinates": [0, 0]}}]})";
  for (const char* id : {"tinlod:dpvalues", "tinlod:concavity"}) {
    const Result r = runAlgorithm(QString::fromUtf8(id), {{"INPUT", QString::fromStdString(dir + "/p.geojson")},
                                                          {"WINDOW", 10},
                                                          {"OUTPUT", QString::fromStdString(dir + "/out.gpkg")}});
    ASSERT_FALSE(r.ok) << id;
    EXPECT_TRUE(r.error.contains(QStringLiteral("INPUT: "))) << r.error.toStdString();
    EXPECT_FALSE(r.error.contains(QStringLiteral("LINES"))) << r.error.toStdString();
  }
}

TEST(Processing, DpValuesMatchTheCoreAndCountCrossings) {
  const std::string dir = test::tempDir();
  std::ofstream(dir + "/l.geojson") << R"({"type": "FeatureCollection", "crs": {"type": "name", "properties": {"name": "urn:ogc:def:crs:EPSG::32632"}},
 "features": [{"type": "Feature", "properties": {}, "geometry": {"type": "LineString", "coordinates": [[0, 0], [5, 4], [10, 0]]}},
              {"type": "Feature", "properties": {}, "geometry": {"type": "LineString", "coordinates": [[0, 1], [5, 4.5], [10, 1]]}}]})";
  const QString out = QString::fromStdString(dir + "/dp.gpkg");
  const Result r = runAlgorithm(QStringLiteral("tinlod:dpvalues"), {{"INPUT", QString::fromStdString(dir + "/l.geojson")},
                                                                    {"THRESHOLD", 3.7},
                                                                    {"POINTS", true},
                                                                    {"OUTPUT", out}});
  ASSERT_TRUE(r.ok) << r.error.toStdString();
  EXPECT_EQ(r.outputs.value("LINES").toLongLong(), 2);
  EXPECT_EQ(r.outputs.value("VERTICES").toLongLong(), 6);
  // The lower peak (value 4) outlives 3.7, the upper one (3.5) does not: its chord cuts the
  // lower peak twice.
  EXPECT_EQ(r.outputs.value("CROSSINGS").toLongLong(), 2);
  EXPECT_EQ(featureCount(out, "vertices"), 6);
  // Every layer written is loaded: the lines, the simplified lines and the vertices.
  for (const char* layer : {"lines", "simplified", "vertices"})
    EXPECT_TRUE(r.context->willLoadLayerOnCompletion(out + "|layername=" + layer)) << layer;
  const Result cut = runAlgorithm(QStringLiteral("tinlod:dpvalues"), {{"INPUT", QString::fromStdString(dir + "/l.geojson")},
                                                                      {"THRESHOLD", 4.5},
                                                                      {"OUTPUT", QString::fromStdString(dir + "/dp2.gpkg")}});
  ASSERT_TRUE(cut.ok) << cut.error.toStdString();
  EXPECT_EQ(cut.outputs.value("CROSSINGS").toLongLong(), 0);  // both chords: parallel
}

// The fixes the core's messages give as commands ("make one with tinlod build") are named as a
// QGIS user makes them.
TEST(Processing, MessagesGiveFixesAsAQgisUserMakesThem) {
  const std::string dir = test::tempDir();
  const QString tin = QString::fromStdString(dir + "/tin.gpkg");
  ASSERT_TRUE(runAlgorithm(QStringLiteral("tinlod:sampletin"), {{"INPUT", QString::fromStdString(defaultDem())}, {"OUTPUT", tin}}).ok);
  const Result lod = runAlgorithm(QStringLiteral("tinlod:extractlod"), {{"HIERARCHY", tin},
                                                                      {"MAX_ERROR", 5},
                                                                      {"OUTPUT", QString::fromStdString(dir + "/lod.gpkg")}});
  ASSERT_FALSE(lod.ok);
  EXPECT_TRUE(lod.error.contains("not a hierarchy: make one with Build TIN hierarchy from DEM")) << lod.error.toStdString();

  std::ofstream(dir + "/l.geojson") << R"({"type": "FeatureCollection", "crs": {"type": "name", "properties": {"name": "urn:ogc:def:crs:EPSG::32632"}},
 "features": [{"type": "Feature", "properties": {}, "geometry": {"type": "LineString", "coordinates": [[0, 0], [5, 4], [10, 0]]}}]})";
  const QString dp = QString::fromStdString(dir + "/dp.gpkg");
  ASSERT_TRUE(runAlgorithm(QStringLiteral("tinlod:dpvalues"), {{"INPUT", QString::fromStdString(dir + "/l.geojson")}, {"OUTPUT", dp}}).ok);
  const Result into = runAlgorithm(QStringLiteral("tinlod:sampletin"), {{"INPUT", QString::fromStdString(defaultDem())}, {"OUTPUT", dp}});
  ASSERT_FALSE(into.ok);
  EXPECT_TRUE(into.error.contains("writing into an existing GeoPackage replaces the layers of the same kind")) << into.error.toStdString();
  const Result locate = runAlgorithm(QStringLiteral("tinlod:locate"), {{"INPUT", QString::fromStdString(dir + "/l.geojson")},
                                                                     {"HIERARCHY", dp},
                                                                     {"OUTPUT", QString::fromStdString(dir + "/located.gpkg")}});
  ASSERT_FALSE(locate.ok);
  EXPECT_TRUE(locate.error.contains("(of Douglas-Peucker simplification values, Polyline concavity or TIN elevation at points), "
                                    "not a TIN or a hierarchy: add it to the map as it is"))
      << locate.error.toStdString();
  // The world in Mollweide: triangles turn over; the warp is QGIS's, not "gdalwarp TARGET_CRS".
  const Result world = runAlgorithm(QStringLiteral("tinlod:greedyinsertion"),
                                    {{"INPUT", QString::fromStdString(test::polarDemFile("world.tif", -180, 360, 180, 1.0))},
                                     {"TARGET_CRS", QStringLiteral("ESRI:54009")},
                                     {"MAX_ERROR", 30},
                                     {"OUTPUT", QString::fromStdString(dir + "/world.gpkg")}});
  ASSERT_FALSE(world.ok);
  EXPECT_TRUE(world.error.contains("warp the DEM to a projected CRS first (Raster > Projections > Warp (Reproject))"))
      << world.error.toStdString();
  for (const Result* r : {&lod, &into, &locate, &world})
    for (const char* command : {"tinlod build", "tinlod lines", "ogrinfo", "-overwrite", "gdalwarp"})
      EXPECT_FALSE(r->error.contains(QString::fromUtf8(command))) << r->error.toStdString();

  // A file tinlod did not write as the hierarchy, and points QGIS writes to a file of its own
  // for the run (a memory layer): the messages name HIERARCHY and INPUT, not QGIS's file.
  QgsProject project;
  const QString region = QString::fromStdString(dir + "/l.geojson");
  ASSERT_TRUE(runAlgorithm(QStringLiteral("tinlod:sampletin"), {{"INPUT", QString::fromStdString(defaultDem())},
                                                                {"OUTPUT", tin}}).ok);
  ASSERT_EQ(std::system(("ogr2ogr -q -f GPKG " + dir + "/plain.gpkg " + dir + "/l.geojson").c_str()), 0);
  const Result notOurs = runAlgorithm(QStringLiteral("tinlod:locate"),
                                      {{"INPUT", region}, {"HIERARCHY", QString::fromStdString(dir + "/plain.gpkg")},
                                       {"OUTPUT", QString::fromStdString(dir + "/x.gpkg")}});
  ASSERT_FALSE(notOurs.ok);
  EXPECT_TRUE(notOurs.error.startsWith("HIERARCHY: '" + QString::fromStdString(dir) + "/plain.gpkg' was not written by tinlod"))
      << notOurs.error.toStdString();
  auto* points = new QgsVectorLayer(QStringLiteral("MultiPoint?crs=EPSG:32632"), QStringLiteral("my points"), QStringLiteral("memory"));
  QgsFeature twoPoints(points->fields());
  twoPoints.setGeometry(QgsGeometry::fromWkt(QStringLiteral("MultiPoint((500 500), (600 600))")));
  points->dataProvider()->addFeatures(QgsFeatureList() << twoPoints);
  project.addMapLayer(points);
  const Result multi = runAlgorithm(QStringLiteral("tinlod:locate"), {{"INPUT", points->id()}, {"HIERARCHY", tin},
                                                                    {"OUTPUT", QString::fromStdString(dir + "/x.gpkg")}},
                                    nullptr, &project);
  ASSERT_FALSE(multi.ok);
  EXPECT_TRUE(multi.error.startsWith("INPUT: feature 1 of INPUT is a multipoint")) << multi.error.toStdString();
  EXPECT_FALSE(multi.error.contains(QgsProcessingUtils::tempFolder())) << multi.error.toStdString();
}

// QGIS asks a CRS for a file without one, or the user assigns it in Layer Properties: that
// CRS is the DEM's, as -s_srs is on the command line (a user trial found it ignored, while
// the errors told them to assign it).
TEST(Processing, TheCrsAssignedToTheLayerIsTheDems) {
  const std::string dir = test::tempDir();
  const QString dem = QString::fromStdString(test::degreesWithoutCrs(dir));
  const Result asFile = runAlgorithm(QStringLiteral("tinlod:sampletin"), {{"INPUT", dem}, {"OUTPUT", QString::fromStdString(dir + "/a.gpkg")}});
  ASSERT_FALSE(asFile.ok);
  EXPECT_TRUE(asFile.error.contains("assign the layer's CRS, EPSG:4326 (Layer Properties > Source)")) << asFile.error.toStdString();
  EXPECT_FALSE(asFile.error.contains("-s_srs")) << asFile.error.toStdString();
  QgsProject project;
  auto* layer = new QgsRasterLayer(dem, QStringLiteral("no crs"), QStringLiteral("gdal"));
  ASSERT_TRUE(layer->isValid());
  EXPECT_FALSE(layer->dataProvider()->crs().isValid());
  layer->setCrs(QgsCoordinateReferenceSystem(QStringLiteral("EPSG:4326")));
  project.addMapLayer(layer);
  const QString tin = QString::fromStdString(dir + "/tin.gpkg");
  const Result assigned = runAlgorithm(QStringLiteral("tinlod:sampletin"), {{"INPUT", layer->id()}, {"OUTPUT", tin}}, nullptr, &project);
  ASSERT_TRUE(assigned.ok) << assigned.error.toStdString();
  QgsVectorLayer triangles(tin + QStringLiteral("|layername=triangles"), QStringLiteral("t"), QStringLiteral("ogr"));
  EXPECT_EQ(triangles.crs().authid(), QStringLiteral("EPSG:32613"));  // UTM zone 13N, at 105.3 W
}

// The core's messages in the dialog's terms: its options are the parameters (a user trial
// found -report, -of and threshold in QGIS's log).
TEST(Processing, ErrorsNameTheDialogsParameters) {
  const std::string dir = test::tempDir();
  const QString dem = QString::fromStdString(defaultDem());
  const auto build = [&](const QVariantMap& more) {
    QVariantMap p{{"INPUT", dem}, {"LOAD_LEVELS", false}, {"OUTPUT", QString::fromStdString(dir + "/h.gpkg")}};
    for (auto it = more.begin(); it != more.end(); ++it) p[it.key()] = it.value();
    return runAlgorithm(QStringLiteral("tinlod:buildhierarchy"), p);
  };
  const std::vector<std::pair<QVariantMap, QString>> cases{
      {{{"THRESHOLD", -5}}, "THRESHOLD must be more than 0 (got -5)"},
      {{{"REPORT", QString::fromStdString(dir + "/r.txt")}}, "REPORT: unknown report format '.txt'"},
      {{{"ACCURACY", QString::fromStdString(dir + "/a.png")}}, "ACCURACY: PNG cannot hold the accuracy raster (4 bands of 32-bit floats)"},
      {{{"ACCURACY", QString::fromStdString(dir + "/a.foo")}}, "ACCURACY: no GDAL raster format is named by the extension '.foo'"},
      {{{"OUTPUT", dem}}, "OUTPUT: '"},
      {{{"INPUT", QString::fromStdString(dir + "/huge.vrt")}}, "of memory and swap this run may use: cut it into tiles with tinlod tiles "
                                                               "(memory bounded by the tile)"}};
  std::ofstream(dir + "/huge.vrt") << "<VRTDataset rasterXSize=\"2000000\" rasterYSize=\"2000000\"><SRS>EPSG:32632</SRS>"
                                      "<GeoTransform>400000, 1, 0, 5300000, 0, -1</GeoTransform><VRTRasterBand "
                                      "dataType=\"Float32\" band=\"1\"/></VRTDataset>";
  for (const auto& [more, said] : cases) {
    const Result r = build(more);
    EXPECT_FALSE(r.ok);
    EXPECT_TRUE(r.error.contains(said)) << r.error.toStdString();
    for (const char* option : {"-report", "-of", "-threshold", "-accuracy", "-block"})
      EXPECT_FALSE(r.error.contains(QString::fromUtf8(option) + QLatin1Char(' '))) << r.error.toStdString();
  }
  EXPECT_FALSE(fs::exists(dir + "/h.gpkg"));
  EXPECT_FALSE(fs::exists(dir + "/a.png"));
  // Against a GeoPackage, an empty BAND is the band it was sampled from: it has no default.
  std::unique_ptr<QgsProcessingAlgorithm> accuracy(
      QgsApplication::processingRegistry()->createAlgorithmById(QStringLiteral("tinlod:accuracy")));
  EXPECT_FALSE(accuracy->parameterDefinition(QStringLiteral("BAND"))->defaultValue().isValid());
}

// Every other vector input from a memory layer, as from a file: the same results.
TEST(Processing, MemoryLayersServeAsEveryVectorInput) {
  const std::string dir = test::tempDir();
  QgsProject project;
  auto run = [&](const QString& id, const QVariantMap& parameters) { return runAlgorithm(id, parameters, nullptr, &project); };
  auto memory = [&](const QString& uri, const QStringList& wkts) {
    auto* layer = new QgsVectorLayer(uri, QStringLiteral("scratch"), QStringLiteral("memory"));
    QgsFeatureList features;
    for (const QString& wkt : wkts) {
      QgsFeature f(layer->fields());
      f.setGeometry(QgsGeometry::fromWkt(wkt));
      features << f;
    }
    layer->dataProvider()->addFeatures(features);
    project.addMapLayer(layer);
    return layer->id();
  };
  // dpvalues: the two lines of DpValuesMatchTheCoreAndCountCrossings.
  const Result dp = run(QStringLiteral("tinlod:dpvalues"),
                        {{"INPUT", memory(QStringLiteral("LineString?crs=EPSG:32632"),
                                          {QStringLiteral("LINESTRING(0 0, 5 4, 10 0)"), QStringLiteral("LINESTRING(0 1, 5 4.5, 10 1)")})},
                         {"THRESHOLD", 3.7}, {"OUTPUT", QString::fromStdString(dir + "/mem_dp.gpkg")}});
  ASSERT_TRUE(dp.ok) << dp.error.toStdString();
  EXPECT_EQ(dp.outputs.value("CROSSINGS").toLongLong(), 2);
  // locate, extractlod's CENTERS and REGION: a hierarchy of the default DEM.
  const QString hier = QString::fromStdString(dir + "/mem_h.gpkg");
  ASSERT_TRUE(run(QStringLiteral("tinlod:buildhierarchy"),
                  {{"INPUT", QString::fromStdString(defaultDem())}, {"LOAD_LEVELS", false}, {"OUTPUT", hier}}).ok);
  const Result located = run(QStringLiteral("tinlod:locate"),
                             {{"INPUT", memory(QStringLiteral("Point?crs=EPSG:32632"),
                                               {QStringLiteral("POINT(404500 5203750)"), QStringLiteral("POINT(404400 5203700)")})},
                              {"HIERARCHY", hier}, {"OUTPUT", QString::fromStdString(dir + "/mem_located.gpkg")}});
  ASSERT_TRUE(located.ok) << located.error.toStdString();
  EXPECT_EQ(located.outputs.value("POINTS").toLongLong(), 2);
  EXPECT_EQ(located.outputs.value("LOCATED").toLongLong(), 2);
  const Result centres = run(QStringLiteral("tinlod:extractlod"),
                             {{"HIERARCHY", hier},
                              {"CENTERS", memory(QStringLiteral("Point?crs=EPSG:32632"), {QStringLiteral("POINT(404500 5203750)")})},
                              {"DROPOFF", 200}, {"OUTPUT", QString::fromStdString(dir + "/mem_lod.gpkg")}});
  const Result centre = run(QStringLiteral("tinlod:extractlod"),
                            {{"HIERARCHY", hier}, {"CENTER", QStringLiteral("404500,5203750 [EPSG:32632]")}, {"DROPOFF", 200},
                             {"OUTPUT", QString::fromStdString(dir + "/point_lod.gpkg")}});
  ASSERT_TRUE(centres.ok) << centres.error.toStdString();
  ASSERT_TRUE(centre.ok) << centre.error.toStdString();
  EXPECT_EQ(centres.outputs.value("TRIANGLES"), centre.outputs.value("TRIANGLES"));
  const Result region = run(QStringLiteral("tinlod:extractlod"),
                            {{"HIERARCHY", hier},
                             {"REGION", memory(QStringLiteral("Polygon?crs=EPSG:32632"),
                                               {QStringLiteral("POLYGON((404300 5203500, 404700 5203500, 404700 5203900, 404300 5203900, 404300 5203500))")})},
                             {"OUTPUT", QString::fromStdString(dir + "/mem_region.gpkg")}});
  ASSERT_TRUE(region.ok) << region.error.toStdString();
  EXPECT_GT(region.outputs.value("TRIANGLES").toLongLong(), 0);
}

TEST(Processing, ConcavityAgreesWithTheCore) {
  const std::string dir = test::tempDir();
  std::ofstream(dir + "/l.geojson") << R"({"type": "FeatureCollection", "crs": {"type": "name", "properties": {"name": "urn:ogc:def:crs:EPSG::32632"}},
 "features": [{"type": "Feature", "properties": {}, "geometry": {"type": "LineString", "coordinates": [[0, 0], [10, 0], [20, 0], [30, 5], [40, 0], [50, 0], [60, 0]]}}]})";
  const Result r = runAlgorithm(QStringLiteral("tinlod:concavity"), {{"INPUT", QString::fromStdString(dir + "/l.geojson")},
                                                                     {"WINDOW", 12},
                                                                     {"OUTPUT", QString::fromStdString(dir + "/c.gpkg")}});
  ASSERT_TRUE(r.ok) << r.error.toStdString();
  ConcavityOptions o;
  o.window = 12;
  const ConcavitySummary core = runConcavityJob(dir + "/l.geojson", dir + "/core.gpkg", o, false, Feedback{});
  EXPECT_EQ(r.outputs.value("VERTICES").toLongLong(), 7);
  EXPECT_EQ(r.outputs.value("CONVEX").toLongLong(), static_cast<long long>(core.convex));
  EXPECT_EQ(r.outputs.value("CONCAVE").toLongLong(), static_cast<long long>(core.concave));
  EXPECT_GE(core.convex, 1u);  // the bump to the left
  EXPECT_EQ(featureCount(QString::fromStdString(dir + "/c.gpkg"), "vertices"), 7);

  // The parts load coloured by class, the three classes in the legend.
  QgsProject project;
  loadAsQgisDoes(*r.context, project);
  const QList<QgsMapLayer*> parts = project.mapLayersByName(QStringLiteral("concavity parts"));
  ASSERT_EQ(parts.size(), 1);
  auto* renderer = dynamic_cast<QgsCategorizedSymbolRenderer*>(qobject_cast<QgsVectorLayer*>(parts[0])->renderer());
  ASSERT_NE(renderer, nullptr) << "parts in one colour";
  EXPECT_EQ(renderer->classAttribute(), QStringLiteral("class"));
  QStringList classes;
  QSet<QRgb> colours;
  for (const QgsRendererCategory& c : renderer->categories()) {
    classes << c.value().toString();
    colours << c.symbol()->color().rgb();
  }
  EXPECT_EQ(classes, QStringList({"convex", "straight", "concave"}));
  EXPECT_EQ(colours.size(), 3);
  QgsFeature part;
  QgsFeatureIterator it = qobject_cast<QgsVectorLayer*>(parts[0])->getFeatures();
  while (it.nextFeature(part))
    EXPECT_TRUE(classes.contains(part.attribute(QStringLiteral("class")).toString())) << "a class the style does not show";
}

TEST(Processing, RealDemRuns) {
  const std::string dir = test::dataDir();
  if (dir.empty()) GTEST_SKIP() << "../shared/data is absent (set TINLOD_TEST_DATA): real-DEM run skipped";
  const QString out = QString::fromStdString(test::tempDir() + "/vancouver.gpkg");
  const Result r = runAlgorithm(QStringLiteral("tinlod:sampletin"),
                                {{"INPUT", QString::fromStdString(dir + "/vancouver_N49W123.tif")}, {"OUTPUT", out}});
  ASSERT_TRUE(r.ok) << r.error.toStdString();
  QgsVectorLayer layer(out + "|layername=triangles", "t", QStringLiteral("ogr"));
  EXPECT_EQ(layer.crs().authid(), QStringLiteral("EPSG:32610"));
  EXPECT_EQ(layer.featureCount(), r.outputs.value("TRIANGLES").toLongLong());
}

}  // namespace
}  // namespace tinlod

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  if (::testing::GTEST_FLAG(list_tests)) return RUN_ALL_TESTS();  // test discovery: no QGIS needed
  // QGIS computes approximate statistics of a raster layer; without this GDAL would leave
  // them as .aux.xml beside the real DEMs in ../shared/data.
  setenv("GDAL_PAM_ENABLED", "NO", 1);
  QgsApplication app(argc, argv, false);
  QgsApplication::init();
  QgsApplication::initQgis();
  QgsApplication::processingRegistry()->addProvider(new QgsNativeAlgorithms(QgsApplication::processingRegistry()));
  if (!tinlod_register_provider()) return 2;
  const int result = RUN_ALL_TESTS();
  tinlod_unregister_provider();
  QgsApplication::exitQgis();
  return result;
}
