/*
 * test_motion.c - reading ground motions (every format, every bad input)
 * and their derived quantities against closed forms; every .AT2 of the
 * shared record collection against records/MANIFEST.tsv and SUMMARY.tsv.
 */
#include "io/motion.h"

#include "harness.h"
#include "tsv.h"

#include <dirent.h>
#include <errno.h>
#include <strings.h>

#define DATA "tests/data/motion/"

/* Tolerances used below. */
#define TOL_EXACT 1e-12     /* relative, for results exact up to rounding */
#define TOL_PGA_G 0.0006    /* g: SUMMARY.tsv rounds PGA to 3 decimals */
#define TOL_DT_REL 1e-9     /* MANIFEST dt against the header's */

static sl_motion *read_fmt(const char *path, sl_format fmt, sl_unit u, double dt_s,
                           sl_error *err)
{
    sl_read_opts o = {0};
    o.format = fmt;
    o.units = u;
    o.dt_s = dt_s;
    return sl_motion_read(path, &o, err);
}

static sl_motion *read_auto(const char *path, sl_unit u, double dt_s, sl_error *err)
{
    return read_fmt(path, SL_FORMAT_AUTO, u, dt_s, err);
}

/* A read that must fail with `code` at `line`, message containing `frag`. */
#define EXPECT_FAIL(m, err, code_, path_, line_, frag)                                   \
    do {                                                                                 \
        CHECK((m) == NULL, "read of %s should fail", (path_));                          \
        sl_motion_free(m);                                                               \
        CHECK((err).code == (code_), "code %d, expected %d (%s)", (int)(err).code,      \
              (int)(code_), (err).msg);                                                  \
        CHECK(!strcmp((err).file, (path_)), "file '%s', expected '%s'", (err).file,      \
              (path_));                                                                  \
        CHECK((err).line == (line_), "line %ld, expected %ld (%s)", (err).line,          \
              (long)(line_), (err).msg);                                                 \
        CHECK(strstr((err).msg, (frag)) != NULL, "message '%s' lacks '%s'", (err).msg,   \
              (frag));                                                                   \
    } while (0)

static void check_values(const sl_motion *m, const double *exp, size_t n, double factor)
{
    CHECK(m->n == n, "n = %zu, expected %zu", m->n, n);
    for (size_t i = 0; i < n && i < m->n; i++)
        CHECK_CLOSE(m->acc_ms2[i], exp[i] * factor, 0, TOL_EXACT);
}

/* ---------------------------------------------------------------- */
/* Good inputs                                                       */
/* ---------------------------------------------------------------- */

static void test_at2_west2(void)
{
    sl_error err;
    sl_motion *m = read_auto(DATA "west2.AT2", SL_UNIT_NONE, 0, &err);
    CHECK(m != NULL, "%s", err.msg);
    if (!m)
        return;
    static const double exp[] = {.01, -.2556093e-2, 0, .5, -.75, .1, .2, -.3, .4, .05, -.06, .125};
    check_values(m, exp, sizeof exp / sizeof exp[0], SL_G);
    CHECK_CLOSE(m->dt_s, 0.01, 0, TOL_EXACT);
    CHECK(!strcmp(m->path, DATA "west2.AT2"), "path '%s'", m->path);
    CHECK(strstr(m->label, "PEER NGA") && strstr(m->label, "Test Station"), "label '%s'",
          m->label);
    CHECK_CLOSE(sl_motion_pga(m), 0.75 * SL_G, 0, TOL_EXACT);
    sl_motion_free(m);

    /* the explicit unit that agrees is fine; forcing AT2 is fine */
    m = read_fmt(DATA "west2.AT2", SL_FORMAT_AT2, SL_UNIT_G, 0.01, &err);
    CHECK(m != NULL && m->n == 12, "%s", err.msg);
    sl_motion_free(m);
}

static void test_at2_old_layout(void)
{
    sl_error err;
    sl_motion *m = read_auto(DATA "nga_old.AT2", SL_UNIT_NONE, 0, &err);
    CHECK(m != NULL, "%s", err.msg);
    if (!m)
        return;
    static const double exp[] = {.001, .002, -.3, .004, .005, -.006, .007};
    check_values(m, exp, 7, SL_G);
    CHECK_CLOSE(m->dt_s, 0.02, 0, TOL_EXACT);
    sl_motion_free(m);
}

static void test_at2_crlf_bom_padding(void)
{
    sl_error err;
    sl_motion *m = read_auto(DATA "crlf_bom.AT2", SL_UNIT_NONE, 0, &err);
    CHECK(m != NULL, "%s", err.msg);
    if (!m)
        return;
    static const double exp[] = {.1, -.2, .3, .4, -.5, .6};
    check_values(m, exp, 6, SL_G);
    CHECK_CLOSE(m->dt_s, 0.005, 0, TOL_EXACT);
    CHECK(strchr(m->label, '\r') == NULL, "label keeps a CR: '%s'", m->label);
    sl_motion_free(m);
}

static void test_at2_units_variants(void)
{
    sl_error err;
    sl_motion *m = read_auto(DATA "cms2.AT2", SL_UNIT_NONE, 0, &err);
    CHECK(m != NULL, "%s", err.msg);
    if (m) {
        static const double exp[] = {100, -250, 12.5, 0};
        check_values(m, exp, 4, 0.01);
    }
    sl_motion_free(m);

    /* "The units are (g)" and an NPTS line make a .txt an AT2 file */
    m = read_auto(DATA "units_are.txt", SL_UNIT_NONE, 0, &err);
    CHECK(m != NULL, "%s", err.msg);
    if (m) {
        static const double exp[] = {.1, -.2, .3, .05};
        check_values(m, exp, 4, SL_G);
        CHECK_CLOSE(m->dt_s, 0.02, 0, TOL_EXACT);
    }
    sl_motion_free(m);

    /* a header without units takes them from the caller */
    m = read_auto(DATA "no_units.AT2", SL_UNIT_MS2, 0, &err);
    CHECK(m != NULL && m->n == 2 && m->acc_ms2[1] == 2.0, "%s", err.msg);
    sl_motion_free(m);
}

