# Tellus top-level entry points. `make demo` and `make test` work on a fresh Debian machine:
# each installs missing packages with apt-get, configures, builds (Release) and runs.
PRESET    ?= release
BUILD_DIR := build/$(PRESET)
JOBS      ?= $(shell nproc)

.PHONY: all deps configure build demo test test-gpu asan test-long tsan fuzz-smoke fuzz fuzz-long build-speed scale-check gpu-check golden-update format clean install deb

all: build

deps:
	@scripts/install-deps.sh

configure: deps
	@cmake --preset $(PRESET) >/dev/null

build: configure
	@cmake --build --preset $(PRESET) -j $(JOBS)

demo: build
	$(BUILD_DIR)/apps/tellus/tellus demo -o demo-out

# The release suite but the tests labelled `long` (about 25 minutes on 2 cores after the build).
test: build
	ctest --preset $(PRESET) -j $(JOBS) -LE long

# The long runs: the tests that check Tellus through other programs (CesiumJS in headless
# Chromium, the Khronos validators, the installed package) and the demo, then the tile cache under
# ThreadSanitizer and a few seconds of each fuzzer (about 25 minutes more on 2 cores).
test-long: build
	ctest --preset $(PRESET) -j $(JOBS) -L long
	@$(MAKE) --no-print-directory tsan fuzz-smoke

# The tile pipeline's concurrency tests under ThreadSanitizer (a reduced build).
tsan: deps
	@cmake --preset tsan >/dev/null
	@cmake --build --preset tsan -j $(JOBS)
	ctest --preset tsan -j $(JOBS)

# Each libFuzzer target (clang) for TELLUS_FUZZ_SECONDS (4) seconds from a seed corpus.
fuzz-smoke: deps
	@cmake --preset fuzz -DTELLUS_FUZZ_SECONDS=4 >/dev/null
	@cmake --build --preset fuzz -j $(JOBS)
	ctest --preset fuzz -j $(JOBS)

# A longer fuzzing run through ctest, one target after another on one core each:
# make fuzz FUZZ_SECONDS=300
FUZZ_SECONDS ?= 300
fuzz: deps
	@cmake --preset fuzz -DTELLUS_FUZZ_SECONDS=$(FUZZ_SECONDS) >/dev/null
	@cmake --build --preset fuzz -j $(JOBS)
	ctest --preset fuzz

# The long run: every target 10 minutes on two cores with a coverage report (80 minutes in
# all; docs/testing.md has the figures): make fuzz-long [FUZZ_LONG_SECONDS=600]
FUZZ_LONG_SECONDS ?= 600
fuzz-long: deps
	@cmake --preset fuzz >/dev/null
	@cmake --build --preset fuzz -j $(JOBS)
	@build/fuzz/fuzz/make_seed_corpus build/fuzz/fuzz/corpus
	scripts/fuzz-long.sh build/fuzz $(FUZZ_LONG_SECONDS)

# Sanitizer build and test run (AddressSanitizer + UndefinedBehaviorSanitizer).
asan:
	@$(MAKE) --no-print-directory PRESET=asan test

# `tellus build` against GDAL's COG writer on the Korea mosaic and a generated 16385² terrain,
# 5 alternating pairs each (about 7 minutes; docs/globe.md has the figures).
build-speed: build
	scripts/build-speed.sh $(BUILD_DIR)/apps/tellus/tellus ../shared/data build/build-speed

# The planet-scale checks (docs/scale.md): generated SRTM tiles of a 20 x 20 degree box (1 GB,
# kept in build/scale), one global store built alone and with mpirun -np 1, 2, 4 (the same bytes
# every time), then served by lighttpd and descended onto by RINGO and the spiral over HTTP.
# About 30 minutes the first time on 2 cores: make scale-check [SCALE_ARGS="--ranks '2 4'"]
SCALE_ARGS ?=
scale-check: build
	scripts/scale-check.sh --tellus $(BUILD_DIR)/apps/tellus/tellus --out build/scale $(SCALE_ARGS)

# Every renderer's frame, render-thread, background and GPU ms and its GPU waits along the
# Korea flyover, the globe paths and the stack preset, into build/gpu-check/summary.md
# (docs/performance.md): make gpu-check [GPU_CHECK_ARGS=--quick]
GPU_CHECK_ARGS ?=
gpu-check: build
	scripts/gpu-check.sh --tellus $(BUILD_DIR)/apps/tellus/tellus --out build/gpu-check $(GPU_CHECK_ARGS)

# Install the command, libraries, headers, CMake package and pkg-config file (docs/ecosystem.md):
# make install [PREFIX=/opt/tellus]   (default /usr/local)
PREFIX ?= /usr/local
install: build
	cmake --install $(BUILD_DIR) --prefix $(PREFIX)

# The Debian package of the same files, in $(BUILD_DIR): make deb, then apt install ./build/release/tellus_*.deb
deb: build
	cd $(BUILD_DIR) && cpack -G DEB

# Re-render the golden images after an intended change of the renderer's output.
golden-update: build
	scripts/update-golden.sh $(BUILD_DIR)

format:
	@git ls-files '*.cpp' '*.hpp' | xargs clang-format -i

clean:
	rm -rf build demo-out
