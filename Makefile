# Downstroke: build, test, demo and bench.
#   make test    install what is missing, build, run every suite headless,
#                then install the egg as a user would and run them again
#   make check   just the suites, on build/ (the quick loop while working)
#   make demo    install what is missing, build, run the platformer demo
#   make bench   the benchmark scenes of docs/performance.org (never part of test),
#                and S1 and S2 in plain C beside them
#   make screenshots  the demos' pictures in docs/images/
#   make web     the platformer (or GAME=path/to/game.scm) for the browser, in build/web/
#   make web-bench  S1 and the platformer in headless Chromium and natively, in one run
# Each module foo.scm becomes build/downstroke.foo.so plus its import library,
# exactly the files `chicken-install` would install.

CSC       ?= csc
# Options for what the .egg does not build: import libraries and the bench.
CSC_FLAGS ?= -O3 -d1
BUILD     := build

# The build graph comes from downstroke.egg, its one statement: MODULES,
# each module's SOURCE_name (its file), FLAGS_name (its csc and link
# options) and a line "$(BUILD)/downstroke.name.so: its source, its C
# files, the modules it imports". tools/egg-graph.scm writes it; make remakes it when the .egg
# changes and reads it again.
include $(BUILD)/graph.mk
$(BUILD)/graph.mk: downstroke.egg tools/egg-graph.scm | deps
	@mkdir -p $(BUILD)
	csi -q -s tools/egg-graph.scm downstroke.egg > $@.tmp && mv $@.tmp $@

LIBS := $(patsubst %,$(BUILD)/downstroke.%.so,$(MODULES))

# make web: the browser build (tools/web.mk).
include tools/web.mk

# Compiled modules are found in build/ first, then in CHICKEN's own repository
# (asked with CHICKEN_INSTALL_REPOSITORY unset, which would otherwise name
# the install destination instead).
CHICKEN_REPO = $(shell env -u CHICKEN_INSTALL_REPOSITORY chicken-install -repository 2>/dev/null)
export CHICKEN_REPOSITORY_PATH = $(abspath $(BUILD)):$(CHICKEN_REPO)

# Tests and benchmarks run headless; demos open a window when there is a display.
HEADLESS := SDL_VIDEODRIVER=dummy SDL_AUDIODRIVER=dummy

.PHONY: all deps libs examples assets check test install-test demo bench web-bench screenshots clean
all: libs

deps:
	@sh tools/install-deps.sh

# Two cores: build two modules at a time.
MAKEFLAGS += -j2

libs: $(LIBS)
$(LIBS): | deps

$(BUILD):
	mkdir -p $(BUILD)

# -J writes downstroke.foo.import.scm beside the library; it is compiled too,
# so `import` loads native code rather than interpreting the import list.
$(BUILD)/downstroke.%.so: | $(BUILD)
	cd $(BUILD) && $(CSC) -s $(FLAGS_$*) -C -I$(CURDIR) -J ../$(SOURCE_$*) -o downstroke.$*.so
	cd $(BUILD) && $(CSC) -s $(CSC_FLAGS) downstroke.$*.import.scm -o downstroke.$*.import.so

# Tiled's own example maps, from Debian's tiled package (cached in tests/data).
examples:
	@sh tools/fetch-tiled-examples.sh

# SUITES="escape physics/" runs only those suites (names, or folders ending
# in /); each suite runs alone in its own process (tests/run.scm).
check: libs examples assets $(BUILD)/bench-scenes $(BUILD)/bench-reference
	cd tests && $(HEADLESS) DOWNSTROKE_MAKE=1 $(if $(SUITES),DOWNSTROKE_SUITES="$(SUITES)") csi -q -s run.scm

# After check, not beside it (-j2): a clean copy installed into a private
# repository by an ordinary user, chicken-install -test, a static game build.
test: check
	@sh tools/install-test.sh

install-test: deps
	@sh tools/install-test.sh

# The demos' art and sounds are generated, not stored: demo/assets/. The
# generator makes them only when missing or older than itself.
assets: libs
	@$(HEADLESS) csi -q -s tools/make-assets.scm

# Opens a window when there is a display; otherwise runs headless and says so.
# The demos' pictures in docs/images/ (demo-NAME.png), from headless runs.
screenshots: libs assets
	$(HEADLESS) sh tools/make-screenshots.sh

demo: libs assets
	bin/demo-platformer

# The scenes of docs/performance.org, compiled like a game would be.
# RUNS=3 runs per scene instance (medians); BENCH_ARGS="S1 --quick" narrows.
RUNS ?= 3
$(BUILD)/bench-scenes: bench/scenes.scm $(LIBS)
	cd $(BUILD) && $(CSC) $(CSC_FLAGS) ../bench/scenes.scm -o bench-scenes

$(BUILD)/bench-draw: bench/draw.scm $(LIBS)
	cd $(BUILD) && $(CSC) $(CSC_FLAGS) ../bench/draw.scm -o bench-draw

# S1 and S2 in plain C (bench/reference/scenes.c, doubles, no CHICKEN): the
# same scenes and checksums, the distance to a C program (docs/performance.org).
REF_CC ?= cc
$(BUILD)/bench-reference: bench/reference/scenes.c | $(BUILD)
	$(REF_CC) -O2 -o $@ bench/reference/scenes.c -lm

bench: libs $(BUILD)/bench-scenes $(BUILD)/bench-draw $(BUILD)/bench-reference
	$(HEADLESS) $(BUILD)/bench-scenes --runs $(RUNS) --csv bench/results.csv $(BENCH_ARGS)
	$(BUILD)/bench-reference --runs $(RUNS) --csv bench/reference/results.csv $(BENCH_ARGS)
	sh tools/plot-bench.sh bench/results.csv docs/images
	$(HEADLESS) csi -q -s bench/map-load.scm
	$(HEADLESS) csi -q -s bench/render.scm
	$(HEADLESS) csi -q -s bench/sprites.scm
	sh tools/bench-draw.sh $(BUILD)

# docs/performance.org, "In the browser": S1 at 1,000 movers and the
# platformer's frame profile, in headless Chromium (tools/web-bench.py) and
# natively, alternating; WEB_BENCH_ROUNDS rounds. Not part of test.
WEB_BENCH_ROUNDS ?= 3
web-bench: libs assets $(BUILD)/bench-scenes
	$(MAKE) --no-print-directory web GAME=bench/scenes.scm
	$(MAKE) --no-print-directory web GAME=demo/platformer.scm ASSETS="demo tests/web"
	/usr/bin/python3 tools/web-bench.py --rounds $(WEB_BENCH_ROUNDS) $(WEB)/scenes $(BUILD)/bench-scenes \
	  --runs 1 --n 1000 S1
	$(HEADLESS) /usr/bin/python3 tools/web-bench.py --rounds $(WEB_BENCH_ROUNDS) --until "profile: frames 540-599" \
	  $(WEB)/platformer bin/demo-platformer --frames 600 --script tests/web/platformer-input.scm --profile

clean:
	rm -rf $(BUILD)
