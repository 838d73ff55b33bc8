/* test_asce.c - ASCE/SEI 43-05 A.1 steps on RG 1.60 spectra where f_es is
 * solvable by hand (power-law segments), every edge case, and Newmark's
 * estimates (REFERENCE.md 2-3). */
#include "method/asce.h"
#include "method/asce_input.h"
#include "harness.h"
#include "signal/rg160.h"
#include "core/units.h"

#define PI 3.14159265358979323846
#define IN_M 0.0254
#define SQ116 1.0770329614269007 /* sqrt(1 + 0.4^2) */

/* RG 1.60 horizontal, 10 %, PGA a (g), on a grid with its control points. */
static sl_spectrum *rg_spectrum(double a_g)
{
    size_t n;
    double *f = sl_rg160_grid(SL_RG160_HORIZONTAL, 0.1, 50, 100, &n);
    sl_spectrum *s = sl_spectrum_alloc(n, 0.10);
    memcpy(s->f_hz, f, n * sizeof *f);
    free(f);
    sl_rg160_psa(SL_RG160_HORIZONTAL, 0.10, a_g * SL_G, s->f_hz, n, s->sa_ms2, NULL);
    return s;
}

static sl_asce *rg_method(const sl_spectrum *s, double a_g)
{
    sl_asce_input in;
    sl_asce_input_default(&in);
    in.h1 = in.h2 = s;
    in.av_ms2 = a_g * SL_G;
    in.zpa_h_ms2 = a_g * SL_G;
    in.pgd_m = 1.4 * 36 * IN_M * a_g;
    return sl_asce_alloc(&in, NULL);
}

/* Hand solution on RG 1.60 (H, 10 %): below D (0.25 Hz) SA = SA_D (f/0.25)^2;
 * D to C (2.5 Hz) SA = k f^p. SA_vH = sqrt(1.16) SA, so
 * f_es = (c_s/(sqrt(1.16) k))^(1/p), delta = c_s/(2 pi f_es)^2. */
static void check_rg(double a_g, const double *mu, int nmu, int segment)
{
    sl_spectrum *s = rg_spectrum(a_g);
    sl_asce *m = rg_method(s, a_g);
    CHECK(m != NULL, "alloc");
    double wd = 2 * PI * 0.25;
    double sd_d = 1.70 * 36 * IN_M * a_g;          /* m */
    double sa_d = wd * wd * sd_d / SL_G;          /* g */
    double p = log(2.28 * a_g / sa_d) / log(10.0); /* D -> C */
    double k = sa_d / pow(0.25, p);
    double cap = 1.5 * 1.4 * 36 * IN_M * a_g;
    for (int i = 0; i < nmu; i++) {
        sl_asce_result r;
        CHECK(sl_asce_eval(m, mu[i], &r, NULL) == SL_OK, "eval");
        double mu_e = mu[i] * (1 - 0.4 * a_g);
        double cs_g = 2 * mu_e;
        CHECK_CLOSE(r.mu_e, mu_e, 0, 1e-15);
        CHECK_CLOSE(r.cs_ms2, cs_g * SL_G, 0, 1e-15);
        double fes, delta;
        if (segment == 1) { /* D to C */
            CHECK(cs_g > SQ116 * sa_d && cs_g < SQ116 * 2.28 * a_g, "mu %g not in D-C", mu[i]);
            fes = pow(cs_g / (SQ116 * k), 1 / p);
            delta = cs_g * SL_G / pow(2 * PI * fes, 2);
        } else { /* constant SD below D */
            CHECK(cs_g < SQ116 * sa_d && cs_g > SQ116 * sa_d * 0.16, "mu %g not in 0.1-0.25",
                  mu[i]);
            fes = 0.25 * sqrt(cs_g / (SQ116 * sa_d));
            delta = SQ116 * sd_d;
        }
        CHECK_CLOSE(r.fes_hz, fes, 0, 1e-10);
        CHECK_CLOSE(r.delta_best_m, delta, 0, 1e-10);
        int capped = 2 * delta > cap;
        CHECK_CLOSE(r.delta_design_m, capped ? cap : 2 * delta, 0, 1e-10);
        CHECK(r.flags == (capped ? (unsigned)SL_ASCE_CAPPED : 0u), "mu %g flags %u", mu[i],
              r.flags);
        CHECK_CLOSE(r.cap_m, cap, 0, 1e-15);
    }
    sl_asce_free(m);
    sl_spectrum_free(s);
}

