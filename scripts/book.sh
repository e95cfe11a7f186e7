#!/usr/bin/env bash
# Builds the book with the API docs beside it and checks it, as CI does:
#   scripts/book.sh          (needs mdbook and mdbook-katex; .ci/run installs the pinned ones)
# 1. mdbook build book, failing on any WARN or ERROR line;
# 2. cargo doc, copied to book/book/api (the book links to api/rotorflow/...);
# 3. every internal link of the built HTML, anchors included, must resolve;
# 4. no raw TeX may be left in the text of a chapter (every formula rendered by KaTeX).
#
# This is the command that builds the book: a bare `mdbook build book` leaves the API links
# (api/rotorflow/...) dead, because the API docs are copied in by step 2.
set -euo pipefail
cd "$(dirname "$0")/.."

log=$(mktemp)
mdbook build book 2>&1 | tee "$log"
if grep -E '(^|[^A-Za-z])(WARN|ERROR)([^A-Za-z]|$)' "$log" >/dev/null; then
    echo "mdbook reported warnings or errors (see above)" >&2
    exit 1
fi
rm -f "$log"

RUSTDOCFLAGS="${RUSTDOCFLAGS:--D warnings}" cargo doc --no-deps --all-features
rm -rf book/book/api
cp -r target/doc book/book/api

python3 scripts/check_book_links.py book/book
python3 scripts/check_book_math.py book/book
