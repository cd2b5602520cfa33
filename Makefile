# Thin wrapper over CMake and CTest. Every target first installs what is missing
# (scripts/setup.sh: Debian packages, as root or through sudo) and builds what it needs.
BUILD      ?= build
BUILD_SAN  ?= build-sanitize
BUILD_SAN_ALL ?= build-sanitize-all
JOBS       ?= $(shell nproc)
OUT        ?= out
FUZZ_SECONDS ?= 30

# A sanitizer report ends the process with this exit code (not one rastercmp itself uses, so a CLI
# test that expects exit 1 or 2 from the executable cannot mistake a report for it), and the test fails.
SAN_EXITCODE := 86
# intercept_tls_get_addr=0: up to LLVM 16 the runtime's __tls_get_addr interceptor takes a dynamic
# TLS block that happens to start 16 bytes past a page boundary for a pre-2.25 glibc header and
# reads garbage; LeakSanitizer's tracer then died at exit ("Tracer caught signal 11") twice in about
# fifteen sanitizer runs of the suite, whose processes hold lavapipe's, LLVM's and the validation
# layer's dynamic TLS (Debian 12's clang is 14). The blocks it then leaves unscanned belong to the driver stack, whose
# leaks are suppressed by name anyway.
SAN_ENV := ASAN_OPTIONS=detect_leaks=1:halt_on_error=1:abort_on_error=0:exitcode=$(SAN_EXITCODE):intercept_tls_get_addr=0 \
  UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1:exitcode=$(SAN_EXITCODE) \
  LSAN_OPTIONS=suppressions=$(CURDIR)/tests/sanitizer/lsan.supp:print_suppressions=0:exitcode=$(SAN_EXITCODE)

.PHONY: setup build build-app conformance test-debian13 test-unstable test test-unit build-san test-sanitize test-sanitize-all fuzz bench soak properties docs-tables docs-check clean

setup:
	@bash scripts/setup.sh

build: setup
	@cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release >/dev/null
	@cmake --build $(BUILD) -j $(JOBS)

# The command-line tool alone (no tests, no benchmarks): what the main job needs.
build-app: setup
	@cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release >/dev/null
	@cmake --build $(BUILD) -j $(JOBS) --target rastercmp real_model_suite

# The main job: the built-in suite and the real models (build/suite: scenes/ and the models
# imported from assimp-testmodels), CPU against lavapipe, with its report.
conformance: build-app
	@$(BUILD)/app/rastercmp conformance --suite $(BUILD)/suite --baseline scenes/methods/expected-failures.txt \
	  --out $(OUT)/conformance

# What CI runs (.ci/run): the test suite (Release), the libraries' tests under ASan + UBSan + LSan,
# then the fuzzers. Two build trees: $(BUILD) and $(BUILD_SAN), which serves both of the last two.
# The Release tests leave a core idle much of the time (they wait on child processes and the
# driver), so the sanitizer tree builds beside them; each step's output is printed when it ends.
test: build
	@$(MAKE) --no-print-directory -j2 --output-sync=target test-unit build-san
	@$(MAKE) --no-print-directory test-sanitize fuzz

test-unit: build
	@cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

# The sanitizer tree (clang): the libraries, their tests and the fuzzers built with ASan + UBSan and
# libFuzzer's coverage hooks, at -O1 with line tables (for the reports' stack traces), without
# bench/, and without the executable and the tests that drive it or link experiments/ and soak/
# (RASTERCMP_BUILD_APP=OFF; test-sanitize-all has them); the fuzz_* mains link libFuzzer.
SAN_CMAKE := -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only" -DRASTERCMP_FUZZ=ON -DRASTERCMP_BENCH=OFF
build-san: setup
	@cmake -S . -B $(BUILD_SAN) $(SAN_CMAKE) -DRASTERCMP_BUILD_APP=OFF >/dev/null
	@cmake --build $(BUILD_SAN) -j $(JOBS)

# The whole test suite under ASan + UBSan (+ LeakSanitizer); any report fails the run.
# Leaks inside the Vulkan driver stack (lavapipe, LLVM, the loader) are not ours: tests/sanitizer/lsan.supp.
# The Vulkan loader unloads the driver (dlclose) when an instance is destroyed; a block the driver
# keeps then looks leaked from an "<unknown module>" that no suppression can name. Preloading
# lavapipe keeps it loaded, so its blocks stay reachable from its globals or match lsan.supp.
test-sanitize: build-san
	@cd $(BUILD_SAN) && $(SAN_ENV) LD_PRELOAD="$$(ls /usr/lib/*/libvulkan_lvp.so 2>/dev/null | head -n 1)" \
	  ctest --output-on-failure -j $(JOBS)

