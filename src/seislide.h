/*
 * seislide.h - the public interface of libseislide: peak sliding
 * displacement of unanchored rigid components on a floor in an earthquake,
 * by nonlinear time-history analysis (NLTHA) and the ASCE/SEI 43-05
 * approximate method. `make install` puts this header and the ones it
 * includes under PREFIX/include/seislide/; include this one only, as
 *
 *     #include <seislide/seislide.h>
 *
 * and build against the shared library (libseislide.so) with
 *
 *     cc prog.c $(pkg-config --cflags --libs seislide)
 *
 * or against the archive (libseislide.a) with
 *
 *     cc prog.c $(pkg-config --cflags seislide) \
 *        $(pkg-config --static --libs seislide | sed 's/-lseislide /-l:libseislide.a /')
 *
 * (a PREFIX outside the system's paths: PKG_CONFIG_PATH=PREFIX/lib/pkgconfig
 * to build, LD_LIBRARY_PATH=PREFIX/lib to run; README.md, "Build").
 *
 * The pipeline, in the order the headers are listed:
 *   floor response spectra (io/floor.h) and ground motions (io/motion.h,
 *   io/setdir.h) -> response spectra and RG 1.60 (signal/) -> synthesized
 *   spectrum-compatible sets (synth/synth.h) -> NLTHA of the sliding block
 *   (slide/slide.h), of the rocking one (rock/rock.h) and the ASCE method
 *   (method/asce_input.h, asce.h) -> design sliding spectra and clearance
 *   (method/design.h) -> the per-floor job (analysis.h) -> the workbook and
 *   CSV tables (report/report.h).
 *
 * Conventions (every header): SI units inside (m, s, m/s^2), named units at
 * the boundary; one status enum with file:line messages (core/status.h);
 * the library never prints or exits (libxlsxwriter's own error lines are
 * held off the standard error while it writes a workbook and go into the
 * error message: report/workbook.c), and leaves GSL's error handler as the
 * caller set it (a GSL failure is returned as SL_ESOLVER); sl_X_alloc with
 * sl_X_free and sl_X_read with sl_X_free in pairs; every exported name
 * starts with sl_ or SL_, and libseislide.so exports exactly the functions
 * marked SL_API (core/api.h). The version: SEISLIDE_VERSION_* (the headers,
 * core/version.h) and sl_version() (the library); the build's identity,
 * the version with a fingerprint of the library's sources: sl_build_id().
 *
 * Threads: every function is reentrant - it may run in several threads at
 * once (POSIX threads or OpenMP) on different objects, and on the same
 * object when the object is only read (a plan, a floor, a motion: declared
 * const). No function keeps hidden state between calls except two
 * process-wide settings made safe by the library: FFTW's planner, made
 * thread-safe once (fftw_make_planner_thread_safe), and GSL's error
 * handler, turned off around the library's GSL calls and then put back
 * (the first call in and the last out). A caller that changes GSL's
 * handler while the library runs in another thread races with it.
 */
#ifndef SEISLIDE_H
#define SEISLIDE_H

#include "core/version.h"
#include "core/status.h"
#include "core/units.h"
#include "core/standards.h"

#include "io/motion.h"
#include "io/setdir.h"
#include "io/floor.h"

#include "signal/spectrum.h"
#include "signal/rg160.h"

#include "synth/synth.h"

#include "slide/slide.h"
#include "rock/rock.h"
#include "rock/rock_floor.h"
#include "rock/rock_lookup.h"

#include "method/asce.h"
#include "method/asce_input.h"
#include "method/design.h"

#include "analysis.h"

#include "report/report.h"

#endif
