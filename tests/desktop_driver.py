# SPDX-License-Identifier: GPL-3.0-or-later
"""Drives the real QGIS desktop as a user would, for tests/desktop_test.sh.

Run by `qgis --code`, inside the desktop's own Python. It installs the plugin zip with
QGIS's plugin installer, opens every tinlod algorithm from the Processing toolbox, fills
its dialog, presses Run, waits for the task, and checks what came onto the map. The
verdicts go to a JSON file the shell script reads; QGIS then quits.

The scenario is a generator stepped by a timer: the toolbox opens a dialog with exec_(),
a nested event loop that only timers can reach, so nothing here may block.

Environment (set by desktop_test.sh): TINLOD_DESKTOP_ZIP, TINLOD_DESKTOP_WORK (inputs:
dem.tif, contours.gpkg; outputs are written there), TINLOD_DESKTOP_ARTEFACTS (map.png,
window.png, dialog logs), TINLOD_DESKTOP_RESULT (the JSON file).
"""

import json
import os
import time
import traceback

from qgis.core import (
    Qgis,
    QgsApplication,
    QgsLayerTreeGroup,
    QgsLayerTreeLayer,
    QgsMapLayerType,
    QgsProject,
    QgsProviderRegistry,
    QgsSettings,
    QgsSingleBandPseudoColorRenderer,
    QgsSingleSymbolRenderer,
    QgsVectorLayer,
    QgsWkbTypes,
)
from qgis.PyQt import sip
from qgis.PyQt.QtCore import QPoint, Qt, QTimer
from qgis.PyQt.QtGui import QImage
from qgis.PyQt.QtTest import QTest
from qgis.PyQt.QtWidgets import QApplication, QCheckBox, QDialog, QDialogButtonBox, QLabel, QMessageBox, QTextEdit
from qgis.utils import iface

ZIP = os.environ["TINLOD_DESKTOP_ZIP"]
WORK = os.environ["TINLOD_DESKTOP_WORK"]
ARTEFACTS = os.environ["TINLOD_DESKTOP_ARTEFACTS"]
RESULT = os.environ["TINLOD_DESKTOP_RESULT"]
ALGORITHMS = ["sampletin", "buildhierarchy", "greedyinsertion", "accuracy", "extractlod", "locate", "dpvalues", "concavity"]
RUN_TIMEOUT_S = 240
# Within desktop_test.sh's own limit, so that a hang still ends with the verdicts written.
SCENARIO_TIMEOUT_S = 480

# The styles of processing/tin_layer_style.cpp, as QGIS reads them back.
TRIANGLE_FILL = (180, 200, 220, 60)
TRIANGLE_OUTLINE = (60, 70, 80, 200)
VERTEX_COLOUR = (200, 60, 40, 255)

checks = []
ran = []  # the algorithms run to their end through their dialogs
messages = []  # the desktop's log panel: where Python tracebacks and plugin errors land
seconds = {}
log_file = open(os.path.join(ARTEFACTS, "driver.log"), "w", encoding="utf-8")


def log(text):
    log_file.write("%8.1f %s\n" % (time.monotonic() - STARTED, text))
    log_file.flush()


def check(what, ok, detail=""):
    checks.append({"what": what, "ok": bool(ok), "detail": "" if ok else str(detail)})
    log(("ok: " if ok else "FAILED: ") + what + ("" if ok else " (%s)" % detail))
    return bool(ok)


def on_message(message, tag, level):
    if level >= Qgis.Warning:
        messages.append({"tag": tag, "level": int(level), "message": message})


STARTED = time.monotonic()
QgsApplication.messageLog().messageReceived.connect(on_message)


# ---------------------------------------------------------------- the map's layers

def path_and_layer(layer):
    parts = QgsProviderRegistry.instance().decodeUri(layer.providerType(), layer.source())
    return os.path.realpath(parts.get("path", "")), parts.get("layerName") or ""


def tree_node(layer):
    return QgsProject.instance().layerTreeRoot().findLayer(layer.id())


def rgba(colour):
    return (colour.red(), colour.green(), colour.blue(), colour.alpha())


