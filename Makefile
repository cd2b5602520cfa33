# Thin wrapper: every target installs what is missing (scripts/setup.sh) and builds first.
BUILD     ?= build
BUILD_SAN ?= build-asan
JOBS      ?= $(shell nproc)
OUT       ?= out
CMAKE_FLAGS ?=

.PHONY: setup configure build conformance test test-fast test-sanitize bench clean

setup:
	@bash scripts/setup.sh

configure: setup
	@cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release $(CMAKE_FLAGS) >/dev/null

build: configure
	@cmake --build $(BUILD) -j $(JOBS)

# The main job: the built-in suite, CPU against lavapipe, with its report.
conformance: build
	@$(BUILD)/app/rastercmp conformance --suite scenes --out $(OUT)/conformance

# Unit, invariant, differential and end-to-end tests.
test: build
	@cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

bench: build
	@$(BUILD)/app/rastercmp bench

clean:
	rm -rf $(BUILD) $(BUILD_SAN) $(OUT)
