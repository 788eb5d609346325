#!/usr/bin/env python3
"""Checks that the documentation reads as a manual, not a work journal.

- README.md has at most --readme-lines lines (default 220);
- no Markdown file under doc/ has more than --doc-lines lines (default 1500);
- no text file of the tree (docs, sources, prm files, meshes, test and
  helper scripts) numbers or dates rounds of work: "forty-fourth session",
  "this session", "(2026-11-27)", "last reviewed". The interactive
  protocol's own "session" (a client's connection) is not matched: only
  ordinal, relative or dated wording is.

- every relative link of a Markdown file (README.md, doc/**/*.md) points at
  an existing file, and its #anchor (if any) at a heading of that file.

Exits 1 and lists every offending file and line.

    check_docs.py --root <source tree>
"""
import argparse
import pathlib
import re
import sys

ORDINAL = (r"(?:first|second|third|fourth|fifth|sixth|seventh|eighth|ninth|"
           r"tenth|eleventh|twelfth|[a-z]+teenth|[a-z]+tieth|"
           r"(?:twenty|thirty|forty|fifty|sixty|seventy|eighty|ninety)-"
           r"(?:first|second|third|fourth|fifth|sixth|seventh|eighth|ninth)|"
           r"\d+(?:st|nd|rd|th))")
DIARY = re.compile(
    r"\b(?:" + ORDINAL + r"|this|last|next|previous|earlier|later)"
    r"\s+sessions?(?:'s)?\b"
    r"|\b20\d\d-[01]\d-[0-3]\d\b"
    r"|\blast reviewed\b",
    re.IGNORECASE)
# The interactive protocol's sessions: a client connected to coshell.
ALLOWED = re.compile(r"interactive session|protocol'?s? (?:own )?session|"
                     r"a session of the protocol", re.IGNORECASE)
TEXT_SUFFIXES = {".md", ".h", ".cc", ".prm", ".py", ".cmake", ".geo", ".sh",
                 ".txt"}
SKIPPED_DIRECTORIES = {".git", "build", "output"}


def text_files(root):
    for path in sorted(root.rglob("*")):
        if any(part in SKIPPED_DIRECTORIES
               for part in path.relative_to(root).parts):
            continue
        if path.is_file() and (path.suffix in TEXT_SUFFIXES
                               or path.name == "CMakeLists.txt"):
            yield path


def diary_lines(path):
    for number, line in enumerate(
            path.read_text(encoding="utf-8", errors="replace").splitlines(),
            1):
        match = DIARY.search(line)
        if match and not ALLOWED.search(line):
            yield number, match.group(0)


LINK = re.compile(r"\[[^\]]*\]\(([^)\s]+)\)")


def anchors(path):
    """GitHub's anchors of a Markdown file's headings."""
    found = set()
    for line in path.read_text(encoding="utf-8").splitlines():
        heading = re.match(r"^#{1,6}\s+(.*?)\s*#*\s*$", line)
        if heading:
            text = re.sub(r"[^\w\- ]", "", heading.group(1).lower())
            found.add(text.replace(" ", "-"))
    return found


def broken_links(path, root):
    text = path.read_text(encoding="utf-8")
    text = re.sub(r"```.*?```", "", text, flags=re.DOTALL)
    for number, line in enumerate(text.splitlines(), 1):
        for target in LINK.findall(line):
            if re.match(r"^[a-z]+:", target):
                continue  # http:, https:, mailto:
            file_part, _, anchor = target.partition("#")
            linked = (path.parent / file_part).resolve() if file_part \
                else path
            if not linked.exists():
                yield number, target, "no such file"
            elif anchor and linked.suffix == ".md" and \
                    anchor not in anchors(linked):
                yield number, target, "no such heading"


def line_count(path):
    return len(path.read_text(encoding="utf-8").splitlines())


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--root", type=pathlib.Path, required=True)
    parser.add_argument("--readme-lines", type=int, default=220)
    parser.add_argument("--doc-lines", type=int, default=1500)
    args = parser.parse_args()
    root = args.root.resolve()
    this_script = pathlib.Path(__file__).resolve()

    problems = []
    readme = line_count(root / "README.md")
    if readme > args.readme_lines:
        problems.append(f"README.md: {readme} lines, more than "
                        f"{args.readme_lines}")
    for path in sorted((root / "doc").rglob("*.md")):
        lines = line_count(path)
        if lines > args.doc_lines:
            problems.append(f"{path.relative_to(root)}: {lines} lines, more "
                            f"than {args.doc_lines}")
    markdown = [root / "README.md"] + sorted((root / "doc").rglob("*.md"))
    for path in markdown:
        for number, target, reason in broken_links(path, root):
            problems.append(f"{path.relative_to(root)}:{number}: link "
                            f"'{target}': {reason}")
    for path in text_files(root):
        if path.resolve() == this_script:
            continue
        for number, wording in diary_lines(path):
            problems.append(f"{path.relative_to(root)}:{number}: work-diary "
                            f"wording '{wording}'")

    for problem in problems:
        print(problem)
    if problems:
        print(f"check_docs: {len(problems)} problem(s)")
        return 1
    print("check_docs: README and doc/ within their lengths, every link "
          "resolves, no work-diary wording")
    return 0


if __name__ == "__main__":
    sys.exit(main())
