#!/usr/bin/env bash
# make run: the cycle-accurate simulation of one frame of the default scene (corridor, shipped in
# scenes/), 800 x 480, FP24 rtz, VTU on, 6 RTUs; checked pixel by pixel against the golden tracer
# (golden_match) and measured against the double-precision reference (error metrics).
set -euo pipefail
RAYCORE=${1:-build/bin/raycore}
shift || true
export SYSTEMC_DISABLE_COPYRIGHT_MESSAGE=1
mkdir -p out
exec "$RAYCORE" simulate corridor --format fp24 --rounding rtz --vtu on --spawn none \
  --out-dir out --png out/run.png --report out/run.json "$@"
