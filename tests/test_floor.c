/* test_floor.c - floor response spectrum files, INI and CSV: the templates
 * and the good fixtures load with the right values, the CSV template is the
 * INI template bit for bit; every bad fixture fails with its file, line
 * (and CSV column) and a message that says what is wrong. Run from the
 * repository root (make test does). */
#include <dirent.h>
#include <fcntl.h>
#include <math.h>
#include <stdio.h>
#include <unistd.h>

#include "io/floor.h"
#include "io/text.h"
#include "harness.h"
#include "core/units.h"

#define FLOORS "tests/data/floors/"

static void test_template(void)
{
    sl_error e;
    sl_error_clear(&e);
    sl_floor *fl = sl_floor_load("templates/floor.ini", &e);
    char buf[2200];
    CHECK(fl != NULL, "template: %s", sl_error_format(&e, buf, sizeof buf));
    if (!fl)
        return;
    CHECK(!strcmp(fl->name, "Example building, floor at el. 30.0 m"), "name '%s'", fl->name);
    CHECK(fl->elevation_m == 30.0 && fl->units == SL_UNIT_G && !fl->h2_same_as_h1, "header");
    for (int k = 0; k < SL_FLOOR_NCOMP; k++) {
        const sl_floor_component *c = &fl->comp[k];
        CHECK(c->nspec == 2 && c->spec[0].damping == 0.05 && c->spec[1].damping == 0.10,
              "%s dampings", sl_floor_comp_name((sl_floor_comp)k));
        CHECK(c->spec[0].n == 24 && c->spec[0].f_hz[0] == 0.1 && c->spec[0].f_hz[23] == 50,
              "%s frequencies", sl_floor_comp_name((sl_floor_comp)k));
        CHECK(sl_floor_sa10(fl, (sl_floor_comp)k) == &c->spec[1], "sa10");
        CHECK(sl_floor_spectrum(fl, (sl_floor_comp)k, 0.07) == NULL, "no 7 %%");
    }
    /* values converted from g; zpa given for H1, from the end for H2 and V */
    CHECK_CLOSE(fl->comp[SL_FLOOR_H1].spec[1].sa_ms2[12], 1.4299 * SL_G, 0, 1e-15);
    CHECK(fl->comp[SL_FLOOR_H1].zpa_given, "h1 zpa given");
    CHECK_CLOSE(fl->comp[SL_FLOOR_H1].zpa_ms2, 0.36 * SL_G, 0, 1e-15);
    CHECK(!fl->comp[SL_FLOOR_H2].zpa_given, "h2 zpa from the end");
    CHECK_CLOSE(fl->comp[SL_FLOOR_H2].zpa_ms2, 0.3063 * SL_G, 0, 1e-15); /* max(5 %, 10 %) */
    CHECK_CLOSE(fl->comp[SL_FLOOR_V].zpa_ms2, 0.3612 * SL_G, 0, 1e-15);
    sl_floor_free(fl);
}

static void test_good_small(void)
{
    sl_error e;
    sl_floor *fl = sl_floor_load(FLOORS "good-small.ini", &e);
    char buf[2200];
    CHECK(fl != NULL, "%s", sl_error_format(&e, buf, sizeof buf));
    if (!fl)
        return;
    CHECK(fl->h2_same_as_h1 && isnan(fl->elevation_m) && !strcmp(fl->description, ""),
          "header");
    CHECK(!fl->has_seed && fl->seed == 0, "no seed given");
    const sl_spectrum *h1 = sl_floor_sa10(fl, SL_FLOOR_H1), *h2 = sl_floor_sa10(fl, SL_FLOOR_H2);
    CHECK(h1 && h2 && h1 != h2 && h2->n == 6, "H2 is a copy of H1");
    for (size_t j = 0; h1 && h2 && j < 6; j++)
        CHECK(h1->f_hz[j] == h2->f_hz[j] && h1->sa_ms2[j] == h2->sa_ms2[j], "point %zu", j);
    /* m/s2: values unchanged; sorted by damping although given 0.10 first */
    CHECK(fl->comp[SL_FLOOR_H1].spec[0].damping == 0.05, "ascending damping");
    CHECK(fl->comp[SL_FLOOR_H1].spec[0].sa_ms2[3] == 8.0, "value");
    const sl_spectrum *v = sl_floor_sa10(fl, SL_FLOOR_V);
    CHECK(v && v->n == 3 && v->f_hz[1] == 10 && v->sa_ms2[2] == 2, "V by blanks");
    CHECK(sl_floor_spectrum(fl, SL_FLOOR_V, 0.05) == NULL, "V has no 5 %%");
    CHECK(fl->comp[SL_FLOOR_V].zpa_ms2 == 2.5 && fl->comp[SL_FLOOR_V].zpa_given, "zpa");
    CHECK(sl_floor_spectrum(fl, SL_FLOOR_H1, 0.1 + 1e-12) == h1, "damping tolerance");
    sl_floor_free(fl);
    sl_floor_free(NULL);
}

/* Each bad fixture: the error's file, line, a phrase of its message and
 * the column (CSV; 0 = none). */
