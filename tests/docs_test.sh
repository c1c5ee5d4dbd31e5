#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Holds the reference pages in docs/ to what the programs say about themselves, so that
# they cannot drift apart. Usage: docs_test.sh TINLOD_CLI PLUGIN_DIR
#
# Conventions the pages follow, and this test reads:
#
# docs/cli/<command>.md, one per command that `tinlod --help` lists (and no other page there):
#   every option is documented by a level-3 heading that starts with the option in a code
#   span:   ### `-method degree|volume|normal|error`
#   Other level-3 headings (positional arguments such as ### `DEM`) do not start with "-".
#   The options of `tinlod COMMAND --help` are the tokens -name that open a line of it or
#   follow ": ", ", " or "[" (prose such as "below -t" is not an option). The two sets must
#   be equal. Where an option's --help line says "(default X)" and its section says
#   "Default: Y", the first words of X and Y must agree.
#
# docs/qgis/<id>.md, one per algorithm `qgis_process.bin list` shows as tinlod:<id> (and no
#   other page there): a "## Parameters" section and an "## Outputs" section, each with a
#   table whose rows start with the name in a code span:
#     | `NAME` | Label | `type` | `default` | flags | Description |   (parameters)
#     | `NAME` | Label | `type` | Description |                       (outputs)
#   The names must equal those of `qgis_process.bin --json help tinlod:<id>`; the type's
#   code span is qgis_process's type id; the default cell starts with the default in a code
#   span (false/true, an enum's index, numbers as %g) or, for no default, with no code span;
#   the flags cell says "optional" and "advanced" exactly when the parameter is. A "|"
#   inside a cell is written "\|".
#
# Links: every relative link in README.md and docs/**/*.md must name an existing file, and
#   an anchor (#...) in it a heading of that page (GitHub's rule: lower case, punctuation
#   other than "-" and "_" dropped, spaces to "-").
set -euo pipefail
tinlod_cli=$1
plugin_dir=$2
root=$(cd "$(dirname "$0")/.." && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# Each command's --help, and each algorithm's --json help from an isolated profile holding
# the plugin (as qgis_process_test.sh does: the user's own profile is never touched).
"$tinlod_cli" --help > "$work/commands.txt"
mkdir "$work/cli" "$work/qgis"
for command in $(sed -n 's/^  \([a-z][a-z]*\)  .*/\1/p' "$work/commands.txt"); do
  "$tinlod_cli" "$command" --help > "$work/cli/$command.txt"
done

# The default DEM's hierarchy, whose `tinlod info` docs/cli/info.md shows.
"$tinlod_cli" makedem -q "$work/dem.tif"
"$tinlod_cli" build -q "$work/dem.tif" "$work/h.gpkg"
"$tinlod_cli" info "$work/h.gpkg" > "$work/info.txt"

# shellcheck source-path=SCRIPTDIR source=script_support.sh
source "$root/tests/script_support.sh"
isolated_qgis "$work" "$plugin_dir"
"$qp" list 2> /dev/null > "$work/list.txt"
for id in $(grep -o 'tinlod:[a-z]*' "$work/list.txt" | sed 's/^tinlod://'); do
  "$qp" --json help "tinlod:$id" 2> /dev/null > "$work/qgis/$id.json"
done

/usr/bin/python3 - "$root" "$work" <<'PY'
import json
import os
import re
import sys

root, work = sys.argv[1], sys.argv[2]
failures = []


def fail(message):
    failures.append(message)
    print("FAILED: " + message)


def read(path):
    with open(path, encoding="utf-8") as f:
        return f.read()


def listed(folder, ext):
    return sorted(name[: -len(ext)] for name in os.listdir(folder) if name.endswith(ext))


def section(text, title):
    """The lines of a "## title" section, up to the next level-2 heading."""
    match = re.search(r"^## " + re.escape(title) + r"[ \t]*$(.*?)(?=^## |\Z)", text, re.M | re.S)
    return match.group(1) if match else None


def cells(row):
    parts = re.split(r"(?<!\\)\|", row.strip())
    return [p.strip() for p in parts[1:-1]]


def first_code(cell):
    match = re.match(r"`([^`]*)`", cell)
    return match.group(1) if match else None


# (a) and (b): a page per command, the same options as its --help.
commands = listed(os.path.join(work, "cli"), ".txt")
if not commands:
    fail("tinlod --help lists no command")
option_pattern = re.compile(r"(?:^[ \t]*|: |, |\[)(-[A-Za-z][A-Za-z0-9_]*)", re.M)
heading_pattern = re.compile(r"^### `(-[A-Za-z][A-Za-z0-9_]*)", re.M)
cli_dir = os.path.join(root, "docs", "cli")
pages = listed(cli_dir, ".md") if os.path.isdir(cli_dir) else []
for command in commands:
    page = os.path.join(cli_dir, command + ".md")
    if not os.path.isfile(page):
        fail("docs/cli/%s.md is missing (tinlod --help lists '%s')" % (command, command))
        continue
    in_help = set(option_pattern.findall(read(os.path.join(work, "cli", command + ".txt"))))
    in_page = set(heading_pattern.findall(read(page)))
    for option in sorted(in_help - in_page):
        fail("docs/cli/%s.md does not document %s (tinlod %s --help has it)" % (command, option, command))
    for option in sorted(in_page - in_help):
        fail("docs/cli/%s.md documents %s, which tinlod %s --help does not have" % (command, option, command))
    print("ok: docs/cli/%s.md documents the %d options of tinlod %s --help" % (command, len(in_help), command))
for page in sorted(set(pages) - set(commands)):
    fail("docs/cli/%s.md describes no command of tinlod --help" % page)

# (a2) Defaults: where an option's --help line says "(default X)" and its section of the
# page says "Default: Y", the first words of X and Y agree.
help_default = re.compile(r"^[ \t]*(-[A-Za-z][A-Za-z0-9_]*)\b[^\n]*?\(default ([^):;]+)[):;]", re.M)
compared = 0
for command in commands:
    page = os.path.join(cli_dir, command + ".md")
    if not os.path.isfile(page):
        continue
    text = read(page)
    for option, value in help_default.findall(read(os.path.join(work, "cli", command + ".txt"))):
        body = re.search(r"^### `" + re.escape(option) + r"\b[^\n]*\n(.*?)(?=^##)", text, re.M | re.S)
        documented = re.search(r"Default:\s+`?([^`\s;]+)", body.group(1)) if body else None
        if not documented:
            continue
        first = lambda words: re.split(r"[\s,]+", words.strip())[0].rstrip(".")
        compared += 1
        if first(value) != first(documented.group(1)):
            fail("docs/cli/%s.md gives %s's default as %s, tinlod %s --help as %s"
                 % (command, option, documented.group(1).rstrip("."), command, value))
if compared < 20:
    fail("only %d defaults were compared between --help and docs/cli: the pattern no longer reads them" % compared)
print("ok: %d defaults in docs/cli agree with --help" % compared)


# (c): a page per algorithm, the same parameters and outputs as qgis_process reports.
def expected_default(parameter):
    value = parameter["default_value"]
    if value is None:
        return None
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float):
        return "%g" % value
    return str(value)


