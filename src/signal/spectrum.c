/* spectrum.c - Nigam-Jennings response spectra (see spectrum.h). */
#include "signal/spectrum.h"
#include "core/fftw_safe.h"
#include "signal/spectrum_kernel.h"

#include "core/units.h"

#include <fftw3.h>
#include <math.h>
#include <omp.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* Relative tolerance for deciding that two grid frequencies coincide. */
#define GRID_REL_TOL 1e-12


void sl_spectrum_opts_default(sl_spectrum_opts *o)
{
    o->steps_per_period = SL_SPECTRUM_STEPS_PER_PERIOD;
    o->free_vibration = 1;
}

double *sl_spectrum_grid(double fmin_hz, double fmax_hz, double per_decade, size_t *n)
{
    *n = 0;
    if (!(fmin_hz > 0) || !isfinite(fmin_hz) || !isfinite(fmax_hz) || fmax_hz < fmin_hz ||
        !(per_decade > 0) || !isfinite(per_decade))
        return NULL;
    double decades = log10(fmax_hz / fmin_hz);
    double k = ceil(per_decade * decades - GRID_REL_TOL * per_decade);
    if (k < 0)
        k = 0;
    if (k > 1e7)
        return NULL;
    size_t m = (size_t)k + 1;
    double *f = malloc(m * sizeof *f);
    if (!f)
        return NULL;
    f[0] = fmin_hz;
    for (size_t i = 1; i + 1 < m; i++)
        f[i] = fmin_hz * pow(10.0, decades * (double)i / k);
    if (m > 1)
        f[m - 1] = fmax_hz;
    *n = m;
    return f;
}

/* ---- the stepping kernel -------------------------------------------- */

static sl_status check_args(const double *acc, size_t n, double dt, const double *f,
                            size_t nf, double zeta, const sl_spectrum_opts *o,
                            sl_error *err)
{
    if (!acc || n == 0)
        return sl_error_set(err, SL_EINVAL, NULL, 0, "spectrum: empty record");
    if (!(dt > 0) || !isfinite(dt))
        return sl_error_set(err, SL_EINVAL, NULL, 0, "spectrum: time step %g s must be positive",
                            dt);
    if (!(zeta >= 0 && zeta < 1))
        return sl_error_set(err, SL_EINVAL, NULL, 0, "spectrum: damping %g outside [0, 1)", zeta);
    if (!(o->steps_per_period >= 1) || !isfinite(o->steps_per_period))
        return sl_error_set(err, SL_EINVAL, NULL, 0,
                            "spectrum: steps per period %g must be at least 1",
                            o->steps_per_period);
    for (size_t j = 0; j < nf; j++) {
        if (!(f[j] > 0) || !isfinite(f[j]))
            return sl_error_set(err, SL_EINVAL, NULL, 0,
                                "spectrum: frequency %g Hz must be positive and finite", f[j]);
        if (!(dt * f[j] * o->steps_per_period <= SL_SPECTRUM_MAX_SUBSTEPS))
            return sl_error_set(err, SL_EINVAL, NULL, 0,
                                "spectrum: %g Hz at dt %g s needs more than %g sub-steps per "
                                "sample",
                                f[j], dt, SL_SPECTRUM_MAX_SUBSTEPS);
    }
    for (size_t i = 0; i < n; i++)
        if (!isfinite(acc[i]))
            return sl_error_set(err, SL_EINVAL, NULL, 0,
                                "spectrum: sample %zu is not finite", i);
    return SL_OK;
}

/* Sub-steps per input step for one frequency. */
static size_t substeps_for(double f, double dt, double spp)
{
    double m = ceil(dt * f * spp);
    return m < 1 ? 1 : (size_t)m;
}

/* Free-vibration sub-steps needed to reach the first extremum: T_d/2. */
static size_t free_steps_for(double f, double zeta, double h)
{
    double td = 1.0 / (f * sqrt(1.0 - zeta * zeta));
    return (size_t)ceil(0.5 * td / h) + 1;
}

/* Coefficients of a set of oscillators: SoA arrays, positions permuted so
 * that groups of equal sub-step count are contiguous. Read-only once made. */
typedef struct work {
    size_t nf;
    size_t *perm;   /* position -> index into the frequencies given to work_init */
    size_t *m;      /* sub-steps per input step, per position */
    size_t *nfree;  /* free-vibration sub-steps, per position */
    double *block;
    double *c[NCOEF];
    double *w2, *tzw;
    double *zw, *iwd; /* z w and 1/w_d: the free vibration's amplitude (eq. F1-F2) */
} work;

static void work_free(work *wk)
{
    free(wk->perm);
    free(wk->m);
    free(wk->nfree);
    free(wk->block);
    memset(wk, 0, sizeof *wk);
}

/* Insertion sort of indices by m (stable, no global state: qsort's comparator
 * would need one, and this must be thread-safe). nf is a few hundred. */
static void sort_by_m(size_t *perm, const size_t *m_of, size_t nf)
{
    for (size_t i = 1; i < nf; i++) {
        size_t key = perm[i];
        size_t j = i;
        while (j > 0 && m_of[perm[j - 1]] > m_of[key]) {
            perm[j] = perm[j - 1];
            j--;
        }
        perm[j] = key;
    }
}