static const struct {
    const char *file;
    long line;
    const char *phrase;
    long col;
} bad[] = {
    {"bad-count.ini", 10, "has 5 values but f_hz (line 8) has 6", 0},
    {"bad-damping-high.ini", 10, "damping 1.5 outside (0, 1)", 0},
    {"bad-damping-zero.ini", 10, "damping 0 outside (0, 1)", 0},
    {"bad-duplicate-damping.ini", 10, "given twice", 0},
    {"bad-duplicate-key.ini", 10, "'f_hz' repeated", 0},
    {"bad-empty-name.ini", 3, "name is empty", 0},
    {"bad-freq-nonpositive.ini", 8, "must be positive", 0},
    {"bad-freq-range.ini", 8, "frequency 1e-300 Hz outside 0.001-10000 Hz", 0},
    {"bad-h2-both.ini", 5, "give one", 0},
    {"bad-h2-value.ini", 5, "same_as_h1", 0},
    {"bad-indented-key.ini", 9, "continuation", 0},
    {"bad-long-line.ini", 9, "line longer than", 0},
    {"bad-missing-floor.ini", 15, "missing section [floor]", 0},
    {"bad-missing-v.ini", 15, "missing section [v]", 0},
    {"bad-no-h2.ini", 2, "H2 not given", 0},
    {"bad-no-spectrum.ini", 12, "[v] has no spectrum", 0},
    {"bad-no-units.ini", 2, "no 'units'", 0},
    {"bad-nonincreasing.ini", 9, "increase strictly", 0},
    {"bad-number.ini", 8, "'5x' is not a finite number", 0},
    {"bad-one-point.ini", 13, "at least 2", 0},
    {"bad-repeated-section.ini", 12, "section [h1] repeated", 0},
    {"bad-seed.ini", 6, "seed: '-3' is not an integer", 0},
    {"bad-syntax.ini", 7, "syntax error", 0},
    {"bad-units.ini", 4, "unknown units 'furlongs/fortnight2'", 0},
    {"bad-unknown-floor-key.ini", 3, "unknown key 'nmae'", 0},
    {"bad-unknown-key.ini", 9, "unknown key 'damping' in [h1]", 0},
    {"bad-unknown-section.ini", 12, "unknown section [h3]", 0},
    {"bad-value-nan.ini", 10, "'nan' is not a finite number", 0},
    {"bad-value-nonpositive.ini", 9, "value -4 must be positive", 0},
    {"bad-value-overflow.ini", 9, "sa_0.1: value 1e+308 g is above 1000 g", 0},
    {"bad-zpa.ini", 15, "zpa: value -1 must be positive", 0},
    {"bad-zpa-huge.ini", 15, "zpa: value 2000 g is above 1000 g", 0},
    {"bad-zpa-end.ini", 15, "zpa: 1e-300 m/s2 is 5e-301 x the 10 % spectrum's value at its "
                            "highest frequency (2 m/s2 at 50 Hz)", 0},
    {"bad-binary.ini", 4, "not a text file: NUL byte at line 4", 0},
    /* CSV */
    {"bad-csv-after-quote.csv", 4, "text after the closing quote", 2},
    {"bad-csv-binary.csv", 3, "not a text file: NUL byte at line 3", 0},
    {"bad-csv-bom-middle.csv", 6, "byte-order mark inside the file", 0},
    {"bad-csv-comment-after.csv", 6, "comment line after the header row", 0},
    {"bad-csv-control.csv", 6, "not a text file: control byte 0x07", 0},
    {"bad-csv-damping-100.csv", 4, "h1_100: damping 100 % outside (0, 100) %", 3},
    {"bad-csv-damping-name.csv", 4, "column 'h1_x': the damping after '_' must be a number", 3},
    {"bad-csv-damping-zero.csv", 4, "h1_0: damping 0 % outside (0, 100) %", 2},
    {"bad-csv-duplicate-column.csv", 4, "damping 5 % given twice (first at line 4, column 2)", 3},
    {"bad-csv-empty-cell.csv", 6, "h1_10: empty cell", 3},
    {"bad-csv-empty-name.csv", 1, "name is empty", 0},
    {"bad-csv-empty.csv", 1, "no header row", 0},
    {"bad-csv-f-range.csv", 7, "frequency 33000 Hz outside 0.001-10000 Hz", 1},
    {"bad-csv-h2-both.csv", 3, "'# h2: same_as_h1' and h2_ columns (line 4): give one", 0},
    {"bad-csv-h4.csv", 4, "unknown column 'h4_5'", 3},
    {"bad-csv-header-only.csv", 4, "f_hz: 0 frequency row(s); at least 2", 1},
    {"bad-csv-inf.csv", 6, "v_5: 'inf' is not a finite number", 4},
    {"bad-csv-nan.csv", 6, "h1_10: 'NaN' is not a finite number", 3},
    {"bad-csv-negative.csv", 6, "h1_5: value -1.2 must be positive", 2},
    {"bad-csv-no-f.csv", 4, "first column 'h1_5': it must be 'f_hz'", 1},
    {"bad-csv-no-h2.csv", 3, "H2 not given", 0},
    {"bad-csv-no-units.csv", 3, "no '# units: ...' line", 0},
    {"bad-csv-no-v.csv", 4, "no v_<damping> column", 0},
    {"bad-csv-nonmonotone.csv", 7, "frequencies must increase strictly: 5 after 10", 1},
    {"bad-csv-not-utf8.csv", 6, "not UTF-8 text: byte 0xe9", 0},
    {"bad-csv-one-row.csv", 4, "f_hz: 1 frequency row(s); at least 2", 1},
    {"bad-csv-quote.csv", 6, "quote not closed", 2},
    {"bad-csv-ragged.csv", 6, "ragged row: 3 cells, the header row has 4", 4},
    {"bad-csv-repeated-key.csv", 4, "key 'units' repeated (first at line 2)", 0},
    {"bad-csv-units.csv", 2, "unknown units 'furlongs'", 0},
    {"bad-csv-extra-cell.csv", 6, "ragged row: 5 cells, the header row has 4", 5}, /* CRLF */
    {"bad-csv-two-errors.csv", 6, "v_5: value -0.6 must be positive", 4}, /* the first in the file */
    {"bad-csv-unknown-key.csv", 4, "unknown comment key 'floor_name'", 0},
    {"bad-csv-zpa-h2-same.csv", 4, "zpa_h2 given but H2 is declared the same as H1", 0},
    {"bad-csv-zpa.csv", 4, "zpa_h1: 1e-300 g is 2.5e-300 x the 5 % spectrum's value", 0},
    /* implausible values, each refused at its cell (floor.h, SL_FLOOR_SPIKE_MAX ...) */
    {"bad-spike.ini", 10, "[h1] sa_0.02 at 10 Hz: value 500 g is 147 x the larger of its "
                          "neighbours (3.4 g at 5 Hz)", 0},
    {"bad-csv-spike.csv", 9, "h1_2 at 10 Hz: value 500 g is 147 x the larger of its neighbours",
     2},
    {"bad-csv-dip.csv", 7, "v_5 at 2 Hz: value 0.0069 g is 1/55.1 of the smaller of its "
                           "neighbours (0.38 g)", 5},
    {"bad-csv-order.csv", 8, "h1_2 at 5 Hz: value 0.34 g is 0.135 x the higher damping's h1_5 "
                             "there (2.52 g, line 8, column 3)", 2},
    {"bad-csv-spread.csv", 5, "h1_2 at 0.5 Hz: value 4.413 g is 13.4 x the higher damping's "
                              "h1_5 there (0.33 g, line 5, column 3)", 2},
    {"bad-csv-swapped.csv", 4, "h1_5: on average over the table (geometric mean) 0.782 x the "
                               "higher damping's h1_10 (line 4, column 3)", 4},
    /* a table short of the rigid range without zpa */
    {"bad-short.ini", 8, "[h1] f_hz: the table ends at 25 Hz, below the rigid range (33 Hz), "
                         "and gives no ZPA, so the floor's ZPA is not known: extend the table "
                         "to 33 Hz or more, or give zpa", 0},
    {"bad-csv-short.csv", 10, "f_hz: the table ends at 25 Hz, below the rigid range (33 Hz), and "
                              "gives no ZPA, so the floor's ZPA is not known: extend the table "
                              "to 33 Hz or more, or give zpa ('# zpa_h1: <value>')", 1},
    /* tables as engineers save them: what is refused says how to fix it */
    {"bad-csv-utf16.csv", 1, "the file is UTF-16LE text, not UTF-8: save it as UTF-8", 0},
    {"bad-csv-utf16le.csv", 1, "the file is UTF-16LE text, not UTF-8: save it as UTF-8", 0},
    {"bad-utf16.ini", 1, "the file is UTF-16BE text, not UTF-8: save it as UTF-8", 0},
    {"bad-csv-units-row.csv", 5, "a units row under the header row ('Hz', 'g', ...): give the "
                                 "units once, as '# units: g'", 1},
    {"bad-csv-per-direction.csv", 3, "column '5%' gives a damping but no direction: a floor "
                                     "file is one file per floor, not per direction", 2},
    {"bad-csv-period-zero.csv", 5, "T_s: period 0 s (the zero-period acceleration): give it as "
                                   "'# zpa_h1: <value>'", 1},
    {"bad-csv-period-order.csv", 7, "T_s: periods must increase (or decrease) strictly: 0.1 "
                                    "after 0.2", 1},
    {"bad-csv-decimal-mixed.csv", 6, "h1_5: '2.520,5' mixes ',' and '.'", 2},
    {"bad-csv-separators.csv", 4, "the header row holds both ',' and ';'", 0},
};
#define N_BAD (sizeof bad / sizeof bad[0])

