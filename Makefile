# The README's two commands. Both install what is missing, then build.
BUILD_DIR ?= build
JOBS ?= $(shell nproc)
# Batched translation units (cmake/TactileBuild.cmake): a whole build in about half the time.
# BATCH=OFF compiles one unit per file, quicker to rebuild after editing one file.
BATCH ?= ON
# WERROR=ON: a warning in core/, widgets/ or app/ fails the build (CI sets it; the folder's
# CMake cache keeps it).
WERROR ?=

SANITIZE_DIR ?= build-asan

.PHONY: run test test-busy test-slurm build deps clean sanitize fuzz format format-check

run: build
	./scripts/run-workbench.sh $(BUILD_DIR)

# Every test but the Slurm end-to-end one, which starts a cluster of its own (test-slurm), and
# the job tests beside busy processes (test-busy), which take the machine for three minutes.
test: build
	cd $(BUILD_DIR) && ctest --output-on-failure -j$(JOBS) -LE 'slurm|busy'

# The workbench's job tests beside two busy processes (tests/busy/beside_busy.sh).
test-busy: build
	cd $(BUILD_DIR) && ctest --output-on-failure -L busy

# Shards submitted to a single-node Slurm on localhost and merged (docs/CLUSTER.md).
test-slurm: build
	cd $(BUILD_DIR) && ctest --output-on-failure -L slurm

# Ninja, a fast linker and ccache (all from scripts/install-deps.sh). A build folder made by
# another generator is configured afresh.
configure = if [ -f $(1)/CMakeCache.txt ] && ! grep -qx 'CMAKE_GENERATOR:INTERNAL=Ninja' $(1)/CMakeCache.txt; \
	  then rm -rf $(1)/CMakeCache.txt $(1)/CMakeFiles; fi; \
	  cmake -S . -B $(1) -G Ninja -DTACTILE_BATCH=$(BATCH) $(if $(WERROR),-DTACTILE_WERROR=$(WERROR))

build: deps
	$(call configure,$(BUILD_DIR)) -DCMAKE_BUILD_TYPE=Release
	cmake --build $(BUILD_DIR) -j$(JOBS)

deps:
	./scripts/install-deps.sh

# The core and command-line tests (and the fuzz corpora) again, built by clang at -O2 with ASan
# and UBSan: any finding aborts the test that met it (tests/fuzz/README.md, "Sanitizers").
# clang, not g++ -O3: the same checks at a third of the compile time. The render tests are not
# built here because they are not run here.
SANITIZE_FLAGS = -O2 -DNDEBUG
sanitize: deps
	$(call configure,$(SANITIZE_DIR)) -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
	  -DCMAKE_BUILD_TYPE=Release -DCMAKE_C_FLAGS_RELEASE="$(SANITIZE_FLAGS)" \
	  -DCMAKE_CXX_FLAGS_RELEASE="$(SANITIZE_FLAGS)" -DTACTILE_SANITIZE=address,undefined \
	  -DTACTILE_BUILD_BENCH=OFF -DTACTILE_BUILD_GUI=OFF -DTACTILE_BUILD_RENDER_TESTS=OFF
	cmake --build $(SANITIZE_DIR) -j$(JOBS)
	cd $(SANITIZE_DIR) && LSAN_OPTIONS=suppressions=$(CURDIR)/tests/lsan.supp:print_suppressions=0 \
	  UBSAN_OPTIONS=print_stacktrace=1 \
	  ctest --output-on-failure -j$(JOBS) -L 'core|cli|workbench|fuzz|sanitizer'

# Every fuzz target for a few seconds (scripts/fuzz.sh --seconds N for longer).
fuzz: deps
	./scripts/fuzz.sh

# clang-format over the tree (.clang-format); CI runs format-check, which fails on any file it
# would change.
format: deps
	./scripts/format.sh

format-check: deps
	./scripts/format.sh --check

clean:
	rm -rf $(BUILD_DIR)
