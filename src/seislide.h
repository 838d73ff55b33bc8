/*
 * seislide.h - the public interface of libseislide: peak sliding
 * displacement of unanchored rigid components on a floor in an earthquake,
 * by nonlinear time-history analysis (NLTHA) and the ASCE/SEI 43-05
 * approximate method. Include this header only; build with
 *
 *     cc prog.c $(pkg-config --cflags --libs seislide)
 *
 * The pipeline, in the order the headers are listed:
 *   floor response spectra (io/floor.h) and ground motions (io/motion.h,
 *   io/setdir.h) -> response spectra and RG 1.60 (signal/) -> synthesized
 *   spectrum-compatible sets (synth/synth.h) -> NLTHA of the sliding block
 *   (slide/slide.h) and the ASCE method (method/asce_input.h, asce.h) ->
 *   design sliding spectra and clearance (method/design.h) -> the per-floor
 *   job (analysis.h) -> the workbook and CSV tables (report/report.h).
 *
 * Conventions (every header): SI units inside (m, s, m/s^2), named units at
 * the boundary; one status enum with file:line messages (core/status.h);
 * the library never prints or exits; *_alloc/*_free and *_read/*_free pairs.
 */
#ifndef SEISLIDE_H
#define SEISLIDE_H

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

#include "method/asce.h"
#include "method/asce_input.h"
#include "method/design.h"

#include "analysis.h"

#include "report/report.h"

#endif
