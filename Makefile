# Thin wrapper: the two commands users need (`make demo`, `make test`) plus `make bench` and `make package`.
# Each installs what it needs (tools/bootstrap), configures a Release build in $(BUILD) and builds.

BUILD ?= build
JOBS ?= $(shell nproc 2>/dev/null || echo 2)
DEMO_OUT ?= out/demo
CMAKE_FLAGS ?=

FUZZ_BUILD ?= build-fuzz
FUZZ_RUNS ?= 1000000

.PHONY: all demo test bench reference package fuzz build configure bootstrap format clean

all: build

bootstrap:
	@tools/bootstrap

configure: bootstrap
	@cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release $(CMAKE_FLAGS) > $(BUILD).configure.log 2>&1 || \
	  { cat $(BUILD).configure.log; exit 1; }

build: configure
	@cmake --build $(BUILD) -j$(JOBS)

# The most complete job the project can do on its bundled sample; prints where the result is.
demo: build
	@tools/demo $(BUILD)/apps/lfsp $(DEMO_OUT)

test: build
	@cd $(BUILD) && ctest --output-on-failure -j$(JOBS)

# The chain rows (bench/chain_bench.cc) time this build beside a reference build of the commit in bench/REFERENCE.
bench: build reference
	@$(BUILD)/bench/lfsp_bench

reference:
	@JOBS=$(JOBS) tools/build_reference $(BUILD)

# The Debian package (CPack, cmake/LfspPackaging.cmake): the command, man pages, Python module, workflow, samples.
package: build
	@cd $(BUILD) && cpack -G DEB > cpack.log 2>&1 || { cat cpack.log; exit 1; }
	@ls $(BUILD)/packages/lfsp_*.deb

# Every fuzz target as a libFuzzer binary with the whole tree instrumented (clang, ASan, UBSan), each run for
# FUZZ_RUNS executions from its seeds; the table of executions, coverage and time goes to FUZZING.md's format.
fuzz:
	@tools/bootstrap --fuzz
	@CC=clang CXX=clang++ cmake -S . -B $(FUZZ_BUILD) -DCMAKE_BUILD_TYPE=RelWithDebInfo -DLFSP_FUZZ=ON \
	  -DLFSP_BUILD_PYTHON=OFF -DLFSP_BUILD_BENCH=OFF > $(FUZZ_BUILD).configure.log 2>&1 || \
	  { cat $(FUZZ_BUILD).configure.log; exit 1; }
	@cmake --build $(FUZZ_BUILD) -j$(JOBS) --target lfsp_fuzz_targets
	@tools/fuzz $(FUZZ_BUILD) $(FUZZ_RUNS)

format:
	@git ls-files '*.cc' '*.h' | xargs clang-format -i

clean:
	@rm -rf $(BUILD) $(BUILD).configure.log $(FUZZ_BUILD) $(FUZZ_BUILD).configure.log
