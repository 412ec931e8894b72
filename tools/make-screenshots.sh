#!/bin/sh
# Screenshots of every demo for the docs (make screenshots): each demo runs
# headless for a number of frames, with scripted input where a still of the
# first frames would show nothing happening, and saves docs/images/demo-NAME.png.
set -e
cd "$(dirname "$0")/.."
out=docs/images
mkdir -p "$out"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# shot NAME FRAMES [SCRIPT]: SCRIPT is an input script, ((frame action ...) ...).
shot() {
  if [ -n "$3" ]; then
    echo "$3" > "$tmp/$1.scm"
    set -- "$1" "$2" --script "$tmp/$1.scm"
  else
    set -- "$1" "$2"
  fi
  name=$1 frames=$2; shift 2
  bin/demo-"$name" --headless --frames "$frames" --screenshot "$out/demo-$name.png" "$@" >/dev/null 2>&1
  echo "wrote $out/demo-$name.png"
}

shot getting-started 40 '((0 right down) (12))'
shot platformer 151 '((0 start) (1 right) (41 right a) (42 right) (91))'
shot shmup 200 '((0 a))'
shot topdown 160 '((0 up) (30 left) (90 down) (110))'
shot sandbox 300
shot tweens 90
shot animation 155
shot audio 120 '((10 a) (11) (40 start) (41) (70 b) (71))'

# docs/physics.org's ladder: the platformer started beside its ladder, up held.
echo '((0 start) (1 up))' > "$tmp/ladder.scm"
bin/demo-platformer --headless --start-x 858 --frames 40 --script "$tmp/ladder.scm" \
  --screenshot "$out/physics-ladder.png" >/dev/null 2>&1
echo "wrote $out/physics-ladder.png"