def single_symbol(layer, geometry, geometry_name):
    """The first symbol layer of a single-symbol layer of `geometry`, or what is wrong instead."""
    if layer.geometryType() != geometry:
        return None, "geometry %s, not %s" % (QgsWkbTypes.geometryDisplayString(layer.geometryType()), geometry_name)
    renderer = layer.renderer()
    if not isinstance(renderer, QgsSingleSymbolRenderer):
        return None, "renderer %s, not a single symbol" % (renderer.type() if renderer else None)
    return renderer.symbol().symbolLayer(0), None


def triangle_style_problem(layer):
    """What is wrong with a TIN triangle layer's style, or None."""
    fill, problem = single_symbol(layer, QgsWkbTypes.PolygonGeometry, "polygons")
    if problem:
        return problem
    if fill.layerType() != "SimpleFill":
        return "symbol layer %s, not a simple fill" % fill.layerType()
    if rgba(fill.color()) != TRIANGLE_FILL or rgba(fill.strokeColor()) != TRIANGLE_OUTLINE:
        return "fill %s outline %s, not the TIN style %s %s" % (
            rgba(fill.color()), rgba(fill.strokeColor()), TRIANGLE_FILL, TRIANGLE_OUTLINE)
    return None


def vertex_style_problem(layer):
    marker, problem = single_symbol(layer, QgsWkbTypes.PointGeometry, "points")
    if problem:
        return problem
    if marker.layerType() != "SimpleMarker" or rgba(marker.color()) != VERTEX_COLOUR:
        return "marker %s %s, not the TIN vertex style %s" % (marker.layerType(), rgba(marker.color()), VERTEX_COLOUR)
    return None


def shade(renderer, value):
    ok, r, g, b, a = renderer.shader().rasterShaderFunction().shade(value)
    return (r, g, b) if ok else None


def is_red(c):
    return c is not None and c[0] > c[2] + 50 and c[0] > c[1]


def is_blue(c):
    return c is not None and c[2] > c[0] + 50 and c[2] > c[1]


def is_white(c):
    return c is not None and min(c) > 220


def at_root(layer):
    node = tree_node(layer)
    return node is not None and node.parent() is QgsProject.instance().layerTreeRoot()


def placement(layer):
    node = tree_node(layer)
    if node is None:
        return "not in the layer tree"
    parent = node.parent()
    where = "at the top level" if parent is QgsProject.instance().layerTreeRoot() else "inside group '%s'" % parent.name()
    return "%s, %s" % (where, "shown" if node.itemVisibilityChecked() else "hidden")


def check_shown_at_root(what, layer):
    check(what, at_root(layer) and tree_node(layer).itemVisibilityChecked(), placement(layer))


def layer_tree_text(group=None, indent=""):
    """The layer tree as a user sees it, for the log: a failed placement is then plain."""
    group = group or QgsProject.instance().layerTreeRoot()
    lines = []
    for child in group.children():
        mark = "[x]" if child.itemVisibilityChecked() else "[ ]"
        if isinstance(child, QgsLayerTreeGroup):
            lines.append("%s%s group '%s'" % (indent, mark, child.name()))
            lines.extend(layer_tree_text(child, indent + "    "))
        else:
            layer = child.layer()
            renderer = layer.renderer() if layer is not None else None
            lines.append("%s%s '%s' %s %s" % (indent, mark, child.name(), renderer.type() if renderer else "-",
                                                "%s|%s" % path_and_layer(layer) if layer is not None else "-"))
    return lines


def one_layer(new_layers, gpkg, layer_name):
    """The one new layer reading `layer_name` of `gpkg` (a file path for rasters)."""
    want = os.path.realpath(gpkg)
    found = [l for l in new_layers if path_and_layer(l) == (want, layer_name)]
    return found[0] if len(found) == 1 else None


def check_name(alg, layer, name):
    """The name the algorithm gives (processing/tin_layer_style.cpp): QGIS's default
    "Prefer output filename for layer names" would call every TIN layer "triangles"."""
    check("%s: the layer is named '%s'" % (alg, name), layer.name() == name, "named '%s'" % layer.name())