/* Line 3 spellings of the units. */
static void test_at2_units_line(void)
{
    static const struct {
        const char *line3;
        sl_unit u; /* SL_UNIT_NONE: an error is expected */
    } cases[] = {
        {"ACCELERATION TIME SERIES IN UNITS OF G", SL_UNIT_G},
        {"ACCELERATION TIME HISTORY IN UNITS OF G.", SL_UNIT_G},
        {"ACCELERATION IN UNITS OF CM/SEC/SEC", SL_UNIT_CMS2},
        {"acceleration in units of cm/s/s", SL_UNIT_CMS2},
        {"ACCELERATION, UNITS OF  CM/SEC2, FILTERED", SL_UNIT_CMS2},
        {"UNITS: GAL", SL_UNIT_CMS2},
        {"The units are (g)", SL_UNIT_G},
        {"The units are (m/s^2)", SL_UNIT_MS2},
        {"IN UNITS OF M/SEC**2", SL_UNIT_MS2},
        {"IN UNITS OF MM/S/S", SL_UNIT_MMS2},
        {"IN UNITS OF INCHES", SL_UNIT_NONE},
        {"UNITS", SL_UNIT_NONE},
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        char text[512];
        snprintf(text, sizeof text, "T\nE\n%s\nNPTS= 2, DT= .01 SEC\n 1.0 -2.0\n",
                 cases[k].line3);
        const char *p = harness_tmpfile("u.AT2", text);
        sl_error err;
        sl_motion *m = read_auto(p, SL_UNIT_NONE, 0, &err);
        if (cases[k].u == SL_UNIT_NONE) {
            CHECK(m == NULL && err.code == SL_EPARSE && err.line == 3, "'%s': %s",
                  cases[k].line3, err.msg);
        } else {
            CHECK(m != NULL, "'%s': %s", cases[k].line3, err.msg);
            if (m)
                CHECK_CLOSE(m->acc_ms2[1], -2.0 * sl_unit_to_ms2(cases[k].u), 0, TOL_EXACT);
        }
        sl_motion_free(m);
        if (p)
            remove(p);
    }
}

static void test_onecol(void)
{
    sl_error err;
    sl_motion *m = read_auto(DATA "onecol.txt", SL_UNIT_CMS2, 0.005, &err);
    CHECK(m != NULL, "%s", err.msg);
    if (!m)
        return;
    static const double exp[] = {0, .5, -.125, 2, -.75};
    check_values(m, exp, 5, 0.01);
    CHECK_CLOSE(m->dt_s, 0.005, 0, 0);
    sl_motion_free(m);

    m = read_fmt(DATA "onecol.txt", SL_FORMAT_ONECOL, SL_UNIT_G, 0.01, &err);
    CHECK(m != NULL && m->n == 5, "%s", err.msg);
    sl_motion_free(m);
}

static void test_twocol_crlf_bom(void)
{
    sl_error err;
    sl_motion *m = read_auto(DATA "twocol.txt", SL_UNIT_G, 0, &err);
    CHECK(m != NULL, "%s", err.msg);
    if (!m)
        return;
    static const double exp[] = {.1, -.2, .3, 0, -.05};
    check_values(m, exp, 5, SL_G);
    CHECK_CLOSE(m->dt_s, 0.005, 0, TOL_EXACT);
    sl_motion_free(m);

    /* an explicit dt that agrees is accepted; forcing TWOCOL works */
    m = read_fmt(DATA "twocol.txt", SL_FORMAT_TWOCOL, SL_UNIT_G, 0.005, &err);
    CHECK(m != NULL && m->n == 5, "%s", err.msg);
    sl_motion_free(m);
}

static void test_csv_units_from_header(void)
{
    sl_error err;
    sl_motion *m = read_auto(DATA "csv_g.csv", SL_UNIT_NONE, 0, &err);
    CHECK(m != NULL, "%s", err.msg);
    if (m) {
        static const double exp[] = {0, .1, -.2, .05};
        check_values(m, exp, 4, SL_G);
        CHECK_CLOSE(m->dt_s, 0.01, 0, TOL_EXACT);
    }
    sl_motion_free(m);

    m = read_auto(DATA "csv_ms2.csv", SL_UNIT_NONE, 0, &err);
    CHECK(m != NULL, "%s", err.msg);
    if (m) {
        static const double exp[] = {1, -2.5, .5};
        check_values(m, exp, 3, 1);
        CHECK_CLOSE(m->dt_s, 0.02, 0, TOL_EXACT);
    }
    sl_motion_free(m);

    /* columns in any order; unit in the acceleration column's name */
    m = read_fmt(DATA "csv_gal.csv", SL_FORMAT_CSV, SL_UNIT_CMS2, 0, &err);
    CHECK(m != NULL, "%s", err.msg);
    if (m) {
        static const double exp[] = {150, -300, 25};
        check_values(m, exp, 3, 0.01);
    }
    sl_motion_free(m);

    /* no unit in the header: from the caller */
    m = read_auto(DATA "csv_nounit.csv", SL_UNIT_MS2, 0, &err);
    CHECK(m != NULL && m->n == 3, "%s", err.msg);
    if (m)
        CHECK_CLOSE(m->acc_ms2[2], 0.3, 0, 0);
    sl_motion_free(m);
}

static void test_number_syntax(void)
{
    /* Fortran E and D exponents, signs, leading dots; commas in a headerless file */
    const char *p = harness_tmpfile("nums.txt", "-.2556093E-02\n+1.5D+01\n1e0\n.5\n");
    sl_error err;
    sl_motion *m = read_auto(p, SL_UNIT_MS2, 0.01, &err);
    CHECK(m != NULL, "%s", err.msg);
    if (m) {
        static const double exp[] = {-.2556093e-2, 15, 1, .5};
        check_values(m, exp, 4, 1);
    }
    sl_motion_free(m);
    if (p)
        remove(p);
    p = harness_tmpfile("comma2.txt", "0.0, 1\n0.5, 2\n1.0, 3\n");
    m = read_auto(p, SL_UNIT_MS2, 0, &err);
    CHECK(m != NULL && m->n == 3, "%s", err.msg);
    if (m)
        CHECK_CLOSE(m->dt_s, 0.5, 0, 0);
    sl_motion_free(m);
    if (p)
        remove(p);
    p = harness_tmpfile("cr_only.txt", "0.0 1\r0.5 2\r1.0 3\r");
    m = read_auto(p, SL_UNIT_MS2, 0, &err);
    CHECK(m != NULL && m->n == 3, "%s", err.msg);
    sl_motion_free(m);
    if (p)
        remove(p);
}

