#!/usr/bin/env bash
# `make bench`: the project's measurements, in sections.
#
#   scripts/bench.sh BUILD_DIR [SECTION ...]     (default: every section, in order)
#   scripts/bench.sh BUILD_DIR --list
#
# Outputs go to BUILD_DIR/bench/. Each section is a shell function `section_<name>` that prints
# its own header and results and returns non-zero on failure; the script runs all requested
# sections, then exits non-zero if any failed. To add a section: define `section_<name>` below
# and append <name> to SECTIONS (a section whose binary is not built says so and is skipped).
#
# Environment:
#   RAYCORE_FP_RANDOM   random vectors per op/mode/format in the fp_oracle section (default 1e8)
#   FP_BENCH_ARGS       arguments for fp_bench (default: 3 repetitions, medians reported;
#                       e.g. FP_BENCH_ARGS=--benchmark_filter=FP24 for one quick pass)
#   BENCH_JOBS          parallel test processes (default: nproc)
#   SHARED_SCENES       where sponza-paper.glb is (default: ../shared/scenes next to the repo)
#   RAYCORE_RANDOM_CONFIGS  configurations of the random_configs section (default 1000)
#   RAYCORE_RANDOM_VIEW_CONFIGS  configurations with random unit views (--pins / --rtl subsets,
#                       --rtl rtu) against the model in the random_configs section (default 200)
set -uo pipefail

SECTIONS=(fp_bench frames throughput cosim random_configs fp_oracle)

usage() { echo "usage: $0 BUILD_DIR [--list | SECTION ...]; sections: ${SECTIONS[*]}" >&2; exit 2; }
[ $# -ge 1 ] || usage
BUILD=$(cd "$1" 2>/dev/null && pwd) || { echo "bench: build directory '$1' not found" >&2; exit 2; }
shift
OUT="$BUILD/bench"
mkdir -p "$OUT"
JOBS=${BENCH_JOBS:-$(nproc)}

header() { printf '\n==== %s ====\n' "$*"; }
machine() {
  echo "machine: $(lscpu | sed -n 's/^Model name: *//p' | head -1), $(nproc) CPUs, load $(cut -d' ' -f1-3 /proc/loadavg)"
}

# ---- fp_bench: software throughput of the hls/fp.h operations --------------------------------
section_fp_bench() {
  header "fp_bench: hls/fp.h software throughput (ops/s, one core)"
  local bin="$BUILD/bin/fp_bench"
  if [ ! -x "$bin" ]; then
    echo "fp_bench not built (Google Benchmark missing?): skipped"
    return 0
  fi
  machine
  local args=${FP_BENCH_ARGS-"--benchmark_repetitions=3 --benchmark_report_aggregates_only=true"}
  echo "command: $bin --benchmark_out=$OUT/fp_bench.json --benchmark_out_format=json $args"
  # shellcheck disable=SC2086
  "$bin" --benchmark_out="$OUT/fp_bench.json" --benchmark_out_format=json $args \
    | tee "$OUT/fp_bench.txt" || return 1
  echo
  echo "FP24 ops/s (items_per_second, from CPU time; medians if repeated; full table above):"
  awk '
    /^FP24\// {
      name = $1
      if (name ~ /_(mean|stddev|cv)$/) next   # with repetitions: keep the median
      sub(/_median$/, "", name)
      split(name, p, "/"); op = p[2]; mode = (p[3] == "" ? "-" : p[3]);
      for (i = 2; i <= NF; i++) if ($i ~ /^items_per_second=/) { v = $i; sub(/items_per_second=/, "", v); sub(/\/s$/, "", v) }
      if (!(op in seen)) { seen[op] = 1; order[++n] = op }
      r[op, mode] = v
    }
    END {
      printf "  %-12s %12s %12s\n", "op", "rtz", "rne"
      for (i = 1; i <= n; i++) {
        op = order[i]
        a = ((op, "rtz") in r) ? r[op, "rtz"] : (((op, "-") in r) ? r[op, "-"] : "")
        b = ((op, "rne") in r) ? r[op, "rne"] : (((op, "-") in r) ? "(same)" : "")
        printf "  %-12s %12s %12s\n", op, a, b
      }
    }' "$OUT/fp_bench.txt"
  echo "JSON: $OUT/fp_bench.json"
}

