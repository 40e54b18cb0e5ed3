#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""The lists of the documentation name every document: the README's "Documentation"
section and the manual page's SEE ALSO each name every docs/*.md, and name none that does
not exist.

Usage: docs_index.py PROJECT_ROOT"""
import os
import re
import sys


def section(text, start, end):
    i = text.index(start)
    j = text.find(end, i + len(start))
    return text[i:j if j >= 0 else len(text)]


def main():
    root = sys.argv[1]
    docs = sorted(f for f in os.listdir(os.path.join(root, "docs")) if f.endswith(".md"))
    with open(os.path.join(root, "README.md")) as f:
        readme = section(f.read(), "## Documentation", "\n## ")
    with open(os.path.join(root, "docs", "dynkit.1")) as f:
        man = section(f.read(), ".SH SEE ALSO", "\n.SH ")
    failures = 0
    for where, text, pattern in (("README.md, Documentation", readme, r"docs/([\w-]+\.md)"),
                                 ("docs/dynkit.1, SEE ALSO", man, r"([\w-]+\.md)")):
        named = set(re.findall(pattern, text))
        for d in docs:
            if d not in named:
                failures += 1
                print("%s does not name docs/%s" % (where, d))
        for d in sorted(named - set(docs)):
            failures += 1
            print("%s names docs/%s, which does not exist" % (where, d))
    print("%d documents; %d missing or stale names" % (len(docs), failures))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
