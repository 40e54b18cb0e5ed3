#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Checks a picture or page that dynkit wrote from hostile text (tests/test_hostile_text.c).

    markup_check.py FILE.svg|FILE.html TEXT...

An SVG must parse as XML (xml.etree: well-formed, every character allowed), hold no script
element and no event attribute (on...), and carry each TEXT intact in the text of some
element. An HTML page (html.parser, the tokenizer of a browser's rules for script data)
must hold no img or iframe element and no event attribute, its data (the JSON of the
script element dynkit-data) must parse, and each TEXT must come back from it as a string
or an object key, or be the page's title. Prints "scripts N" (the script elements seen)
and exits 0, or prints what was wrong and exits 1."""
import json
import sys
import xml.etree.ElementTree as ET
from html.parser import HTMLParser


def fail(msg):
    print("markup_check:", msg)
    sys.exit(1)


def strings(value, out):
    """Every string and key of a JSON value."""
    if isinstance(value, str):
        out.add(value)
    elif isinstance(value, list):
        for v in value:
            strings(v, out)
    elif isinstance(value, dict):
        for k, v in value.items():
            out.add(k)
            strings(v, out)


def check_svg(path, texts):
    try:
        root = ET.parse(path).getroot()
    except ET.ParseError as e:
        fail(f"{path}: not well-formed XML: {e}")
    seen = set()
    for el in root.iter():
        tag = el.tag.split("}")[-1]
        if tag in ("script", "foreignObject", "image"):
            fail(f"{path}: a {tag} element")
        for name in el.attrib:
            if name.split("}")[-1].lower().startswith("on"):
                fail(f"{path}: an event attribute {name}")
        seen.add("".join(el.itertext()))
    for t in texts:
        if not any(t in s for s in seen):
            fail(f"{path}: {t!r} is not in the text of any element")
    print("scripts 0")


class Page(HTMLParser):
    def __init__(self):
        super().__init__(convert_charrefs=True)
        self.scripts = 0
        self.in_data = False
        self.in_title = False
        self.data = ""
        self.title = ""

    def handle_starttag(self, tag, attrs):
        if tag in ("img", "iframe", "object", "embed"):
            fail(f"an {tag} element")
        for name, _ in attrs:
            if name.lower().startswith("on"):
                fail(f"an event attribute {name} on {tag}")
        if tag == "script":
            self.scripts += 1
            self.in_data = ("id", "dynkit-data") in attrs
        self.in_title = tag == "title"

    def handle_endtag(self, tag):
        self.in_data = False
        self.in_title = False

    def handle_data(self, data):
        if self.in_data:
            self.data += data
        if self.in_title:
            self.title += data


def check_html(path, texts):
    p = Page()
    with open(path, encoding="utf-8") as f:
        p.feed(f.read())
    p.close()
    try:
        data = json.loads(p.data)
    except ValueError as e:
        fail(f"{path}: the page's data is not JSON: {e}")
    found = set()
    strings(data, found)
    for t in texts:
        if t != p.title and not any(t in s for s in found):
            fail(f"{path}: {t!r} is neither the title nor in the page's data")
    print("scripts", p.scripts)


def main():
    if len(sys.argv) < 2:
        fail("usage: markup_check.py FILE.svg|FILE.html TEXT...")
    path, texts = sys.argv[1], sys.argv[2:]
    (check_svg if path.endswith(".svg") else check_html)(path, texts)


if __name__ == "__main__":
    main()
