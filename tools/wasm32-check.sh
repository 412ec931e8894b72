#!/bin/sh
# Runs suites where fixnums are 31 bits wide: each suite is compiled as a
# program for wasm32 (the host's csc translates it, emscripten compiles
# it and links it with make web's library build/web/libdownstroke.a) and
# run under node, from tests/ with the real files (NODERAWFS), as
# tests/suite.scm runs it natively. Prints each suite's last line, then
# the total "N passed, N failed"; fails when any suite fails.
#   tools/wasm32-check.sh WEB-DEPS-FOLDER SUITE...     (make wasm32-check)
set -e
deps=$1; shift
top=$(cd "$(dirname "$0")/.." && pwd)
out=$top/build/web/wasm32
mkdir -p "$out"
export NODE_PATH=${NODE_PATH:-/usr/share/nodejs}
CFLAGS="-O1 -fno-strict-aliasing -fwrapv -DHAVE_CHICKEN_CONFIG_H -DC_ENABLE_PTABLES
  -I$deps/include/chicken -I$deps/include -I$top -w"
LIBS="${WASM32_LIB:-$top/build/web/libdownstroke.a}"
for l in SDL2_ttf freetype SDL2_image SDL2_mixer SDL2 expat zstd z chicken; do
  LIBS="$LIBS $deps/lib/lib$l.a"
done

passed=0; failed=0; bad=""
for name in "$@"; do
  file=$(ls "$top"/*/tests/"$name"-test.scm "$top"/tests/"$name"-test.scm 2>/dev/null | head -1)
  [ -n "$file" ] || { echo "wasm32-check: no suite $name" >&2; exit 2; }
  # the harness, the suite, and its closing count, with what tests/suite.scm
  # imports for the suites it loads
  cat > "$out/$name.scm" <<EOF
(include "$top/tests/harness.scm")
(import (downstroke test) (chicken format) (chicken process-context posix))
(include "$file")
(test-exit)
EOF
  (cd "$top/tests" && csc -t "$out/$name.scm" -static -O1 -o "$out/$name.c" 2>"$out/$name.log") &&
    emcc $CFLAGS -c "$out/$name.c" -o "$out/$name.o" 2>>"$out/$name.log" &&
    emcc -O0 "$out/$name.o" $LIBS -sNODERAWFS=1 -sALLOW_MEMORY_GROWTH=1 -sEXIT_RUNTIME=1 \
         -o "$out/$name.js" 2>>"$out/$name.log" ||
    { echo "FAIL $name: did not build (build/web/wasm32/$name.log)"; tail -5 "$out/$name.log"; exit 1; }
  # emscripten warns on stderr at every getrusage (each collection), so a
  # collection during exit can follow the count: read the last count line,
  # and take node's exit status as well
  status=0
  (cd "$top/tests" && node --no-experimental-fetch "$out/$name.js") >"$out/$name.out" 2>&1 || status=$?
  last=$(grep -E '^[0-9]+ passed, [0-9]+ failed$' "$out/$name.out" | tail -1)
  [ -n "$last" ] || last="no count printed (exit status $status, build/web/wasm32/$name.out)"
  p=$(echo "$last" | sed -n 's/^\([0-9]*\) passed, \([0-9]*\) failed$/\1/p')
  f=$(echo "$last" | sed -n 's/^\([0-9]*\) passed, \([0-9]*\) failed$/\2/p')
  if [ -n "$p" ] && [ "$f" = 0 ] && [ "$status" != 0 ]; then
    last="$last, but node exited with status $status"; f=1
  fi
  if [ -z "$p" ]; then
    echo "FAIL $name (wasm32): $last"; failed=$((failed + 1)); bad="$bad $name"
  else
    [ "$f" = 0 ] && echo "ok   $name (wasm32): $last" || { echo "FAIL $name (wasm32): $last"; bad="$bad $name"; }
    passed=$((passed + p)); failed=$((failed + f))
  fi
done
[ -z "$bad" ] || echo "wasm32-check: failed:$bad (outputs in build/web/wasm32/)"
echo "$passed passed, $failed failed"
[ -z "$bad" ]
