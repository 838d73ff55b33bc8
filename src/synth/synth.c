/* synth.c - spectrum-compatible motions by iterative Fourier-amplitude
 * correction (see synth.h and docs/synthesis.md). */
#include "synth/synth.h"

#include <fftw3.h>
#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "io/atomic.h"
#include "signal/rg160.h"
#include "core/units.h"

/* Coarse phase: the iteration first computes and checks the spectrum at
 * every SYNTH_COARSE_STRIDE-th grid point (33 per decade by default) on
 * SYNTH_COARSE_SPP sub-steps per period (sampled-peak error <= 1 - cos(pi/6)
 * = 13 %, less on average), with a margin SYNTH_COARSE_MARGIN inside the
 * band; only the final iterations compute every point at full accuracy
 * (20 sub-steps per period). docs/synthesis.md 3.3. */
#define SYNTH_COARSE_STRIDE 3
#define SYNTH_COARSE_SPP 6.0
/* Multirate ratio of the coarse phase's spectrum (spectrum.h eq. M1): each
 * oscillator at f runs at the lowest rate fs/2^l >= SYNTH_COARSE_RATIO f.
 * Synthetic motions only; records keep the single-rate coarse spectrum. */
#define SYNTH_COARSE_RATIO 20.0
/* Over-relaxation of the correction: X_k *= r^SYNTH_RELAX (1.6: 10 iterations
 * per component against 16 at 1.0, RG 1.60, 12 sets). */
#define SYNTH_RELAX 1.6
/* Iterations without improvement after which an attempt is given up. */
#define SYNTH_STALL 8u
#define SYNTH_COARSE_MARGIN 0.02
/* Smallest motion handled, samples. */
#define SYNTH_MIN_N 16
/* Largest FFT length accepted (a guard against absurd options). */
#define SYNTH_MAX_NFFT ((size_t)1 << 28)
/* The FFT length's only prime factors (FFTW's fastest codelets). */
/* A target is rigid at its end when its SA at the last frequency is within
 * this factor of its ZPA (set_target; compress_peaks eq. C2). */
#define SYNTH_RIGID_RATIO 1.1

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

static sl_status check_target(const sl_synth_target *t, sl_error *err)
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

struct sl_synth {
    size_t n;            /* motion samples */
    double dt;           /* s */
    size_t nfft;         /* N, even */
    size_t nbin;         /* N/2 + 1 */
    double df;           /* 1/(N dt), Hz */
    sl_synth_params p;
    double *grid;        /* check grid, Hz */
    size_t ngrid;
    size_t *bin_j;       /* bin k: r(f_k) = r_j^(1 - w) r_{j+1}^w ... */
    double *bin_w;
    size_t *bin_ja;      /* ... or, when grid points [ja, jb) fall in the */
    size_t *bin_jb;      /* bin's cell f_k +- df/2, the mean of their ln r */
    double *env;         /* n: envelope */
    double *taper;       /* ntaper: half-cosine end taper, 0 at the end sample */
    size_t ntaper;
    double *bl[2];       /* n: baseline shapes (t/T)(1 - t/T) (t/T)^i */
    double bl_inv[2][2]; /* inverse of the end-value matrix of the shapes */
    fftw_plan r2c, c2r;  /* on fftw_malloc'd arrays of N reals, N/2 + 1 complexes */
};

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

/* End values (v(T), d(T)) of a from rest by the exact piecewise-linear
 * integration of motion.h. */
static void end_values(const double *a, size_t n, double dt, double *v_end, double *d_end)
{
    double v = 0, d = 0;
    for (size_t i = 0; i + 1 < n; i++) {
        d += dt * v + dt * dt * (2 * a[i] + a[i + 1]) / 6;
        v += dt * (a[i] + a[i + 1]) / 2;
    }
    *v_end = v;
    *d_end = d;
}

