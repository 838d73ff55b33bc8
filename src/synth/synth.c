/* synth.c - spectrum-compatible motions: parameters, targets and the plan
 * (see synth.h, synth_internal.h and docs/synthesis.md). */
#include "synth/synth_internal.h"
#include "core/fftw_safe.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "signal/rg160.h"
#include "core/units.h"

/* The FFT length's only prime factors (FFTW's fastest codelets). */
static const unsigned synth_small_primes[] = {2, 3, 5, 7};

/* ------------------------------------------------------------------ */
/* Parameters                                                          */
/* ------------------------------------------------------------------ */

void sl_synth_params_default(sl_synth_params *p)
{
    memset(p, 0, sizeof *p);
    p->fmin_hz = SL_SPECTRUM_FMIN_HZ;
    p->fmax_hz = SL_SPECTRUM_FMAX_HZ;
    p->per_decade = SL_SPECTRUM_PER_DECADE;
    p->tol_below = SL_SYNTH_TOL_BELOW;
    p->tol_above = SL_SYNTH_TOL_ABOVE;
    p->max_run_below = SL_SYNTH_MAX_RUN_BELOW;
    p->min_d5_75_s = SL_SYNTH_MIN_D5_75_S;
    p->min_duration_s = SL_SYNTH_MIN_DURATION_S;
    p->max_corr = SL_SYNTH_MAX_CORR;
    p->end_vel_frac = SL_SYNTH_END_VEL_FRAC;
    p->end_disp_frac = SL_SYNTH_END_DISP_FRAC;
    p->max_peaks = SL_SYNTH_MAX_PEAKS;
    p->pga_tol_below = SL_SYNTH_PGA_TOL_BELOW;
    p->wavelet_rate = SL_SYNTH_WAVELET_RATE;
    p->pga_sigma = SL_SYNTH_PGA_SIGMA;
    p->wavelet_cycles = SL_SYNTH_WAVELET_CYCLES;
    p->wavelet_spread = SL_SYNTH_WAVELET_SPREAD;
    p->psd_frac = 0; /* reported, not required (docs/synthesis.md 9) */
    p->max_iter = SL_SYNTH_MAX_ITER;
    p->max_attempts = SL_SYNTH_MAX_ATTEMPTS;
    p->aim = SL_SYNTH_AIM;
    p->rise_frac = SL_SYNTH_RISE_FRAC;
    p->hold_frac = SL_SYNTH_HOLD_FRAC;
    p->end_amp = SL_SYNTH_END_AMP;
    p->taper_s = SL_SYNTH_TAPER_S;
    p->hp_frac = SL_SYNTH_HP_FRAC;
    p->hp_order = SL_SYNTH_HP_ORDER;
    p->match_margin = SL_SYNTH_MATCH_MARGIN;
    p->psd_report = 1;
}

