# The two commands of the README: `make demo` and `make test`. Both install what they need first.
BUILD ?= build
JOBS ?= $(shell nproc)
CMAKE_FLAGS ?= -DCMAKE_BUILD_TYPE=RelWithDebInfo

.PHONY: deps configure build demo test test-fast sanitize tsan fuzz fuzz-short cross bench bench-docs clean

deps:
	bash .ci/install-deps.sh

configure: deps
	cmake -S . -B $(BUILD) $(CMAKE_FLAGS) >/dev/null

build: configure
	cmake --build $(BUILD) -j $(JOBS)

# Only what the demo runs: the command-line tool and the library it links (not the tests or the benchmark).
demo: configure
	cmake --build $(BUILD) -j $(JOBS) --target tetprobe_cli
	$(BUILD)/samples/tetprobe demo --out $(BUILD)/demo

# Every test: the normal build, the ASan+UBSan build of the whole suite, a short fuzz run, and the
# run-time library cross-built for Windows x64 and Linux aarch64, its C harness run under wine and qemu.
test: test-fast sanitize tsan fuzz-short cross

test-fast: build
	ctest --test-dir $(BUILD) --output-on-failure -j $(JOBS)

sanitize: deps
	cmake -S . -B $(BUILD)-asan -DCMAKE_BUILD_TYPE=Debug -DTETPROBE_SANITIZE=ON \
	  -DCMAKE_C_COMPILER=clang-14 -DCMAKE_CXX_COMPILER=clang++-14 >/dev/null
	cmake --build $(BUILD)-asan -j $(JOBS)
	ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
	  ctest --test-dir $(BUILD)-asan --output-on-failure -j $(JOBS) -L 'unit|c'

# ThreadSanitizer: both shared libraries link under it, and the tests that query one store from many
# threads, the batches on threads and the multi-threaded bake run under it (Embree's own thread pool
# is suppressed by name in tests/tsan.supp).
tsan: deps
	cmake -S . -B $(BUILD)-tsan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DTETPROBE_TSAN=ON \
	  -DCMAKE_C_COMPILER=clang-14 -DCMAKE_CXX_COMPILER=clang++-14 >/dev/null
	cmake --build $(BUILD)-tsan -j $(JOBS) --target tetprobe tetprobe_runtime tetprobe_tests
	TSAN_OPTIONS="halt_on_error=1 suppressions=$(CURDIR)/tests/tsan.supp" \
	  $(BUILD)-tsan/tests/tetprobe_tests "[threads]"

fuzz-build: deps
	cmake -S . -B $(BUILD)-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DTETPROBE_FUZZ=ON \
	  -DCMAKE_C_COMPILER=clang-14 -DCMAKE_CXX_COMPILER=clang++-14 >/dev/null
	cmake --build $(BUILD)-fuzz -j $(JOBS) --target fuzz_load fuzz_build fuzz_bsp

fuzz-short: fuzz-build
	bash tests/fuzz/run.sh $(BUILD)-fuzz short

FUZZ_SECONDS ?= 600
fuzz: fuzz-build
	bash tests/fuzz/run.sh $(BUILD)-fuzz $(FUZZ_SECONDS)

# Windows x64 (MinGW-w64, run under wine) and Linux aarch64 (run under qemu-user): the run-time library.
cross: deps
	bash .ci/cross.sh $(BUILD) $(JOBS)

# The benchmark report (issue 8): every part of tetprobe_bench writes its JSON (the store part its
# markdown) into $(BENCH_OUT), scipy times find_simplex on the locate part's points, and report.py
# writes report.md and the PNG plots there (placement_vs_uniform.py adds placement.json before it). A
# part that fails is named "not run" in the report, so the old results of a part are removed first. `make bench-docs` copies the report into docs/bench/.
# The real levels (issue 15): run_levels.sh installs Debian's openarena-081-maps if missing, extracts the
# levels into $(BUILD)/levels (never the repository) and runs BENCH_LEVELS: "default" (two levels), "all"
# (every level of the benchmark) or names separated by commas; each level's reference is cached in
# $(BUILD)/levels/cache, so a second run skips it.
BENCH_OUT ?= $(BUILD)/bench
BENCH_PARTS ?= methods precision locate bake probes leak
BENCH_LEVELS ?= default
bench: build
	rm -rf $(BENCH_OUT) && mkdir -p $(BENCH_OUT)
	bash samples/bench/run_levels.sh $(BUILD) $(BENCH_OUT) $(BENCH_LEVELS) > $(BENCH_OUT)/levels.txt \
	  || echo "the real-level part failed: the report says so"
	$(BUILD)/samples/tetprobe_bench store > $(BENCH_OUT)/store.md.tmp && mv $(BENCH_OUT)/store.md.tmp $(BENCH_OUT)/store.md \
	  || echo "tetprobe_bench store failed: the report says so"
	for part in $(BENCH_PARTS); do \
	  $(BUILD)/samples/tetprobe_bench $$part --out $(BENCH_OUT) > $(BENCH_OUT)/$$part.txt \
	    || echo "tetprobe_bench $$part failed: the report says so"; \
	done
	/usr/bin/python3 samples/bench/scipy_locate.py $(BENCH_OUT)
	TETPROBE_LIBRARY=$(BUILD)/libtetprobe.so PYTHONPATH=bindings/python \
	  /usr/bin/python3 samples/bench/placement_vs_uniform.py $(BENCH_OUT) > $(BENCH_OUT)/placement.txt \
	  || echo "placement_vs_uniform.py failed: the report says so"
	/usr/bin/python3 samples/bench/report.py $(BENCH_OUT)

bench-docs:
	rm -rf docs/bench && mkdir -p docs/bench
	cp $(BENCH_OUT)/report.md $(BENCH_OUT)/*.png docs/bench/

clean:
	rm -rf $(BUILD) $(BUILD)-asan $(BUILD)-tsan $(BUILD)-fuzz
