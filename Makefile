# Two commands on a fresh Debian bookworm machine:
#   make demo   install missing packages, build (Release), run the main job on a built-in sample
#   make test   the same set-up, then the test suite through ctest (make test-heavy: the large models)
# Both are idempotent and work offline once the packages are installed.

BUILD  ?= build
JOBS   ?= $(shell nproc)
OUT    ?= out/demo
CMAKE_FLAGS ?=

.PHONY: all deps configure build demo test test-heavy bench fuzz picture clean

all: build

deps:
	@scripts/install-deps.sh

configure: deps
	@cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release $(CMAKE_FLAGS) >/dev/null

build: configure
	@cmake --build $(BUILD) -j$(JOBS)

demo: build
	@scripts/demo.sh $(BUILD)/polycube $(OUT)

test: build
	@ctest --test-dir $(BUILD) --output-on-failure -j$(JOBS) --timeout 600 -LE heavy

# The construction of the large shared models (cup, bunny, rocker-arm, moai, max-planck),
# certified and simplified: about 12 minutes on 2 cores.
test-heavy: build
	@ctest --test-dir $(BUILD) --output-on-failure -j$(JOBS) --timeout 1200 -L heavy

bench: build
	@bench/run.sh $(BUILD)

# make fuzz [FUZZ_SECONDS=60]: every reader's libFuzzer target for that long (build-fuzz/).
FUZZ_SECONDS ?= 60
fuzz:
	@scripts/install-deps.sh scripts/packages-fuzz.txt
	@scripts/fuzz.sh $(FUZZ_SECONDS)

# The README's picture (docs/img/flange.png): the flange sample, its polycube and its hex mesh,
# rendered by VTK's Python (scripts/render_picture.py) from a `polycube run`.
picture: build
	@scripts/install-deps.sh scripts/packages-picture.txt
	@mkdir -p out/picture docs/img
	@$(BUILD)/polycube -q sample flange -o out/picture/flange.obj
	@$(BUILD)/polycube -q run out/picture/flange.obj -o out/picture/run --hexes 3000
	@xvfb-run -a /usr/bin/python3 scripts/render_picture.py out/picture/run out/picture/flange.obj docs/img/flange.png
	@echo "wrote docs/img/flange.png"

clean:
	@rm -rf $(BUILD) out