static sl_status work_init(work *wk, const double *f, size_t nf, double dt, double zeta,
                           double spp, sl_error *err)
{
    memset(wk, 0, sizeof *wk);
    wk->nf = nf;
    enum { NARR = NCOEF + 4 };
    size_t cnt = nf ? nf : 1;
    size_t *m_of = malloc(cnt * sizeof *m_of);
    wk->perm = malloc(cnt * sizeof *wk->perm);
    wk->m = malloc(cnt * sizeof *wk->m);
    wk->nfree = malloc(cnt * sizeof *wk->nfree);
    wk->block = malloc((size_t)NARR * cnt * sizeof *wk->block);
    if (!m_of || !wk->perm || !wk->m || !wk->nfree || !wk->block) {
        free(m_of);
        work_free(wk);
        return sl_error_set(err, SL_ENOMEM, NULL, 0, "spectrum: out of memory");
    }
    for (int k = 0; k < NCOEF; k++)
        wk->c[k] = wk->block + (size_t)k * cnt;
    wk->w2 = wk->block + (size_t)NCOEF * cnt;
    wk->tzw = wk->w2 + cnt;
    wk->zw = wk->tzw + cnt;
    wk->iwd = wk->zw + cnt;
    for (size_t j = 0; j < nf; j++) {
        m_of[j] = substeps_for(f[j], dt, spp);
        wk->perm[j] = j;
    }
    sort_by_m(wk->perm, m_of, nf);
    for (size_t p = 0; p < nf; p++) {
        size_t j = wk->perm[p];
        double w = 2.0 * SL_PI * f[j];
        double h = dt / (double)m_of[j];
        double c[NCOEF];
        sl_spectrum_coefs_auto(w, zeta, h, c);
        for (int k = 0; k < NCOEF; k++)
            wk->c[k][p] = c[k];
        wk->m[p] = m_of[j];
        wk->nfree[p] = free_steps_for(f[j], zeta, h);
        wk->w2[p] = w * w;
        wk->tzw[p] = 2.0 * zeta * w;
        wk->zw[p] = zeta * w;
        wk->iwd[p] = 1.0 / (w * sqrt(1.0 - zeta * zeta));
    }
    free(m_of);
    return SL_OK;
}

/* ---- the free vibration after the record: skipped where it cannot matter.
 * From (u0, v0) at the last sample, u(t) = e^(-z w t) (u0 cos w_d t +
 * (v0 + z w u0)/w_d sin w_d t), so for every t >= 0
 *     |u(t)| <= R_u = hypot(u0, (v0 + z w u0)/w_d),                      (F1)
 * and y = w^2 u + 2 z w v obeys (1) with a = 0, y'(0) = w^2 v0 - 2 z w y0:
 *     |y(t)| <= R_y = hypot(y0, (w^2 v0 - z w y0)/w_d).                  (F2)
 * When R (1 + SL_SPECTRUM_FREE_MARGIN) < the peak over the record in every
 * lane of a block, its free sub-steps cannot raise a peak and are skipped:
 * the same bits (the rounding of the map, some 1e-13 relative over a
 * million sub-steps, is far inside the margin). docs/spectra.md. */
#define SL_SPECTRUM_FREE_MARGIN 1e-6

/* Tests: 0 runs every free sub-step (sl_spectrum_free_skip()). */
static int free_skip_enabled = 1;
/* Free sub-steps skipped by this thread (a count for tests). */
static _Thread_local unsigned long long free_skipped;

int sl_spectrum_free_skip(int on)
{
    int was = free_skip_enabled;
    free_skip_enabled = on != 0;
    return was;
}

unsigned long long sl_spectrum_free_skipped(void) { return free_skipped; }

/* Free amplitudes from (u0, v0): R_u (F1) into *ru, R_y (F2) into *ry;
 * zw = z w, iwd = 1/w_d, w2 = w^2, tzw = 2 z w. */
static inline void free_amplitudes(double zw, double iwd, double w2, double tzw, double u0,
                                   double v0, double *ru, double *ry)
{
    double y0 = w2 * u0 + tzw * v0;
    *ru = hypot(u0, (v0 + zw * u0) * iwd);
    *ry = hypot(y0, (w2 * v0 - zw * y0) * iwd);
}

void sl_spectrum_free_amplitudes(double f_hz, double zeta, double u0, double v0, double *ru,
                                 double *ry)
{
    double w = 2.0 * SL_PI * f_hz;
    free_amplitudes(zeta * w, 1.0 / (w * sqrt(1.0 - zeta * zeta)), w * w, 2.0 * zeta * w, u0,
                    v0, ru, ry);
}

/* 1 when the free vibration from (u0, v0) at position p may reach umax
 * (or, want_amax, amax); NaN compares false, so it is taken as "may". */
static inline int free_can_exceed(const work *wk, size_t p, double u0, double v0, double umax,
                                  int want_amax, double amax)
{
    double ru, ry;
    free_amplitudes(wk->zw[p], wk->iwd[p], wk->w2[p], wk->tzw[p], u0, v0, &ru, &ry);
    const double k = 1.0 + SL_SPECTRUM_FREE_MARGIN;
    return !(ru * k < umax) || (want_amax && !(ry * k < amax));
}

