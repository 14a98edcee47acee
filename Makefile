# lvsim - top-level entry points. `make demo` and `make test` work on a fresh
# Debian 12 machine: they install missing packages, configure, build and run.
BUILD      ?= build
BUILD_ASAN ?= build-asan
JOBS       ?= 2
CMAKE_FLAGS ?=

.PHONY: all build deps demo test test-asan test-valgrind bench clean

all: build

deps:
	@scripts/install-deps.sh

$(BUILD)/CMakeCache.txt:
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=RelWithDebInfo $(CMAKE_FLAGS)

build: $(BUILD)/CMakeCache.txt
	cmake --build $(BUILD) -j $(JOBS)

# viewer before build: the build copies CesiumJS from viewer/node_modules to build/share/lvsim.
# One line for the build (its log in $(BUILD)/build.log, shown when it fails), then the demo.
demo: deps viewer
	@scripts/build-quiet.sh $(BUILD) $(JOBS) $(CMAKE_FLAGS)
	@scripts/demo.sh $(BUILD)

# The viewer's npm packages before ctest: npm runs outside any test's time limit and never
# beside test_fresh_clone's own `npm ci` (two installs sharing ~/.npm can hang).
test: deps viewer build
	ctest --test-dir $(BUILD) --output-on-failure -j $(JOBS)

# The whole suite under AddressSanitizer + UndefinedBehaviorSanitizer.
test-asan: deps
	cmake -S . -B $(BUILD_ASAN) -DCMAKE_BUILD_TYPE=Debug -DLV_SANITIZE=ON -DLV_BUILD_BENCH=OFF
	cmake --build $(BUILD_ASAN) -j $(JOBS)
	ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
	  LSAN_OPTIONS=suppressions=$(CURDIR)/tests/lsan.supp \
	  ctest --test-dir $(BUILD_ASAN) --output-on-failure -j $(JOBS) -LE no-asan

# Every unit test under valgrind memcheck (slow: a few minutes).
test-valgrind: deps build
	scripts/valgrind-tests.sh $(BUILD)

bench: deps build
	@for b in $(BUILD)/bench/bench_*; do [ -x "$$b" ] && "$$b"; done
	@bench/whole_process.py --lvsim $(BUILD)/lvsim
	@if command -v valgrind >/dev/null; then bench/instr_flight.py $(BUILD)/bench/bench_flight; fi

# The fuzz targets (libFuzzer, clang; docs/fuzzing.md), each for FUZZ_TIME seconds (default
# 60); FUZZ_TARGETS picks some of them.
FUZZ_TARGETS ?= mission tables cli fmu results
.PHONY: fuzz
fuzz: deps
	cmake -S . -B build-fuzz -DCMAKE_C_COMPILER=clang -DCMAKE_BUILD_TYPE=RelWithDebInfo -DLV_BUILD_BENCH=OFF
	cmake --build build-fuzz -j $(JOBS) --target lv_fuzz
	@for t in $(FUZZ_TARGETS); do \
	  echo "== fuzz_$$t, $(or $(FUZZ_TIME),60) s"; \
	  fuzz/run.sh build-fuzz/fuzz/fuzz_$$t $(or $(FUZZ_TIME),60) || exit 1; \
	done

clean:
	rm -rf $(BUILD) $(BUILD_ASAN)

# The 3-D viewer's npm packages (CesiumJS, playwright-core for its test) from viewer/package-lock.json.
.PHONY: viewer
viewer:
	@viewer/install.sh
