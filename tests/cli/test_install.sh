#!/bin/sh
# `make install` into a scratch DESTDIR with a non-standard PREFIX installs
# seislide.h with the public headers it needs (and no internal one) under
# include/seislide/, libseislide.a, libseislide.so (soname libseislide.so.0)
# and seislide.pc. A tiny program with #include <seislide/seislide.h>,
# built with the README's lines (the plain pkg-config line against the
# shared library; the --static line; the archive), computes an ASCE/SEI
# 43-05 estimate on RG 1.60 that it checks by hand. Then the library's
# hygiene: every exported symbol is sl_/SL_, no research code (src/study) in
# it, src/signal includes nothing from src/io, no src/**/*.c over 1,000 lines.
# The interface: installed twice with two PREFIX values, the second's
# seislide.pc names the second (nothing cached from the first); every
# installed header compiles alone as C11 and as C++17 with -Wall -Wextra
# -Werror -pedantic; libseislide.so exports exactly the SL_API functions of
# the installed headers and no data; sl_version() is SEISLIDE_VERSION_STRING
# and seislide.pc's Version; a C++ program links against the library.
. "$(dirname "$0")/lib.sh"
t_suite cli_install
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
D=$T_TMP/dest
P=/opt/seislide
# The install rebuilds nothing in an up-to-date tree; LDFLAGS as the build's
# (make asan), should it link the shared library. A first install with
# another PREFIX (and the default LIBDIR) into another DESTDIR; then the one
# the rest of the test uses, with LIBDIR named.
# shellcheck disable=SC2086
make -s -C "$ROOT" install DESTDIR="$T_TMP/first" PREFIX=/opt/seislide-first $SEISLIDE_MAKEVARS \
  LDFLAGS="$SEISLIDE_LDFLAGS" >"$T_TMP/make.out" 2>&1
[ $? -eq 0 ] && t_pass || t_fail "first make install failed: $(head -c 400 "$T_TMP/make.out")"
grep -qx 'prefix=/opt/seislide-first' "$T_TMP/first/opt/seislide-first/lib/pkgconfig/seislide.pc" &&
  grep -qx 'libdir=/opt/seislide-first/lib' "$T_TMP/first/opt/seislide-first/lib/pkgconfig/seislide.pc" &&
  t_pass || t_fail "first install: seislide.pc does not name /opt/seislide-first and its lib/"
# shellcheck disable=SC2086
make -s -C "$ROOT" install DESTDIR="$D" PREFIX=$P LIBDIR=$P/lib64 $SEISLIDE_MAKEVARS \
  LDFLAGS="$SEISLIDE_LDFLAGS" >"$T_TMP/make.out" 2>&1
[ $? -eq 0 ] && t_pass || t_fail "make install failed: $(head -c 400 "$T_TMP/make.out")"
I=$D$P/include/seislide
L=$D$P/lib64
pc=$L/pkgconfig/seislide.pc
grep -qx "prefix=$P" "$pc" && grep -qx "libdir=$P/lib64" "$pc" && ! grep -q seislide-first "$pc" &&
  t_pass || t_fail "second install: seislide.pc is not the second's: $(grep -E '^(prefix|libdir)=' "$pc" | tr '\n' ' ')"
# The version, declared once (src/core/version.h): the .pc and the program say it.
V=$(sed -n 's/^#define SEISLIDE_VERSION_[A-Z]* \([0-9][0-9]*\)$/\1/p' "$ROOT/src/core/version.h" | paste -sd.)
grep -qx "Version: $V" "$pc" && t_pass || t_fail "seislide.pc: Version is not $V"
# (and the build's source fingerprint: tests/cli/test_build_id.sh)
"$SEISLIDE_BIN" --version | grep -Eqx "seislide $V \(source [0-9a-f]{12}\)" && t_pass ||
  t_fail "seislide --version: '$("$SEISLIDE_BIN" --version)', expected 'seislide $V (source <12 hex digits>)'"
for h in seislide.h core/status.h slide/slide.h method/asce_input.h report/report.h; do
  [ -f "$I/$h" ] && t_pass || t_fail "$h not installed"
done
for h in io/atomic.h cli/cli.h cli.h slide/engine.h study/study.h; do
  [ -e "$I/$h" ] && t_fail "internal header $h installed" || t_pass
