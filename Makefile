# Two commands do everything on a fresh Debian 12 machine:
#   make demo   install dependencies, build (Release), run the main job (outputs under out/)
#   make test   install dependencies, build, run the whole test suite through ctest
BUILD_DIR ?= build
JOBS ?= $(shell nproc)
CMAKE_FLAGS ?= -DCMAKE_BUILD_TYPE=Release

.PHONY: all deps configure build test test-fast demo bench clean

all: build

deps:
	scripts/install-deps

configure: deps
	cmake -S . -B $(BUILD_DIR) $(CMAKE_FLAGS)

build: configure
	cmake --build $(BUILD_DIR) -j $(JOBS)

# Tests keep their lobe tables in the build tree, never in the user's cache, so a stale cache cannot hide a bug.
TEST_ENV = SURFSCATTER_CACHE_DIR=$(abspath $(BUILD_DIR))/test-table-cache

test: build
	cd $(BUILD_DIR) && $(TEST_ENV) ctest --output-on-failure -j $(JOBS)

# Everything but the suites labelled "slow" (chi-square sweeps, renders).
test-fast: build
	cd $(BUILD_DIR) && $(TEST_ENV) ctest --output-on-failure -j $(JOBS) -LE slow

demo: build
	scripts/demo $(BUILD_DIR)

bench: build
	scripts/run-benchmarks $(BUILD_DIR)

clean:
	rm -rf $(BUILD_DIR) out
