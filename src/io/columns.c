/*
 * columns.c - the column reader (io/motion_read.h): one column
 * (acceleration, dt from the caller), two columns (time, acceleration; dt
 * from the time column) or CSV with a header naming a time column and an
 * acceleration column with its unit ("time_s,acc_g"). Three steps: layout
 * detection from the first non-comment line, the rows, and dt from the
 * time column. See docs/formats.md.
 */
#include "io/motion_read.h"

#include <ctype.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Most fields on one line of a column or CSV file. */
#define SL_MOTION_FIELDS_MAX 16

typedef struct field {
    const char *s;
    size_t n;
} field;

/* Split a line into fields: separated by commas (each trimmed, possibly
 * empty) when `comma`, else by runs of white space. Returns the count
 * (which may exceed `max`; only `max` are stored). */
static size_t split(const char *s, size_t n, int comma, field *f, size_t max)
{
    size_t count = 0, i = 0;
    if (comma) {
        for (;;) {
            size_t j = i;
            while (j < n && s[j] != ',')
                j++;
            const char *fs = s + i;
            size_t fn = j - i;
            sl_text_trim(&fs, &fn);
            if (count < max) {
                f[count].s = fs;
                f[count].n = fn;
            }
            count++;
            if (j >= n)
                break;
            i = j + 1;
        }
        return count;
    }
    for (;;) {
        while (i < n && sl_text_is_space(s[i]))
            i++;
        if (i >= n)
            break;
        size_t j = i;
        while (j < n && !sl_text_is_space(s[j]))
            j++;
        if (count < max) {
            f[count].s = s + i;
            f[count].n = j - i;
        }
        count++;
        i = j;
    }
    return count;
}

static int has_char(const char *s, size_t n, char c)
{
    return memchr(s, c, n) != NULL;
}

typedef enum col_kind { COL_TIME, COL_ACC } col_kind;

/* Classify one CSV header name: "time_s", "t (s)", "acc_g", "acc (cm/s2)",
 * "a[m/s2]", "gal", "g". Sets kind and unit (SL_UNIT_NONE when the name
 * gives none). Error for anything else. */
static sl_status csv_column(const field *f, col_kind *kind, sl_unit *u, const char *path,
                            long line, sl_error *err)
{
    const char *s = f->s;
    size_t n = f->n;
    if (n >= 2 && s[0] == '"' && s[n - 1] == '"') {
        s++;
        n -= 2;
        sl_text_trim(&s, &n);
    }
    sl_quoted q = sl_text_quote(s, n);
    size_t b = 0;
    while (b < n && isalpha((unsigned char)s[b]))
        b++;
    const char *rest = s + b;
    size_t rn = n - b;
    while (rn > 0 && (sl_text_is_space(*rest) || *rest == '_' || *rest == '(' || *rest == '[' ||
                      *rest == '-')) {
        rest++;
        rn--;
    }
    while (rn > 0 && (sl_text_is_space(rest[rn - 1]) || rest[rn - 1] == ')' || rest[rn - 1] == ']'))
        rn--;
    char base[16];
    if (b == 0 || b >= sizeof base)
        goto unknown;
    for (size_t i = 0; i < b; i++)
        base[i] = (char)tolower((unsigned char)s[i]);
    base[b] = '\0';
    if (!strcmp(base, "t") || !strcmp(base, "time")) {
        *kind = COL_TIME;
        *u = SL_UNIT_NONE;
        if (rn > 0) {
            char tu[8];
            size_t k = 0;
            for (size_t i = 0; i < rn && k + 1 < sizeof tu; i++)
                tu[k++] = (char)tolower((unsigned char)rest[i]);
            tu[k] = '\0';
            if (rn >= sizeof tu || (strcmp(tu, "s") && strcmp(tu, "sec") && strcmp(tu, "seconds")))
                return sl_error_set(err, SL_EPARSE, path, line,
                                    "time column '%s': unit must be seconds (s)", q.s);
        }
        return SL_OK;
    }
    if (!strcmp(base, "a") || !strcmp(base, "acc") || !strcmp(base, "accel") ||
        !strcmp(base, "acceleration")) {
        *kind = COL_ACC;
        *u = SL_UNIT_NONE;
        if (rn > 0) {
            *u = sl_text_unit(rest, rn);
            if (*u == SL_UNIT_NONE) {
                sl_quoted qu = sl_text_quote(rest, rn);
                return sl_error_set(err, SL_EPARSE, path, line,
                                    "unknown units '%s' in column '%s'", qu.s, q.s);
            }
        }
        return SL_OK;
    }
    /* a bare unit name: "g", "gal", "m/s2", "cm/s^2" */
    *u = sl_text_unit(s, n);
    if (*u != SL_UNIT_NONE) {
        *kind = COL_ACC;
        return SL_OK;
    }
unknown:
    return sl_error_set(err, SL_EPARSE, path, line,
                        "unknown column '%s' (expected a time column such as 'time_s' "
                        "and one acceleration column such as 'acc_g')",
                        q.s);
}

