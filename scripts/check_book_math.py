#!/usr/bin/env python3
"""Checks that no raw TeX reaches a reader of the built book.

Usage: scripts/check_book_math.py book/book

mdbook-katex renders `$…$` and `$$…$$` to MathML at build time. Anything TeX-like that is
left in the visible text of a chapter (outside <math>, <code>, <pre>, <script> and <style>)
is a formula that was not rendered: a missing or unbalanced `$`, or pseudo-TeX such as
`I^{ijkl}` or `\\omega` typed as plain text. Every such fragment is listed, and the script
exits 1. The API documentation copied into book/book/api is not checked.
"""

import html.parser
import os
import re
import sys

# A brace after ^ or _, a TeX command, or a dollar sign left by an unrendered formula.
RAW_TEX = re.compile(r"[\^_]\{|\\[A-Za-z]{2,}|\$")
SKIP = {"math", "code", "pre", "script", "style", "kbd"}


class Text(html.parser.HTMLParser):
    def __init__(self):
        super().__init__(convert_charrefs=True)
        self.depth = 0
        self.found = []

    def handle_starttag(self, tag, attrs):
        if tag in SKIP:
            self.depth += 1

    def handle_endtag(self, tag):
        if tag in SKIP and self.depth > 0:
            self.depth -= 1

    def handle_data(self, data):
        if self.depth == 0:
            for m in RAW_TEX.finditer(data):
                start = max(0, m.start() - 40)
                self.found.append(data[start : m.end() + 40].replace("\n", " "))


def main(root):
    failures = 0
    pages = 0
    for dirpath, dirnames, filenames in os.walk(root):
        rel = os.path.relpath(dirpath, root)
        if rel == "api" or rel.startswith("api" + os.sep):
            dirnames[:] = []
            continue
        for name in filenames:
            # print.html repeats every chapter; toc.html is the navigation.
            if not name.endswith(".html") or name in ("print.html", "toc.html", "404.html"):
                continue
            pages += 1
            path = os.path.join(dirpath, name)
            parser = Text()
            with open(path, encoding="utf-8") as f:
                parser.feed(f.read())
            for fragment in parser.found:
                failures += 1
                print(f"{os.path.relpath(path, root)}: raw TeX in the text: …{fragment}…")
    if pages < 5:
        print(f"only {pages} chapter pages found under {root}")
        return 1
    if failures:
        print(f"{failures} unrendered formula fragment(s)")
        return 1
    print(f"math check: {pages} pages, no raw TeX outside rendered formulas")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else "book/book"))
