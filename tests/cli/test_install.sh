#!/bin/sh
# `make install` into a scratch DESTDIR installs seislide.h with the public
# headers it needs (and no internal one), libseislide.a and seislide.pc; a
# tiny program built with pkg-config against the installed tree computes
# an ASCE/SEI 43-05 estimate on RG 1.60 that it checks by hand.
. "$(dirname "$0")/lib.sh"
t_suite cli_install
D=$T_TMP/dest
P=/usr/local
# shellcheck disable=SC2086
make -s install DESTDIR="$D" PREFIX=$P $SEISLIDE_MAKEVARS >"$T_TMP/make.out" 2>&1
[ $? -eq 0 ] && t_pass || t_fail "make install failed: $(head -c 400 "$T_TMP/make.out")"
I=$D$P/include/seislide
for h in seislide.h io/motion.h slide/slide.h method/asce_input.h report/report.h; do
  [ -f "$I/$h" ] && t_pass || t_fail "$h not installed"
done
for h in io/atomic.h cli/cli.h cli.h slide/engine.h study/study.h; do
  [ -e "$I/$h" ] && t_fail "internal header $h installed" || t_pass
done
[ -f "$D$P/lib/libseislide.a" ] && t_pass || t_fail "libseislide.a not installed"
[ -f "$D$P/lib/pkgconfig/seislide.pc" ] && t_pass || t_fail "seislide.pc not installed"
if ! command -v pkg-config >/dev/null 2>&1; then
  t_skip "pkg-config not found: the compile test is not run"; t_end; exit $?
fi
export PKG_CONFIG_PATH="$D$P/lib/pkgconfig" PKG_CONFIG_SYSROOT_DIR="$D"
grep -q "^Requires.private: gsl fftw3 xlsxwriter inih" "$D$P/lib/pkgconfig/seislide.pc" && t_pass ||
  t_fail "seislide.pc: Requires.private"
cat >"$T_TMP/prog.c" <<'PROG'
/* mu = 0.1 on RG 1.60 at 0.3 g: mu_e = mu (1 - 0.4 x 0.3) = 0.088,
 * c_s = 2 mu_e g = 0.176 g; 2 x the best estimate exceeds the cap
 * 1.5 x 1.4 x 36 in x 0.3 = 0.576072 m: flag capped (1), design = cap. */
#include <seislide.h>
#include <stdio.h>
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
        printf("%.6f %.6f %u %.6f\n", r.mu_e, r.cs_ms2 / SL_G, r.flags, r.delta_design_m);
    sl_asce_free(a);
    sl_asce_source_free(&src);
    return bad;
}
PROG
CC=${CC:-cc}
# shellcheck disable=SC2046,SC2086
$CC $(pkg-config --cflags seislide) -o "$T_TMP/prog" "$T_TMP/prog.c" \
  $(pkg-config --static --libs seislide) $SEISLIDE_LDFLAGS >"$T_TMP/cc.out" 2>&1
[ $? -eq 0 ] && t_pass || t_fail "compile against the installed tree: $(head -c 600 "$T_TMP/cc.out")"
if [ -x "$T_TMP/prog" ]; then
  out=$("$T_TMP/prog")
  [ "$out" = "0.088000 0.176000 1 0.576072" ] && t_pass || t_fail "program printed '$out'"
fi
t_end
