/*
 * clock.h - a monotonic clock for timings (wall time of runs, benches).
 *
 * sl_clock_s() is CLOCK_MONOTONIC (POSIX clock_gettime) in seconds: only
 * differences of two readings mean anything; it never goes back when the
 * system time is set. Thread-safe; no state.
 */
#ifndef SL_CLOCK_H
#define SL_CLOCK_H

/* Seconds on the monotonic clock (an arbitrary origin), resolution 1 ns. */
double sl_clock_s(void);

#endif
