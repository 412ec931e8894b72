#!/bin/sh
# Fetch the example maps Tiled ships (Debian package `tiled`) for the TMX tests.
#
#   sh tools/fetch-tiled-examples.sh [DEST]
#
# DEST defaults to tests/data (git-ignored). The .deb is downloaded with
# `apt-get download` into DEST/cache, unpacked with `dpkg -x` into a temporary
# directory, and only usr/share/doc/tiled/examples is kept, as
# DEST/tiled-examples. Debian gzips documentation files, so the maps, tilesets
# and templates arrive as *.tmx.gz / *.tsx.gz; they are unzipped in place
# (the maps name `objs.tsx`, not `objs.tsx.gz`). Images are kept: the loader
# checks that every image a tileset names exists.
#
# Idempotent: when DEST/tiled-examples/.complete exists nothing is done.
# Exit status 0 on success; non-zero (with a message) when the package cannot
# be fetched, so the caller can decide to skip the example-map tests.
set -eu

here=$(cd "$(dirname "$0")/.." && pwd)
dest=${1:-$here/tests/data}
out=$dest/tiled-examples

if [ -f "$out/.complete" ]; then
    exit 0
fi

mkdir -p "$dest/cache"
cd "$dest/cache"
deb=$(ls tiled_*.deb 2>/dev/null | head -n 1 || true)
if [ -z "$deb" ]; then
    echo "fetch-tiled-examples: downloading the tiled package" >&2
    apt-get download tiled >&2 || {
        echo "fetch-tiled-examples: 'apt-get download tiled' failed" >&2
        exit 1
    }
    deb=$(ls tiled_*.deb | head -n 1)
fi

tmp=$(mktemp -d "${TMPDIR:-/tmp}/tiled-deb.XXXXXX")
trap 'rm -rf "$tmp"' EXIT INT TERM
dpkg -x "$deb" "$tmp"
src=$tmp/usr/share/doc/tiled/examples
if [ ! -d "$src" ]; then
    echo "fetch-tiled-examples: $deb has no usr/share/doc/tiled/examples" >&2
    exit 1
fi

rm -rf "$out"
mkdir -p "$out"
cp -R "$src/." "$out/"
# Undo Debian's documentation compression for the files Tiled itself reads.
find "$out" -type f \( -name '*.tmx.gz' -o -name '*.tsx.gz' -o -name '*.tx.gz' \
    -o -name '*.xml.gz' -o -name '*.tiled-project.gz' \) -exec gzip -d -f {} \;
echo "$deb" > "$out/.complete"
echo "fetch-tiled-examples: examples in $out" >&2