done
# Nothing outside include/seislide/ (generic names such as analysis.h never
# land beside the user's own headers).
n=$(find "$D$P/include" -mindepth 1 -maxdepth 1 | wc -l)
[ "$n" -eq 1 ] && t_pass || t_fail "include/ holds $n entries, expected seislide/ only"
# Every installed header includes its siblings as <seislide/...>, each of them
# installed; no quoted include is left.
q=$(grep -rl '^[[:space:]]*#[[:space:]]*include[[:space:]]*"' "$I")
[ -z "$q" ] && t_pass || t_fail "quoted #include left in installed headers: $q"
miss=
for inc in $(grep -rhoE '#[[:space:]]*include[[:space:]]*<seislide/[^>]*>' "$I" |
             sed -E 's/.*<seislide\/([^>]*)>.*/\1/' | sort -u); do
  [ -f "$I/$inc" ] || miss="$miss $inc"
done
[ -z "$miss" ] && t_pass || t_fail "included but not installed:$miss"
[ -f "$L/libseislide.a" ] && t_pass || t_fail "libseislide.a not installed"
[ -L "$L/libseislide.so" ] && [ -L "$L/libseislide.so.0" ] && [ -f "$L/libseislide.so" ] &&
  t_pass || t_fail "libseislide.so -> libseislide.so.0 -> the library: links missing"
if command -v readelf >/dev/null 2>&1; then
  readelf -d "$L/libseislide.so" | grep -q 'SONAME.*\[libseislide\.so\.0\]' && t_pass ||
    t_fail "libseislide.so: soname is not libseislide.so.0"
fi
[ -f "$L/pkgconfig/seislide.pc" ] && t_pass || t_fail "seislide.pc not installed"

# ---- the link lines of the README ("Build"), against the installed tree --
if ! command -v pkg-config >/dev/null 2>&1; then
  t_skip "pkg-config not found: the compile tests are not run"
else
  # As a user of a non-standard prefix: PKG_CONFIG_PATH to find seislide.pc,
  # LD_LIBRARY_PATH to run against libseislide.so; the sysroot stands for
  # DESTDIR (pkg-config prefixes the -I and -L it prints with it).
  export PKG_CONFIG_PATH="$L/pkgconfig" PKG_CONFIG_SYSROOT_DIR="$D"
  grep -q "^Requires.private: gsl fftw3 xlsxwriter inih" "$L/pkgconfig/seislide.pc" && t_pass ||
    t_fail "seislide.pc: Requires.private"
  cf=$(pkg-config --cflags seislide)
  case " $cf " in
  *" -I$D$P/include "*) t_pass ;;
  *) t_fail "pkg-config --cflags seislide: '$cf' lacks -I$D$P/include" ;;
  esac
  case "$cf" in
  *include/seislide*) t_fail "pkg-config --cflags seislide puts include/seislide itself on the path: '$cf'" ;;
  *) t_pass ;;
  esac
  CC=${CC:-cc}
  # A generic name must not resolve with seislide's flags.
  printf '#include <analysis.h>\nint main(void) { return 0; }\n' >"$T_TMP/generic.c"
  # shellcheck disable=SC2046
  $CC -fsyntax-only $(pkg-config --cflags seislide) "$T_TMP/generic.c" >/dev/null 2>&1 &&
    t_fail "#include <analysis.h> resolves with pkg-config --cflags seislide" || t_pass
  cat >"$T_TMP/prog.c" <<'PROG'
/* mu = 0.1 on RG 1.60 at 0.3 g: mu_e = mu (1 - 0.4 x 0.3) = 0.088,
 * c_s = 2 mu_e g = 0.176 g; 2 x the best estimate exceeds the cap
 * 1.5 x 1.4 x 36 in x 0.3 = 0.576072 m: flag capped (1), design = cap. */
