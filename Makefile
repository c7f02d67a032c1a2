# pointnpr — the README's two commands:
#   make demo   install dependencies, build, run the pipeline on the sample scan + generated shapes
#   make test   install dependencies, build, run the whole test suite (CTest), then again under
#               AddressSanitizer + UndefinedBehaviorSanitizer with the PLY fuzz target
JOBS ?= $(shell nproc 2>/dev/null || echo 2)
BUILD ?= build
ASAN_BUILD ?= build-asan
FUZZ_SECONDS ?= 60

.PHONY: all deps build test test-release test-asan demo bench clean

all: build

deps:
	bash packaging/install-deps.sh

build: deps
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release -DPNPR_WERROR=ON -DPNPR_QUALITY_GATE=ON
	cmake --build $(BUILD) -j $(JOBS)

test-release: build
	ctest --test-dir $(BUILD) --output-on-failure -j $(JOBS)

test-asan: deps
	CC=clang CXX=clang++ cmake -S . -B $(ASAN_BUILD) -DCMAKE_BUILD_TYPE=RelWithDebInfo \
	  -DPNPR_WERROR=ON -DPNPR_SANITIZE=ON -DPNPR_FUZZ=ON -DPNPR_FUZZ_SECONDS=$(FUZZ_SECONDS)
	cmake --build $(ASAN_BUILD) -j $(JOBS)
	ASAN_OPTIONS=detect_leaks=1:abort_on_error=0 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
	  ctest --test-dir $(ASAN_BUILD) --output-on-failure -j $(JOBS)

test: test-release test-asan

demo: build
	bash scripts/demo.sh $(BUILD)

bench: deps
	bash packaging/install-deps.sh --bench
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release -DPNPR_WERROR=ON -DPNPR_BENCH_PEERS=ON
	cmake --build $(BUILD) -j $(JOBS)
	bash bench/run.sh $(BUILD)

clean:
	rm -rf $(BUILD) $(ASAN_BUILD)