def check_tin(alg, new_layers, gpkg, with_vertices, results):
    base = os.path.splitext(os.path.basename(gpkg))[0]
    triangles = one_layer(new_layers, gpkg, "triangles")
    if check("%s: its triangles are a layer on the map" % alg, triangles,
             "new layers: %s" % describe(new_layers)):
        check_name(alg, triangles, base + " triangles")
        reported = int(results["TRIANGLES"]) if results else None
        check("%s: the triangles layer has every triangle the run reported" % alg,
              triangles.isValid() and reported and triangles.featureCount() == reported,
              "valid %s, %d features, TRIANGLES %s" % (triangles.isValid(), triangles.featureCount(), reported))
        problem = triangle_style_problem(triangles)
        check("%s: the triangles have the TIN style" % alg, problem is None, problem)
        check_shown_at_root("%s: the triangles are shown at the top level of the layer tree" % alg, triangles)
    expected = 2 if with_vertices else 1
    if with_vertices:
        vertices = one_layer(new_layers, gpkg, "vertices")
        if check("%s: its vertices are a layer on the map" % alg, vertices, "new layers: %s" % describe(new_layers)):
            check_name(alg, vertices, base + " vertices")
            problem = vertex_style_problem(vertices)
            check("%s: the vertices have the vertex style" % alg, problem is None, problem)
            check("%s: the vertices are hidden at the top level of the layer tree" % alg,
                  at_root(vertices) and not tree_node(vertices).itemVisibilityChecked(), placement(vertices))
    check("%s: exactly %d new layers" % (alg, expected), len(new_layers) == expected, describe(new_layers))
    return triangles


def describe(layers):
    return ", ".join("'%s' (%s|%s)" % ((l.name(),) + path_and_layer(l)) for l in layers) or "none"


# ---------------------------------------------------------------- the user's actions

def toolbox():
    import qgis.utils
    return qgis.utils.plugins["processing"].toolbox


def find_in_toolbox(algorithm_id):
    """The toolbox tree's index of the algorithm, as the user finds it by typing its name."""
    tree = toolbox().algorithmTree
    model = tree.model()
    pending = [model.index(r, 0) for r in range(model.rowCount())]
    while pending:
        index = pending.pop()
        alg = tree.algorithmForIndex(index)
        if alg is not None and alg.id() == algorithm_id:
            return index
        pending.extend(model.index(r, 0, index) for r in range(model.rowCount(index)))
    return None


def open_from_toolbox(algorithm_id):
    """Double-clicks the algorithm in the toolbox; the dialog opens modal, later."""
    alg = QgsApplication.processingRegistry().algorithmById(algorithm_id)
    toolbox().set_filter_string(alg.displayName())
    tree = toolbox().algorithmTree
    index = find_in_toolbox(algorithm_id)
    if index is None:
        return False
    tree.scrollTo(index)
    tree.setCurrentIndex(index)
    # After this tick returns: the double-click runs the dialog's exec_(), which must not
    # run inside the scenario's own step.
    QTimer.singleShot(0, lambda: double_click(tree.viewport(), tree.visualRect(index).center()))
    return True


def double_click(widget, point):
    # A view acts on a double-click only where the press before it landed, as with a mouse.
    QTest.mouseClick(widget, Qt.LeftButton, Qt.NoModifier, point)
    QTest.mouseDClick(widget, Qt.LeftButton, Qt.NoModifier, point)


def algorithm_dialog(algorithm_id):
    """The open dialog of the algorithm. Not QApplication.activeModalWidget(): the toolbox
    calls show() before exec_(), which leaves the dialog out of Qt's modal stack."""
    for widget in QApplication.topLevelWidgets():
        alg = getattr(widget, "algorithm", None)
        if widget.isVisible() and callable(alg) and alg() is not None and alg().id() == algorithm_id:
            return widget
    return None