static void test_bad_files(void)
{
    for (size_t i = 0; i < N_BAD; i++) {
        char path[256];
        snprintf(path, sizeof path, FLOORS "%s", bad[i].file);
        sl_error e;
        sl_error_clear(&e);
        sl_floor *fl = sl_floor_load(path, &e);
        CHECK(fl == NULL, "%s loaded", bad[i].file);
        sl_floor_free(fl);
        CHECK(e.code != SL_OK, "%s: no code", bad[i].file);
        CHECK(!strcmp(e.file, path), "%s: file '%s'", bad[i].file, e.file);
        CHECK(e.line == bad[i].line, "%s: line %ld, expected %ld (%s)", bad[i].file, e.line,
              bad[i].line, e.msg);
        CHECK(strstr(e.msg, bad[i].phrase) != NULL, "%s: message '%s' lacks '%s'",
              bad[i].file, e.msg, bad[i].phrase);
        CHECK(e.col == bad[i].col, "%s: column %ld, expected %ld (%s)", bad[i].file, e.col,
              bad[i].col, e.msg);
    }
}

/* The CSV template holds the INI template's spectra: the same floor, bit
 * for bit (values, dampings, ZPA, name), so the same seed and results. */
static void test_csv_template_equals_ini(void)
{
    sl_error e;
    char buf[2200];
    sl_floor *a = sl_floor_load("templates/floor.ini", &e);
    sl_floor *b = sl_floor_load("templates/floor.csv", &e);
    CHECK(a && b, "%s", sl_error_format(&e, buf, sizeof buf));
    if (!a || !b) {
        sl_floor_free(a);
        sl_floor_free(b);
        return;
    }
    CHECK(a->format == SL_FLOOR_INI && b->format == SL_FLOOR_CSV, "formats");
    CHECK(!strcmp(a->name, b->name) && !strcmp(a->description, b->description) &&
          a->elevation_m == b->elevation_m && a->units == b->units &&
          a->h2_same_as_h1 == b->h2_same_as_h1 && a->has_seed == b->has_seed,
          "header fields");
    for (int k = 0; k < SL_FLOOR_NCOMP; k++) {
        const sl_floor_component *x = &a->comp[k], *y = &b->comp[k];
        CHECK(x->nspec == y->nspec && x->zpa_ms2 == y->zpa_ms2 && x->zpa_given == y->zpa_given,
              "%s: nspec/zpa", sl_floor_comp_name((sl_floor_comp)k));
        for (size_t s = 0; s < x->nspec && s < y->nspec; s++) {
            CHECK(x->spec[s].n == y->spec[s].n && x->spec[s].damping == y->spec[s].damping,
                  "%s spectrum %zu", sl_floor_comp_name((sl_floor_comp)k), s);
            for (size_t j = 0; j < x->spec[s].n && j < y->spec[s].n; j++)
                CHECK(x->spec[s].f_hz[j] == y->spec[s].f_hz[j] &&
                          x->spec[s].sa_ms2[j] == y->spec[s].sa_ms2[j],
                      "%s spectrum %zu point %zu", sl_floor_comp_name((sl_floor_comp)k), s, j);
        }
    }
    sl_floor_free(a);
    sl_floor_free(b);
}

