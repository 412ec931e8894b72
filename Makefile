# Downstroke: build, test, demo and bench.
#   make test    install what is missing, build, run every suite headless,
#                then install the egg as a user would and run them again
#   make check   just the suites, on build/ (the quick loop while working)
#   make demo    install what is missing, build, run the platformer demo
#   make bench   the benchmark scenes of bench-spec.md (never part of test)
#   make screenshots  the demos' pictures in docs/images/
# Each module foo.scm becomes build/downstroke.foo.so plus its import library,
# exactly the files `chicken-install` would install.

CSC       ?= csc
CSC_FLAGS ?= -O3 -d1
BUILD     := build

# Order matters only for reading; make follows the dependency lines below.
MODULES := test util media-header keywords numbers srfi-197 entity check camera tween animation particles xml decode json map tmj tmx tilemap scene broadphase physics overlap pipeline sdl2 mapdraw renderer input sound text assets prefabs objects game level repl save-text save engine

# C libraries a module binds through the FFI (passed to the linker by csc).
LINK_xml    := -L -lexpat
LINK_decode := -L -lz -L -lzstd
# SDL2's flags as Debian's pkg-config gives them (the .egg cannot run pkg-config).
SDL_CFLAGS  := -C -I/usr/include/SDL2 -C -D_REENTRANT
LINK_sdl2   := $(SDL_CFLAGS) -L -lSDL2 -L -lSDL2_image
LINK_input  := $(SDL_CFLAGS) -L -lSDL2
LINK_sound  := $(SDL_CFLAGS) -L -lSDL2 -L -lSDL2_mixer
LINK_text   := $(SDL_CFLAGS) -L -lSDL2 -L -lSDL2_ttf

LIBS := $(patsubst %,$(BUILD)/downstroke.%.so,$(MODULES))

# Compiled modules are found in build/ first, then in CHICKEN's own repository
# (asked with CHICKEN_INSTALL_REPOSITORY unset, which would otherwise name
# the install destination instead).
CHICKEN_REPO = $(shell env -u CHICKEN_INSTALL_REPOSITORY chicken-install -repository 2>/dev/null)
export CHICKEN_REPOSITORY_PATH = $(abspath $(BUILD)):$(CHICKEN_REPO)

# Tests and benchmarks run headless; demos open a window when there is a display.
HEADLESS := SDL_VIDEODRIVER=dummy SDL_AUDIODRIVER=dummy

.PHONY: all deps libs examples assets check test install-test demo bench screenshots clean
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
$(BUILD)/downstroke.%.so: %.scm | $(BUILD)
	cd $(BUILD) && $(CSC) -s $(CSC_FLAGS) -C -I$(CURDIR) $(LINK_$*) -J ../$< -o downstroke.$*.so
	cd $(BUILD) && $(CSC) -s $(CSC_FLAGS) downstroke.$*.import.scm -o downstroke.$*.import.so

