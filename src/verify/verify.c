/* verify.c - the checker, the runner and the table of verification
 * problems (verify.h; the problems themselves in verify_*.c, their
 * references in docs/verification.md). */
#include "verify/verify.h"

#include <inttypes.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "core/clock.h"
#include "verify/verify_problems.h"

/* Each problem: area, id, what it checks (unit), reference source,
 * tolerance basis, quick subset, function. The texts are the record's; the
 * hand calculations behind them are in docs/verification.md. */
static const sl_verify_problem problems[] = {
    /* ---- the engine ---------------------------------------------------- */
    {"engine", "E01", "1-D peak sliding under a sampled rectangular pulse, m",
     "closed form: U = D(t_m) + V (T - t_m) - mu g T^2/2, T = V/(mu g) (integral of the "
     "piecewise-linear input)",
     "1e-12 relative: the 1-D kernel is exact for piecewise-linear input (rounding only)", 1,
     sl_verify_e01_pulse},
    {"engine", "E02", "1-D peak sliding under a rectangular pulse against Newmark's formula, m",
     "Newmark (1965): U = V^2/(2 mu g) (1 - mu g/A), V = A t0",
     "2 dt/t0 relative: the sampled pulse ends with a ramp of one dt, which changes U by O(dt/t0)",
     0, sl_verify_e02_newmark},
    {"engine", "E03", "1-D peak sliding under a half-sine pulse, mu 0.2, m",
     "closed form: onset asin(mu g/A), U = int w dt + w(T)^2/(2 mu g) (docs/verification.md)",
     "1e-5 relative: the sine sampled at T/1000 read as piecewise linear differs by "
     "O((pi/1000)^2)", 1, sl_verify_e03_half_sine},
    {"engine", "E04", "1-D peak sliding under a half-sine pulse, mu 0.05, m",
     "closed form, as E03", "1e-5 relative, as E03", 0, sl_verify_e04_half_sine},
    {"engine", "E05", "one-way sliding (up_ratio infinite) under pulses +A, -A, +A: peak, m",
     "closed form: twice the slide of one ramped pulse (the -A pulse moves nothing one way)",
     "1e-10 relative: exact kernel, rounding only", 1, sl_verify_e05_one_way},
    {"engine", "E06", "2-D engine, a 1-D record along 45 degrees: peak, m",
     "exact 1-D kernel on the same record (closed-form stops and starts, E01-E05)",
     "max(1e-3 peak, 1e-6 m): the 2-D engine's stated accuracy (docs/integrators.md)", 1,
     sl_verify_e06_45deg},
    {"engine", "E07", "2-D engine, a 1-D record along 20 degrees: peak, m",
     "exact 1-D kernel on the same record", "max(1e-3 peak, 1e-6 m), as E06", 0,
     sl_verify_e07_20deg},
    {"engine", "E08", "2-D engine, a two-component motion rotated by 30 degrees: peak, m",
     "invariance: the peak of the unrotated motion (isotropic friction)",
     "2 max(1e-3 peak, 1e-6 m): each run within its stated accuracy", 0,
     sl_verify_e08_rotation},
    {"engine", "E09", "1-D peak under a rectangular pulse with constant vertical -0.3 g, m",
     "closed form of E01 with mu g replaced by mu (g + a_v)",
     "1e-10 relative: exact kernel, rounding only", 1, sl_verify_e09_vertical},
    {"engine", "E10", "lift-off (a_v = -2 g throughout, a_h = A): peak, m",
     "closed form: free flight A t^2/2 over the record, then a stop at V/(mu g): "
     "U = A T^2/2 + (A T)^2/(2 mu g)",
     "1e-10 relative: exact kernel, rounding only", 1, sl_verify_e10_liftoff},
    {"engine", "E11", "friction threshold of a sampled record, mu",
     "closed form: max |a| / g of the samples (no sliding at or above it)",
     "1e-15 relative: one division", 0, sl_verify_e11_threshold},
    /* ---- the rocking engine (Housner 1963) ------------------------------- */
    {"rock", "H01", "uplift from rest under a_h = -k t (b/h 0.2, k 3 m/s^3): instant, s",
     "(K3) by hand: |a_h| = g tan(alpha) at t = g (b/h) / k = 0.6537767 s",
     "1e-14 relative: the root of a linear function (rounding only)", 1,
     sl_verify_h01_uplift},
    {"rock", "H02", "the same with a constant a_v = -0.3 g: instant, s",
     "(K3) by hand: t = (g + a_v)(b/h) / k = 0.4576437 s",
     "1e-14 relative: the root of a linear function", 0, sl_verify_h02_uplift_vertical},
    {"rock", "H03", "restitution at the first impact (b 0.3 m, h 1 m): theta' after / before",
     "angular momentum about the new corner: (I_G + m (h^2 - b^2)) / I_O, I_G = m R^2/3, "
     "I_O = 4 m R^2/3: 1 - 1.5 sin^2(alpha) = 0.8761468",
     "1e-14 relative: one product per impact", 1, sl_verify_h03_restitution},
    {"rock", "H04", "free rocking of a slender block (b/h 0.01) from alpha/2: first impact, s",
     "linearised (Housner 1963): (1/p) arccosh(1/(1 - theta0/alpha)) = 0.4856146 s",
     "2 alpha^2 relative: the linearisation's own error, O(alpha^2) (measured 2.9e-6)", 0,
     sl_verify_h04_period_linear},
    {"rock", "H05", "free rocking (b 0.3 m, h 1 m, r = 1) from 0.6 alpha: period, s",
     "quadrature of the exact equation: 4 int_0^theta0 dtheta / sqrt(2 p^2 (cos(alpha - "
     "theta0) - cos(alpha - theta))) (GSL QAWS) = 2.365692 s",
     "1e-8 relative: the step rule keeps the integrator far below it (measured 9e-11)", 1,
     sl_verify_h05_period_exact},
    {"rock", "H06", "r = 1, no forcing (b 0.25 m, h 0.8 m) from 0.7 alpha: speed at the 41st "
     "impact, rad/s",
     "energy kept: p sqrt(2 (cos(alpha - theta0) - cos(alpha))) = 0.8523465 rad/s",
     "1e-8 relative: the integrator's drift over 20 cycles (measured 2.7e-9)", 0,
     sl_verify_h06_energy},
    {"rock", "H07", "rectangular pulse of 0.2 s, slender block (b/h 0.01): smallest "
     "overturning A/g",
     "linearised block, derived in docs/verification.md: A = g alpha / (1 - exp(-p t_p)) "
     "= 0.02389498",
     "2 alpha^2 relative: the linearisation's own error (measured 3.7e-5)", 0,
     sl_verify_h07_pulse_linear},
    {"rock", "H08", "rectangular pulse of 0.2 s, b/h 0.2: smallest overturning A/g",
     "quadrature of the exact equation: the pulse's end state, then the energy to reach "
     "alpha (docs/verification.md) = 0.4822036",
     "1e-6 relative: the sampled pulse's end ramp, O(dt^2) (measured 1.6e-8)", 1,
     sl_verify_h08_pulse_exact},
    /* ---- the reference models ------------------------------------------ */
    {"refmodel", "R01", "smoothed hysteretic model (U_y 1e-6 m, eta 20), pulse of E01: peak, m",
     "closed form of E01", "1 % relative: the model tends to Coulomb as sqrt(U_y); at 1e-6 m it "
     "is within 1 % (docs/refmodels.md)", 0, sl_verify_r01_smooth},
    {"refmodel", "R02", "elastic-plastic model (U_y 1e-6 m), pulse of E01: peak, m",
     "closed form of E01", "1 % relative, as R01", 1, sl_verify_r02_plastic},
    {"refmodel", "R03", "smoothed model with constant vertical -0.3 g: peak, m",
     "closed form of E09", "1 % relative, as R01", 0, sl_verify_r03_smooth_vertical},
    {"refmodel", "R04", "elastic-plastic model with constant vertical -0.3 g: peak, m",
     "closed form of E09", "1 % relative, as R01", 0, sl_verify_r04_plastic_vertical},
    /* ---- response spectra ---------------------------------------------- */
    {"spectrum", "S01", "PSA of a step a0 H(t), 5 % damping, in units of a0",
     "closed form 1 + exp(-pi z/sqrt(1 - z^2)) = 1.854468 (damped SDOF, e.g. Chopra, "
     "Dynamics of Structures, 4.3)",
     "1e-10 relative: the first peak falls on a sample; Nigam-Jennings is exact", 1,
     sl_verify_s01_step5},
    {"spectrum", "S02", "PSA of a step, 10 % damping, in units of a0",
     "closed form, as S01: 1.729248", "1e-10 relative, as S01", 0, sl_verify_s02_step10},
    {"spectrum", "S03", "PSA of a short rectangular pulse (t_d < T/2), undamped, m/s^2",
     "closed form 2 a0 sin(pi t_d/T) (shock spectrum; the peak comes after the pulse)",
     "1e-10 relative: exact recurrence, the peak on a sample", 1, sl_verify_s03_pulse},
    {"spectrum", "S04", "PSA of a resonant sine (120 s, 5 %), m/s^2",
     "closed form steady state w^2 X, X = A/(2 z w^2) at resonance",
     "1.25 % relative: the peak sampled at T/20 is low by up to 1 - cos(pi/20) = 1.23 %", 0,
     sl_verify_s04_resonance},
    /* ---- RG 1.60 --------------------------------------------------------- */
    {"rg160", "G01", "horizontal 5 %: SA at B (9 Hz), in units of the PGA",
     "RG 1.60 Table I: 2.61", "1e-12 relative: a table value (rounding only)", 1,
     sl_verify_g01},
    {"rg160", "G02", "horizontal 5 %: SA at C (2.5 Hz), in units of the PGA",
     "RG 1.60 Table I: 3.13", "1e-12 relative, as G01", 0, sl_verify_g02},
    {"rg160", "G03", "horizontal 5 %: SD at D (0.25 Hz), m per g of PGA",
     "RG 1.60 Table I: 2.05 x 36 in = 1.87452 m", "1e-12 relative, as G01", 0, sl_verify_g03},
    {"rg160", "G04", "horizontal: SA at A (33 Hz) and above (50 Hz), in units of the PGA",
     "RG 1.60: the ZPA, 1.0", "1e-12 relative, as G01", 0, sl_verify_g04},
    {"rg160", "G05", "vertical 5 %: SA at C (3.5 Hz), in units of the PGA",
     "RG 1.60 Table II: 2.98", "1e-12 relative, as G01", 1, sl_verify_g05},
    {"rg160", "G06", "horizontal 2 %: SA at B (9 Hz), in units of the PGA",
     "RG 1.60 Table I: 3.54", "1e-12 relative, as G01", 0, sl_verify_g06},
    {"rg160", "G07", "horizontal 5 %, 1 g: SA at 1 Hz, g",
     "RG 1.60 Table I, log-log line D-C by hand: 1.4739 g",
     "5e-5 g: the hand value's printed precision", 1, sl_verify_g07},
    {"rg160", "G08", "horizontal 10 %, 1 g: SA at 5 Hz, g",
     "RG 1.60 Table I, log-log line C-B by hand: 2.0658 g",
     "5e-5 g: the hand value's printed precision", 0, sl_verify_g08},
    /* ---- ASCE 43-05 ------------------------------------------------------ */
    {"asce", "A01", "worked example step 1: mu_e = mu (1 - 0.4 A_v/g), mu 0.2, A_v 0.3 g",
     "ASCE/SEI 43-05 A.1 step 1 by hand: 0.176", "1e-14 relative: arithmetic", 1,
     sl_verify_a01},
    {"asce", "A02", "worked example step 2: c_s = 2 mu_e g, m/s^2",
     "ASCE/SEI 43-05 A.1 step 2 by hand: 0.352 g = 3.4519408 m/s^2",
     "1e-14 relative: arithmetic", 0, sl_verify_a02},
    {"asce", "A03", "worked example steps 3-4: f_es on RG 1.60 H 10 % at 0.3 g, Hz",
     "by hand on the D-C line of RG 1.60 with SA_vH = sqrt(1.16) SA: 0.95283 Hz "
     "(docs/verification.md)",
     "1e-9 relative: a power law solved in closed form", 1, sl_verify_a03},
    {"asce", "A04", "worked example step 5: delta_s = c_s/(2 pi f_es)^2, m",
     "by hand: 0.096311 m (docs/verification.md)", "1e-9 relative, as A03", 0, sl_verify_a04},
    {"asce", "A05", "worked example steps 6-7: design 2 delta_s, cap 1.5 PGD (PGD 0.3 m), m",
     "ASCE/SEI 43-05 A.1 (factor 2) and the cap by hand: 0.19262 m (below the cap 0.45 m)",
     "1e-12 relative: arithmetic", 0, sl_verify_a05},
    {"asce", "A06", "constant-displacement branch: delta_s at mu 0.04, RG 1.60 H 10 % 0.3 g, m",
     "by hand: below D, SD_vH = sqrt(1.16) x 1.70 x 36 in x 0.3 = 0.50227 m",
     "1e-9 relative: closed form", 0, sl_verify_a06},
    {"asce", "A07", "no sliding: mu_e g at or above the ZPA gives delta 0, m",
     "ASCE/SEI 43-05 A.1: no sliding, 0", "0: exact", 0, sl_verify_a07},
    /* ---- synthesis ------------------------------------------------------- */
    {"synth", "Y01", "RG 1.60 0.3 g, seed 2027, H1: lowest computed/target PSA (5 %)",
     "US NRC SRP 3.7.1: no point more than 10 % below the target (at least 0.90)",
     "the limit itself", 1, sl_verify_y01},
    {"synth", "Y02", "the same motion: highest computed/target PSA",
     "US NRC SRP 3.7.1: no point more than 30 % above (at most 1.30)", "the limit itself", 0,
     sl_verify_y02},
    {"synth", "Y03", "the same motion: longest run of grid points below the target",
     "US NRC SRP 3.7.1: at most 9 consecutive points", "the limit itself", 0, sl_verify_y03},
    {"synth", "Y04", "the same motion: strong-motion duration (5-75 % Arias), s",
     "US NRC SRP 3.7.1: at least 6 s", "the limit itself", 0, sl_verify_y04},
    {"synth", "Y05", "set of seed 2027: largest |correlation| of two components",
     "US NRC SRP 3.7.1: at most 0.16", "the limit itself", 0, sl_verify_y05},
    {"synth", "Y06", "the same motion: |velocity at the end| / PGV",
     "US NRC SRP 3.7.1 (baseline corrected, at rest): at most 0.01", "the limit itself", 0,
     sl_verify_y06},
    {"synth", "Y07", "the same motion's exact bits (FNV-1a 64 of the H1 samples)",
     "recorded at release 0.1.0 (GCC 12.2, -O2 -ffp-contract=off, x86-64, AVX2 and baseline "
     "alike; glibc 2.36 libm with and without FMA: a81521776e5490f1, 720d9329d435974b)",
     "0: any change of compiler, library or CPU path that moves a bit shows", 1,
     sl_verify_y07},
    /* ---- statistics ------------------------------------------------------ */
    {"stats", "T01", "SE of the mean of {1, 2, 3, 4, 5}",
     "by hand: s = sqrt(2.5), SE = s/sqrt(5) = sqrt(0.5) = 0.70710678",
     "1e-14 relative: arithmetic", 1, sl_verify_t01},
    {"stats", "T02", "zero-inflated log-normal mean of {0, 0, e, e^3}",
     "by hand, stats.h (1): 0.5 exp(2 + 2/2) = 10.042768", "1e-14 relative: arithmetic", 0,
     sl_verify_t02},
    {"stats", "T03", "its SE (delta method)",
     "by hand, stats.h (2): Var(ln M) = 0.5 + 1 + 2 = 3.25, SE = M sqrt(3.25)",
     "1e-14 relative: arithmetic", 0, sl_verify_t03},
    {"stats", "T04", "90 % band of the sample 1..11: lower end",
     "by hand: order statistic at 0.05 x 10 = 0.5 -> 1.5 (linear interpolation)",
     "1e-15 absolute: interpolation", 0, sl_verify_t04},
    {"stats", "T05", "percentile bootstrap 90 % band of the mean of ten 0 and ten 1: width",
     "binomial(20, 1/2): 5 % and 95 % quantiles 6 and 14, width (14 - 6)/20 = 0.40",
     "0.05: one binomial step (the band's ends are Monte Carlo quantiles of 20000 resamples)", 1,
     sl_verify_t05},
    {"stats", "T06", "design value min(FS mean, cap) and its SE, capped row: SE, m",
     "by hand: peaks {1, 3}, PGD {1, 2}, FS 3, cap 1.5 x 1.5: SE = 1.5 sd(PGD)/sqrt 2 = 0.75",
     "1e-14 relative: arithmetic", 0, sl_verify_t06},
    /* ---- input reading --------------------------------------------------- */
    {"input", "I01", "one floor as INI and as CSV: fields and values that differ",
     "the same description: 0 differences", "0: exact", 1, sl_verify_i01},
    {"input", "I02", "a floor in g read into SI: SA at 2 Hz of 0.5 g, m/s^2",
     "by hand: 0.5 x 9.80665 = 4.903325", "1e-15 relative: one product", 0, sl_verify_i02},
    {"input", "I03", "a floor whose frequencies fall: refused, line of the error",
     "the file as written: line 8 (status bad input)", "0: exact", 1, sl_verify_i03},
    {"input", "I04", "a CSV floor with a bad number: refused, column of the error",
     "the file as written: column 3 (of line 6)", "0: exact", 0, sl_verify_i04},
    /* ---- the workbook's lookup ------------------------------------------ */
    {"workbook", "W01", "Lookup formula evaluated on its cells vs sl_design_clearance_at, m",
     "sl_design_clearance_at, the C function the formula twins (W02 checks it by hand)",
     "1e-12 relative: the same arithmetic in another order", 1, sl_verify_w01},
    {"workbook", "W02", "the C function sl_design_clearance_at at the same mu, m",
     "by hand: C0 + (mu - mu0)(C1 - C0)/(mu1 - mu0) = 0.03 + 0.5 x 0.02 = 0.04 m", "1e-12 relative", 0, sl_verify_w02},
};