/* Oscillators stepped together (time loop inside): blocks of BLOCK_WIDE
 * lanes (4 AVX2 vectors: enough independent chains to hide the latency of
 * the recurrence), a group's last few in blocks of BLOCK_WIDE3, BLOCK_MID or
 * BLOCK_NARROW so that few lanes are idle. A block of 12 (3 AVX2 vectors)
 * takes about as long a sub-step as one of 8 or 4 (the latency of the
 * recurrence: a multiply and three adds), so run_groups() prefers it. */
#define BLOCK_WIDE 16
#define BLOCK_WIDE3 12
#define BLOCK_MID 8
#define BLOCK_NARROW 4

/* The kernel on GCC vectors (vector_size: 4 doubles, one AVX2 register, or
 * 2, one SSE2 register), so that a block's state u, v, max|u| (and
 * max|u''+a|) stays in registers across the time loop. (The former
 * scalar-lane loop, vectorised by GCC, became a loop over the block's
 * vectors that stored and reloaded the state at every sub-step, with the
 * store-to-load forwarding in the recurrence's chain: a full spectrum, 20 s
 * at 200/s, 271 points, took 0.96 ms, and up to 2.8 ms where its stack
 * arrays fell badly; now 0.63 ms, the baseline instance 1.40 ms; CPU time,
 * SEISLIDE_TEST_VERBOSE=1 build/tests/test_spectrum.) Positions
 * [p0, p0 + nb) (nb <= W, one sub-step count m) over the n values of the
 * input at their sub-step (the record, or for m > 1 its sub-step input made
 * by substep_input()) and nfree free sub-steps; max|u| into umax[p],
 * max|u''+a| into amax[p] (when want_amax). Every lane does exactly the
 * arithmetic of map (2) in the same order as a one-at-a-time loop (|x| by
 * clearing the sign bit, as fabs; the maximum by MAXV(x, max) =
 * x > max ? x : max), and there is no FMA
 * contraction (-std=c11 sets -ffp-contract=off): the result does not depend
 * on the blocking, the vector width or the instance the CPU runs. W and
 * want_amax are constants after inlining. KERNEL_DEFINE(NAME, VT, IT, L,
 * MAXV, ATTR) defines the kernel NAME on the vector type VT of L doubles
 * (IT: the integer vector of its size), with function attributes ATTR. */
#define KERNEL_DEFINE(NAME, VT, IT, L, MAXV, ATTR)                                            \
    static inline __attribute__((always_inline)) ATTR void NAME(                              \
        const work *wk, size_t p0, size_t nb, const double *acc, size_t n,                    \
        size_t nfree, double *umax_out, double *amax_out, const size_t W,                     \
        const int want_amax)                                                                  \
    {                                                                                         \
        enum { NVMAX = BLOCK_WIDE / (L) };                                                    \
        const size_t nv = W / (L);                                                            \
        VT c11[NVMAX], c12[NVMAX], c21[NVMAX], c22[NVMAX];                                    \
        VT bu0[NVMAX], bu1[NVMAX], bv0[NVMAX], bv1[NVMAX], w2[NVMAX], tzw[NVMAX];             \
        VT u[NVMAX], v[NVMAX], umax[NVMAX], amax[NVMAX];                                      \
        /* Unused lanes copy the first oscillator (results discarded). */                     \
        for (size_t q = 0; q < nv; q++) {                                                     \
            for (size_t l = 0; l < (L); l++) {                                                \
                size_t b = (L) * q + l, p = p0 + (b < nb ? b : 0);                            \
                c11[q][l] = wk->c[C11][p];                                                    \
                c12[q][l] = wk->c[C12][p];                                                    \
                c21[q][l] = wk->c[C21][p];                                                    \
                c22[q][l] = wk->c[C22][p];                                                    \
                bu0[q][l] = wk->c[BU0][p];                                                    \
                bu1[q][l] = wk->c[BU1][p];                                                    \
                bv0[q][l] = wk->c[BV0][p];                                                    \
                bv1[q][l] = wk->c[BV1][p];                                                    \
                w2[q][l] = wk->w2[p];                                                         \
                tzw[q][l] = wk->tzw[p];                                                       \
                u[q][l] = v[q][l] = umax[q][l] = amax[q][l] = 0.0;                            \
            }                                                                                 \
        }                                                                                     \
        IT abs_mask;                                                                          \
        for (size_t l = 0; l < (L); l++)                                                      \
            abs_mask[l] = INT64_MAX;                                                          \
        for (size_t i = 0; i + 1 < n; i++)                                                    \
            KERNEL_STEP(VT, IT, L, MAXV, acc[i], acc[i + 1]);                                 \
        /* free vibration after the record, unless no lane can reach its peak */              \
        if (nfree > 0 && free_skip_enabled) {                                                 \
            int need = 0;                                                                     \
            for (size_t b = 0; b < nb && !need; b++) {                                        \
                const size_t q = b / (L), l = b % (L), p = p0 + b;                            \
                need = free_can_exceed(wk, p, u[q][l], v[q][l], umax[q][l], want_amax,        \
                                       amax[q][l]);                                           \
            }                                                                                 \
            if (!need) {                                                                      \
                free_skipped += nfree;                                                        \
                nfree = 0;                                                                    \
            }                                                                                 \
        }                                                                                     \
        for (size_t k = 0; k < nfree; k++)                                                    \
            KERNEL_STEP(VT, IT, L, MAXV, 0.0, 0.0);                                           \
        for (size_t b = 0; b < nb; b++) {                                                     \
            umax_out[p0 + b] = umax[b / (L)][b % (L)];                                        \
            if (want_amax)                                                                    \
                amax_out[p0 + b] = amax[b / (L)][b % (L)];                                    \
        }                                                                                     \
    }