# ---- fp_oracle: hls/fp.h against MPFR with many random vectors ---------------------------------
# Sums the FPSUM lines the tests print (one per format, op, mode and vector set; the exhaustive
# shards are merged) into a table.
fp_summary_table() {
  awk '
    /^FPSUM / {
      set = $5; sub(/\[[0-9]+\/[0-9]+\]$/, "", set)
      key = $2 " " $3 " " $4 " " set
      v = $6; sub(/vectors=/, "", v); m = $7; sub(/mismatches=/, "", m)
      if (!(key in vec)) order[++n] = key
      vec[key] += v; mis[key] += m
    }
    END {
      for (i = 1; i <= n; i++) {
        split(order[i], k, " ")
        printf "  %-6s %-24s %-4s %-20s %14.0f %10d\n", k[1], k[2], k[3], k[4], vec[order[i]], mis[order[i]]
        tv += vec[order[i]]; tm += mis[order[i]]
      }
      printf "ZZZZ total: %.0f vectors, %d mismatches\n", tv, tm
    }' "$1" | LC_ALL=C sort -k1,1 -k2,2 -k4,4 -k3,3 | sed 's/^ZZZZ /  /' |
    { printf "  %-6s %-24s %-4s %-20s %14s %10s\n" format op mode set vectors mismatches; cat; }
}

# ---- frames: golden tracer, reference and cycle model on full 800x480 frames -------------------
# Golden speed (FP24 and FP32, both cores), kd-tree build, reference speed, and the cycle model of
# sponza-paper with 6 RTUs, VTU off and on (golden_match must be true; cycles within 3%: the VTU's
# fill latency cost 0.08% with the one-pipe baseline, 0.94% at the faster defaults; 1.86% before its
# four node lanes and depth 4, issue 26 part 5).
json_get() {  # json_get FILE a.b.c  -> value (python3 if present, else jq-free grep fallback)
  python3 -c 'import json,sys; d=json.load(open(sys.argv[1]))
for k in sys.argv[2].split("."): d=d[k]
print(d)' "$1" "$2" 2>/dev/null
}
section_frames() {
  header "frames: full 800x480 frames (golden, reference, cycle model)"
  local rc_bin="$BUILD/bin/raycore"
  local scenes=${SHARED_SCENES:-$(cd "$(dirname "$0")/.." && pwd)/../shared/scenes}
  local sponza="$scenes/sponza-paper.glb"
  if [ ! -x "$rc_bin" ]; then echo "raycore not built: skipped"; return 0; fi
  if [ ! -f "$sponza" ]; then echo "sponza-paper.glb not found in $scenes (set SHARED_SCENES): skipped"; return 0; fi
  machine
  export SYSTEMC_DISABLE_COPYRIGHT_MESSAGE=1
  local rc=0 f
  for f in "fp24 --rounding rtz" "fp32 --rounding rne"; do
    local tag=${f%% *}
    echo "command: $rc_bin render $sponza --format $f --vtu on --threads 0 --out-dir $OUT"
    # shellcheck disable=SC2086
    "$rc_bin" render "$sponza" --format $f --vtu on --threads 0 --out-dir "$OUT" \
      --report "$OUT/golden-$tag.json" --png "$OUT/golden-$tag.png" || rc=1
  done
  for v in off on; do
    echo "command: $rc_bin simulate $sponza --vtu $v --no-reference --out-dir $OUT"
    "$rc_bin" simulate "$sponza" --vtu "$v" --no-reference --out-dir "$OUT" \
      --report "$OUT/simulate-vtu-$v.json" --png "$OUT/simulate-vtu-$v.png" || rc=1
  done
  local c0 c1
  c0=$(json_get "$OUT/simulate-vtu-off.json" hardware.cycles)
  c1=$(json_get "$OUT/simulate-vtu-on.json" hardware.cycles)
  if [ -n "$c0" ] && [ -n "$c1" ]; then
    python3 -c "import sys; a,b=float(sys.argv[1]),float(sys.argv[2]); r=b/a; print('VTU on/off cycle ratio: %.4f (%s)' % (r, 'within 3%' if abs(r-1)<=0.03 else 'NOT within 3%')); sys.exit(0 if abs(r-1)<=0.03 else 1)" "$c0" "$c1" || rc=1
  fi
  for v in off on; do
    [ "$(json_get "$OUT/simulate-vtu-$v.json" golden_match)" = "True" ] || { echo "golden_match false (VTU $v)"; rc=1; }
  done
  return $rc
}