#include <seislide/seislide.h>
#include <stdio.h>
#include <string.h>
int main(void)
{
    sl_asce_source src;
    sl_error err;
    sl_error_clear(&err);
    if (sl_asce_input_from_rg160(0.3, &src, &err)) {
        fprintf(stderr, "%s\n", err.msg);
        return 1;
    }
    sl_asce *a = sl_asce_alloc(&src.in, &err);
    sl_asce_result r;
    int bad = !a || sl_asce_eval(a, 0.1, &r, &err) != SL_OK;
    if (!bad)
        printf("%.6f %.6f %u %.6f %s %d\n", r.mu_e, r.cs_ms2 / SL_G, r.flags, r.delta_design_m,
               sl_version(), strcmp(sl_version(), SEISLIDE_VERSION_STRING) == 0);
    sl_asce_free(a);
    sl_asce_source_free(&src);
    return bad;
}
PROG
  want="0.088000 0.176000 1 0.576072 $V 1"
  cd "$T_TMP" || exit 2
  # 1. the plain line: the shared library
  # shellcheck disable=SC2046,SC2086
  $CC prog.c $(pkg-config --cflags --libs seislide) $SEISLIDE_LDFLAGS -o prog >cc.out 2>&1
  [ $? -eq 0 ] && t_pass || t_fail "plain pkg-config line: $(head -c 600 cc.out)"
  if [ -x prog ]; then
    out=$(LD_LIBRARY_PATH="$L${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}" ./prog)
    [ "$out" = "$want" ] && t_pass || t_fail "plain line: program printed '$out'"
    if command -v readelf >/dev/null 2>&1; then
      readelf -d prog | grep -q 'NEEDED.*\[libseislide\.so\.0\]' && t_pass ||
        t_fail "plain line: the program does not use libseislide.so.0"
    fi
  fi
  # 2. the --static line (-lseislide takes the shared library where both are
  #    installed; the private dependencies are listed as well)
  # shellcheck disable=SC2046,SC2086
  $CC prog.c $(pkg-config --cflags seislide) $(pkg-config --static --libs seislide) \
    $SEISLIDE_LDFLAGS -o prog_s >cc.out 2>&1
  [ $? -eq 0 ] && t_pass || t_fail "--static pkg-config line: $(head -c 600 cc.out)"
  if [ -x prog_s ]; then
    out=$(LD_LIBRARY_PATH="$L${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}" ./prog_s)
    [ "$out" = "$want" ] && t_pass || t_fail "--static line: program printed '$out'"
  fi
  # 3. the archive: -l:libseislide.a in place of -lseislide, with the
  #    --static dependencies; the program runs without libseislide.so
  # shellcheck disable=SC2046,SC2086
  $CC prog.c $(pkg-config --cflags seislide) \
    $(pkg-config --static --libs seislide | sed 's/-lseislide /-l:libseislide.a /') \
    $SEISLIDE_LDFLAGS -o prog_a >cc.out 2>&1
  [ $? -eq 0 ] && t_pass || t_fail "archive line: $(head -c 600 cc.out)"
  if [ -x prog_a ]; then
    out=$(env -u LD_LIBRARY_PATH ./prog_a)
    [ "$out" = "$want" ] && t_pass || t_fail "archive line: program printed '$out'"
    if command -v readelf >/dev/null 2>&1; then
      readelf -d prog_a | grep -q 'NEEDED.*libseislide' &&
        t_fail "archive line: the program still needs libseislide.so" || t_pass
    fi
  fi
  # 4. the same program as C++17 (SL_API gives the declarations C linkage)
  if command -v "${CXX:-g++}" >/dev/null 2>&1; then
    # shellcheck disable=SC2046,SC2086
    ${CXX:-g++} -std=c++17 -x c++ prog.c -x none $(pkg-config --cflags --libs seislide) $SEISLIDE_LDFLAGS \
      -o prog_cxx >cc.out 2>&1
    [ $? -eq 0 ] && t_pass || t_fail "C++ program: $(head -c 600 cc.out)"
    if [ -x prog_cxx ]; then
      out=$(LD_LIBRARY_PATH="$L${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}" ./prog_cxx)
      [ "$out" = "$want" ] && t_pass || t_fail "C++ program printed '$out'"
    fi
  else
    t_skip "no C++ compiler: the C++ program is not built"
  fi
  # Every installed header alone, as C11 and as C++17, warning-free under
  # -Wall -Wextra -Werror -pedantic (seislide.h includes all the others).
  bad=
  for h in $(cd "$D$P/include" && find seislide -name '*.h' | sort); do
    printf '#include <%s>\nint sl_header_test;\n' "$h" >hdr.c
    # shellcheck disable=SC2046
    $CC -std=c11 -Wall -Wextra -Werror -pedantic -fsyntax-only $(pkg-config --cflags seislide) \
      hdr.c >cc.out 2>&1 || bad="$bad $h(C11: $(head -c 200 cc.out))"
    if command -v "${CXX:-g++}" >/dev/null 2>&1; then
      # shellcheck disable=SC2046
      ${CXX:-g++} -std=c++17 -x c++ -Wall -Wextra -Werror -pedantic -fsyntax-only \
        $(pkg-config --cflags seislide) hdr.c >cc.out 2>&1 || bad="$bad $h(C++17: $(head -c 200 cc.out))"
    fi
  done
  [ -z "$bad" ] && t_pass || t_fail "headers not clean:$bad"
  cd "$ROOT" || exit 2
