# tb/rtl/icarus_lib.sh - what the Icarus runners share (sourced by tb/rtl/run_icarus.sh and
# tb/sweep/run_spawn_icarus.sh; their testbenches include tb/rtl/tb_stream.vh).
#   icarus_setup <FP24|FP32> <rtz|rne|raycore>   checks iverilog/vvp; sets e, m (exponent/mantissa
#                                        bits), rne and raycore (the RNE and RAYCORE parameters)
#   icarus_result <log> <n> <label>      passes only if the RESULT line says every one of the n > 0
#                                        vectors was checked with no mismatch; prints <label>
icarus_setup() {
  command -v iverilog >/dev/null && command -v vvp >/dev/null ||
    { echo "$(basename "$0"): iverilog/vvp not found (make deps)" >&2; exit 1; }
  case $1 in FP24) e=7 m=16 ;; FP32) e=8 m=23 ;; *) echo "bad format $1" >&2; exit 2 ;; esac
  raycore=0
  case $2 in rtz) rne=0 ;; rne) rne=1 ;; raycore) rne=0 raycore=1 ;; *) echo "bad mode $2" >&2; exit 2 ;; esac
}
icarus_result() {
  local line checked bad
  line=$(grep '^RESULT ' "$1" || true)
  checked=$(sed -n 's/^RESULT vectors=\([0-9]*\).*/\1/p' <<<"$line")
  bad=$(sed -n 's/.* mismatches=\([0-9]*\).*/\1/p' <<<"$line")
  echo "ICARUS $3 vectors=${checked:-0} of $2 mismatches=${bad:-?}"
  [ -n "$checked" ] && [ "$checked" -eq "$2" ] && [ "$checked" -gt 0 ] && [ "$bad" -eq 0 ]
}
