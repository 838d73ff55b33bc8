/*
 * floor.h - floor response spectrum files, one file per floor, in either of
 * two formats (docs/formats-floor.md; templates/floor.ini, floor.csv),
 * chosen by the extension: .csv (any case) is CSV, anything else INI:
 *
 * INI, read with inih (Debian libinih):
 *
 *     [floor]
 *     name        = Reactor building, el. 30.0 m   ; required, free text
 *     elevation_m = 30.0                           ; optional, m
 *     units       = g                              ; required: g, m/s2, cm/s2, gal, mm/s2
 *     h2          = same_as_h1                     ; only when there is no [h2]
 *     building    = Reactor building               ; optional, free text
 *     description = ...                            ; optional, free text
 *     seed        = 12345                          ; optional, integer >= 0: the
 *                                                  ; floor's own seed (else its
 *                                                  ; spectra's content is used)
 *
 *     [h1]                    ; also [h2] and [v]
 *     f_hz    = 0.1, 0.2, 0.5, 1, 2, 5, 10, 20, 33, 50
 *     sa_0.05 = ...           ; pseudo-spectral acceleration at 5 % damping
 *     sa_0.10 = ...           ; one key per damping ratio, in (0, 1)
 *     zpa     = 0.30          ; optional; else the high-frequency end
 *
 *   Lists are separated by commas and/or blanks and may continue on
 *   indented lines (inih multi-line values); a line holds at most 197
 *   characters (inih's 200-byte line buffer; a longer line is an error,
 *   never split). Comments start with ';' or '#' at the start of a line, or
 *   ' ;' after a value.
 *
 * CSV (RFC 4180; LF or CRLF; UTF-8 with or without BOM; no line-length
 * limit): "# key: value" comment lines with the same floor keys (name,
 * units required; elevation_m, building, description, seed, h2, and
 * zpa_h1, zpa_h2, zpa_v), then a header row "f_hz,h1_5,h1_10,h2_5,...,v_2"
 * (<h1|h2|v>_<damping in percent>), then one row per frequency. Every cell
 * holds a number (an empty cell is an error). Errors name file:line:column
 * (column = 1-based field of the row). The first column may be T_s
 * (periods, s; turned into 1/T in ascending order); a header row with ';'
 * and no ',' makes ';' the separator and a comma the decimal mark (a
 * European spreadsheet's CSV). UTF-16 text is refused as such (both
 * formats), and so, each with how to fix it, a table of one direction and
 * a row of units under the header.
 *
 * Validation, the same for both formats (one checking path, floor.c; every
 * error names the file and the line): [floor], [h1], [v] (or their
 * columns) present; H2 given or `h2 = same_as_h1` declared (never assumed),
 * not both; known keys only, each once; frequencies in SL_FLOOR_F_MIN_HZ-
 * SL_FLOOR_F_MAX_HZ and strictly increasing (at least SL_FLOOR_MIN_POINTS);
 * values positive, finite and at most SL_FLOOR_MAX_SA_G once converted to
 * SI, as many as frequencies; a file larger than SL_FLOOR_MAX_BYTES is
 * refused before it is read, and a file with a NUL byte is "not a text
 * file"; damping ratios in (0, 1), each once per direction; units known;
 * name not empty; a given ZPA within SL_FLOOR_ZPA_END_MIN-SL_FLOOR_ZPA_END_MAX
 * of the spectrum's high-frequency end (below); without a given ZPA the
 * table reaches SL_FLOOR_RIGID_HZ; every value plausible against its
 * neighbours and the other dampings of its direction (SL_FLOOR_SPIKE_MAX,
 * SL_FLOOR_DIP_MAX, SL_FLOOR_ORDER_MIN, SL_FLOOR_SPREAD_MAX).
 *
 * Zero-period acceleration of a component: the `zpa` key (CSV: `# zpa_h1:`)
 * when given, else the largest over its dampings of the value at its
 * highest frequency, each such value checked against the one before it
 * (SL_FLOOR_END_STEP_MIN/_MAX). A given ZPA is checked against the value at the
 * highest frequency of the table at its lowest damping (the spectrum that
 * is last to reach the ZPA): a ratio outside 0.2-1.25 is an input error
 * naming the zpa line (a typo or a units slip, e.g. zpa = 1e-300; a ZPA in
 * g under a table in m/s^2 gives 0.102, in m/s^2 under one in g 9.81).
 *
 * Memory: sl_floor_load() returns a floor the caller frees with
 * sl_floor_free(). The struct is plain data; its spectra are owned by it.
 * Values are stored in SI (m/s^2), whatever the file's units or format.
 */
