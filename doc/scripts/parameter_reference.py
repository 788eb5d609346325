#!/usr/bin/env python3
"""Writes or checks doc/parameters.md, the reference of every parameter.

The reference is generated from the ParameterHandler declarations
themselves (`coshell --print-parameters-json`), so it lists exactly the
parameters coshell reads, with their defaults, the values they accept and
their documentation. A ctest (`docs.parameter_reference`) runs --check, so
the committed page cannot drift from the code.

    parameter_reference.py --coshell build/coshell --write doc/parameters.md
    parameter_reference.py --coshell build/coshell --check doc/parameters.md

With --require-units, every numeric entry (a Double or Integer, or a list
of them) must state its unit in its documentation as "Unit: ..."
(e.g. "Unit: s.", "Unit: dimensionless.").
"""
import argparse
import difflib
import json
import re
import subprocess
import sys

HEADER = """# Parameter reference

Every parameter a scene file (`.prm`) can set, by subsection, with its
default, the values it accepts and what it means. This page is generated
from the code's own declarations; do not edit it by hand. Regenerate it
after changing a declaration:

    /usr/bin/python3 doc/scripts/parameter_reference.py \\
        --coshell build/coshell --write doc/parameters.md

(the ctest `docs.parameter_reference` fails while it is out of date).
`build/coshell --print-parameters` prints the same entries in `.prm` form,
ready to copy into a scene; `--print-parameters FILE.prm` prints a scene's
values. Units: scenes are unit-consistent, the code fixes none; "length"
is the scene's length unit (m in the plate benchmarks, mm in the IOL
scenes, whose forces are in N, times in s and masses in tonnes).
"""
NUMERIC = re.compile(r"^\[(?:Double|Integer)|^\[List of <\[(?:Double|Integer)")


def demangle(name):
    """ParameterHandler's JSON keys: other characters than letters and
    digits are written as _XX (hexadecimal)."""
    return re.sub(r"_([0-9a-fA-F]{2})", lambda m: chr(int(m.group(1), 16)),
                  name)


def is_entry(node):
    return isinstance(node, dict) and "default_value" in node


def walk(node, path, entries):
    """(subsection path, entry name, entry) in declaration-sorted order."""
    for key in node:
        child = node[key]
        if is_entry(child):
            entries.append((path, demangle(key), child))
    for key in node:
        child = node[key]
        if isinstance(child, dict) and not is_entry(child):
            walk(child, path + [demangle(key)], entries)
    return entries


def one_line(text):
    return " ".join(str(text).split())


def anchor(title):
    slug = re.sub(r"[^a-z0-9 _-]", "", title.lower())
    return slug.replace(" ", "-")


def numbered(title):
    """'Contact / Obstacle 3' -> ('Contact / Obstacle', 3), else None."""
    match = re.match(r"^(.*\S) (\d+)$", title)
    return (match.group(1), int(match.group(2))) if match else None


def described(section):
    """What the reference prints of a subsection's entries."""
    return [(name, str(entry["default_value"]),
             entry.get("pattern_description", ""),
             entry.get("documentation", "")) for name, entry in section]


def common_description(members):
    """The entries the numbered subsections 'members' ((number, section)
    pairs) share, a default that names its own subsection's number
    written with k (Contact/Obstacle 3/Name = obstacle 3: obstacle k); None
    when they differ otherwise."""
    listed = [described(section) for _, section in members]
    common = []
    for rows in zip(*listed):
        if any(row[0] != rows[0][0] or row[2:] != rows[0][2:]
               for row in rows) or len({len(x) for x in listed}) > 1:
            return None
        defaults = {row[1] for row in rows}
        if len(defaults) > 1:
            with_k = {re.sub(rf"\b{number}\b", "k", row[1])
                      for (number, _), row in zip(members, rows)}
            if len(with_k) > 1:
                return None
            defaults = with_k
        common.append((rows[0][0], defaults.pop(), rows[0][2], rows[0][3]))
    return common


def merge_numbered(sections):
    """Subsections that differ only by their number (Stage 1 ... Stage 8)
    and declare the same entries are listed once, as 'Stage k'."""
    merged, groups = {}, {}
    for title, section in sections.items():
        number = numbered(title)
        if number:
            groups.setdefault(number[0], []).append((number[1], section))
    for title, section in sections.items():
        number = numbered(title)
        members = groups.get(number[0], []) if number else []
        common = common_description(members) if len(members) > 1 else None
        if common is not None:
            numbers = sorted(m[0] for m in members)
            key = f"{number[0]} k (k = {numbers[0]} to {numbers[-1]})"
            merged.setdefault(key, common)
        else:
            merged[title] = described(section)
    return merged


def markdown(entries):
    sections = {}
    for path, name, entry in entries:
        sections.setdefault(" / ".join(path) or "(top level)", []).append(
            (name, entry))
    sections = merge_numbered(sections)
    lines = [HEADER, "## Subsections", ""]
    for title in sections:
        lines.append(f"- [{title}](#{anchor(title)})")
    for title, section in sections.items():
        lines += ["", f"## {title}", ""]
        for name, default, accepts, documentation in section:
            default, accepts = one_line(default), one_line(accepts)
            documentation = one_line(documentation)
            lines.append(f"- **`{name}`** = `{default}` · accepts "
                         f"`{accepts}`")
            if documentation:
                lines.append(f"  {documentation}")
    return "\n".join(lines) + "\n"


def entries_without_units(entries):
    missing = []
    for path, name, entry in entries:
        pattern = entry.get("pattern_description", "")
        if NUMERIC.match(pattern) and "Unit:" not in entry.get(
                "documentation", ""):
            missing.append("/".join(path + [name]))
    return missing


def declared_entries(coshell):
    printed = subprocess.run([coshell, "--print-parameters-json"],
                             check=True, capture_output=True, text=True)
    return walk(json.loads(printed.stdout), [], [])


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--coshell", required=True)
    action = parser.add_mutually_exclusive_group(required=True)
    action.add_argument("--write", metavar="FILE")
    action.add_argument("--check", metavar="FILE")
    parser.add_argument("--require-units", action="store_true")
    args = parser.parse_args()

    entries = declared_entries(args.coshell)
    text = markdown(entries)
    failures = []
    if args.require_units:
        failures += [f"{entry}: numeric entry without 'Unit: ...' in its "
                     f"documentation" for entry in
                     entries_without_units(entries)]
    if args.write:
        with open(args.write, "w", encoding="utf-8") as page:
            page.write(text)
        print(f"parameter_reference: {len(entries)} entries written to "
              f"{args.write}")
    else:
        with open(args.check, encoding="utf-8") as page:
            committed = page.read()
        if committed != text:
            diff = difflib.unified_diff(committed.splitlines(),
                                        text.splitlines(), args.check,
                                        "generated", lineterm="", n=1)
            print("\n".join(list(diff)[:60]))
            failures.append(f"{args.check} is out of date: regenerate it "
                            f"with doc/scripts/parameter_reference.py "
                            f"--coshell {args.coshell} --write {args.check}")
    for failure in failures:
        print(failure)
    if failures:
        return 1
    if args.check:
        print(f"parameter_reference: {args.check} matches the "
              f"{len(entries)} declared entries")
    return 0


if __name__ == "__main__":
    sys.exit(main())
