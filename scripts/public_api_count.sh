#!/usr/bin/env bash
# Counts the library's public API as rustdoc documents it: the item pages by kind (struct,
# enum, trait, fn, type alias, constant, static, macro) and the inherent methods and
# associated constants listed on them, then the total.
#
#   scripts/public_api_count.sh            # builds the docs first
#   scripts/public_api_count.sh --no-build # counts what target/doc holds
#   scripts/public_api_count.sh --list     # also prints every counted path
#
# Only the library counts (the binary's modules are not API). A method counts on the page of
# the type that has it, from the inherent impls only: trait implementations (Clone, Debug,
# operators, …) are the traits' API, not the crate's. Required and provided methods of the
# crate's own traits count on the trait's page. Pages that only redirect (an item of a
# private module, documented at its public path) do not count; an item reachable by two
# public paths has two full pages and counts twice, which is what a reader of the docs meets.
set -euo pipefail
cd "$(dirname "$0")/.."
build=1
list=0
for arg in "$@"; do
    case "$arg" in
        --no-build) build=0 ;;
        --list) list=1 ;;
        *) echo "unknown argument: $arg" >&2; exit 2 ;;
    esac
done
if [[ $build == 1 ]]; then
    # rustdoc never deletes the pages of items that are gone: start from an empty directory.
    rm -rf target/doc/rotorflow
    cargo doc --no-deps --all-features --lib >/dev/null
fi
doc=target/doc/rotorflow
[[ -d "$doc" ]] || { echo "no $doc: run without --no-build" >&2; exit 1; }
LIST=$list python3 - "$doc" <<'PY'
import os, re, sys
root = sys.argv[1]
kinds = ["struct", "enum", "trait", "fn", "type", "constant", "static", "macro", "union"]
counts = {k: 0 for k in kinds}
members = 0
listing = []
anchor = re.compile(r'id="((?:tymethod|method|associatedconstant)\.[^"]+)"')
for dirpath, _, files in os.walk(root):
    for f in sorted(files):
        kind = f.split(".", 1)[0]
        if kind not in counts or not f.endswith(".html"):
            continue
        text = open(os.path.join(dirpath, f), encoding="utf-8").read()
        # An item of a private module re-exported elsewhere gets a page that only redirects
        # to its public path: not a second item.
        if 'http-equiv="refresh"' in text[:1000]:
            continue
        counts[kind] += 1
        path = os.path.relpath(os.path.join(dirpath, f), root)
        listing.append(path)
        # Inherent items come before the trait implementations; a trait's own page lists
        # its required and provided methods before its implementors.
        for stop in ('id="trait-implementations"', 'id="synthetic-implementations"',
                     'id="blanket-implementations"', 'id="implementors"',
                     'id="foreign-impls"'):
            i = text.find(stop)
            if i >= 0:
                text = text[:i]
        names = sorted(set(anchor.findall(text)))
        members += len(names)
        listing.extend(f"{path}#{n}" for n in names)
for k in kinds:
    print(f"{k:<10} {counts[k]:5d}")
print(f"{'members':<10} {members:5d}")
print(f"{'total':<10} {sum(counts.values()) + members:5d}")
if os.environ.get("LIST") == "1":
    print("\n".join(sorted(listing)))
PY