/* BOM, CRLF, quoted header and cells, blanks, free comments, the optional
 * keys, a damping of 2.5 %. */
static void test_good_small_csv(void)
{
    sl_error e;
    char buf[2200];
    sl_floor *fl = sl_floor_load(FLOORS "good-small.csv", &e);
    CHECK(fl != NULL, "%s", sl_error_format(&e, buf, sizeof buf));
    if (!fl)
        return;
    CHECK(!strcmp(fl->name, "Test floor, \"CSV\" form"), "name '%s'", fl->name);
    CHECK(!strcmp(fl->building, "Aux") && fl->elevation_m == 12.5 && fl->units == SL_UNIT_MS2,
          "keys");
    CHECK(fl->has_seed && fl->seed == 42 && !fl->h2_same_as_h1, "seed, h2");
    const sl_floor_component *h1 = &fl->comp[SL_FLOOR_H1];
    CHECK(h1->nspec == 2 && h1->spec[0].damping == 0.05 && h1->spec[1].damping == 0.10, "h1");
    CHECK(h1->spec[0].n == 4 && h1->spec[0].f_hz[2] == 10 && h1->spec[0].sa_ms2[1] == 2.5,
          "h1 values");
    CHECK(h1->zpa_given && h1->zpa_ms2 == 3.2, "zpa_h1");
    const sl_spectrum *v = sl_floor_spectrum(fl, SL_FLOOR_V, 0.025);
    CHECK(v && v->damping == 0.025 && v->sa_ms2[2] == 2.0, "v_2.5 (quoted cell)");
    const sl_spectrum *v10 = sl_floor_spectrum(fl, SL_FLOOR_V, 0.10);
    CHECK(v10 && v10->damping == 0.10 && v10->sa_ms2[3] == 1.2, "v_1e1 is 10 %%");
    CHECK(!fl->comp[SL_FLOOR_V].zpa_given && fl->comp[SL_FLOOR_V].zpa_ms2 == 1.5, "v zpa");
    CHECK(fl->comp[SL_FLOOR_H2].nspec == 1 && fl->comp[SL_FLOOR_H2].spec[0].sa_ms2[3] == 2.7,
          "h2");
    sl_floor_free(fl);
}

/* A fresh folder (dir, a mkdtemp template) and the path of file `name` in
 * it; 0 when the folder cannot be made. */
static int tmp_path(char *dir, char *path, size_t n, const char *name)
{
    if (!mkdtemp(dir))
        return 0;
    snprintf(path, n, "%s/%s", dir, name);
    return 1;
}

/* A file larger than SL_FLOOR_MAX_BYTES is refused before it is read; a
 * CSV line longer than any buffer is read. */
static void test_sizes(void)
{
    char dir[] = "/tmp/sl-floor-XXXXXX", path[64];
    CHECK(tmp_path(dir, path, sizeof path, "huge.csv"), "mkdtemp");
    int fd = open(path, O_CREAT | O_WRONLY | O_TRUNC, 0600);
    CHECK(fd >= 0, "open");
    if (fd < 0)
        return;
    CHECK(ftruncate(fd, (off_t)SL_FLOOR_MAX_BYTES + 1) == 0, "ftruncate");
    close(fd);
    sl_error e;
    sl_error_clear(&e);
    CHECK(sl_floor_load(path, &e) == NULL && e.code == SL_EINVAL &&
              strstr(e.msg, "larger than the 16777216 bytes a floor file may have"),
          "huge: %s", e.msg);
    /* one long header and row: 3000 columns of H1 dampings would exceed
     * SL_FLOOR_MAX_DAMPINGS, so the long line is a long name instead */
    FILE *f = fopen(path, "w");
    CHECK(f != NULL, "fopen");
    if (!f)
        return;
    fputs("# name: ", f);
    for (int i = 0; i < 5000; i++)
        fputc('a' + i % 26, f);
    fputs("\n# units: g\n# h2: same_as_h1\nf_hz,h1_5,v_5\n1,0.5,0.3\n33,0.4,0.3\n", f);
    fclose(f);
    sl_floor *fl = sl_floor_load(path, &e);
    CHECK(fl && strlen(fl->name) == 5000, "long line: %s", fl ? "" : e.msg);
    sl_floor_free(fl);
    remove(path);
    rmdir(dir);
}

/* units = gal on values in g: loaded, then refused by the plausibility
 * check in the unit the file wrote. */
static void test_plausible_units_text(void)
{
    sl_error e;
    sl_floor *fl = sl_floor_load(FLOORS "implausible-gal.ini", &e);
    CHECK(fl != NULL, "load");
    if (!fl)
        return;
    CHECK(sl_floor_check_plausible(fl, &e) == SL_EINVAL && e.line == 4 &&
              strstr(e.msg, "units = gal gives a horizontal ZPA of 0.0003161 g"),
          "message '%s'", e.msg);
    sl_floor_free(fl);
}

/* Two floors with the same spectra, bit for bit (values, dampings, ZPAs,
 * name, units); frequencies within rel_f (0: bit for bit). */