const sl_verify_problem *sl_verify_problems(size_t *n)
{
    *n = sizeof problems / sizeof problems[0];
    return problems;
}

static void num_text(char *buf, double x)
{
    if (isnan(x))
        snprintf(buf, SL_VERIFY_TEXT, "nan");
    else
        snprintf(buf, SL_VERIFY_TEXT, "%.10g", x);
}

void sl_verify_judge(const sl_verify_problem *p, const sl_verify_value *v, sl_verify_result *r)
{
    r->problem = p;
    r->value = *v;
    const double ref = v->reference, got = v->computed;
    switch (v->kind) {
    case SL_VERIFY_BITS:
        r->error = v->ref_bits == v->got_bits ? 0.0 : 1.0;
        r->tolerance = 0.0;
        snprintf(r->reference, SL_VERIFY_TEXT, "%016" PRIx64, v->ref_bits);
        snprintf(r->computed, SL_VERIFY_TEXT, "%016" PRIx64, v->got_bits);
        break;
    case SL_VERIFY_AT_MOST:
    case SL_VERIFY_AT_LEAST: {
        double over = v->kind == SL_VERIFY_AT_MOST ? got - ref : ref - got;
        r->error = over > 0 ? over : (isnan(over) ? NAN : 0.0);
        r->tolerance = v->abs_tol;
        snprintf(r->reference, SL_VERIFY_TEXT, "%s %.10g",
                 v->kind == SL_VERIFY_AT_MOST ? "<=" : ">=", ref);
        num_text(r->computed, got);
        break;
    }
    default:
        r->error = fabs(got - ref);
        r->tolerance = v->abs_tol + v->rel_tol * fabs(ref);
        num_text(r->reference, ref);
        num_text(r->computed, got);
        break;
    }
    snprintf(r->error_text, SL_VERIFY_TEXT, "%.3g", r->error);
    snprintf(r->tolerance_text, SL_VERIFY_TEXT, "%.3g", r->tolerance);
    r->pass = r->error <= r->tolerance; /* NaN fails */
}