static void test_rg160_power_law_segment(void)
{
    const double mu3[] = {0.1, 0.15, 0.2, 0.25, 0.3};
    check_rg(0.3, mu3, 5, 1);
    const double mu6[] = {0.2, 0.3, 0.5, 0.7};
    check_rg(0.6, mu6, 4, 1);
}

static void test_rg160_constant_sd_segment(void)
{
    const double mu3[] = {0.02, 0.04, 0.06};
    check_rg(0.3, mu3, 3, 0);
    const double mu8[] = {0.05, 0.1, 0.12};
    check_rg(0.8, mu8, 3, 0);
}

/* c_s below SA_vH at the lowest frequency: constant-SD extension. */
static void test_below_fmin(void)
{
    /* RG 1.60 at 0.3 g from 0.1 Hz: SD_vH(0.1) = sqrt(1.16) SD_D */
    sl_spectrum *s = rg_spectrum(0.3);
    sl_asce *m = rg_method(s, 0.3);
    sl_asce_result r;
    sl_asce_eval(m, 0.005, &r, NULL);
    double sd = SQ116 * 1.70 * 36 * IN_M * 0.3;
    double savh_min = SQ116 * s->sa_ms2[0];
    CHECK(r.flags & SL_ASCE_BELOW_FMIN, "flags %u", r.flags);
    CHECK_CLOSE(r.delta_best_m, sd, 0, 1e-12);
    CHECK_CLOSE(r.fes_hz, 0.1 * sqrt(r.cs_ms2 / savh_min), 0, 1e-12);
    sl_asce_eval(m, 0.0, &r, NULL); /* mu = 0: f_es = 0, same limit */
    CHECK(r.flags & SL_ASCE_BELOW_FMIN, "mu 0 flags %u", r.flags);
    CHECK(r.fes_hz == 0.0, "fes %g", r.fes_hz);
    CHECK_CLOSE(r.delta_best_m, sd, 0, 1e-12);
    sl_asce_free(m);
    sl_spectrum_free(s);

    /* a spectrum from 0.5 Hz: delta = SA_vH(f_min)/(2 pi f_min)^2 */
    sl_spectrum *flat = sl_spectrum_alloc(3, 0.10);
    double ff[3] = {0.5, 2, 10}, fs[3] = {2, 4, 3};
    for (int i = 0; i < 3; i++) {
        flat->f_hz[i] = ff[i];
        flat->sa_ms2[i] = fs[i];
    }
    sl_asce_input in;
    sl_asce_input_default(&in);
    in.h1 = in.h2 = flat;
    in.zpa_h_ms2 = 2.0;
    m = sl_asce_alloc(&in, NULL);
    sl_asce_eval(m, 0.05, &r, NULL);
    CHECK(r.flags == SL_ASCE_BELOW_FMIN, "flags %u", r.flags);
    CHECK_CLOSE(r.delta_best_m, 2.0 * SQ116 / pow(2 * PI * 0.5, 2), 0, 1e-14);
    CHECK(isnan(r.cap_m), "no cap without a displacement");
    /* continuity at c_s = SA_vH(f_min): below_fmin just below, a crossing at
     * f_min just above, the same f_es and delta on both sides */
    double mu_eq = 2.0 * SQ116 / (2 * SL_G);
    sl_asce_result lo, hi;
    sl_asce_eval(m, mu_eq * (1 - 1e-13), &lo, NULL);
    sl_asce_eval(m, mu_eq * (1 + 1e-13), &hi, NULL);
    CHECK(lo.flags == SL_ASCE_BELOW_FMIN && hi.flags == 0, "flags %u %u", lo.flags, hi.flags);
    CHECK_CLOSE(lo.fes_hz, 0.5, 0, 1e-12);
    CHECK_CLOSE(hi.fes_hz, 0.5, 0, 1e-12);
    CHECK_CLOSE(hi.delta_best_m, lo.delta_best_m, 0, 1e-12);
    sl_asce_free(m);
    sl_spectrum_free(flat);
}

