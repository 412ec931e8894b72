#!/bin/sh
# Builds what a browser build of a Downstroke game links with, for wasm32 with
# Debian's emscripten, from Debian's own source packages: CHICKEN 5.3's
# runtime, SDL2, SDL2_image, SDL2_mixer, zlib, freetype, SDL2_ttf, expat and
# zstd. It builds them once into
#   ${XDG_CACHE_HOME:-$HOME/.cache}/downstroke-web/KEY/{include,lib}
# where KEY names the source versions, emcc's version and this recipe, so that
# a change to any of them builds a new set and later runs reuse the old one.
# Prints that folder on its last line.
#   tools/web-deps.sh          build if missing, print the folder
#   tools/web-deps.sh --key    print the folder only (built or not)
set -e
HERE=$(cd "$(dirname "$0")" && pwd)
# Bump when the way a library is built below changes.
RECIPE=3
PACKAGES="chicken libsdl2 libsdl2-image libsdl2-mixer zlib freetype libsdl2-ttf expat libzstd"
JOBS=2
export NODE_PATH=${NODE_PATH:-/usr/share/nodejs}

say() { echo "web-deps: $*" >&2; }
die() { say "$*"; exit 1; }

# Debian's emscripten (and the rest make web needs), when missing.
command -v emcc >/dev/null || sh "$HERE/install-deps.sh" web >&2 ||
  die "emcc is missing and could not be installed (tools/install-deps.sh web)"

# Debian's source packages need a deb-src entry for the archive the machine
# installs from; add one beside its deb entry when apt knows no source.
ensure_deb_src() {
  apt-cache showsrc chicken 2>/dev/null | grep -q '^Version:' && return 0
  [ "$(id -u)" -eq 0 ] || die "no deb-src entry for Debian's archive; as root, run tools/web-deps.sh once to add it"
  codename=$(. /etc/os-release && echo "$VERSION_CODENAME")
  say "adding a deb-src entry for $codename"
  cat > /etc/apt/sources.list.d/downstroke-src.sources <<EOF
Types: deb-src
URIs: http://deb.debian.org/debian
Suites: $codename
Components: main
Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg
EOF
  apt-get update -qq
}

version_of() { apt-cache showsrc "$1" | awk '/^Version:/ { print $2; exit }'; }

ensure_deb_src
VERSIONS=""
for p in $PACKAGES; do
  v=$(version_of "$p")
  [ -n "$v" ] || die "apt knows no source package $p"
  VERSIONS="$VERSIONS $p=$v"
done
EMCC_VERSION=$(emcc --version 2>/dev/null | head -1)
KEY=$( { echo "recipe $RECIPE"; echo "$VERSIONS"; echo "$EMCC_VERSION";
         cat "$HERE/web/chicken-runtime.patch"; } | sha256sum | cut -c1-16)
CACHE=${XDG_CACHE_HOME:-$HOME/.cache}/downstroke-web
PREFIX=$CACHE/$KEY
if [ "$1" = "--key" ]; then echo "$PREFIX"; exit 0; fi
if [ -f "$PREFIX/versions" ]; then echo "$PREFIX"; exit 0; fi

START=$(date +%s)
say "building into $PREFIX:$VERSIONS"
SOURCES=$CACHE/sources
WORK=$PREFIX.work
mkdir -p "$SOURCES" "$WORK/include" "$WORK/lib"

