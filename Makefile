# The README's two commands. Both install what is missing, then build.
BUILD_DIR ?= build
JOBS ?= $(shell nproc)

SANITIZE_DIR ?= build-asan

.PHONY: run test build deps clean sanitize fuzz

run: build
	./scripts/run-workbench.sh $(BUILD_DIR)

test: build
	cd $(BUILD_DIR) && ctest --output-on-failure -j$(JOBS)

build: deps
	cmake -S . -B $(BUILD_DIR) -DCMAKE_BUILD_TYPE=Release
	cmake --build $(BUILD_DIR) -j$(JOBS)

deps:
	./scripts/install-deps.sh

# The core and command-line tests (and the fuzz corpora) again, built with ASan and UBSan:
# any finding aborts the test that met it (tests/fuzz/README.md, "Sanitizers").
sanitize: deps
	cmake -S . -B $(SANITIZE_DIR) -DCMAKE_BUILD_TYPE=Release -DTACTILE_SANITIZE=address,undefined \
	  -DTACTILE_BUILD_BENCH=OFF -DTACTILE_BUILD_GUI=OFF
	cmake --build $(SANITIZE_DIR) -j$(JOBS)
	cd $(SANITIZE_DIR) && LSAN_OPTIONS=suppressions=$(CURDIR)/tests/lsan.supp:print_suppressions=0 \
	  UBSAN_OPTIONS=print_stacktrace=1 \
	  ctest --output-on-failure -j$(JOBS) -L 'core|cli|fuzz'

# Every fuzz target for a few seconds (scripts/fuzz.sh --seconds N for longer).
fuzz: deps
	./scripts/fuzz.sh

clean:
	rm -rf $(BUILD_DIR)
