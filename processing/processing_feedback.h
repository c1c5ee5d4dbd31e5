// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <qgsexception.h>
#include <qgsprocessingfeedback.h>

#include <QList>
#include <QPair>
#include <QString>

#include <exception>

#include "tinlod/feedback.h"

namespace tinlod::qgis {

// A command-line option's name, and the algorithm's parameter it is ("-level", "LEVEL").
// A name ending in ':' is a message's prefix ("points:", "INPUT"); kFileOf + a path names
// the parameter of that file (a message naming the file in quotes, and no parameter, gets
// "HIERARCHY: " before it).
using ParameterNames = QList<QPair<QString, QString>>;
inline const QString kFileOf = QStringLiteral("file:");

// The core's Feedback over a QgsProcessingFeedback: progress bar, phase text, warnings
// (their options named as the algorithm's parameters), information, and cancellation from
// the dialog's Cancel button.
Feedback processingFeedback(QgsProcessingFeedback* feedback, const ParameterNames& names = {});

// The core's message with its command-line option names as the algorithm's parameters
// ("-level 99 does not exist" from LEVEL is "LEVEL 99 does not exist").
QString withParameterNames(const QString& message, const ParameterNames& names);

// Runs core work, turning tinlod::Error (and any std::exception) into the
// QgsProcessingException that QGIS shows the user, the options the message names given as
// the algorithm's parameters (`names`: option, parameter).
template <typename Work>
auto translateErrors(Work&& work, const ParameterNames& names = {}) -> decltype(work()) {
  try {
    return work();
  } catch (const std::exception& e) {
    throw QgsProcessingException(withParameterNames(QString::fromStdString(e.what()), names));
  }
}

}  // namespace tinlod::qgis
