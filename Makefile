# seislide - see README.md. Targets: all test bench bench-plant study install clean asan mutate
# physfloors tailfloors rockfloors plausfloors zpafloors source-id.
CC      ?= cc
PREFIX  ?= /usr/local
LIBDIR  ?= $(PREFIX)/lib
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
# IEEE operations as written, no fused multiply-add: the same bits from gcc and clang on any
# CPU (gcc implies it with -std=c11, clang does not; docs/synthesis.md 3.7)
FP      := -ffp-contract=off
ALL_CFLAGS  = $(WARN) $(FP) $(WERROR) -fopenmp -D_XOPEN_SOURCE=700 -Isrc $(PKG_CFLAGS) $(OPT) $(CFLAGS)
ALL_LDFLAGS = -fopenmp $(LDFLAGS)
# FFTW's planner made thread-safe by the library (core/fftw.c) is in
# libfftw3_threads (Debian's libfftw3-dev; it has no .pc of its own).
LIBS_ALL    = -lfftw3_threads $(PKG_LIBS) -lm

# libseislide is the numerical core (every src/ module but the command line
# and the study); src/study (the source study, the bench, physical floors)
# is research code in its own archive, linked by the program and the tools.
LIB_SRC   := $(filter-out src/cli/% src/study/%,$(wildcard src/*.c src/*/*.c))
STUDY_SRC := $(wildcard src/study/*.c)
CLI_SRC   := $(wildcard src/cli/*.c)
TEST_SRC  := $(wildcard tests/test_*.c)
LIB_OBJ   := $(LIB_SRC:%.c=$(BUILD)/%.o)
STUDY_OBJ := $(STUDY_SRC:%.c=$(BUILD)/%.o)
CLI_OBJ   := $(CLI_SRC:%.c=$(BUILD)/%.o)
TEST_BIN  := $(TEST_SRC:tests/%.c=$(BUILD)/tests/%)
LIB       := $(BUILD)/libseislide.a
STUDY_LIB := $(BUILD)/libseislide-study.a
PROG      ?= seislide
# The version, declared once in src/core/version.h (MAJOR, MINOR, PATCH in that order).
VERSION   := $(shell sed -n 's/^\#define SEISLIDE_VERSION_[A-Z]* \([0-9][0-9]*\)$$/\1/p' src/core/version.h | paste -sd.)
# The build's source fingerprint (docs/reliability.md, "Which code made a number"): the
# SHA-256 of the list of SHA-256 sums of this Makefile and of every file under src/ (by
# name and content), so a tarball gives the same as a checkout. Compiled into the library
# (src/core/version.h: sl_source_id, sl_build_id) from $(BUILD)/source_id.h, rewritten only
# when it changes; it is in every cache key (plant/entry.h) and every program line.
ID_FILES  := Makefile $(sort $(wildcard src/*.[ch] src/*/*.[ch]))
SOURCE_ID := $(shell sha256sum $(ID_FILES) | sha256sum | cut -c1-64)
# The shared library: libseislide.so.VERSION, soname libseislide.so.SO_MAJOR
# (raised when the interface changes incompatibly). Its objects are the static
# library's, compiled position-independent (PIC; docs/dependencies.md has the
# measured cost).
SO_MAJOR  := 0
SONAME    := libseislide.so.$(SO_MAJOR)
SHLIB     := $(BUILD)/libseislide.so.$(VERSION)
PIC       ?= -fPIC
# Tests whose source includes a study header also link the study archive.
STUDY_TESTS := $(patsubst tests/%.c,$(BUILD)/tests/%,$(shell grep -l '^\#include "study/' $(TEST_SRC)))
# The public headers: seislide.h and what it includes (not io/atomic.h, cli.h, engine.h ...),
# found by the compiler, so a header added to or moved under seislide.h follows.
PUBLIC_H  := $(filter src/%.h,$(shell $(CC) -MM -Isrc $(PKG_CFLAGS) src/seislide.h))

.PHONY: all test bench study install clean asan check-tools mutate physfloors tailfloors bench-plant \
  plausfloors zpafloors rockfloors source-id FORCE
all: $(PROG) $(SHLIB) $(TEST_BIN)

# The fingerprint (above), for tests and release notes.
source-id:
	@echo $(SOURCE_ID)

$(BUILD)/source_id.h: FORCE
	@mkdir -p $(dir $@)
	@test -n "$(SOURCE_ID)" || { echo "cannot compute the source fingerprint (sha256sum)" >&2; exit 1; }
	@printf '#define SL_SOURCE_ID "%s"\n#define SL_SOURCE_ID_SHORT "%s"\n' \
	  $(SOURCE_ID) $(shell echo $(SOURCE_ID) | cut -c1-12) > $@.new
	@if cmp -s $@.new $@; then rm -f $@.new; else mv -f $@.new $@; fi

