/* test_lookup.c - the workbook's Lookup formulas against their C twin,
 * sl_design_clearance_at(), with the workbook recalculated by LibreOffice
 * (headless): grid, between-grid, last-row, out-of-range, unknown-floor and
 * blank cases. Every formula's cached value is written as 0
 * (lookup_zero_cache), so a value read back can only come from LibreOffice's
 * own recalculation. Skipped, with a message, when soffice is absent (CI
 * installs libreoffice-calc-nogui). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "core/units.h"
#include "harness.h"
#include "oracle.h"
#include "method/design.h"
#include "report/report.h"
#include "report/sheets.h"

#define N_MU 16
#define N_SETS 2

/* Two floors with clearances that change curvature between grid points, so
 * that a reversed interpolation cannot agree by symmetry. */
static sl_design *make_design(double scale, double zpa_g)
{
    double mu[N_MU], peak[N_SETS * N_MU], asce[N_MU];
    const double pgd[N_SETS] = {2.0, 2.4};
    for (int k = 0; k < N_MU; k++) {
        mu[k] = 0.05 * (k + 1);
        double base = scale * exp(-6.0 * mu[k]) * (1.0 + 0.3 * (k % 3));
        peak[k] = 0.9 * base;
        peak[N_MU + k] = 1.1 * base;
        asce[k] = 1.2 * base;
    }
    sl_design_input in = oracle_design_input(N_MU, N_SETS, mu, peak, asce, pgd, zpa_g * SL_G);
    sl_error e;
    return sl_design_compute(&in, &e);
}

typedef struct lcase {
    const char *floor; /* "" = blank */
    double mu;         /* NAN = blank */
    const char *check; /* expected input check */
    const char *mu_text; /* non-NULL: text typed as mu */
} lcase;

static const lcase cases[] = {
    {"Roof, el. 36 m", 0.30, "ok", NULL}, /* on the grid */
    {"Roof, el. 36 m", 0.337, "ok", NULL}, /* between grid points */
    {"Ground", 0.0712, "ok", NULL}, /* between, first interval */
    {"ground", 0.80, "ok", NULL}, /* last row; MATCH ignores case */
    {"Ground", 0.05, "ok", NULL}, /* first row */
    {"Ground", 0.9, "mu outside the table", NULL},
    {"Ground", 0.01, "mu outside the table", NULL},
    {"Attic", 0.3, "unknown floor: choose one from the list", NULL},
    {"", 0.3, "choose a floor from the list", NULL},
    {"Roof, el. 36 m", NAN, "type mu", NULL},
    {"Roof, el. 36 m", NAN, "mu must be a number", "0,3"},
};
#define N_CASES (sizeof cases / sizeof cases[0])

/* Field `col` (0-based) of CSV line `row` (0-based) of a LibreOffice CSV
 * export (fields quoted with '"'), into buf. */
static int csv_cell(const char *path, int row, int col, char *buf, size_t n)
{
    FILE *f = fopen(path, "r");
    if (!f)
        return -1;
    char line[8192];
    int r = 0, found = -1;
    while (fgets(line, sizeof line, f)) {
        if (r++ != row)
            continue;
        int c = 0;
        size_t k = 0;
        int q = 0;
        for (char *p = line; *p && *p != '\n' && *p != '\r'; p++) {
            if (*p == '"') {
                if (q && p[1] == '"') {
                    if (c == col && k + 1 < n)
                        buf[k++] = '"';
                    p++;
                } else {
                    q = !q;
                }
            } else if (*p == ',' && !q) {
                c++;
            } else if (c == col && k + 1 < n) {
                buf[k++] = *p;
            }
        }
        buf[k] = '\0';
        found = c >= col ? 0 : -1;
        break;
    }
    fclose(f);
    return found;
}