/* mu_e g >= horizontal ZPA: no sliding, delta 0 with the flag. */
static void test_no_sliding(void)
{
    double a_g = 0.4;
    sl_spectrum *s = rg_spectrum(a_g);
    sl_asce *m = rg_method(s, a_g);
    double mu_lim = a_g / (1 - 0.4 * a_g); /* mu_e = a */
    sl_asce_result r;
    sl_asce_eval(m, mu_lim * (1 + 1e-12), &r, NULL);
    CHECK(r.flags == SL_ASCE_NO_SLIDING && r.delta_best_m == 0 && r.delta_design_m == 0 &&
              isnan(r.fes_hz),
          "above: flags %u delta %g", r.flags, r.delta_best_m);
    sl_asce_eval(m, 0.9, &r, NULL);
    CHECK(r.flags == SL_ASCE_NO_SLIDING, "0.9: flags %u", r.flags);
    sl_asce_eval(m, mu_lim * (1 - 1e-6), &r, NULL);
    CHECK(r.flags == 0 && r.delta_best_m > 0, "just below: flags %u", r.flags);
    char buf[64];
    CHECK(!strcmp(sl_asce_status_name(SL_ASCE_NO_SLIDING, buf, sizeof buf), "no_sliding"), "%s",
          buf);
    sl_asce_free(m);
    sl_spectrum_free(s);
}

/* c_s above the whole spectrum while mu_e g < ZPA: no answer (NAN). */
static void test_no_crossing(void)
{
    sl_spectrum *s = sl_spectrum_alloc(4, 0.10);
    double ff[4] = {0.1, 1, 10, 50};
    for (int i = 0; i < 4; i++) {
        s->f_hz[i] = ff[i];
        s->sa_ms2[i] = 0.4 * SL_G;
    }
    sl_asce_input in;
    sl_asce_input_default(&in);
    in.h1 = in.h2 = s;
    in.zpa_h_ms2 = 0.4 * SL_G;
    in.pgd_m = 0.2;
    sl_asce *m = sl_asce_alloc(&in, NULL);
    sl_asce_result r;
    sl_asce_eval(m, 0.3, &r, NULL); /* c_s 0.6 g > 0.431 g, mu g 0.3 g < 0.4 g */
    CHECK(r.flags == SL_ASCE_NO_CROSSING, "flags %u", r.flags);
    CHECK(isnan(r.fes_hz) && isnan(r.delta_best_m) && isnan(r.delta_design_m), "NAN");
    sl_asce_free(m);
    sl_spectrum_free(s);
}

/* Scan upward: the first crossing counts, not a later one. */
static void test_first_crossing(void)
{
    sl_spectrum *s = sl_spectrum_alloc(4, 0.10);
    double ff[4] = {1, 2, 3, 4}, sa[4] = {1, 3, 1, 5};
    memcpy(s->f_hz, ff, sizeof ff);
    memcpy(s->sa_ms2, sa, sizeof sa);
    sl_asce_input in;
    sl_asce_input_default(&in);
    in.h1 = in.h2 = s;
    in.zpa_h_ms2 = 5;
    sl_asce *m = sl_asce_alloc(&in, NULL);
    sl_asce_result r;
    double mu = 2 * SQ116 / (2 * SL_G); /* c_s = 2 sqrt(1.16): SA crosses 2 */
    sl_asce_eval(m, mu, &r, NULL);
    CHECK_CLOSE(r.fes_hz, pow(2.0, log(2.0) / log(3.0)), 0, 1e-12);
    mu = 4 * SQ116 / (2 * SL_G); /* only the last interval reaches 4 */
    sl_asce_eval(m, mu, &r, NULL);
    CHECK_CLOSE(r.fes_hz, 3 * pow(4.0 / 3.0, log(4.0) / log(5.0)), 0, 1e-12);
    sl_asce_free(m);
    sl_spectrum_free(s);
}

