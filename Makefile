# Sylva: `make demo` renders the demo gallery into out/, `make test` runs every test.
# Both install missing Debian packages first (scripts/setup.sh) and build in Release.
BUILD ?= build
ASAN_BUILD ?= build-asan
JOBS ?= $(shell nproc)
CMAKE_FLAGS ?=

.PHONY: all setup build test demo sanitize fuzz perf golden docs format clean

all: build

setup:
	@scripts/setup.sh

$(BUILD)/build.ninja:
	cmake -S . -B $(BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Release $(CMAKE_FLAGS)

build: setup $(BUILD)/build.ninja
	cmake --build $(BUILD) -j $(JOBS)

test: build
	cd $(BUILD) && ctest -LE perf --output-on-failure -j $(JOBS) --timeout 900

# Unit tests under AddressSanitizer + UndefinedBehaviorSanitizer (no benchmarks), built with
# clang at -O1 with line tables only: half the build time of GCC's -O2 -g, the same checks.
sanitize: setup
	cmake -S . -B $(ASAN_BUILD) -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSYLVA_SANITIZE=ON \
	  -DSYLVA_BUILD_PERF=OFF -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
	  "-DCMAKE_C_FLAGS_RELWITHDEBINFO=-O1 -gline-tables-only" \
	  "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -gline-tables-only"
	cmake --build $(ASAN_BUILD) -j $(JOBS)
	cd $(ASAN_BUILD) && ASAN_OPTIONS=detect_leaks=0:abort_on_error=1 \
	  UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
	  ctest -L unit -LE perf --output-on-failure -j $(JOBS) --timeout 1800

# The libFuzzer harnesses (clang, build-fuzz/), FUZZ_SECONDS each (default 60): tests/fuzz/.
fuzz: setup
	@scripts/fuzz.sh

demo: build
	@scripts/demo.sh $(BUILD)/cli/sylva out

perf: build
	cd $(BUILD) && ctest -L perf --output-on-failure -V

# Rewrites tests/golden/*.png (whole renders) and tests/golden/passes/*.png (each pass's
# output) from the current renderer (look at them before committing).
golden: build
	SYLVA_UPDATE_GOLDEN=1 $(BUILD)/tests/cli/test_cli --gtest_filter='Golden*'
	SYLVA_UPDATE_GOLDEN=1 $(BUILD)/tests/styles/test_styles --gtest_filter='*PassGolden*'

# Rewrites the README's generated tables (options and style parameters) from their
# declarations; the docs.readme test fails when they are stale.
docs: build
	$(BUILD)/cli/sylva_docs README.md

format:
	git ls-files '*.cpp' '*.h' | xargs clang-format -i

clean:
	rm -rf $(BUILD) $(ASAN_BUILD) build-fuzz out
