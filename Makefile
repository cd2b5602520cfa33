# Thin wrapper over CMake and CTest. Every target first installs what is missing
# (scripts/setup.sh: Debian packages, as root or through sudo) and builds what it needs.
BUILD      ?= build
BUILD_SAN  ?= build-sanitize
BUILD_FUZZ ?= build-fuzz
JOBS       ?= $(shell nproc)
OUT        ?= out
FUZZ_SECONDS ?= 45

.PHONY: setup build conformance test test-unit test-sanitize fuzz bench clean

setup:
	@bash scripts/setup.sh

build: setup
	@cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release >/dev/null
	@cmake --build $(BUILD) -j $(JOBS)

# The main job: the built-in suite, CPU against lavapipe, with its report.
conformance: build
	@$(BUILD)/app/rastercmp conformance --suite scenes --baseline scenes/methods/expected-failures.txt \
	  --out $(OUT)/conformance

# What CI runs: the test suite, then the fuzzers. The ASan+UBSan run is `make test-sanitize`
# (not yet part of `make test`: its full run has not been timed inside CI's budget).
test: test-unit fuzz

test-unit: build
	@cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

# ASan + UBSan (+ LeakSanitizer) build of the whole test suite; any report fails the run.
# Leaks inside the Vulkan driver stack (lavapipe, LLVM, the loader) are not ours: tests/sanitizer/lsan.supp.
test-sanitize: setup
	@cmake -S . -B $(BUILD_SAN) -DCMAKE_BUILD_TYPE=RelWithDebInfo -DRASTERCMP_SANITIZE=ON >/dev/null
	@cmake --build $(BUILD_SAN) -j $(JOBS)
	@cd $(BUILD_SAN) && \
	  ASAN_OPTIONS=detect_leaks=1:abort_on_error=0:halt_on_error=1 \
	  UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
	  LSAN_OPTIONS=suppressions=$(CURDIR)/tests/sanitizer/lsan.supp:print_suppressions=0 \
	  RASTERCMP_SANITIZER_BUILD=1 ctest --output-on-failure -j $(JOBS)

# libFuzzer (clang) on the scene parser and the clipper, FUZZ_SECONDS each, from the seed corpus.
# A crash leaves its input in $(BUILD_FUZZ)/artifacts/: add it to fuzz/regressions/ as a test.
fuzz: setup
	@CC=clang CXX=clang++ cmake -S . -B $(BUILD_FUZZ) -DCMAKE_BUILD_TYPE=RelWithDebInfo -DRASTERCMP_FUZZ=ON >/dev/null
	@cmake --build $(BUILD_FUZZ) -j $(JOBS) --target fuzz_scene_parser fuzz_clipper
	@mkdir -p $(BUILD_FUZZ)/artifacts
	@for t in scene_parser clipper; do \
	  mkdir -p $(BUILD_FUZZ)/corpus/$$t && \
	  echo "fuzz: $$t for $(FUZZ_SECONDS) s" && \
	  $(BUILD_FUZZ)/fuzz/fuzz_$$t -max_total_time=$(FUZZ_SECONDS) -print_final_stats=1 \
	    -artifact_prefix=$(BUILD_FUZZ)/artifacts/$$t- \
	    $(BUILD_FUZZ)/corpus/$$t fuzz/corpus/$$t $$(test -d fuzz/regressions/$$t && echo fuzz/regressions/$$t) \
	    2>$(BUILD_FUZZ)/fuzz_$$t.log \
	  || { tail -n 40 $(BUILD_FUZZ)/fuzz_$$t.log; exit 1; }; \
	  grep -E "stat::number_of_executed_units" $(BUILD_FUZZ)/fuzz_$$t.log; \
	done

bench: build
	@$(BUILD)/app/rastercmp bench

clean:
	rm -rf $(BUILD) $(BUILD_SAN) $(BUILD_FUZZ) $(OUT)