algorithms = listed(os.path.join(work, "qgis"), ".json")
if len(algorithms) < 8:
    fail("qgis_process lists %d tinlod algorithms, fewer than the 8 documented" % len(algorithms))
qgis_dir = os.path.join(root, "docs", "qgis")
pages = listed(qgis_dir, ".md") if os.path.isdir(qgis_dir) else []
for algorithm in algorithms:
    page = os.path.join(qgis_dir, algorithm + ".md")
    where = "docs/qgis/%s.md" % algorithm
    if not os.path.isfile(page):
        fail("%s is missing (qgis_process lists tinlod:%s)" % (where, algorithm))
        continue
    described = json.loads(read(os.path.join(work, "qgis", algorithm + ".json")))
    text = read(page)
    for title, key in (("Parameters", "parameters"), ("Outputs", "outputs")):
        body = section(text, title)
        if body is None:
            fail("%s has no '## %s' section" % (where, title))
            continue
        rows = {}
        for line in body.splitlines():
            if line.startswith("|"):
                row = cells(line)
                name = first_code(row[0]) if row else None
                if name and re.fullmatch(r"[A-Z][A-Z0-9_]*", name):
                    rows[name] = row
        truth = described[key]
        for name in sorted(set(truth) - set(rows)):
            fail("%s does not document %s %s" % (where, key[:-1], name))
        for name in sorted(set(rows) - set(truth)):
            fail("%s documents %s %s, which tinlod:%s does not have" % (where, key[:-1], name, algorithm))
        for name in sorted(set(truth) & set(rows)):
            row, item = rows[name], truth[name]
            type_id = item["type"]["id"] if key == "parameters" else item["type"]
            if len(row) < 3 or first_code(row[2]) != type_id:
                fail("%s: %s's type should be `%s`" % (where, name, type_id))
            if key != "parameters":
                continue
            if len(row) < 5:
                fail("%s: %s's row has no default or flags cell" % (where, name))
                continue
            default = expected_default(item)
            if first_code(row[3]) != default:
                fail("%s: %s's default cell should %s" % (where, name,
                     "start with `%s`" % default if default is not None else "start with no code span (no default)"))
            for flag, truth_flag in (("optional", item["optional"]), ("advanced", item["is_advanced"])):
                if (flag in row[4]) != truth_flag:
                    fail("%s: %s is %s%s" % (where, name, "" if truth_flag else "not ", flag))
        print("ok: %s documents the %d %s of tinlod:%s" % (where, len(truth), key, algorithm))