static void check_same_floor(const char *pa, const char *pb, double rel_f)
{
    sl_error e;
    char buf[2200];
    sl_floor *a = sl_floor_load(pa, &e);
    CHECK(a != NULL, "%s", sl_error_format(&e, buf, sizeof buf));
    sl_floor *b = sl_floor_load(pb, &e);
    CHECK(b != NULL, "%s", sl_error_format(&e, buf, sizeof buf));
    if (a && b) {
        CHECK(!strcmp(a->name, b->name) && a->units == b->units &&
                  a->elevation_m == b->elevation_m,
              "%s: header", pb);
        for (int k = 0; k < SL_FLOOR_NCOMP; k++) {
            const sl_floor_component *ca = &a->comp[k], *cb = &b->comp[k];
            CHECK(ca->nspec == cb->nspec && ca->zpa_ms2 == cb->zpa_ms2 &&
                      ca->zpa_given == cb->zpa_given,
                  "%s %s: dampings or ZPA", pb, sl_floor_comp_name((sl_floor_comp)k));
            for (size_t q = 0; q < ca->nspec && q < cb->nspec; q++) {
                const sl_spectrum *x = &ca->spec[q], *y = &cb->spec[q];
                CHECK(x->n == y->n && x->damping == y->damping, "%s: spectrum %zu", pb, q);
                for (size_t j = 0; j < x->n && j < y->n; j++) {
                    CHECK(x->sa_ms2[j] == y->sa_ms2[j], "%s: value %zu/%zu: %.17g vs %.17g", pb,
                          q, j, x->sa_ms2[j], y->sa_ms2[j]);
                    CHECK_CLOSE(y->f_hz[j], x->f_hz[j], 0, rel_f);
                }
            }
        }
    }
    sl_floor_free(a);
    sl_floor_free(b);
}

/* A table as a European spreadsheet saves it (';', decimal commas, comment
 * rows padded with empty cells, an empty row, CRLF) is the CSV template bit
 * for bit; a table of periods (T_s, ascending) is the template with its
 * frequencies 1/T, sorted ascending (within the rounding of 1/T). */
static void test_tables_as_saved(void)
{
    check_same_floor("templates/floor.csv", FLOORS "good-semicolon.csv", 0);
    check_same_floor("templates/floor.csv", FLOORS "good-periods.csv", 1e-15);
}

/* The plausibility rules at their thresholds: a table whose one value is
 * exactly at the limit loads, a hair beyond it is refused at that cell.
 * Spike (1 Hz) and dip (2 Hz) in v_5; order: the h1_2 cell at 20 Hz k x
 * h1_10, its others 2 x; spread and order on average: the whole h1_2 column
 * k x h1_10 (so that only the rule tried can fail), refused at its first row
 * and at its header. */
static void test_plausibility_thresholds(void)
{
    char dir[] = "/tmp/sl-floor-XXXXXX", path[64];
    CHECK(tmp_path(dir, path, sizeof path, "t.csv"), "mkdtemp");
    const struct {
        const char *what;
        double k_ok, k_bad;
        long line, col; /* the cell refused */
    } c[] = {
        {"spike", SL_FLOOR_SPIKE_MAX, SL_FLOOR_SPIKE_MAX * 1.001, 6, 4},
        {"dip", SL_FLOOR_DIP_MAX, SL_FLOOR_DIP_MAX * 1.001, 7, 4},
        {"order", SL_FLOOR_ORDER_MIN, SL_FLOOR_ORDER_MIN / 1.001, 8, 2},
        {"spread", SL_FLOOR_SPREAD_MAX * 5, SL_FLOOR_SPREAD_MAX * 5 * 1.001, 5, 2},
        {"order on average", SL_FLOOR_ORDER_MEAN_MIN, SL_FLOOR_ORDER_MEAN_MIN / 1.001, 4, 2},
    };
    for (size_t i = 0; i < sizeof c / sizeof c[0]; i++)
        for (int beyond = 0; beyond < 2; beyond++) {
            double k = beyond ? c[i].k_bad : c[i].k_ok;
            /* h1_2 against h1_10 = 1: order, one cell (20 Hz) k, the others 2; spread and
             * order on average, the whole column k */
            double h = i >= 3 ? k : i == 2 ? 2.0 : 1.0, h20 = i >= 2 ? k : h;
            double v1 = i == 0 ? k : 1.0, v2 = i == 1 ? 1.0 / k : 1.0; /* v_5 */
            FILE *f = fopen(path, "w");
            CHECK(f != NULL, "fopen");
            if (!f)
                return;
            fprintf(f, "# name: t\n# units: g\n# h2: same_as_h1\nf_hz,h1_2,h1_10,v_5\n"
                       "0.5,%.17g,1,1\n1,%.17g,1,%.17g\n2,%.17g,1,%.17g\n20,%.17g,1,1\n"
                       "33,%.17g,1,1\n",
                    h, h, v1, h, v2, h20, h);
            fclose(f);
            sl_error e;
            sl_error_clear(&e);
            sl_floor *fl = sl_floor_load(path, &e);
            if (beyond)
                CHECK(!fl && e.line == c[i].line && e.col == c[i].col,
                      "%s at %.17g: refused at %ld:%ld (%s)", c[i].what, k, e.line, e.col,
                      e.msg);
            else
                CHECK(fl != NULL, "%s at the limit %.17g refused: %s", c[i].what, k, e.msg);
            sl_floor_free(fl);
        }
    remove(path);
    rmdir(dir);
}

/* Both ends of a table are checked as its inside is (issue 39: the last row
 * of 02-el12 divided by 10 passed, ZPA 0.039 g): h1_5 of 1 at 0.5, 1, 2, 20,
 * 33, 40 and 50 Hz with one end changed by k, each rule at its bound (loads)
 * and a hair beyond it (refused at that cell): the dip at the last frequency
 * (a ZPA given, so that only the dip can refuse it) and at the first, the
 * spike at either end, and, with the ZPA taken from the table's end, its
 * step from the value before it in the rigid range. */
