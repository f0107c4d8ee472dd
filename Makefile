# rescuesim: the two quick-start commands are `make run` and `make test`.
# Every target installs missing Debian packages first (scripts/install-deps.sh).

BUILD   ?= build
JOBS    ?= $(shell nproc 2>/dev/null || echo 2)
CMAKE_FLAGS ?=
RUN_ARGS ?=

.PHONY: all deps configure build run test bench clean

all: build

deps:
	@scripts/install-deps.sh

$(BUILD)/CMakeCache.txt: | deps
	cmake -S . -B $(BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Release \
	  -DPython_EXECUTABLE=/usr/bin/python3 $(CMAKE_FLAGS)

configure: deps
	cmake -S . -B $(BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Release \
	  -DPython_EXECUTABLE=/usr/bin/python3 $(CMAKE_FLAGS)

build: deps $(BUILD)/CMakeCache.txt
	cmake --build $(BUILD) -j $(JOBS)

# the default rescue scenario, headless; outputs go to runs/default/
run: build
	$(BUILD)/bin/rescuesim run $(RUN_ARGS)

# the bridge tests drive reference npm clients (tests/js), installed into $(BUILD)/js
test: build
	scripts/install-test-js.sh $(BUILD)/js
	ctest --test-dir $(BUILD) --output-on-failure -j $(JOBS)

bench: build
	$(BUILD)/bin/rescuesim bench --out $(BUILD)/bench.json

clean:
	rm -rf $(BUILD) runs
