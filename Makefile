# SPDX-License-Identifier: MIT
# arvo: a plain Makefile. `make` builds ./arvo; `make check` runs every suite.
#   MODE=release (default) | debug        SANITIZE=1  (ASan + UBSan) | thread (TSan)
#   make fuzz FUZZ_SECONDS=N   runs the libFuzzer targets (clang; make deps-fuzz)
#   make deps      installs the Debian packages arvo needs (as root)
#   make install PREFIX=/usr/local DESTDIR=

MODE     ?= release
PREFIX   ?= /usr/local
DESTDIR  ?=
CC       ?= cc
CXX      ?= c++
BUILD    ?= build/$(MODE)$(if $(SANITIZE),-$(if $(filter thread,$(SANITIZE)),tsan,san))

# The warning list (after Lua's makefile): everything below must stay silent.
WARN = -Wall -Wextra -Wpedantic -Wshadow -Wundef -Wpointer-arith -Wcast-align \
       -Wwrite-strings -Wmissing-prototypes -Wstrict-prototypes \
       -Wmissing-declarations -Wformat=2 -Wvla -Wold-style-definition
CXXWARN = -Wall -Wextra -Wpedantic -Wshadow

ifeq ($(MODE),debug)
  OPT = -O0 -g3
else
  OPT = -O2 -g
endif
ifeq ($(SANITIZE),thread)
  OPT += -fsanitize=thread -fno-omit-frame-pointer
  LDSAN = -fsanitize=thread
else ifdef SANITIZE
  OPT += -fsanitize=address,undefined,float-cast-overflow -fno-omit-frame-pointer -fno-sanitize-recover=undefined,float-cast-overflow
  LDSAN = -fsanitize=address,undefined,float-cast-overflow
endif

# The eye pass's hot path (camera rays, ray packets, shading) at -O3 in
# release builds: fewer instructions per pixel, the same bits (no fast-math)
HOT_C = tracer/eyepass.c tracer/bvh.c tracer/camera.c tracer/shape.c tracer/shapes/sphere.c \
        tracer/render.c tracer/material.c tracer/leafbox.c tracer/surface.c tracer/shapes/box.c \
        tracer/shapes/torus.c tracer/shapes/cone.c tracer/shapes/cylinder.c tracer/pattern.c \
        tracer/noisepat.c common/xform.c tracer/light/illum.c tracer/shapes/plane.c \
        tracer/light/lightpass.c tracer/light/polygon.c tracer/csg.c tracer/polysolve.c \
        tracer/shapes/blob.c tracer/shapes/lathe.c tracer/shapes/mesh.c \
        tracer/shapes/outline.c tracer/shapes/poly.c tracer/shapes/polygon.c tracer/shapes/prism.c \
        tracer/shapes/sor.c tracer/shapes/superellipsoid.c tracer/shapes/text.c tracer/shapes/triangle.c \
        tracer/shapes/disc.c
ifneq ($(MODE),debug)
$(HOT_C:%.c=$(BUILD)/%.o): OPT := $(subst -O2,-O3,$(OPT)) -fno-math-errno
endif

PKGS     = OpenEXR OpenColorIO libpng freetype2
PKG_CFLAGS := $(shell pkg-config --cflags $(PKGS) 2>/dev/null)
PKG_LIBS   := $(shell pkg-config --libs $(PKGS) 2>/dev/null)

VERSION  = 0.1.0
CPPFLAGS += -D_DEFAULT_SOURCE -DARVO_VERSION='"$(VERSION)"' -MMD -MP
# -ffp-contract=off: no multiply-add fused, whatever the compiler (GCC's
# default under -std=c11, not clang's): the AVX-512 lanes and the scalar
# code they match must round each step alike (docs/design.md)
CFLAGS   += -std=c11 -ffp-contract=off $(OPT) $(WARN) -pthread $(PKG_CFLAGS)
CXXFLAGS += -std=c++14 $(OPT) $(CXXWARN) $(PKG_CFLAGS)
LDLIBS   += $(PKG_LIBS) -lembree3 -lstdc++ -lm -pthread

# Every .c under the source directories; main.c is the program's entry.
SRCDIRS  = common lexer parser eval tracer tools
LIB_C    = $(shell find $(SRCDIRS) -name '*.c' | sort)
LIB_CXX  = $(shell find $(SRCDIRS) -name '*.cpp' | sort)
LIB_OBJ  = $(LIB_C:%.c=$(BUILD)/%.o) $(LIB_CXX:%.cpp=$(BUILD)/%.o)
MAIN_OBJ = $(BUILD)/main.o