/* ---------------------------------------------------------------- */
/* Bad inputs: code, file, line and the offending value              */
/* ---------------------------------------------------------------- */

static void test_missing_file(void)
{
    sl_error err;
    const char *p = DATA "no-such-file.AT2";
    sl_motion *m = read_auto(p, SL_UNIT_NONE, 0, &err);
    EXPECT_FAIL(m, err, SL_EIO, p, 0, strerror(ENOENT));
    m = read_auto(DATA, SL_UNIT_G, 0.01, &err); /* a directory */
    CHECK(m == NULL && err.code == SL_EIO, "directory: code %d (%s)", (int)err.code, err.msg);
    sl_motion_free(m);
}

static void test_at2_truncated(void)
{
    sl_error err;
    sl_motion *m = read_auto(DATA "trunc.AT2", SL_UNIT_NONE, 0, &err);
    EXPECT_FAIL(m, err, SL_EPARSE, DATA "trunc.AT2", 6, "truncated: NPTS=10 but only 7 values");
    m = read_auto(DATA "short_header.AT2", SL_UNIT_NONE, 0, &err);
    EXPECT_FAIL(m, err, SL_EPARSE, DATA "short_header.AT2", 2, "truncated AT2 header");
}

static void test_at2_npts_vs_data(void)
{
    sl_error err;
    /* more values than NPTS: the line of the first extra value, quoted */
    sl_motion *m = read_auto(DATA "extra.AT2", SL_UNIT_NONE, 0, &err);
    EXPECT_FAIL(m, err, SL_EPARSE, DATA "extra.AT2", 6, "extra value '.7E+00'");
    CHECK(strstr(err.msg, "NPTS=6") != NULL, "%s", err.msg);
    /* fewer: truncated (see test_at2_truncated) */
    m = read_auto(DATA "trunc.AT2", SL_UNIT_NONE, 0, &err);
    CHECK(m == NULL && err.code == SL_EPARSE, "%s", err.msg);
}

static void test_bad_tokens(void)
{
    sl_error err;
    sl_motion *m = read_auto(DATA "bad_token.AT2", SL_UNIT_NONE, 0, &err);
    EXPECT_FAIL(m, err, SL_EPARSE, DATA "bad_token.AT2", 8, "non-numeric value 'abc'");
    char buf[2048];
    sl_error_format(&err, buf, sizeof buf);
    CHECK(!strcmp(buf, DATA "bad_token.AT2:8: non-numeric value 'abc'"), "formatted '%s'", buf);

    m = read_auto(DATA "nan.txt", SL_UNIT_G, 0.01, &err);
    EXPECT_FAIL(m, err, SL_EINVAL, DATA "nan.txt", 3, "value 'nan' is not finite");
    m = read_auto(DATA "inf.AT2", SL_UNIT_NONE, 0, &err);
    EXPECT_FAIL(m, err, SL_EINVAL, DATA "inf.AT2", 6, "value 'Inf' is not finite");
    m = read_auto(DATA "bad_number.txt", SL_UNIT_G, 0.01, &err);
    EXPECT_FAIL(m, err, SL_EPARSE, DATA "bad_number.txt", 3, "non-numeric value '1.2.3'");
    m = read_auto(DATA "hex.txt", SL_UNIT_G, 0.01, &err);
    EXPECT_FAIL(m, err, SL_EPARSE, DATA "hex.txt", 2, "non-numeric value '0x10'");
    m = read_auto(DATA "wrong_fields.txt", SL_UNIT_G, 0, &err);
    EXPECT_FAIL(m, err, SL_EPARSE, DATA "wrong_fields.txt", 3, "expected 2 fields, found 3");
    m = read_auto(DATA "three_cols.txt", SL_UNIT_G, 0, &err);
    EXPECT_FAIL(m, err, SL_EPARSE, DATA "three_cols.txt", 1, "cannot tell the format");
    m = read_fmt(DATA "twocol.txt", SL_FORMAT_ONECOL, SL_UNIT_G, 0.01, &err);
    EXPECT_FAIL(m, err, SL_EPARSE, DATA "twocol.txt", 2, "expected 1 field, found 2");
    m = read_fmt(DATA "onecol.txt", SL_FORMAT_CSV, SL_UNIT_G, 0.01, &err);
    EXPECT_FAIL(m, err, SL_EPARSE, DATA "onecol.txt", 2, "CSV header expected");
    m = read_auto(DATA "csv_badcol.csv", SL_UNIT_G, 0, &err);
    EXPECT_FAIL(m, err, SL_EPARSE, DATA "csv_badcol.csv", 1, "unknown column 'vel_m/s'");
    m = read_auto(DATA "empty.txt", SL_UNIT_G, 0.01, &err);
    EXPECT_FAIL(m, err, SL_EPARSE, DATA "empty.txt", 0, "empty file");
    m = read_auto(DATA "comments_only.txt", SL_UNIT_G, 0.01, &err);
    EXPECT_FAIL(m, err, SL_EPARSE, DATA "comments_only.txt", 3, "no data");
    m = read_fmt(DATA "onecol.txt", SL_FORMAT_AT2, SL_UNIT_G, 0, &err);
    EXPECT_FAIL(m, err, SL_EPARSE, DATA "onecol.txt", 4, "AT2 header");
    m = read_auto(DATA "bad_header.AT2", SL_UNIT_NONE, 0, &err);
    EXPECT_FAIL(m, err, SL_EPARSE, DATA "bad_header.AT2", 4, "AT2 header: expected");
}

