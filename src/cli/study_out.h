/*
 * study_out.h - how `seislide study` writes what the study library
 * (study/study_parts.h) computed: the report (markdown, in memory until
 * the end), the data files (TSV, units in the headers) and the gnuplot
 * scripts and figures. Internal to the command line.
 */
#ifndef SL_STUDY_OUT_H
#define SL_STUDY_OUT_H

#include <stdio.h>

#include "study/study_parts.h"

#define STUDY_FIGDIR "validation"

typedef struct study_out {
    const char *out;   /* folder of validation.md */
    char figdir[4096]; /* out/validation */
    int plots;         /* run gnuplot */
    FILE *md;          /* the report */
    sl_error err;
} study_out;

/* Write text to dir/name atomically. 0 or -1 (message printed). */
int study_write_text(study_out *o, const char *dir, const char *name, const char *text,
                     size_t len);
/* A TSV in figdir: a title line, a header of ncol names, nrow rows (NAN as
 * NaN, which gnuplot skips). 0 or -1 (message printed). */
int study_write_tsv(study_out *o, const char *name, const char *title, const char *const *hdr,
                    const double *const *col, size_t ncol, size_t nrow);
/* A history as TSV: t_s, then the two displacements and forces with the
 * given column names. */
int study_write_history(study_out *o, const char *name, const char *title,
                        const char *const hdr[5], const sl_history *h);
/* The design spectra of a group as TSV (mu, x, the six curves, sd). */
int study_write_spectra(study_out *o, const char *name, const char *title,
                        const sl_study_spectra *sp);
/* figdir/base.gp with the common header and the body (a printf format),
 * then gnuplot when plots are on. 0 or -1 (message printed). */
int study_plot(study_out *o, const char *base, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;
/* "1e-7" (not "1e-07"): a power of ten as the study writes it. */
const char *study_sci(double v, char *buf, size_t n);

/* The report's sections (study_report.c). Parts return 0 or -1. */
int study_report_part1(study_out *o, const sl_study_part1 *p);
int study_report_part2(study_out *o, const sl_study_part2 *p);
int study_report_part3(study_out *o, const sl_study_part3 *p);
int study_report_part4(study_out *o, const sl_study_part4 *p);
int study_report_part5(study_out *o, const sl_study_part5 *p);
/* The claims table; a part not in `parts` (bit k = part k+1) is NULL. */
void study_report_claims(study_out *o, const sl_study_part1 *p1, const sl_study_part2 *p2,
                         const sl_study_part3 *p3, const sl_study_part4 *p4);
/* The report's opening paragraph. */
void study_report_preamble(study_out *o);
/* Sections 7 and 8, rocking and the intensity tail against physical floor
 * motions: figdir/STUDY_ROCKING_MD and figdir/STUDY_TAIL_MD (written by
 * `make rockfloors` and `make tailfloors`, which take longer than the
 * study) carried as they are, or how to make them where they are absent.
 * 0 or -1 (message printed). */
#define STUDY_ROCKING_MD "rocking_floors.md"
#define STUDY_TAIL_MD "tail_floors.md"
int study_report_carried(study_out *o);
/* Compute (study/study_parts.h) and write the parts asked for (bit k = part
 * k+1), with progress on stderr unless quiet. 0 or -1 (message printed). */
int study_report_run(study_out *o, const char *records, int parts, int quiet);
/* mkdir path (an existing one is fine). 0 or -1 (errno set). */
int study_make_dir(const char *path);

#endif
