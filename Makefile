# seislide - see README.md. Targets: all test bench study install clean asan mutate physfloors.
CC      ?= cc
PREFIX  ?= /usr/local
DESTDIR ?=
BUILD   ?= build
OPT     ?= -O2 -g -fno-math-errno -ftree-vectorize
PKGS    := gsl fftw3 xlsxwriter inih zlib
WARN    := -std=c11 -Wall -Wextra -Wpedantic -Wshadow
# Warnings are errors in CI (CI=true, as GitHub Actions and most CI systems set it),
# so `make test` there fails on any warning; locally: make WERROR=-Werror.
ifeq ($(CI),true)
WERROR  ?= -Werror
endif
PKG_CFLAGS := $(shell pkg-config --cflags $(PKGS))
PKG_LIBS   := $(shell pkg-config --libs $(PKGS))
ALL_CFLAGS  = $(WARN) $(WERROR) -fopenmp -D_XOPEN_SOURCE=700 -Isrc $(PKG_CFLAGS) $(OPT) $(CFLAGS)
ALL_LDFLAGS = -fopenmp $(LDFLAGS)
LIBS_ALL    = $(PKG_LIBS) -lm

LIB_SRC  := $(filter-out src/cli/%,$(wildcard src/*.c src/*/*.c))
CLI_SRC  := $(wildcard src/cli/*.c)
TEST_SRC := $(wildcard tests/test_*.c)
LIB_OBJ  := $(LIB_SRC:%.c=$(BUILD)/%.o)
CLI_OBJ  := $(CLI_SRC:%.c=$(BUILD)/%.o)
TEST_BIN := $(TEST_SRC:tests/%.c=$(BUILD)/tests/%)
LIB      := $(BUILD)/libseislide.a
PROG     ?= seislide
VERSION  := $(shell sed -n 's/^\#define SEISLIDE_VERSION "\(.*\)"/\1/p' src/cli/cli.h)
# The public headers: seislide.h and what it includes (not io/atomic.h, cli.h, engine.h ...).
PUBLIC_H := $(filter src/%.h,$(shell $(CC) -MM -Isrc $(PKG_CFLAGS) src/seislide.h))

.PHONY: all test bench study install clean asan check-tools mutate physfloors
all: $(PROG) $(TEST_BIN)

$(BUILD)/%.o: %.c $(wildcard src/*.h src/*/*.h tests/*.h)
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) -c $< -o $@

$(LIB): $(LIB_OBJ)
	$(AR) rcs $@ $^

$(PROG): $(CLI_OBJ) $(LIB)
	$(CC) $(ALL_LDFLAGS) -o $@ $(CLI_OBJ) $(LIB) $(LIBS_ALL)

$(BUILD)/tests/%: tests/%.c $(LIB) tests/harness.h tests/oracle.h tests/tsv.h
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) $(ALL_LDFLAGS) -o $@ $< $(LIB) $(LIBS_ALL)

# Every layer, one verdict: "N passed, N failed, N skipped"; the suites run in parallel
# (tests/run.sh: SEISLIDE_TEST_JOBS at a time, default 3; each suite's output printed whole).
test: all
	@SEISLIDE_BIN=$(abspath $(PROG)) SEISLIDE_TESTBIN=$(abspath $(BUILD)/tests) \
	  SEISLIDE_MAKEVARS="BUILD=$(BUILD) PROG=$(PROG)" SEISLIDE_LDFLAGS="$(LDFLAGS)" sh tests/run.sh

bench: all
	./$(PROG) bench

# The source study reproduced from ../shared/records (or $$SEISLIDE_SHARED/records):
# docs/validation.md and docs/validation/ (figures need gnuplot: gnuplot-nox).
study: $(PROG)
	./$(PROG) study -o docs

# Synthesized floor sets against physical floor motions from every usable
# three-component record of ../shared/records (docs/synthesis.md 10; minutes).
physfloors: $(BUILD)/tools/physfloors
	nice $(BUILD)/tools/physfloors -x

$(BUILD)/tools/%: tools/%.c $(LIB)
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) $(ALL_LDFLAGS) -o $@ $< $(LIB) $(LIBS_ALL)

# ASan + UBSan build in its own directory, running the same tests.
asan:
	LSAN_OPTIONS="suppressions=$(abspath tests/lsan.supp):print_suppressions=0" \
	$(MAKE) BUILD=build-asan PROG=build-asan/seislide \
	  OPT="-O1 -g -fno-omit-frame-pointer -fsanitize=address,undefined -fno-sanitize-recover=undefined" \
	  LDFLAGS="-fsanitize=address,undefined" test

$(BUILD)/seislide.pc: seislide.pc.in Makefile src/cli/cli.h
	@mkdir -p $(dir $@)
	sed -e 's|@PREFIX@|$(PREFIX)|' -e 's|@VERSION@|$(VERSION)|' $< > $@

# The program, the static library, seislide.h with the public headers it
# includes (under include/seislide/), seislide.pc and the manual page.
# Mutation testing (minutes; not part of test): tests/mutations.txt, one line each,
# applied in 2 scratch copies in parallel, each running only the suites that can see
# the mutated file (tools/mutate.sh); ends with "N mutations, M survived, ...".
mutate:
	sh tools/mutate.sh

install: $(PROG) $(BUILD)/seislide.pc
	install -d $(DESTDIR)$(PREFIX)/bin $(DESTDIR)$(PREFIX)/lib/pkgconfig \
	  $(DESTDIR)$(PREFIX)/share/man/man1
	install -m 755 $(PROG) $(DESTDIR)$(PREFIX)/bin/seislide
	install -m 644 $(LIB) $(DESTDIR)$(PREFIX)/lib/libseislide.a
	for h in $(PUBLIC_H:src/%=%); do \
	  install -D -m 644 src/$$h $(DESTDIR)$(PREFIX)/include/seislide/$$h || exit 1; done
	install -m 644 $(BUILD)/seislide.pc $(DESTDIR)$(PREFIX)/lib/pkgconfig/seislide.pc
	install -m 644 docs/seislide.1 $(DESTDIR)$(PREFIX)/share/man/man1/seislide.1

clean:
	rm -rf build build-asan $(PROG)