#ifndef SL_FLOOR_H
#define SL_FLOOR_H

#include <stddef.h>
#include <stdint.h>

#include "core/api.h"
#include "core/spectrum_type.h"
#include "core/standards.h"
#include "core/status.h"
#include "core/units.h"

/* Fewest frequencies a spectrum may have. */
#define SL_FLOOR_MIN_POINTS 2
/* Most damping ratios per component. */
#define SL_FLOOR_MAX_DAMPINGS 16
/* Two damping ratios closer than this are the same (sa_0.1 = sa_0.10). */
#define SL_FLOOR_DAMPING_TOL 1e-9
/* Frequencies a floor spectrum may hold, Hz (outside: a typo or a unit
 * error, refused with the line). */
#define SL_FLOOR_F_MIN_HZ 1e-3
#define SL_FLOOR_F_MAX_HZ 1e4
/* Largest spectral value or ZPA accepted, g (above: not a floor motion). */
#define SL_FLOOR_MAX_SA_G 1000.0
/* Largest floor file read, bytes (checked before reading). */
#define SL_FLOOR_MAX_BYTES (16 * 1024 * 1024)
/* Plausible horizontal ZPA of a floor, g (sl_floor_check_plausible). */
#define SL_FLOOR_ZPA_MIN_G 0.01
#define SL_FLOOR_ZPA_MAX_G 5.0
/* A given ZPA must lie within these multiples of the spectrum's value at
 * its highest frequency, at its lowest damping. A spectrum approaches the
 * ZPA from above: a table ending near a mode of the floor ends well above
 * it (physical floors, tools/plausfloors.c: 0.255-1.001; docs/formats-floor.md,
 * "Zero-period acceleration"), hardly ever below it. */
#define SL_FLOOR_ZPA_END_MIN 0.2
#define SL_FLOOR_ZPA_END_MAX 1.25
/* Plausibility of the spectral values (docs/formats-floor.md,
 * "Plausibility"; thresholds from the worst ratios measured on physical
 * floor spectra, tools/plausfloors.c, with a margin). A value is refused
 * when it is more than SL_FLOOR_SPIKE_MAX times the larger of its two
 * neighbours in its column (at an end: its one neighbour), when the smaller
 * of its two neighbours is more than SL_FLOOR_DIP_MAX times it, when a lower
 * damping's value is below SL_FLOOR_ORDER_MIN times a higher damping's at
 * the same frequency, or above SL_FLOOR_SPREAD_MAX x (z_hi / z_lo) times it
 * (z_hi / z_lo: the ratio of the two dampings, the steady-state resonance
 * amplification ratio), and when a lower damping's column is on average
 * (geometric mean over the frequencies) below SL_FLOOR_ORDER_MEAN_MIN times
 * a higher damping's. */
#define SL_FLOOR_SPIKE_MAX 10.0
#define SL_FLOOR_DIP_MAX 6.0
/* The ends of a table are checked as its inside: a value at the first or
 * last frequency lacks one neighbour, and the trend of the two values next
 * to it (the straight line in log SA over log f through them, extended to
 * the end's frequency) stands in for it; the dip is the smaller of the one
 * neighbour and the trend over the value. At the last frequency the bound
 * is SL_FLOOR_DIP_MAX (physical floors: 2.81 at most); at the first, the
 * low-frequency end where the spectrum of a processed record falls steeply
 * into its table (physical floors: up to 13.3), SL_FLOOR_DIP_FIRST_MAX. */