UNIT_SRC = $(sort $(wildcard tests/unit/test_*.c))
UNIT_BIN = $(UNIT_SRC:tests/unit/%.c=$(BUILD)/tests/%)

ifeq ($(V),1)
  Q =
else
  Q = @
endif

.PHONY: all clean check check-tsan test unit deps deps-fuzz fuzz fuzz-build install demo bench bench-accuracy lint povray-compat povray-corpus povray-photons gallery
all: arvo

arvo: $(BUILD)/arvo
	$(Q)cp $< $@

$(BUILD)/arvo: $(MAIN_OBJ) $(BUILD)/libarvo.a
	@echo "  LD      $@"
	$(Q)$(CC) $(OPT) $(LDSAN) -pthread -o $@ $^ $(LDLIBS)

$(BUILD)/libarvo.a: $(LIB_OBJ)
	@echo "  AR      $@"
	$(Q)rm -f $@ && ar rcs $@ $^

$(BUILD)/%.o: %.c
	@mkdir -p $(dir $@)
	@echo "  CC      $<"
	$(Q)$(CC) $(CPPFLAGS) $(CFLAGS) -c -o $@ $<

$(BUILD)/%.o: %.cpp
	@mkdir -p $(dir $@)
	@echo "  CXX     $<"
	$(Q)$(CXX) $(CPPFLAGS) $(CXXFLAGS) -c -o $@ $<

$(BUILD)/tests/%: tests/unit/%.c $(BUILD)/libarvo.a
	@mkdir -p $(dir $@)
	@echo "  CC      $<"
	$(Q)$(CC) $(CPPFLAGS) $(CFLAGS) -MF $@.d -o $@ $< $(BUILD)/libarvo.a $(LDSAN) $(LDLIBS)

unit: $(UNIT_BIN)

# Fuzzing (tests/fuzz, docs/design.md §8): each target's LLVMFuzzerTestOneInput
# is linked with a replay driver by the normal compiler (make check replays
# tests/fuzz/<target>/), and with libFuzzer by clang (make fuzz).
FUZZ_TARGETS = scene image
FUZZ_REPLAY  = $(FUZZ_TARGETS:%=$(BUILD)/fuzz/replay_%)
FUZZ_SECONDS ?= 60
FUZZ_CC      ?= clang
FUZZ_CXX     ?= clang++
FUZZ_BUILD   = build/fuzz
FUZZ_SAN     = -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined
FUZZ_OBJ     = $(LIB_C:%.c=$(FUZZ_BUILD)/%.o) $(LIB_CXX:%.cpp=$(FUZZ_BUILD)/%.o) $(FUZZ_BUILD)/tests/fuzz/fuzz_common.o

$(BUILD)/fuzz/replay_%: tests/fuzz/fuzz_%.c tests/fuzz/replay.c tests/fuzz/fuzz_common.c $(BUILD)/libarvo.a
	@mkdir -p $(dir $@)
	@echo "  CC      $@"
	$(Q)$(CC) $(CPPFLAGS) $(CFLAGS) -MF $@.d -o $@ tests/fuzz/fuzz_$*.c tests/fuzz/replay.c tests/fuzz/fuzz_common.c \
	    $(BUILD)/libarvo.a $(LDSAN) $(LDLIBS)

$(FUZZ_BUILD)/%.o: %.c
	@mkdir -p $(dir $@)
	@echo "  CC      $< (fuzz)"
	$(Q)$(FUZZ_CC) $(CPPFLAGS) -std=c11 -O1 -g $(WARN) -pthread $(PKG_CFLAGS) $(FUZZ_SAN) -fsanitize=fuzzer-no-link -c -o $@ $<

$(FUZZ_BUILD)/%.o: %.cpp
	@mkdir -p $(dir $@)
	@echo "  CXX     $< (fuzz)"
	$(Q)$(FUZZ_CXX) $(CPPFLAGS) -std=c++14 -O1 -g $(CXXWARN) $(PKG_CFLAGS) $(FUZZ_SAN) -fno-sanitize=vptr -c -o $@ $<

$(FUZZ_BUILD)/fuzz_%: $(FUZZ_BUILD)/tests/fuzz/fuzz_%.o $(FUZZ_OBJ)
	@echo "  LD      $@"
	$(Q)$(FUZZ_CC) -pthread $(FUZZ_SAN) -fsanitize=fuzzer -o $@ $(filter %.o,$^) $(LDLIBS)

