# tests/fuzz/fuzz.mk - fuzz targets of the readers of untrusted bytes (included
# by the Makefile; docs/reliability.md).
#
#  - `make` builds each target as a replay program (tests/fuzz/replay.c) with
#    the project's compiler; `make test` runs it over the seed corpus
#    (tests/fuzz/corpus/NAME) and every past finding (tests/fuzz/regress/NAME).
#  - `make fuzz FUZZ_SECONDS=N` builds the library and the targets with clang,
#    libFuzzer, AddressSanitizer and UndefinedBehaviorSanitizer in build-fuzz/
#    and runs each target N seconds (default 60) on a scratch copy of its
#    corpus, FUZZ_JOBS at a time (default 2); new inputs stay in
#    build-fuzz/corpus/NAME, findings in build-fuzz/findings/NAME.
#    Needs (as root): apt-get install -y clang libclang-rt-14-dev libomp-14-dev
FUZZ_SRC     := $(wildcard tests/fuzz/fuzz_*.c)
FUZZ_NAMES   := $(FUZZ_SRC:tests/fuzz/%.c=%)
FUZZ_REPLAY  := $(FUZZ_NAMES:%=$(BUILD)/fuzz-replay/%)
FUZZ_CC      ?= clang
FUZZ_SECONDS ?= 60
FUZZ_JOBS    ?= 2
FUZZ_SAN     := -fsanitize=address,undefined -fno-sanitize-recover=undefined

all: $(FUZZ_REPLAY)

$(BUILD)/fuzz-replay/%: tests/fuzz/%.c tests/fuzz/replay.c tests/fuzz/fuzz_common.h $(LIB)
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) $(ALL_LDFLAGS) -o $@ $< tests/fuzz/replay.c $(LIB) $(LIBS_ALL)

.PHONY: fuzz fuzz-build
fuzz-build:
	$(MAKE) BUILD=build-fuzz CC=$(FUZZ_CC) WERROR= \
	  OPT="-O1 -g -fno-omit-frame-pointer -fsanitize=fuzzer-no-link $(FUZZ_SAN)" \
	  build-fuzz/libseislide.a
	@mkdir -p build-fuzz/bin
	for n in $(FUZZ_NAMES); do \
	  $(FUZZ_CC) $(WARN) -fopenmp -D_XOPEN_SOURCE=700 -Isrc $(PKG_CFLAGS) -O1 -g \
	    -fsanitize=fuzzer $(FUZZ_SAN) -o build-fuzz/bin/$$n tests/fuzz/$$n.c \
	    build-fuzz/libseislide.a $(LIBS_ALL) || exit 1; done

fuzz: fuzz-build
	sh tests/fuzz/run.sh $(FUZZ_SECONDS) $(FUZZ_JOBS) $(FUZZ_NAMES)