#define SL_FLOOR_DIP_FIRST_MAX 17.0
/* A ZPA taken from the table's end (no ZPA given) is checked against the
 * trend before it: where the table's last two frequencies lie in the rigid
 * range (>= SL_FLOOR_RIGID_HZ), the last value of each damping over the one
 * before it lies within SL_FLOOR_END_STEP_MIN-MAX (physical floors:
 * 0.356-1.232), else the last row slipped. */
#define SL_FLOOR_END_STEP_MIN 0.28
#define SL_FLOOR_END_STEP_MAX 1.55
#define SL_FLOOR_ORDER_MIN 0.5
#define SL_FLOOR_SPREAD_MAX 1.5
/* A lower damping's spectrum is refused when the geometric mean over the
 * table's frequencies of SA(lower) / SA(higher) is below this (the columns
 * or keys of two dampings swapped). */
#define SL_FLOOR_ORDER_MEAN_MIN 0.9
/* A table without a given ZPA must reach the rigid range, Hz (the ZPA is
 * read from its end; below this frequency it is not known). */
#define SL_FLOOR_RIGID_HZ 33.0
/* A horizontal ZPA outside this band (inside SL_FLOOR_ZPA_MIN_G-MAX_G) is
 * unusual for a floor: a warning, not an error (sl_floor_zpa_warning). */
#define SL_FLOOR_ZPA_WARN_MIN_G 0.05
#define SL_FLOOR_ZPA_WARN_MAX_G 3.0
/* The damping of the spectra the ASCE/SEI 43-05 method uses. */
#define SL_FLOOR_ASCE_DAMPING SL_ASCE_DAMPING /* core/standards.h */

/* The format of a floor file, from its extension. */
typedef enum sl_floor_format {
    SL_FLOOR_INI = 0, /* .ini */
    SL_FLOOR_CSV      /* .csv */
} sl_floor_format;

typedef enum sl_floor_comp {
    SL_FLOOR_H1 = 0,
    SL_FLOOR_H2,
    SL_FLOOR_V,
    SL_FLOOR_NCOMP
} sl_floor_comp;

/* One direction of a floor. */
typedef struct sl_floor_component {
    size_t nspec;       /* number of damping ratios given */
    sl_spectrum *spec;  /* nspec spectra, ascending damping, same frequencies, m/s^2 */
    double zpa_ms2;     /* zero-period acceleration, m/s^2 */
    int zpa_given;      /* 1: from the `zpa` key; 0: from the high-frequency end */
    long line;          /* line of the section header or CSV header row
                           (H2 = H1: that of [h1]) */
} sl_floor_component;

typedef struct sl_floor {
    char *path;         /* the file read */
    char *name;         /* the floor's name */
    char *description;  /* free text, "" when not given */
    char *building;     /* free text, "" when not given */
    sl_floor_format format; /* the file's format */
    double elevation_m; /* NAN when not given */
    sl_unit units;      /* units of the file (values stored in m/s^2) */
    long units_line;    /* line of the units key */
    char *units_text;   /* the units as written ("gal", "cm/s2") */
    int h2_same_as_h1;  /* 1 when the file declared `h2 = same_as_h1` (H2 copies H1) */
    int has_seed;       /* 1 when the file gave `seed =` */
    uint64_t seed;      /* that seed (0 when not given) */
    sl_floor_component comp[SL_FLOOR_NCOMP];
} sl_floor;

/* Read and validate a floor file, CSV when its name ends in .csv (any
 * case), else INI. Returns NULL and fills err (file, line,
 * message; SL_EIO, SL_EPARSE, SL_EINVAL or SL_ENOMEM) on failure. */
SL_API sl_floor *sl_floor_load(const char *path, sl_error *err);

/* Plausibility of the horizontal ZPA (the larger of H1 and H2): SL_OK, or
 * SL_EINVAL naming the file, the units line and the value when it lies
 * outside SL_FLOOR_ZPA_MIN_G-SL_FLOOR_ZPA_MAX_G (e.g. units = gal on values
 * in g). The caller decides whether that stops the run. */