/* The layout of a column file, from its first non-comment line. */
typedef struct layout {
    const char *s;     /* that line (data when !header) */
    size_t n;
    long first_line;   /* its number */
    int comma;         /* fields separated by commas (else blanks) */
    int header;        /* the line is a CSV header */
    size_t ncols;      /* fields per data line */
    long t_col, a_col; /* time and acceleration columns (-1: none) */
    sl_unit file_u;    /* unit named by the header (SL_UNIT_NONE: none) */
} layout;

/* The columns of a CSV header line (L->s): one time and one acceleration
 * column, each classified by csv_column(). */
static sl_status header_columns(const char *path, const field *f, size_t nf, layout *L,
                                sl_error *err)
{
    for (size_t k = 0; k < nf; k++) {
        col_kind kind = COL_ACC;
        sl_unit cu = SL_UNIT_NONE;
        if (csv_column(&f[k], &kind, &cu, path, L->first_line, err) != SL_OK)
            return err ? err->code : SL_EPARSE;
        if (kind == COL_TIME) {
            if (L->t_col >= 0)
                return sl_error_set(err, SL_EPARSE, path, L->first_line,
                                    "more than one time column");
            L->t_col = (long)k;
        } else {
            if (L->a_col >= 0)
                return sl_error_set(err, SL_EPARSE, path, L->first_line,
                                    "more than one acceleration column");
            L->a_col = (long)k;
            L->file_u = cu;
        }
    }
    if (L->a_col < 0 || L->t_col < 0)
        return sl_error_set(err, SL_EPARSE, path, L->first_line,
                            "no %s column in the CSV header",
                            L->a_col < 0 ? "acceleration" : "time");
    return SL_OK;
}

/* Layout detection: find the first non-comment line of `t`, decide whether
 * it is a CSV header (fmt CSV: it must be; AUTO: commas, a letter and a
 * non-numeric field) and where the time and acceleration columns are
 * (one column: acceleration; two: time, acceleration). */
static sl_status detect_layout(const char *path, sl_text *t, sl_format fmt, layout *L,
                               sl_error *err)
{
    memset(L, 0, sizeof *L);
    L->t_col = L->a_col = -1;
    L->file_u = SL_UNIT_NONE;
    int found = 0;
    while (sl_text_next(t, &L->s, &L->n)) {
        if (!sl_text_skip_line(L->s, L->n)) {
            found = 1;
            break;
        }
    }
    if (!found)
        return sl_error_set(err, SL_EPARSE, path, t->lineno, "no data");
    L->first_line = t->lineno;
    L->comma = has_char(L->s, L->n, ',');
    field f[SL_MOTION_FIELDS_MAX];
    size_t nf = split(L->s, L->n, L->comma, f, SL_MOTION_FIELDS_MAX);
    if (nf > SL_MOTION_FIELDS_MAX)
        return sl_error_set(err, SL_EPARSE, path, L->first_line, "too many fields (%zu)", nf);
    int all_numeric = 1;
    for (size_t k = 0; k < nf; k++) {
        double x;
        if (sl_text_parse_num(f[k].s, f[k].n, &x) == SL_NUM_BAD)
            all_numeric = 0;
    }
    if (fmt == SL_FORMAT_CSV) {
        if (!L->comma || all_numeric)
            return sl_error_set(err, SL_EPARSE, path, L->first_line,
                                "CSV header expected (a time column and an acceleration "
                                "column, e.g. 'time_s,acc_g')");
        L->header = 1;
    } else if (fmt == SL_FORMAT_AUTO) {
        int letter = 0;
        for (size_t k = 0; k < L->n; k++)
            letter = letter || isalpha((unsigned char)L->s[k]);
        L->header = L->comma && letter && !all_numeric;
    }
    L->ncols = nf;
    if (L->header)
        return header_columns(path, f, nf, L, err);
    size_t want = fmt == SL_FORMAT_ONECOL ? 1 : fmt == SL_FORMAT_TWOCOL ? 2 : nf;
    if (fmt == SL_FORMAT_AUTO && nf != 1 && nf != 2)
        return sl_error_set(err, SL_EPARSE, path, L->first_line,
                            "cannot tell the format: %zu fields (expected an AT2 header, "
                            "a CSV header, or 1 or 2 numeric columns)",
                            nf);
    L->ncols = want;
    L->t_col = want == 2 ? 0 : -1;
    L->a_col = want == 2 ? 1 : 0;
    return SL_OK;
}

/* Rows: every data line (the layout's first line too when it is not a
 * header) has ncols numbers; accelerations are converted to SI with unit u
 * into a, times go to tv with their lines. */