# What each module imports from this library (compile-time dependencies);
# tests/layout-test.scm checks these lines against the imports and the .egg.
$(BUILD)/downstroke.sound.so: $(BUILD)/downstroke.keywords.so $(BUILD)/downstroke.media-header.so
$(BUILD)/downstroke.sdl2.so: $(BUILD)/downstroke.keywords.so $(BUILD)/downstroke.media-header.so
$(BUILD)/downstroke.decode.so: $(BUILD)/downstroke.keywords.so
$(BUILD)/downstroke.tween.so:     $(BUILD)/downstroke.entity.so $(BUILD)/downstroke.keywords.so $(BUILD)/downstroke.numbers.so
$(BUILD)/downstroke.animation.so: $(BUILD)/downstroke.entity.so
$(BUILD)/downstroke.particles.so: $(BUILD)/downstroke.entity.so $(BUILD)/downstroke.keywords.so $(BUILD)/downstroke.numbers.so
$(BUILD)/downstroke.map.so:       $(BUILD)/downstroke.util.so $(BUILD)/downstroke.keywords.so $(BUILD)/downstroke.numbers.so
$(BUILD)/downstroke.tmj.so:       $(BUILD)/downstroke.json.so $(BUILD)/downstroke.util.so
$(BUILD)/downstroke.tmx.so:       $(BUILD)/downstroke.media-header.so $(BUILD)/downstroke.xml.so $(BUILD)/downstroke.decode.so $(BUILD)/downstroke.util.so $(BUILD)/downstroke.map.so $(BUILD)/downstroke.keywords.so $(BUILD)/downstroke.tmj.so
$(BUILD)/downstroke.tilemap.so:   $(BUILD)/downstroke.map.so $(BUILD)/downstroke.tmx.so $(BUILD)/downstroke.objects.so
$(BUILD)/downstroke.scene.so:     $(BUILD)/downstroke.entity.so $(BUILD)/downstroke.map.so $(BUILD)/downstroke.keywords.so $(BUILD)/downstroke.camera.so $(BUILD)/downstroke.check.so
$(BUILD)/downstroke.physics.so:   $(BUILD)/downstroke.util.so $(BUILD)/downstroke.broadphase.so $(BUILD)/downstroke.entity.so $(BUILD)/downstroke.scene.so $(BUILD)/downstroke.map.so $(BUILD)/downstroke.keywords.so
$(BUILD)/downstroke.overlap.so:   $(BUILD)/downstroke.entity.so $(BUILD)/downstroke.scene.so $(BUILD)/downstroke.physics.so $(BUILD)/downstroke.broadphase.so $(BUILD)/downstroke.keywords.so
$(BUILD)/downstroke.check.so:     $(BUILD)/downstroke.keywords.so $(BUILD)/downstroke.entity.so $(BUILD)/downstroke.particles.so
$(BUILD)/downstroke.camera.so:    $(BUILD)/downstroke.keywords.so $(BUILD)/downstroke.entity.so $(BUILD)/downstroke.map.so $(BUILD)/downstroke.numbers.so
$(BUILD)/downstroke.pipeline.so:  $(BUILD)/downstroke.scene.so $(BUILD)/downstroke.physics.so $(BUILD)/downstroke.tween.so $(BUILD)/downstroke.animation.so $(BUILD)/downstroke.particles.so $(BUILD)/downstroke.srfi-197.so
$(BUILD)/downstroke.input.so:     $(BUILD)/downstroke.sdl2.so $(BUILD)/downstroke.keywords.so
$(BUILD)/downstroke.text.so:      $(BUILD)/downstroke.media-header.so $(BUILD)/downstroke.sdl2.so $(BUILD)/downstroke.keywords.so
$(BUILD)/downstroke.assets.so:    $(BUILD)/downstroke.util.so
$(BUILD)/downstroke.prefabs.so:   $(BUILD)/downstroke.entity.so $(BUILD)/downstroke.util.so $(BUILD)/downstroke.keywords.so
$(BUILD)/downstroke.objects.so:   $(BUILD)/downstroke.map.so $(BUILD)/downstroke.prefabs.so $(BUILD)/downstroke.util.so $(BUILD)/downstroke.keywords.so
$(BUILD)/downstroke.game.so:      $(BUILD)/downstroke.assets.so $(BUILD)/downstroke.keywords.so
$(BUILD)/downstroke.level.so:     $(BUILD)/downstroke.game.so $(BUILD)/downstroke.scene.so $(BUILD)/downstroke.tilemap.so $(BUILD)/downstroke.objects.so $(BUILD)/downstroke.sdl2.so $(BUILD)/downstroke.renderer.so $(BUILD)/downstroke.util.so $(BUILD)/downstroke.keywords.so
$(BUILD)/downstroke.repl.so:      
$(BUILD)/downstroke.save-text.so: 
$(BUILD)/downstroke.save.so:      $(BUILD)/downstroke.save-text.so
$(BUILD)/downstroke.engine.so:    $(BUILD)/downstroke.game.so $(BUILD)/downstroke.level.so $(BUILD)/downstroke.pipeline.so $(BUILD)/downstroke.scene.so $(BUILD)/downstroke.sdl2.so $(BUILD)/downstroke.renderer.so $(BUILD)/downstroke.input.so $(BUILD)/downstroke.keywords.so $(BUILD)/downstroke.repl.so $(BUILD)/downstroke.camera.so $(BUILD)/downstroke.save.so
$(BUILD)/downstroke.mapdraw.so:   $(BUILD)/downstroke.sdl2.so $(BUILD)/downstroke.map.so
$(BUILD)/downstroke.renderer.so:  $(BUILD)/downstroke.particles.so $(BUILD)/downstroke.mapdraw.so $(BUILD)/downstroke.physics.so $(BUILD)/downstroke.sdl2.so $(BUILD)/downstroke.entity.so $(BUILD)/downstroke.scene.so $(BUILD)/downstroke.map.so $(BUILD)/downstroke.keywords.so $(BUILD)/downstroke.check.so $(BUILD)/downstroke.numbers.so

# C files a module includes (its foreign-declare), found through -I.
$(BUILD)/downstroke.pipeline.so: needs.c
$(BUILD)/downstroke.renderer.so: keys.c
$(BUILD)/downstroke.physics.so: motion.c motion.h
$(BUILD)/downstroke.broadphase.so: broadphase.c
$(BUILD)/downstroke.repl.so: repl.c

# Tiled's own example maps, from Debian's tiled package (cached in tests/data).
examples:
	@sh tools/fetch-tiled-examples.sh

check: libs examples assets
	cd tests && $(HEADLESS) DOWNSTROKE_MAKE=1 csi -q -s run.scm

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

# The scenes of bench-spec.md, compiled like a game would be.
# RUNS=3 runs per scene instance (medians); BENCH_ARGS="S1 --quick" narrows.
RUNS ?= 3
$(BUILD)/bench-scenes: bench/scenes.scm $(LIBS)
	cd $(BUILD) && $(CSC) $(CSC_FLAGS) ../bench/scenes.scm -o bench-scenes

bench: libs $(BUILD)/bench-scenes
	$(HEADLESS) $(BUILD)/bench-scenes --runs $(RUNS) --csv bench/results.csv $(BENCH_ARGS)
	sh tools/plot-bench.sh bench/results.csv docs/images
	$(HEADLESS) csi -q -s bench/map-load.scm
	$(HEADLESS) csi -q -s bench/render.scm
	$(HEADLESS) csi -q -s bench/sprites.scm

clean:
	rm -rf $(BUILD)