static void test_csv_header_errors(void)
{
    static const struct {
        const char *text;
        long line;
        const char *frag;
    } cases[] = {
        {"acc_g,acc_m/s2\n1,2\n", 1, "more than one acceleration column"},
        {"time_s,time\n0,1\n", 1, "more than one time column"},
        {"time_s,t,acc_g\n0,0,1\n", 1, "more than one time column"},
        {"time_ms,acc_g\n0,1\n", 1, "time column 'time_ms': unit must be seconds"},
        {"time,acc_furlong\n0,1\n", 1, "unknown units 'furlong' in column 'acc_furlong'"},
        {"# c\ntime_s,acc_g\n0,1\n0.01,\n", 4, "empty field 2"},
        {"time_s,acc_g\n0,1\n", 2, "need at least 2 samples"},
        {"time_s,acc_g\n0,1\n0.01,2,3\n", 3, "expected 2 fields, found 3"},
        {"time_s,acc_g\n0,1\n0.01,abc\n", 3, "non-numeric value 'abc'"},
        {"time_s,acc_g\n", 1, "no data"},
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        const char *p = harness_tmpfile("hdr.csv", cases[k].text);
        sl_error err;
        sl_motion *m = read_auto(p, SL_UNIT_NONE, 0, &err);
        CHECK(m == NULL && err.code == SL_EPARSE && err.line == cases[k].line &&
                  strstr(err.msg, cases[k].frag) != NULL,
              "case %zu: code %d line %ld '%s', expected line %ld '%s'", k, (int)err.code,
              err.line, err.msg, cases[k].line, cases[k].frag);
        sl_motion_free(m);
        if (p)
            remove(p);
    }
}

static void test_bad_dt(void)
{
    sl_error err;
    sl_motion *m = read_auto(DATA "dt0.AT2", SL_UNIT_NONE, 0, &err);
    EXPECT_FAIL(m, err, SL_EINVAL, DATA "dt0.AT2", 4, "dt 0 must be > 0");
    m = read_auto(DATA "onecol.txt", SL_UNIT_G, -0.01, &err);
    EXPECT_FAIL(m, err, SL_EINVAL, DATA "onecol.txt", 0, "dt -0.01 must be > 0");
    m = read_auto(DATA "onecol.txt", SL_UNIT_G, 0, &err);
    EXPECT_FAIL(m, err, SL_EINVAL, DATA "onecol.txt", 0, "dt not given");
    m = read_auto(DATA "time_back.txt", SL_UNIT_G, 0, &err);
    EXPECT_FAIL(m, err, SL_EINVAL, DATA "time_back.txt", 3, "does not increase");
    /* an explicit dt that disagrees with the file */
    m = read_auto(DATA "west2.AT2", SL_UNIT_NONE, 0.02, &err);
    EXPECT_FAIL(m, err, SL_EINVAL, DATA "west2.AT2", 4, "disagrees with the file's dt");
    m = read_auto(DATA "twocol.txt", SL_UNIT_G, 0.01, &err);
    EXPECT_FAIL(m, err, SL_EINVAL, DATA "twocol.txt", 0, "disagrees with the file's dt");
}

static void test_nonuniform_time(void)
{
    sl_error err;
    sl_motion *m = read_auto(DATA "nonuniform.txt", SL_UNIT_G, 0, &err);
    EXPECT_FAIL(m, err, SL_EINVAL, DATA "nonuniform.txt", 5, "non-uniform time column");
    CHECK(strstr(err.msg, "t = 0.05 s") != NULL, "%s", err.msg);
    /* a single late sample: its line is named */
    const char *p = harness_tmpfile("late.txt", "0 1\n0.01 1\n0.02 1\n0.0301 1\n0.04 1\n");
    m = read_auto(p, SL_UNIT_G, 0, &err);
    EXPECT_FAIL(m, err, SL_EINVAL, p, 4, "t = 0.0301");
    if (p)
        remove(p);
    /* rounding far below 1e-6 relative is accepted */
    p = harness_tmpfile("round.txt", "0 1\n0.0100000000001 1\n0.02 1\n");
    m = read_auto(p, SL_UNIT_G, 0, &err);
    CHECK(m != NULL, "%s", err.msg);
    sl_motion_free(m);
    if (p)
        remove(p);
}

static void test_units_rules(void)
{
    sl_error err;
    sl_motion *m = read_auto(DATA "onecol.txt", SL_UNIT_NONE, 0.01, &err);
    EXPECT_FAIL(m, err, SL_EINVAL, DATA "onecol.txt", 0,
                "units not given (use --units g|m/s2|cm/s2)");
    m = read_auto(DATA "twocol.txt", SL_UNIT_NONE, 0, &err);
    EXPECT_FAIL(m, err, SL_EINVAL, DATA "twocol.txt", 0, "units not given");
    m = read_auto(DATA "csv_nounit.csv", SL_UNIT_NONE, 0, &err);
    EXPECT_FAIL(m, err, SL_EINVAL, DATA "csv_nounit.csv", 1, "units not given");
    m = read_auto(DATA "no_units.AT2", SL_UNIT_NONE, 0, &err);
    EXPECT_FAIL(m, err, SL_EINVAL, DATA "no_units.AT2", 3, "units not given");
    /* AT2 header says g, caller says cm/s2 */
    m = read_auto(DATA "west2.AT2", SL_UNIT_CMS2, 0, &err);
    EXPECT_FAIL(m, err, SL_EINVAL, DATA "west2.AT2", 3, "units g in the file disagree");
    /* CSV header says g, caller says m/s2 */
    m = read_auto(DATA "csv_g.csv", SL_UNIT_MS2, 0, &err);
    EXPECT_FAIL(m, err, SL_EINVAL, DATA "csv_g.csv", 1, "disagree");
    m = read_auto(DATA "unknown_units.AT2", SL_UNIT_G, 0, &err);
    EXPECT_FAIL(m, err, SL_EPARSE, DATA "unknown_units.AT2", 3,
                "unknown units 'FURLONGS/FORTNIGHT'");
}

/* ---------------------------------------------------------------- */
/* Sets                                                              */
/* ---------------------------------------------------------------- */