sl_status sl_synth_params_check(const sl_synth_params *p, sl_error *err)
{
#define SYNTH_REQUIRE(cond, what)                                                    \
    do {                                                                             \
        if (!(cond))                                                                 \
            return sl_error_set(err, SL_EINVAL, NULL, 0, "synth: bad parameter: %s", \
                                what);                                               \
    } while (0)
    SYNTH_REQUIRE(p, "no parameters");
    SYNTH_REQUIRE(p->fmin_hz > 0 && isfinite(p->fmin_hz), "fmin_hz must be > 0");
    SYNTH_REQUIRE(p->fmax_hz >= p->fmin_hz && isfinite(p->fmax_hz), "fmax_hz must be >= fmin_hz");
    SYNTH_REQUIRE(p->per_decade > 0 && isfinite(p->per_decade), "per_decade must be > 0");
    SYNTH_REQUIRE(p->tol_below >= 0 && p->tol_below < 1, "tol_below must be in [0, 1)");
    SYNTH_REQUIRE(p->tol_above >= 0 && isfinite(p->tol_above), "tol_above must be >= 0");
    SYNTH_REQUIRE(p->min_d5_75_s >= 0 && isfinite(p->min_d5_75_s), "min_d5_75_s must be >= 0");
    SYNTH_REQUIRE(p->min_duration_s >= 0 && isfinite(p->min_duration_s),
                  "min_duration_s must be >= 0");
    SYNTH_REQUIRE(p->max_corr >= 0 && p->max_corr <= 1, "max_corr must be in [0, 1]");
    SYNTH_REQUIRE(p->end_vel_frac >= 0 && isfinite(p->end_vel_frac), "end_vel_frac must be >= 0");
    SYNTH_REQUIRE(p->end_disp_frac >= 0 && isfinite(p->end_disp_frac),
                  "end_disp_frac must be >= 0");
    SYNTH_REQUIRE(p->wavelet_rate >= 0 && isfinite(p->wavelet_rate), "wavelet_rate must be >= 0");
    SYNTH_REQUIRE(p->wavelet_cycles > 0 && isfinite(p->wavelet_cycles),
                  "wavelet_cycles must be > 0");
    SYNTH_REQUIRE(p->wavelet_spread >= 0 && isfinite(p->wavelet_spread),
                  "wavelet_spread must be >= 0");
    SYNTH_REQUIRE(p->pga_tol_below >= 0 && p->pga_tol_below <= 1, "pga_tol_below must be in [0, 1]");
    SYNTH_REQUIRE(p->pga_sigma >= 0 && p->pga_sigma <= 1, "pga_sigma must be in [0, 1]");
    SYNTH_REQUIRE(p->psd_frac >= 0 && isfinite(p->psd_frac), "psd_frac must be >= 0");
    SYNTH_REQUIRE(p->max_attempts >= 1, "max_attempts must be >= 1");
    SYNTH_REQUIRE(p->aim > 0 && isfinite(p->aim), "aim must be > 0");
    SYNTH_REQUIRE(p->rise_frac > 0 && p->rise_frac <= p->hold_frac && p->hold_frac < 1,
                  "envelope needs 0 < rise_frac <= hold_frac < 1");
    SYNTH_REQUIRE(p->end_amp > 0 && p->end_amp <= 1, "end_amp must be in (0, 1]");
    SYNTH_REQUIRE(p->taper_s >= 0 && isfinite(p->taper_s), "taper_s must be >= 0");
    SYNTH_REQUIRE(p->hp_frac >= 0 && p->hp_frac < 1, "hp_frac must be in [0, 1)");
    SYNTH_REQUIRE(p->match_margin >= 0 && isfinite(p->match_margin),
                  "match_margin must be >= 0");
    SYNTH_REQUIRE(p->hp_order > 0 && p->hp_order <= 32, "hp_order must be in (0, 32]");
#undef SYNTH_REQUIRE
    return SL_OK;
}

const char *sl_synth_comp_name(sl_synth_comp c)
{
    static const char *const names[SL_SYNTH_NCOMP] = {"h1", "h2", "v"};
    return (unsigned)c < SL_SYNTH_NCOMP ? names[c] : "?";
}

/* ------------------------------------------------------------------ */
/* Targets                                                             */
/* ------------------------------------------------------------------ */

sl_status sl_synth_targets_rg160(double pga_ms2, double zeta, const sl_synth_params *p,
                                 sl_spectrum *spec[SL_SYNTH_NCOMP],
                                 sl_synth_target tgt[SL_SYNTH_NCOMP], sl_error *err)
{
    sl_synth_params def;
    if (!p) {
        sl_synth_params_default(&def);
        p = &def;
    }
    for (int c = 0; c < SL_SYNTH_NCOMP; c++)
        spec[c] = NULL;
    if (!(pga_ms2 > 0) || !isfinite(pga_ms2))
        return sl_error_set(err, SL_EINVAL, NULL, 0, "synth: RG 1.60 PGA must be > 0");
    sl_status st = SL_OK;
    for (int c = 0; c < SL_SYNTH_NCOMP && !st; c++) {
        sl_rg160_dir dir = c == SL_SYNTH_V ? SL_RG160_VERTICAL : SL_RG160_HORIZONTAL;
        size_t nf = 0;
        double *f = sl_rg160_grid(dir, p->fmin_hz, p->fmax_hz, p->per_decade, &nf);
        spec[c] = f ? sl_spectrum_alloc(nf, zeta) : NULL;
        if (!spec[c]) {
            free(f);
            st = sl_error_set(err, SL_ENOMEM, NULL, 0, "synth: out of memory");
            break;
        }
        memcpy(spec[c]->f_hz, f, nf * sizeof *f);
        free(f);
        st = sl_rg160_psa(dir, zeta, pga_ms2, spec[c]->f_hz, nf, spec[c]->sa_ms2, err);
        tgt[c].spec = spec[c];
        tgt[c].zpa_ms2 = pga_ms2;
    }
    if (st)
        for (int c = 0; c < SL_SYNTH_NCOMP; c++) {
            sl_spectrum_free(spec[c]);
            spec[c] = NULL;
        }
    return st;
}

