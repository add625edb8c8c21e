# Thin wrapper around CMake. Every target installs missing Debian packages first.
BUILD_DIR ?= build
JOBS      ?= 2
SCENARIO  ?= config/scenarios/lola-walk.yaml

.PHONY: all deps configure build test demo bench experiments clean

all: build

deps:
	@scripts/install-deps.sh

configure: deps
	@cmake -S . -B $(BUILD_DIR) -DCMAKE_BUILD_TYPE=Release > /dev/null

build: configure
	@cmake --build $(BUILD_DIR) -j$(JOBS)

test: build
	@cd $(BUILD_DIR) && ctest --output-on-failure -j$(JOBS)

demo: build
	@$(BUILD_DIR)/biped run $(SCENARIO)

bench: build
	@$(BUILD_DIR)/bench/biped_benchmarks --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
	@$(BUILD_DIR)/biped bench --robot lola
	@$(BUILD_DIR)/biped bench --robot johnnie

# The paper's experiments (experiments/README.md): runs into out/experiments/, figures into docs/figures/.
experiments: build
	@BIPED=$(BUILD_DIR)/biped experiments/run.sh

clean:
	rm -rf $(BUILD_DIR)