/* One sub-step of every vector of the block with input as -> as1 (map (2)):
 * u, v, then max|u| and (want_amax) max|w^2 u + 2 zeta w v| by selects. */
#define KERNEL_STEP(VT, IT, L, MAXV, as, as1)                                                 \
    do {                                                                                      \
        VT xa, xa1;                                                                           \
        for (size_t l = 0; l < (L); l++) {                                                    \
            xa[l] = (as);                                                                     \
            xa1[l] = (as1);                                                                   \
        }                                                                                     \
        _Pragma("GCC unroll 8") for (size_t q = 0; q < nv; q++) {                             \
            VT un = c11[q] * u[q] + c12[q] * v[q] + bu0[q] * xa + bu1[q] * xa1;               \
            VT vn = c21[q] * u[q] + c22[q] * v[q] + bv0[q] * xa + bv1[q] * xa1;               \
            u[q] = un;                                                                        \
            v[q] = vn;                                                                        \
            umax[q] = MAXV((VT)((IT)un & abs_mask), umax[q]);                                 \
            if (want_amax)                                                                    \
                amax[q] = MAXV((VT)((IT)(w2[q] * un + tzw[q] * vn) & abs_mask), amax[q]);     \
        }                                                                                     \
    } while (0)

typedef double sl_v2d __attribute__((vector_size(16)));
typedef long long sl_v2i __attribute__((vector_size(16)));
/* Lane-wise a > b ? a : b: MAXPD on x86-64 (which is exactly this select,
 * NaN and signed zeros included), else the select by masks. */
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#define MAX_V2(a, b) __builtin_ia32_maxpd((a), (b))
#else
static inline sl_v2d max_v2(sl_v2d a, sl_v2d b)
{
    sl_v2i gt = a > b;
    return (sl_v2d)(((sl_v2i)a & gt) | ((sl_v2i)b & ~gt));
}
#define MAX_V2(a, b) max_v2((a), (b))
#endif
KERNEL_DEFINE(kernel_v2, sl_v2d, sl_v2i, 2, MAX_V2, )

/* The kernel's instances: wide and narrow blocks, with and without the
 * absolute acceleration. */
#define RUN_WIDTHS(KERNEL)                                                                    \
    do {                                                                                      \
        size_t W_ = nb > BLOCK_WIDE3  ? BLOCK_WIDE                                            \
                    : nb > BLOCK_MID  ? BLOCK_WIDE3                                           \
                    : nb > BLOCK_NARROW ? BLOCK_MID                                           \
                                        : BLOCK_NARROW;                                       \
        if (W_ == BLOCK_WIDE && amax_out)                                                     \
            KERNEL(wk, p0, nb, acc, n, nfree, umax_out, amax_out, BLOCK_WIDE, 1);             \
        else if (W_ == BLOCK_WIDE)                                                            \
            KERNEL(wk, p0, nb, acc, n, nfree, umax_out, NULL, BLOCK_WIDE, 0);                 \
        else if (W_ == BLOCK_WIDE3 && amax_out)                                               \
            KERNEL(wk, p0, nb, acc, n, nfree, umax_out, amax_out, BLOCK_WIDE3, 1);            \
        else if (W_ == BLOCK_WIDE3)                                                           \
            KERNEL(wk, p0, nb, acc, n, nfree, umax_out, NULL, BLOCK_WIDE3, 0);                \
        else if (W_ == BLOCK_MID && amax_out)                                                 \
            KERNEL(wk, p0, nb, acc, n, nfree, umax_out, amax_out, BLOCK_MID, 1);              \
        else if (W_ == BLOCK_MID)                                                             \
            KERNEL(wk, p0, nb, acc, n, nfree, umax_out, NULL, BLOCK_MID, 0);                  \
        else if (amax_out)                                                                    \
            KERNEL(wk, p0, nb, acc, n, nfree, umax_out, amax_out, BLOCK_NARROW, 1);           \
        else                                                                                  \
            KERNEL(wk, p0, nb, acc, n, nfree, umax_out, NULL, BLOCK_NARROW, 0);               \
    } while (0)

/* Baseline instance (x86-64: SSE2, 2 doubles a vector; any other CPU). */
static void run_block_base(const work *wk, size_t p0, size_t nb, const double *acc, size_t n,
                           size_t nfree, double *umax_out, double *amax_out)
{
    RUN_WIDTHS(kernel_v2);
}

/* Function multiversioning by hand (GCC, x86-64): an AVX2 instance on 4
 * doubles a vector, chosen at run time when the CPU has AVX2 (GCC's
 * target_clones cannot give the two instances different vector types). The
 * same bits as the baseline (see KERNEL_DEFINE). */
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) &&                        \
    !defined(SL_SPECTRUM_NO_CLONES)
