/*
 * setdir.h - a recorded three-component set read from one folder: PEER
 * .AT2 files (the layout of a PEER NGA-West2 download, RSN*), two horizontals and
 * one vertical told apart by sl_motion_name_is_vertical(); or, in a folder
 * without .AT2 files, the agency formats of io/formats.h: one GeoNet .V2A
 * or CSMIP .V2 file with three channels, three USGS .smc files, or three
 * CWA .acc files (_E, _N, _Z); the vertical by its component name
 * (sl_component_is_vertical()), H1 and H2 the others in file order.
 *
 * Units: SI (the reader converts). Memory: the set's motions are owned by
 * the caller after a successful read and freed with sl_set_free_motions().
 */
#ifndef SL_SETDIR_H
#define SL_SETDIR_H

#include "core/api.h"
#include "core/status.h"
#include "io/motion.h"

/* Read the set in folder `dir`: its *.AT2 files (else the agency files
 * above), exactly two horizontals and one vertical; H1 is the horizontal
 * whose name sorts first (the first channel in a multi-channel file).
 * Components of different length are cut to the shortest (PEER sets
 * sometimes differ by a few samples; sl_set_check() with truncate). On
 * success *set holds three motions the caller owns. Returns SL_OK, or an
 * error naming the folder or file (SL_EINVAL for a name too long, SL_EIO
 * when the folder cannot be read or does not hold 2 + 1 components, the
 * reader's errors). On failure *set is zeroed and nothing is left
 * allocated. */
SL_API sl_status sl_set_read_dir(const char *dir, sl_set *set, sl_error *err);

/* Read the set of up to three files: path[0] H1 (required), path[1] H2
 * and path[2] V (NULL when absent), each with sl_motion_read() and ro, then
 * sl_set_check_fit() with truncate (fit may be NULL). On success *set holds
 * the motions the caller owns (sl_set_free_motions()). Returns SL_OK or the
 * first error (a reader's, naming the file, or the check's); then *set is
 * zeroed and nothing is left allocated. */
SL_API sl_status sl_set_read_files(const char *const path[3], const sl_read_opts *ro, int truncate,
                                   sl_set *set, sl_set_fit *fit, sl_error *err);

/* Free the motions of a set that owns them (as sl_set_read_dir() leaves
 * it) and zero the set; harmless on NULL and on empty components. */
SL_API void sl_set_free_motions(sl_set *set);

#endif
