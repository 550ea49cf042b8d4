#!/usr/bin/env bash
# Renders the pictures of the charts and animations in docs/ from the program's SVG, with
# rsvg-convert (Debian's librsvg2-bin, installed if missing). An animation's picture is its
# first frame.
#
#   bash docs/render.sh
set -euo pipefail
cd "$(dirname "$0")/.."
command -v rsvg-convert >/dev/null || apt-get install -y -q librsvg2-bin >/dev/null
cargo build -q --release -p mechanisms
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
sweep() { target/release/mechanisms sweep "$@" --out-dir "$scratch" --csv - >/dev/null; }
sweep four-bar 180 80 200 150 --coupler-point 100,30
rsvg-convert -o docs/sweep-four-bar.png "$scratch/sweep.svg"
rsvg-convert -o docs/animation-four-bar.png "$scratch/animation.svg"
sweep slider-crank 200 50 0
rsvg-convert -o docs/sweep-slider-crank.png "$scratch/sweep.svg"
sweep jansen
rsvg-convert -o docs/jansen-leg.png "$scratch/animation.svg"