#define SL_KERNEL_AVX2 1
typedef double sl_v4d __attribute__((vector_size(32)));
typedef long long sl_v4i __attribute__((vector_size(32)));
#define MAX_V4(a, b) __builtin_ia32_maxpd256((a), (b))
KERNEL_DEFINE(kernel_v4, sl_v4d, sl_v4i, 4, MAX_V4, __attribute__((target("avx2"))))

__attribute__((target("avx2"))) static void
run_block_avx2(const work *wk, size_t p0, size_t nb, const double *acc, size_t n, size_t nfree,
               double *umax_out, double *amax_out)
{
    RUN_WIDTHS(kernel_v4);
}
#endif

/* Set by sl_spectrum_kernel_baseline(): the baseline instance even on an
 * AVX2 CPU (tests). */
static int kernel_force_baseline;

int sl_spectrum_kernel_baseline(int force)
{
    int was = kernel_force_baseline;
    kernel_force_baseline = force != 0;
    return was;
}

int sl_spectrum_kernel_avx2(void)
{
#ifdef SL_KERNEL_AVX2
    return !kernel_force_baseline && __builtin_cpu_supports("avx2");
#else
    return 0;
#endif
}

static void run_block(const work *wk, size_t p0, size_t nb, const double *acc, size_t n,
                      size_t nfree, double *umax_out, double *amax_out)
{
#ifdef SL_KERNEL_AVX2
    if (sl_spectrum_kernel_avx2()) {
        run_block_avx2(wk, p0, nb, acc, n, nfree, umax_out, amax_out);
        return;
    }
#endif
    run_block_base(wk, p0, nb, acc, n, nfree, umax_out, amax_out);
}

/* Lanes of the next block of a group with `left` still to run: up to
 * BLOCK_WIDE; 12 when 17-24 are left (12 + up to 12, not 16 + a narrow
 * block that takes as long as 12). */
static size_t next_block(size_t left)
{
    if (left <= BLOCK_WIDE)
        return left;
    if (left <= 2 * BLOCK_WIDE3)
        return BLOCK_WIDE3;
    return BLOCK_WIDE;
}

/* The sub-step input of a group of m > 1 sub-steps per sample, made once
 * for all its blocks: xs[i m + s] = a_i + (a_{i+1} - a_i) (s/m), s < m, and
 * xs[(n - 1) m] = a_{n-1}, the values (same operations) that the kernel
 * would otherwise interpolate in every block; (n - 1) m + 1 values. */
static void substep_input(const double *acc, size_t n, size_t m, double *xs)
{
    const double inv_m = 1.0 / (double)m;
    for (size_t i = 0; i + 1 < n; i++) {
        const double a0 = acc[i], da = acc[i + 1] - acc[i];
        xs[i * m] = a0;
        for (size_t s = 1; s < m; s++)
            xs[i * m + s] = a0 + da * ((double)s * inv_m);
    }
    xs[(n - 1) * m] = acc[n - 1];
}

/* Every group of equal m, in blocks: the record, then (free_vib) the free
 * sub-steps of the block's lowest frequency. A group runs in blocks of
 * next_block() lanes, each in the narrowest instance that holds it; a group
 * of m > 1 on its sub-step input in xs ((n - 1) m + 1 values), which the
 * kernel then steps as samples. */
static void run_groups(const work *wk, const double *acc, size_t n, int free_vib, double *umax,
                       double *amax, double *xs)
{
    size_t nf = wk->nf;
    for (size_t p0 = 0; p0 < nf;) {
        size_t m = wk->m[p0];
        size_t p1 = p0 + 1;
        while (p1 < nf && wk->m[p1] == m)
            p1++;
        const double *in = acc;
        size_t nin = n;
        if (m > 1) {
            substep_input(acc, n, m, xs);
            in = xs;
            nin = (n - 1) * m + 1;
        }
        for (size_t q = p0; q < p1;) {
            size_t left = p1 - q;
            size_t nb = next_block(left);
            /* free sub-steps of the block's lowest frequency; the higher
             * ones run on past their first extremum, where later extrema
             * of a free damped vibration are smaller */
            size_t nfree = 0;
            for (size_t p = q; p < q + nb && free_vib; p++)
                nfree = wk->nfree[p] > nfree ? wk->nfree[p] : nfree;
            run_block(wk, q, nb, in, nin, nfree, umax, amax);
            q += nb;
        }
        p0 = p1;
    }
}

/* ---- plans: coefficients made once, optional multirate -------------- */

#define MAX_LEVELS 16

/* sinc(x) = sin(pi x)/(pi x). */
static double sinc(double x)
{
    return fabs(x) < 1e-8 ? 1.0 : sin(SL_PI * x) / (SL_PI * x);
}

typedef struct level {
    size_t d;        /* decimation factor 2^l */
    size_t n;        /* samples at this level */
    size_t nf;       /* oscillators at this level */
    size_t *out;     /* position -> index into the plan's frequencies */
    work wk;
    size_t nkeep;    /* DFT bins kept: k < nkeep */
    double *gain;    /* nkeep factors: interpolation match / N (eq. M2) */
    fftw_plan c2r;   /* length nfft / d */
} level;

struct sl_spectrum_plan {
    size_t n, nf, nlev, nfft;
    double dt;
    int free_vib;
    fftw_plan r2c;   /* length nfft (multirate only) */
    level lev[MAX_LEVELS];
};

