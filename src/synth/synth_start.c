/* synth_start.c - start motions: a random sum of wave packets (synth.h
 * eq. 1, docs/synthesis.md 3.1), the target on the grid, the high-pass and the
 * first gain. */
#include "synth/synth_internal.h"
#include "core/gslerr.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>

#include "core/units.h"

/* ------------------------------------------------------------------ */
/* One motion                                                          */
/* ------------------------------------------------------------------ */

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
sl_status sl_synth_set_target(sl_synth_motion *m, const sl_synth_target *t, sl_error *err)
{
    sl_status st = sl_synth_check_target(t, err);
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
    m->sharp = sl_synth_sharp_target(m);
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

/* The spread frequency draw of the start packets (docs/synthesis.md 3.1,
 * eq. 1a). On u = log(f/f0)/log(f1/f0) in [0, 1], cut into SPREAD_CELLS
 * equal cells, e(u) = T(f)^2 is the expected energy of one packet of
 * amplitude T sqrt(f) and width c/(2 f), so the log-uniform start of K0
 * packets has the expected energy E = K0 mean(e), and a packet at a narrow
 * peak carries a large share of it. The packets' density relative to the
 * log-uniform one is
 *   rel(u) = max(1, N e(u) / (K0 mean(e))),   N = wavelet_spread,
 * (K = K0 mean(rel) packets) and each packet's amplitude is divided by
 * sqrt(rel): the expected energy per log-frequency, count x amplitude^2, is
 * that of the log-uniform start, and no packet's expected energy exceeds
 * E/N. Where no packet carries more than E/N anyway (a broad spectrum),
 * rel = 1 and nothing changes. */
#define SPREAD_CELLS 64
typedef struct spread_table {
    double cdf[SPREAD_CELLS + 1];
    double rel[SPREAD_CELLS];
    double mean_rel;
} spread_table;

static void spread_init(spread_table *fo, const sl_spectrum *sp, double f0, double f1, double n_min,
                       double k0)
{
    double e[SPREAD_CELLS], mean = 0;
    for (size_t i = 0; i < SPREAD_CELLS; i++) {
        double a = target_ext(sp, f0 * pow(f1 / f0, ((double)i + 0.5) / SPREAD_CELLS));
        e[i] = a * a;
        mean += e[i] / SPREAD_CELLS;
    }
    fo->cdf[0] = 0;
    for (size_t i = 0; i < SPREAD_CELLS; i++) {
        double r = n_min * e[i] / (k0 * mean);
        fo->rel[i] = r > 1 ? r : 1;
        fo->cdf[i + 1] = fo->cdf[i] + fo->rel[i] / SPREAD_CELLS;
    }
    fo->mean_rel = fo->cdf[SPREAD_CELLS];
}

/* u in [0, 1] from a uniform x in [0, 1) by the inverse of the piecewise
 * linear CDF; *rel: the density of its cell relative to the uniform one. */
static double spread_draw(const spread_table *fo, double x, double *rel)
{
    double c = x * fo->cdf[SPREAD_CELLS];
    size_t i = 0;
    while (i + 1 < SPREAD_CELLS && fo->cdf[i + 1] <= c)
        i++;
    double width = fo->cdf[i + 1] - fo->cdf[i];
    double in = width > 0 ? (c - fo->cdf[i]) / width : 0.5;
    *rel = fo->rel[i];
    return ((double)i + (in < 0 ? 0 : in > 1 ? 1 : in)) / SPREAD_CELLS;
}

/* Start a motion from m->acc at any level: scale it by the one gain that
 * brings its spectrum to aim x target on average (log mean over the checked
 * points), then make iteration 0. */
sl_status sl_synth_start(sl_synth_motion *m, sl_error *err)
{
    const sl_synth *s = m->s;
    m->iter = 0;
    m->stride = SYNTH_COARSE_STRIDE;
    m->coarse = s->p.max_iter > 1 && (m->stride > 1 || SYNTH_COARSE_SPP < 20.0);
    if (s->p.hp_frac > 0)
        highpass(m);
    sl_status st = sl_synth_spectrum_of_acc(m, err);
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
    st = sl_synth_finish(m, err);
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

/* acc[j] += amp exp(-x^2/(2 sg^2)) cos(2 pi f x + phi), x = j dt - tk, for
 * j0 <= j <= j1 (eq. 1), by recurrences instead of an exp and a cos per
 * sample: the Gaussian as g_{j+1} = g_j q_j, q_{j+1} = q_j exp(-dt^2/sg^2)
 * (q_j = exp(-(2 x_j dt + dt^2)/(2 sg^2))), the cosine as the rotation of
 * (cos, sin) by 2 pi f dt; both restarted from the direct formula every
 * WAVELET_RESTART samples, so the relative round-off stays below about
 * WAVELET_RESTART^2 x 1e-16 (measured <= 3e-13 of the amplitude,
 * tests/test_synth.c). */
#define WAVELET_RESTART 128
void sl_synth_add_wavelet(double *acc, size_t j0, size_t j1, double dt, double tk, double amp,
                          double sg, double f, double phi)
{
    const double inv2s2 = 0.5 / (sg * sg), w = 2 * SL_PI * f;
    const double cd = cos(w * dt), sd = sin(w * dt), qq = exp(-2 * dt * dt * inv2s2);
    for (size_t js = j0; js <= j1; js += WAVELET_RESTART) {
        const size_t je = j1 - js < WAVELET_RESTART ? j1 : js + WAVELET_RESTART - 1;
        const double x0 = dt * (double)js - tk;
        double g = amp * exp(-x0 * x0 * inv2s2), q = exp(-(2 * x0 * dt + dt * dt) * inv2s2);
        double c = cos(w * x0 + phi), sn = sin(w * x0 + phi);
        for (size_t j = js; j <= je; j++) {
            acc[j] += g * c;
            g *= q;
            q *= qq;
            const double c1 = c * cd - sn * sd;
            sn = sn * cd + c * sd;
            c = c1;
        }
    }
}

/* m->acc <- the sum of K Gabor wavelets (eq. 1), drawn from rng. */
static void sum_packets(sl_synth_motion *m, const sl_synth_target *t, gsl_rng *rng)
{
    const sl_synth *s = m->s;
    /* A sum of K Gabor wavelets (Gaussian-windowed cosines of
     * wavelet_cycles cycles within +-1 standard deviation... see
     * docs/synthesis.md 3.1):
     *   a(t) = sum_q A_q exp(-(t - t_q)^2/(2 s_q^2)) cos(2 pi f_q (t - t_q) + phi_q),
     *   s_q = cycles/(2 f_q), f_q log-uniform on [f0, f1] (or by eq. 1a), t_q drawn
     *   with density E(t)^2, phi_q uniform, A_q = T(f_q) sqrt(f_q),
     * K = rate x log2(f1/f0) x 0.4 T (0.4 T: the energy width of E^2). */
    const double f0 = SL_SYNTH_WAVELET_FLO_FRAC * t->spec->f_hz[0];
    const double f1 = t->spec->f_hz[t->spec->n - 1];
    const double T = s->dt * (double)(s->n - 1), nc = s->p.wavelet_cycles;
    /* Only for narrow-band floor targets (SA/ZPA above SYNTH_CREST_AMP, where
     * the peak-count check does not apply), and not with the mode sweep,
     * which carries the peak band of the sharpest ones: a ground-like
     * target keeps the log-uniform start (spread on RG 1.60 raised the
     * horizontals' peaks above 0.9 PGA from 2.1 to 2.8 a motion). */
    const double spread = m->sharp == SYNTH_SHARP_CREST ? s->p.wavelet_spread : 0;
    const size_t K0 = (size_t)ceil(s->p.wavelet_rate * log2(f1 / f0) * T * 0.4);
    spread_table fo;
    fo.mean_rel = 1;
    if (spread > 0)
        spread_init(&fo, t->spec, f0, f1, spread, (double)K0);
    const size_t K = spread > 0 ? (size_t)ceil((double)K0 * fo.mean_rel) : K0;
    for (size_t j = 0; j < s->n; j++)
        m->acc[j] = 0;
    for (size_t q = 0; q < K; q++) {
        double rel = 1, x = gsl_rng_uniform(rng);
        double f = f0 * pow(f1 / f0, spread > 0 ? spread_draw(&fo, x, &rel) : x);
        size_t jt;
        do { /* rejection sampling of t_q with density E^2 */
            jt = (size_t)(gsl_rng_uniform(rng) * (double)s->n);
            if (jt >= s->n)
                jt = s->n - 1;
        } while (gsl_rng_uniform(rng) > s->env[jt] * s->env[jt]);
        double phi = 2 * SL_PI * gsl_rng_uniform(rng);
        double amp = target_ext(t->spec, f) * sqrt(f / rel);
        double sg = nc / (2 * f), tk = s->dt * (double)jt;
        double ja = floor((tk - 3 * sg) / s->dt), jb = ceil((tk + 3 * sg) / s->dt);
        size_t j0 = ja < 0 ? 0 : (size_t)ja;
        size_t j1 = jb >= (double)(s->n - 1) ? s->n - 1 : (size_t)jb;
        sl_synth_add_wavelet(m->acc, j0, j1, s->dt, tk, amp, sg, f, phi);
    }
}

sl_status sl_synth_set_random(sl_synth_motion *m, const sl_synth_target *t, uint64_t seed,
                              size_t set, sl_synth_comp comp, unsigned attempt, sl_error *err)
{
    m->ready = 0;
    m->record = 0;
    sl_status st = sl_synth_set_target(m, t, err);
    if (st)
        return st;
    const sl_synth *s = m->s;
    sl_gsl_quiet_begin(); /* GSL's handler off: a failure is a status (gslerr.h) */
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    sl_gsl_quiet_end();
    if (!rng)
        return sl_error_set(err, SL_ENOMEM, NULL, 0, "synth: out of memory");
    gsl_rng_set(rng, sl_synth_stream_seed(seed, set, comp, attempt));
    if (s->p.wavelet_rate > 0) {
        sum_packets(m, t, rng);
        if (m->sharp & SYNTH_SHARP_SWEEP) /* very sharp targets: eq. S1 (synth_sharp.c) */
            sl_synth_add_mode_sweep(m, rng);
        m->level = peak_level(&s->p, rng);
        gsl_rng_free(rng);
        m->attempt = attempt;
        m->knee = SL_SYNTH_KNEE;
        return sl_synth_start(m, err);
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
    return sl_synth_start(m, err);
}
