# The two commands of the README. Both install missing Debian packages first
# (scripts/install-deps.sh), then configure and build a Release build.
#   make render       renders the Whitted scene to whitted.png
#   make test         the whole suite: the unit and program tests, the same
#                     under AddressSanitizer and UBSan, and a short run of
#                     every fuzz target
BUILD ?= build
JOBS ?= $(shell nproc 2>/dev/null || echo 2)
PREFIX ?= /usr/local
# Seconds per fuzz target in make test (make fuzz: FUZZ_SECONDS each).
FUZZ_SMOKE_SECONDS ?= 10
FUZZ_SECONDS ?= 3600

.PHONY: render test test-unit test-asan fuzz fuzz-smoke build deps peers \
        clean format install uninstall

render: build
	@./$(BUILD)/glint render whitted -o whitted.png

test: test-unit test-asan fuzz-smoke

test-unit: build
	ctest --test-dir $(BUILD) --output-on-failure -j $(JOBS)

# Everything built by clang with ASan and UBSan (any report fails the test)
# and libFuzzer's coverage, then the whole ctest suite but the install test
# (which compiles programs against the library with a plain compiler, and
# cannot link an instrumented one). The fuzz targets share this build.
SANITIZE_BUILD = $(BUILD)-sanitize
# -O1 and line tables only: the instrumented SIMD tracers (deeply inlined)
# compile in a fraction of the time of -O2 -g, with symbolized reports.
SANITIZE_FLAGS = -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only"
test-asan: deps
	@mkdir -p $(SANITIZE_BUILD)
	@CC=clang cmake -S . -B $(SANITIZE_BUILD) -DCMAKE_BUILD_TYPE=RelWithDebInfo \
	  $(SANITIZE_FLAGS) -DGLINT_FUZZ=ON $(QUIET_MAKE) \
	  >$(SANITIZE_BUILD)/configure.log 2>&1 \
	  || { cat $(SANITIZE_BUILD)/configure.log; exit 1; }
	@cmake --build $(SANITIZE_BUILD) -j $(JOBS) -- --no-print-directory -s
	ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 \
	UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
	  ctest --test-dir $(SANITIZE_BUILD) --output-on-failure -j $(JOBS) \
	  -E install_and_use

fuzz-smoke: deps
	FUZZ_BUILD=$(SANITIZE_BUILD) bash scripts/fuzz.sh $(FUZZ_SMOKE_SECONDS)

# Long fuzzing runs: FUZZ_SECONDS per target, FUZZ_JOBS in parallel.
fuzz: deps
	FUZZ_BUILD=$(SANITIZE_BUILD) bash scripts/fuzz.sh $(FUZZ_SECONDS)

# Quiet: the configure summary and the build's warnings, not every file.
QUIET_MAKE = -DCMAKE_RULE_MESSAGES=OFF -DCMAKE_TARGET_MESSAGES=OFF

build: deps
	@mkdir -p $(BUILD)
	@cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release $(QUIET_MAKE) \
	  >$(BUILD)/configure.log 2>&1 || { cat $(BUILD)/configure.log; exit 1; }
	@grep -e '^-- .*\(found\|OpenEXR\|Embree\|SDL2\)' $(BUILD)/configure.log || true
	@cmake --build $(BUILD) -j $(JOBS) -- --no-print-directory -s
	@echo "glint: built $(BUILD)/glint"

deps:
	@bash scripts/install-deps.sh

# Headers, libraries, the program, glint.pc, the CMake package, man pages.
install: build
	cmake --install $(BUILD) --prefix $(PREFIX)

# What install put in place, as its manifest lists it.
uninstall:
	@test -f $(BUILD)/install_manifest.txt || \
	  { echo "uninstall: no $(BUILD)/install_manifest.txt (nothing installed from this build)" >&2; exit 1; }
	xargs -d '\n' rm -f -- <$(BUILD)/install_manifest.txt

# Optional: Tachyon, Embree 3 and assimp for glint bench's comparisons.
peers:
	bash scripts/install-deps.sh --peers

format:
	clang-format -i $$(git ls-files '*.c' '*.h')

clean:
	rm -rf $(BUILD) $(SANITIZE_BUILD)