void sl_spectrum_plan_free(sl_spectrum_plan *p)
{
    if (!p)
        return;
    for (size_t l = 0; l < p->nlev; l++) {
        level *lv = &p->lev[l];
        free(lv->out);
        free(lv->gain);
        work_free(&lv->wk);
        if (lv->c2r) {
            fftw_destroy_plan(lv->c2r);
        }
    }
    if (p->r2c) {
        fftw_destroy_plan(p->r2c);
    }
    free(p);
}

/* Smallest 2-3-5-7-smooth integer >= x. */
static size_t smooth_at_least(size_t x)
{
    for (size_t k = x < 1 ? 1 : x;; k++) {
        size_t r = k;
        static const size_t pr[] = {2, 3, 5, 7};
        for (int i = 0; i < 4; i++)
            while (r % pr[i] == 0)
                r /= pr[i];
        if (r == 1)
            return k;
    }
}

sl_spectrum_plan *sl_spectrum_plan_alloc(size_t n, double dt_s, const double *f_hz, size_t nf,
                                         double zeta, const sl_spectrum_opts *opts,
                                         double ratio, sl_error *err)
{
    sl_spectrum_opts o;
    if (opts)
        o = *opts;
    else
        sl_spectrum_opts_default(&o);
    double dummy = 0.0;
    if (nf == 0 || !f_hz) {
        sl_error_set(err, SL_EINVAL, NULL, 0, "spectrum: no frequencies");
        return NULL;
    }
    if (check_args(&dummy, 1, dt_s, f_hz, nf, zeta, &o, err))
        return NULL;
    if (n == 0) {
        sl_error_set(err, SL_EINVAL, NULL, 0, "spectrum: empty record");
        return NULL;
    }
    if (!(ratio == 0 || (ratio >= SL_SPECTRUM_MIN_RATIO && isfinite(ratio)))) {
        sl_error_set(err, SL_EINVAL, NULL, 0,
                     "spectrum: multirate ratio %g must be 0 or at least %g", ratio,
                     SL_SPECTRUM_MIN_RATIO);
        return NULL;
    }
    sl_spectrum_plan *p = calloc(1, sizeof *p);
    size_t *lev_of = malloc(nf * sizeof *lev_of);
    double *fl = malloc(nf * sizeof *fl);
    if (!p || !lev_of || !fl) {
        free(p);
        free(lev_of);
        free(fl);
        sl_error_set(err, SL_ENOMEM, NULL, 0, "spectrum: out of memory");
        return NULL;
    }
    p->n = n;
    p->nf = nf;
    p->dt = dt_s;
    p->free_vib = o.free_vibration;
    /* Level of each oscillator: the largest l with fs/2^l >= ratio f
     * (eq. M1), keeping at least 8 samples per level. */
    const double fs = 1.0 / dt_s;
    size_t top = 0;
    for (size_t j = 0; j < nf; j++) {
        size_t l = 0;
        if (ratio > 0)
            while (l + 1 < MAX_LEVELS && fs / (double)((size_t)1 << (l + 1)) >= ratio * f_hz[j] &&
                   (n - 1) / ((size_t)1 << (l + 1)) >= 8)
                l++;
        lev_of[j] = l;
        top = l > top ? l : top;
    }
    p->nlev = top + 1;
    sl_status st = SL_OK;
    if (top > 0) {
        /* One zero-padded DFT of length N = 2^top M (so every level's length
         * N/2^l is an integer); padding n/8 + 2^(top+3) samples keeps the
         * circular wrap of the band-limited reconstruction off the record. */
        size_t dmax = (size_t)1 << top;
        size_t need = n + n / 8 + 8 * dmax;
        p->nfft = dmax * smooth_at_least((need + dmax - 1) / dmax);
        if (p->nfft % 2)
            p->nfft *= 2;
    }
    for (size_t l = 0; l < p->nlev && !st; l++) {
        level *lv = &p->lev[l];
        lv->d = (size_t)1 << l;
        lv->n = (n - 1) / lv->d + 1;
        for (size_t j = 0; j < nf; j++)
            if (lev_of[j] == l)
                lv->nf++;
        lv->out = malloc((lv->nf ? lv->nf : 1) * sizeof *lv->out);
        if (!lv->out) {
            st = sl_error_set(err, SL_ENOMEM, NULL, 0, "spectrum: out of memory");
            break;
        }
        size_t q = 0;
        for (size_t j = 0; j < nf; j++)
            if (lev_of[j] == l) {
                fl[q] = f_hz[j];
                lv->out[q++] = j;
            }
        st = work_init(&lv->wk, fl, lv->nf, dt_s * (double)lv->d, zeta, o.steps_per_period, err);
        if (st)
            break;
        for (size_t pos = 0; pos < lv->nf; pos++) /* position -> caller index */
            fl[pos] = (double)lv->out[lv->wk.perm[pos]];
        for (size_t pos = 0; pos < lv->nf; pos++)
            lv->out[pos] = (size_t)fl[pos];
        if (l == 0 || lv->nf == 0)
            continue;
        /* Bins strictly below the level's Nyquist frequency fs/(2d), each
         * times sinc^2(f/fs)/sinc^2(f/fs_l): the piecewise-linear reading at
         * the level's rate then has the baseband spectrum of the
         * piecewise-linear reading at the full rate (eq. M2). */
        lv->nkeep = p->nfft / (2 * lv->d);
        lv->gain = malloc(lv->nkeep * sizeof *lv->gain);
        if (!lv->gain) {
            st = sl_error_set(err, SL_ENOMEM, NULL, 0, "spectrum: out of memory");
            break;
        }
        for (size_t k = 0; k < lv->nkeep; k++) {
            double fk = (double)k / ((double)p->nfft * dt_s);
            double s1 = sinc(fk / fs), s2 = sinc(fk * dt_s * (double)lv->d);
            lv->gain[k] = s1 * s1 / (s2 * s2) / (double)p->nfft;
        }
    }
    free(lev_of);
    free(fl);
    if (!st && top > 0) {
        double *r = fftw_malloc(p->nfft * sizeof *r);
        fftw_complex *c = fftw_malloc((p->nfft / 2 + 1) * sizeof *c);
        if (r && c) {
            sl_fftw_thread_safe();
            {
                p->r2c = fftw_plan_dft_r2c_1d((int)p->nfft, r, c, FFTW_ESTIMATE);
                for (size_t l = 1; l < p->nlev; l++)
                    if (p->lev[l].nf)
                        p->lev[l].c2r = fftw_plan_dft_c2r_1d((int)(p->nfft / p->lev[l].d), c,
                                                             r, FFTW_ESTIMATE);
            }
        }
        fftw_free(r);
        fftw_free(c);
        int ok = p->r2c != NULL;
        for (size_t l = 1; l < p->nlev; l++)
            ok = ok && (p->lev[l].nf == 0 || p->lev[l].c2r);
        if (!ok)
            st = sl_error_set(err, SL_ENOMEM, NULL, 0, "spectrum: cannot make FFTW plans");
    }
    if (st) {
        sl_spectrum_plan_free(p);
        return NULL;
    }
    return p;
}

