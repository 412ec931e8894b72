#!/bin/sh
# Tiled's own JSON export of every map the tests load, for tiled/tests/tmj-test.scm.
#
#   sh tools/export-tiled-json.sh [DEST]
#
# Runs `tiled --export-map json` (Debian's tiled package, headless through
# QT_QPA_PLATFORM=offscreen) on tests/maps/*.tmx, the demos' levels
# (demo/levels/*.tmx, which the demo tests play) and, when they have been
# fetched (tools/fetch-tiled-examples.sh), on Tiled's example maps in
# tests/data/tiled-examples. Each export is DEST/NAME.tmj, NAME the map's
# path under tests/ (or under the top for the demos) with / written as __
# (maps__features.tmj, demo__levels__topdown.tmj,
# data__tiled-examples__rpg__island.tmj), and NAME.full.tmj, the export with
# external tilesets embedded and template instances detached (Tiled's
# --embed-tilesets --detach-templates); Tiled writes the paths inside
# relative to DEST, so they still name the same files. DEST defaults to
# tests/maps/tiled-json, the copies committed for machines without tiled;
# the test writes fresh ones to tests/data/tiled-json when tiled runs.
# Exit status: 0, or 1 when tiled is missing or fails on a map.
set -eu

here=$(cd "$(dirname "$0")/.." && pwd)
dest=${1:-$here/tests/maps/tiled-json}
command -v tiled >/dev/null 2>&1 || { echo "export-tiled-json: tiled is not installed" >&2; exit 1; }
mkdir -p "$dest"
cd "$here/tests"
maps=$(ls maps/*.tmx ../demo/levels/*.tmx; [ -f data/tiled-examples/.complete ] && find data/tiled-examples -name '*.tmx' | sort || true)
for m in $maps; do
    name=$(echo "${m%.tmx}" | sed 's|^\.\./||; s|/|__|g')
    QT_QPA_PLATFORM=offscreen XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-/tmp} \
        tiled --export-map json "$m" "$dest/$name.tmj" >/dev/null 2>&1 || {
        echo "export-tiled-json: tiled could not export $m" >&2; exit 1; }
    [ -f "$dest/$name.tmj" ] || { echo "export-tiled-json: no export of $m" >&2; exit 1; }
    # the same with the external tilesets and templates written out, so
    # that they too are compared with what Tiled read
    QT_QPA_PLATFORM=offscreen XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-/tmp} \
        tiled --embed-tilesets --detach-templates --export-map json "$m" "$dest/$name.full.tmj" >/dev/null 2>&1 || {
        echo "export-tiled-json: tiled could not export $m with its tilesets" >&2; exit 1; }
done