fi

# ---- the library's hygiene ------------------------------------------------
if command -v nm >/dev/null 2>&1; then
  # Every global symbol defined by the library starts with sl_ or SL_ (an
  # OpenMP named critical section, `omp critical(sl_x)`, is the compiler's
  # common symbol .gomp_critical_user_sl_x, and AddressSanitizer marks a
  # global sl_x or SL_X with __odr_asan.sl_x: our names behind their prefixes).
  bad=$(nm -g --defined-only "$L/libseislide.a" 2>/dev/null |
        awk 'NF == 3 && $3 !~ /^(sl_|SL_|\.gomp_critical_user_sl_|__odr_asan[._](sl_|SL_))/ { print $3 }' |
        sort -u)
  [ -z "$bad" ] && t_pass || t_fail "libseislide.a exports names without sl_/SL_: $(echo $bad | head -c 400)"
  bad=$(nm -D --defined-only "$L/libseislide.so" 2>/dev/null |
        awk 'NF == 3 && $3 !~ /^(sl_|SL_)/ { print $3 }' | sort -u)
  [ -z "$bad" ] && t_pass || t_fail "libseislide.so exports names without sl_/SL_: $(echo $bad | head -c 400)"
  n=$(nm -D --defined-only "$L/libseislide.so" 2>/dev/null | grep -c ' T sl_')
  [ "$n" -gt 50 ] && t_pass || t_fail "libseislide.so exports only $n sl_ functions"
  # Exported = declared: the names libseislide.so defines are the SL_API
  # declarations of the installed headers, both ways; and every sl_
  # function declared at file scope in them carries SL_API.
  nm -D --defined-only "$L/libseislide.so" | awk 'NF == 3 { print $3 }' | sort -u >"$T_TMP/exported"
  grep -rh '^SL_API' "$I" | sed -E 's/^[^([]*[^a-z0-9_](sl_[a-z0-9_]+) *[([].*/\1/' |
    sort -u >"$T_TMP/declared"
  only=$(comm -23 "$T_TMP/exported" "$T_TMP/declared" | tr '\n' ' ')
  [ -z "$only" ] && t_pass || t_fail "exported but declared in no installed header with SL_API: $only"
  only=$(comm -13 "$T_TMP/exported" "$T_TMP/declared" | tr '\n' ' ')
  [ -z "$only" ] && t_pass || t_fail "declared SL_API but not exported: $only"
  [ "$(wc -l <"$T_TMP/declared")" -gt 100 ] && t_pass ||
    t_fail "only $(wc -l <"$T_TMP/declared") SL_API declarations found"
  bare=$(grep -rnE '^[a-z][a-z0-9_ *]*[ *]sl_[a-z0-9_]+ *\(' "$I" | grep -vE ':(typedef|struct|enum|static) ' |
         sed "s|$I/||" | head -5)
  [ -z "$bare" ] && t_pass || t_fail "function declared without SL_API: $bare"
  # No data exported, writable or not (only functions: type T).
  data=$(nm -D --defined-only "$L/libseislide.so" | awk 'NF == 3 && $2 != "T" { print $2, $3 }' | tr '\n' ' ')
  [ -z "$data" ] && t_pass || t_fail "libseislide.so exports data: $data"
  # The research code (src/study: the study, the bench, physical floors) is
  # not in the public library.
  bad=$(nm -g --defined-only "$L/libseislide.a" "$L/libseislide.so" 2>/dev/null |
        awk 'NF == 3 && $3 ~ /^sl_(study|bench|pf|building)_/ { print $3 }' | sort -u)
  [ -z "$bad" ] && t_pass || t_fail "research code in the library: $(echo $bad | head -c 400)"