for page in sorted(set(pages) - set(algorithms)):
    fail("docs/qgis/%s.md describes no tinlod algorithm of qgis_process" % page)


# (d): relative links and their anchors.
def slug(heading):
    text = re.sub(r"[^\w\- ]", "", heading.strip().lower())
    return text.replace(" ", "-")


def anchors(path):
    found, seen = set(), {}
    for heading in re.findall(r"^#{1,6} (.*)$", re.sub(r"^```.*?^```", "", read(path), flags=re.M | re.S), re.M):
        base = slug(heading)
        count = seen.get(base, 0)
        seen[base] = count + 1
        found.add(base if count == 0 else "%s-%d" % (base, count))
    return found


markdown = [os.path.join(root, "README.md")]
for folder, _, names in os.walk(os.path.join(root, "docs")):
    markdown += [os.path.join(folder, n) for n in names if n.endswith(".md")]
links = 0
for path in sorted(markdown):
    text = re.sub(r"^```.*?^```", "", read(path), flags=re.M | re.S)
    text = re.sub(r"`[^`\n]*`", "", text)
    for target in re.findall(r"\]\(([^)\s]+)(?:\s+\"[^\"]*\")?\)", text):
        if re.match(r"[a-z][a-z0-9+.-]*:", target):
            continue
        links += 1
        name = os.path.relpath(path, root)
        file_part, _, anchor = target.partition("#")
        resolved = os.path.normpath(os.path.join(os.path.dirname(path), file_part)) if file_part else path
        if not os.path.exists(resolved):
            fail("%s links to %s, which does not exist" % (name, target))
        elif anchor and resolved.endswith(".md") and anchor not in anchors(resolved):
            fail("%s links to %s, but %s has no heading '#%s'" % (name, target, file_part or name, anchor))
print("ok: %d relative links in %d pages checked" % (links, len(markdown)))

# (e): the default DEM's rows of info.md's example are those tinlod info prints now (but
# for the seconds, which vary), and so is its size.
example = re.search(r"default DEM's hierarchy:\n\n```\n(.*?)```", read(os.path.join(root, "docs/cli/info.md")), re.S)
if not example:
    fail("docs/cli/info.md has no example of the default DEM's hierarchy")
else:
    before = len(failures)
    actual = read(os.path.join(work, "info.txt"))
    def rows(text):
        return {f[0]: f[:4] + f[6:] for f in (line.split() for line in text.splitlines()) if len(f) == 10 and f[0].isdigit()}
    shown, now = rows(example.group(1)), rows(actual)
    for level, fields in sorted(shown.items()):
        if now.get(level) != fields:
            fail("docs/cli/info.md shows level %s of the default DEM as %s; tinlod info says %s" % (level, fields, now.get(level)))
    size = re.search(r"[\d.]+ MB", example.group(1))
    if not shown or not size or size.group(0) not in actual.splitlines()[0]:
        fail("docs/cli/info.md's example does not start as tinlod info does: %s" % actual.splitlines()[0])
    if len(failures) == before:
        print("ok: docs/cli/info.md's %d rows of the default DEM are tinlod info's" % len(shown))

if failures:
    print("%d failures" % len(failures))
    sys.exit(1)
print("all docs checks passed")
PY