# (the library's objects are rebuilt when the Makefile changes: a tree
# built before they were PIC would not link the shared library)
# Hidden by default: the shared library exports the functions whose
# declaration in an installed header carries SL_API (src/core/api.h), no other.
$(LIB_OBJ): OBJ_CFLAGS := $(PIC) -fvisibility=hidden
$(LIB_OBJ): Makefile
# (the version's object includes the fingerprint, above)
$(BUILD)/src/core/version.o: $(BUILD)/source_id.h
$(BUILD)/src/core/version.o: OBJ_CFLAGS += -I$(BUILD)
$(BUILD)/%.o: %.c $(wildcard src/*.h src/*/*.h tests/*.h)
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) $(OBJ_CFLAGS) -c $< -o $@

# `seislide verify` records the flags it was built with (docs/verification.md)
$(BUILD)/src/cli/cmd_verify.o: OBJ_CFLAGS = -DSL_BUILD_FLAGS='"$(strip $(FP) $(OPT) $(CFLAGS))"'
$(BUILD)/src/cli/cmd_verify.o: Makefile

$(LIB): $(LIB_OBJ)
	rm -f $@
	$(AR) rcs $@ $^

$(STUDY_LIB): $(STUDY_OBJ)
	rm -f $@
	$(AR) rcs $@ $^

# exports only sl_* and SL_* (the version script); every dependency is linked
# in (--no-undefined), so a program needs -lseislide alone
$(SHLIB): $(LIB_OBJ)
	@printf '{ global: sl_*; SL_*; local: *; };\n' > $(BUILD)/libseislide.map
	$(CC) -shared -Wl,-soname,$(SONAME) -Wl,--no-undefined \
	  -Wl,--version-script=$(BUILD)/libseislide.map $(ALL_LDFLAGS) -o $@ $^ $(LIBS_ALL)

$(PROG): $(CLI_OBJ) $(STUDY_LIB) $(LIB)
	$(CC) $(ALL_LDFLAGS) -o $@ $(CLI_OBJ) $(STUDY_LIB) $(LIB) $(LIBS_ALL)

$(STUDY_TESTS): TEST_LIBS := $(STUDY_LIB)
$(BUILD)/tests/%: tests/%.c $(STUDY_LIB) $(LIB) tests/harness.h tests/oracle.h tests/tsv.h tests/fsfault.h
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) $(ALL_LDFLAGS) -o $@ $< $(TEST_LIBS) $(LIB) $(LIBS_ALL)

# Every layer, one verdict: "N passed, N failed, N skipped"; the suites run in parallel
# (tests/run.sh: SEISLIDE_TEST_JOBS at a time, default 3; each suite's output printed whole).
test: all
	@SEISLIDE_BIN=$(abspath $(PROG)) SEISLIDE_TESTBIN=$(abspath $(BUILD)/tests) \
	  SEISLIDE_MAKEVARS="BUILD=$(BUILD) PROG=$(PROG)" SEISLIDE_LDFLAGS="$(LDFLAGS)" sh tests/run.sh

bench: all
	./$(PROG) bench

# A plant of BENCH_PLANT_FLOORS floors (default 12) from a building model, run at
# 1 and 2 threads and as 2 shards (GNU parallel); docs/plant.md, "Speed: make bench-plant".
bench-plant: $(PROG) $(BUILD)/tools/benchplant
	bash tools/bench-plant.sh ./$(PROG) $(BUILD)/tools/benchplant

# The source study reproduced from ../shared/records (or $$SEISLIDE_SHARED/records):
# docs/validation.md and docs/validation/ (figures need gnuplot: gnuplot-nox).
study: $(PROG)
	./$(PROG) study -o docs

# Synthesized floor sets against physical floor motions from every usable
# three-component record of ../shared/records (docs/synthesis.md 10; minutes).
physfloors: $(BUILD)/tools/physfloors
	nice $(BUILD)/tools/physfloors -x

# Rocking (probability of tipping) on synthesized floor sets against the physical
# floor motions behind their spectra, the six buildings (docs/rocking.md), into
# docs/validation/rocking_floors.md, which `seislide study` carries into
# docs/validation.md (section 7); 17 min on 2 cores (measured with other work running).
ROCKFLOORS_MD := docs/validation/rocking_floors.md
rockfloors: $(BUILD)/tools/rockfloors
	nice $(BUILD)/tools/rockfloors -b asfxyz > $(ROCKFLOORS_MD).new || { rm -f $(ROCKFLOORS_MD).new; exit 1; }
	mv -f $(ROCKFLOORS_MD).new $(ROCKFLOORS_MD)

# The intensity tail near the sliding threshold on buildings of other periods and
# dampings (docs/synthesis.md 11; the default buildings: the
# 5 % building, a stiff 3 % and a soft 2 % one; minutes): every table on stdout, the
# summary into docs/validation/tail_floors.md, which `seislide study` carries into
# docs/validation.md (section 8).
TAILFLOORS_MD := docs/validation/tail_floors.md
tailfloors: $(BUILD)/tools/tailfloors
	nice $(BUILD)/tools/tailfloors -s 48 -m $(TAILFLOORS_MD).new || { rm -f $(TAILFLOORS_MD).new; exit 1; }
	mv -f $(TAILFLOORS_MD).new $(TAILFLOORS_MD)

# The worst ratios of physical floor spectra behind the plausibility rules of floor
# files (docs/formats-floor.md, "Plausibility"; minutes).
plausfloors: $(BUILD)/tools/plausfloors
	nice $(BUILD)/tools/plausfloors floors templates/floor.ini templates/floor.csv tests/data/floors/sharp-8.ini

# How far apart the ZPAs of one building's floors lie on physical floors: the bounds of
# the check of a building's floors against each other (docs/formats-floor.md, "Floors of
# one building"; seconds).
zpafloors: $(BUILD)/tools/zpafloors
	nice $(BUILD)/tools/zpafloors

$(BUILD)/tools/%: tools/%.c $(STUDY_LIB) $(LIB)
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) $(ALL_LDFLAGS) -o $@ $< $(STUDY_LIB) $(LIB) $(LIBS_ALL)

# ASan + UBSan build in its own directory, running the same tests.
asan:
	LSAN_OPTIONS="suppressions=$(abspath tests/lsan.supp):print_suppressions=0" \
	$(MAKE) BUILD=build-asan PROG=build-asan/seislide \
	  OPT="-O1 -g -fno-omit-frame-pointer -fsanitize=address,undefined -fno-sanitize-recover=undefined" \
	  LDFLAGS="-fsanitize=address,undefined" test

# Mutation testing (minutes; not part of test): tests/mutations.txt, one line each,
# applied in 2 scratch copies in parallel, each running only the suites that can see
# the mutated file (tools/mutate.sh); ends with "N mutations, M survived, ...".
mutate:
	sh tools/mutate.sh

# The program; the static and the shared library (with the soname and the
# development links); seislide.h and the public headers it includes under
# include/seislide/, their quoted includes ("core/status.h") rewritten to
# <seislide/core/status.h> so that Cflags -I$${includedir} finds them and no
# generic name (analysis.h, core/status.h) lands on a user's include path;
# seislide.pc, written here from this install's PREFIX and LIBDIR (nothing
# cached: a second install with another PREFIX writes its own), the
# manual page, and the documentation under share/doc/seislide (README.md,
# docs/*.md and the figures of docs/validation/: the manuals a record such as
# `seislide verify`'s verification.csv refers to, by that installed path).
install: $(PROG) $(LIB) $(SHLIB)
	install -d $(DESTDIR)$(PREFIX)/bin $(DESTDIR)$(LIBDIR)/pkgconfig \
	  $(DESTDIR)$(PREFIX)/share/man/man1 $(DESTDIR)$(PREFIX)/include/seislide
	install -m 755 $(PROG) $(DESTDIR)$(PREFIX)/bin/seislide
	install -m 644 $(LIB) $(DESTDIR)$(LIBDIR)/libseislide.a
	install -m 755 $(SHLIB) $(DESTDIR)$(LIBDIR)/$(notdir $(SHLIB))
	ln -sf $(notdir $(SHLIB)) $(DESTDIR)$(LIBDIR)/$(SONAME)
	ln -sf $(SONAME) $(DESTDIR)$(LIBDIR)/libseislide.so
	for h in $(PUBLIC_H:src/%=%); do \
	  install -d $(DESTDIR)$(PREFIX)/include/seislide/$$(dirname $$h) && \
	  sed 's|^\([[:space:]]*#[[:space:]]*include[[:space:]]*\)"\([^"]*\)"|\1<seislide/\2>|' \
	    src/$$h > $(DESTDIR)$(PREFIX)/include/seislide/$$h && \
	  chmod 644 $(DESTDIR)$(PREFIX)/include/seislide/$$h || exit 1; done
	sed -e 's|@PREFIX@|$(PREFIX)|' -e 's|@LIBDIR@|$(LIBDIR)|' -e 's|@VERSION@|$(VERSION)|' \
	  seislide.pc.in > $(DESTDIR)$(LIBDIR)/pkgconfig/seislide.pc
	chmod 644 $(DESTDIR)$(LIBDIR)/pkgconfig/seislide.pc
	install -m 644 docs/seislide.1 $(DESTDIR)$(PREFIX)/share/man/man1/seislide.1
	install -d $(DESTDIR)$(PREFIX)/share/doc/seislide/validation
	install -m 644 README.md docs/*.md $(DESTDIR)$(PREFIX)/share/doc/seislide/
	install -m 644 docs/validation/*.svg $(DESTDIR)$(PREFIX)/share/doc/seislide/validation/

clean:
	rm -rf build build-asan build-clang $(PROG)
include tests/fuzz/fuzz.mk
