# The README's two commands. Both install what is missing, then build.
BUILD_DIR ?= build
JOBS ?= $(shell nproc)

.PHONY: run test build deps clean

run: build
	./scripts/run-workbench.sh $(BUILD_DIR)

test: build
	cd $(BUILD_DIR) && ctest --output-on-failure -j$(JOBS)

build: deps
	cmake -S . -B $(BUILD_DIR) -DCMAKE_BUILD_TYPE=Release
	cmake --build $(BUILD_DIR) -j$(JOBS)

deps:
	./scripts/install-deps.sh

clean:
	rm -rf $(BUILD_DIR)
