# Tellus top-level entry points. `make demo` and `make test` work on a fresh Debian machine:
# each installs missing packages with apt-get, configures, builds (Release) and runs.
PRESET    ?= release
BUILD_DIR := build/$(PRESET)
JOBS      ?= $(shell nproc)

.PHONY: all deps configure build demo test test-gpu asan golden-update format clean

all: build

deps:
	@scripts/install-deps.sh

configure: deps
	@cmake --preset $(PRESET) >/dev/null

build: configure
	@cmake --build --preset $(PRESET) -j $(JOBS)

demo: build
	$(BUILD_DIR)/apps/tellus/tellus demo -o demo-out

test: build
	ctest --preset $(PRESET)

# Sanitizer build and test run (AddressSanitizer + UndefinedBehaviorSanitizer).
asan:
	@$(MAKE) --no-print-directory PRESET=asan test

# Re-render the golden images after an intended change of the renderer's output.
golden-update: build
	scripts/update-golden.sh $(BUILD_DIR)

format:
	@git ls-files '*.cpp' '*.hpp' | xargs clang-format -i

clean:
	rm -rf build demo-out