size_t sl_spectrum_plan_levels(const sl_spectrum_plan *p) { return p->nlev; }

sl_status sl_spectrum_plan_compute(const sl_spectrum_plan *p, const double *acc_ms2,
                                   double *psa_ms2, double *sd_m, double *sa_abs_ms2,
                                   sl_error *err)
{
    if (!acc_ms2)
        return sl_error_set(err, SL_EINVAL, NULL, 0, "spectrum: empty record");
    for (size_t i = 0; i < p->n; i++)
        if (!isfinite(acc_ms2[i]))
            return sl_error_set(err, SL_EINVAL, NULL, 0, "spectrum: sample %zu is not finite", i);
    if (sa_abs_ms2 && p->nlev > 1)
        return sl_error_set(err, SL_EINVAL, NULL, 0,
                            "spectrum: a multirate plan gives PSA and SD only");
    size_t nxs = 1; /* the largest sub-step input (m sorted: the last is the largest) */
    for (size_t l = 0; l < p->nlev; l++) {
        const work *w = &p->lev[l].wk;
        size_t k = w->nf ? (p->lev[l].n - 1) * w->m[w->nf - 1] + 1 : 0;
        nxs = k > nxs ? k : nxs;
    }
    double *umax = malloc((2 * p->nf + nxs) * sizeof *umax);
    double *r = NULL;
    fftw_complex *x = NULL, *c = NULL;
    size_t nbin = p->nfft / 2 + 1;
    if (p->nlev > 1) {
        r = fftw_malloc(p->nfft * sizeof *r);
        x = fftw_malloc(nbin * sizeof *x);
        c = fftw_malloc(nbin * sizeof *c);
    }
    if (!umax || (p->nlev > 1 && (!r || !x || !c))) {
        free(umax);
        fftw_free(r);
        fftw_free(x);
        fftw_free(c);
        return sl_error_set(err, SL_ENOMEM, NULL, 0, "spectrum: out of memory");
    }
    double *amax = sa_abs_ms2 ? umax + p->nf : NULL;
    if (p->nlev > 1) {
        for (size_t i = 0; i < p->nfft; i++)
            r[i] = i < p->n ? acc_ms2[i] : 0.0;
        fftw_execute_dft_r2c(p->r2c, r, x);
    }
    for (size_t l = 0; l < p->nlev; l++) {
        const level *lv = &p->lev[l];
        if (lv->nf == 0)
            continue;
        const double *a = acc_ms2;
        if (l > 0) {
            /* the band-limited copy at step d dt (eq. M2) */
            size_t nb = p->nfft / lv->d / 2 + 1;
            for (size_t k = 0; k < nb; k++) {
                double g = k < lv->nkeep ? lv->gain[k] : 0.0;
                c[k][0] = x[k][0] * g;
                c[k][1] = x[k][1] * g;
            }
            fftw_execute_dft_c2r(lv->c2r, c, r);
            a = r;
        }
        run_groups(&lv->wk, a, lv->n, p->free_vib, umax, amax, umax + 2 * p->nf);
        for (size_t pos = 0; pos < lv->nf; pos++) {
            size_t j = lv->out[pos];
            if (sd_m)
                sd_m[j] = umax[pos];
            if (psa_ms2)
                psa_ms2[j] = lv->wk.w2[pos] * umax[pos];
            if (sa_abs_ms2)
                sa_abs_ms2[j] = amax[pos];
        }
    }
    free(umax);
    fftw_free(r);
    fftw_free(x);
    fftw_free(c);
    return SL_OK;
}