static void test_set_check(void)
{
    sl_error err;
    sl_motion *a = read_auto(DATA "set_a.txt", SL_UNIT_MS2, 0, &err);
    sl_motion *b = read_auto(DATA "set_b_dt.txt", SL_UNIT_MS2, 0, &err);
    sl_motion *c = read_auto(DATA "set_c_short.txt", SL_UNIT_MS2, 0, &err);
    CHECK(a && b && c, "fixtures: %s", err.msg);
    if (!a || !b || !c)
        goto done;

    sl_set s = {NULL, a, NULL};
    CHECK(sl_set_check(&s, 0, &err) == SL_EINVAL && strstr(err.msg, "H1"), "%s", err.msg);

    /* mixed dt: both files and both values named */
    s = (sl_set){a, b, NULL};
    CHECK(sl_set_check(&s, 1, &err) == SL_EINVAL, "mixed dt accepted");
    CHECK(strstr(err.msg, "set_a.txt") && strstr(err.msg, "set_b_dt.txt") &&
              strstr(err.msg, "0.01") && strstr(err.msg, "0.02"),
          "message '%s'", err.msg);
    CHECK(a->n == 4 && b->n == 4, "set modified on error");

    /* mixed lengths by default: the shorter padded with zeros, reported */
    sl_motion *a2 = sl_motion_copy(a), *c2 = sl_motion_copy(c);
    CHECK(a2 && c2, "copies");
    if (a2 && c2) {
        s = (sl_set){a2, NULL, c2};
        sl_set_fit fit;
        double c_last = c2->acc_ms2[2];
        CHECK(sl_set_check_fit(&s, 0, &fit, &err) == SL_OK, "%s", err.msg);
        CHECK(a2->n == 4 && c2->n == 4, "n = %zu, %zu", a2->n, c2->n);
        CHECK(c2->acc_ms2[3] == 0.0 && c2->acc_ms2[2] == c_last, "padding %g", c2->acc_ms2[3]);
        CHECK(fit.changed && !fit.truncated && fit.n == 4 && fit.n_in[0] == 4 &&
                  fit.n_in[1] == 0 && fit.n_in[2] == 3,
              "fit %d %zu %zu %zu", fit.changed, fit.n, fit.n_in[0], fit.n_in[2]);
    }
    sl_motion_free(a2);
    sl_motion_free(c2);
    s = (sl_set){a, NULL, c};

    /* with truncation: cut to the shortest */
    CHECK(sl_set_check(&s, 1, &err) == SL_OK, "%s", err.msg);
    CHECK(a->n == 3 && c->n == 3, "n = %zu, %zu", a->n, c->n);
    CHECK(a->dt_s == c->dt_s, "dt not shared");

    /* non-finite values */
    c->acc_ms2[1] = NAN;
    s = (sl_set){a, c, NULL};
    CHECK(sl_set_check(&s, 0, &err) == SL_EINVAL && strstr(err.msg, "not finite") &&
              !strcmp(err.file, DATA "set_c_short.txt"),
          "%s: %s", err.file, err.msg);
    c->acc_ms2[1] = -0.6;

    /* dt within 1e-6 relative is the same dt */
    sl_motion *d = sl_motion_copy(c);
    CHECK(d != NULL, "copy");
    if (d) {
        d->dt_s = c->dt_s * (1 + 0.5e-6);
        s = (sl_set){c, d, NULL};
        CHECK(sl_set_check(&s, 0, &err) == SL_OK, "%s", err.msg);
        CHECK(d->dt_s == c->dt_s, "dt not shared");
        sl_motion_free(d);
    }
done:
    sl_motion_free(a);
    sl_motion_free(b);
    sl_motion_free(c);
}

static void test_set_peaks(void)
{
    const double dt = 0.01, a1 = 2.0, a2 = -3.0;
    const size_t n = 101; /* T = 1 s */
    double x1[101], x2[101];
    for (size_t i = 0; i < n; i++) {
        x1[i] = a1;
        x2[i] = a2;
    }
    sl_motion *h1 = sl_motion_from_array(x1, n, dt, "h1");
    sl_motion *h2 = sl_motion_from_array(x2, n, dt, "h2");
    CHECK(h1 && h2, "from_array");
    if (!h1 || !h2)
        goto done;
    double T = dt * (double)(n - 1);
    double d1 = fabs(a1) * T * T / 2, d2 = fabs(a2) * T * T / 2;
    sl_set s = {h1, h2, NULL};
    CHECK_CLOSE(sl_set_pga_h(&s), 3.0, 0, TOL_EXACT);
    CHECK_CLOSE(sl_set_pgd_100_40(&s), d2 + 0.4 * d1, 0, TOL_EXACT);
    s.h2 = NULL;
    CHECK_CLOSE(sl_set_pga_h(&s), 2.0, 0, TOL_EXACT);
    CHECK_CLOSE(sl_set_pgd_100_40(&s), d1, 0, TOL_EXACT);
done:
    sl_motion_free(h1);
    sl_motion_free(h2);
}

/* ---------------------------------------------------------------- */
/* Derived quantities against closed forms                           */
/* ---------------------------------------------------------------- */

static void test_constant_acceleration(void)
{
    /* a = a0 for T: v = a0 t, d = a0 t^2/2 exactly at every sample */
    const double a0 = 1.5, dt = 0.01;
    const size_t n = 201;
    double *x = malloc(n * sizeof *x), *v = malloc(n * sizeof *v), *d = malloc(n * sizeof *d);
    for (size_t i = 0; i < n; i++)
        x[i] = a0;
    sl_motion *m = sl_motion_from_array(x, n, dt, "const");
    CHECK(m != NULL, "from_array");
    if (m) {
        double T = dt * (double)(n - 1);
        CHECK_CLOSE(sl_motion_pga(m), a0, 0, 0);
        CHECK_CLOSE(sl_motion_pgv(m), a0 * T, 0, TOL_EXACT);
        CHECK_CLOSE(sl_motion_pgd(m), a0 * T * T / 2, 0, TOL_EXACT);
        sl_motion_integrate(m, v, d);
        for (size_t i = 0; i < n; i++) {
            double t = dt * (double)i;
            CHECK_CLOSE(v[i], a0 * t, 1e-15, TOL_EXACT);
            CHECK_CLOSE(d[i], a0 * t * t / 2, 1e-15, TOL_EXACT);
        }
        /* Arias: pi/(2g) a0^2 T; constant amplitude: D5-75 = 0.70 T */
        CHECK_CLOSE(sl_motion_arias(m), 3.14159265358979323846 / (2 * SL_G) * a0 * a0 * T, 0,
                    TOL_EXACT);
        CHECK_CLOSE(sl_motion_d5_75(m), 0.70 * T, 0, TOL_EXACT);
        /* scaling: peaks scale by |s|, Arias by s^2 */
        sl_motion_scale(m, -2);
        CHECK_CLOSE(sl_motion_pga(m), 2 * a0, 0, 0);
        CHECK_CLOSE(sl_motion_pgd(m), a0 * T * T, 0, TOL_EXACT);
        CHECK_CLOSE(sl_motion_arias(m), 4 * 3.14159265358979323846 / (2 * SL_G) * a0 * a0 * T,
                    0, TOL_EXACT);
    }
    sl_motion_free(m);
    free(x);
    free(v);
    free(d);
}

