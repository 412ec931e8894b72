#!/bin/sh
# Turns bench/results.csv into the plots docs/performance.org shows.
# Needs gnuplot (Debian's gnuplot-nox), installed here when missing.
set -e
csv=${1:-bench/results.csv}
out=${2:-docs/images}
mkdir -p "$out"
if ! command -v gnuplot >/dev/null; then
  if [ "$(id -u)" -eq 0 ]; then SUDO=""; else SUDO="sudo"; fi
  # Only gnuplot: its recommends pull in ImageMagick and Ghostscript.
  install="$SUDO env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends gnuplot-nox"
  $install || { $SUDO apt-get update -qq && $install; }
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# One data file per (scene, mode): columns n-or-speed, us/entity-frame, wrong %.
awk -F, -v dir="$tmp" 'NR > 1 {
  key = $2
  if ($1 == "S3") print $4, $7, $9 > (dir "/s3-" key ".dat")
  if ($1 == "S1") print $3, $7 > (dir "/s1-" key ".dat")
  if ($1 == "S2") print $3, $7 > (dir "/s2-" key ".dat")
  if ($1 == "S1-step") { gsub(/ /, "_", $2); print $2, $7 > (dir "/steps.dat") }
}' "$csv"

gnuplot <<GP
set terminal pngcairo size 760,420 font "DejaVu Sans,10"
set grid
set key top left
set logscale x

set output "$out/s3-cost.png"
set title "S3: cost per mover-frame against speed"
set xlabel "speed (px/frame)"; set ylabel "microseconds per mover-frame"
plot "$tmp/s3-discrete.dat" using 1:2 with linespoints title "discrete", \
     "$tmp/s3-swept.dat" using 1:2 with linespoints title "swept"

set output "$out/s3-error.png"
set title "S3: movers ending in the wrong place against speed"
set ylabel "% wrong (tunnelled or not flush)"; set yrange [-5:105]
plot "$tmp/s3-discrete.dat" using 1:3 with linespoints title "discrete", \
     "$tmp/s3-swept.dat" using 1:3 with linespoints title "swept"
set autoscale y

set output "$out/s1-s2-scaling.png"
set title "S1 and S2: cost per entity-frame against crowd size"
set xlabel "entities"; set ylabel "microseconds per entity-frame"; set logscale y
plot "$tmp/s1-discrete.dat" using 1:2 with linespoints title "S1 discrete", \
     "$tmp/s1-swept.dat" using 1:2 with linespoints title "S1 swept", \
     "$tmp/s2-all-pairs.dat" using 1:2 with linespoints title "S2 all pairs", \
     "$tmp/s2-spatial-hash.dat" using 1:2 with linespoints title "S2 spatial hash"
unset logscale

set output "$out/s1-steps.png"
set title "S1, 10,000 movers: each step alone, microseconds per entity"
set style data histograms; set style fill solid 0.6; set boxwidth 0.8
set xtics rotate by -35 noenhanced; unset key; set xlabel ""; set ylabel "us per entity"
plot "$tmp/steps.dat" using 2:xtic(1)
GP
echo "plots written to $out"
