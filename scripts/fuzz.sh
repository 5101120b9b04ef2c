#!/usr/bin/env bash
# Fuzzes the glTF scene loader (scenes/gltf.cpp + tinygltf) with libFuzzer, for a bounded time.
#
#   scripts/fuzz.sh                 # 60 s
#   FUZZ_SECONDS=600 scripts/fuzz.sh
#
# Built with clang (-fsanitize=fuzzer,address,undefined), outside the CMake build: the loader and
# tinygltf itself are compiled into the fuzzer, so both are instrumented. The working corpus and
# any crash / timeout / out-of-memory inputs go to $FUZZ_DIR (default build-fuzz/); the seeds are
# tb/fuzz/seeds/. A finding makes the script exit non-zero and print the input's path; pin it as a
# literal case in tb/scenes/test_fuzz_regressions.cpp once fixed.
#
# Environment: FUZZ_SECONDS (60), FUZZ_DIR (build-fuzz), FUZZ_JOBS (1), CLANGXX (clang++ or clang++-14),
# FUZZ_NICE (19: the fuzzer runs at low priority).
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
OUT=${FUZZ_DIR:-$ROOT/build-fuzz}
SECS=${FUZZ_SECONDS:-60}
JOBS=${FUZZ_JOBS:-1}
NICE=${FUZZ_NICE:-19}
CLANGXX=${CLANGXX:-$(command -v clang++ || command -v clang++-14 || true)}
if [ -z "$CLANGXX" ]; then
  echo "fuzz: clang++ not found (Debian: apt-get install clang libclang-rt-14-dev, or make deps)" >&2
  exit 1
fi
mkdir -p "$OUT/obj" "$OUT/corpus" "$OUT/artifacts"

FLAGS=(-std=c++17 -O1 -g -fno-omit-frame-pointer -fsanitize=fuzzer-no-link,address,undefined
       -fno-sanitize-recover=undefined -ffp-contract=off -I"$ROOT" -w
       -DTINYGLTF_NO_STB_IMAGE -DTINYGLTF_NO_STB_IMAGE_WRITE -DTINYGLTF_NO_EXTERNAL_IMAGE)
# tinygltf's implementation is compiled once (it only changes with the Debian package); the
# loader and the target every time (a few seconds).
compile() {
  local src=$1 obj=$OUT/obj/$(basename "${1%.*}").o
  echo "fuzz: compiling ${src#"$ROOT"/}"
  nice -n "$NICE" "$CLANGXX" "${FLAGS[@]}" -c "$src" -o "$obj"
  OBJS+=("$obj")
}
OBJS=()
if [ ! -f "$OUT/obj/tinygltf_impl.o" ] || [ /usr/include/tiny_gltf.h -nt "$OUT/obj/tinygltf_impl.o" ]; then
  compile "$ROOT/tb/fuzz/tinygltf_impl.cpp"
else
  OBJS+=("$OUT/obj/tinygltf_impl.o")
fi
compile "$ROOT/scenes/gltf.cpp"
compile "$ROOT/tb/fuzz/fuzz_loader.cpp"
"$CLANGXX" -fsanitize=fuzzer,address,undefined "${OBJS[@]}" -o "$OUT/fuzz_loader"

echo "fuzz: running $OUT/fuzz_loader for ${SECS}s (corpus $OUT/corpus, seeds tb/fuzz/seeds)"
PARALLEL=()
[ "$JOBS" -gt 1 ] && PARALLEL=(-jobs="$JOBS" -workers="$JOBS")  # writes fuzz-N.log into $OUT
cd "$OUT"
set +e
ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:allocator_may_return_null=1} \
UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1} \
nice -n "$NICE" "$OUT/fuzz_loader" "$OUT/corpus" "$ROOT/tb/fuzz/seeds" \
  -dict="$ROOT/tb/fuzz/gltf.dict" -max_total_time="$SECS" -max_len=16384 -timeout=10 -rss_limit_mb=2048 \
  -malloc_limit_mb=1024 "${PARALLEL[@]}" -print_final_stats=1 \
  -artifact_prefix="$OUT/artifacts/" 2>&1 | tee "$OUT/fuzz.log" | grep -v '^#[0-9]*	\(NEW\|REDUCE\|pulse\)'
rc=${PIPESTATUS[0]}
set -e
found=$(find "$OUT/artifacts" -type f -newer "$OUT/fuzz_loader" | head -20)
if [ "$rc" -ne 0 ] || [ -n "$found" ]; then
  echo "fuzz: FINDINGS (exit $rc):" >&2
  for f in $found; do echo "  $f" >&2; done
  echo "fuzz: reproduce with $OUT/fuzz_loader <file>; full log in $OUT/fuzz.log" >&2
  exit 1
fi
echo "fuzz: no findings in ${SECS}s ($(ls "$OUT/corpus" | wc -l) corpus inputs); log in $OUT/fuzz.log"
