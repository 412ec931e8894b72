#!/bin/sh
# Installs the Debian packages Downstroke builds and tests with, but only the
# ones that are missing, so `make test` on a ready machine touches nothing.
set -e
PACKAGES="chicken-bin libchicken-dev gcc pkg-config libsdl2-dev libsdl2-image-dev
libsdl2-mixer-dev libsdl2-ttf-dev libexpat1-dev zlib1g-dev libzstd-dev
fonts-dejavu-core xvfb xauth tiled"
# `install-deps.sh web`: also what make web and its tests need (Debian's
# emscripten, with node; chromium and python3 for the browser tests; zip for
# a jam page).
[ "$1" = "web" ] && PACKAGES="$PACKAGES emscripten nodejs chromium zip python3"
# `install-deps.sh bench`: LÖVE 11.4, the other side of bench/draw.scm
# (bench/love; docs/performance.org, "Drawing against LÖVE"). Not for CI.
[ "$1" = "bench" ] && PACKAGES="$PACKAGES love"

missing=""
for p in $PACKAGES; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" ||
    missing="$missing $p"
done
[ -z "$missing" ] && exit 0

if [ "$(id -u)" -eq 0 ]; then SUDO=""; else SUDO="sudo"; fi
echo "install-deps: installing$missing"
$SUDO apt-get update -qq
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq $missing
