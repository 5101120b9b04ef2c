#!/usr/bin/env bash
# make throughput: rays/cycle per RTU against RTU area for the levers of issue 14 (docs/results.md).
#
#   scripts/throughput.sh [BUILD] [raycore throughput options...]   e.g. --scenes corridor --width 200
#
# 1. `raycore throughput --list` -> OUT/jobs.txt (one `raycore simulate` per scene x configuration)
# 2. GNU parallel runs them (TP_JOBS at a time, default nproc)
# 3. `raycore throughput --collect OUT` -> OUT/throughput.{md,csv}, OUT/plot-<scene>.dat (and the
#    tables into TP_DOC, default docs/results.md; empty: none)
# 4. gnuplot: OUT/throughput.png (copied to docs/throughput.png when TP_DOC is set)
# Environment: TP_OUT (out/throughput), TP_JOBS, TP_DOC.
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=${1:-build}
[ $# -gt 0 ] && shift
RAYCORE=$BUILD/bin/raycore
OUT=${TP_OUT:-out/throughput}
DOC=${TP_DOC-docs/results.md}
export SYSTEMC_DISABLE_COPYRIGHT_MESSAGE=1
[ -x "$RAYCORE" ] || { echo "throughput: no $RAYCORE (build first: make build)" >&2; exit 1; }
command -v parallel >/dev/null || { echo "throughput: GNU parallel is needed (make deps)" >&2; exit 1; }
mkdir -p "$OUT"
t0=$(date +%s)
"$RAYCORE" throughput --list --out "$OUT" "$@" > "$OUT/jobs.txt"
echo "throughput: $(wc -l < "$OUT/jobs.txt") jobs (list: $OUT/jobs.txt)"
failed=0
parallel --will-cite --jobs "${TP_JOBS:-$(nproc)}" --joblog "$OUT/joblog.tsv" < "$OUT/jobs.txt" || failed=$?
[ $failed -ne 0 ] && echo "throughput: $failed jobs failed (see $OUT/joblog.tsv)" >&2
COLLECT=("$RAYCORE" throughput --collect "$OUT")
[ -n "$DOC" ] && COLLECT+=(--doc "$DOC")
"${COLLECT[@]}"
echo "throughput: $(( $(date +%s) - t0 )) s wall"
command -v gnuplot >/dev/null || { echo "throughput: gnuplot not installed: no plot" >&2; exit 0; }
scenes=$(ls "$OUT"/plot-*.dat | sed 's|.*/plot-||; s|\.dat$||' | tr '\n' ' ')
gnuplot -e "dir='$OUT'; out='$OUT/throughput.png'; scenes='$scenes'" scripts/throughput.gp
echo "throughput: wrote $OUT/throughput.png"
[ -n "$DOC" ] && cp "$OUT/throughput.png" docs/throughput.png
exit $failed
