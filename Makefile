# facet - build, test, install.  See README.md.
#
#   make                build every program into $(O)/bin
#   make check          unit and command tests (the README's test command)
#   make sanitize       the whole test suite under ASan+UBSan
#   make regold         rewrite the tests' golden files from this build
#   make fuzz           libFuzzer targets (clang), FUZZ_TIME seconds each
#   make bench          throughput figures beside a reference run
#   make demo           the pipelines on the bundled samples, into out/
#   make gallery        the demo, and the README's pictures in docs/gallery
#   make install        PREFIX=/usr/local DESTDIR=
#   make lint-man       mandoc -Tlint on every page

.DEFAULT_GOAL := all
O ?= build
PREFIX ?= /usr/local
BINDIR = $(PREFIX)/bin
MANDIR = $(PREFIX)/share/man
CC ?= cc
ifeq ($(origin CC),default)
CC = gcc
endif
OPT ?= -O2
CFLAGS ?= $(OPT) -g
BASE_WARN = -std=c11 -Wall -Wextra -Werror -ffp-contract=off
WARN = $(BASE_WARN) $(NO_TRUNC_WARN)
# Messages are cut to their buffer on purpose; gcc's guess that they might be is noise.
NO_TRUNC_WARN := $(shell $(CC) -Werror -Wno-format-truncation -E -x c /dev/null >/dev/null 2>&1 && echo -Wno-format-truncation)
ALL_CPPFLAGS = -D_POSIX_C_SOURCE=200809L -D_DEFAULT_SOURCE -Isrc/lib $(CPPFLAGS)

# Dependencies are checked (and installed, as root on Debian) once, and their
# flags cached; see tools/install-deps.
ifeq ($(filter clean uninstall,$(MAKECMDGOALS)),)
include build/config.mk
endif
build/config.mk: tools/install-deps
	@mkdir -p build
	@tools/install-deps --quiet
	@{ echo "DEP_CFLAGS = $$(pkg-config --cflags libpng libjpeg zlib lapack blas)"; \
	   echo "DEP_LIBS = $$(pkg-config --libs libpng libjpeg zlib lapack blas)"; } > $@.tmp && mv $@.tmp $@