def open_outputs_after_running(dialog):
    """Ticks every enabled "Open output file after running algorithm", as a user would."""
    ticked = []
    for box in dialog.findChildren(QCheckBox):
        if box.text().startswith("Open output file after running") and box.isEnabled():
            if not box.isChecked():
                QTest.mouseClick(box, Qt.LeftButton, Qt.NoModifier, QPoint(8, box.height() // 2))
            ticked.append(box)
    return ticked


def dialog_log(dialog):
    texts = [w.toPlainText() for w in dialog.findChildren(QTextEdit) if w.objectName() == "txtLog"]
    return "\n".join(texts)


class Watchdog:
    """Answers any modal window that pops up (a question, an error, a stack trace) and notes
    it: a user would have been stopped there, and the scenario would wait behind it."""

    def __init__(self):
        self.seen = []
        self.timer = QTimer()
        self.timer.timeout.connect(self.look)
        self.timer.start(300)

    def look(self):
        widget = QApplication.activeModalWidget()
        if not isinstance(widget, QDialog) or hasattr(widget, "algorithm"):
            return
        if isinstance(widget, QMessageBox):
            text = widget.text()
        else:
            text = " ".join([l.text() for l in widget.findChildren(QLabel)] +
                            [t.toPlainText() for t in widget.findChildren(QTextEdit)])
        self.seen.append("%s: %s" % (widget.windowTitle(), " ".join(text.split())[:1500]))
        log("modal window answered: " + self.seen[-1])
        button = widget.escapeButton() if isinstance(widget, QMessageBox) else None
        if button is not None:
            button.click()
        else:
            widget.reject()


watchdog = Watchdog()


# ---------------------------------------------------------------- the scenario

class Wait:
    """Yielded by the scenario: resume when `ready()` is true, or after `timeout` s."""

    def __init__(self, ready, timeout, what):
        self.ready, self.deadline, self.what = ready, time.monotonic() + timeout, what


class Stop(Exception):
    """The scenario cannot go on (a run that never ends holds its dialog open)."""


def pause(seconds_):
    end = time.monotonic() + seconds_
    return Wait(lambda: time.monotonic() >= end, seconds_ + 1, "a pause")


def install_plugin():
    import pyplugin_installer
    import qgis.utils

    start = time.monotonic()
    pyplugin_installer.instance().installFromZipFile(ZIP)
    seconds["install"] = round(time.monotonic() - start, 1)
    check("the installer asked nothing (no modal window)", not watchdog.seen, watchdog.seen)
    folder = os.path.join(qgis.utils.home_plugin_path, "tinlod")
    check("the installer unpacked the plugin into the profile", os.path.isfile(os.path.join(folder, "metadata.txt")),
          "no %s/metadata.txt" % folder)
    check("the plugin is loaded and started", "tinlod" in qgis.utils.plugins and "tinlod" in qgis.utils.active_plugins,
          "loaded: %s" % sorted(qgis.utils.plugins))
    check("the plugin is enabled in the profile's settings", QgsSettings().value("PythonPlugins/tinlod", False, type=bool),
          "PythonPlugins/tinlod is not true")
    provider = QgsApplication.processingRegistry().providerById("tinlod")
    if check("the Processing provider 'tinlod' is registered", provider is not None,
             "providers: %s" % [p.id() for p in QgsApplication.processingRegistry().providers()]):
        ids = sorted(a.id() for a in provider.algorithms())
        check("the provider has the 8 algorithms", ids == sorted("tinlod:" + a for a in ALGORITHMS), ids)


def run_algorithm(alg, parameters):
    """Opens `alg` from the toolbox, fills it in, runs it, closes it; yields Waits.
    Returns (results or None, new layers)."""
    algorithm_id = "tinlod:" + alg
    before = set(QgsProject.instance().mapLayers())
    boxes_before = len(watchdog.seen)
    if not check("%s: found in the Processing toolbox" % alg, open_from_toolbox(algorithm_id), "not in the toolbox"):
        return None, []
    wait = Wait(lambda: algorithm_dialog(algorithm_id) is not None, 20, "its dialog")
    yield wait
    dialog = algorithm_dialog(algorithm_id)
    if not check("%s: the dialog opens on a double-click in the toolbox" % alg, dialog, "no dialog within 20 s"):
        return None, []
    dialog.setParameters(parameters)
    ticked = open_outputs_after_running(dialog)
    if "ACCURACY" in parameters:
        check("%s: 'Open output file after running' is ticked for the accuracy raster" % alg,
              ticked and all(b.isChecked() for b in ticked), "no such box enabled")
    finished = []
    dialog.algorithmFinished.connect(lambda ok, results: finished.append((ok, results)))
    run = dialog.buttonBox().button(QDialogButtonBox.Ok)
    start = time.monotonic()
    QTest.mouseClick(run, Qt.LeftButton)
    wait = Wait(lambda: finished, RUN_TIMEOUT_S, "the run")
    yield wait
    seconds[alg] = round(time.monotonic() - start, 1)
    text = dialog_log(dialog)
    with open(os.path.join(ARTEFACTS, "dialog_%s.log" % alg), "w", encoding="utf-8") as f:
        f.write(text)
    if not finished:
        raise Stop("%s: the run did not finish within %d s; the dialog's log:\n%s" % (alg, RUN_TIMEOUT_S, text[-3000:]))
    ok = finished[0][0]
    if check("%s: the run finishes successfully" % alg, ok, "the dialog's log:\n" + text[-3000:]):
        ran.append(alg)
    errors = [line for line in text.splitlines()
              if any(m in line for m in ("Traceback", "were not correctly generated", "Execution failed"))]
    check("%s: no error in the dialog's log" % alg, not errors, "\n".join(errors))
    check("%s: no modal window stopped the user" % alg, len(watchdog.seen) == boxes_before, watchdog.seen[boxes_before:])
    # A user closes the dialog, which QGIS keeps open after a run.
    close = dialog.buttonBox().button(QDialogButtonBox.Close)
    QTest.mouseClick(close, Qt.LeftButton)
    def closed():  # the toolbox's dialogs delete themselves on closing
        return sip.isdeleted(dialog) or not dialog.isVisible()

    yield Wait(closed, 10, "the dialog to close")
    check("%s: the dialog closes" % alg, closed(), "still open")
    new = [QgsProject.instance().mapLayer(i) for i in set(QgsProject.instance().mapLayers()) - before]
    point = iface.layerTreeInsertionPoint()
    log("%s: %d new layers; QGIS now adds layers to group '%s' at %d" % (alg, len(new), point.group.name(), point.position))
    return (finished[0][1] if ok else None), new


def cancel_a_run():
    """Runs a long build from its dialog and presses Cancel as a user would; yields Waits."""
    alg, out = "buildhierarchy", os.path.join(WORK, "cancelled.gpkg")
    if not open_from_toolbox("tinlod:" + alg):
        return
    yield Wait(lambda: algorithm_dialog("tinlod:" + alg) is not None, 20, "its dialog")
    dialog = algorithm_dialog("tinlod:" + alg)
    if not check("cancel: the build's dialog opens again", dialog, "no dialog within 20 s"):
        return
    dialog.setParameters({"INPUT": os.path.join(WORK, "big.tif"), "OUTPUT": out})
    finished = []
    dialog.algorithmFinished.connect(lambda ok, results: finished.append(ok))
    QTest.mouseClick(dialog.buttonBox().button(QDialogButtonBox.Ok), Qt.LeftButton)
    yield pause(3)
    check("cancel: the build is still running after 3 s", not finished, "it ended first: the DEM is too small to cancel")
    cancel = dialog.cancelButton()
    check("cancel: the dialog's Cancel button is enabled", cancel is not None and cancel.isEnabled(), "disabled")
    asked = time.monotonic()
    QTest.mouseClick(cancel, Qt.LeftButton)
    yield Wait(lambda: finished, RUN_TIMEOUT_S, "the cancelled run")
    stopped = round(time.monotonic() - asked, 2)
    seconds["cancel"] = stopped
    text = dialog_log(dialog)
    with open(os.path.join(ARTEFACTS, "dialog_cancel.log"), "w", encoding="utf-8") as f:
        f.write(text)
    check("cancel: the run stops within 2 s of Cancel (%s s)" % stopped, finished and stopped < 2, text[-2000:])
    check("cancel: the run ends unsuccessful", finished and not finished[0], "it reported success")
    check("cancel: no output is left", not os.path.exists(out), out)
    leftovers = [n for n in os.listdir(WORK) if n.startswith(".cancelled.gpkg.tinlod-")]
    check("cancel: no staging folder is left", not leftovers, leftovers)
    check("cancel: no modal window asked anything", not [s for s in watchdog.seen if "cancel" in s.lower()], watchdog.seen)
    QTest.mouseClick(dialog.buttonBox().button(QDialogButtonBox.Close), Qt.LeftButton)
    yield pause(1)


def scenario():
    install_plugin()
    if QgsApplication.processingRegistry().providerById("tinlod") is None:
        return
    # No window manager under Xvfb to maximise it: the window takes the screen itself.
    iface.mainWindow().setGeometry(QApplication.primaryScreen().availableGeometry())
    toolbox().show()
    project = QgsProject.instance()
    dem = iface.addRasterLayer(os.path.join(WORK, "dem.tif"), "dem")
    contours = iface.addVectorLayer(os.path.join(WORK, "contours.gpkg"), "contours", "ogr")
    check("the inputs open in QGIS", dem and dem.isValid() and contours and contours.isValid(), "dem or contours invalid")
    out = {name: os.path.join(WORK, name + ".gpkg") for name in ("sample", "hier", "greedy", "lod", "located", "dp", "cc")}

    results, new = yield from run_algorithm("sampletin", {"INPUT": dem, "BLOCK": 3, "OUTPUT": out["sample"]})
    sample_vertices = one_layer(new, out["sample"], "vertices")
    check_tin("sampletin", new, out["sample"], True, results)

    results, new = yield from run_algorithm(
        "buildhierarchy", {"INPUT": dem, "METHOD": 1, "DELETE_PCT": 20, "STOP_PCT": 5, "OUTPUT": out["hier"]})
    levels = int(results["LEVELS"]) if results else 0
    group = project.layerTreeRoot().findGroup("hier levels")
    if check("buildhierarchy: the levels are a group 'hier levels' on the map", group,
             "groups: %s" % [g.name() for g in project.layerTreeRoot().findGroups()]):
        children = group.children()
        names = [c.name() for c in children]
        expected = ["level_%d" % i for i in range(levels)]
        check("buildhierarchy: the group holds every level, level_0 to level_%d" % (levels - 1),
              levels > 1 and sorted(names) == sorted(expected), names)
        check("buildhierarchy: the levels are in level order, level_0 first", names == expected, names)
        wrong_source, wrong_style = [], []
        for child in children:
            layer = child.layer() if isinstance(child, QgsLayerTreeLayer) else None
            if layer is None or path_and_layer(layer) != (os.path.realpath(out["hier"]), child.name()):
                wrong_source.append("%s: %s" % (child.name(), describe([layer] if layer else [])))
            elif triangle_style_problem(layer):
                wrong_style.append("%s: %s" % (child.name(), triangle_style_problem(layer)))
        check("buildhierarchy: each level layer reads its own view of hier.gpkg", not wrong_source, "\n".join(wrong_source))
        check("buildhierarchy: every level has the TIN style", not wrong_style, "\n".join(wrong_style))
        shown = [c.name() for c in children if c.itemVisibilityChecked()]
        check("buildhierarchy: only the coarsest level is shown", shown == ["level_%d" % (levels - 1)], shown)
        check("buildhierarchy: the group is at the top level of the layer tree", group.parent() is project.layerTreeRoot(),
              "inside group '%s'" % group.parent().name())
    check("buildhierarchy: exactly its %d levels are new layers" % levels, len(new) == levels, describe(new))
    coarsest = project.mapLayersByName("level_%d" % (levels - 1)) if levels else []
    level0 = project.mapLayersByName("level_0")

    # QGIS made a hidden level current; a layer the user adds next goes above the group, not in it.
    mine = project.addMapLayer(QgsVectorLayer("Point?crs=EPSG:4326", "my points", "memory"))
    check("buildhierarchy: a layer the user adds next goes at the top level, not into the levels' group",
          mine is not None and at_root(mine), placement(mine) if mine else "not added")
    if mine is not None:
        project.removeMapLayer(mine)

    # A user who has just looked at a level has it current, and QGIS adds the next results
    # beside it, inside the hierarchy's group, where they do not belong.
    if coarsest:
        iface.layerTreeView().setCurrentLayer(coarsest[0])
    results, new = yield from run_algorithm("greedyinsertion", {"INPUT": dem, "MAX_ERROR": 5, "OUTPUT": out["greedy"]})
    check_tin("greedyinsertion", new, out["greedy"], True, results)

    hierarchy_layer = level0[0] if level0 else out["hier"]
    accuracy_raster = os.path.join(WORK, "accuracy.tif")
    results, new = yield from run_algorithm("accuracy", {
        "INPUT": dem, "HIERARCHY": hierarchy_layer, "ACCURACY": accuracy_raster,
        "REPORT": os.path.join(WORK, "accuracy.html")})
    rasters = [l for l in new if l.type() == QgsMapLayerType.RasterLayer]
    raster = rasters[0] if len(rasters) == 1 and path_and_layer(rasters[0])[0] == os.path.realpath(accuracy_raster) else None
    if check("accuracy: the accuracy raster is a layer on the map", raster, "new layers: %s" % describe(new)):
        renderer = raster.renderer()
        if check("accuracy: it is drawn with a single-band pseudocolor renderer",
                 isinstance(renderer, QgsSingleBandPseudoColorRenderer), renderer.type() if renderer else None):
            check("accuracy: the renderer shows band 1 (the elevation difference)", renderer.band() == 1, renderer.band())
            low, high = renderer.classificationMin(), renderer.classificationMax()
            check("accuracy: its colours are symmetric about zero", high > 0 and abs(low + high) < 1e-9 * high,
                  "from %r to %r" % (low, high))
            ramp = renderer.shader().rasterShaderFunction().sourceColorRamp()
            check("accuracy: its colour ramp is ColorBrewer RdBu",
                  ramp is not None and ramp.type() == "colorbrewer" and ramp.schemeName() == "RdBu",
                  "ramp %s" % (ramp.properties() if ramp else None))
            colours = {v: shade(renderer, v) for v in (low, 0.0, high)}
            check("accuracy: blue where the TIN is too low, white at zero, red where too high",
                  is_blue(colours[low]) and is_white(colours[0.0]) and is_red(colours[high]), colours)
        check_shown_at_root("accuracy: the raster is shown at the top level of the layer tree", raster)
    check("accuracy: exactly 1 new layer", len(new) == 1, describe(new))
    report = os.path.join(WORK, "accuracy.html")
    check("accuracy: the report is written", os.path.isfile(report) and os.path.getsize(report) > 0, "no accuracy.html")

    results, new = yield from run_algorithm("extractlod", {"HIERARCHY": hierarchy_layer, "MAX_ERROR": 20, "OUTPUT": out["lod"]})
    check_tin("extractlod", new, out["lod"], False, results)

    vertices = sample_vertices or out["sample"] + "|layername=vertices"
    results, new = yield from run_algorithm("locate", {
        "INPUT": vertices, "HIERARCHY": hierarchy_layer, "LEVEL": 0, "OUTPUT": out["located"]})
    points = one_layer(new, out["located"], "points")
    if check("locate: its points are a layer on the map", points, "new layers: %s" % describe(new)):
        check_name("locate", points, "located points")  # after its file, as a batch's outputs must differ
        check("locate: the points are points with an elevation field",
              points.geometryType() == QgsWkbTypes.PointGeometry and points.fields().indexOf("elevation") >= 0,
              "%s, fields %s" % (QgsWkbTypes.geometryDisplayString(points.geometryType()), points.fields().names()))
        check("locate: every sampled vertex is on the layer",
              results is not None and points.featureCount() == int(results["POINTS"]) > 0,
              "%d features, POINTS %s" % (points.featureCount(), results and results.get("POINTS")))
        check_shown_at_root("locate: the points are shown at the top level of the layer tree", points)
    check("locate: exactly 1 new layer", len(new) == 1, describe(new))

    # DP values with a threshold loads its simplified lines beside the lines.
    for alg, name, layer_name, title, key, params, layers in (
            ("dpvalues", "dp", "lines", "lines with DP values", "LINES", {"THRESHOLD": 20}, 2),
            ("concavity", "cc", "parts", "concavity parts", None, {"WINDOW": 300}, 1)):
        results, new = yield from run_algorithm(alg, dict(params, INPUT=contours, OUTPUT=out[name]))
        layer = one_layer(new, out[name], layer_name)
        if check("%s: its %s are a layer on the map" % (alg, layer_name), layer, "new layers: %s" % describe(new)):
            check_name(alg, layer, title)
            check("%s: the %s are lines" % (alg, layer_name), layer.geometryType() == QgsWkbTypes.LineGeometry,
                  QgsWkbTypes.geometryDisplayString(layer.geometryType()))
            expected = None
            if results is not None:
                expected = int(results[key]) if key else sum(int(results[k]) for k in ("CONVEX", "STRAIGHT", "CONCAVE"))
            check("%s: the layer has every %s the run reported" % (alg, layer_name[:-1]),
                  expected and layer.featureCount() == expected, "%d features, reported %s" % (layer.featureCount(), expected))
            check_shown_at_root("%s: the %s are shown at the top level of the layer tree" % (alg, layer_name), layer)
            if alg == "concavity":
                renderer = layer.renderer()
                check("concavity: the parts are coloured by class", renderer.type() == "categorizedSymbol"
                      and renderer.classAttribute() == "class" and [c.value() for c in renderer.categories()]
                      == ["convex", "straight", "concave"], renderer.type())
        check("%s: exactly %d new layer%s" % (alg, layers, "s" if layers > 1 else ""), len(new) == layers, describe(new))

    yield from cancel_a_run()
    yield from screenshot(dem)


def screenshot(dem):
    canvas = iface.mapCanvas()
    canvas.setExtent(canvas.mapSettings().layerExtentToOutputExtent(dem, dem.extent()))
    canvas.refreshAllLayers()
    yield pause(0.5)
    yield Wait(lambda: not canvas.isDrawing(), 60, "the map to render")
    path = os.path.join(ARTEFACTS, "map.png")
    canvas.saveAsImage(path)
    iface.mainWindow().grab().save(os.path.join(ARTEFACTS, "window.png"))
    image = QImage(path)
    colours = {image.pixel(x, y) for x in range(0, image.width(), 7) for y in range(0, image.height(), 7)} if not image.isNull() else set()
    check("the map renders to a screenshot with the layers drawn", len(colours) > 50,
          "%s: %dx%d, %d colours" % (path, image.width(), image.height(), len(colours)))


# ---------------------------------------------------------------- stepping and the end

steps = None
stepping = False
waiting = None
finished_once = False


def finish(crashed=None):
    global steps, finished_once
    if finished_once:
        return
    finished_once = True
    steps = None
    ticker.stop()
    watchdog.timer.stop()
    if crashed:
        check("the scenario ran to its end", False, crashed)
    check("every tinlod algorithm ran successfully from its dialog", ran == ALGORITHMS,
          "not: %s" % [a for a in ALGORITHMS if a not in ran])
    python_errors = [m for m in messages if m["tag"] == "Python error"]
    check("no Python traceback in the desktop", not python_errors, "\n".join(m["message"] for m in python_errors)[:4000])
    plugin_errors = [m for m in messages if m["tag"] == "tinlod" and m["level"] >= Qgis.Critical]
    check("no error from the tinlod plugin", not plugin_errors, "\n".join(m["message"] for m in plugin_errors))
    seconds["total"] = round(time.monotonic() - STARTED, 1)
    tree = layer_tree_text()
    log("the layer tree at the end:\n  " + "\n  ".join(tree))
    with open(RESULT, "w", encoding="utf-8") as f:
        json.dump({"checks": checks, "messages": messages, "seconds": seconds, "layer_tree": tree}, f, indent=1)
    log("done: %d checks, %d failed" % (len(checks), sum(not c["ok"] for c in checks)))
    # Quit as a user does (QgsApplication.exit() would tear the project down after the
    # main window's docks, which crashes QGIS 3.22), without the "save the project?" question.
    QgsProject.instance().setDirty(False)
    QTimer.singleShot(100, iface.actionExit().trigger)


def step():
    global stepping, waiting
    if stepping or steps is None:  # a step that opened a nested event loop is still running
        return
    stepping = True
    try:
        if waiting is not None:
            if not waiting.ready() and time.monotonic() < waiting.deadline:
                return
            if not waiting.ready():
                log("timed out waiting for " + waiting.what)
            waiting = None
        waiting = next(steps)
    except StopIteration:
        finish()
    except Stop as e:
        finish(str(e))
    except Exception:  # noqa: BLE001 (any failure of the driver is a failed test, reported)
        finish(traceback.format_exc())
    finally:
        stepping = False


def start():
    global steps
    log("QGIS %s started; installing %s" % (Qgis.QGIS_VERSION, ZIP))
    steps = scenario()
    ticker.start(50)
    QTimer.singleShot(SCENARIO_TIMEOUT_S * 1000,
                      lambda: finish("the scenario did not end within %d s; see driver.log" % SCENARIO_TIMEOUT_S))


ticker = QTimer()
ticker.timeout.connect(step)
QTimer.singleShot(0, start)