# ---- cosim: the frame with pin-level units (SystemC twins, then Verilated RTL) in place ---------
# sponza-paper 800x480, 6 RTUs, VTU on: the vtu, ist and rgu as SystemC twins (--pins) and as Verilated
# --sc RTL (--rtl) must give the transaction model's cycle count (frames section) and golden_match;
# reports each run's simulated cycles/s and rays/s. Needs `frames` first (its VTU-on report).
section_cosim() {
  header "cosim: sponza-paper 800x480 with vtu+ist+hit+rgu as pin-level twins and as Verilated RTL, then every unit in RTL (--rtl all), then with the bus and its L2 too (--rtl all,membus), then every RTU one Verilated rtu.v with the bus (--rtl rtu), all at the defaults (the 512 KB L2)"
  local rc_bin="$BUILD/bin/raycore"
  local scenes=${SHARED_SCENES:-$(cd "$(dirname "$0")/.." && pwd)/../shared/scenes}
  local sponza="$scenes/sponza-paper.glb"
  if [ ! -x "$rc_bin" ]; then echo "raycore not built: skipped"; return 0; fi
  if [ ! -f "$sponza" ]; then echo "sponza-paper.glb not found in $scenes (set SHARED_SCENES): skipped"; return 0; fi
  machine
  export SYSTEMC_DISABLE_COPYRIGHT_MESSAGE=1
  local rc=0 ref="$OUT/simulate-vtu-on.json" run view units tag
  if [ ! -f "$ref" ]; then
    "$rc_bin" simulate "$sponza" --vtu on --no-reference --out-dir "$OUT" --report "$ref" \
      --png "$OUT/simulate-vtu-on.png" || return 1
  fi
  # view:units:tag; rtl-all has every unit of the RTUs in RTL, rtl-all-membus the bus (membus_l2.v,
  # the default L2) too, rtl-rtu every RTU as one Verilated rtu.v with the bus.
  for run in pins:vtu,ist,hit,rgu:pins rtl:vtu,ist,hit,rgu:rtl rtl:all:rtl-all \
             rtl:all,membus:rtl-all-membus rtl:rtu:rtl-rtu; do
    IFS=: read -r view units tag <<<"$run"
    ref="$OUT/simulate-vtu-on.json"
    # --rtl rtu: the RTUs' models on two host threads (the section runs alone).
    local threads=1
    [ "$tag" = rtl-rtu ] && threads=2
    echo "command: RAYCORE_RTL_THREADS=$threads $rc_bin simulate $sponza --vtu on --$view $units --no-reference --out-dir $OUT"
    RAYCORE_RTL_THREADS=$threads "$rc_bin" simulate "$sponza" --vtu on --"$view" "$units" --no-reference --out-dir "$OUT" \
      --report "$OUT/simulate-$tag.json" --png "$OUT/simulate-$tag.png" || { rc=1; continue; }
    local c0 c1
    c0=$(json_get "$ref" hardware.cycles)
    c1=$(json_get "$OUT/simulate-$tag.json" hardware.cycles)
    printf '%-14s cycles %s (model %s) golden_match %s wall %.1f s, %.0f cycles/s, %.0f rays/s, %s pin clock edges\n' \
      "--$view $units" "$c1" "$c0" "$(json_get "$OUT/simulate-$tag.json" golden_match)" \
      "$(json_get "$OUT/simulate-$tag.json" sim.wall_seconds)" \
      "$(json_get "$OUT/simulate-$tag.json" sim.cycles_per_second)" \
      "$(json_get "$OUT/simulate-$tag.json" sim.rays_per_second)" \
      "$(json_get "$OUT/simulate-$tag.json" sim.pin_clock_edges)"
    [ "$c0" = "$c1" ] || { echo "cycles differ from the transaction model ($view $units)"; rc=1; }
    [ "$(json_get "$OUT/simulate-$tag.json" golden_match)" = "True" ] || { echo "golden_match false ($view $units)"; rc=1; }
  done
  return $rc
}