static void test_ramp(void)
{
    /* a = c t (piecewise linear, so exact): v = c t^2/2, d = c t^3/6,
     * int a^2 dt = c^2 T^3/3 */
    const double c = 0.8, dt = 0.02;
    const size_t n = 151;
    double *x = malloc(n * sizeof *x), *v = malloc(n * sizeof *v), *d = malloc(n * sizeof *d);
    for (size_t i = 0; i < n; i++)
        x[i] = c * dt * (double)i;
    sl_motion *m = sl_motion_from_array(x, n, dt, NULL);
    CHECK(m != NULL && !strcmp(m->label, "") && !strcmp(m->path, ""), "from_array");
    if (m) {
        double T = dt * (double)(n - 1);
        sl_motion_integrate(m, v, d);
        for (size_t i = 0; i < n; i++) {
            double t = dt * (double)i;
            CHECK_CLOSE(v[i], c * t * t / 2, 1e-15, 1e-11);
            CHECK_CLOSE(d[i], c * t * t * t / 6, 1e-15, 1e-11);
        }
        CHECK_CLOSE(sl_motion_pgv(m), c * T * T / 2, 0, 1e-11);
        CHECK_CLOSE(sl_motion_pgd(m), c * T * T * T / 6, 0, 1e-11);
        CHECK_CLOSE(sl_motion_arias(m), 3.14159265358979323846 / (2 * SL_G) * c * c * T * T * T / 3,
                    0, 1e-11);
        /* Husid H(t) = (t/T)^3: D5-75 = T (0.75^(1/3) - 0.05^(1/3)) within the
         * piecewise interpolation of a cubic (dt/T = 1/150) */
        CHECK_CLOSE(sl_motion_d5_75(m), T * (cbrt(0.75) - cbrt(0.05)), 0, 1e-3);
    }
    sl_motion_free(m);
    free(x);
    free(v);
    free(d);
}

static void test_sine_arias(void)
{
    /* a = A sin(w t) over whole periods. Continuous: I_a = pi/(2g) A^2 T/2.
     * For the piecewise-linear interpolant the sums close exactly:
     * I_a = pi/(2g) A^2 T/2 (2 + cos(w dt))/3. */
    const double A = 3.0, P = 0.5;
    const size_t per = 400, periods = 20, n = per * periods + 1;
    const double pi = 3.14159265358979323846, dt = P / (double)per, w = 2 * pi / P;
    double *x = malloc(n * sizeof *x);
    for (size_t i = 0; i < n; i++)
        x[i] = A * sin(w * dt * (double)i);
    sl_motion *m = sl_motion_from_array(x, n, dt, "sine");
    CHECK(m != NULL, "from_array");
    if (m) {
        double T = dt * (double)(n - 1);
        double cont = pi / (2 * SL_G) * A * A * T / 2;
        CHECK_CLOSE(sl_motion_arias(m), cont * (2 + cos(w * dt)) / 3, 0, 1e-11);
        CHECK_CLOSE(sl_motion_arias(m), cont, 0, (w * dt) * (w * dt) / 6 * 1.01);
        /* steady amplitude: D5-75 near 0.70 T (within one half period) */
        CHECK_CLOSE(sl_motion_d5_75(m), 0.70 * T, P / 2, 0);
        /* PGV of a sine from rest: v = A/w (1 - cos wt), peak 2A/w */
        CHECK_CLOSE(sl_motion_pgv(m), 2 * A / w, 0, 1e-4);
        CHECK_CLOSE(sl_motion_pga(m), A, 0, 1e-4);
    }
    sl_motion_free(m);
    free(x);
}

static void test_d5_75_edges(void)
{
    /* alternating +-a0: each step holds dt a0^2/3, the Husid curve is linear */
    double x[11];
    for (int i = 0; i < 11; i++)
        x[i] = (i % 2) ? -2.0 : 2.0;
    sl_motion *m = sl_motion_from_array(x, 11, 0.1, "alt");
    CHECK(m != NULL, "from_array");
    if (m) {
        CHECK_CLOSE(sl_motion_d5_75(m), 0.70 * 1.0, 0, TOL_EXACT);
        CHECK_CLOSE(sl_motion_arias(m), 3.14159265358979323846 / (2 * SL_G) * 4.0 / 3 * 1.0, 0,
                    TOL_EXACT);
    }
    sl_motion_free(m);
    /* zero motion: Arias 0, D5-75 0; one sample: everything 0 */
    double z[5] = {0};
    m = sl_motion_from_array(z, 5, 0.01, "zero");
    CHECK(m && sl_motion_arias(m) == 0 && sl_motion_d5_75(m) == 0 && sl_motion_pgd(m) == 0,
          "zero motion");
    sl_motion_free(m);
    double one = 5.0;
    m = sl_motion_from_array(&one, 1, 0.01, "one");
    CHECK(m && sl_motion_d5_75(m) == 0 && sl_motion_pga(m) == 5.0 && sl_motion_pgv(m) == 0,
          "one sample");
    sl_motion_free(m);
}

