# The browser build, included by the Makefile (docs/guide.org, "Shipping
# to the web"):
#   make web                          the platformer demo
#   make web GAME=path/to/game.scm    any game, unchanged
# gives build/web/NAME/ with index.html, index.js, index.wasm and
# index.data (the game's files), to serve or upload as it is.
#
# The modules are translated to C by the host's csc (as the egg builds
# them, plus -static, -unit and the feature downstroke-web) and compiled
# for wasm32 by Debian's emscripten against the libraries tools/web-deps.sh
# builds once from Debian's sources and keeps outside the clone.
#
# The game runs in the browser from a folder ROOT, mounted as /: the
# repository for a game inside it (the demos read demo/assets/...), else
# the game's own folder. ASSETS (default: the game's folder) is preloaded
# at its place under ROOT.

GAME      ?= demo/platformer.scm
WEB       := $(BUILD)/web
WEB_NAME   = $(basename $(notdir $(GAME)))
WEB_OUT    = $(WEB)/$(WEB_NAME)
WEB_GAME   = $(abspath $(GAME))
WEB_ROOT   = $(if $(filter $(CURDIR)/%,$(WEB_GAME)),$(CURDIR),$(patsubst %/,%,$(dir $(WEB_GAME))))
ASSETS    ?= $(patsubst %/,%,$(dir $(WEB_GAME)))
# More files, as emscripten's --preload-file takes them: HOST-PATH@PAGE-PATH.
# The demos draw their text with Debian's DejaVu font, read from its system
# path, so their pages carry it there.
DEMO_FONT := /usr/share/fonts/truetype/dejavu/DejaVuSans-Bold.ttf
WEB_PRELOAD ?= $(if $(filter $(CURDIR)/demo/%,$(WEB_GAME)),$(DEMO_FONT)@$(DEMO_FONT))
# The libraries' folder; asking web-deps.sh costs a few apt-cache calls, so
# only the web targets do it.
ifneq ($(filter web% wasm32-check,$(MAKECMDGOALS)),)
WEB_DEPS  := $(shell sh tools/web-deps.sh --key)
endif
EMCC       = NODE_PATH=/usr/share/nodejs emcc
EMAR       = NODE_PATH=/usr/share/nodejs emar
# As csc compiles CHICKEN's C (csc -cflags), for wasm32.
WEB_CFLAGS = -O2 -fno-strict-aliasing -fwrapv -DHAVE_CHICKEN_CONFIG_H -DC_ENABLE_PTABLES \
             -I$(WEB_DEPS)/include/chicken -I$(WEB_DEPS)/include/SDL2 -I$(WEB_DEPS)/include \
             -I$(CURDIR) -Wno-unused-value -Wno-parentheses-equality -Wno-tautological-compare
# The browser's call stack is about 1 MB: CHICKEN's nursery (its C stack
# between two minor collections) must stay well below it.
WEB_NURSERY ?= 128k
WEB_LIBS   = SDL2_ttf freetype SDL2_image SDL2_mixer SDL2 expat zstd z chicken
WEB_LDFLAGS = -O2 -sALLOW_MEMORY_GROWTH=1 -sFORCE_FILESYSTEM=1 -lidbfs.js \
  -sEXPORTED_RUNTIME_METHODS=['FS','addRunDependency','removeRunDependency'] \
  -sDEFAULT_LIBRARY_FUNCS_TO_INCLUDE=['$$autoResumeAudioContext','$$dynCall'] \
  -sMINIFY_HTML=0 --shell-file tools/web/shell.html --pre-js tools/web/pre.js

WEB_OBJS := $(patsubst %,$(WEB)/obj/downstroke.%.o,$(MODULES))

.PHONY: web web-deps wasm32-check web-test
web-deps: deps
	@sh tools/install-deps.sh web
	@sh tools/web-deps.sh >/dev/null