# ---- throughput: rays/cycle per RTU of the three paper frames, default and baseline configs -----
# 800x480, 6 RTUs, 100-cycle memory, FP24 rtz, VTU off: the simulator's defaults (chosen by `make
# throughput`) and the RayCore-like baseline (configs/baseline.json, closest-hit shadow rays).
section_throughput() {
  header "throughput: rays/cycle per RTU, sponza-paper / sibenik-paper / corridor (goal 0.08 at <= 1.1 GB/s)"
  local rc_bin="$BUILD/bin/raycore"
  local root; root=$(cd "$(dirname "$0")/.." && pwd)
  local scenes=${SHARED_SCENES:-$root/../shared/scenes}
  if [ ! -x "$rc_bin" ]; then echo "raycore not built: skipped"; return 0; fi
  machine
  export SYSTEMC_DISABLE_COPYRIGHT_MESSAGE=1
  local rc=0 s arg cfg
  printf '%-14s %-9s %10s %12s %9s %9s %9s %8s %s
' scene config cycles rays/cyc/RTU Mrays/s steps/ray tests/ray GB/s golden
  for s in sponza-paper sibenik-paper corridor; do
    arg=$s
    [ "$s" != corridor ] && arg="$scenes/$s.glb"
    if [ "$s" != corridor ] && [ ! -f "$arg" ]; then echo "$arg not found (set SHARED_SCENES): skipped"; continue; fi
    for cfg in default baseline; do
      local extra=() out="$OUT/throughput-$s-$cfg.json"
      [ $cfg = baseline ] && extra=(--config "$root/configs/baseline.json" --shadow-hit closest)
      "$rc_bin" simulate "$arg" --vtu off --no-reference --quiet --out-dir "$OUT" --report "$out"         --png "$OUT/throughput-$s-$cfg.png" "${extra[@]}" || { rc=1; continue; }
      printf '%-14s %-9s %10s %12.4f %9.1f %9.1f %9.1f %8.3f %s
' "$s" "$cfg"         "$(json_get "$out" hardware.cycles)" "$(json_get "$out" hardware.rays_per_cycle_per_rtu)"         "$(json_get "$out" hardware.mrays_per_s)" "$(json_get "$out" hardware.per_ray.trv_steps)"         "$(json_get "$out" hardware.per_ray.tri_tests)" "$(json_get "$out" hardware.bus.bandwidth_gb_s)"         "$(json_get "$out" golden_match)"
      [ "$(json_get "$out" golden_match)" = "True" ] || { echo "golden_match false ($s $cfg)"; rc=1; }
    done
  done
  echo "commands: raycore simulate SCENE --vtu off --no-reference [--config configs/baseline.json --shadow-hit closest]"
  return $rc
}