# The upstream tarball of a source package; apt-get source may fail on the
# Debian part (not needed here) after it got the .orig tarball.
fetch() {
  p=$1; v=$(echo "$VERSIONS" | tr ' ' '\n' | sed -n "s/^$p=//p")
  upstream=$(echo "$v" | sed 's/^[0-9]*://; s/-[^-]*$//')
  orig=$(ls "$SOURCES/${p}_${upstream}.orig.tar."* 2>/dev/null | grep -v '\.asc$' | head -1)
  if [ -z "$orig" ]; then
    (cd "$SOURCES" && apt-get source --download-only -qq "$p=$v" >/dev/null 2>&1) || true
    orig=$(ls "$SOURCES/${p}_${upstream}.orig.tar."* 2>/dev/null | grep -v '\.asc$' | head -1)
    [ -n "$orig" ] || die "apt-get source $p=$v gave no .orig tarball"
  fi
  rm -rf "$WORK/src-$p" && mkdir -p "$WORK/src-$p"
  tar -xf "$orig" -C "$WORK/src-$p"
  # the one folder the tarball holds
  ls -d "$WORK/src-$p"/*/ | head -1
}

# Each library leaves a stamp so that a build stopped half-way goes on.
step() {
  name=$1; shift
  [ -f "$WORK/stamp-$name" ] && return 0
  t0=$(date +%s)
  say "$name ..."
  "$@" > "$WORK/log-$name" 2>&1 || { tail -30 "$WORK/log-$name" >&2; die "$name failed; log: $WORK/log-$name"; }
  touch "$WORK/stamp-$name"
  say "$name done in $(( $(date +%s) - t0 )) s"
}

CFLAGS_WEB="-O2"
compile_all() { # out.a cflags... -- files...
  out=$1; shift; flags=""
  while [ "$1" != "--" ]; do flags="$flags $1"; shift; done; shift
  objdir=$(mktemp -d "$WORK/obj.XXXX")
  for f in "$@"; do echo "$f"; done |
    xargs -P $JOBS -I{} sh -c 'emcc '"$CFLAGS_WEB $flags"' -c "{}" -o "'"$objdir"'/$(echo "{}" | tr / _).o"'
  rm -f "$out"; emar rcs "$out" "$objdir"/*.o
}

build_chicken() {
  src=$(fetch chicken)
  cd "$src"
  patch -p1 < "$HERE/web/chicken-runtime.patch"
  m="make PLATFORM=linux ARCH= C_COMPILER=emcc LIBRARIAN=emar STATICBUILD=1 PREFIX=/downstroke-web
     C_COMPILER_OPTIMIZATION_OPTIONS=-O2"
  $m chicken-config.h
  # emscripten is not Linux to the C preprocessor: the runtime finds its
  # executable the generic way.
  echo "#define SEARCH_EXE_PATH 1" >> chicken-config.h
  $m -j$JOBS libchicken.a
  mkdir -p "$WORK/include/chicken"
  cp chicken.h chicken-config.h "$WORK/include/chicken/"
  cp libchicken.a "$WORK/lib/"
}

cmake_lib() { # src build-dir cmake-options...
  s=$1; b=$2; shift 2
  emcmake cmake -S "$s" -B "$b" -DCMAKE_BUILD_TYPE=Release -DCMAKE_INSTALL_PREFIX="$WORK" \
    -DCMAKE_C_FLAGS="$CFLAGS_WEB" -DBUILD_SHARED_LIBS=OFF "$@"
  cmake --build "$b" -j$JOBS
  cmake --install "$b"
}

# SDL ships its emscripten configuration (include/SDL_config_emscripten.h,
# chosen by SDL_config.h), so no configure step is needed (its CMake one
# takes longer than the build): the portable parts and the emscripten,
# dummy and generic back ends are compiled as they are.
build_sdl2() {
  src=$(fetch libsdl2)
  s=$src/src
  compile_all "$WORK/lib/libSDL2.a" -I"$src/include" -w -- \
    $(ls "$s"/*.c "$s"/atomic/*.c "$s"/audio/*.c "$s"/audio/emscripten/*.c "$s"/audio/dummy/*.c \
         "$s"/audio/disk/*.c "$s"/cpuinfo/*.c "$s"/dynapi/*.c "$s"/events/*.c "$s"/file/*.c \
         "$s"/filesystem/emscripten/*.c "$s"/haptic/*.c "$s"/haptic/dummy/*.c "$s"/hidapi/SDL_hidapi.c \
         "$s"/joystick/*.c "$s"/joystick/emscripten/*.c "$s"/loadso/dlopen/*.c "$s"/locale/*.c \
         "$s"/locale/emscripten/*.c "$s"/misc/*.c "$s"/misc/emscripten/*.c "$s"/power/*.c \
         "$s"/power/emscripten/*.c "$s"/render/*.c "$s"/render/opengles2/*.c "$s"/render/software/*.c \
         "$s"/sensor/*.c "$s"/sensor/dummy/*.c "$s"/stdlib/*.c "$s"/thread/*.c "$s"/thread/generic/*.c \
         "$s"/timer/*.c "$s"/timer/unix/*.c "$s"/video/*.c "$s"/video/emscripten/*.c \
         "$s"/video/dummy/*.c "$s"/video/yuv2rgb/*.c)
  mkdir -p "$WORK/include/SDL2"
  cp "$src"/include/*.h "$WORK/include/SDL2/"
}

SDLINC="-I$WORK/include/SDL2 -I$WORK/include"
build_sdl2_image() {
  src=$(fetch libsdl2-image)
  # PNG, JPEG and others through its bundled stb_image; PNG saving through
  # its bundled miniz.
  compile_all "$WORK/lib/libSDL2_image.a" $SDLINC -DUSE_STBIMAGE -DLOAD_PNG -DLOAD_JPG \
    -DLOAD_BMP -DLOAD_GIF -DLOAD_TGA -DLOAD_PNM -DLOAD_QOI -DLOAD_PCX -DLOAD_XPM \
    -DSDL_IMAGE_SAVE_PNG=1 -DSDL_IMAGE_SAVE_JPG=0 -- \
    "$src"/IMG.c "$src"/IMG_stb.c "$src"/IMG_png.c "$src"/IMG_jpg.c "$src"/IMG_bmp.c \
    "$src"/IMG_gif.c "$src"/IMG_tga.c "$src"/IMG_pnm.c "$src"/IMG_qoi.c "$src"/IMG_pcx.c \
    "$src"/IMG_xpm.c "$src"/IMG_lbm.c "$src"/IMG_xcf.c "$src"/IMG_xv.c "$src"/IMG_svg.c \
    "$src"/IMG_tif.c "$src"/IMG_webp.c "$src"/IMG_avif.c "$src"/IMG_jxl.c
  cp "$src"/SDL_image.h "$WORK/include/SDL2/"
}

build_sdl2_mixer() {
  src=$(fetch libsdl2-mixer)
  # WAV and AIFF/VOC natively, Ogg Vorbis through its bundled stb_vorbis.
  compile_all "$WORK/lib/libSDL2_mixer.a" $SDLINC -I"$src/include" -I"$src/src" -I"$src/src/codecs" \
    -DMUSIC_WAV -DMUSIC_OGG -DOGG_USE_STB -- \
    "$src"/src/*.c "$src"/src/codecs/load_aiff.c "$src"/src/codecs/load_voc.c \
    "$src"/src/codecs/music_wav.c "$src"/src/codecs/music_ogg.c "$src"/src/codecs/music_ogg_stb.c \
    "$src"/src/codecs/mp3utils.c
  cp "$src"/include/SDL_mixer.h "$WORK/include/SDL2/"
}

build_zlib() {
  src=$(fetch zlib)
  compile_all "$WORK/lib/libz.a" -DHAVE_UNISTD_H -DHAVE_STDARG_H -- \
    $(for f in adler32 compress crc32 deflate gzclose gzlib gzread gzwrite infback \
               inffast inflate inftrees trees uncompr zutil; do echo "$src/$f.c"; done)
  cp "$src"/zlib.h "$src"/zconf.h "$WORK/include/"
}

build_freetype() {
  src=$(fetch freetype)
  cmake_lib "$src" "$WORK/b-freetype" -DFT_REQUIRE_ZLIB=ON -DFT_DISABLE_BZIP2=ON \
    -DFT_DISABLE_PNG=ON -DFT_DISABLE_HARFBUZZ=ON -DFT_DISABLE_BROTLI=ON \
    -DZLIB_LIBRARY="$WORK/lib/libz.a" -DZLIB_INCLUDE_DIR="$WORK/include"
}

build_sdl2_ttf() {
  src=$(fetch libsdl2-ttf)
  compile_all "$WORK/lib/libSDL2_ttf.a" $SDLINC -I"$WORK/include/freetype2" -DTTF_USE_HARFBUZZ=0 -- \
    "$src"/SDL_ttf.c
  cp "$src"/SDL_ttf.h "$WORK/include/SDL2/"
}

# Expat's configuration is a handful of facts about emscripten's libc,
# written here instead of a CMake configure step.
build_expat() {
  src=$(fetch expat)/expat
  cat > "$src/lib/expat_config.h" <<'EOF'
#define EXPAT_CONFIG_H 1
#define BYTEORDER 1234
#define HAVE_FCNTL_H 1
#define HAVE_INTTYPES_H 1
#define HAVE_STDINT_H 1
#define HAVE_STDLIB_H 1
#define HAVE_STRING_H 1
#define HAVE_SYS_STAT_H 1
#define HAVE_SYS_TYPES_H 1
#define HAVE_UNISTD_H 1
#define STDC_HEADERS 1
#define XML_CONTEXT_BYTES 1024
#define XML_DEV_URANDOM 1
#define XML_DTD 1
#define XML_NS 1
EOF
  compile_all "$WORK/lib/libexpat.a" -DHAVE_EXPAT_CONFIG_H -I"$src/lib" -- \
    "$src"/lib/xmlparse.c "$src"/lib/xmlrole.c "$src"/lib/xmltok.c
  cp "$src"/lib/expat.h "$src"/lib/expat_external.h "$WORK/include/"
}

build_zstd() {
  src=$(fetch libzstd)
  compile_all "$WORK/lib/libzstd.a" -DZSTD_DISABLE_ASM -DZSTD_MULTITHREAD=0 -I"$src/lib" -I"$src/lib/common" -- \
    "$src"/lib/common/*.c "$src"/lib/decompress/*.c "$src"/lib/compress/*.c
  cp "$src"/lib/zstd.h "$src"/lib/zstd_errors.h "$WORK/include/"
}

step chicken build_chicken
step sdl2 build_sdl2
step sdl2-image build_sdl2_image
step sdl2-mixer build_sdl2_mixer
step zlib build_zlib
step freetype build_freetype
step sdl2-ttf build_sdl2_ttf
step expat build_expat
step zstd build_zstd

echo "$VERSIONS" | tr ' ' '\n' | sed '/^$/d' > "$WORK/versions"
echo "$EMCC_VERSION" >> "$WORK/versions"
rm -rf "$WORK"/src-* "$WORK"/b-* "$WORK"/obj.*
rm -rf "$PREFIX" && mv "$WORK" "$PREFIX"
say "built in $(( $(date +%s) - START )) s"
echo "$PREFIX"
