# The two commands of the README. Both install missing Debian packages first
# (scripts/install-deps.sh), then configure and build a Release build.
BUILD ?= build
JOBS ?= $(shell nproc 2>/dev/null || echo 2)

PREFIX ?= /usr/local

.PHONY: render test build deps peers clean format install

render: build
	./$(BUILD)/glint render whitted -o whitted.png

test: build
	ctest --test-dir $(BUILD) --output-on-failure -j $(JOBS)

build: deps
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release
	cmake --build $(BUILD) -j $(JOBS)

deps:
	bash scripts/install-deps.sh

# Headers, libraries, the program, glint.pc, the CMake package, man pages.
install: build
	cmake --install $(BUILD) --prefix $(PREFIX)

# Optional: Tachyon, Embree 3 and assimp for glint bench's comparisons.
peers:
	bash scripts/install-deps.sh --peers

format:
	clang-format -i $$(git ls-files '*.c' '*.h')

clean:
	rm -rf $(BUILD)
