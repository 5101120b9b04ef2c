#!/usr/bin/env bash
# make run: one frame of the default scene (corridor, shipped in scenes/), 800 x 480, FP24 rtz,
# VTU on, traced by the golden tracer and checked against the double-precision reference.
# (The cycle-accurate frame simulation is issue 4's `raycore simulate`; until it lands this is the
# frame the hardware model will have to reproduce bit for bit.)
set -euo pipefail
RAYCORE=${1:-build/bin/raycore}
shift || true
mkdir -p out
exec "$RAYCORE" render corridor --format fp24 --rounding rtz --vtu on --spawn none \
  --out-dir out --png out/run.png --report out/run.json "$@"