double sl_synth_floor_damping(const sl_floor *fl, sl_floor_comp c)
{
    const sl_floor_component *fc = &fl->comp[c];
    if (sl_floor_spectrum(fl, c, SL_SYNTH_DAMPING))
        return SL_SYNTH_DAMPING;
    return fc->nspec > 0 ? fc->spec[0].damping : SL_SYNTH_DAMPING; /* ascending */
}

sl_status sl_synth_targets_floor(const sl_floor *fl, double zeta,
                                 sl_synth_target tgt[SL_SYNTH_NCOMP], sl_error *err)
{
    for (int c = 0; c < SL_SYNTH_NCOMP; c++) {
        sl_floor_comp fc = (sl_floor_comp)c; /* same order H1, H2, V */
        double z = zeta > 0 ? zeta : sl_synth_floor_damping(fl, fc);
        const sl_spectrum *s = sl_floor_spectrum(fl, fc, z);
        if (!s)
            return sl_error_set(err, SL_EINVAL, fl->path, fl->comp[c].line,
                                "[%s] gives no spectrum at damping %g", sl_floor_comp_name(fc),
                                z);
        tgt[c].spec = s;
        tgt[c].zpa_ms2 = fl->comp[c].zpa_ms2;
    }
    return SL_OK;
}

sl_status sl_synth_check_target(const sl_synth_target *t, sl_error *err)
{
    if (!t || !t->spec || t->spec->n < 2 || !t->spec->f_hz || !t->spec->sa_ms2)
        return sl_error_set(err, SL_EINVAL, NULL, 0, "synth: target needs >= 2 points");
    if (!(t->spec->damping > 0 && t->spec->damping < 1))
        return sl_error_set(err, SL_EINVAL, NULL, 0, "synth: target damping %g outside (0, 1)",
                            t->spec->damping);
    if (!(t->zpa_ms2 > 0) || !isfinite(t->zpa_ms2))
        return sl_error_set(err, SL_EINVAL, NULL, 0, "synth: target ZPA must be > 0");
    for (size_t i = 0; i < t->spec->n; i++) {
        if (!(t->spec->sa_ms2[i] > 0) || !isfinite(t->spec->sa_ms2[i]) ||
            !(t->spec->f_hz[i] > 0) || (i > 0 && !(t->spec->f_hz[i] > t->spec->f_hz[i - 1])))
            return sl_error_set(err, SL_EINVAL, NULL, 0,
                                "synth: target point %zu not positive and increasing", i);
    }
    return SL_OK;
}

/* ------------------------------------------------------------------ */
/* The plan                                                            */
/* ------------------------------------------------------------------ */

/* Smallest even 2^a 3^b 5^c 7^d >= n (0 when above SYNTH_MAX_NFFT). */
static size_t good_size(size_t n)
{
    for (size_t m = n + (n & 1); m <= SYNTH_MAX_NFFT; m += 2) {
        size_t r = m;
        for (size_t q = 0; q < sizeof synth_small_primes / sizeof synth_small_primes[0]; q++)
            while (r % synth_small_primes[q] == 0)
                r /= synth_small_primes[q];
        if (r == 1)
            return m;
    }
    return 0;
}
void sl_synth_free(sl_synth *s)
{
    if (!s)
        return;
    {
        if (s->r2c)
            fftw_destroy_plan(s->r2c);
        if (s->c2r)
            fftw_destroy_plan(s->c2r);
    }
    free(s->grid);
    free(s->bin_j);
    free(s->bin_w);
    free(s->bin_ja);
    free(s->bin_jb);
    free(s->bin_fade);
    free(s->env);
    free(s->taper);
    free(s->bl[0]);
    free(s->bl[1]);
    free(s);
}