/* SA_vH with H1 the larger at each frequency; grids merged. */
static void test_combination(void)
{
    sl_spectrum *a = sl_spectrum_alloc(5, 0.10), *b = sl_spectrum_alloc(3, 0.10);
    double fa[5] = {0.5, 1, 2, 4, 8}, sa[5] = {1, 2, 4, 8, 8};
    double fb[3] = {1, 3, 10}, sb[3] = {6, 3, 1};
    memcpy(a->f_hz, fa, sizeof fa);
    memcpy(a->sa_ms2, sa, sizeof sa);
    memcpy(b->f_hz, fb, sizeof fb);
    memcpy(b->sa_ms2, sb, sizeof sb);
    sl_asce_input in;
    sl_asce_input_default(&in);
    in.h1 = a;
    in.h2 = b;
    in.zpa_h_ms2 = 8;
    sl_asce *m1 = sl_asce_alloc(&in, NULL);
    in.h1 = b;
    in.h2 = a;
    sl_asce *m2 = sl_asce_alloc(&in, NULL);
    const double *f1, *s1, *f2, *s2;
    size_t n1 = sl_asce_combined(m1, &f1, &s1), n2 = sl_asce_combined(m2, &f2, &s2);
    const double fu[5] = {1, 2, 3, 4, 8}; /* union inside the overlap [1, 8] */
    CHECK(n1 == 5 && n2 == 5, "n %zu %zu", n1, n2);
    for (size_t i = 0; i < 5 && n1 == 5; i++) {
        CHECK(f1[i] == fu[i], "f %g", f1[i]);
        double x = sl_spectrum_interp(a, fu[i]), y = sl_spectrum_interp(b, fu[i]);
        double hi = fmax(x, y), lo = fmin(x, y);
        CHECK_CLOSE(s1[i], sqrt(hi * hi + 0.16 * lo * lo), 0, 1e-14);
        CHECK(s1[i] == s2[i], "order of H1/H2 matters at %g", fu[i]);
    }
    CHECK_CLOSE(s1[0], sqrt(36 + 0.16 * 4), 0, 1e-14); /* H2 larger at 1 Hz */
    sl_asce_free(m1);
    sl_asce_free(m2);
    sl_spectrum_free(a);
    sl_spectrum_free(b);
}

static void test_bad_input(void)
{
    sl_spectrum *s = sl_spectrum_alloc(3, 0.05);
    double ff[3] = {1, 2, 3};
    memcpy(s->f_hz, ff, sizeof ff);
    for (int i = 0; i < 3; i++)
        s->sa_ms2[i] = 1;
    sl_asce_input in;
    sl_asce_input_default(&in);
    in.h1 = in.h2 = s;
    in.zpa_h_ms2 = 1;
    sl_error e;
    sl_error_clear(&e);
    CHECK(sl_asce_alloc(&in, &e) == NULL && e.code == SL_EINVAL, "5 %% damped accepted");
    CHECK(strstr(e.msg, "damped") != NULL, "message '%s'", e.msg);
    s->damping = 0.10;
    in.zpa_h_ms2 = 0;
    CHECK(sl_asce_alloc(&in, &e) == NULL, "ZPA 0 accepted");
    in.zpa_h_ms2 = 1;
    s->sa_ms2[1] = 0;
    CHECK(sl_asce_alloc(&in, &e) == NULL, "SA 0 accepted");
    s->sa_ms2[1] = 1;
    sl_asce *m = sl_asce_alloc(&in, &e);
    sl_asce_result r;
    CHECK(sl_asce_eval(m, -0.1, &r, &e) == SL_EINVAL, "mu < 0");
    CHECK(sl_asce_eval(m, NAN, &r, &e) == SL_EINVAL, "mu NaN");
    sl_asce_free(m);
    sl_spectrum *t = sl_spectrum_alloc(2, 0.10);
    t->f_hz[0] = 5;
    t->f_hz[1] = 6;
    t->sa_ms2[0] = t->sa_ms2[1] = 1;
    in.h2 = t;
    CHECK(sl_asce_alloc(&in, &e) == NULL && strstr(e.msg, "overlap"), "no overlap: '%s'", e.msg);
    sl_spectrum_free(t);
    sl_spectrum_free(s);
    sl_asce_free(NULL);
}