SL_API sl_status sl_floor_check_plausible(const sl_floor *fl, sl_error *err);

/* An unusual horizontal ZPA (SL_FLOOR_ZPA_WARN_MIN_G-MAX_G; floor.h): when
 * zpa_h_ms2 lies outside that band, writes into buf (size n) the warning
 * "units = m/s2 gives a horizontal ZPA of 0.0398 g, unusual for a floor
 * (...)", naming the units as written (units_text) the way the file of
 * format fmt writes the key, and returns 1; else buf "" and 0. The run's
 * stderr and the workbook's Notes both use it. */
SL_API int sl_floor_zpa_warning_text(double zpa_h_ms2, const char *units_text,
                                     sl_floor_format fmt, char *buf, size_t n);

/* The same for a floor read (its larger horizontal ZPA, units and
 * format). */
SL_API int sl_floor_zpa_warning(const sl_floor *fl, char *buf, size_t n);

/* The worst ratios of a floor's values (the quantities the plausibility
 * rules bound, above), over every direction, damping and frequency. */
typedef struct sl_floor_plausibility {
    double spike;  /* largest value / larger neighbour (ends: the one neighbour) */
    double dip;    /* largest smaller neighbour / value (inside the table, and at its last
                      frequency the smaller of its neighbour and the trend) */
    double order;  /* smallest SA(lower damping) / SA(higher damping), same frequency */
    double spread; /* largest SA(lower) / SA(higher) / (z_hi / z_lo) */
    double order_mean; /* smallest geometric mean over frequency of SA(lower) / SA(higher) */
    double dip_first;  /* the dip at the first frequency (SL_FLOOR_DIP_FIRST_MAX) */
    /* the last value over the one before it where both frequencies are in the
     * rigid range (SL_FLOOR_END_STEP_MIN-MAX): lowest and highest; 1 when no
     * table ends so */
    double end_step_lo, end_step_hi;
    /* where each is (in this order: spike, dip, order, spread, order_mean,
     * dip_first, end_step_lo, end_step_hi): direction, frequency (Hz;
     * order_mean: the first) and (lower) damping ratio */
    int at_comp[8];
    double at_f_hz[8], at_damping[8];
} sl_floor_plausibility;
SL_API void sl_floor_plausibility_of(const sl_floor *fl, sl_floor_plausibility *p);

/* The format a path names by its extension: SL_FLOOR_CSV for .csv (any
 * case), else SL_FLOOR_INI. */
SL_API sl_floor_format sl_floor_format_of(const char *path);

/* The floor files named by `arg`: the file itself, or every *.ini and
 * *.csv in it (any case of the extension; hidden files skipped) when it is
 * a folder (sorted by name). Appends strdup'd paths to paths[*n], at most
 * `max` in all. SL_EIO (missing, unreadable, no floor file) or SL_EINVAL (more
 * than max) with the path in err. */
SL_API sl_status sl_floor_list(const char *arg, char **paths, size_t *n, size_t max, sl_error *err);

/* Free a floor; harmless on NULL. */
SL_API void sl_floor_free(sl_floor *fl);

/* Section name of a component: "h1", "h2", "v". */
SL_API const char *sl_floor_comp_name(sl_floor_comp c);

/* The spectrum of component c at damping ratio `damping` (matched within
 * SL_FLOOR_DAMPING_TOL), or NULL when the file does not give it. Borrowed
 * pointer, valid until sl_floor_free(). */
SL_API const sl_spectrum *sl_floor_spectrum(const sl_floor *fl, sl_floor_comp c, double damping);

/* The 10 %-damped spectrum of component c (SL_FLOOR_ASCE_DAMPING), or NULL
 * when it is missing: the caller must then say so in its output and use its
 * documented fallback; the library never substitutes one silently. */
SL_API const sl_spectrum *sl_floor_sa10(const sl_floor *fl, sl_floor_comp c);

#endif