static void make_envelope(sl_synth *s)
{
    double T = s->dt * (double)(s->n - 1);
    double t1 = s->p.rise_frac * T, t2 = s->p.hold_frac * T;
    double c = log(1.0 / s->p.end_amp) / (T - t2);
    for (size_t j = 0; j < s->n; j++) {
        double t = s->dt * (double)j;
        if (t < t1)
            s->env[j] = (t / t1) * (t / t1);
        else if (t <= t2)
            s->env[j] = 1.0;
        else
            s->env[j] = exp(-c * (t - t2));
    }
}

static int make_bins(sl_synth *s)
{
    s->bin_j = malloc(s->nbin * sizeof *s->bin_j);
    s->bin_w = malloc(s->nbin * sizeof *s->bin_w);
    s->bin_ja = malloc(s->nbin * sizeof *s->bin_ja);
    s->bin_jb = malloc(s->nbin * sizeof *s->bin_jb);
    if (!s->bin_j || !s->bin_w || !s->bin_ja || !s->bin_jb)
        return -1;
    size_t ja = 0, jb = 0;
    for (size_t k = 0; k < s->nbin; k++) {
        double lo = s->df * ((double)k - 0.5), hi = s->df * ((double)k + 0.5);
        while (ja < s->ngrid && s->grid[ja] < lo)
            ja++;
        if (jb < ja)
            jb = ja;
        while (jb < s->ngrid && s->grid[jb] < hi)
            jb++;
        s->bin_ja[k] = ja;
        s->bin_jb[k] = jb;
    }
    size_t j = 0;
    for (size_t k = 0; k < s->nbin; k++) {
        double f = s->df * (double)k;
        if (s->ngrid == 1 || f <= s->grid[0]) {
            s->bin_j[k] = 0;
            s->bin_w[k] = 0;
            continue;
        }
        if (f >= s->grid[s->ngrid - 1]) {
            s->bin_j[k] = s->ngrid - 2;
            s->bin_w[k] = 1;
            continue;
        }
        while (j + 2 < s->ngrid && s->grid[j + 1] <= f)
            j++;
        s->bin_j[k] = j;
        s->bin_w[k] = log(f / s->grid[j]) / log(s->grid[j + 1] / s->grid[j]);
    }
    return 0;
}

