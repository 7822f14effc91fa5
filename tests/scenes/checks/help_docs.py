#!/usr/bin/python3
"""Checks of the help_docs scene (tests/scenes/help_docs.sh); usage: help_docs.py links SOURCE_DIR.

Every relative markdown link ([text](target) and ![alt](target)) outside code in
README.md and docs/**/*.md must name an existing file (or directory) of the
source tree, and its #anchor, if any, a heading of the target page (GitHub's
slugs); README.md must link every page under docs/ and name every script of
src/plots/ (issue 33: the README lists every plot script)."""
import glob
import os
import re
import sys
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from scene_check import main, require

LINK = re.compile(r"!?\[(?:[^\]\[]|\[[^\]]*\])*\]\(([^)\s]+)(?:\s+\"[^\"]*\")?\)")


def _prose(text):
    """text without fenced code blocks and inline code spans."""
    text = re.sub(r"^```.*?^```[ \t]*$", "", text, flags=re.M | re.S)
    return re.sub(r"`[^`\n]*`", "", text)


def _slugs(path):
    """The anchors GitHub gives the headings of a markdown file (the text of
    code spans kept, other punctuation dropped, spaces as hyphens, repeats
    numbered)."""
    seen, out = {}, set()
    text = re.sub(r"^```.*?^```[ \t]*$", "", open(path, encoding="utf-8").read(), flags=re.M | re.S)
    for line in text.splitlines():
        m = re.match(r"^#{1,6}\s+(.*?)\s*#*\s*$", line)
        if not m:
            continue
        s = re.sub(r"[^\w\- ]", "", m.group(1).replace("`", "").lower()).replace(" ", "-")
        n = seen.get(s, 0)
        seen[s] = n + 1
        out.add(s if n == 0 else "%s-%d" % (s, n))
    return out


def links(src):
    """Every relative link resolves, every anchor names a heading, README.md links every docs page."""
    src = os.path.abspath(src)
    pages = ["README.md"] + sorted(os.path.relpath(p, src) for p in glob.glob(os.path.join(src, "docs", "**", "*.md"), recursive=True))
    bad, n, readme_targets = [], 0, set()
    for page in pages:
        text = _prose(open(os.path.join(src, page), encoding="utf-8").read())
        for target in LINK.findall(text):
            if re.match(r"^[a-z]+:", target):  # http:, https:, mailto:
                continue
            n += 1
            path, _, anchor = target.partition("#")
            full = os.path.normpath(os.path.join(src, os.path.dirname(page), path)) if path else os.path.join(src, page)
            rel = os.path.relpath(full, src)
            if page == "README.md":
                readme_targets.add(rel)
            if not os.path.exists(full):
                bad.append("%s: %s (no such file)" % (page, target))
                continue
            if anchor and full.endswith(".md") and anchor not in _slugs(full):
                bad.append("%s: %s (no heading #%s in %s)" % (page, target, anchor, rel))
    require(not bad, "\n  ".join([""] + bad))
    docs = {p for p in pages if p.startswith("docs" + os.sep)}
    unlinked = sorted(docs - readme_targets)
    require(not unlinked, "docs pages README.md does not link", unlinked)
    require(n >= 100, "fewer links than expected: is the link pattern still right?", n)
    readme = open(os.path.join(src, "README.md"), encoding="utf-8").read()
    scripts = sorted(os.path.relpath(p, src) for p in glob.glob(os.path.join(src, "src", "plots", "*.py")))
    unnamed = [s for s in scripts if "`%s`" % s not in readme]
    require(not unnamed, "plot scripts README.md does not list", unnamed)
    print("docs links OK: %d relative links in %d pages, every docs page linked from README.md, its %d plot scripts listed"
          % (n, len(pages), len(scripts)))


if __name__ == "__main__":
    main(globals())