static void test_table_ends(void)
{
    char dir[] = "/tmp/sl-floor-XXXXXX", path[64];
    CHECK(tmp_path(dir, path, sizeof path, "e.csv"), "mkdtemp");
    enum { DIP_LAST, DIP_FIRST, SPIKE_LAST, SPIKE_FIRST, STEP_LOW, STEP_HIGH };
    const struct {
        const char *what;
        int rule;
        double k;
        int ok;
    } c[] = {
        {"dip at the last frequency", DIP_LAST, SL_FLOOR_DIP_MAX, 1},
        {"dip at the last frequency", DIP_LAST, SL_FLOOR_DIP_MAX * 1.001, 0},
        {"dip at the first frequency", DIP_FIRST, SL_FLOOR_DIP_FIRST_MAX, 1},
        {"dip at the first frequency", DIP_FIRST, SL_FLOOR_DIP_FIRST_MAX * 1.001, 0},
        {"spike at the last frequency", SPIKE_LAST, SL_FLOOR_SPIKE_MAX, 1},
        {"spike at the last frequency", SPIKE_LAST, SL_FLOOR_SPIKE_MAX * 1.001, 0},
        {"spike at the first frequency", SPIKE_FIRST, SL_FLOOR_SPIKE_MAX, 1},
        {"spike at the first frequency", SPIKE_FIRST, SL_FLOOR_SPIKE_MAX * 1.001, 0},
        {"a ZPA from the end, low", STEP_LOW, SL_FLOOR_END_STEP_MIN, 1},
        {"a ZPA from the end, low", STEP_LOW, SL_FLOOR_END_STEP_MIN / 1.001, 0},
        {"a ZPA from the end, high", STEP_HIGH, SL_FLOOR_END_STEP_MAX, 1},
        {"a ZPA from the end, high", STEP_HIGH, SL_FLOOR_END_STEP_MAX * 1.001, 0},
    };
    static const double fz[] = {0.5, 1, 2, 20, 33, 40, 50};
    for (size_t i = 0; i < sizeof c / sizeof c[0]; i++) {
        double v[7] = {1, 1, 1, 1, 1, 1, 1}, zpa = 0;
        int last = c[i].rule != DIP_FIRST && c[i].rule != SPIKE_FIRST;
        double end = c[i].rule == DIP_LAST || c[i].rule == DIP_FIRST ? 1.0 / c[i].k : c[i].k;
        if (c[i].rule == STEP_LOW)
            end = c[i].k;
        v[last ? 6 : 0] = end;
        if (c[i].rule == DIP_LAST || c[i].rule == SPIKE_LAST)
            zpa = end; /* given: the step rule stays out */
        FILE *f = fopen(path, "w");
        CHECK(f != NULL, "fopen");
        if (!f)
            return;
        fprintf(f, "# name: t\n# units: g\n# h2: same_as_h1\n");
        if (zpa > 0)
            fprintf(f, "# zpa_h1: %.17g\n", zpa);
        fprintf(f, "f_hz,h1_5,v_5\n");
        for (int j = 0; j < 7; j++)
            fprintf(f, "%g,%.17g,1\n", fz[j], v[j]);
        fclose(f);
        sl_error e;
        sl_error_clear(&e);
        sl_floor *fl = sl_floor_load(path, &e);
        long line = zpa > 0 ? 5 : 4; /* the header row's line */
        long want = line + (last ? 7 : 1);
        if (c[i].ok)
            CHECK(fl != NULL, "%s at the bound %.17g refused: %s", c[i].what, c[i].k, e.msg);
        else
            CHECK(!fl && e.line == want && e.col == 2, "%s at %.17g: refused at %ld:%ld, "
                  "expected %ld:2 (%s)", c[i].what, c[i].k, e.line, e.col, want, e.msg);
        sl_floor_free(fl);
    }
    /* a steady steep rise into the table (x 32 per octave, as f^5: the trend
     * gives the first value exactly) loads, though its neighbour is 32 x it */
    FILE *f = fopen(path, "w");
    CHECK(f != NULL, "fopen");
    if (f) {
        fprintf(f, "# name: t\n# units: g\n# h2: same_as_h1\nf_hz,h1_5,v_5\n0.1,0.001,1\n"
                   "0.2,0.032,1\n0.4,1.024,1\n2,1.024,1\n20,1.024,1\n33,1.024,1\n50,1.024,1\n");
        fclose(f);
        sl_error e;
        sl_floor *fl = sl_floor_load(path, &e);
        CHECK(fl != NULL, "a steady rise into the table refused: %s", fl ? "" : e.msg);
        sl_floor_free(fl);
    }
    remove(path);
    rmdir(dir);
}

/* The slip of issue 39 itself: 02-el12 without its zpa keys, the last row of
 * H1 and H2 divided by 10 (ZPA 0.039 g, `asce --floor` gave 0 mm), is refused
 * at H1's last value, naming the value and its neighbour; divided by 5 (dip
 * 5, under the dip's bound) the ZPA from the end is refused against the
 * value before it; the file as shipped, without its zpa keys, loads. */
static void test_last_row_slip(void)
{
    char dir[] = "/tmp/sl-floor-XXXXXX", path[64];
    CHECK(tmp_path(dir, path, sizeof path, "el12.ini"), "mkdtemp");
    const double div[] = {1, 10, 5};
    for (size_t t = 0; t < 3; t++) {
        char cmd[600];
        /* the zpa lines out; in [h1] and [h2] the last value of each sa_ list
         * (the line that ends the list: "0.3900" or "0.3750") divided */
        snprintf(cmd, sizeof cmd,
                 "awk -v d=%g '/^\\[/{s=$0} /^zpa/{next} "
                 "(s==\"[h1]\"||s==\"[h2]\") && /0\\.3(900|750)$/ && !/^[a-z]/"
                 "{n=split($0,a,\", \"); a[n]=sprintf(\"%%.5f\", a[n]/d); "
                 "l=a[1]; for(i=2;i<=n;i++) l=l \", \" a[i]; print l; next} {print}' "
                 "floors/02-el12.ini > %s", div[t], path);
        CHECK(system(cmd) == 0, "awk");
        sl_error e;
        sl_error_clear(&e);
        sl_floor *fl = sl_floor_load(path, &e);
        if (t == 0)
            CHECK(fl != NULL && !fl->comp[0].zpa_given &&
                      fabs(fl->comp[0].zpa_ms2 / SL_G - 0.39) < 1e-12,
                  "02-el12 without zpa: %s", e.msg);
        else if (t == 1)
            CHECK(!fl && e.line == 16 && strstr(e.msg, "[h1] sa_0.02 at 50 Hz, the last") &&
                      strstr(e.msg, "value 0.039 g is 1/10") && strstr(e.msg, "(0.39 g at 40 Hz)"),
                  "the last row / 10: %s:%ld: %s", e.file, e.line, e.msg);
        else
            CHECK(!fl && e.line == 16 && strstr(e.msg, "gives the ZPA (none is given)") &&
                      strstr(e.msg, "value 0.078 g"),
                  "the last row / 5: %s:%ld: %s", e.file, e.line, e.msg);
        sl_floor_free(fl);
    }
    remove(path);
    rmdir(dir);
}