/* A_v lowers mu_e: mu_e = mu (1 - 0.4 A_v/g). */
static void test_vertical(void)
{
    sl_spectrum *s = rg_spectrum(0.5);
    sl_asce_input in;
    sl_asce_input_default(&in);
    in.h1 = in.h2 = s;
    in.zpa_h_ms2 = 0.5 * SL_G;
    const double av_g[3] = {0, 0.5, 1.0};
    double prev = 0;
    for (int k = 0; k < 3; k++) {
        in.av_ms2 = av_g[k] * SL_G;
        sl_asce *m = sl_asce_alloc(&in, NULL);
        sl_asce_result r;
        sl_asce_eval(m, 0.2, &r, NULL);
        CHECK_CLOSE(r.mu_e, 0.2 * (1 - 0.4 * av_g[k]), 0, 1e-15);
        CHECK(r.delta_best_m > prev, "more vertical, more sliding");
        prev = r.delta_best_m;
        sl_asce_free(m);
    }
    sl_spectrum_free(s);
}

static void test_status_names(void)
{
    char buf[64];
    CHECK(!strcmp(sl_asce_status_name(0, buf, sizeof buf), "ok"), "%s", buf);
    CHECK(!strcmp(sl_asce_status_name(SL_ASCE_CAPPED | SL_ASCE_BELOW_FMIN, buf, sizeof buf),
                  "below_fmin+capped"),
          "%s", buf);
    CHECK(!strcmp(sl_asce_status_name(SL_ASCE_NO_CROSSING, buf, sizeof buf), "no_crossing"),
          "%s", buf);
    char small[5];
    sl_asce_status_name(SL_ASCE_NO_SLIDING, small, sizeof small);
    CHECK(strlen(small) == 4, "truncated safely: '%s'", small);
}

/* Newmark (1965): U = V^2/(2 mu g)(1 - mu g/A) and 2 V^2/(mu g)(1 - mu g/A)^2. */
static void test_newmark(void)
{
    double g = SL_G, v = 0.5, a = 3.0, mu = 0.1, r = mu * g / a;
    CHECK_CLOSE(sl_asce_newmark_sym(v, a, mu, g), v * v / (2 * mu * g) * (1 - r), 0, 1e-15);
    CHECK_CLOSE(sl_asce_newmark_asym(v, a, mu, g), 2 * v * v / (mu * g) * (1 - r) * (1 - r), 0,
                1e-15);
    /* the rectangular pulse of REFERENCE.md 4: V = A t0 */
    double t0 = 0.4;
    CHECK_CLOSE(sl_asce_newmark_sym(a * t0, a, mu, g),
                pow(a * t0, 2) / (2 * mu * g) * (1 - mu * g / a), 0, 1e-15);
    CHECK(sl_asce_newmark_sym(v, 0.25 * g, 0.25, g) == 0.0, "mu g = A");
    CHECK(sl_asce_newmark_asym(v, a, 1.0, g) == 0.0, "mu g > A");
    CHECK(isnan(sl_asce_newmark_sym(v, a, 0.0, g)), "mu 0");
    CHECK(isnan(sl_asce_newmark_asym(NAN, a, 0.1, g)), "V NaN");
}


/* The ASCE input of a floor (asce_input.h), against a hand calculation.
 * Floor: H1 zpa 0.2 g, H2 zpa 0.5 g, V zpa 0.1 g; both horizontals
 * SA_0.10 = 0.05, 0.5, 0.6 g at 0.1, 1, 10 Hz, then 0.2 (H1) and 0.5 g (H2)
 * at 50 Hz (each ZPA agrees with its spectrum's end, as floor.h requires).
 *  - ZPA_h is the LARGER horizontal, 0.5 g (with the smaller, 0.2 g, the
 *    block below would be reported as not sliding);
 *  - mu = 0.3: mu_e = 0.3 (1 - 0.4 x 0.1) = 0.288, c_s = 0.576 g; SA_vH =
 *    sqrt(1.16) SA (equal horizontals) crosses c_s between 1 and 10 Hz:
 *    log-log, f_es = 10^(ln(c_s/SA_vH(1))/ln(0.6/0.5)), delta = c_s/(2 pi f_es)^2;
 *  - no cap (a floor gives no peak displacement). */