static sl_status read_rows(const char *path, sl_text *t, const layout *L, sl_unit u,
                           sl_dvec *a, sl_dvec *tv, sl_lvec *lines, sl_error *err)
{
    const char *s = L->s;
    size_t n = L->n;
    field f[SL_MOTION_FIELDS_MAX];
    double fac = sl_unit_to_ms2(u);
    int have = !L->header; /* the first line holds data */
    for (;;) {
        if (!have) {
            if (!sl_text_next(t, &s, &n))
                break;
            if (sl_text_skip_line(s, n))
                continue;
        }
        have = 0;
        long line = t->lineno;
        size_t nf = split(s, n, L->comma, f, SL_MOTION_FIELDS_MAX);
        if (nf != L->ncols)
            return sl_error_set(err, SL_EPARSE, path, line, "expected %zu field%s, found %zu",
                                L->ncols, L->ncols == 1 ? "" : "s", nf);
        for (size_t k = 0; k < nf; k++) {
            double x;
            sl_num_result r = sl_text_parse_num(f[k].s, f[k].n, &x);
            if (r != SL_NUM_OK) {
                if (f[k].n == 0)
                    return sl_error_set(err, SL_EPARSE, path, line, "empty field %zu", k + 1);
                return sl_text_token_error(err, path, line, f[k].s, f[k].n, r);
            }
            int bad = 0;
            if ((long)k == L->a_col) {
                sl_status st = sl_motion_check_acc(fac * x, x, u, path, line, err);
                if (st != SL_OK)
                    return st;
                bad = sl_dvec_push(a, fac * x);
            } else if ((long)k == L->t_col) {
                if (!(fabs(x) <= SL_MOTION_MAX_TIME_S))
                    return sl_error_set(err, SL_EINVAL, path, line, "time %g s outside +-%g s",
                                        x, SL_MOTION_MAX_TIME_S);
                bad = sl_dvec_push(tv, x) || sl_lvec_push(lines, line);
            }
            if (bad)
                return sl_error_set(err, SL_ENOMEM, path, 0, "out of memory");
        }
    }
    if (a->n == 0)
        return sl_error_set(err, SL_EPARSE, path, t->lineno, "no data");
    return SL_OK;
}

/* dt from a time column: strictly increasing, every step within
 * SL_MOTION_DT_REL_TOL of the first (so the line of a jump is named); dt is
 * then the mean step, the most accurate value. */
static sl_status time_column_dt(const char *path, const sl_dvec *tv, const sl_lvec *lines,
                                double opt_dt, double *dt, sl_error *err)
{
    if (tv->n < 2)
        return sl_error_set(err, SL_EPARSE, path, lines->v[0],
                            "need at least 2 samples to get dt from the time column");
    for (size_t i = 1; i < tv->n; i++)
        if (!(tv->v[i] > tv->v[i - 1]))
            return sl_error_set(err, SL_EINVAL, path, lines->v[i],
                                "time %.9g s does not increase (previous %.9g s): "
                                "dt must be > 0",
                                tv->v[i], tv->v[i - 1]);
    double h0 = tv->v[1] - tv->v[0];
    for (size_t i = 2; i < tv->n; i++) {
        double h = tv->v[i] - tv->v[i - 1];
        if (fabs(h - h0) > SL_MOTION_DT_REL_TOL * h0)
            return sl_error_set(err, SL_EINVAL, path, lines->v[i],
                                "non-uniform time column: step %.9g s to t = %.9g s differs "
                                "from the first step %.9g s by more than %g relative",
                                h, tv->v[i], h0, SL_MOTION_DT_REL_TOL);
    }
    *dt = (tv->v[tv->n - 1] - tv->v[0]) / (double)(tv->n - 1);
    return sl_motion_check_opt_dt(opt_dt, *dt, path, 0, err);
}

sl_motion *sl_motion_read_columns(const char *path, sl_text *t, sl_format fmt,
                                  const sl_read_opts *o, sl_error *err)
{
    layout L;
    if (detect_layout(path, t, fmt, &L, err) != SL_OK)
        return NULL;
    sl_unit u;
    if (sl_motion_resolve_units(L.file_u, o->units, path, L.header ? L.first_line : 0, &u,
                                err) != SL_OK)
        return NULL;
    if (L.t_col < 0 && !(o->dt_s > 0)) {
        sl_error_set(err, SL_EINVAL, path, 0,
                     "dt not given for a file without a time column (use --dt)");
        return NULL;
    }
    sl_dvec a = {0}, tv = {0};
    sl_lvec lines = {0};
    sl_motion *m = NULL;
    double dt = o->dt_s;
    if (read_rows(path, t, &L, u, &a, &tv, &lines, err) != SL_OK)
        goto done;
    if (L.t_col >= 0 && time_column_dt(path, &tv, &lines, o->dt_s, &dt, err) != SL_OK)
        goto done;
    const char *base = strrchr(path, '/');
    base = base ? base + 1 : path;
    m = sl_motion_new_owned(path, base, strlen(base), a.v, a.n, dt);
    if (m)
        a.v = NULL; /* owned by m */
    else
        sl_error_set(err, SL_ENOMEM, path, 0, "out of memory");
done:
    free(a.v);
    free(tv.v);
    free(lines.v);
    return m;
}