sl_synth *sl_synth_alloc(size_t n, double dt_s, const sl_synth_params *p, sl_error *err)
{
    sl_synth_params def;
    if (!p) {
        sl_synth_params_default(&def);
        p = &def;
    }
    if (sl_synth_params_check(p, err))
        return NULL;
    if (n < SYNTH_MIN_N || !(dt_s > 0) || !isfinite(dt_s)) {
        sl_error_set(err, SL_EINVAL, NULL, 0, "synth: need >= %d samples and dt > 0",
                     SYNTH_MIN_N);
        return NULL;
    }
    double pad = ceil(1.0 / (p->fmin_hz * dt_s));
    size_t nfft = pad < (double)SYNTH_MAX_NFFT ? good_size(n + (size_t)pad) : 0;
    if (nfft == 0) {
        sl_error_set(err, SL_EINVAL, NULL, 0, "synth: motion too long for the FFT");
        return NULL;
    }
    sl_synth *s = calloc(1, sizeof *s);
    if (!s) {
        sl_error_set(err, SL_ENOMEM, NULL, 0, "synth: out of memory");
        return NULL;
    }
    s->n = n;
    s->dt = dt_s;
    s->p = *p;
    s->nfft = nfft;
    s->nbin = nfft / 2 + 1;
    s->df = 1.0 / ((double)nfft * dt_s);
    s->grid = sl_spectrum_grid(p->fmin_hz, p->fmax_hz, p->per_decade, &s->ngrid);
    s->env = malloc(n * sizeof *s->env);
    s->bl[0] = malloc(n * sizeof *s->bl[0]);
    s->bl[1] = malloc(n * sizeof *s->bl[1]);
    if (!s->grid || !s->env || !s->bl[0] || !s->bl[1] || make_bins(s)) {
        sl_synth_free(s);
        sl_error_set(err, SL_ENOMEM, NULL, 0, "synth: out of memory");
        return NULL;
    }
    make_envelope(s);
    s->bin_fade = malloc(s->nbin * sizeof *s->bin_fade);
    if (!s->bin_fade) {
        sl_synth_free(s);
        sl_error_set(err, SL_ENOMEM, NULL, 0, "synth: out of memory");
        return NULL;
    }
    for (size_t k = 0; k < s->nbin; k++)
        s->bin_fade[k] = sl_synth_edge_fade(s->df * (double)k, s->grid[0], s->grid[s->ngrid - 1]);
    /* End taper: w_j = (1 - cos(pi j/m))/2, j < m = taper_s/dt (at most n/2). */
    s->ntaper = (size_t)ceil(p->taper_s / dt_s);
    if (s->ntaper > n / 2)
        s->ntaper = n / 2;
    s->taper = malloc((s->ntaper ? s->ntaper : 1) * sizeof *s->taper);
    if (!s->taper) {
        sl_synth_free(s);
        sl_error_set(err, SL_ENOMEM, NULL, 0, "synth: out of memory");
        return NULL;
    }
    for (size_t j = 0; j < s->ntaper; j++)
        s->taper[j] = 0.5 * (1 - cos(SL_PI * (double)j / (double)s->ntaper));
    /* Baseline shapes and the 2x2 map from their coefficients to end values. */
    double T = dt_s * (double)(n - 1), m[2][2];
    for (size_t j = 0; j < n; j++) {
        double x = dt_s * (double)j / T;
        s->bl[0][j] = x * (1 - x);
        s->bl[1][j] = x * x * (1 - x);
    }
    for (int i = 0; i < 2; i++)
        sl_synth_end_values(s->bl[i], n, dt_s, &m[0][i], &m[1][i]);
    double det = m[0][0] * m[1][1] - m[0][1] * m[1][0];
    if (!(fabs(det) > 0)) {
        sl_synth_free(s);
        sl_error_set(err, SL_ESOLVER, NULL, 0, "synth: singular baseline system");
        return NULL;
    }
    s->bl_inv[0][0] = m[1][1] / det;
    s->bl_inv[0][1] = -m[0][1] / det;
    s->bl_inv[1][0] = -m[1][0] / det;
    s->bl_inv[1][1] = m[0][0] / det;
    /* FFTW plans, once, on scratch arrays of the alignment fftw_malloc gives
     * every later array (required by fftw_execute_dft_r2c/c2r). */
    double *r = fftw_malloc(nfft * sizeof *r);
    fftw_complex *c = fftw_malloc(s->nbin * sizeof *c);
    const int have_buffers = r && c;
    if (have_buffers) {
        sl_fftw_thread_safe();
        {
            s->r2c = fftw_plan_dft_r2c_1d((int)nfft, r, c, FFTW_ESTIMATE);
            s->c2r = fftw_plan_dft_c2r_1d((int)nfft, c, r, FFTW_ESTIMATE);
        }
    }
    fftw_free(r);
    fftw_free(c);
    if (!s->r2c || !s->c2r) {
        sl_synth_free(s);
        sl_error_set(err, have_buffers ? SL_ESOLVER : SL_ENOMEM, NULL, 0,
                     "synth: cannot make the FFTW plans of length %zu", nfft);
        return NULL;
    }
    return s;
}

size_t sl_synth_n(const sl_synth *s) { return s->n; }
double sl_synth_dt(const sl_synth *s) { return s->dt; }
size_t sl_synth_nfft(const sl_synth *s) { return s->nfft; }
const sl_synth_params *sl_synth_params_of(const sl_synth *s) { return &s->p; }
const double *sl_synth_envelope(const sl_synth *s) { return s->env; }

const double *sl_synth_grid(const sl_synth *s, size_t *nf)
{
    *nf = s->ngrid;
    return s->grid;
}

/* SplitMix64 (Steele, Lea and Flood 2014) finaliser. */
static uint64_t splitmix64(uint64_t x)
{
    x += UINT64_C(0x9E3779B97F4A7C15);
    x = (x ^ (x >> 30)) * UINT64_C(0xBF58476D1CE4E5B9);
    x = (x ^ (x >> 27)) * UINT64_C(0x94D049BB133111EB);
    return x ^ (x >> 31);
}

unsigned long sl_synth_stream_seed(uint64_t seed, size_t set, sl_synth_comp comp,
                                   unsigned attempt)
{
    uint64_t h = splitmix64(seed);
    h = splitmix64(h ^ (uint64_t)set);
    h = splitmix64(h ^ (uint64_t)comp);
    h = splitmix64(h ^ (uint64_t)attempt);
    return (unsigned long)(h & UINT64_C(0xFFFFFFFF));
}