static void test_input_from_floor(void)
{
    const char *text =
        "[floor]\nname = hand\nunits = g\n"
        "[h1]\nf_hz = 0.1, 1, 10, 50\nsa_0.10 = 0.05, 0.5, 0.6, 0.2\nzpa = 0.2\n"
        "[h2]\nf_hz = 0.1, 1, 10, 50\nsa_0.10 = 0.05, 0.5, 0.6, 0.5\nzpa = 0.5\n"
        "[v]\nf_hz = 0.1, 1, 10, 50\nsa_0.10 = 0.02, 0.2, 0.2, 0.1\nzpa = 0.1\n";
    const char *path = harness_tmpfile("asce-floor.ini", text);
    sl_error err;
    sl_error_clear(&err);
    sl_floor *fl = sl_floor_load(path, &err);
    CHECK(fl != NULL, "%s", err.msg);
    if (!fl)
        return;
    CHECK_CLOSE(sl_asce_floor_zpa_h(fl), 0.5 * SL_G, 0, 1e-12);
    sl_asce_source src;
    CHECK(sl_asce_input_from_floor(fl, NULL, &src, &err) == SL_OK, "%s", err.msg);
    CHECK_CLOSE(src.in.zpa_h_ms2, 0.5 * SL_G, 0, 1e-12);
    CHECK_CLOSE(src.in.av_ms2, 0.1 * SL_G, 0, 1e-12);
    CHECK(isnan(src.in.pgd_m), "a floor has no cap: pgd %g", src.in.pgd_m);
    sl_asce *m = sl_asce_alloc(&src.in, &err);
    CHECK(m != NULL, "%s", err.msg);
    sl_asce_result r;
    CHECK(m && sl_asce_eval(m, 0.3, &r, &err) == SL_OK, "%s", err.msg);
    if (m) {
        double cs = 2 * 0.288 * SL_G, sa1 = sqrt(1.16) * 0.5 * SL_G;
        double fes = pow(10.0, log(cs / sa1) / log(0.6 / 0.5));
        CHECK(!(r.flags & SL_ASCE_NO_SLIDING), "mu 0.3 reported as no sliding (flags %u)",
              r.flags);
        CHECK_CLOSE(r.fes_hz, fes, 0, 1e-9);
        CHECK_CLOSE(r.delta_best_m, cs / pow(2 * PI * fes, 2), 0, 1e-9);
        CHECK(isnan(r.cap_m), "cap %g", r.cap_m);
        sl_asce_eval(m, 0.55, &r, &err); /* mu_e g = 0.528 g >= 0.5 g */
        CHECK(r.flags == SL_ASCE_NO_SLIDING, "mu 0.55: flags %u", r.flags);
    }
    sl_asce_free(m);
    sl_asce_source_free(&src);
    sl_floor_free(fl);
    /* without sa_0.10 and without a fallback: an error naming the file */
    const char *t5 = "[floor]\nname = five\nunits = g\n"
                     "[h1]\nf_hz = 0.1, 1, 10, 50\nsa_0.05 = 0.05, 0.5, 0.6, 0.2\nzpa = 0.2\n"
                     "[h2]\nf_hz = 0.1, 1, 10, 50\nsa_0.05 = 0.05, 0.5, 0.6, 0.5\nzpa = 0.5\n"
                     "[v]\nf_hz = 0.1, 1, 10, 50\nsa_0.05 = 0.02, 0.2, 0.2, 0.1\nzpa = 0.1\n";
    path = harness_tmpfile("asce-floor5.ini", t5);
    fl = sl_floor_load(path, &err);
    CHECK(fl != NULL, "%s", err.msg);
    CHECK(fl && sl_asce_input_from_floor(fl, NULL, &src, &err) == SL_EUNSUPPORTED &&
              strstr(err.file, "asce-floor5.ini") && strstr(err.msg, "sa_0.10"),
          "missing sa_0.10: %s: %s", err.file, err.msg);
    sl_floor_free(fl);
}

