#!/usr/bin/env python3
"""Every relative link in the package's Markdown files resolves.

A link to a file must name an existing file; a link with an anchor (`#section`, or
`docs/x.md#section`) must name a heading of that Markdown file, with GitHub's anchor rule:
lower case, punctuation dropped, spaces turned into hyphens, repeated headings numbered -1, -2...
Headings inside fenced code blocks do not count, and links inside them are not checked.

    test/doc_links_test.py [PACKAGE_DIR]      # default: the directory above this script
Exits 1 and lists every broken link, 0 when all resolve.
"""
import os
import re
import sys

LINK = re.compile(r"!?\[(?:[^\]\[]|\[[^\]]*\])*\]\(([^()\s]+)(?:\s+\"[^\"]*\")?\)")
HEADING = re.compile(r"^(#{1,6})\s+(.*?)\s*#*\s*$")
FENCE = re.compile(r"^\s*(```|~~~)")
INLINE_CODE = re.compile(r"`[^`]*`")


def prose_lines(path):
    """(line number, text) of the lines outside fenced code blocks."""
    inside = False
    with open(path, encoding="utf-8") as f:
        for number, line in enumerate(f, 1):
            if FENCE.match(line):
                inside = not inside
                continue
            if not inside:
                yield number, line.rstrip("\n")


def slug(heading):
    """GitHub's anchor of a heading's text."""
    text = re.sub(r"!?\[([^\]]*)\]\([^)]*\)", r"\1", heading)  # a link's text only
    text = text.lower()
    text = re.sub(r"[^\w\- ]", "", text)
    return text.replace(" ", "-")


def anchors(path):
    seen = {}
    result = set()
    for _, line in prose_lines(path):
        match = HEADING.match(line)
        if not match:
            continue
        base = slug(match.group(2))
        count = seen.get(base, 0)
        seen[base] = count + 1
        result.add(base if count == 0 else "%s-%d" % (base, count))
    return result


def markdown_files(root):
    for directory, subdirs, files in os.walk(root):
        subdirs[:] = [d for d in subdirs if not d.startswith(".") and not d.startswith("build")]
        for name in files:
            if name.endswith(".md"):
                yield os.path.join(directory, name)


def broken_links(root):
    cache = {}
    problems = []
    for path in sorted(markdown_files(root)):
        for number, line in prose_lines(path):
            for target in LINK.findall(INLINE_CODE.sub("", line)):
                if re.match(r"^[a-z][a-z0-9+.-]*:", target):  # http:, mailto:, package: ...
                    continue
                file_part, _, anchor = target.partition("#")
                linked = os.path.normpath(os.path.join(os.path.dirname(path), file_part)) \
                    if file_part else path
                where = "%s:%d: %s" % (os.path.relpath(path, root), number, target)
                if not os.path.exists(linked):
                    problems.append("%s: no file %s" % (where, os.path.relpath(linked, root)))
                    continue
                if not anchor:
                    continue
                if not linked.endswith(".md"):
                    problems.append("%s: an anchor into a file that is not Markdown" % where)
                    continue
                if linked not in cache:
                    cache[linked] = anchors(linked)
                if anchor not in cache[linked]:
                    problems.append("%s: no heading with the anchor #%s in %s"
                                    % (where, anchor, os.path.relpath(linked, root)))
    return problems


def main():
    root = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else
                           os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
    problems = broken_links(root)
    for problem in problems:
        print(problem)
    if problems:
        print("%d broken link(s)" % len(problems))
        return 1
    print("every relative link of the Markdown files under %s resolves" % root)
    return 0


if __name__ == "__main__":
    sys.exit(main())
