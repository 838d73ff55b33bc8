/*
 * spectrum_kernel.h - which instance of the oscillator bank runs, and the
 * switch tests use to compare them. Internal: not installed, not exported
 * by libseislide.so.
 */
#ifndef SL_SPECTRUM_KERNEL_H
#define SL_SPECTRUM_KERNEL_H

/* The oscillator bank's instances. Built by GCC for x86-64 there are two:
 * one on AVX2 vectors (4 doubles), run when the CPU has AVX2, and the
 * baseline (SSE2, 2 doubles); elsewhere only the baseline. Both do the same
 * IEEE operations in the same order, so spectra are the same bits on either.
 * sl_spectrum_kernel_avx2() is 1 when the AVX2 instance runs.
 * sl_spectrum_kernel_baseline(1) makes every later spectrum use the baseline
 * (for tests that compare the two; not to be called while spectra are being
 * computed in other threads); 0 restores the choice by CPU. Returns the
 * previous setting. */
int sl_spectrum_kernel_avx2(void);
int sl_spectrum_kernel_baseline(int force);

/* The free vibration after the record (spectrum.c, eq. F1-F2) is skipped in
 * a block when no lane's free amplitude reaches its peak. For tests:
 * sl_spectrum_free_skip(0) runs every free sub-step (the same bits; not to
 * be called while spectra are being computed in other threads), 1 restores
 * the skip; returns the previous setting. sl_spectrum_free_skipped() is the
 * number of free sub-steps (of one block) skipped so far by the calling
 * thread. */
int sl_spectrum_free_skip(int on);
unsigned long long sl_spectrum_free_skipped(void);

/* The bounds the skip uses, for an oscillator at f_hz, damping zeta, from
 * the state (u0 m, v0 m/s) at the last sample: *ru >= |u(t)| (F1) and
 * *ry >= |u''(t) + a(t)| (F2) for every t after the record. */
void sl_spectrum_free_amplitudes(double f_hz, double zeta, double u0, double v0, double *ru,
                                 double *ry);

/* The recurrence's coefficients (spectrum_coefs.c): x1 = A x0 + B (a0, a1)
 * over a step h at w = 2 pi f rad/s and damping z, in this order; the series
 * where w h < SL_SPECTRUM_SERIES_WH, else the closed form. */
enum { C11, C12, C21, C22, BU0, BU1, BV0, BV1, NCOEF };
void sl_spectrum_coefs_auto(double w, double z, double h, double c[NCOEF]);

#endif
