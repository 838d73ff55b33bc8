/*
 * fftw_safe.h - FFTW's planner made thread-safe, once, by the library.
 *
 * Only fftw_execute() is thread-safe in FFTW by default: planning and
 * fftw_destroy_plan() must not run in two threads at once (FFTW 3 manual,
 * 5.4 "Thread safety"). fftw_make_planner_thread_safe() (FFTW >= 3.3.5, in
 * libfftw3_threads) puts a lock around every planner call, process-wide, so
 * the library's plans, and the caller's own, may be made and destroyed from
 * any thread (OpenMP or pthreads) without a convention between callers.
 *
 * Internal (not installed): called before every plan the library makes.
 */
#ifndef SL_FFTW_SAFE_H
#define SL_FFTW_SAFE_H

/* Install FFTW's planner lock on the first call (pthread_once); later calls
 * return at once. Call before making a plan. */
void sl_fftw_thread_safe(void);

#endif
