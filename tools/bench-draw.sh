#!/bin/sh
# The drawing scenes of docs/performance.org ("Drawing against LÖVE"):
# bench/draw.scm (compiled to build/bench-draw) and, when `love` is
# installed (tools/install-deps.sh bench), bench/love, in turn, ROUNDS
# rounds (default 5) under one Xvfb screen each run; prints each side's
# median CPU ms per frame and the ratio Downstroke / LÖVE, and stops if the
# two sides print different places (they would not be drawing the same).
#   sh tools/bench-draw.sh [BUILD_DIR]     (BUILD_DIR: the modules, default build)
# SCENES (a comma-separated list, default the five below) picks others:
#   SCENES="sprites 2200,fancy 1100" sh tools/bench-draw.sh
set -e
BUILD=${1:-build}
ROUNDS=${ROUNDS:-5}
REPO=$(cd "$BUILD" && pwd):$(env -u CHICKEN_INSTALL_REPOSITORY chicken-install -repository)
ms() { sed -n 's/.*: \([0-9.]*\) ms CPU per frame.*/\1/p'; }
places() { sed -n 's/.*, places \([0-9/]*\)$/\1/p'; }
median() { sort -n | awk '{v[NR]=$1} END {print (NR%2 ? v[(NR+1)/2] : (v[NR/2]+v[NR/2+1])/2)}'; }
has_love=no; [ -z "$NO_LOVE" ] && command -v love >/dev/null 2>&1 && has_love=yes
SCENES=${SCENES:-sprites 1000,sprites 5000,fancy 1000,fancy 5000,map}
echo "$SCENES" | tr ',' '\n' | while read -r scene; do
  ds=""; lv=""; i=0
  while [ $i -lt "$ROUNDS" ]; do
    out=$(env -u SDL_VIDEODRIVER CHICKEN_REPOSITORY_PATH="$REPO" xvfb-run -a -s '-screen 0 1024x768x24' build/bench-draw $scene </dev/null)
    ds="$ds $(echo "$out" | ms)"
    if [ $has_love = yes ]; then
      lout=$(env -u SDL_VIDEODRIVER xvfb-run -a -s '-screen 0 1024x768x24' love bench/love $scene </dev/null 2>/dev/null)
      lv="$lv $(echo "$lout" | ms)"
      # the two sides must draw the same places, or the times do not compare
      if [ "$(echo "$out" | places)" != "$(echo "$lout" | places)" ]; then
        echo "draw $scene: the two sides drew different places:" >&2
        echo "  $out" >&2; echo "  $lout" >&2
        exit 1
      fi
    fi
    i=$((i + 1))
  done
  d=$(echo $ds | tr ' ' '\n' | median)
  if [ $has_love = yes ]; then
    l=$(echo $lv | tr ' ' '\n' | median)
    echo "draw $scene: Downstroke $d ms, LÖVE $l ms CPU per frame (medians of $ROUNDS), ratio $(echo "$d $l" | awk '{printf "%.2f", $1/$2}')"
  else
    echo "draw $scene: Downstroke $d ms CPU per frame (median of $ROUNDS; LÖVE not installed)"
  fi
done
