// SPDX-License-Identifier: GPL-3.0-or-later
// Build tool: the reference (docs/, Markdown) as HTML pages for the plugin's help/html
// folder, which the dialogs' Help button opens in a browser (a user trial found the raw
// Markdown, whose links to the other pages led nowhere). Links between pages keep working:
// x.md becomes x.html; other files (the images) are copied.
//
//   tinlod_help_pages DOCS_DIR OUT_DIR
#include <QCoreApplication>
#include <QDir>
#include <QDirIterator>
#include <QFile>
#include <QFileInfo>
#include <QRegularExpression>
#include <QTextDocument>
#include <QTextStream>

#include <cstdio>

namespace {

// The page's links to other pages (relative, with or without an anchor) as HTML pages.
QString htmlLinks(QString markdown) {
  static const QRegularExpression link(QStringLiteral("\\]\\(((?![a-z]+://)[^)#\\s]*)\\.md(#[^)\\s]*)?\\)"));
  return markdown.replace(link, QStringLiteral("](\\1.html\\2)"));
}

QString page(const QString& markdown, const QString& title) {
  QTextDocument document;
  document.setMarkdown(htmlLinks(markdown), QTextDocument::MarkdownDialectGitHub);
  QString body = document.toHtml();
  // Qt's HTML names no encoding; tables get visible cells.
  body.replace(QStringLiteral("<head>"),
               QStringLiteral("<head><meta charset=\"utf-8\"><title>%1</title>"
                              "<style>table{border-collapse:collapse}td,th{border:1px solid #bbb;padding:3px 6px;"
                              "vertical-align:top}body{max-width:60em;margin:1em auto}</style>")
                   .arg(title.toHtmlEscaped()));
  return body;
}

bool write(const QString& path, const QString& text) {
  QDir().mkpath(QFileInfo(path).absolutePath());
  QFile out(path);
  if (!out.open(QIODevice::WriteOnly | QIODevice::Truncate)) return false;
  out.write(text.toUtf8());
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  QCoreApplication app(argc, argv);
  if (argc != 3) {
    std::fprintf(stderr, "usage: tinlod_help_pages DOCS_DIR OUT_DIR\n");
    return 2;
  }
  const QDir docs(QString::fromLocal8Bit(argv[1]));
  const QString out = QString::fromLocal8Bit(argv[2]);
  int pages = 0;
  for (QDirIterator it(docs.absolutePath(), QDir::Files, QDirIterator::Subdirectories); it.hasNext();) {
    const QString source = it.next();
    const QString relative = docs.relativeFilePath(source);
    if (!relative.endsWith(QStringLiteral(".md"))) {
      QDir().mkpath(QFileInfo(out + '/' + relative).absolutePath());
      QFile::remove(out + '/' + relative);
      if (!QFile::copy(source, out + '/' + relative)) {
        std::fprintf(stderr, "cannot copy %s\n", qPrintable(source));
        return 1;
      }
      continue;
    }
    QFile in(source);
    if (!in.open(QIODevice::ReadOnly)) {
      std::fprintf(stderr, "cannot read %s\n", qPrintable(source));
      return 1;
    }
    const QString markdown = QString::fromUtf8(in.readAll());
    const QString title = markdown.section('\n', 0, 0).remove(QRegularExpression(QStringLiteral("^#+\\s*")));
    const QString target = out + '/' + relative.chopped(3) + QStringLiteral(".html");
    if (!write(target, page(markdown, title))) {
      std::fprintf(stderr, "cannot write %s\n", qPrintable(target));
      return 1;
    }
    ++pages;
  }
  return pages > 0 ? 0 : 1;
}