/* The ASCE input of RG 1.60 (asce_input.h): A_v = ZPA = PGA, the cap from
 * 36 in per g per horizontal combined 100-40: 1.4 x 36 in x PGA. */
static void test_input_from_rg160(void)
{
    sl_asce_source src;
    sl_error err;
    sl_error_clear(&err);
    CHECK(sl_asce_input_from_rg160(0.3, &src, &err) == SL_OK, "%s", err.msg);
    CHECK_CLOSE(src.in.zpa_h_ms2, 0.3 * SL_G, 0, 1e-15);
    CHECK_CLOSE(src.in.av_ms2, 0.3 * SL_G, 0, 1e-15);
    CHECK_CLOSE(src.in.pgd_m, 1.4 * 36 * IN_M * 0.3, 0, 1e-12);
    CHECK(src.in.h1 == src.in.h2 && src.in.h1->damping == 0.10, "spectra");
    sl_asce_source_free(&src);
    CHECK(sl_asce_input_from_rg160(-1, &src, &err) == SL_EINVAL, "negative PGA accepted");
}

/* The ASCE input of a motion set (asce_input.h): A_v = the vertical peak,
 * ZPA_h = the LARGER horizontal peak, PGD = the 100-40 combination, the
 * spectra at 10 % on the default grid; without V, A_v = 0; without H2 an
 * error. Constant records (a = c on [0, T]) have closed-form peaks:
 * PGA = c, PGD = c T^2 / 2. */
static void test_input_from_set(void)
{
    enum { N = 201 };
    const double dt = 0.01, T = (N - 1) * dt;
    double a1[N], a2[N], av[N];
    for (int i = 0; i < N; i++) {
        a1[i] = 1.0;
        a2[i] = -2.0;
        av[i] = 0.5;
    }
    sl_motion *h1 = sl_motion_from_array(a1, N, dt, "h1"), *h2 = sl_motion_from_array(a2, N, dt, "h2"),
              *v = sl_motion_from_array(av, N, dt, "v");
    sl_set set = {h1, h2, v};
    sl_asce_source src;
    sl_error err;
    sl_error_clear(&err);
    CHECK(sl_asce_input_from_set(&set, &src, &err) == SL_OK, "%s", err.msg);
    CHECK_CLOSE(src.in.av_ms2, 0.5, 0, 1e-15);
    CHECK_CLOSE(src.in.zpa_h_ms2, 2.0, 0, 1e-15);
    double d1 = 1.0 * T * T / 2, d2 = 2.0 * T * T / 2;
    CHECK_CLOSE(src.in.pgd_m, d2 + 0.4 * d1, 0, 1e-9);
    CHECK(src.in.h1 && src.in.h1->damping == 0.10 && src.in.h1->f_hz[0] == SL_SPECTRUM_FMIN_HZ,
          "10 %% spectra on the default grid");
    sl_asce_source_free(&src);
    set.v = NULL;
    CHECK(sl_asce_input_from_set(&set, &src, &err) == SL_OK && src.in.av_ms2 == 0, "no V: A_v 0");
    sl_asce_source_free(&src);
    set.h2 = NULL;
    CHECK(sl_asce_input_from_set(&set, &src, &err) == SL_EINVAL, "no H2 accepted");
    sl_motion_free(h1);
    sl_motion_free(h2);
    sl_motion_free(v);
}

int main(void)
{
    RUN(test_input_from_set);
    RUN(test_input_from_floor);
    RUN(test_input_from_rg160);
    RUN(test_rg160_power_law_segment);
    RUN(test_rg160_constant_sd_segment);
    RUN(test_below_fmin);
    RUN(test_no_sliding);
    RUN(test_no_crossing);
    RUN(test_first_crossing);
    RUN(test_combination);
    RUN(test_bad_input);
    RUN(test_vertical);
    RUN(test_status_names);
    RUN(test_newmark);
    return HARNESS_END("asce");
}