/* A given ZPA against the lowest damping's value at the table's last
 * frequency (5 m/s2 at 50 Hz, 2 %): accepted at SL_FLOOR_ZPA_END_MIN and
 * _MAX, refused just beyond them naming the zpa line; the worst physical
 * floor (0.255: a 2 % table ending near a vertical mode, docs/formats-floor.md)
 * accepted; the slips refused: a ZPA in g under a table in m/s2 (1/9.81), in
 * m/s2 under one in g (9.81), typed x10 or /10, a table ending on a peak 6 x
 * the ZPA. */
static void test_zpa_end_thresholds(void)
{
    char dir[] = "/tmp/sl-floor-XXXXXX", path[64];
    CHECK(tmp_path(dir, path, sizeof path, "z.csv"), "mkdtemp");
    const struct {
        double r;
        int ok;
    } c[] = {
        {SL_FLOOR_ZPA_END_MIN, 1},          {SL_FLOOR_ZPA_END_MIN / 1.001, 0},
        {SL_FLOOR_ZPA_END_MAX, 1},          {SL_FLOOR_ZPA_END_MAX * 1.001, 0},
        {0.255, 1},                         {1.001, 1},
        {1.0 / 9.80665, 0},                 {9.80665, 0},
        {10.0, 0},                          {0.1, 0},
        {1.0 / 6.0, 0},                     {0.199, 0},
        {1.26, 0},
    };
    for (size_t i = 0; i < sizeof c / sizeof c[0]; i++) {
        FILE *f = fopen(path, "w");
        CHECK(f != NULL, "fopen");
        if (!f)
            return;
        fprintf(f, "# name: t\n# units: m/s2\n# h2: same_as_h1\n# zpa_h1: %.17g\n"
                   "f_hz,h1_2,h1_10,v_5\n0.5,5,4,1\n1,6,4,1\n2,7,4,1\n10,6,4,1\n50,5,4,1\n",
                5.0 * c[i].r);
        fclose(f);
        sl_error e;
        sl_error_clear(&e);
        sl_floor *fl = sl_floor_load(path, &e);
        if (c[i].ok)
            CHECK(fl != NULL && fabs(fl->comp[0].zpa_ms2 - 5.0 * c[i].r) < 1e-12,
                  "ZPA %.17g x the end refused: %s", c[i].r, e.msg);
        else
            CHECK(!fl && e.line == 4 && strstr(e.msg, "zpa_h1") &&
                      strstr(e.msg, "x the 2 % spectrum's value at its highest frequency"),
                  "ZPA %.17g x the end: refused at line %ld (%s)", c[i].r, e.line, e.msg);
        sl_floor_free(fl);
    }
    remove(path);
    rmdir(dir);
}

/* An unusual ZPA: the warning names the units as written (and the key as
 * the format writes it) and the ZPA; a usual one gives none. */
static void test_zpa_warning(void)
{
    char w[600];
    /* a 0.39 g floor in g labelled m/s2; in m/s2 labelled g */
    CHECK(sl_floor_zpa_warning_text(0.39, "m/s2", SL_FLOOR_INI, w, sizeof w) == 1 &&
              strstr(w, "units = m/s2 gives a horizontal ZPA of 0.0398 g, unusual for a floor"),
          "low: '%s'", w);
    CHECK(sl_floor_zpa_warning_text(0.39 * SL_G * SL_G, "g", SL_FLOOR_CSV, w, sizeof w) == 1 &&
              strstr(w, "# units: g gives a horizontal ZPA of 3.82 g, unusual for a floor"),
          "high: '%s'", w);
    CHECK(sl_floor_zpa_warning_text(0.39 * SL_G, "g", SL_FLOOR_INI, w, sizeof w) == 0 && !w[0],
          "usual: '%s'", w);
    CHECK(sl_floor_zpa_warning_text(SL_FLOOR_ZPA_WARN_MIN_G * SL_G, "g", SL_FLOOR_INI, w,
                                    sizeof w) == 0 &&
              sl_floor_zpa_warning_text(SL_FLOOR_ZPA_WARN_MAX_G * SL_G, "g", SL_FLOOR_INI, w,
                                        sizeof w) == 0,
          "the band's ends are usual");
    CHECK(sl_floor_zpa_warning_text(SL_FLOOR_ZPA_WARN_MIN_G * SL_G * 0.999, "g", SL_FLOOR_INI,
                                    w, sizeof w) == 1 &&
              sl_floor_zpa_warning_text(SL_FLOOR_ZPA_WARN_MAX_G * SL_G * 1.001, "g",
                                        SL_FLOOR_INI, w, sizeof w) == 1,
          "just outside the band");
    /* from a floor read: its larger horizontal ZPA (the template: 0.36 g) */
    sl_error e;
    sl_floor *fl = sl_floor_load("templates/floor.ini", &e);
    CHECK(fl && sl_floor_zpa_warning(fl, w, sizeof w) == 0, "template warned: '%s'", w);
    sl_floor_free(fl);
}