static void test_memory_api(void)
{
    double x[3] = {1, 2, 3};
    sl_motion_free(NULL);
    CHECK(sl_motion_from_array(x, 3, 0, "x") == NULL, "dt 0 accepted");
    CHECK(sl_motion_from_array(x, 3, -1, "x") == NULL, "dt < 0 accepted");
    CHECK(sl_motion_from_array(x, 3, NAN, "x") == NULL, "dt NaN accepted");
    CHECK(sl_motion_from_array(x, 0, 0.01, "x") == NULL, "n 0 accepted");
    CHECK(sl_motion_copy(NULL) == NULL, "copy(NULL)");
    sl_motion *m = sl_motion_from_array(x, 3, 0.01, "label");
    sl_motion *c = sl_motion_copy(m);
    CHECK(m && c && c != m && c->acc_ms2 != m->acc_ms2 && c->n == 3 && c->dt_s == 0.01 &&
              !strcmp(c->label, "label"),
          "copy");
    if (m && c) {
        x[0] = 9;
        m->acc_ms2[0] = 7;
        CHECK(c->acc_ms2[0] == 1, "copy shares or aliases the input");
    }
    sl_motion_free(m);
    sl_motion_free(c);
    /* a NULL opts and a NULL err are accepted */
    m = sl_motion_read(DATA "west2.AT2", NULL, NULL);
    CHECK(m && m->n == 12, "read with NULL opts");
    sl_motion_free(m);
    CHECK(sl_motion_read(DATA "no-such", NULL, NULL) == NULL, "missing file with NULL err");
}

/* ---------------------------------------------------------------- */
/* The shared record collection                                      */
/* ---------------------------------------------------------------- */


/* The MANIFEST's component column says vertical. */
static int component_is_vertical(const char *c)
{
    static const char *const v[] = {"UP", "DWN", "DOWN", "VER", "VRT", "V", "Z"};
    for (size_t k = 0; k < sizeof v / sizeof v[0]; k++)
        if (!strcasecmp(c, v[k]))
            return 1;
    return 0;
}

/* Known errors in SUMMARY.tsv: the vertical comparison is skipped there. */
static const char *summary_erratum(const char *dir)
{
    if (!strcmp(dir, "RSN88_SFERN_FSD"))
        return "SUMMARY.tsv counts RSN88_SFERN_FSD-UP.AT2 (header: VRT) as horizontal "
               "(n_h 3, n_v 0, pga_v nan)";
    return NULL;
}

typedef struct dir_peak {
    char dir[256];
    double h_g, v_g;
    int n_h, n_v;
} dir_peak;

/* The entry of directory dir[0..len), added if `add`; NULL if absent. */
static dir_peak *peak_for(dir_peak *p, size_t *np, const char *dir, size_t len, int add)
{
    for (size_t i = 0; i < *np; i++)
        if (strlen(p[i].dir) == len && !strncmp(p[i].dir, dir, len))
            return &p[i];
    if (!add || len >= sizeof p->dir)
        return NULL;
    dir_peak *q = &p[(*np)++];
    memcpy(q->dir, dir, len);
    q->dir[len] = '\0';
    q->h_g = q->v_g = NAN;
    return q;
}

/* Check the per-directory peaks against SUMMARY.tsv. */
static void check_summary(const char *shared, dir_peak *peaks, size_t np, int *checked)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/records/SUMMARY.tsv", shared);
    tsv s;
    CHECK(tsv_read(path, &s) == 0, "cannot read %s", path);
    if (!s.buf)
        return;
    long c_dir = tsv_col(&s, "dir"), c_h = tsv_col(&s, "pga_h_g"), c_v = tsv_col(&s, "pga_v_g");
    long c_nh = tsv_col(&s, "n_h"), c_nv = tsv_col(&s, "n_v");
    CHECK(c_dir >= 0 && c_h >= 0 && c_v >= 0 && c_nh >= 0 && c_nv >= 0, "SUMMARY columns");
    if (c_dir < 0 || c_h < 0 || c_v < 0 || c_nh < 0 || c_nv < 0) {
        tsv_free(&s);
        return;
    }
    for (size_t r = 1; r < s.nrow; r++) {
        const char *dir = tsv_get(&s, r, c_dir);
        dir_peak *p = peak_for(peaks, &np, dir, strlen(dir), 0);
        if (!p)
            continue; /* no AT2 files in this directory */
        double sh = strtod(tsv_get(&s, r, c_h), NULL), sv = strtod(tsv_get(&s, r, c_v), NULL);
        CHECK_CLOSE(p->h_g, sh, TOL_PGA_G, 0);
        if (fabs(p->h_g - sh) > TOL_PGA_G)
            fprintf(stderr, "    (%s: horizontal PGA)\n", dir);
        const char *why = summary_erratum(dir);
        if (why) {
            fprintf(stderr, "  note %s: %s; vertical not compared\n", h_cur_name, why);
            (*checked)++;
            continue;
        }
        CHECK(p->n_h == atoi(tsv_get(&s, r, c_nh)) && p->n_v == atoi(tsv_get(&s, r, c_nv)),
              "%s: %d horizontal and %d vertical files, SUMMARY says %s and %s", dir, p->n_h,
              p->n_v, tsv_get(&s, r, c_nh), tsv_get(&s, r, c_nv));
        if (isnan(sv)) {
            CHECK(p->n_v == 0, "%s: SUMMARY has no vertical PGA", dir);
        } else {
            CHECK_CLOSE(p->v_g, sv, TOL_PGA_G, 0);
            if (fabs(p->v_g - sv) > TOL_PGA_G)
                fprintf(stderr, "    (%s: vertical PGA)\n", dir);
        }
        (*checked)++;
    }
    tsv_free(&s);
}

/* Every "*.AT2" under records/DIR/ must be a MANIFEST row of format AT2;
 * returns how many there are. */
