# seislide - see README.md. Targets: all test bench study install clean asan.
CC      ?= cc
PREFIX  ?= /usr/local
DESTDIR ?=
BUILD   ?= build
OPT     ?= -O2 -g -fno-math-errno -ftree-vectorize
PKGS    := gsl fftw3 xlsxwriter inih zlib
WARN    := -std=c11 -Wall -Wextra -Wpedantic -Wshadow
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

.PHONY: all test bench study install clean asan check-tools
all: $(PROG) $(TEST_BIN)

$(BUILD)/%.o: %.c $(wildcard src/*.h src/*/*.h tests/*.h)
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) -c $< -o $@

$(LIB): $(LIB_OBJ)
	$(AR) rcs $@ $^

$(PROG): $(CLI_OBJ) $(LIB)
	$(CC) $(ALL_LDFLAGS) -o $@ $(CLI_OBJ) $(LIB) $(LIBS_ALL)

$(BUILD)/tests/%: tests/%.c $(LIB) tests/harness.h tests/oracle.h
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) $(ALL_LDFLAGS) -o $@ $< $(LIB) $(LIBS_ALL)

# Every layer, one verdict: "N passed, N failed, N skipped".
test: all
	@SEISLIDE_BIN=$(abspath $(PROG)) SEISLIDE_TESTBIN=$(abspath $(BUILD)/tests) sh tests/run.sh

bench: all
	./$(PROG) bench

# The source study reproduced from ../shared/records (or $$SEISLIDE_SHARED/records):
# docs/validation.md and docs/validation/ (figures need gnuplot: gnuplot-nox).
study: $(PROG)
	./$(PROG) study -o docs

# ASan + UBSan build in its own directory, running the same tests.
asan:
	LSAN_OPTIONS="suppressions=$(abspath tests/lsan.supp):print_suppressions=0" \
	$(MAKE) BUILD=build-asan PROG=build-asan/seislide \
	  OPT="-O1 -g -fno-omit-frame-pointer -fsanitize=address,undefined -fno-sanitize-recover=undefined" \
	  LDFLAGS="-fsanitize=address,undefined" test

install: $(PROG)
	install -d $(DESTDIR)$(PREFIX)/bin $(DESTDIR)$(PREFIX)/lib $(DESTDIR)$(PREFIX)/include/seislide \
	  $(DESTDIR)$(PREFIX)/share/man/man1
	install -m 755 $(PROG) $(DESTDIR)$(PREFIX)/bin/seislide
	install -m 644 $(LIB) $(DESTDIR)$(PREFIX)/lib/libseislide.a
	install -m 644 src/*.h $(DESTDIR)$(PREFIX)/include/seislide/
	install -m 644 docs/seislide.1 $(DESTDIR)$(PREFIX)/share/man/man1/seislide.1

clean:
	rm -rf build build-asan $(PROG)
