# RayCore + VTU model. `make run` and `make test` are the two commands a user types on a fresh
# machine: both install the Debian packages they need (deps) and build first.
BUILD      ?= build
ASAN_BUILD ?= build-asan
RUN_BUILD  ?= build-run
JOBS       ?= $(shell nproc)
GEN        := $(shell command -v ninja >/dev/null 2>&1 && echo "-G Ninja")
CTEST      := ctest --output-on-failure -j $(JOBS)
RAYCORE    := $(BUILD)/bin/raycore
export SYSTEMC_DISABLE_COPYRIGHT_MESSAGE := 1

.PHONY: all deps configure build run test test-release test-asan lint bench chip area area-rtu area-configs timing fuzz table3 sweep throughput clean

all: build

deps:
	@./scripts/deps.sh

$(BUILD)/CMakeCache.txt:
	cmake -S . -B $(BUILD) $(GEN) -DCMAKE_BUILD_TYPE=Release

configure: deps $(BUILD)/CMakeCache.txt

build: configure
	cmake --build $(BUILD) -j $(JOBS)

# Only what the run needs: the raycore binary without the Verilated models (`--rtl`), in its own
# build folder (the tests, benches and the RTL in the frame are `make build` / `make test`'s).
run: deps
	cmake -S . -B $(RUN_BUILD) $(GEN) -DCMAKE_BUILD_TYPE=Release -DRAYCORE_RTL=OFF
	cmake --build $(RUN_BUILD) --target raycore -j $(JOBS)
	./scripts/run.sh $(RUN_BUILD)/bin/raycore

# The unit tests in Release (all of them), then once more under ASan + UBSan (the C++ unit
# tests; Verilated models are left out of the sanitizer build, see README). Under the sanitizers
# the randomised configurations are 24 others (seed 2; Release runs seed 1's 48).
test: test-release test-asan

test-release: build
	cd $(BUILD) && $(CTEST)

test-asan: deps
	cmake -S . -B $(ASAN_BUILD) $(GEN) -DCMAKE_BUILD_TYPE=RelWithDebInfo -DRAYCORE_SANITIZE=ON -DRAYCORE_RTL=OFF
	cmake --build $(ASAN_BUILD) -j $(JOBS)
	cd $(ASAN_BUILD) && ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 RAYCORE_FP_RANDOM=200000 \
	  RAYCORE_RANDOM_CONFIGS=24 RAYCORE_RANDOM_CONFIG_SEED=2 $(CTEST) -L unit

lint: deps
	./scripts/lint.sh

area: deps
	./scripts/area.sh

# Only the section "One RTU at the cycle model's defaults" of docs/area.md (make area writes it too).
area-rtu: deps
	./scripts/area_rtu.sh

# rtu.v synthesised whole at several trv pipes x ist units (docs/area_configs.md): what the
# throughput study's area model is fitted to and checked against (make throughput refuses a misfit).
area-configs: deps
	./scripts/area_configs.sh

# Static timing (yosys -> OSU 0.18 um cells -> OpenSTA): every rtl/fp operator, every unit and rtl/units/rtu.v
# whole, FO4 measured, the clock at 28 nm: docs/timing.md and docs/timing.json (scripts/timing.sh).
timing: deps
	./scripts/timing.sh

# A whole frame on chip.v (the chip top: the bus with the L2, membus_l2.v, or with --l2-kb 0 in ARGS
# membus_if.v, and one RTU) closed-loop with tb/rtl/tb_chip.v's
# memory, against the transaction model (tb/rtl/run_chip.sh; SIM=icarus for Icarus, ARGS: the
# frame's simulate options).
chip: configure
	cmake --build $(BUILD) --target raycore -j $(JOBS)
	./tb/rtl/run_chip.sh $(RAYCORE) $(BUILD)/chip $(ARGS)

bench: build
	./scripts/bench.sh $(BUILD)

# The paper's Table 3 (three scenes x 24/32-bit x VTU off/on, 800 x 480) into docs/results.md,
# under the four shadow-ray conventions {unit, segment} x {front, all}.
table3: configure
	cmake --build $(BUILD) --target raycore -j $(JOBS)
	$(RAYCORE) table3

# The speed-against-error sweep (scenes x format x VTU x spawn, GNU parallel): out/sweep/ and
# docs/sweep.md; SWEEP_JOBS, SWEEP_SSHLOGIN and options after ARGS (see docs/sweep.md).
sweep: build
	./scripts/sweep.sh $(BUILD) $(ARGS)

# Throughput against RTU area (issue 14): the levers as a ladder and a grid on the three paper
# frames (GNU parallel): out/throughput/, docs/results.md's tables and docs/throughput.png.
throughput: build
	./scripts/throughput.sh $(BUILD) $(ARGS)

# libFuzzer on the glTF loader (clang), bounded time: FUZZ_SECONDS (default 60).
fuzz: deps
	./scripts/fuzz.sh

clean:
	rm -rf $(BUILD) $(ASAN_BUILD) build-*