LIB_SRC = $(sort $(wildcard src/lib/*/*.c))
CMD_SRC = $(sort $(wildcard src/cmd/*.c))
TOOL_SRC = $(sort $(wildcard tools/*.c))
UNIT_SRC = $(sort $(wildcard tests/unit/test_*.c))
BENCH_SRC = $(sort $(wildcard bench/*.c))

LIB = $(O)/libfacet.a
LIB_OBJ = $(LIB_SRC:%.c=$(O)/%.o)
PROGS = $(CMD_SRC:src/cmd/%.c=$(O)/bin/%) $(TOOL_SRC:tools/%.c=$(O)/bin/%)
UNITS = $(UNIT_SRC:tests/unit/%.c=$(O)/tests/%)
BENCHES = $(BENCH_SRC:bench/%.c=$(O)/bench/%)
LDLIBS = $(DEP_LIBS) -lm

# Pipeline scripts, installed beside the programs (and copied into $(O)/bin
# so that the tests find them where they find the programs).
SCRIPTS = tools/sunfuse
SCRIPT_BIN = $(SCRIPTS:tools/%=$(O)/bin/%)

all: $(PROGS) $(SCRIPT_BIN)

$(SCRIPT_BIN): $(O)/bin/%: tools/%
	@mkdir -p $(@D)
	cp $< $@

$(O)/%.o: %.c
	@mkdir -p $(@D)
	$(CC) $(WARN) $(CFLAGS) $(ALL_CPPFLAGS) $(DEP_CFLAGS) -MMD -MP -c $< -o $@

$(LIB): $(LIB_OBJ)
	@rm -f $@
	$(AR) rcs $@ $^

$(O)/bin/%: $(O)/src/cmd/%.o $(LIB)
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) $(LDFLAGS) $^ $(LDLIBS) -o $@

$(O)/bin/%: $(O)/tools/%.o $(LIB)
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) $(LDFLAGS) $^ $(LDLIBS) -o $@

$(O)/tests/%: $(O)/tests/unit/%.o $(LIB)
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) $(LDFLAGS) $^ $(LDLIBS) -o $@

$(O)/bench/%: $(O)/bench/%.o $(LIB)
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) $(LDFLAGS) $^ $(LDLIBS) -o $@

check: $(PROGS) $(SCRIPT_BIN) $(UNITS)
	@FCT_BIN=$(O)/bin FCT_UNITS=$(O)/tests sh tests/run

# The golden files the command tests compare against, rewritten from this
# build's output (tests/regold says which changed); review with git diff.
regold: $(PROGS) $(SCRIPT_BIN)
	@FCT_BIN=$(O)/bin sh tests/regold

# ASan+UBSan build of everything, then the whole suite against it.
SAN_FLAGS = -O1 -g -fno-omit-frame-pointer -fsanitize=address,undefined,float-cast-overflow -fno-sanitize-recover=all
sanitize:
	FCT_SANITIZE=1 $(MAKE) O=build/san CFLAGS="$(SAN_FLAGS)" LDFLAGS="$(SAN_FLAGS)" check

FUZZ_TIME ?= 60
FUZZ_SRC = $(sort $(wildcard fuzz/fuzz_*.c))
FUZZ_FLAGS = -g -O1 -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=all
fuzz: build/config.mk
	@command -v clang >/dev/null || { echo "make fuzz: clang is missing (tools/install-deps --fuzz)" >&2; exit 1; }
	$(MAKE) O=build/fuzzlib CC=clang CFLAGS="-g -O1 -fsanitize=fuzzer-no-link,address,undefined" build/fuzzlib/libfacet.a
	@mkdir -p build/fuzz
	@for f in $(FUZZ_SRC); do n=$$(basename $$f .c); \
	  echo "clang $$f -> build/fuzz/$$n"; \
	  clang $(BASE_WARN) $(FUZZ_FLAGS) $(ALL_CPPFLAGS) $(DEP_CFLAGS) $$f build/fuzzlib/libfacet.a $(LDLIBS) -o build/fuzz/$$n || exit 1; done
	FUZZ_TIME=$(FUZZ_TIME) sh fuzz/run $(FUZZ_SRC:fuzz/%.c=build/fuzz/%)

bench: $(PROGS) $(BENCHES)
	@FCT_BIN=$(O)/bin FCT_BENCH=$(O)/bench sh bench/run

# md5 sums of every output on the demo's and the bench's inputs, for a
# change that must not alter any: make fingerprint FP=dir > list.
FP ?= build/fingerprint
fingerprint: $(PROGS) $(SCRIPT_BIN) $(BENCHES)
	@FCT_BIN=$(O)/bin FCT_BENCH=$(O)/bench sh tools/fingerprint $(FP)

demo: $(PROGS) $(SCRIPT_BIN)
	@FCT_BIN=$(O)/bin sh tools/demo

# The README's pictures: the demo, then small contact sheets in docs/gallery.
gallery: $(PROGS) $(SCRIPT_BIN)
	@FCT_BIN=$(O)/bin sh tools/demo --gallery docs/gallery

lint-man:
	@command -v mandoc >/dev/null || { echo "lint-man: mandoc is missing (tools/install-deps)" >&2; exit 1; }
	mandoc -Tlint -Wwarning man/man1/*.1

install: $(PROGS)
	mkdir -p $(DESTDIR)$(BINDIR) $(DESTDIR)$(MANDIR)/man1
	cp $(PROGS) $(SCRIPTS) $(DESTDIR)$(BINDIR)/
	cp man/man1/*.1 $(DESTDIR)$(MANDIR)/man1/

uninstall:
	cd $(DESTDIR)$(BINDIR) && rm -f $(notdir $(PROGS) $(SCRIPTS))
	cd $(DESTDIR)$(MANDIR)/man1 && rm -f $(notdir $(wildcard man/man1/*.1))

clean:
	rm -rf build out

.PHONY: all check regold sanitize fuzz bench demo fingerprint gallery lint-man install uninstall clean
.SECONDARY:
.DELETE_ON_ERROR:

-include $(LIB_OBJ:.o=.d) $(PROGS:$(O)/bin/%=$(O)/src/cmd/%.d) $(PROGS:$(O)/bin/%=$(O)/tools/%.d) \
	$(UNITS:$(O)/tests/%=$(O)/tests/unit/%.d) $(BENCHES:%=%.d)