# A module's C: translated from its source once its native build (and so
# its import library and those of the modules it imports) is done.
$(WEB)/obj/downstroke.%.c: $(BUILD)/downstroke.%.so
	@mkdir -p $(WEB)/obj
	$(CSC) -t $(SOURCE_$*) -static -unit downstroke.$* -feature downstroke-web \
	  $(filter-out -L -C -l% -I% -D%,$(FLAGS_$*)) -I$(CURDIR) -o $@

# kept: make would otherwise delete them as intermediate files
.PRECIOUS: $(WEB)/obj/%.c
$(WEB)/obj/%.o: $(WEB)/obj/%.c tools/web.mk | web-deps
	$(EMCC) $(WEB_CFLAGS) -c $< -o $@

$(WEB)/libdownstroke.a: $(WEB_OBJS)
	rm -f $@ && $(EMAR) rcs $@ $^

# The game: its C is made afresh each time (its own includes are unknown
# here), then linked with the library and everything it needs.
web: libs assets web-deps $(WEB)/libdownstroke.a
	@mkdir -p $(WEB_OUT)
	cd $(WEB_ROOT) && $(CSC) -t $(WEB_GAME) -static -feature downstroke-web -O3 -d1 \
	  -nursery $(WEB_NURSERY) -o $(abspath $(WEB_OUT))/game.c
	$(EMCC) $(WEB_CFLAGS) -c $(WEB_OUT)/game.c -o $(WEB_OUT)/game.o
	$(EMCC) $(WEB_OUT)/game.o $(WEB)/libdownstroke.a $(patsubst %,$(WEB_DEPS)/lib/lib%.a,$(WEB_LIBS)) \
	  $(WEB_LDFLAGS) $(foreach a,$(abspath $(ASSETS)),--preload-file $(a)@$(patsubst $(WEB_ROOT)%,%,$(a))$(if $(filter $(WEB_ROOT),$(a)),/)) \
	  $(foreach f,$(WEB_PRELOAD),--preload-file $(f)) \
	  -o $(WEB_OUT)/index.html
	@rm -f $(WEB_OUT)/game.c $(WEB_OUT)/game.o $(WEB_OUT)/game.link
	@echo "web: $(WEB_OUT)/index.html (serve the folder: python3 -m http.server -d $(WEB_OUT))"

# The suites that exercise every place where a value may pass 2^30, run
# where fixnums are 31 bits wide (wasm32, under node): tools/wasm32-check.sh.
# Left out: suites that start processes (bounded-run, the demos) or open
# a display, which a program under node cannot.
WASM32_SUITES ?= util entity tween camera scene tilemap tmx decode json broadphase swept pipeline oneway riders overlap
wasm32-check: libs examples assets web-deps $(WEB)/libdownstroke.a
	sh tools/wasm32-check.sh $(WEB_DEPS) $(WASM32_SUITES)

# The browser tests (tools/web-test.py): the platformer and the shmup run a
# scripted input in headless Chromium and their last frame must match the
# native headless run's; a save must survive a reload. The demos' pages
# carry tests/web/ (the input scripts) beside demo/.
WEB_SHOTS := $(WEB)/native
web-test: libs assets web-deps $(WEB)/libdownstroke.a
	$(MAKE) --no-print-directory web GAME=demo/platformer.scm ASSETS="demo tests/web"
	$(MAKE) --no-print-directory web GAME=demo/shmup.scm ASSETS="demo tests/web"
	$(MAKE) --no-print-directory web GAME=tests/web/save-game.scm
	@mkdir -p $(WEB_SHOTS)
	$(HEADLESS) bin/demo-platformer --headless --frames 240 --script tests/web/platformer-input.scm \
	  --screenshot $(WEB_SHOTS)/platformer.png > /dev/null
	$(HEADLESS) bin/demo-shmup --headless --frames 150 --script tests/web/shmup-input.scm \
	  --screenshot $(WEB_SHOTS)/shmup.png > /dev/null
	/usr/bin/python3 tools/web-test.py $(WEB) $(WEB_SHOTS)
