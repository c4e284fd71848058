# Two commands do everything on a fresh Debian 12 machine:
#   make demo   install dependencies, build what the main job runs (library, CLI, Python package; no tests or
#               benchmarks), run it (outputs under out/)
#   make test   install dependencies, build everything, run the whole test suite through ctest
BUILD_DIR ?= build
JOBS ?= $(shell nproc)
CMAKE_FLAGS ?= -DCMAKE_BUILD_TYPE=Release

.PHONY: all deps configure build build-demo test test-fast test-sanitize fuzz fuzz-build demo bench clean

all: build

deps:
	scripts/install-deps

configure: deps
	cmake -S . -B $(BUILD_DIR) $(CMAKE_FLAGS)

build: configure
	cmake --build $(BUILD_DIR) -j $(JOBS)

# What the demo runs: the library (linked into both), the surfscatter CLI and the Python package.
DEMO_TARGETS = surfscatter _surfscatter

build-demo: configure
	cmake --build $(BUILD_DIR) -j $(JOBS) --target $(DEMO_TARGETS)

# Tests keep their lobe tables in the build tree, never in the user's cache, so a stale cache cannot hide a bug.
TEST_ENV = SURFSCATTER_CACHE_DIR=$(abspath $(BUILD_DIR))/test-table-cache

test: build fuzz-build
	cd $(BUILD_DIR) && $(TEST_ENV) ctest --output-on-failure -j $(JOBS)
	scripts/run-fuzzers $(FUZZ_BUILD_DIR) $(FUZZ_SMOKE_SECONDS)

# Everything but the suites labelled "slow" (chi-square sweeps, renders).
test-fast: build
	cd $(BUILD_DIR) && $(TEST_ENV) ctest --output-on-failure -j $(JOBS) -LE slow

# libFuzzer targets (fuzz/, clang) in their own build folder; `make fuzz` runs each for FUZZ_SECONDS, `make test` for
# FUZZ_SMOKE_SECONDS (its corpus, with the regression inputs of past findings, then a few seconds of mutation).
FUZZ_BUILD_DIR ?= build-fuzz
FUZZ_SECONDS ?= 600
FUZZ_SMOKE_SECONDS ?= 5
FUZZ_TARGETS ?=

fuzz-build: deps
	CXX=clang++-14 cmake -S . -B $(FUZZ_BUILD_DIR) -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSURFSCATTER_FUZZ=ON \
	  -DSURFSCATTER_BUILD_TESTS=OFF -DSURFSCATTER_BUILD_BENCH=OFF
	cmake --build $(FUZZ_BUILD_DIR) -j $(JOBS) --target fuzzers

fuzz: fuzz-build
	scripts/run-fuzzers $(FUZZ_BUILD_DIR) $(FUZZ_SECONDS) $(FUZZ_TARGETS)

# AddressSanitizer + UndefinedBehaviorSanitizer build in its own folder, running the fast suite (no "slow" label).
SANITIZE_BUILD_DIR ?= build-sanitize
# Leak reports unwind fully (Gwyddion's modules have no frame pointers), so that scripts/lsan.supp can name them.
SANITIZE_ENV = ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:fast_unwind_on_malloc=0 \
  UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  LSAN_OPTIONS=suppressions=$(abspath scripts/lsan.supp):print_suppressions=0 \
  SURFSCATTER_CACHE_DIR=$(abspath $(SANITIZE_BUILD_DIR))/test-table-cache

test-sanitize: deps
	cmake -S . -B $(SANITIZE_BUILD_DIR) -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSURFSCATTER_SANITIZE=ON \
	  -DSURFSCATTER_BUILD_BENCH=OFF
	cmake --build $(SANITIZE_BUILD_DIR) -j $(JOBS)
	cd $(SANITIZE_BUILD_DIR) && $(SANITIZE_ENV) ctest --output-on-failure -j $(JOBS) -LE slow

demo: build-demo
	scripts/demo $(BUILD_DIR)

bench: build
	scripts/run-benchmarks $(BUILD_DIR)

clean:
	rm -rf $(BUILD_DIR) $(FUZZ_BUILD_DIR) $(SANITIZE_BUILD_DIR) out