unit: $(FUZZ_REPLAY)

fuzz-build: $(FUZZ_TARGETS:%=$(FUZZ_BUILD)/fuzz_%)
.PRECIOUS: $(FUZZ_BUILD)/%.o

fuzz: deps-fuzz all
	$(Q)$(MAKE) --no-print-directory fuzz-build
	$(Q)sh tests/fuzz/fuzz.sh $(FUZZ_SECONDS) $(FUZZ_TARGETS)

# deps: install what arvo needs, only when something is missing.
DEB_PKGS = build-essential pkg-config libopenexr-dev libimath-dev libopencolorio-dev \
           opencolorio-tools openimageio-tools openexr libpng-dev gnuplot-nox mandoc \
           povray povray-includes povray-examples hyperfine libembree-dev parallel time \
           libfreetype-dev
deps:
	@missing=$$(for p in $(DEB_PKGS); do dpkg-query -W -f='$${Status}\n' $$p 2>/dev/null | \
	   grep -q '^install ok installed' || echo $$p; done); \
	if [ -n "$$missing" ]; then \
	  echo "make deps: installing $$missing"; \
	  SUDO=$$( [ "$$(id -u)" = 0 ] || echo sudo ); \
	  $$SUDO apt-get update -qq && \
	  DEBIAN_FRONTEND=noninteractive $$SUDO apt-get install -y -qq --no-install-recommends $$missing; \
	fi

# deps-fuzz: clang and its libFuzzer runtime, for make fuzz only.
DEB_PKGS_FUZZ = clang libclang-rt-14-dev
deps-fuzz:
	@$(MAKE) --no-print-directory deps DEB_PKGS="$(DEB_PKGS_FUZZ)"

# check also builds an ASan + UBSan arvo for tests/sanitized (a subset: the
# hostile suite, the fuzz replay, small renders), unless all of it is sanitized.
check: deps
	$(Q)$(MAKE) --no-print-directory all unit
	$(Q)$(if $(SANITIZE),:,$(MAKE) --no-print-directory SANITIZE=1 $(BUILD)-san/arvo $(FUZZ_TARGETS:%=$(BUILD)-san/fuzz/replay_%))
	$(Q)MODE=$(MODE) SANITIZE=$(SANITIZE) BUILD=$(BUILD) sh tests/run.sh

# ThreadSanitizer on the threaded passes (tests/sanitized/tsan.sh).
check-tsan: deps
	$(Q)$(MAKE) --no-print-directory SANITIZE=thread build/$(MODE)-tsan/arvo
	$(Q)MODE=$(MODE) sh tests/sanitized/tsan.sh

test: check

demo: deps
	$(Q)$(MAKE) --no-print-directory all
	./arvo -o demo.exr -o demo.png stdlib-scenes/demo.scn

bench: deps all
	sh bench/run.sh

# the README gallery: every demo at its defaults, with its render time
gallery: deps all
	sh docs/gallery/make.sh

# caustic error against time: arvo's light-pass methods and POV-Ray's photons
# on the analytic references A, B, C (bench/results/accuracy.*, docs/accuracy.*)
bench-accuracy: deps all
	sh bench/accuracy/run.sh

# POV-Ray's example scenes through arvo and POV-Ray 3.7 (tests/povray-compat/)
povray-compat: all
	sh tests/povray-compat/compat.sh
povray-corpus: all
	TIMEOUT=40 sh tests/povray-compat/compat.sh --corpus
povray-photons: all
	sh tests/povray-compat/photons.sh

lint:
	mandoc -Tlint -W warning man/arvo.1 man/arvo-scn.5

install: arvo
	install -d $(DESTDIR)$(PREFIX)/bin $(DESTDIR)$(PREFIX)/share/arvo $(DESTDIR)$(PREFIX)/share/man/man1 $(DESTDIR)$(PREFIX)/share/man/man5
	install -m 755 arvo $(DESTDIR)$(PREFIX)/bin/arvo
	cp -R stdlib-scenes/. $(DESTDIR)$(PREFIX)/share/arvo/
	install -m 644 man/arvo.1 $(DESTDIR)$(PREFIX)/share/man/man1/arvo.1
	install -m 644 man/arvo-scn.5 $(DESTDIR)$(PREFIX)/share/man/man5/arvo-scn.5

clean:
	rm -rf build arvo

-include $(shell find build -name '*.d' 2>/dev/null)
