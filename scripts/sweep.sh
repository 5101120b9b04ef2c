#!/usr/bin/env bash
# make sweep: the speed-against-error sweep (issues 6 and 15; docs/sweep.md): scenes x format x VTU x
# spawn x store; --stores and --shadow-spawn go to `raycore sweep --list` like any other option.
#
#   scripts/sweep.sh [BUILD] [raycore sweep options...]     e.g. scripts/sweep.sh build --scenes corridor
#
# 1. added hardware: scripts/sweep_area.sh (yosys) -> OUT/area.tsv
# 2. `raycore sweep --list` -> OUT/jobs.txt (one `raycore simulate|errormap` command per line)
# 3. GNU parallel runs the lines (here, or on several hosts with SWEEP_SSHLOGIN)
# 4. `raycore sweep --collect OUT` -> OUT/sweep.{csv,json,md}, plot data (and docs/sweep.md)
# 5. gnuplot: OUT/sweep.png (error vs rays/cycle, Pareto front, one panel per scene), the error-map
#    montages OUT/maps-<scene>.png, and the far-offset plot (tb/robust/plot_far_offset.sh)
#
# Environment: SWEEP_OUT (out/sweep), SWEEP_JOBS (parallel jobs, default nproc), SWEEP_SSHLOGIN
# (parallel --sshlogin list; the working directory must be the same path on every host: a shared
# filesystem), SWEEP_RESUME=1 (rerun only jobs that failed or did not run, from OUT/joblog.tsv),
# SWEEP_DOC (markdown file to update, default docs/sweep.md; empty: none; the PNGs are then not
# copied to docs/ either), SWEEP_AREA=0 (skip yosys), SWEEP_FAR_OFFSET=0 (skip the far-offset plot).
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=${1:-build}
[ $# -gt 0 ] && shift
RAYCORE=$BUILD/bin/raycore
OUT=${SWEEP_OUT:-out/sweep}
DOC=${SWEEP_DOC-docs/sweep.md}
export SYSTEMC_DISABLE_COPYRIGHT_MESSAGE=1
[ -x "$RAYCORE" ] || { echo "sweep: no $RAYCORE (build first: make build)" >&2; exit 1; }
command -v parallel >/dev/null || { echo "sweep: GNU parallel is needed (make deps)" >&2; exit 1; }
mkdir -p "$OUT"
t0=$(date +%s)

AREA=()
if [ "${SWEEP_AREA:-1}" != 0 ]; then
  ./scripts/sweep_area.sh > "$OUT/area.tsv.tmp" && mv "$OUT/area.tsv.tmp" "$OUT/area.tsv"
  AREA=(--area "$OUT/area.tsv")
fi
t_area=$(date +%s)

"$RAYCORE" sweep --list --out "$OUT" "$@" > "$OUT/jobs.txt"
njobs=$(wc -l < "$OUT/jobs.txt")
echo "sweep: $njobs jobs (list: $OUT/jobs.txt)"
PAR=(--will-cite --jobs "${SWEEP_JOBS:-$(nproc)}" --joblog "$OUT/joblog.tsv")
[ -n "${SWEEP_SSHLOGIN:-}" ] && PAR+=(--sshlogin "$SWEEP_SSHLOGIN" --workdir "$PWD")
[ "${SWEEP_RESUME:-0}" = 1 ] && PAR+=(--resume-failed)
failed=0
parallel "${PAR[@]}" < "$OUT/jobs.txt" || failed=$?
[ $failed -ne 0 ] && echo "sweep: $failed jobs failed (see $OUT/joblog.tsv; SWEEP_RESUME=1 reruns them)" >&2
t_jobs=$(date +%s)

COLLECT=("$RAYCORE" sweep --collect "$OUT")
[ ${#AREA[@]} -gt 0 ] && COLLECT+=("${AREA[@]}")
[ -n "$DOC" ] && COLLECT+=(--doc "$DOC")
"${COLLECT[@]}"

command -v gnuplot >/dev/null || { echo "sweep: gnuplot not installed: no plots" >&2; exit 0; }
gnuplot -e "dir='$OUT'; out='$OUT/sweep.png'" scripts/sweep.gp
echo "sweep: wrote $OUT/sweep.png"
# Error-map montages, one per scene (full frames on top, the worst windows enlarged below).
if [ -s "$OUT/maps.tsv" ]; then
  for scene in $(cut -f1 "$OUT/maps.tsv" | sort -u); do
    awk -F'\t' -v s="$scene" '$1 == s' "$OUT/maps.tsv" > "$OUT/maps-$scene.tsv"
    gnuplot -e "list='$OUT/maps-$scene.tsv'; scene='$scene'; out='$OUT/maps-$scene.png'" scripts/sweep_maps.gp
    echo "sweep: wrote $OUT/maps-$scene.png"
  done
fi
# The far-offset plot: tb/robust/plot_far_offset.sh run from a copy, so that it writes into OUT
# (it writes <its root>/docs/far_offset.{dat,png}) instead of docs/.
if [ "${SWEEP_FAR_OFFSET:-1}" != 0 ]; then
  if [ -x "$BUILD/bin/test_robust" ] && [ -f tb/robust/plot_far_offset.sh ]; then
    fo=$(mktemp -d "${TMPDIR:-/tmp}/raycore-far.XXXXXX")
    mkdir -p "$fo/tb/robust" "$fo/docs"
    cp tb/robust/plot_far_offset.sh "$fo/tb/robust/"
    if sh "$fo/tb/robust/plot_far_offset.sh" "$(cd "$BUILD" && pwd)" >/dev/null; then
      cp "$fo/docs/far_offset.dat" "$fo/docs/far_offset.png" "$OUT/"
      echo "sweep: wrote $OUT/far_offset.png (tb/robust FarOffset.VtuKeepsErrorFlat)"
    else
      echo "sweep: far-offset plot failed (tb/robust/plot_far_offset.sh)" >&2
    fi
    rm -rf "$fo"
  else
    echo "sweep: no $BUILD/bin/test_robust: far-offset plot skipped (docs/far_offset.png is the last one)" >&2
  fi
fi
if [ -n "$DOC" ]; then
  cp "$OUT/sweep.png" docs/sweep.png
  for f in "$OUT"/maps-*.png; do [ -f "$f" ] && cp "$f" "docs/sweep_$(basename "$f")"; done
  [ -f "$OUT/far_offset.png" ] && cp "$OUT/far_offset.png" docs/sweep_far_offset.png
  echo "sweep: copied the plots to docs/ (sweep.png, sweep_maps-*.png, sweep_far_offset.png)"
fi
t1=$(date +%s)
echo "sweep: $njobs jobs; wall $((t1 - t0)) s (area $((t_area - t0)) s, jobs $((t_jobs - t_area)) s, collect + plots $((t1 - t_jobs)) s)"
exit $([ $failed -eq 0 ] && echo 0 || echo 1)
