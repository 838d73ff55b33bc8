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

#endif