# ---- random_configs: the randomised-configuration test, long -----------------------------------
# random_runs BIN COUNT_VAR N LOG SUM SEED...: BIN with COUNT_VAR=N/2 configurations per seed.
random_runs() {
  local bin=$1 var=$2 n=$3 log=$4 sum=$5 seed rc=0
  shift 5
  for seed in "$@"; do
    echo "command: $var=$((n / 2)) RAYCORE_RANDOM_CONFIG_SEED=$seed $bin"
    env SYSTEMC_DISABLE_COPYRIGHT_MESSAGE=1 "$var=$((n / 2))" RAYCORE_RANDOM_CONFIG_SEED="$seed" \
      "$bin" > "$OUT/$log-$seed.log" 2>&1 || rc=1
    grep -E "$sum|Failure|RAYCORE_RANDOM_CONFIG_SEED=" "$OUT/$log-$seed.log" | head -8
  done
  return $rc
}

section_random_configs() {
  local n=${RAYCORE_RANDOM_CONFIGS:-1000}
  header "random_configs: $n random configurations of the cycle model, each against the golden tracer"
  local bin="$BUILD/bin/test_random_config"
  if [ ! -x "$bin" ]; then echo "test_random_config not built: skipped"; return 0; fi
  machine
  local t0=$SECONDS rc=0
  random_runs "$bin" RAYCORE_RANDOM_CONFIGS "$n" random_configs RANDOMCONFIGSUM 101 102 || rc=1
  # The same draws with random unit views (tb/systemc/test_random_config.cpp, RandomViews): each
  # view runs the frame exactly as the transaction model or refuses it with what it is built for.
  local views=${RAYCORE_RANDOM_VIEW_CONFIGS:-200} vbin="$BUILD/bin/test_random_config_rtl"
  if [ -x "$vbin" ]; then
    random_runs "$vbin" RAYCORE_RANDOM_VIEW_CONFIGS "$views" random_views RANDOMVIEWSUM 103 104 || rc=1
  else
    echo "test_random_config_rtl not built (RAYCORE_RTL=OFF): the unit views are not drawn"
  fi
  echo "wall time: $((SECONDS - t0)) s; logs: $OUT/random_configs-*.log, $OUT/random_views-*.log"
  return $rc
}

section_fp_oracle() {
  local n=${RAYCORE_FP_RANDOM:-100000000}
  header "fp_oracle: hls/fp.h vs MPFR and host float, RAYCORE_FP_RANDOM=$n"
  if [ ! -x "$BUILD/bin/fp_oracle_test" ]; then
    echo "fp_oracle_test not built: skipped"
    return 0
  fi
  machine
  local sum="$OUT/fp_oracle_summary.txt" log="$OUT/fp_oracle.log"
  rm -f "$sum"
  echo "command: RAYCORE_FP_RANDOM=$n ctest -R '^fp\\.' -L unit -j $JOBS --timeout 100000 (in $BUILD)"
  local t0=$SECONDS rc=0
  (cd "$BUILD" && RAYCORE_FP_RANDOM=$n RAYCORE_FP_SUMMARY="$sum" \
     ctest -R '^fp\.' -L unit -j "$JOBS" --timeout 100000 --output-on-failure) > "$log" 2>&1 || rc=$?
  grep -E '^(Total Test time|[0-9]+% tests passed)' "$log"
  sed -n '/^The following tests FAILED/,/^Errors while running/p' "$log" | head -40
  echo "wall time: $((SECONDS - t0)) s; log: $log; summary lines: $sum"
  [ -s "$sum" ] && fp_summary_table "$sum"
  return $rc
}

# ---- driver -------------------------------------------------------------------------------------
if [ "${1:-}" = "--list" ]; then printf '%s\n' "${SECTIONS[@]}"; exit 0; fi
run=("$@")
[ ${#run[@]} -gt 0 ] || run=("${SECTIONS[@]}")
failed=()
for s in "${run[@]}"; do
  if ! declare -F "section_$s" >/dev/null; then
    echo "bench: unknown section '$s' (sections: ${SECTIONS[*]})" >&2
    exit 2
  fi
  "section_$s" || failed+=("$s")
done
echo
if [ ${#failed[@]} -gt 0 ]; then
  echo "bench: FAILED sections: ${failed[*]}"
  exit 1
fi
echo "bench: all sections done (${run[*]}); outputs in $OUT"