void sl_synth_free(sl_synth *s)
{
    if (!s)
        return;
#pragma omp critical(sl_fftw_planner)
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
        end_values(s->bl[i], n, dt_s, &m[0][i], &m[1][i]);
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
#pragma omp critical(sl_fftw_planner)
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

/* ------------------------------------------------------------------ */
/* One motion                                                          */
/* ------------------------------------------------------------------ */

struct sl_synth_motion {
    const sl_synth *s;
    int ready;             /* a set_* succeeded */
    double zpa;            /* m/s^2 */
    double damping;
    const sl_spectrum *tspec; /* the target spectrum (borrowed) */
    double fc_hz;          /* compression: content above this only (compress_peaks) */
    double knee;           /* compression knee: SL_SYNTH_KNEE, records SL_SYNTH_KNEE_RECORD */
    double level;          /* compression level / ZPA (peak_level()) */
    int record;            /* started from a record: dead-band correction */
    size_t j_lo, j_hi;     /* checked grid points [j_lo, j_hi) */
    int rigid_end;         /* the target's end SA within SYNTH_RIGID_RATIO of its ZPA */
    unsigned iter;         /* iterations since set_* */
    unsigned attempt;
    double *tgt;           /* grid: target (NAN outside) */
    double *psa;           /* grid: spectrum of the current iterate */
    double *lnr;           /* grid: ln of the correction ratio */
    double *hp;            /* nbin: high-pass magnitude H(f_k) (set_target) */
    fftw_complex *cwork;   /* nbin */
    double *rwork;         /* N */
    double *acc;           /* n: current iterate */
    double *best_acc;      /* n: best iterate */
    double *best_psa;      /* grid */
    double best_score;     /* violation of the best iterate (0 = passes) */
    int coarse;            /* coarse phase: spectrum at every stride-th point */
    size_t stride;         /* SYNTH_COARSE_STRIDE, on SYNTH_COARSE_SPP sub-steps */
    unsigned best_iter;
    /* Spectrum plans of the checked range (coefficients made once, remade
     * when the range or damping changes): full accuracy, and the coarse
     * phase's points (multirate, SYNTH_COARSE_RATIO). */
    sl_spectrum_plan *plan_full, *plan_coarse;
    size_t plan_lo, plan_hi;
    double plan_zeta;
    int plan_record;       /* records: coarse phase without multirate (its worst
                            * error, 10 % at 0.1 Hz on records, steers a
                            * dead-band match astray: docs/synthesis.md 3.2) */
    size_t *cidx;          /* ngrid: grid index of each coarse point */
    size_t ncoarse;
    double *cval;          /* ngrid: coarse spectrum values */
};

void sl_synth_motion_free(sl_synth_motion *m)
{
    if (!m)
        return;
    free(m->tgt);
    free(m->psa);
    free(m->lnr);
    free(m->hp);
    fftw_free(m->cwork);
    fftw_free(m->rwork);
    free(m->acc);
    free(m->best_acc);
    free(m->best_psa);
    free(m->cidx);
    free(m->cval);
    sl_spectrum_plan_free(m->plan_full);
    sl_spectrum_plan_free(m->plan_coarse);
    free(m);
}

sl_synth_motion *sl_synth_motion_alloc(const sl_synth *s, sl_error *err)
{
    sl_synth_motion *m = calloc(1, sizeof *m);
    if (!m) {
        sl_error_set(err, SL_ENOMEM, NULL, 0, "synth: out of memory");
        return NULL;
    }
    m->s = s;
    m->tgt = malloc(s->ngrid * sizeof *m->tgt);
    m->psa = malloc(s->ngrid * sizeof *m->psa);
    m->lnr = malloc(s->ngrid * sizeof *m->lnr);
    m->hp = malloc(s->nbin * sizeof *m->hp);
    m->best_psa = malloc(s->ngrid * sizeof *m->best_psa);
    m->cwork = fftw_malloc(s->nbin * sizeof *m->cwork);
    m->rwork = fftw_malloc(s->nfft * sizeof *m->rwork);
    m->acc = malloc(s->n * sizeof *m->acc);
    m->best_acc = malloc(s->n * sizeof *m->best_acc);
    m->cidx = malloc(s->ngrid * sizeof *m->cidx);
    m->cval = malloc(s->ngrid * sizeof *m->cval);
    if (!m->tgt || !m->psa || !m->lnr || !m->hp || !m->best_psa || !m->cwork || !m->rwork ||
        !m->acc || !m->best_acc || !m->cidx || !m->cval) {
        sl_synth_motion_free(m);
        sl_error_set(err, SL_ENOMEM, NULL, 0, "synth: out of memory");
        return NULL;
    }
    return m;
}

/* Target on the grid and the checked range. */
static sl_status set_target(sl_synth_motion *m, const sl_synth_target *t, sl_error *err)
{
    sl_status st = check_target(t, err);
    if (st)
        return st;
    const sl_synth *s = m->s;
    m->zpa = t->zpa_ms2;
    m->damping = t->spec->damping;
    m->tspec = t->spec;
    /* half the frequency of the target's largest SA */
    size_t jp = 0;
    for (size_t j = 1; j < t->spec->n; j++)
        jp = t->spec->sa_ms2[j] > t->spec->sa_ms2[jp] ? j : jp;
    m->fc_hz = SL_SYNTH_COMPRESS_FC_FRAC * t->spec->f_hz[jp];
    m->j_lo = s->ngrid;
    m->j_hi = 0;
    /* A tiny relative slack admits grid points equal to the target's end
     * frequencies up to rounding. */
    const double slack = 1e-12;
    const double tf0 = t->spec->f_hz[0], tf1 = t->spec->f_hz[t->spec->n - 1];
    for (size_t j = 0; j < s->ngrid; j++) {
        double f = s->grid[j];
        if (f >= tf0 * (1 - slack) && f <= tf1 * (1 + slack)) {
            double fc = f < tf0 ? tf0 : f > tf1 ? tf1 : f;
            m->tgt[j] = sl_spectrum_interp(t->spec, fc);
            if (m->j_lo == s->ngrid)
                m->j_lo = j;
            m->j_hi = j + 1;
        } else {
            m->tgt[j] = NAN;
        }
    }
    /* Rigid at its end: T at the last frequency within a factor
     * SYNTH_RIGID_RATIO of the ZPA (compress_peaks eq. C2 raises the PGA
     * of such targets' motions). Otherwise the ZPA and the spectrum
     * disagree, and the low PGA is reported (sl_synth_check.pga_zpa), not
     * forced. */
    const double tend = t->spec->sa_ms2[t->spec->n - 1];
    m->rigid_end = tend <= SYNTH_RIGID_RATIO * m->zpa && tend * SYNTH_RIGID_RATIO >= m->zpa;
    if (m->j_lo >= m->j_hi)
        return sl_error_set(err, SL_EINVAL, NULL, 0,
                            "synth: the target (%g-%g Hz) does not overlap the check grid "
                            "(%g-%g Hz)",
                            tf0, tf1, s->grid[0], s->grid[s->ngrid - 1]);
    /* Zero-phase Butterworth high-pass magnitude at fc = hp_frac x f_lo:
     * H(f) = 1/sqrt(1 + (fc/f)^(2 order)) (H(0) = 0: no mean). */
    const double fc = s->p.hp_frac * s->grid[m->j_lo];
    m->hp[0] = 0;
    for (size_t k = 1; k < s->nbin; k++)
        m->hp[k] = fc > 0 ? 1 / sqrt(1 + pow(fc / (s->df * (double)k), 2 * s->p.hp_order)) : 1;
    return SL_OK;
}

/* m->acc <- the high-pass H of m->acc (zero-padded DFT, first n samples). */
static void highpass(sl_synth_motion *m)
{
    const sl_synth *s = m->s;
    for (size_t j = 0; j < s->nfft; j++)
        m->rwork[j] = j < s->n ? m->acc[j] : 0.0;
    fftw_execute_dft_r2c(s->r2c, m->rwork, m->cwork);
    for (size_t k = 0; k < s->nbin; k++) {
        m->cwork[k][0] *= m->hp[k];
        m->cwork[k][1] *= m->hp[k];
    }
    fftw_execute_dft_c2r(s->c2r, m->cwork, m->rwork);
    const double inv_n = 1.0 / (double)s->nfft;
    for (size_t j = 0; j < s->n; j++)
        m->acc[j] = m->rwork[j] * inv_n;
}

/* Target PSA at any frequency: log-log inside, constant SD below, constant
 * above (for the initial amplitudes only). */
static double target_ext(const sl_spectrum *sp, double f)
{
    double f0 = sp->f_hz[0], f1 = sp->f_hz[sp->n - 1];
    if (f <= f0)
        return sp->sa_ms2[0] * (f / f0) * (f / f0);
    if (f >= f1)
        return sp->sa_ms2[sp->n - 1];
    return sl_spectrum_interp(sp, f);
}

/* Spectral checks of psa against the target over the checked range. */
typedef struct spec_check {
    double min_ratio, f_min, max_ratio, f_max;
    size_t run, n_below;
} spec_check;

static void spectral_check(const sl_synth_motion *m, const double *psa, spec_check *c)
{
    const sl_synth *s = m->s;
    c->min_ratio = INFINITY;
    c->max_ratio = -INFINITY;
    c->f_min = c->f_max = NAN;
    c->run = c->n_below = 0;
    size_t run = 0;
    for (size_t j = m->j_lo; j < m->j_hi; j++) {
        double r = psa[j] / m->tgt[j];
        if (m->coarse) {
            if (isnan(psa[j]))
                continue; /* not computed in the coarse phase */
            /* coarse phase: a margin inside the band for the points between */
            r = r < 1 ? r - SYNTH_COARSE_MARGIN : r + SYNTH_COARSE_MARGIN;
        }
        if (!(r >= c->min_ratio)) { /* also takes NaN, so NaN fails the check */
            c->min_ratio = r;
            c->f_min = s->grid[j];
        }
        if (r > c->max_ratio) {
            c->max_ratio = r;
            c->f_max = s->grid[j];
        }
        if (!(r >= 1)) {
            run += m->coarse ? m->stride : 1;
            c->n_below++;
            if (run > c->run)
                c->run = run;
        } else {
            run = 0;
        }
    }
}

/* Violation of the spectral limits: 0 when every one holds. */
static double violation(const sl_synth_params *p, const spec_check *c, size_t npoints)
{
    double v = 0;
    double lo = 1 - p->tol_below, hi = 1 + p->tol_above;
    if (!(c->min_ratio >= lo))
        v += isnan(c->min_ratio) ? INFINITY : lo - c->min_ratio;
    if (!(c->max_ratio <= hi))
        v += isnan(c->max_ratio) ? INFINITY : c->max_ratio - hi;
    if (c->run > p->max_run_below)
        v += (double)(c->run - p->max_run_below) / (double)npoints;
    return v;
}

/* The plans of the checked range [j_lo, j_hi) at m->damping, remade only
 * when these change. */
static sl_status make_plans(sl_synth_motion *m, sl_error *err)
{
    const sl_synth *s = m->s;
    if (m->plan_full && m->plan_lo == m->j_lo && m->plan_hi == m->j_hi &&
        m->plan_zeta == m->damping && m->plan_record == m->record)
        return SL_OK;
    sl_spectrum_plan_free(m->plan_full);
    sl_spectrum_plan_free(m->plan_coarse);
    m->plan_full = m->plan_coarse = NULL;
    /* coarse points: j_lo, j_lo + stride, ..., and j_hi - 1 */
    size_t nc = 0;
    for (size_t j = m->j_lo; j < m->j_hi; j += SYNTH_COARSE_STRIDE)
        m->cidx[nc++] = j;
    if (m->cidx[nc - 1] != m->j_hi - 1)
        m->cidx[nc++] = m->j_hi - 1;
    m->ncoarse = nc;
    for (size_t q = 0; q < nc; q++)
        m->cval[q] = s->grid[m->cidx[q]];
    sl_spectrum_opts o;
    sl_spectrum_opts_default(&o);
    m->plan_full = sl_spectrum_plan_alloc(s->n, s->dt, s->grid + m->j_lo, m->j_hi - m->j_lo,
                                          m->damping, &o, 0.0, err);
    o.steps_per_period = SYNTH_COARSE_SPP;
    o.free_vibration = 0; /* coarse: no free-vibration tail (about 10 % of the time) */
    if (m->plan_full)
        m->plan_coarse = sl_spectrum_plan_alloc(s->n, s->dt, m->cval, nc, m->damping, &o,
                                                m->record ? 0.0 : SYNTH_COARSE_RATIO, err);
    if (!m->plan_full || !m->plan_coarse) {
        sl_spectrum_plan_free(m->plan_full);
        m->plan_full = NULL;
        return err ? err->code : SL_ENOMEM;
    }
    m->plan_lo = m->j_lo;
    m->plan_hi = m->j_hi;
    m->plan_zeta = m->damping;
    m->plan_record = m->record;
    return SL_OK;
}

/* Spectrum of m->acc into m->psa: at every checked grid point at full
 * accuracy, or in the coarse phase at the coarse points (NAN elsewhere). */
static sl_status spectrum_of_acc(sl_synth_motion *m, sl_error *err)
{
    const sl_synth *s = m->s;
    for (size_t j = 0; j < s->ngrid; j++)
        m->psa[j] = NAN;
    sl_status st = make_plans(m, err);
    if (st)
        return st;
    if (!m->coarse)
        return sl_spectrum_plan_compute(m->plan_full, m->acc, m->psa + m->j_lo, NULL, NULL,
                                        err);
    st = sl_spectrum_plan_compute(m->plan_coarse, m->acc, m->cval, NULL, NULL, err);
    for (size_t q = 0; q < m->ncoarse && !st; q++)
        m->psa[m->cidx[q]] = m->cval[q];
    return st;
}

/* Soft-knee compression of the peaks (the time-domain part of matching the
 * high-frequency end, SA -> PGA; as REQPY's local PGA correction). With
 * L = aim x ZPA, K = knee x L and P = max|a| > L: the motion is split
 * exactly into a_low (DFT bins below fc = SL_SYNTH_COMPRESS_FC_FRAC x the
 * frequency of the target's largest SA) and
 * a_high = a - a_low; every half-cycle of a (samples between two sign
 * changes) whose peak x exceeds K has its a_high part multiplied by y(x)/x,
 *     y(x) = K + (x - K) (L - K)/(P - K),
 * the linear map of [K, P] onto [K, L]. Half-cycles keep their zero
 * crossings and shape, peaks keep their order with their spacing shrunk in
 * proportion: no flat tops and no run of equal peaks (the count above
 * 0.9 PGA is checked, sl_synth_check.peaks); the long-period content is
 * untouched. The spectral step does the rest. Returns the number of
 * half-cycles scaled. */
static size_t compress_peaks(sl_synth_motion *m, double level, double knee)
{
    const sl_synth *s = m->s;
    double *a = m->acc;
    const size_t n = s->n;
    double pk = 0;
    for (size_t i = 0; i < n; i++)
        pk = fabs(a[i]) > pk ? fabs(a[i]) : pk;
    /* Expansion (eq. C2; synthetic motions for a target rigid at its end,
     * set_target): when P < L, K = knee x P and the same map
     *     y(x) = K + (x - K)(L - K)/(P - K)
     * takes [K, P] onto [K, L] with a gain > 1: the high-frequency part of
     * the half-cycles above knee x P is raised so that the PGA comes to
     * about L. Without it the correction lifts SA at the rigid end by
     * resonant content near the end frequency instead of by the peak
     * (SA(50 Hz)/PGA 1.10-1.22, PGA 0.86-0.93 ZPA on physical floor
     * spectra; docs/synthesis.md 3.3, 10). Records: compression only. */
    const int expand = !(pk > level);
    if (expand && (m->record || !m->rigid_end || !(pk > 0)))
        return 0;
    const double K = knee * (expand ? pk : level);
    /* a_low into rwork (first n samples) */
    for (size_t j = 0; j < s->nfft; j++)
        m->rwork[j] = j < n ? a[j] : 0.0;
    fftw_execute_dft_r2c(s->r2c, m->rwork, m->cwork);
    for (size_t k = 0; k < s->nbin; k++)
        if (s->df * (double)k >= m->fc_hz)
            m->cwork[k][0] = m->cwork[k][1] = 0;
    fftw_execute_dft_c2r(s->c2r, m->cwork, m->rwork);
    const double inv_n = 1.0 / (double)s->nfft;
    size_t count = 0, i = 0;
    while (i < n) {
        size_t j = i;
        double hp = 0;
        while (j < n && (a[j] >= 0) == (a[i] >= 0)) {
            hp = fabs(a[j]) > hp ? fabs(a[j]) : hp;
            j++;
        }
        if (hp > K) {
            double g = (K + (hp - K) * (level - K) / (pk - K)) / hp;
            for (size_t q = i; q < j; q++) {
                double lo = m->rwork[q] * inv_n;
                a[q] = lo + g * (a[q] - lo);
            }
            count++;
        }
        i = j;
    }
    return count;
}

/* Make m->acc (any level) an admissible iterate: end taper and baseline
 * correction (no peak limiting, no peak scaling: the PGA is what the
 * spectral matching of the high-frequency end makes it); then its spectrum,
 * and keep it if it is the best so far. */
static sl_status finish(sl_synth_motion *m, sl_error *err)
{
    const sl_synth *s = m->s;
    const size_t n = s->n;
    for (size_t j = 0; j < s->ntaper && j < n; j++) {
        m->acc[j] *= s->taper[j];
        m->acc[n - 1 - j] *= s->taper[j];
    }
    compress_peaks(m, m->level * m->zpa, m->knee);
    /* Baseline: subtract c0 bl0 + c1 bl1 so that v(T) = d(T) = 0. */
    double ve, de;
    end_values(m->acc, n, s->dt, &ve, &de);
    double c0 = s->bl_inv[0][0] * ve + s->bl_inv[0][1] * de;
    double c1 = s->bl_inv[1][0] * ve + s->bl_inv[1][1] * de;
    double peak = 0;
    for (size_t j = 0; j < n; j++) {
        m->acc[j] -= c0 * s->bl[0][j] + c1 * s->bl[1][j];
        double x = fabs(m->acc[j]);
        peak = x > peak ? x : peak;
    }
    if (!(peak > 0) || !isfinite(peak))
        return sl_error_set(err, SL_ESOLVER, NULL, 0, "synth: motion vanished or overflowed");
    sl_status st = spectrum_of_acc(m, err);
    if (st)
        return st;
    spec_check c;
    spectral_check(m, m->psa, &c);
    double v = violation(&s->p, &c, m->j_hi - m->j_lo);
    if (m->iter == 0 || v < m->best_score) {
        m->best_score = v;
        m->best_iter = m->iter;
        memcpy(m->best_acc, m->acc, n * sizeof *m->acc);
        memcpy(m->best_psa, m->psa, s->ngrid * sizeof *m->psa);
    }
    return SL_OK;
}

/* Start a motion from m->acc at any level: scale it by the one gain that
 * brings its spectrum to aim x target on average (log mean over the checked
 * points), then make iteration 0. */
static sl_status start(sl_synth_motion *m, sl_error *err)
{
    const sl_synth *s = m->s;
    m->iter = 0;
    m->stride = SYNTH_COARSE_STRIDE;
    m->coarse = s->p.max_iter > 1 && (m->stride > 1 || SYNTH_COARSE_SPP < 20.0);
    if (s->p.hp_frac > 0)
        highpass(m);
    sl_status st = spectrum_of_acc(m, err);
    if (st)
        return st;
    double sum = 0;
    size_t cnt = 0;
    for (size_t j = m->j_lo; j < m->j_hi; j++)
        if (!isnan(m->psa[j])) {
            sum += log(s->p.aim * m->tgt[j] / m->psa[j]);
            cnt++;
        }
    double gain = exp(sum / (double)(cnt ? cnt : 1));
    if (!isfinite(gain) || !(gain > 0))
        return sl_error_set(err, SL_ESOLVER, NULL, 0, "synth: cannot set the level");
    for (size_t j = 0; j < s->n; j++)
        m->acc[j] *= gain;
    st = finish(m, err);
    m->ready = st == SL_OK;
    return st;
}

/* The peak level of a synthetic motion, as a fraction of the ZPA: real
 * motions sharing one mean spectrum scatter in PGA (the physical floor
 * motions of tests/test_physical_floors.c: coefficient of variation about
 * 0.15), and a block with mu g near the ZPA slides in the motions whose peak
 * exceeds it. So each motion draws its level from a lognormal of median
 * aim and log standard deviation pga_sigma, kept 0.02 inside the spectral
 * band [1 - tol_below, 1 + tol_above]; pga_sigma = 0 gives aim. */
static double peak_level(const sl_synth_params *p, gsl_rng *rng)
{
    double z = gsl_ran_gaussian_ziggurat(rng, 1.0);
    double l = p->aim * exp(p->pga_sigma * z);
    double lo = 1 - p->tol_below + 0.02, hi = 1 + p->tol_above - 0.02;
    return p->pga_sigma > 0 ? (l < lo ? lo : l > hi ? hi : l) : p->aim;
}

sl_status sl_synth_set_random(sl_synth_motion *m, const sl_synth_target *t, uint64_t seed,
                              size_t set, sl_synth_comp comp, unsigned attempt, sl_error *err)
{
    m->ready = 0;
    m->record = 0;
    sl_status st = set_target(m, t, err);
    if (st)
        return st;
    const sl_synth *s = m->s;
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    if (!rng)
        return sl_error_set(err, SL_ENOMEM, NULL, 0, "synth: out of memory");
    gsl_rng_set(rng, sl_synth_stream_seed(seed, set, comp, attempt));
    if (s->p.wavelet_rate > 0) {
        /* A sum of K Gabor wavelets (Gaussian-windowed cosines of
         * wavelet_cycles cycles within +-1 standard deviation... see
         * docs/synthesis.md 3.1):
         *   a(t) = sum_q A_q exp(-(t - t_q)^2/(2 s_q^2)) cos(2 pi f_q (t - t_q) + phi_q),
         *   s_q = cycles/(2 f_q), f_q log-uniform on [f0, f1], t_q drawn
         *   with density E(t)^2, phi_q uniform, A_q = T(f_q) sqrt(f_q),
         * K = rate x log2(f1/f0) x 0.4 T (0.4 T: the energy width of E^2). */
        const double f0 = SL_SYNTH_WAVELET_FLO_FRAC * t->spec->f_hz[0];
        const double f1 = t->spec->f_hz[t->spec->n - 1];
        const double T = s->dt * (double)(s->n - 1), nc = s->p.wavelet_cycles;
        const size_t K = (size_t)ceil(s->p.wavelet_rate * log2(f1 / f0) * T * 0.4);
        for (size_t j = 0; j < s->n; j++)
            m->acc[j] = 0;
        for (size_t q = 0; q < K; q++) {
            double f = f0 * pow(f1 / f0, gsl_rng_uniform(rng));
            size_t jt;
            do { /* rejection sampling of t_q with density E^2 */
                jt = (size_t)(gsl_rng_uniform(rng) * (double)s->n);
                if (jt >= s->n)
                    jt = s->n - 1;
            } while (gsl_rng_uniform(rng) > s->env[jt] * s->env[jt]);
            double phi = 2 * SL_PI * gsl_rng_uniform(rng);
            double amp = target_ext(t->spec, f) * sqrt(f);
            double sg = nc / (2 * f), tk = s->dt * (double)jt;
            double ja = floor((tk - 3 * sg) / s->dt), jb = ceil((tk + 3 * sg) / s->dt);
            size_t j0 = ja < 0 ? 0 : (size_t)ja;
            size_t j1 = jb >= (double)(s->n - 1) ? s->n - 1 : (size_t)jb;
            for (size_t j = j0; j <= j1; j++) {
                double x = s->dt * (double)j - tk;
                m->acc[j] += amp * exp(-0.5 * x * x / (sg * sg)) * cos(2 * SL_PI * f * x + phi);
            }
        }
        m->level = peak_level(&s->p, rng);
        gsl_rng_free(rng);
        m->attempt = attempt;
        m->knee = SL_SYNTH_KNEE;
        return start(m, err);
    }
    m->cwork[0][0] = m->cwork[0][1] = 0;
    for (size_t k = 1; k < s->nbin; k++) {
        double f = s->df * (double)k;
        /* no content above the target's last frequency: the PGA is then
         * the high-frequency end of the matched spectrum (SA -> PGA) */
        double amp = f > t->spec->f_hz[t->spec->n - 1] ? 0.0 : target_ext(t->spec, f) / sqrt(f);
        double phi = 2 * SL_PI * gsl_rng_uniform(rng);
        m->cwork[k][0] = amp * cos(phi);
        m->cwork[k][1] = amp * sin(phi);
    }
    m->level = peak_level(&s->p, rng);
    gsl_rng_free(rng);
    m->knee = SL_SYNTH_KNEE;
    m->cwork[s->nbin - 1][1] = 0; /* the Nyquist bin of a real signal is real */
    /* The stationary motion (FFTW c2r, unnormalised: divide by N) times the
     * envelope. */
    fftw_execute_dft_c2r(s->c2r, m->cwork, m->rwork);
    const double inv_n = 1.0 / (double)s->nfft;
    for (size_t j = 0; j < s->n; j++)
        m->acc[j] = m->rwork[j] * inv_n * s->env[j];
    m->attempt = attempt;
    return start(m, err);
}

sl_status sl_synth_set_record(sl_synth_motion *m, const sl_synth_target *t,
                              const double *acc_ms2, size_t n, sl_error *err)
{
    m->ready = 0;
    const sl_synth *s = m->s;
    if (!acc_ms2 || n == 0 || n > s->n)
        return sl_error_set(err, SL_EINVAL, NULL, 0,
                            "synth: record of %zu samples does not fit the plan (%zu)", n,
                            s->n);
    sl_status st = set_target(m, t, err);
    if (st)
        return st;
    double amax = 0;
    for (size_t j = 0; j < s->n; j++) {
        double x = j < n ? acc_ms2[j] : 0.0;
        if (!isfinite(x))
            return sl_error_set(err, SL_EINVAL, NULL, 0, "synth: record sample %zu not finite",
                                j);
        amax = fabs(x) > amax ? fabs(x) : amax;
        m->acc[j] = x;
    }
    if (!(amax > 0))
        return sl_error_set(err, SL_EINVAL, NULL, 0, "synth: record is all zeros");
    m->attempt = 0;
    m->knee = SL_SYNTH_KNEE_RECORD;
    m->level = s->p.aim;
    m->record = 1;
    return start(m, err);
}

/* End of the coarse phase: the best iterate and its spectrum at every
 * checked point at full accuracy (the checks are always made on this). */
static sl_status end_coarse(sl_synth_motion *m, sl_error *err)
{
    const sl_synth *s = m->s;
    m->coarse = 0;
    memcpy(m->acc, m->best_acc, s->n * sizeof *m->acc);
    sl_status st = spectrum_of_acc(m, err);
    if (st) {
        m->ready = 0;
        return st;
    }
    spec_check c;
    spectral_check(m, m->psa, &c);
    m->best_score = violation(&s->p, &c, m->j_hi - m->j_lo);
    memcpy(m->best_psa, m->psa, s->ngrid * sizeof *m->psa);
    return SL_OK;
}

sl_status sl_synth_iterate(sl_synth_motion *m, sl_error *err)
{
    if (!m->ready)
        return sl_error_set(err, SL_EINVAL, NULL, 0, "synth: iterate before set");
    const sl_synth *s = m->s;
    if (m->coarse && (m->best_score == 0 || m->iter + 1 >= s->p.max_iter)) {
        sl_status st = end_coarse(m, err);
        if (!st)
            m->iter++;
        return st;
    }
    const double lo = -log(SL_SYNTH_RATIO_CLAMP), hi = log(SL_SYNTH_RATIO_CLAMP);
    /* records: the dead band where S/T already complies (no correction) */
    const double band_lo = m->record && s->p.match_margin > 0 ? 1 + s->p.match_margin : INFINITY;
    const double band_hi = 1 + s->p.tol_above - s->p.match_margin;
    size_t jprev = m->j_lo;
    for (size_t j = m->j_lo; j < m->j_hi; j++) {
        if (isnan(m->psa[j]) && m->coarse)
            continue;
        double ratio = m->psa[j] / m->tgt[j];
        /* records: no correction inside the dead band; elsewhere (and for
         * synthetic motions) towards aim x T */
        double x = ratio >= band_lo && ratio <= band_hi
                       ? 0.0
                       : SYNTH_RELAX * log(s->p.aim * m->tgt[j] / m->psa[j]);
        if (!isfinite(x)) {
            m->ready = 0;
            return sl_error_set(err, SL_ESOLVER, NULL, 0, "synth: spectrum not finite at %g Hz",
                                s->grid[j]);
        }
        m->lnr[j] = x < lo ? lo : x > hi ? hi : x;
        for (size_t q = jprev + 1; q < j; q++) /* coarse phase: linear between */
            m->lnr[q] = m->lnr[jprev] +
                        (m->lnr[j] - m->lnr[jprev]) * (double)(q - jprev) / (double)(j - jprev);
        jprev = j;
    }
    for (size_t j = 0; j < m->j_lo; j++)
        m->lnr[j] = m->lnr[m->j_lo];
    for (size_t j = m->j_hi; j < s->ngrid; j++)
        m->lnr[j] = m->lnr[m->j_hi - 1];
    /* X = DFT of the current iterate, zero-padded (FFTW r2c, unnormalised). */
    for (size_t j = 0; j < s->nfft; j++)
        m->rwork[j] = j < s->n ? m->acc[j] : 0.0;
    fftw_execute_dft_r2c(s->r2c, m->rwork, m->cwork);
    /* X_k *= r(f_k). Outside the checked range the correction fades
     * out linearly in log2 f over SL_SYNTH_EDGE_OCTAVES: those bins have no
     * check of their own, and a full correction there drifts. */
    const double f_lo = s->grid[m->j_lo], f_hi = s->grid[m->j_hi - 1];
    for (size_t k = 1; k < s->nbin; k++) {
        size_t j = s->bin_j[k];
        double w = s->bin_w[k], f = s->df * (double)k, x = 0;
        if (s->bin_jb[k] > s->bin_ja[k]) {
            for (size_t q = s->bin_ja[k]; q < s->bin_jb[k]; q++)
                x += m->lnr[q];
            x /= (double)(s->bin_jb[k] - s->bin_ja[k]);
        } else {
            x = s->ngrid == 1 ? m->lnr[0] : (1 - w) * m->lnr[j] + w * m->lnr[j + 1];
        }
        double oct = f < f_lo ? log2(f_lo / f) : f > f_hi ? log2(f / f_hi) : 0.0;
        double fade = oct >= SL_SYNTH_EDGE_OCTAVES ? 0.0 : 1.0 - oct / SL_SYNTH_EDGE_OCTAVES;
        double g = exp(fade * x) * m->hp[k]; /* correction, then the high-pass */
        m->cwork[k][0] *= g;
        m->cwork[k][1] *= g;
    }
    m->cwork[0][0] = m->cwork[0][1] = 0; /* no mean */
    fftw_execute_dft_c2r(s->c2r, m->cwork, m->rwork);
    const double inv_n = 1.0 / (double)s->nfft;
    for (size_t j = 0; j < s->n; j++)
        m->acc[j] = m->rwork[j] * inv_n;
    m->iter++;
    sl_status st = finish(m, err);
    if (st)
        m->ready = 0;
    return st;
}

int sl_synth_test(const sl_synth_motion *m)
{
    return m->ready && !m->coarse && m->best_score == 0;
}

unsigned sl_synth_iterations(const sl_synth_motion *m) { return m->iter; }

const double *sl_synth_acc(const sl_synth_motion *m) { return m->best_acc; }
const double *sl_synth_psa(const sl_synth_motion *m) { return m->best_psa; }
const double *sl_synth_target_psa(const sl_synth_motion *m) { return m->tgt; }

void sl_synth_check_motion(const sl_synth_motion *m, sl_synth_check *out)
{
    const sl_synth *s = m->s;
    const sl_synth_params *p = &s->p;
    memset(out, 0, sizeof *out);
    spec_check c;
    spectral_check(m, m->best_psa, &c);
    out->damping = m->damping;
    out->f_lo_hz = s->grid[m->j_lo];
    out->f_hi_hz = s->grid[m->j_hi - 1];
    out->npoints = m->j_hi - m->j_lo;
    out->min_ratio = c.min_ratio;
    out->f_min_ratio_hz = c.f_min;
    out->max_ratio = c.max_ratio;
    out->f_max_ratio_hz = c.f_max;
    out->run_below = c.run;
    out->n_below = c.n_below;
    /* Integrals and peaks of the best iterate (piecewise-linear, exact). */
    const double *a = m->best_acc;
    const double dt = s->dt;
    double v = 0, d = 0, pv = 0, pd = 0, pa = fabs(a[0]);
    for (size_t i = 0; i + 1 < s->n; i++) {
        d += dt * v + dt * dt * (2 * a[i] + a[i + 1]) / 6;
        v += dt * (a[i] + a[i + 1]) / 2;
        pv = fabs(v) > pv ? fabs(v) : pv;
        pd = fabs(d) > pd ? fabs(d) : pd;
        pa = fabs(a[i + 1]) > pa ? fabs(a[i + 1]) : pa;
    }
    sl_motion tmp = {.path = NULL, .label = NULL, .n = s->n, .dt_s = dt,
                     .acc_ms2 = m->best_acc};
    out->d5_75_s = sl_motion_d5_75(&tmp);
    out->duration_s = dt * (double)(s->n - 1);
    out->pga_ms2 = pa;
    out->zpa_ms2 = m->zpa;
    out->pgv_ms = pv;
    out->pgd_m = pd;
    out->v_end_ms = v;
    out->d_end_m = d;
    out->max_corr = NAN;
    out->corr_record = out->peaks_record = NAN;
    out->iterations = m->best_iter;
    out->attempt = m->attempt;
    out->ok_below = c.min_ratio >= 1 - p->tol_below;
    out->ok_above = c.max_ratio <= 1 + p->tol_above;
    out->ok_run = c.run <= p->max_run_below;
    out->ok_d5_75 = out->d5_75_s >= p->min_d5_75_s;
    /* Compare with a tolerance of rounding so that 4000 x 0.005 passes 20 s. */
    out->ok_duration = out->duration_s >= p->min_duration_s * (1 - 1e-9);
    out->ok_end = fabs(v) <= p->end_vel_frac * pv && fabs(d) <= p->end_disp_frac * pd;
    /* PGA/ZPA inside the spectral band (SA at the high-frequency end is the
     * PGA; nothing pins it). */
    out->pga_zpa = pa / m->zpa;
    /* The spectrum's high-frequency end bounds the PGA only when the motion
     * has little content near the highest checked frequency; a PGA far below
     * the ZPA means the target's ZPA and its spectrum disagree (or the
     * motion resonates the stiff oscillators): below 1 - pga_tol_below
     * fails. */
    /* Checked when the target is rigid at its end (SA within 5 % of its
     * last value over the last 0.6 octave, as RG 1.60 from 33 to 50 Hz);
     * a spectrum cut while still falling only bounds the PGA from above. */
    const sl_spectrum *ts = m->tspec;
    double fe = ts->f_hz[ts->n - 1], se = ts->sa_ms2[ts->n - 1];
    double sb = fe / 1.5 >= ts->f_hz[0] ? sl_spectrum_interp(ts, fe / 1.5) : NAN;
    int rigid = sb <= 1.05 * se && sb >= se / 1.05;
    out->ok_pga = out->pga_zpa <= 1 + p->tol_above &&
                  (!rigid || out->pga_zpa >= 1 - p->pga_tol_below);
    out->peaks = sl_realism_peaks_above(m->best_acc, s->n, SL_REALISM_PEAK_FRAC);
    /* Checked for broadband (ground-like) targets, max SA/ZPA <= 
     * SL_SYNTH_PEAKS_MAX_AMP; narrow-band floor targets are reported only
     * (docs/synthesis.md 9). */
    double amp = 0;
    for (size_t j = m->j_lo; j < m->j_hi; j++)
        amp = m->tgt[j] / m->zpa > amp ? m->tgt[j] / m->zpa : amp;
    out->ok_peaks = amp > SL_SYNTH_PEAKS_MAX_AMP || out->peaks <= p->max_peaks;
    sl_realism_ratios(pa, pv, pd, &out->va_s, &out->adv2);
    double da;
    sl_error e;
    if (sl_realism_expected(m->tspec, &out->va_expect_s, &da, &out->adv2_expect, &e)) {
        out->va_expect_s = out->adv2_expect = NAN;
    }
    sl_psd_check pc;
    out->ok_psd = 1;
    out->psd_min_ratio = out->f_psd_min_hz = NAN;
    if (!sl_psd_check_motion(m->best_acc, s->n, dt, m->tspec, p->psd_frac, SL_PSD_FMIN_HZ,
                             SL_PSD_FMAX_HZ, &pc, &e)) {
        out->psd_min_ratio = pc.min_ratio;
        out->f_psd_min_hz = pc.f_min_ratio_hz;
        out->ok_psd = p->psd_frac > 0 ? pc.ok : 1; /* 0: reported only */
    }
    out->ok_corr = 1;
    out->pass = out->ok_below && out->ok_above && out->ok_run && out->ok_d5_75 &&
                out->ok_duration && out->ok_end && out->ok_pga && out->ok_peaks && out->ok_psd;
}

double sl_synth_corr(const double *a, const double *b, size_t n)
{
    if (n == 0)
        return 0;
    double ma = 0, mb = 0;
    for (size_t i = 0; i < n; i++) {
        ma += a[i];
        mb += b[i];
    }
    ma /= (double)n;
    mb /= (double)n;
    double sab = 0, saa = 0, sbb = 0;
    for (size_t i = 0; i < n; i++) {
        double x = a[i] - ma, y = b[i] - mb;
        sab += x * y;
        saa += x * x;
        sbb += y * y;
    }
    if (!(saa > 0) || !(sbb > 0))
        return 0;
    return sab / sqrt(saa * sbb);
}

/* ------------------------------------------------------------------ */
/* Sets                                                                */
/* ------------------------------------------------------------------ */

/* The slot of component c in an sl_set. */
static sl_motion **set_slot(sl_set *st, sl_synth_comp c)
{
    return c == SL_SYNTH_H1 ? &st->h1 : c == SL_SYNTH_H2 ? &st->h2 : &st->v;
}

sl_motion *sl_synth_set_motion(const sl_synth_set *s, sl_synth_comp c)
{
    if (!s || (unsigned)c >= SL_SYNTH_NCOMP)
        return NULL;
    return *set_slot((sl_set *)&s->set, c);
}

void sl_synth_set_clear(sl_synth_set *set)
{
    if (!set)
        return;
    for (int c = 0; c < SL_SYNTH_NCOMP; c++)
        sl_motion_free(*set_slot(&set->set, (sl_synth_comp)c));
    memset(set, 0, sizeof *set);
}

/* One motion run: set, then iterate until the test passes or the cap. */
typedef struct job {
    size_t set;           /* index into out */
    sl_synth_comp comp;
    unsigned attempt;
    const double *rec;    /* record samples (match), else NULL */
    size_t rec_n;
    double *acc;          /* result, n samples (malloc'd) */
    sl_synth_check check;
    sl_status st;
    sl_error err;
} job;

static void run_job(const sl_synth *s, sl_synth_motion *m, const sl_synth_target *t,
                    uint64_t seed, size_t set_index, job *jb)
{
    sl_error_clear(&jb->err);
    jb->st = jb->rec ? sl_synth_set_record(m, t, jb->rec, jb->rec_n, &jb->err)
                     : sl_synth_set_random(m, t, seed, set_index, jb->comp, jb->attempt,
                                           &jb->err);
    /* Stagnation: an attempt whose best iterate has not improved for
     * SYNTH_STALL iterations is given up (the next attempt, with new
     * phases, is cheaper than the rest of the cap: CPU time of 20 RG 1.60
     * sets 3.6 s without, 3.1-3.3 s with 6-8; docs/synthesis.md 8). */
    while (!jb->st && !sl_synth_test(m) && sl_synth_iterations(m) < s->p.max_iter &&
           sl_synth_iterations(m) < m->best_iter + SYNTH_STALL)
        jb->st = sl_synth_iterate(m, &jb->err);
    /* An attempt given up in the coarse phase is redone, unless it is the
     * last: then its best iterate gets the full-accuracy spectrum, so that
     * what is reported is checked on it (a redone attempt's checks only
     * decide the redo, and a coarse failure is a failure either way). */
    if (!jb->st && m->coarse && (jb->rec || jb->attempt + 1 >= s->p.max_attempts))
        jb->st = end_coarse(m, &jb->err);
    if (jb->st)
        return;
    sl_synth_check_motion(m, &jb->check);
    jb->check.corr_record = jb->check.peaks_record = NAN;
    if (jb->rec) {
        jb->check.corr_record = sl_synth_corr(sl_synth_acc(m), jb->rec, jb->rec_n);
        jb->check.peaks_record =
            (double)sl_realism_peaks_above(jb->rec, jb->rec_n, SL_REALISM_PEAK_FRAC);
    }
    if (!jb->acc)
        jb->acc = malloc(s->n * sizeof *jb->acc);
    if (!jb->acc) {
        jb->st = sl_error_set(&jb->err, SL_ENOMEM, NULL, 0, "synth: out of memory");
        return;
    }
    memcpy(jb->acc, sl_synth_acc(m), s->n * sizeof *jb->acc);
}

/* Run jobs[idx[0..nidx-1]] in parallel; each thread has its own workspace.
 * Returns the first failure in index order (err filled). */
static sl_status run_jobs(const sl_synth *s, const sl_synth_target tgt[SL_SYNTH_NCOMP],
                          uint64_t seed, size_t first_set, job *jobs, const size_t *idx,
                          size_t nidx, size_t *done, size_t total, sl_synth_progress progress,
                          void *ctx, sl_error *err)
{
    long long nj = (long long)nidx;
#pragma omp parallel
    {
        sl_error e;
        sl_synth_motion *m = sl_synth_motion_alloc(s, &e);
#pragma omp for schedule(dynamic, 1)
        for (long long q = 0; q < nj; q++) {
            job *jb = &jobs[idx[q]];
            if (!m) {
                jb->st = sl_error_set(&jb->err, SL_ENOMEM, NULL, 0, "synth: out of memory");
                continue;
            }
            run_job(s, m, &tgt[jb->comp], seed, first_set + jb->set, jb);
#pragma omp critical(sl_synth_progress)
            {
                (*done)++;
                if (progress)
                    progress(ctx, *done, total);
            }
        }
        sl_synth_motion_free(m);
    }
    for (size_t q = 0; q < nidx; q++) {
        job *jb = &jobs[idx[q]];
        if (jb->st)
            return sl_error_set(err, jb->st, NULL, 0, "%s", jb->err.msg);
    }
    return SL_OK;
}

static const int synth_pairs[SL_SYNTH_NPAIR][2] = {
    {SL_SYNTH_H1, SL_SYNTH_H2}, {SL_SYNTH_H1, SL_SYNTH_V}, {SL_SYNTH_H2, SL_SYNTH_V}};

/* Correlations of set `k` (jobs k*3 + c); returns the pair with the largest
 * |rho| above the limit, or -1. */
static int set_corr(const sl_synth *s, job *jb3, double corr[SL_SYNTH_NPAIR])
{
    int worst = -1;
    double worst_r = s->p.max_corr;
    for (int q = 0; q < SL_SYNTH_NPAIR; q++) {
        job *a = &jb3[synth_pairs[q][0]], *b = &jb3[synth_pairs[q][1]];
        if (!a->acc || !b->acc) {
            corr[q] = NAN;
            continue;
        }
        size_t n = s->n;
        if (a->rec && b->rec)
            n = a->rec_n < b->rec_n ? a->rec_n : b->rec_n;
        corr[q] = sl_synth_corr(a->acc, b->acc, n);
        if (fabs(corr[q]) > worst_r) {
            worst_r = fabs(corr[q]);
            worst = q;
        }
    }
    return worst;
}

/* Fill out[k] from the jobs (motions copied into sl_motion). */
static sl_status collect(const sl_synth *s, job *jobs, size_t count, const char *prefix,
                         size_t first_set, sl_synth_set *out, sl_error *err)
{
    int all_pass = 1;
    for (size_t k = 0; k < count; k++) {
        sl_synth_set *o = &out[k];
        memset(o, 0, sizeof *o);
        job *jb3 = &jobs[k * SL_SYNTH_NCOMP];
        set_corr(s, jb3, o->corr);
        o->pass = 1;
        for (int c = 0; c < SL_SYNTH_NCOMP; c++) {
            job *jb = &jb3[c];
            if (!jb->acc)
                continue;
            char label[64];
            if (prefix)
                snprintf(label, sizeof label, "%s_%s", prefix, sl_synth_comp_name((sl_synth_comp)c));
            else
                snprintf(label, sizeof label, "set%02zu_%s", first_set + k + 1,
                         sl_synth_comp_name((sl_synth_comp)c));
            sl_motion **slot = set_slot(&o->set, (sl_synth_comp)c);
            *slot = sl_motion_from_array(jb->acc, s->n, s->dt, label);
            if (!*slot) {
                for (size_t q = 0; q <= k; q++)
                    sl_synth_set_clear(&out[q]);
                return sl_error_set(err, SL_ENOMEM, NULL, 0, "synth: out of memory");
            }
            o->check[c] = jb->check;
            double mc = NAN;
            for (int q = 0; q < SL_SYNTH_NPAIR; q++)
                if ((synth_pairs[q][0] == c || synth_pairs[q][1] == c) && !isnan(o->corr[q]))
                    mc = isnan(mc) || fabs(o->corr[q]) > mc ? fabs(o->corr[q]) : mc;
            o->check[c].max_corr = mc;
            o->check[c].ok_corr = isnan(mc) || mc <= s->p.max_corr;
            o->check[c].pass = o->check[c].pass && o->check[c].ok_corr;
            o->pass = o->pass && o->check[c].pass;
        }
        all_pass = all_pass && o->pass;
    }
    return all_pass ? SL_OK : SL_ENOCONV;
}

static void free_jobs(job *jobs, size_t nj)
{
    if (!jobs)
        return;
    for (size_t i = 0; i < nj; i++)
        free(jobs[i].acc);
    free(jobs);
}

sl_status sl_synth_make_sets(const sl_synth *s, const sl_synth_target tgt[SL_SYNTH_NCOMP],
                             uint64_t seed, size_t first_set, size_t count,
                             sl_synth_set *out, sl_synth_progress progress, void *ctx,
                             sl_error *err)
{
    if (count == 0)
        return SL_OK;
    for (int c = 0; c < SL_SYNTH_NCOMP; c++)
        if (check_target(&tgt[c], err))
            return SL_EINVAL;
    size_t nj = count * SL_SYNTH_NCOMP;
    job *jobs = calloc(nj, sizeof *jobs);
    size_t *idx = malloc(nj * sizeof *idx);
    if (!jobs || !idx) {
        free(jobs);
        free(idx);
        return sl_error_set(err, SL_ENOMEM, NULL, 0, "synth: out of memory");
    }
    for (size_t i = 0; i < nj; i++) {
        jobs[i].set = i / SL_SYNTH_NCOMP;
        jobs[i].comp = (sl_synth_comp)(i % SL_SYNTH_NCOMP);
        idx[i] = i;
    }
    size_t done = 0, total = nj, nidx = nj;
    sl_status st = SL_OK;
    /* Rounds: run the pending jobs, then redo (next attempt) every component
     * that failed its spectral or D5-75 checks and the later component of each set's
     * worst correlated pair, while attempts remain. Every decision depends
     * only on results, so the rounds are the same for any thread count. */
    while (nidx > 0) {
        st = run_jobs(s, tgt, seed, first_set, jobs, idx, nidx, &done, total, progress, ctx,
                      err);
        if (st)
            break;
        nidx = 0;
        for (size_t k = 0; k < count; k++) {
            job *jb3 = &jobs[k * SL_SYNTH_NCOMP];
            int redo[SL_SYNTH_NCOMP] = {0, 0, 0};
            for (int c = 0; c < SL_SYNTH_NCOMP; c++) {
                const sl_synth_check *ck = &jb3[c].check;
                redo[c] = !(ck->ok_below && ck->ok_above && ck->ok_run && ck->ok_d5_75 &&
                            ck->ok_pga && ck->ok_peaks && ck->ok_psd);
            }
            double corr[SL_SYNTH_NPAIR];
            int q = set_corr(s, jb3, corr);
            if (q >= 0 && !redo[synth_pairs[q][0]])
                redo[synth_pairs[q][1]] = 1;
            for (int c = 0; c < SL_SYNTH_NCOMP; c++)
                if (redo[c] && jb3[c].attempt + 1 < s->p.max_attempts) {
                    jb3[c].attempt++;
                    idx[nidx++] = k * SL_SYNTH_NCOMP + (size_t)c;
                }
        }
        total += nidx;
    }
    if (!st)
        st = collect(s, jobs, count, NULL, first_set, out, err);
    free_jobs(jobs, nj);
    free(idx);
    return st;
}

sl_status sl_synth_make_set(const sl_synth *s, const sl_synth_target tgt[SL_SYNTH_NCOMP],
                            uint64_t seed, size_t set, sl_synth_set *out, sl_error *err)
{
    return sl_synth_make_sets(s, tgt, seed, set, 1, out, NULL, NULL, err);
}

sl_status sl_synth_match_set(const sl_synth *s, const sl_synth_target tgt[SL_SYNTH_NCOMP],
                             const sl_motion *const rec[SL_SYNTH_NCOMP], sl_synth_set *out,
                             sl_error *err)
{
    job jobs[SL_SYNTH_NCOMP];
    size_t idx[SL_SYNTH_NCOMP], nidx = 0;
    memset(jobs, 0, sizeof jobs);
    for (int c = 0; c < SL_SYNTH_NCOMP; c++) {
        jobs[c].comp = (sl_synth_comp)c;
        if (!rec[c])
            continue;
        if (fabs(rec[c]->dt_s - s->dt) > 1e-9 * s->dt || rec[c]->n > s->n)
            return sl_error_set(err, SL_EINVAL, rec[c]->path, 0,
                                "synth: record (%zu samples at %g s) does not fit the plan "
                                "(%zu at %g s)",
                                rec[c]->n, rec[c]->dt_s, s->n, s->dt);
        if (check_target(&tgt[c], err))
            return SL_EINVAL;
        jobs[c].rec = rec[c]->acc_ms2;
        jobs[c].rec_n = rec[c]->n;
        idx[nidx++] = (size_t)c;
    }
    if (nidx == 0)
        return sl_error_set(err, SL_EINVAL, NULL, 0, "synth: no record to match");
    size_t done = 0;
    sl_status st = run_jobs(s, tgt, 0, 0, jobs, idx, nidx, &done, nidx, NULL, NULL, err);
    if (!st)
        st = collect(s, jobs, 1, "match", 0, out, err);
    for (int c = 0; c < SL_SYNTH_NCOMP; c++)
        free(jobs[c].acc);
    return st;
}

/* ------------------------------------------------------------------ */
/* Other dampings of a floor file                                      */
/* ------------------------------------------------------------------ */

/* Component c of every set against table `spec` (damping z): per-motion
 * and set-mean S/T on the plan's grid inside the table's range, into
 * check[c].other[q]. */
static sl_status check_one_damping(const sl_synth *s, const sl_spectrum *spec,
                                   sl_synth_set *sets, size_t nsets, sl_synth_comp c, size_t q,
                                   sl_error *err)
{
    const double slack = 1e-12; /* as set_target */
    const double f0 = spec->f_hz[0], f1 = spec->f_hz[spec->n - 1];
    size_t ja = s->ngrid, jb = 0;
    for (size_t j = 0; j < s->ngrid; j++)
        if (s->grid[j] >= f0 * (1 - slack) && s->grid[j] <= f1 * (1 + slack)) {
            ja = ja == s->ngrid ? j : ja;
            jb = j + 1;
        }
    for (size_t k = 0; k < nsets; k++) {
        sl_synth_other *o = &sets[k].check[c].other[q];
        o->damping = spec->damping;
        o->min_ratio = o->max_ratio = o->set_min = o->set_max = NAN;
        o->f_set_min_hz = o->f_set_max_hz = NAN;
        o->ok_set = 1;
    }
    if (ja >= jb)
        return SL_OK; /* no grid point inside the table: nothing to check */
    const size_t nf = jb - ja;
    double *tgt = malloc(nf * sizeof *tgt);
    double *sum = calloc(nf, sizeof *sum);
    double *psa = malloc(nsets * nf * sizeof *psa);
    if (!tgt || !sum || !psa) {
        free(tgt);
        free(sum);
        free(psa);
        return sl_error_set(err, SL_ENOMEM, NULL, 0, "synth: out of memory");
    }
    for (size_t j = 0; j < nf; j++) {
        double f = s->grid[ja + j];
        tgt[j] = sl_spectrum_interp(spec, f < f0 ? f0 : f > f1 ? f1 : f);
    }
    sl_status st = SL_OK;
    long long nk = (long long)nsets;
#pragma omp parallel for schedule(dynamic, 1)
    for (long long k = 0; k < nk; k++) {
        const sl_motion *mo = sl_synth_set_motion(&sets[k], c);
        sl_error e;
        sl_status sk = sl_spectrum_compute(mo->acc_ms2, mo->n, mo->dt_s, s->grid + ja, nf,
                                           spec->damping, psa + (size_t)k * nf, NULL, NULL, &e);
        if (sk) {
#pragma omp critical(sl_synth_dampings)
            if (!st)
                st = sl_error_set(err, sk, NULL, 0, "%s", e.msg);
        }
    }
    for (size_t k = 0; k < nsets && !st; k++) {
        sl_synth_other *o = &sets[k].check[c].other[q];
        o->min_ratio = INFINITY;
        o->max_ratio = -INFINITY;
        for (size_t j = 0; j < nf; j++) {
            double r = psa[k * nf + j] / tgt[j];
            o->min_ratio = r < o->min_ratio ? r : o->min_ratio;
            o->max_ratio = r > o->max_ratio ? r : o->max_ratio;
            sum[j] += r; /* summed in set order: the same bits for any thread count */
        }
    }
    if (!st) {
        double lo = INFINITY, hi = -INFINITY, flo = NAN, fhi = NAN;
        for (size_t j = 0; j < nf; j++) {
            double r = sum[j] / (double)nsets;
            if (r < lo) {
                lo = r;
                flo = s->grid[ja + j];
            }
            if (r > hi) {
                hi = r;
                fhi = s->grid[ja + j];
            }
        }
        int ok = lo >= 1 - s->p.tol_below && hi <= 1 + s->p.tol_above;
        for (size_t k = 0; k < nsets; k++) {
            sl_synth_other *o = &sets[k].check[c].other[q];
            o->set_min = lo;
            o->set_max = hi;
            o->f_set_min_hz = flo;
            o->f_set_max_hz = fhi;
            o->ok_set = ok;
        }
    }
    free(tgt);
    free(sum);
    free(psa);
    return st;
}

sl_status sl_synth_check_dampings(const sl_synth *s, const sl_floor *fl, sl_synth_set *sets,
                                  size_t nsets, sl_error *err)
{
    if (!s || !fl || !sets || nsets == 0)
        return sl_error_set(err, SL_EINVAL, NULL, 0, "synth: no sets to check");
    /* (components absent from a set, as with records, are skipped) */
    for (int c = 0; c < SL_SYNTH_NCOMP; c++) {
        int absent = 0; /* records: a component not given is not checked */
        for (size_t k = 0; k < nsets; k++) {
            sets[k].check[c].n_other = 0;
            absent = absent || !sl_synth_set_motion(&sets[k], (sl_synth_comp)c);
        }
        if (absent)
            continue;
        const sl_floor_component *fc = &fl->comp[c];
        const double zm = sets[0].check[c].damping;
        size_t q = 0;
        for (size_t i = 0; i < fc->nspec && q < SL_SYNTH_MAX_OTHER; i++) {
            const sl_spectrum *sp = &fc->spec[i];
            if (fabs(sp->damping - zm) <= SL_FLOOR_DAMPING_TOL * (zm > 1 ? zm : 1))
                continue; /* the damping matched */
            sl_status st = check_one_damping(s, sp, sets, nsets, (sl_synth_comp)c, q, err);
            if (st)
                return st;
            q++;
        }
        for (size_t k = 0; k < nsets; k++)
            sets[k].check[c].n_other = q;
    }
    return SL_OK;
}

int sl_synth_dampings_ok(const sl_synth_set *sets, size_t nsets)
{
    for (size_t k = 0; k < nsets; k++)
        for (int c = 0; c < SL_SYNTH_NCOMP; c++)
            for (size_t q = 0; q < sets[k].check[c].n_other; q++)
                if (!sets[k].check[c].other[q].ok_set)
                    return 0;
    return 1;
}

/* ------------------------------------------------------------------ */
/* Input and output                                                    */
/* ------------------------------------------------------------------ */

double *sl_synth_resample(const double *acc_ms2, size_t n, double dt_s, double dt_new_s,
                          size_t *n_new)
{
    *n_new = 0;
    if (!acc_ms2 || n == 0 || !(dt_s > 0) || !(dt_new_s > 0) || !isfinite(dt_s) ||
        !isfinite(dt_new_s))
        return NULL;
    double dur = dt_s * (double)(n - 1);
    /* A relative slack keeps the last sample when dur/dt_new is whole. */
    double cnt = floor(dur / dt_new_s * (1 + 1e-12)) + 1;
    if (cnt > (double)SYNTH_MAX_NFFT)
        return NULL;
    size_t m = (size_t)cnt;
    double *out = malloc(m * sizeof *out);
    if (!out)
        return NULL;
    for (size_t j = 0; j < m; j++) {
        double x = dt_new_s * (double)j / dt_s;
        size_t i = (size_t)x;
        if (i + 1 >= n) {
            out[j] = acc_ms2[n - 1];
            continue;
        }
        double w = x - (double)i;
        out[j] = acc_ms2[i] + w * (acc_ms2[i + 1] - acc_ms2[i]);
    }
    *n_new = m;
    return out;
}

double sl_synth_match_dt(double dt_s)
{
    /* the slack keeps dt itself when it is SL_SYNTH_MAX_DT_S up to rounding */
    double k = ceil(dt_s / SL_SYNTH_MAX_DT_S * (1 - 1e-9));
    return dt_s / (k < 1 ? 1 : k);
}

sl_motion *sl_synth_resample_motion(const sl_motion *m, double dt_s)
{
    if (!m || !(dt_s > 0))
        return NULL;
    if (fabs(m->dt_s - dt_s) <= 1e-9 * dt_s)
        return sl_motion_copy(m);
    size_t n2 = 0;
    double *a = sl_synth_resample(m->acc_ms2, m->n, m->dt_s, dt_s, &n2);
    sl_motion *r = a ? sl_motion_from_array(a, n2, dt_s, m->label) : NULL;
    free(a);
    if (r && m->path) {
        char *p = strdup(m->path);
        if (!p) {
            sl_motion_free(r);
            return NULL;
        }
        free(r->path);
        r->path = p;
    }
    return r;
}

sl_status sl_synth_write_at2(const char *path, const sl_motion *m, const char *title,
                             sl_error *err)
{
    sl_atomic *a = sl_atomic_open(path, err);
    if (!a)
        return err ? err->code : SL_EIO;
    FILE *f = sl_atomic_file(a);
    fprintf(f, "SEISLIDE SYNTHETIC MOTION\n%s\nACCELERATION TIME SERIES IN UNITS OF G\n",
            title && *title ? title : (m->label ? m->label : ""));
    fprintf(f, "NPTS= %zu, DT= %.10g SEC\n", m->n, m->dt_s);
    /* Values per line in the PEER layout. */
    enum { PER_LINE = 5 };
    for (size_t i = 0; i < m->n; i++) {
        fprintf(f, " %16.9E", m->acc_ms2[i] / SL_G);
        if ((i + 1) % PER_LINE == 0 || i + 1 == m->n)
            fputc('\n', f);
    }
    return sl_atomic_commit(a, err);
}