# The whole test suite under the sanitizers, the executable's tests included (the CLI tests run the
# sanitized rastercmp), in a tree of its own: a longer run than make test's (docs/reliability.md).
test-sanitize-all: setup
	@cmake -S . -B $(BUILD_SAN_ALL) $(SAN_CMAKE) -DRASTERCMP_BUILD_APP=ON >/dev/null
	@cmake --build $(BUILD_SAN_ALL) -j $(JOBS)
	@cd $(BUILD_SAN_ALL) && $(SAN_ENV) LD_PRELOAD="$$(ls /usr/lib/*/libvulkan_lvp.so 2>/dev/null | head -n 1)" \
	  ctest --output-on-failure -j $(JOBS)

# libFuzzer on the scene parser and the clipper, FUZZ_SECONDS each, from the seed corpus, the two
# side by side (one core each). A crash leaves its input in $(BUILD_SAN)/artifacts/: add it to
# fuzz/regressions/ as a test.
FUZZERS := scene_parser clipper
fuzz: build-san
	@mkdir -p $(BUILD_SAN)/artifacts
	@$(MAKE) --no-print-directory -j2 --output-sync=target $(addprefix fuzz-,$(FUZZERS))

# One fuzzer of an already built sanitizer tree.
fuzz-%:
	@mkdir -p $(BUILD_SAN)/corpus/$* && \
	  echo "fuzz: $* for $(FUZZ_SECONDS) s" && \
	  $(SAN_ENV) $(BUILD_SAN)/fuzz/fuzz_$* -max_total_time=$(FUZZ_SECONDS) -print_final_stats=1 \
	    -artifact_prefix=$(BUILD_SAN)/artifacts/$*- \
	    $(BUILD_SAN)/corpus/$* fuzz/corpus/$* $$(test -d fuzz/regressions/$* && echo fuzz/regressions/$*) \
	    2>$(BUILD_SAN)/fuzz_$*.log \
	  || { tail -n 40 $(BUILD_SAN)/fuzz_$*.log; exit 1; }; \
	  grep -E "stat::number_of_executed_units" $(BUILD_SAN)/fuzz_$*.log

bench: build-app
	@$(BUILD)/app/rastercmp bench

# The random differential soak (docs/soak.md): 10^6 primitives of generated scenes against lavapipe,
# every failure reduced and written to $(OUT)/soak. Exit 1 when anything failed.
SOAK_SEED  ?= 1
SOAK_COUNT ?= 1000000
soak: build-app
	@$(BUILD)/app/rastercmp soak --seed $(SOAK_SEED) --count $(SOAK_COUNT) --out $(OUT)/soak

# docs/experiments.md's measured tables (docs/experiments.md, top): each marker's command runs once
# with this build's rastercmp; docs-tables rewrites the tables in place, docs-check exits 1 listing
# every cell that drifted (deterministic cells must be equal, timed medians inside the new interval;
# DOCS_TIMED=report lists timed drift without failing on it).
DOCS_EXPERIMENTS ?= docs/experiments.md
DOCS_TIMED ?= fail
docs-tables: setup
	@cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release >/dev/null
	@cmake --build $(BUILD) -j $(JOBS) --target rastercmp
	@$(BUILD)/app/rastercmp docs update $(DOCS_EXPERIMENTS)

docs-check: setup
	@cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release >/dev/null
	@cmake --build $(BUILD) -j $(JOBS) --target rastercmp
	@$(BUILD)/app/rastercmp docs check $(DOCS_EXPERIMENTS) --timed $(DOCS_TIMED)

# rapidcheck's properties with fresh seeds (ctest fixes one, tests/CMakeLists.txt): PROPERTY_RUNS
# runs of every property binary; each failure's output, with the RC_PARAMS line that replays it,
# is kept in $(OUT)/properties/, and the target fails if there was one.
PROPERTY_RUNS ?= 20
PROPERTY_TESTS := test_spec_properties test_cpu_invariants test_compare_diff test_conformance_expectations \
  test_methods_depth test_methods_fill test_methods_line_clip test_methods_lines test_methods_polygon_clip \
  test_methods_visibility
properties: build
	@mkdir -p $(OUT)/properties
	@failed=0; for run in $$(seq 1 $(PROPERTY_RUNS)); do for t in $(PROPERTY_TESTS); do \
	  log=$(OUT)/properties/$$t-run$$run.log; \
	  if env -u RC_PARAMS $(BUILD)/tests/$$t --gtest_brief=1 > $$log 2>&1; then rm -f $$log; \
	  else failed=$$((failed + 1)); echo "properties: $$t failed (run $$run): $$log"; fi; done; done; \
	  echo "properties: $(PROPERTY_RUNS) runs of $(words $(PROPERTY_TESTS)) binaries, $$failed failed"; \
	  test $$failed -eq 0

# README's Quick start (make conformance, make test) from a clean clone of HEAD in a minimal Debian 13
# or Debian unstable root made with debootstrap, on that release's lavapipe (scripts/debian-root.sh:
# root and Debian's registry needed; docs/contributing.md gives the times).
test-debian13:
	@bash scripts/debian-root.sh trixie

test-unstable:
	@bash scripts/debian-root.sh sid

clean:
	rm -rf $(BUILD) $(BUILD_SAN) $(BUILD_SAN_ALL) $(OUT)