sl_status sl_verify_run(const sl_verify_problem *tab, size_t n, int quick,
                        const sl_verify_ctx *ctx, sl_verify_result *out, size_t *n_run,
                        size_t *n_pass, size_t *n_fail, sl_verify_done_fn done, void *cb_ctx)
{
    *n_run = *n_pass = *n_fail = 0;
    if (!tab || !out)
        return SL_EINVAL;
    size_t total = 0;
    for (size_t i = 0; i < n; i++)
        total += !quick || tab[i].quick;
    for (size_t i = 0; i < n; i++) {
        if (quick && !tab[i].quick)
            continue;
        sl_verify_result *r = &out[*n_run];
        memset(r, 0, sizeof *r);
        sl_verify_value v = {SL_VERIFY_CLOSE, NAN, NAN, 0, 0, 0, 0};
        sl_error err;
        sl_error_clear(&err);
        double t0 = sl_clock_s();
        sl_status st = tab[i].run(ctx, &v, &err);
        r->seconds = sl_clock_s() - t0;
        if (st != SL_OK)
            v.computed = NAN; /* a failed computation fails the problem */
        sl_verify_judge(&tab[i], &v, r);
        r->seconds = sl_clock_s() - t0;
        r->status = st;
        if (st != SL_OK) {
            r->pass = 0;
            snprintf(r->msg, sizeof r->msg, "%s", err.msg[0] ? err.msg : sl_status_message(st));
        }
        if (r->pass)
            (*n_pass)++;
        else
            (*n_fail)++;
        (*n_run)++;
        if (done)
            done(cb_ctx, r, *n_run, total);
    }
    return *n_fail ? SL_ENOCONV : SL_OK;
}

uint64_t sl_verify_fingerprint(const double *x, size_t n)
{
    uint64_t h = 14695981039346656037ull;
    const unsigned char *b = (const unsigned char *)x;
    for (size_t i = 0; i < n * sizeof *x; i++) {
        h ^= b[i];
        h *= 1099511628211ull;
    }
    return h;
}