static size_t scan_at2(const char *shared, const tsv *man, long c_path, long c_fmt)
{
    char path[2048];
    size_t count = 0;
    snprintf(path, sizeof path, "%s/records", shared);
    DIR *top = opendir(path);
    CHECK(top != NULL, "cannot list %s", path);
    if (!top)
        return 0;
    struct dirent *d;
    while ((d = readdir(top)) != NULL) {
        if (d->d_name[0] == '.')
            continue;
        snprintf(path, sizeof path, "%s/records/%s", shared, d->d_name);
        DIR *sub = opendir(path);
        if (!sub)
            continue; /* a file, not a directory */
        struct dirent *e;
        while ((e = readdir(sub)) != NULL) {
            size_t n = strlen(e->d_name);
            if (n < 4 || strcasecmp(e->d_name + n - 4, ".AT2"))
                continue;
            count++;
            snprintf(path, sizeof path, "%s/%s", d->d_name, e->d_name);
            int listed = 0;
            for (size_t r = 1; r < man->nrow && !listed; r++)
                listed = !strcmp(tsv_get(man, r, c_path), path) &&
                         !strcmp(tsv_get(man, r, c_fmt), "AT2");
            CHECK(listed, "%s is not an AT2 row of MANIFEST.tsv", path);
        }
        closedir(sub);
    }
    closedir(top);
    return count;
}

/* Read every file of format `fmt_name` in MANIFEST.tsv (units and format
 * as given to sl_motion_read), check n and dt against MANIFEST and the
 * peak accelerations per directory against SUMMARY. */
static void check_records(const char *fmt_name, sl_unit units, size_t min_files)
{
    const char *shared = harness_shared_dir();
    char path[2048];
    if (!shared)
        SKIP("shared data folder not found (set SEISLIDE_SHARED or put it at ../shared)");
    snprintf(path, sizeof path, "%s/records/MANIFEST.tsv", shared);
    tsv man;
    if (tsv_read(path, &man) != 0)
        SKIP("%s not found or malformed", path);
    long c_path = tsv_col(&man, "local_path"), c_fmt = tsv_col(&man, "format");
    long c_npts = tsv_col(&man, "npts"), c_dt = tsv_col(&man, "dt");
    long c_comp = tsv_col(&man, "component");
    CHECK(c_path >= 0 && c_fmt >= 0 && c_npts >= 0 && c_dt >= 0 && c_comp >= 0,
          "MANIFEST columns");
    dir_peak *peaks = calloc(man.nrow + 1, sizeof *peaks);
    size_t np = 0, files = 0;
    if (!peaks || c_path < 0 || c_fmt < 0 || c_npts < 0 || c_dt < 0 || c_comp < 0)
        goto done;
    for (size_t r = 1; r < man.nrow; r++) {
        if (strcmp(tsv_get(&man, r, c_fmt), fmt_name))
            continue;
        const char *local = tsv_get(&man, r, c_path);
        snprintf(path, sizeof path, "%s/records/%s", shared, local);
        sl_read_opts o = {0};
        o.units = units;
        sl_error err;
        sl_motion *m = sl_motion_read(path, &o, &err);
        char msg[2200];
        CHECK(m != NULL, "%s", sl_error_format(&err, msg, sizeof msg));
        if (!m)
            continue;
        files++;
        long npts = atol(tsv_get(&man, r, c_npts));
        double dt = strtod(tsv_get(&man, r, c_dt), NULL);
        CHECK(m->n == (size_t)npts, "%s: n %zu, MANIFEST npts %ld", local, m->n, npts);
        CHECK_CLOSE(m->dt_s, dt, 0, TOL_DT_REL);
        int vert = sl_motion_name_is_vertical(local);
        CHECK(vert == component_is_vertical(tsv_get(&man, r, c_comp)),
              "%s: name says %s, MANIFEST component '%s'", local,
              vert ? "vertical" : "horizontal", tsv_get(&man, r, c_comp));
        const char *slash = strchr(local, '/');
        size_t dlen = slash ? (size_t)(slash - local) : strlen(local);
        dir_peak *p = peak_for(peaks, &np, local, dlen, 1);
        CHECK(p != NULL, "%s: directory name too long", local);
        if (!p) {
            sl_motion_free(m);
            continue;
        }
        double g = sl_motion_pga(m) / SL_G;
        if (vert) {
            p->v_g = p->n_v ? fmax(p->v_g, g) : g;
            p->n_v++;
        } else {
            p->h_g = p->n_h ? fmax(p->h_g, g) : g;
            p->n_h++;
        }
        sl_motion_free(m);
    }
    size_t rows = 0;
    for (size_t r = 1; r < man.nrow; r++)
        rows += !strcmp(tsv_get(&man, r, c_fmt), fmt_name);
    CHECK(files == rows && files >= min_files, "%zu %s files read of %zu in MANIFEST (at least %zu expected)",
          files, fmt_name, rows, min_files);
    if (!strcmp(fmt_name, "AT2")) {
        size_t on_disk = scan_at2(shared, &man, c_path, c_fmt);
        CHECK(on_disk == rows, "%zu .AT2 files under records/, %zu in MANIFEST", on_disk, rows);
    }
    int checked = 0;
    check_summary(shared, peaks, np, &checked);
    CHECK(checked == (int)np, "%d of %zu directories found in SUMMARY.tsv", checked, np);
done:
    free(peaks);
    tsv_free(&man);
}

/* Every .AT2 of the collection (432 files when written). */
static void test_records_at2(void)
{
    check_records("AT2", SL_UNIT_NONE, 432);
}

/* The two-column m/s2 records (CWA 2022 Chihshang, 18 files when written). */
static void test_records_twocol(void)
{
    check_records("TWOCOL_MS2", SL_UNIT_MS2, 18);
}

int main(void)
{
    RUN(test_at2_west2);
    RUN(test_at2_old_layout);
    RUN(test_at2_crlf_bom_padding);
    RUN(test_at2_units_variants);
    RUN(test_at2_units_line);
    RUN(test_onecol);
    RUN(test_twocol_crlf_bom);
    RUN(test_csv_units_from_header);
    RUN(test_number_syntax);
    RUN(test_missing_file);
    RUN(test_at2_truncated);
    RUN(test_at2_npts_vs_data);
    RUN(test_bad_tokens);
    RUN(test_csv_header_errors);
    RUN(test_bad_dt);
    RUN(test_nonuniform_time);
    RUN(test_units_rules);
    RUN(test_set_check);
    RUN(test_set_peaks);
    RUN(test_constant_acceleration);
    RUN(test_ramp);
    RUN(test_sine_arias);
    RUN(test_d5_75_edges);
    RUN(test_memory_api);
    RUN(test_records_at2);
    RUN(test_records_twocol);
    return HARNESS_END("motion");
}