sl_status sl_spectrum_compute_opts(const double *acc_ms2, size_t n, double dt_s,
                                   const double *f_hz, size_t nf, double zeta,
                                   const sl_spectrum_opts *opts, double *psa_ms2,
                                   double *sd_m, double *sa_abs_ms2, sl_error *err)
{
    sl_spectrum_opts o;
    if (opts)
        o = *opts;
    else
        sl_spectrum_opts_default(&o);
    if (nf == 0)
        return SL_OK;
    if (!f_hz)
        return sl_error_set(err, SL_EINVAL, NULL, 0, "spectrum: no frequencies");
    sl_status st = check_args(acc_ms2, n, dt_s, f_hz, nf, zeta, &o, err);
    if (st)
        return st;
    sl_error e2;
    sl_error_clear(&e2);
    sl_spectrum_plan *p = sl_spectrum_plan_alloc(n, dt_s, f_hz, nf, zeta, &o, 0.0, &e2);
    if (!p)
        return sl_error_set(err, e2.code ? e2.code : SL_ENOMEM, NULL, 0, "%s", e2.msg);
    st = sl_spectrum_plan_compute(p, acc_ms2, psa_ms2, sd_m, sa_abs_ms2, err);
    sl_spectrum_plan_free(p);
    return st;
}

sl_status sl_spectrum_compute(const double *acc_ms2, size_t n, double dt_s,
                              const double *f_hz, size_t nf, double zeta,
                              double *psa_ms2, double *sd_m, double *sa_abs_ms2,
                              sl_error *err)
{
    return sl_spectrum_compute_opts(acc_ms2, n, dt_s, f_hz, nf, zeta, NULL, psa_ms2, sd_m,
                                    sa_abs_ms2, err);
}

sl_status sl_spectrum_batch(const sl_motion *const *motions, size_t nm,
                            const double *f_hz, size_t nf, double zeta,
                            const sl_spectrum_opts *opts, double *psa_ms2,
                            double *sd_m, double *sa_abs_ms2, sl_error *err)
{
    if (nm == 0)
        return SL_OK;
    if (!motions)
        return sl_error_set(err, SL_EINVAL, NULL, 0, "spectrum: no motions");
    sl_status *st = calloc(nm, sizeof *st);
    sl_error *errs = calloc(nm, sizeof *errs);
    if (!st || !errs) {
        free(st);
        free(errs);
        return sl_error_set(err, SL_ENOMEM, NULL, 0, "spectrum: out of memory");
    }
    long long nm_ll = (long long)nm;
#pragma omp parallel for schedule(dynamic, 1)
    for (long long i = 0; i < nm_ll; i++) {
        size_t k = (size_t)i;
        const sl_motion *m = motions[k];
        if (!m) {
            st[k] = sl_error_set(&errs[k], SL_EINVAL, NULL, 0, "spectrum: missing motion");
            continue;
        }
        st[k] = sl_spectrum_compute_opts(m->acc_ms2, m->n, m->dt_s, f_hz, nf, zeta, opts,
                                         psa_ms2 ? psa_ms2 + k * nf : NULL,
                                         sd_m ? sd_m + k * nf : NULL,
                                         sa_abs_ms2 ? sa_abs_ms2 + k * nf : NULL, &errs[k]);
    }
    sl_status ret = SL_OK;
    for (size_t k = 0; k < nm; k++) {
        if (st[k]) {
            const char *path = motions[k] && motions[k]->path ? motions[k]->path : NULL;
            ret = sl_error_set(err, st[k], path && *path ? path : NULL, 0, "%s", errs[k].msg);
            break;
        }
    }
    free(st);
    free(errs);
    return ret;
}

sl_status sl_spectrum_history(const double *acc_ms2, size_t n, double dt_s,
                              double f_hz, double zeta, const sl_spectrum_opts *opts,
                              double *u_m, double *v_ms, sl_error *err)
{
    sl_spectrum_opts o;
    if (opts)
        o = *opts;
    else
        sl_spectrum_opts_default(&o);
    sl_status st = check_args(acc_ms2, n, dt_s, &f_hz, 1, zeta, &o, err);
    if (st)
        return st;
    size_t m = substeps_for(f_hz, dt_s, o.steps_per_period);
    double c[NCOEF];
    sl_spectrum_coefs_auto(2.0 * SL_PI * f_hz, zeta, dt_s / (double)m, c);
    double u = 0.0, v = 0.0, inv_m = 1.0 / (double)m;
    for (size_t i = 0; i < n; i++) {
        if (u_m)
            u_m[i] = u;
        if (v_ms)
            v_ms[i] = v;
        if (i + 1 == n)
            break;
        double a0 = acc_ms2[i], da = acc_ms2[i + 1] - acc_ms2[i], as = a0;
        for (size_t s = 1; s <= m; s++) {
            double as1 = s == m ? acc_ms2[i + 1] : a0 + da * ((double)s * inv_m);
            double un = c[C11] * u + c[C12] * v + c[BU0] * as + c[BU1] * as1;
            double vn = c[C21] * u + c[C22] * v + c[BV0] * as + c[BV1] * as1;
            u = un;
            v = vn;
            as = as1;
        }
    }
    return SL_OK;
}