static void test_lookup_libreoffice(void)
{
    if (system("command -v soffice >/dev/null 2>&1") != 0)
        SKIP("soffice (LibreOffice) not found: the Lookup formulas are not recalculated; "
             "install libreoffice-calc-nogui");
    char dir[] = "/tmp/sl-lookup-XXXXXX";
    CHECK(mkdtemp(dir) != NULL, "temporary folder");
    sl_design *d[2] = {make_design(1.0, 0.3), make_design(0.6, 0.63)};
    CHECK(d[0] && d[1], "designs");
    if (!d[0] || !d[1])
        return;
    d[1]->n_sets = 7; /* the policy text must give the chosen floor's own count */
    sl_report_floor fl[2] = {
        {.id = "ground", .name = "Ground", .path = "ground.ini", .elevation_m = NAN,
         .units = "g", .zpa_h_ms2 = 0.3 * SL_G, .design = d[0], .note = ""},
        {.id = "roof", .name = "Roof, el. 36 m", .path = "roof.ini", .elevation_m = 36,
         .units = "g", .zpa_h_ms2 = 0.63 * SL_G, .design = d[1], .note = ""}};
    char cmd[8192];
    /* a private LibreOffice profile that recalculates every formula on load */
    char prof[512], xcu[600];
    snprintf(prof, sizeof prof, "%s/profile/user", dir);
    snprintf(cmd, sizeof cmd, "mkdir -p '%s'", prof);
    CHECK(system(cmd) == 0, "profile folder");
    snprintf(xcu, sizeof xcu, "%s/registrymodifications.xcu", prof);
    FILE *x = fopen(xcu, "w");
    CHECK(x != NULL, "profile file");
    if (!x)
        return;
    fputs("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<oor:items "
          "xmlns:oor=\"http://openoffice.org/2001/registry\" "
          "xmlns:xs=\"http://www.w3.org/2001/XMLSchema\" "
          "xmlns:xsi=\"http://www.w3.org/2001/XMLSchema-instance\">\n"
          "<item oor:path=\"/org.openoffice.Office.Calc/Formula/Load\"><prop "
          "oor:name=\"OOXMLRecalcMode\" oor:op=\"fuse\"><value>0</value></prop></item>\n"
          "</oor:items>\n", x);
    fclose(x);
    int n = snprintf(cmd, sizeof cmd,
                     "cd '%s' && timeout 180 soffice -env:UserInstallation=file://%s/profile "
                     "--headless --convert-to 'csv:Text - txt - csv (StarCalc):44,34,76,1,,0,"
                     "false,true,false,false' --outdir csv", dir, dir);
    for (size_t c = 0; c < N_CASES; c++) {
        sl_report r;
        sl_report_init(&r);
        r.version = "seislide test";
        r.created = 1;
        r.n_floors = 2;
        r.floors = fl;
        r.lookup_floor = cases[c].floor;
        r.lookup_mu = cases[c].mu;
        r.lookup_mu_text = cases[c].mu_text;
        r.lookup_zero_cache = 1;
        char path[600];
        snprintf(path, sizeof path, "%s/case%02zu.xlsx", dir, c);
        sl_error e;
        CHECK(sl_report_write_xlsx(&r, path, &e) == SL_OK, "write case %zu: %s", c, e.msg);
        n += snprintf(cmd + n, sizeof cmd - (size_t)n, " case%02zu.xlsx", c);
    }
    n += snprintf(cmd + n, sizeof cmd - (size_t)n, " >/dev/null 2>&1");
    CHECK(system(cmd) == 0, "soffice conversion: %s", cmd);
    for (size_t c = 0; c < N_CASES; c++) {
        char csv[700], check[256] = "", result[256] = "", policy[2048] = "";
        snprintf(csv, sizeof csv, "%s/csv/case%02zu.csv", dir, c);
        /* Lookup!B15: the input check; B14: the clearance (rows 1-based) */
        CHECK(csv_cell(csv, 14, 1, check, sizeof check) == 0, "case %zu: no B15 in %s", c, csv);
        CHECK(csv_cell(csv, 13, 1, result, sizeof result) == 0, "case %zu: no B14", c);
        /* A31: the policy paragraph, with the chosen floor's number of sets */
        CHECK(csv_cell(csv, 30, 0, policy, sizeof policy) == 0, "case %zu: no A31", c);
        CHECK(!strcmp(check, cases[c].check), "case %zu (%s, %g): check '%s', expected '%s'", c,
              cases[c].floor, cases[c].mu, check, cases[c].check);
        if (!strcmp(cases[c].check, "ok")) {
            const sl_design *dd = !strcmp(cases[c].floor, "Ground") ||
                                          !strcmp(cases[c].floor, "ground")
                                      ? d[0]
                                      : d[1];
            double exp = 1000.0 * sl_design_clearance_at(dd, cases[c].mu);
            char *end;
            double got = strtod(result, &end);
            CHECK(end != result, "case %zu: result '%s' is not a number", c, result);
            CHECK_CLOSE(got, exp, 1e-9, 1e-9);
            /* B17: the floor's ZPA, read through the named range floor_zpa_g */
            char zpa[64] = "";
            CHECK(csv_cell(csv, 16, 1, zpa, sizeof zpa) == 0, "case %zu: no B17", c);
            double zpa_g = dd == d[0] ? 0.3 : 0.63;
            CHECK(fabs(strtod(zpa, NULL) - zpa_g) < 5e-4, "case %zu: ZPA '%s', expected %g", c, zpa,
                  zpa_g);
            char want[80];
            snprintf(want, sizeof want, "of %zu synthesized motion sets of this floor", dd->n_sets);
            CHECK(strstr(policy, want) != NULL, "case %zu: policy '%s' lacks '%s'", c, policy, want);
        } else {
            CHECK(!strcmp(result, "-"), "case %zu: result '%s', expected '-'", c, result);
            CHECK(strstr(policy, "of the floor's synthesized motion sets") != NULL,
                  "case %zu: policy '%s'", c, policy);
        }
    }
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    CHECK(system(cmd) == 0, "clean up");
    sl_design_free(d[0]);
    sl_design_free(d[1]);
}