/* UTF-16 without a byte-order mark, big-endian (the fixtures hold the
 * other forms): named as such at line 1. */
static void test_utf16_no_bom(void)
{
    char dir[] = "/tmp/sl-floor-XXXXXX", path[64];
    CHECK(tmp_path(dir, path, sizeof path, "be.csv"), "mkdtemp");
    const char *text = "# name: t\n# units: g\n";
    FILE *f = fopen(path, "wb");
    CHECK(f != NULL, "fopen");
    if (!f)
        return;
    for (const char *p = text; *p; p++) {
        fputc(0, f);
        fputc(*p, f);
    }
    fclose(f);
    sl_error e;
    sl_error_clear(&e);
    CHECK(!sl_floor_load(path, &e) && e.line == 1 &&
              strstr(e.msg, "the file is UTF-16BE text, not UTF-8"),
          "BE without BOM: %s", e.msg);
    remove(path);
    rmdir(dir);
}

/* Every bad-*.ini fixture is in the table above. */
static void test_every_fixture_listed(void)
{
    DIR *d = opendir(FLOORS);
    CHECK(d != NULL, "cannot open " FLOORS);
    if (!d)
        return;
    struct dirent *ent;
    while ((ent = readdir(d))) {
        if (strncmp(ent->d_name, "bad-", 4))
            continue;
        int found = 0;
        for (size_t i = 0; i < N_BAD; i++)
            found |= !strcmp(ent->d_name, bad[i].file);
        CHECK(found, "fixture %s not in the test table", ent->d_name);
    }
    closedir(d);
}

static void test_missing_file(void)
{
    sl_error e;
    sl_error_clear(&e);
    CHECK(sl_floor_load(FLOORS "no-such-file.ini", &e) == NULL, "loaded");
    CHECK(e.code == SL_EIO && strstr(e.file, "no-such-file.ini"), "code %d file '%s'", e.code,
          e.file);
    CHECK(sl_floor_load(NULL, &e) == NULL && e.code == SL_EINVAL, "NULL path");
    CHECK(!strcmp(sl_floor_comp_name(SL_FLOOR_V), "v"), "names");
}

/* Messages quote what was written: whole UTF-8 characters kept (RFC 3629),
 * control characters and bytes that are not UTF-8 as '?', cut on a
 * character boundary; and a floor file's bad value shows as written. */
static void test_quote_as_written(void)
{
    const char *name = "B\xc3\xa2timent r\xc3\xa9" "acteur \xe2\x82\xac \xf0\x9f\x8f\xad";
    CHECK(!strcmp(sl_text_quote(name, strlen(name)).s, name), "'%s'",
          sl_text_quote(name, strlen(name)).s);
    /* a control byte, DEL, a C1 control (U+0085), a stray continuation byte,
     * an overlong '/', a surrogate and a lone lead byte at the end */
    const char *mixed = "a\x01" "b\x7f" "c\xc2\x85" "d\x80" "e\xc0\xaf" "f\xed\xa0\x80" "g\xe2\x82";
    CHECK(!strcmp(sl_text_quote(mixed, strlen(mixed)).s, "a?b?c?d?e??f???g??"), "'%s'",
          sl_text_quote(mixed, strlen(mixed)).s);
    char cut[64];
    memset(cut, 'x', SL_TEXT_QUOTE_MAX - 1);
    strcpy(cut + SL_TEXT_QUOTE_MAX - 1, "\xc3\xa9z"); /* the 2-byte e-acute crosses the cap */
    sl_quoted q = sl_text_quote(cut, strlen(cut));
    CHECK(strlen(q.s) == SL_TEXT_QUOTE_MAX - 1 + 3 && !strcmp(q.s + SL_TEXT_QUOTE_MAX - 1, "..."),
          "'%s'", q.s);
    CHECK(sl_text_utf8_len("\xc3\xa9", 1) == 0 && sl_text_utf8_len("\xc3\xa9", 2) == 2 &&
              sl_text_utf8_len("", 0) == 0,
          "lengths bounded by n");
    /* the template with one value typed as "2.52" followed by a micro sign */
    FILE *in = fopen("templates/floor.ini", "rb");
    CHECK(in != NULL, "templates/floor.ini");
    if (!in)
        return;
    static char text[1 << 16];
    size_t len = fread(text, 1, sizeof text - 1, in);
    fclose(in);
    text[len] = '\0';
    char *v = strstr(text, "2.5216");
    CHECK(v != NULL, "the template's value 2.5216");
    if (!v)
        return;
    memcpy(v, "2.52\xc2\xb5", 6);
    char dir[] = "/tmp/seislide-quote-XXXXXX";
    CHECK(mkdtemp(dir) != NULL, "mkdtemp");
    char path[128];
    snprintf(path, sizeof path, "%s/f.ini", dir);
    FILE *f = fopen(path, "wb");
    CHECK(f != NULL, "%s", path);
    if (!f)
        return;
    fwrite(text, 1, len, f);
    fclose(f);
    sl_error e;
    sl_error_clear(&e);
    CHECK(sl_floor_load(path, &e) == NULL && strstr(e.msg, "'2.52\xc2\xb5'"), "message '%s'",
          e.msg);
    remove(path);
    rmdir(dir);
}

int main(void)
{
    RUN(test_template);
    RUN(test_good_small);
    RUN(test_bad_files);
    RUN(test_csv_template_equals_ini);
    RUN(test_good_small_csv);
    RUN(test_sizes);
    RUN(test_plausible_units_text);
    RUN(test_tables_as_saved);
    RUN(test_plausibility_thresholds);
    RUN(test_zpa_warning);
    RUN(test_zpa_end_thresholds);
    RUN(test_table_ends);
    RUN(test_last_row_slip);
    RUN(test_utf16_no_bom);
    RUN(test_every_fixture_listed);
    RUN(test_missing_file);
    RUN(test_quote_as_written);
    return HARNESS_END("floor");
}