else
  t_skip "nm not found: exported symbols not checked"
fi
# The layers: src/signal includes nothing from src/io.
bad=$(grep -lE '^[[:space:]]*#[[:space:]]*include[[:space:]]*"io/' "$ROOT"/src/signal/*.[ch])
[ -z "$bad" ] && t_pass || t_fail "src/signal includes from src/io: $(echo $bad | sed "s|$ROOT/||g")"
# One concern per file: no src/**/*.c over 1,000 lines (each one named).
big=$(find "$ROOT/src" -name '*.c' -exec wc -l {} + |
      awk '$2 != "total" && $1 > 1000 { sub(".*/src/", "src/", $2); printf " %s (%d lines)", $2, $1 }')
[ -z "$big" ] && t_pass || t_fail "over 1,000 lines:$big"
# Functions a reader can hold: none over 120 lines in src/cli or
# src/analysis.c (from its first line at column 0 to its closing brace), and
# no src/cli/cmd_*.c over 250 lines.
long=$(for f in "$ROOT"/src/cli/*.c "$ROOT"/src/analysis.c; do
         awk '/^[A-Za-z_].*\(/ && !/;[[:space:]]*$/ && !/^(typedef|struct|enum|static const)/ { s = FNR; h = $0 }
              /^}/ && s { if (FNR - s + 1 > 120) printf " %s:%d (%d lines)", FILENAME, s, FNR - s + 1; s = 0 }' "$f"
       done | sed "s|$ROOT/||g")
[ -z "$long" ] && t_pass || t_fail "functions over 120 lines:$long"
long=$(for f in "$ROOT"/src/cli/cmd_*.c; do
         n=$(wc -l <"$f"); [ "$n" -gt 250 ] && printf ' %s (%d lines)' "${f#"$ROOT"/}" "$n"
       done)
[ -z "$long" ] && t_pass || t_fail "command files over 250 lines:$long"
# The installed program verifies itself (docs/verification.md): from an
# empty folder outside the source tree, without the records
# (SEISLIDE_SHARED unset), every problem passes and the record is written.
mkdir -p "$T_TMP/empty" && cd "$T_TMP/empty" || exit 2
env -u SEISLIDE_SHARED "$D$P/bin/seislide" verify -o rec --checked-by "make test" \
  >"$T_TMP/verify.out" 2>"$T_TMP/verify.err"
rc=$?
# Y07, the release bits, fails by design on a machine whose compiler, FFTW or
# CPU path differs from the release's (docs/verification.md 5): a skip there.
if grep -q '^FAIL synth *Y07 ' "$T_TMP/verify.out" && [ "$(grep -c '^FAIL' "$T_TMP/verify.out")" -eq 1 ]; then
  t_skip "installed verify: Y07 (the release bits) differs on this machine; every other problem passed"
else
  [ $rc -eq 0 ] && t_pass || t_fail "installed verify: exit $rc ($(grep -m3 FAIL "$T_TMP/verify.out"))"
  grep -Eq '^[0-9]+ passed, 0 failed$' "$T_TMP/verify.out" && ! grep -q '^FAIL' "$T_TMP/verify.out" &&
    t_pass || t_fail "installed verify: $(tail -1 "$T_TMP/verify.out")"
fi
[ -s rec/verification.csv ] && [ -s rec/verification.xlsx ] && t_pass ||
  t_fail "installed verify: the record is missing ($(ls rec 2>&1))"
# the record names the explanations where make install put them (issue 42)
for f in verification.md run.md components.md README.md validation/fig1_rinaldi_228.svg; do
  [ -s "$D$P/share/doc/seislide/$f" ] && t_pass || t_fail "make install did not install share/doc/seislide/$f"
done
grep -q "^# explanations: $D$P/share/doc/seislide/verification.md" rec/verification.csv && t_pass ||
  t_fail "installed verify: the record does not name the installed docs: $(grep '^# explanations' rec/verification.csv)"
cd "$ROOT" || exit 2
t_end
