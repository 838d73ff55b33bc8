/*
 * plant_book.h - the plant index: one row per floor of every building, as
 * plant.csv and plant.xlsx.
 *
 * Row: building, floor id, floor name, elevation, horizontal ZPA, motion
 * sets, convergence ("converged", "max_sets", "fixed"), the required
 * clearance at mu = SL_PLANT_BOOK_MU (sl_plant_book_clearance: the computed
 * point; empty where the grid does not hold that mu) and the governing method: which design curve gives the
 * clearance at the grid rows where it is not zero ("NLTHA", "ASCE", "NLTHA
 * and ASCE" under the envelope policy), " (capped)" when the cap governs at
 * any of them; the ASCE/SEI 43-05 design value at the same six mu (beside
 * the governing clearance); the motion checks ("passed", or "FAILED n of m" motion
 * components: a floor accepted with --accept-failed-checks).
 *
 * plant.csv starts with a "# WARNING: CHECKS FAILED: ..." line per floor whose
 * motions failed their checks, then the comment lines of every building CSV (report.h,
 * sl_report_write_csv): program, content, command, created, seed, a
 * "# floor_file_crc32: CRC BUILDING/ID (PATH, N bytes)" line per floor, the
 * title block, then the units; one writer for both (csv.c).
 *
 * plant.xlsx: "Lookup" (building from a drop-down list, floor from a list of
 * that building's floors, mu typed; the clearance in mm by linear
 * interpolation in mu with every step visible, the same formula and input
 * checks as the building workbook's Lookup, report.h; only the three inputs
 * editable), "Plant" (the rows above) and "Data" (the tables the Lookup
 * reads: every floor's clearance on the whole friction grid; hidden, not
 * printed). Printed, every page is A4 with the building workbook's page
 * header and footer (layout.c): the Lookup one portrait page at 100 %, the
 * Plant sheet landscape, fitted to the page width, its header repeated on
 * every page. Every sheet is protected (no password: a guard against typing
 * over).
 */
#ifndef SL_PLANT_BOOK_H
#define SL_PLANT_BOOK_H

#include <stddef.h>
#include <time.h>

#include "method/design.h"
#include "report/report.h"

#define SL_PLANT_BOOK_CSV "plant.csv"
#define SL_PLANT_BOOK_XLSX "plant.xlsx"
#define SL_PLANT_BOOK_NMU 6
extern const double SL_PLANT_BOOK_MU[SL_PLANT_BOOK_NMU]; /* 0.05 0.1 0.2 0.3 0.4 0.5 */

typedef struct sl_plant_book_row {
    const char *building, *id, *name;
    double elevation_m;       /* NAN: not given */
    double zpa_h_ms2;
    size_t n_sets;
    const char *stop;
    const sl_design *design;  /* every row the same friction grid */
    const char *path;         /* the floor file, for the record (NULL: "-") */
    unsigned long crc32;      /* of the file's bytes */
    long size_bytes;
    size_t n_failed_motions;  /* motion components that failed their SRP 3.7.1 checks, of
                                 3 n_sets (kept only by --accept-failed-checks) */
    const double *design_se_m; /* per grid row, the SE of the NLTHA design value (NULL:
                                  FS sd / sqrt(N), as text.c) */
    const char *warnings;     /* the run's warnings about the floor (sl_report_floor.warnings;
                                 NULL or "": none): plant.csv's column warnings, the Lookup */
} sl_plant_book_row;

typedef struct sl_plant_book {
    const char *version, *command_line;
    const char *seed;         /* the run's seed as text (NULL: "-") */
    time_t created;
    sl_report_project project;
    size_t n;
    const sl_plant_book_row *rows; /* grouped by building */
    /* The Lookup's initial inputs (NULL: the first row's; "": blank; mu NAN:
     * blank) and, for tests, 0 as every formula's cached value. */
    const char *lookup_building, *lookup_floor;
    double lookup_mu;
    int lookup_zero_cache;
} sl_plant_book;

/* Two friction values closer than this are the same grid point. */
#define SL_PLANT_BOOK_MU_TOL 1e-9

/* The clearance (m) of design d at the grid row whose mu is within
 * SL_PLANT_BOOK_MU_TOL of mu; NAN when the grid holds no such row. A fixed
 * column of the plant index is a computed point, never interpolated across
 * a coarse grid (a curve between two computed points need not be straight). */
double sl_plant_book_clearance(const sl_design *d, double mu);

/* The ASCE/SEI 43-05 design value (m) of design d at the same grid row (NAN
 * when the grid holds no such row, or ASCE is undefined there): plant.csv's
 * asce_design_mm_mu_X, beside the governing clearance. */
double sl_plant_book_asce(const sl_design *d, double mu);

/* The governing method of a row as text (above), into buf of size n. */
const char *sl_plant_book_governing(const sl_design *d, char *buf, size_t n);

/* dir/plant.csv and dir/plant.xlsx, each written atomically. */
sl_status sl_plant_book_write_csv(const sl_plant_book *b, const char *dir, sl_error *err);
sl_status sl_plant_book_write_xlsx(const sl_plant_book *b, const char *dir, sl_error *err);

#endif