/* The grid rows around mu that the Lookup's cached step values use must be
 * the ones its formulas find: MATCH(mu, grid, 1), the last grid mu at or
 * below mu (counted here directly), and the row after it (the last row at
 * the grid's end); row 0 when the inputs are not ok. */
static void test_lookup_bracket(void)
{
    sl_design *d = make_design(1.0, 0.3);
    CHECK(d != NULL, "design");
    if (!d)
        return;
    for (size_t k = 0; k < d->n; k++) {
        const double probe[] = {d->rows[k].mu, k + 1 < d->n ? 0.5 * (d->rows[k].mu +
                                d->rows[k + 1].mu) : d->rows[k].mu};
        for (int p = 0; p < 2; p++) {
            size_t at_or_below = 0;
            for (size_t j = 0; j < d->n; j++)
                at_or_below += d->rows[j].mu <= probe[p];
            size_t k1, k0 = sl_rpt_lookup_bracket(d, 1, probe[p], &k1);
            CHECK(k0 == at_or_below - 1, "mu %g: row %zu, MATCH gives %zu", probe[p], k0,
                  at_or_below - 1);
            CHECK(k1 == (k0 + 1 < d->n ? k0 + 1 : k0), "mu %g: next row %zu", probe[p], k1);
        }
    }
    size_t k1, k0 = sl_rpt_lookup_bracket(d, 0, d->rows[d->n - 1].mu, &k1);
    CHECK(k0 == 0 && k1 == 1, "inputs not ok: rows %zu, %zu", k0, k1);
    sl_design_free(d);
}

int main(void)
{
    RUN(test_lookup_bracket);
    RUN(test_lookup_libreoffice);
    return HARNESS_END("lookup");
}
