# rescuesim: the two quick-start commands are `make run` and `make test`.
# Every target installs missing Debian packages first (scripts/install-deps.sh).

BUILD   ?= build
JOBS    ?= $(shell nproc 2>/dev/null || echo 2)
CMAKE_FLAGS ?=
RUN_ARGS ?=

.PHONY: all deps configure build cli run test test-asan test-tsan fuzz-smoke lint check-includes bench clean install deb wheel

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

# only the CLI and what it links (not the tests, benchmarks and examples)
cli: deps $(BUILD)/CMakeCache.txt
	cmake --build $(BUILD) --target rescuesim -j $(JOBS)

# installs the CLI, the demonstrations' programs, the worlds, examples, docs and the Python
# package under PREFIX (docs/install.md); sudo for a system prefix
PREFIX ?= /usr/local
install: build
	cmake --install $(BUILD) --prefix $(PREFIX)

# a Debian package of the same files under /usr, in $(BUILD)/packages (docs/install.md)
deb: build
	cpack --config $(BUILD)/CPackConfig.cmake -G DEB -B $(BUILD)/packages
	@ls $(BUILD)/packages/*.deb

# a Python wheel of the extension and package, in $(BUILD)/packages (docs/install.md)
wheel: build
	scripts/make-wheel.sh $(BUILD) $(BUILD)/packages

# the default rescue scenario, headless; outputs go to runs/default/
run: cli
	$(BUILD)/bin/rescuesim run $(RUN_ARGS)

# the bridge tests drive reference npm clients (tests/js), installed into $(BUILD)/js
test: build
	scripts/install-test-js.sh $(BUILD)/js
	RESCUESIM_REQUIRE_GL=1 ctest --test-dir $(BUILD) --output-on-failure -j $(JOBS)

# the unit suites under AddressSanitizer + UBSan (Debug, in build-asan); ROS, Python, the
# benchmarks and the GL-bound render suite are left out. LSan's suppressions name third-party
# libraries only (scripts/lsan.supp).
ASAN_BUILD ?= build-asan
ASAN_SUITES ?= core world import msgs viz physics raycast robots sensors sim autonomy
ASAN_JOBS ?= $(JOBS)
# Mesa's DRI driver is dlopen'ed by EGL for the camera tests and dlclose'd at eglTerminate; what
# it keeps in its own globals then looks leaked ("<unknown module>" frames, which no suppression
# can name). Preloading the driver keeps it mapped to the end, so LeakSanitizer sees those roots.
MESA_DRI ?= $(firstword $(wildcard /usr/lib/$(shell gcc -dumpmachine 2>/dev/null)/dri/swrast_dri.so /usr/lib/dri/swrast_dri.so))
test-asan: deps
	cmake -S . -B $(ASAN_BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Debug -DRESCUESIM_SANITIZE=ON -DRESCUESIM_PCH=OFF \
	  -DRESCUESIM_ROS1=OFF -DRESCUESIM_ROS2=OFF -DRESCUESIM_PYTHON=OFF -DRESCUESIM_BENCH=OFF \
	  -DPython_EXECUTABLE=/usr/bin/python3 $(CMAKE_FLAGS)
	cmake --build $(ASAN_BUILD) -j $(ASAN_JOBS) --target $(addsuffix _tests,$(ASAN_SUITES))
	$(if $(MESA_DRI),LD_PRELOAD=$(MESA_DRI)) \
	ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:verify_asan_link_order=0 \
	UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
	LSAN_OPTIONS=suppressions=$(CURDIR)/scripts/lsan.supp:print_suppressions=0 \
	  ctest --test-dir $(ASAN_BUILD) --output-on-failure -j $(ASAN_JOBS) -L '^($(subst $() $(),|,$(ASAN_SUITES)))$$'

# the suites that run threads under ThreadSanitizer (RelWithDebInfo, build-tsan): the worker
# pool (core), the bus, the bridges' shared parts, the camera renderer (EGL on llvmpipe), the
# simulation and the session (the camera render thread, RunControl's posted tasks), the four
# bridges with threads of their own (foxglove's WebSocket I/O and serialiser, mcap's writer,
# ros1's sender, spinner and services, ros2's sender and receiver beside Cyclone's threads) and
# the viewer's loop (TSAN_APP_TESTS: `rescuesim view` under Xvfb, its simulation thread and
# render worker beside the window's thread). Many tests run the TSan-built rescuesim as a child,
# which inherits TSAN_OPTIONS, so a race there fails the test too. Under TSan the pool runs on
# std::threads and Embree builds on the calling thread (docs/building.md), llvmpipe rasterises
# on the calling thread (LP_NUM_THREADS=0), and where an uninstrumented library orders our
# accesses the code says so (core/tsan.h); scripts/tsan.supp names third-party frames only, each
# with its reason. A GL test without a context fails here instead of skipping
# (RESCUESIM_REQUIRE_GL=1).
# TSAN_EXCLUDE names the tests left out, each for a reason of TSan's own:
#   FoxgloveProbe.*: runs rescuesim-bench, which this build does not make (RESCUESIM_BENCH=OFF);
#   FoxgloveServer.ClientDecodesTopicsAndDrivesTheRobot: its client expects > 2 s of sim time and
#     a scan rate within a wall-clock window, which TSan's slowdown misses on a busy machine;
#   FoxgloveServer.BadClientsGetStatusErrorsAndSlowOnesLoseFramesNotMemory: bounds the process's
#     RSS growth to 64 MiB, which TSan's allocator and shadow memory exceed by themselves;
#   UrdfCorpusSim.*: 27 single robots in physics, one island each, so one thread: nothing for
#     TSan to see, and a minute of its time.
TSAN_BUILD ?= build-tsan
TSAN_SUITES ?= core bus bridges_common sensors_camera sim session foxglove mcap ros1 ros2
TSAN_APP_TESTS ?= ^ViewSnapshot\.(WindowScreenshotShowsMainViewAndFourPanels|TheScenariosControllerDrivesTheRobotInTheWindow)$$
TSAN_EXCLUDE ?= ^FoxgloveProbe\.|^FoxgloveServer\.(ClientDecodesTopicsAndDrivesTheRobot|BadClientsGetStatusErrorsAndSlowOnesLoseFramesNotMemory)$$|^UrdfCorpusSim\.
TSAN_JOBS ?= $(JOBS)
TSAN_ENV = LP_NUM_THREADS=0 RESCUESIM_REQUIRE_GL=1 \
	TSAN_OPTIONS=halt_on_error=1:second_deadlock_stack=1:suppressions=$(CURDIR)/scripts/tsan.supp
test-tsan: deps
	cmake -S . -B $(TSAN_BUILD) -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DRESCUESIM_TSAN=ON -DRESCUESIM_PCH=OFF \
	  -DRESCUESIM_ROS1=ON -DRESCUESIM_ROS2=ON -DRESCUESIM_PYTHON=OFF -DRESCUESIM_BENCH=OFF \
	  -DPython_EXECUTABLE=/usr/bin/python3 $(CMAKE_FLAGS)
	cmake --build $(TSAN_BUILD) -j $(TSAN_JOBS) --target rescuesim $(addsuffix _tests,$(TSAN_SUITES)) \
	  $(if $(TSAN_APP_TESTS),app_tests)
	$(TSAN_ENV) ctest --test-dir $(TSAN_BUILD) --output-on-failure -j $(TSAN_JOBS) -L '^($(subst $() $(),|,$(TSAN_SUITES)))$$' \
	  $(if $(TSAN_EXCLUDE),-E '$(TSAN_EXCLUDE)')
	$(if $(TSAN_APP_TESTS),$(TSAN_ENV) ctest --test-dir $(TSAN_BUILD) --output-on-failure -j $(TSAN_JOBS) -L '^app$$' -R '$(TSAN_APP_TESTS)' \
	  --no-tests=error)

# every fuzz target for 20 s (clang + libFuzzer, in build-fuzz); FUZZ_SECONDS to change
FUZZ_SECONDS ?= 20
fuzz-smoke: deps
	scripts/fuzz.sh --smoke $(FUZZ_SECONDS)

# the formatter and linter (.clang-format, .clang-tidy) on the lines a change touches, and no
# line over 140 columns anywhere (scripts/lint.sh says what "a change" is; LINT_BASE=<commit>
# sets where it starts). clang-tidy reads $(BUILD)/compile_commands.json, hence the configure.
LINT_BASE ?=
lint: deps $(BUILD)/CMakeCache.txt
	LINT_BASE=$(LINT_BASE) BUILD=$(BUILD) LINT_JOBS=$(JOBS) scripts/lint.sh

# the include direction of docs/architecture.md section 3 (also a ctest test, label checks)
check-includes:
	scripts/check-includes.sh

# every benchmark figure into $(BUILD)/bench.json. The benchmarks are their own program,
# rescuesim-bench (src/bench), which `rescuesim bench` runs; `build` builds it with what the
# report also times (the Python API, the batch runner), while `cli` (make run) leaves it out
bench: build
	$(BUILD)/bin/rescuesim bench --out $(BUILD)/bench.json

clean:
	rm -rf $(BUILD) runs
