# Thin wrapper around CMake. Every target first installs the Debian packages it needs
# (scripts/install-deps.sh: `demo` installs only what build/biped needs, the others everything).
# Builds are quiet: one progress line, the compiler's output in $(BUILD_DIR)/build.log.
BUILD_DIR ?= build
JOBS      ?= 2
SCENARIO  ?= config/scenarios/lola-walk.yaml

# CMake's generated Makefiles are sub-makes: without this, each prints "Entering/Leaving directory".
MAKEFLAGS += --no-print-directory
# A new build folder uses Ninja where it is installed (it keeps both cores busy across the
# libraries; install-deps.sh installs it); an existing one keeps its generator.
CONFIGURE = cmake -S . -B $(BUILD_DIR) -DCMAKE_BUILD_TYPE=Release \
            $$([ -f $(BUILD_DIR)/CMakeCache.txt ] || ! command -v ninja > /dev/null || echo -G Ninja) > /dev/null
BUILD     = scripts/build.sh $(BUILD_DIR) $(JOBS)

.PHONY: all deps configure build test demo bench experiments clean

all: build

deps:
	@scripts/install-deps.sh all

configure: deps
	@$(CONFIGURE)

build: configure
	@$(BUILD)

test: build
	@cd $(BUILD_DIR) && ctest --output-on-failure --no-tests=error -j$(JOBS)

# Only what the demo needs: the Debian packages of build/biped, and build/biped (not the tests and
# benchmarks); then the default scenario.
demo:
	@echo "demo 1/3: Debian packages for build/biped (scripts/install-deps.sh demo)"
	@scripts/install-deps.sh demo
	@echo "demo 2/3: building build/biped (the first time: about 3 min on 2 cores)"
	@$(CONFIGURE)
	@$(BUILD) biped
	@echo "demo 3/3: build/biped run $(SCENARIO)"
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
