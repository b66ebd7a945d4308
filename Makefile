# Sylva. `make demo` builds only the sylva program and its codecs plugin and renders the demo
# gallery into out/; `make test` builds the rest (the tests) in the same build and runs them.
# Both install missing Debian packages first (scripts/setup.sh) and build in Release.
BUILD ?= build
ASAN_BUILD ?= build-asan
EGL_BUILD ?= build-egl-only
JOBS ?= $(shell nproc)
CMAKE_FLAGS ?=
PREFIX ?= /usr/local
# ccache where it is installed (scripts/setup.sh --test installs it): the EGL-only build of
# `make test` then reuses the main build's objects (paths made relative to the checkout).
LAUNCHER := $(if $(shell command -v ccache),-DCMAKE_C_COMPILER_LAUNCHER=ccache -DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
export CCACHE_BASEDIR ?= $(CURDIR)

.PHONY: all setup setup-test sylva build test egl-only demo gallery line-sheet wash-sheet installable install package sanitize \
	fuzz perf golden docs format clean

all: build

setup:
	@scripts/setup.sh

setup-test:
	@scripts/setup.sh --test

$(BUILD)/build.ninja:
	cmake -S . -B $(BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Release $(LAUNCHER) $(CMAKE_FLAGS)

# The program and its plugin only: 43 of the build's 260 steps.
sylva: setup $(BUILD)/build.ninja
	cmake --build $(BUILD) -j $(JOBS) --target sylva sylva_codecs

build: setup-test $(BUILD)/build.ninja
	cmake --build $(BUILD) -j $(JOBS)

test: build
	cd $(BUILD) && ctest -LE perf --output-on-failure -j $(JOBS) --timeout 900
	$(MAKE) egl-only

# The build without OSMesa (Mesa 25.1 removed it): the program alone, configured on its own with
# -DSYLVA_OSMESA=OFF, then a render and the error for --gl osmesa (tests/install/egl_only.sh).
egl-only: setup
	cmake -S . -B $(EGL_BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Release -DSYLVA_OSMESA=OFF \
	  -DSYLVA_BUILD_TESTS=OFF -DSYLVA_BUILD_PERF=OFF $(LAUNCHER) $(CMAKE_FLAGS)
	cmake --build $(EGL_BUILD) -j $(JOBS) --target sylva sylva_codecs
	tests/install/egl_only.sh $(EGL_BUILD)/cli/sylva

demo: sylva
	@scripts/demo.sh $(BUILD)/cli/sylva out

# Rewrites docs/gallery.png, the README's picture (every built-in style on the shared ash).
gallery: sylva
	@scripts/gallery.sh $(BUILD)/cli/sylva docs/gallery.png

# Rewrites docs/line-sheet.png (standard, ink and pen on every shared tree).
line-sheet: sylva
	@scripts/tree_sheet.sh $(BUILD)/cli/sylva docs/line-sheet.png

# Rewrites docs/wash-sheet.jpg (standard, watercolor, pen-and-wash and toon-ink on every shared
# tree).
wash-sheet: sylva
	@scripts/tree_sheet.sh $(BUILD)/cli/sylva docs/wash-sheet.jpg 256 \
	  standard,watercolor,pen-and-wash,toon-ink

# What an install holds: sylva, its plugin, the man page (not the tests).
installable: setup $(BUILD)/build.ninja
	cmake --build $(BUILD) -j $(JOBS) --target sylva_installable

# Installs sylva, its plugin, the presets and the man page under PREFIX (cmake/install.cmake).
install: installable
	cmake --install $(BUILD) --prefix $(PREFIX)

# The .deb, sylva_VERSION_ARCH.deb in $(BUILD)/ (cpack; Depends from dpkg-shlibdeps).
package: installable
	cd $(BUILD) && cpack -G DEB

# Unit tests under AddressSanitizer + UndefinedBehaviorSanitizer (no benchmarks), built with
# clang at -O1 with line tables only: half the build time of GCC's -O2 -g, the same checks.
# Unity batches as in Release (CI's time: one object per source took twice as long to build).
# What runs in `make test` only (SANITIZE_SKIP; CI's time, 61 min of tests under ASan before):
# Readme.ExampleCommandsRun (the README's commands: full-size renders of the shared trees,
# 2.5 min), Park.TheLargestCountIsAccepted (4 min), EveryParameter.JustOutside... (450 runs of
# sylva that stop at the parameter's check, which fuzz_set and fuzz_options fuzz under ASan),
# EveryParameter for the presets whose builder another preset covers (expressive: standard's;
# outline and pen: ink's), and the foliage.* keys but under `standard` (the preprocessing does not
# depend on the style).
SANITIZE_SKIP = ^Readme\.ExampleCommandsRun$$|^Park\.TheLargestCountIsAccepted$$|JustOutsideIsOneErrorNamingTheKey|EveryParameter\..*/(expressive|outline|pen)_|EveryParameter\..*/(ink|toon|watercolor|blobs)_foliage_
sanitize: setup-test
	cmake -S . -B $(ASAN_BUILD) -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSYLVA_SANITIZE=ON \
	  -DSYLVA_BUILD_PERF=OFF -DSYLVA_UNITY_BUILD=ON -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
	  "-DCMAKE_C_FLAGS_RELWITHDEBINFO=-O1 -gline-tables-only" \
	  "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -gline-tables-only"
	cmake --build $(ASAN_BUILD) -j $(JOBS)
	cd $(ASAN_BUILD) && ASAN_OPTIONS=detect_leaks=0:abort_on_error=1 \
	  UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
	  ctest -L unit -LE perf -E '$(SANITIZE_SKIP)' --output-on-failure -j $(JOBS) \
	  --timeout 1800

# The libFuzzer harnesses (clang, build-fuzz/), FUZZ_SECONDS each (default 60): tests/fuzz/.
fuzz: setup-test
	@scripts/fuzz.sh

perf: build
	cd $(BUILD) && ctest -L perf --output-on-failure -V

# Rewrites tests/golden/*.png (whole renders) and tests/golden/passes/*.png (each pass's
# output) from the current renderer (look at them before committing).
golden: build
	SYLVA_UPDATE_GOLDEN=1 $(BUILD)/tests/cli/test_cli --gtest_filter='Golden*'
	SYLVA_UPDATE_GOLDEN=1 $(BUILD)/tests/styles/test_styles --gtest_filter='*PassGolden*'

# Rewrites the generated tables in README.md and docs/*.md (options and style parameters) from
# their declarations; the docs.tables test fails when one is stale.
docs: setup $(BUILD)/build.ninja
	cmake --build $(BUILD) -j $(JOBS) --target sylva_docs
	$(BUILD)/cli/sylva_docs README.md docs

format:
	git ls-files '*.cpp' '*.h' | xargs clang-format -i

clean:
	rm -rf $(BUILD) $(ASAN_BUILD) $(EGL_BUILD) build-fuzz out
