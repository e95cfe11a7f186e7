#!/usr/bin/env python3
"""Checks the internal links of the built book (and of the API docs copied into it).

Usage: scripts/check_book_links.py book/book

Every href and src in the book's HTML pages that is not an external URL must point to a
file that exists in the built tree, and a #fragment must name an id (or name) in the target
page. The API documentation (target/doc, copied to book/book/api by scripts/book.sh) is a
link target only: its own pages are not checked. Exits 1 and lists every broken link.
"""

import html.parser
import os
import sys
import urllib.parse

EXTERNAL = ("http://", "https://", "mailto:", "javascript:", "data:")


class Page(html.parser.HTMLParser):
    def __init__(self):
        super().__init__(convert_charrefs=True)
        self.links = []
        self.ids = set()

    def handle_starttag(self, tag, attrs):
        for name, value in attrs:
            if value is None:
                continue
            if name in ("id", "name"):
                self.ids.add(value)
            if name in ("href", "src") and tag in ("a", "img", "script", "link", "iframe"):
                self.links.append(value)


def parse(path, cache):
    if path not in cache:
        page = Page()
        with open(path, encoding="utf-8", errors="replace") as f:
            page.feed(f.read())
        cache[path] = page
    return cache[path]


def main():
    root = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else "book/book")
    api = os.path.join(root, "api")
    cache = {}
    broken = []
    checked = 0
    for directory, _, files in os.walk(root):
        if directory == api or directory.startswith(api + os.sep):
            continue
        for name in files:
            if not name.endswith(".html"):
                continue
            source = os.path.join(directory, name)
            for link in parse(source, cache).links:
                if link.startswith(EXTERNAL) or link.startswith("//"):
                    continue
                parts = urllib.parse.urlsplit(link)
                target = source
                if parts.path:
                    target = os.path.normpath(
                        os.path.join(directory, urllib.parse.unquote(parts.path))
                    )
                    if os.path.isdir(target):
                        target = os.path.join(target, "index.html")
                checked += 1
                where = os.path.relpath(source, root)
                if not os.path.exists(target):
                    broken.append(f"{where}: {link} (no file)")
                    continue
                fragment = urllib.parse.unquote(parts.fragment)
                if fragment and target.endswith(".html"):
                    if fragment not in parse(target, cache).ids:
                        broken.append(f"{where}: {link} (no id '{fragment}')")
    for b in broken:
        print("broken link:", b)
    print(f"{checked} internal links checked, {len(broken)} broken")
    return 1 if broken or checked == 0 else 0


if __name__ == "__main__":
    sys.exit(main())
