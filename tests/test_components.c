/* test_components.c - the components check (report/components.h): the
 * interpolation against sl_design_clearance_at() on random tables; a
 * hand-made results folder and list (BOM, CRLF, comments, quoted commas,
 * quotes and line breaks, a blank row) with every verdict worked out by
 * hand, the boundaries included (mu = b/h rocks; a margin of 0 with an SE
 * is marginal, with none ok; a margin of exactly 2 SE is ok; the grid's
 * ends are inside); the ASCE value beside the required clearance; refused
 * rows naming line and column, every one of a list in one pass; a list
 * separated by ';' with decimal commas; the name rule against the C
 * library's own Unicode case tables. */
#include <gsl/gsl_rng.h>
#include <locale.h>
#include <wctype.h>

#include "io/casefold.h"

#include "harness.h"
#include "method/design.h"
#include "report/components.h"

static void test_interp_twin(void)
{
    gsl_rng *g = gsl_rng_alloc(gsl_rng_mt19937);
    gsl_rng_set(g, 32);
    double mu[20], c[20];
    sl_design_row rows[20];
    int bad = 0;
    for (int t = 0; t < 500; t++) {
        size_t n = 2 + gsl_rng_uniform_int(g, 19);
        double m = 0.01 + 0.1 * gsl_rng_uniform(g);
        for (size_t k = 0; k < n; k++) {
            mu[k] = m;
            m += 0.001 + 0.2 * gsl_rng_uniform(g);
            c[k] = 1e3 * gsl_rng_uniform(g);
            rows[k] = (sl_design_row){.mu = mu[k], .clearance_m = c[k]};
        }
        sl_design d = {.n = n, .rows = rows};
        for (int q = 0; q < 20; q++) {
            double x = mu[0] - 0.05 + (mu[n - 1] - mu[0] + 0.1) * gsl_rng_uniform(g);
            if (q < 3) /* a grid point: exactly the table's value */
                x = mu[gsl_rng_uniform_int(g, n)];
            double a = sl_comp_interp(mu, c, n, x), b = sl_design_clearance_at(&d, x);
            int in = x >= mu[0] && x <= mu[n - 1];
            if (in ? !(fabs(a - b) <= 1e-9 + 1e-12 * fabs(b)) : !(isnan(a) && isnan(b)))
                bad++;
            for (size_t k = 0; k < n && q < 3; k++)
                if (x == mu[k] && a != c[k])
                    bad++;
        }
    }
    CHECK(bad == 0, "%d interpolations differ from sl_design_clearance_at", bad);
    CHECK(isnan(sl_comp_interp(mu, c, 2, NAN)), "NAN mu");
    gsl_rng_free(g);
}

static void put(const char *dir, const char *name, const char *text)
{
    char path[600];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *f = fopen(path, "wb");
    if (f) {
        fputs(text, f);
        fclose(f);
    }
}

/* One building, two floors on the grid 0.1, 0.2, 0.4. */
static void make_results(const char *dir)
{
    put(dir, "floors.csv", "# program: seislide test\r\n# seed: 7\r\nfloor_id,floor,file\r\n"
                           "gf,\"Ground, north\",gf.ini\r\nroof,Roof,roof.ini\r\n");
    put(dir, "floor_gf.csv", "# program: seislide test\r\n# seed: 7\r\n# floor_file_crc32: 0000abcd gf "
                             "(gf.ini, 12 bytes)\r\n# clearance_policy: nltha\r\n"
                             "mu,clearance_mm,nltha_design_se_mm,asce_design_mm\r\n"
                             "0.1,100,10,200\r\n0.2,50,6,120\r\n0.4,10,2,\r\n");
    put(dir, "floor_roof.csv", "mu,mu_g_over_zpa,clearance_mm,nltha_design_se_mm\r\n"
                               "0.1,1,300,30\r\n0.2,2,200,20\r\n0.4,4,100,\r\n");
}

static void test_table(void)
{
    char dir[] = "/tmp/sl-components-XXXXXX";
    CHECK(mkdtemp(dir) != NULL, "temporary folder");
    make_results(dir);
    sl_comp_results r;
    sl_error e;
    CHECK(sl_comp_results_load(dir, &r, &e) == SL_OK, "results: %s", e.msg);
    if (r.n_floors != 2)
        return;
    CHECK(r.n_mu == 3 && !r.is_plant && !strcmp(r.seed, "7") && r.floors[0].crc32 == 0xabcd,
          "grid %zu, seed %s", r.n_mu, r.seed);
    CHECK(isnan(r.floors[1].se_mm[2]), "an empty SE is NAN");
    CHECK(!strcmp(r.policy, "nltha") && r.floors[0].asce_mm[1] == 120 &&
          isnan(r.floors[0].asce_mm[2]) && isnan(r.floors[1].asce_mm[0]),
          "policy %s; ASCE read, empty or absent NAN", r.policy);
    /* BOM, CRLF, a comment, quoted fields, an extra column first, a blank row */
    put(dir, "list.csv",
        "\xEF\xBB\xBF# the list\r\nnote,TAG,Building,Floor,MU,base_m,cg_height_m,clearance_mm\r\n"
        "\"a, b\",T1,,gf,0.15,1,1,75\r\n"            /* 75 exactly: margin 0, ok */
        "\"say \"\"hi\"\"\",T2,,\" ground, NORTH\",0.15,1,1,74.9\r\n" /* short by 0.1 */
        "\"two\r\nlines\",T3,,roof,0.15,0.3,1,500\r\n" /* b/h 0.15 = mu: rocking */
        ",,,,,,,\r\n"                                /* skipped */
        "x,T4,,Roof,0.45,2,1,500\r\n"                /* above the grid */
        "x,T5,,roof,0.4,2,1,100\r\n"                 /* the grid's last row: inside, ok */
        "x,T6,,roof,0.05,2,1,100\r\n"               /* below the grid */
        "x,T7,,roof,0.5,0.6,1,100\r\n");            /* b/h 0.3, above the grid: rocking */
    char path[600];
    snprintf(path, sizeof path, "%s/list.csv", dir);
    sl_comp_table t;
    CHECK(sl_comp_table_read(path, &r, &t, NULL, &e) == SL_OK, "list: %s:%ld:%ld: %s", e.file, e.line,
          e.col, e.msg);
    if (t.n != 7) {
        CHECK(0, "%zu rows, 7 expected", t.n);
        sl_comp_results_free(&r);
        return;
    }
    /* T1: margin 0 with an SE of 8: marginal; T5: margin 0, its SE empty (0): ok;
     * rocking decided before outside: the sliding table does not apply at all */
    const sl_comp_verdict v[] = {SL_COMP_MARGINAL, SL_COMP_SHORT, SL_COMP_ROCKING,
                                 SL_COMP_OUTSIDE, SL_COMP_OK, SL_COMP_OUTSIDE, SL_COMP_ROCKING};
    const long line[] = {3, 4, 5, 8, 9, 10, 11};
    for (size_t i = 0; i < 7; i++)
        CHECK(t.rows[i].verdict == v[i] && t.rows[i].line == line[i], "row %zu: verdict %d line "
              "%ld", i + 1, (int)t.rows[i].verdict, t.rows[i].line);
    /* a slender row's own sliding verdict is rocking too (T3 inside the grid, T7 above
     * it): the workbook caches it in the sliding-verdict cell, whose formula says so */
    CHECK(t.rows[2].slide_verdict == SL_COMP_ROCKING && t.rows[6].slide_verdict == SL_COMP_ROCKING,
          "sliding verdicts of the slender rows %d %d", (int)t.rows[2].slide_verdict,
          (int)t.rows[6].slide_verdict);
    CHECK_CLOSE(t.rows[0].required_mm, 75.0, 0, 0);
    CHECK_CLOSE(t.rows[0].se_mm, 8.0, 0, 1e-15);
    CHECK_CLOSE(t.rows[0].asce_mm, 160.0, 0, 1e-15);
    CHECK_CLOSE(t.rows[1].margin_mm, -0.1, 1e-12, 0);
    CHECK_CLOSE(t.rows[2].required_mm, 250.0, 0, 0);
    CHECK_CLOSE(t.rows[2].b_over_h, 0.15, 0, 1e-15);
    CHECK_CLOSE(t.rows[4].required_mm, 100.0, 0, 0);
    CHECK(t.rows[1].floor == 0 && t.rows[2].floor == 1, "floors by name and by id, any case");
    CHECK(!strcmp(t.rows[1].field[0], "say \"hi\"") && !strcmp(t.rows[2].field[0], "two\nlines") &&
          !strcmp(t.header[1], "TAG"), "fields as written");
    CHECK(t.count[SL_COMP_OK] == 1 && t.count[SL_COMP_MARGINAL] == 1 &&
          t.count[SL_COMP_SHORT] == 1 &&
          t.count[SL_COMP_ROCKING] == 2 && t.count[SL_COMP_OUTSIDE] == 2, "counts");
    char why[300];
    CHECK(!strcmp(sl_comp_reason(&r, &t.rows[2], why, sizeof why), "mu 0.15 >= b/h 0.15: rocks "
                  "before it slides; its rocking is computed by seislide components"), "reason '%s'", why);
    CHECK(!strcmp(sl_comp_reason(&r, &t.rows[1], why, sizeof why), "required 75.0 mm (SE 8.0) > "
                  "available 74.9 mm: 0.1 mm short"), "reason '%s'", why);
    CHECK(!strcmp(sl_comp_reason(&r, &t.rows[0], why, sizeof why), "required 75.0 mm (SE 8.0) <= "
                  "available 75.0 mm: margin 0.0 mm < 2 SE (16.0 mm), inside the noise of the "
                  "motion sets"), "reason '%s'", why);
    sl_comp_table_free(&t);
    /* refused: line and column named */
    const struct { const char *text; long line, col; const char *msg; } bad[] = {
        {"tag,building,floor,mu,base_m,cg_height_m,clearance_mm\nA,,gf,0.2,1,1,1\nA,,gf,0.2,1,1,1\n",
         3, 1, "again: first on line 2"},
        {"tag,building,floor,mu,base_m,cg_height_m,clearance_mm\nA,,gf,0.2,1,0,1\n", 2, 6, "> 0"},
        {"tag,building,floor,mu,base_m,cg_height_m,clearance_mm\nA,,attic,0.2,1,1,1\n", 2, 3,
         "gf (Ground, north), roof (Roof)"},
        {"tag,building,floor,mu,base_m,cg_height_m,clearance_mm\nA,B1,gf,0.2,1,1,1\n", 2, 2,
         "one building"},
        {"tag,building,floor,mu,base_m,cg_height_m\nA,,gf,0.2,1,1\n", 1, 0, "clearance_mm"},
    };
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        put(dir, "bad.csv", bad[k].text);
        snprintf(path, sizeof path, "%s/bad.csv", dir);
        sl_status st = sl_comp_table_read(path, &r, &t, NULL, &e);
        CHECK(st != SL_OK && e.line == bad[k].line && e.col == bad[k].col &&
              strstr(e.msg, bad[k].msg) && t.n == 0 && !t.rows,
              "case %zu: %d %ld:%ld %s", k, (int)st, e.line, e.col, e.msg);
    }
    /* the margin against 2 SE: at mu 0.1 required 100 mm, SE 10 mm */
    put(dir, "m.csv", "tag,building,floor,mu,base_m,cg_height_m,clearance_mm\n"
                      "M1,,gf,0.1,2,1,120\nM2,,gf,0.1,2,1,119.9\nM3,,gf,0.1,2,1,100\n"
                      "M4,,gf,0.1,2,1,99.9\n");
    snprintf(path, sizeof path, "%s/m.csv", dir);
    if (sl_comp_table_read(path, &r, &t, NULL, &e) == SL_OK && t.n == 4) {
        CHECK(t.rows[0].verdict == SL_COMP_OK && t.rows[1].verdict == SL_COMP_MARGINAL &&
              t.rows[2].verdict == SL_COMP_MARGINAL && t.rows[3].verdict == SL_COMP_SHORT,
              "2 SE exactly ok, below it marginal, margin 0 marginal, below 0 short: %d %d %d %d",
              (int)t.rows[0].verdict, (int)t.rows[1].verdict, (int)t.rows[2].verdict,
              (int)t.rows[3].verdict);
        sl_comp_table_free(&t);
    } else {
        CHECK(0, "m.csv: %s", e.msg);
    }
    /* ';' and decimal commas: the same rows as ',' and points */
    put(dir, "semi.csv", "tag;building;floor;mu;base_m;cg_height_m;clearance_mm;note\r\n"
                         "S1;;gf;0,15;1;1;74,9;\"a; b\"\r\nS2;;Roof;0.4;2;1;100;x\r\n");
    snprintf(path, sizeof path, "%s/semi.csv", dir);
    if (sl_comp_table_read(path, &r, &t, NULL, &e) == SL_OK && t.n == 2) {
        CHECK(t.sep == ';' && t.rows[0].mu == 0.15 && t.rows[0].clearance_mm == 74.9 &&
              t.rows[0].verdict == SL_COMP_SHORT && t.rows[1].verdict == SL_COMP_OK &&
              !strcmp(t.rows[0].field[7], "a; b"), "a list separated by ';'");
        sl_comp_table_free(&t);
    } else {
        CHECK(0, "semi.csv: %s:%ld:%ld: %s", e.file, e.line, e.col, e.msg);
    }
    put(dir, "semi2.csv", "tag;building;floor;mu;base_m;cg_height_m;clearance_mm\n"
                          "S1;;gf;0,15;1;1;1.074,9\n");
    snprintf(path, sizeof path, "%s/semi2.csv", dir);
    CHECK(sl_comp_table_read(path, &r, &t, NULL, &e) == SL_EPARSE && e.line == 2 && e.col == 7 &&
          strstr(e.msg, "one decimal comma"), "a thousands separator refused: %ld:%ld %s",
          e.line, e.col, e.msg);
    put(dir, "semi3.csv", "tag;building,floor;mu;base_m;cg_height_m;clearance_mm\n");
    snprintf(path, sizeof path, "%s/semi3.csv", dir);
    CHECK(sl_comp_table_read(path, &r, &t, NULL, &e) == SL_EPARSE && e.line == 1 &&
          strstr(e.msg, "both ',' and ';'"), "a header with both separators: %s", e.msg);
    /* every bad row in one pass, in file order, each with line and column */
    put(dir, "many.csv", "tag,building,floor,mu,base_m,cg_height_m,clearance_mm\n"
                         "A,,gf,0.2,1,1,1\n"       /* good */
                         "B,,attic,x,1,1,1\n"      /* floor and mu: two problems */
                         "C,,gf,0.2,1,1\n"         /* too few fields */
                         "D,,gf,0.2,1,1,1\n"       /* good */
                         "a,,gf,0.2,0,1,-2\n"      /* tag again, base, clearance */
                         "E,,roof,0.2,1,1,1\n");   /* good */
    snprintf(path, sizeof path, "%s/many.csv", dir);
    sl_comp_problems *pb = malloc(sizeof *pb);
    if (pb) {
        sl_status st = sl_comp_table_read(path, &r, &t, pb, &e);
        const long wl[] = {3, 3, 4, 6, 6, 6}, wc[] = {3, 4, 7, 1, 5, 7};
        int same = pb->n == 6;
        for (size_t i = 0; same && i < 6; i++)
            same = pb->e[i].line == wl[i] && pb->e[i].col == wc[i];
        CHECK(st != SL_OK && same && pb->n_bad_rows == 3 && pb->n_rows == 6 && !pb->n_more &&
              t.n == 0 && !t.rows && strstr(e.msg, "3 of 6 rows refused (6 problems)") &&
              e.line == 0 && strstr(e.file, "many.csv"), "every problem: %zu (%zu rows of %zu): "
              "%s", pb->n, pb->n_bad_rows, pb->n_rows, e.msg);
        for (size_t i = 0; !same && i < pb->n; i++)
            fprintf(stderr, "    %ld:%ld %s\n", pb->e[i].line, pb->e[i].col, pb->e[i].msg);
        /* past the cap: counted, not kept */
        FILE *f = fopen(path, "w");
        if (f) {
            fputs("tag,building,floor,mu,base_m,cg_height_m,clearance_mm\n", f);
            for (int i = 0; i < SL_COMP_MAX_PROBLEMS + 10; i++)
                fprintf(f, "T%d,,gf,0.2,1,1,-1\n", i);
            fclose(f);
        }
        st = sl_comp_table_read(path, &r, &t, pb, &e);
        CHECK(st == SL_EINVAL && pb->n == SL_COMP_MAX_PROBLEMS && pb->n_more == 10 &&
              pb->n_bad_rows == SL_COMP_MAX_PROBLEMS + 10 &&
              pb->e[SL_COMP_MAX_PROBLEMS - 1].line == SL_COMP_MAX_PROBLEMS + 1,
              "the cap: %zu kept, %zu more", pb->n, pb->n_more);
        /* one problem: err is that problem */
        put(dir, "one.csv", "tag,building,floor,mu,base_m,cg_height_m,clearance_mm\nA,,gf,0,1,1,1\n");
        snprintf(path, sizeof path, "%s/one.csv", dir);
        st = sl_comp_table_read(path, &r, &t, pb, &e);
        CHECK(st == SL_EINVAL && pb->n == 1 && e.line == 2 && e.col == 4, "one problem: %s",
              e.msg);
        free(pb);
    }
    sl_comp_results_free(&r);
    char cmd[700];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    CHECK(system(cmd) == 0, "clean up");
}

/* A floor reference that is one floor's id and another's name (without case):
 * the results are refused when read, naming both floors and files, and a row
 * never resolves it by an order of preference (issue 39: floor=Roof took the
 * table of roof.ini, named "Ground slab", 29 % low). */
static void test_ambiguous_floor(void)
{
    char dir[] = "/tmp/sl-components-XXXXXX";
    CHECK(mkdtemp(dir) != NULL, "temporary folder");
    make_results(dir);
    put(dir, "floors.csv", "floor_id,floor\r\nroof,Ground slab\r\ntop,ROOF\r\n");
    put(dir, "floor_top.csv", "mu,clearance_mm,nltha_design_se_mm\r\n0.1,500,30\r\n"
                              "0.2,400,20\r\n0.4,300,10\r\n");
    sl_comp_results r;
    sl_error e;
    CHECK(sl_comp_results_load(dir, &r, &e) == SL_EINVAL && strstr(e.msg, "roof ('Ground slab'") &&
              strstr(e.msg, "top ('ROOF'") && strstr(e.file, "floors.csv"),
          "results refused: %s: %s", e.file, e.msg);
    /* the resolver alone, on results made by hand: the row is refused */
    put(dir, "floors.csv", "floor_id,floor\r\nroof,Ground slab\r\ntop,Top\r\n");
    CHECK(sl_comp_results_load(dir, &r, &e) == SL_OK, "results: %s", e.msg);
    if (r.n_floors == 2) {
        char *keep = r.floors[1].name;
        r.floors[1].name = "Roof";
        put(dir, "list.csv", "tag,building,floor,mu,base_m,cg_height_m,clearance_mm\n"
                             "A,,top,0.2,1,1,450\nB,,ROOF,0.2,1,1,450\n");
        char path[600];
        snprintf(path, sizeof path, "%s/list.csv", dir);
        sl_comp_table t;
        sl_status st = sl_comp_table_read(path, &r, &t, NULL, &e);
        CHECK(st == SL_EINVAL && e.line == 3 && e.col == 3 && strstr(e.msg, "names two floors") &&
                  strstr(e.msg, "roof (Ground slab, file") && strstr(e.msg, "top (Roof, file"),
              "ambiguous row: %d %ld:%ld %s", (int)st, e.line, e.col, e.msg);
        r.floors[1].name = keep;
    }
    sl_comp_results_free(&r);
    char cmd[700];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    CHECK(system(cmd) == 0, "clean up");
}

/* The name rule: the spreadsheet's TRIM and case-insensitive MATCH. */
static void test_names(void)
{
    CHECK(sl_comp_same_name("bâtiment RÉACTEUR", "Bâtiment réacteur"), "Latin-1");
    CHECK(sl_comp_same_name("  Floor   el. 12 M ", "floor el. 12 m"), "blanks trimmed, runs one");
    CHECK(sl_comp_same_name("ΑΝΤΙΔΡΑΣΤΗΡΑΣ", "αντιδραστηρας") &&
          sl_comp_same_name("ЭТАЖ −3 М", "этаж −3 м") && sl_comp_same_name("ŁÓDŹ", "łódź"),
          "Greek, Cyrillic, Latin Extended-A");
    CHECK(!sl_comp_same_name("Floor 1", "Floor 2") && !sl_comp_same_name("ab", "a b") &&
          !sl_comp_same_name("e\xCC\x81", "\xC3\xA9") && !sl_comp_same_name("a", "") &&
          sl_comp_same_name(" ", ""), "different names stay different (no normalization)");
    CHECK(sl_comp_same_name("\xFF\xFEx", "\xFF\xFEX") && !sl_comp_same_name("\xFFx", "\xFEx"),
          "bytes that are not UTF-8 kept");
    char k[64];
    CHECK(!strcmp(sl_casefold_key("  Ȿ  ÉTAGE ", k, sizeof k), "ȿ étage"), "key '%s'", k);
    CHECK(!strcmp(sl_casefold_key("\xC8\xBA", k, sizeof k), "\xE2\xB1\xA5"),
          "U+023A folds to 3 bytes");
    /* every letter of the BMP against the C library's own case tables (glibc's
     * C.UTF-8): a code point towlower maps, and its fold, agree, but for the
     * foldings that are not lower cases (the micro sign, long s, final sigma,
     * ...), where towupper of both agrees instead */
    locale_t loc = newlocale(LC_CTYPE_MASK, "C.UTF-8", (locale_t)0);
    if (loc == (locale_t)0)
        SKIP("no C.UTF-8 locale: the table is not checked against the C library's");
    size_t n = 0, bad = 0;
    for (unsigned long c = 0; c < 0x10000; c++) {
        if (c >= 0xD800 && c <= 0xDFFF)
            continue;
        wint_t lo = towlower_l((wint_t)c, loc), up = towupper_l((wint_t)c, loc);
        unsigned long f = sl_casefold_cp(c);
        if (lo == (wint_t)c && f == c)
            continue;
        n++;
        int ok = f == (unsigned long)lo ||
                 towupper_l((wint_t)f, loc) == towupper_l((wint_t)c, loc) ||
                 (up != (wint_t)c && towlower_l(up, loc) == (wint_t)f);
        if (!ok && bad++ < 5)
            fprintf(stderr, "    U+%04lX: fold U+%04lX, towlower U+%04lX\n", c, f,
                    (unsigned long)lo);
    }
    freelocale(loc);
    CHECK(n > 1000 && bad == 0, "%zu of %zu letters disagree with the C library", bad, n);
}

/* Rocking rows (components.h): the mode from mu, b/h and mu_max (a bound
 * equal to b/h is both), the block an item gives (b = base / 2), the
 * optional columns, and the verdicts once the rocking results are given:
 * the rocking one by rock_floor.h's rule at the row's clearance, the worse
 * governing a row checked both ways, the counts following. */
static void test_rocking_rows(void)
{
    char dir[] = "/tmp/sl-components-XXXXXX";
    CHECK(mkdtemp(dir) != NULL, "temporary folder");
    make_results(dir);
    sl_comp_results r;
    sl_error e;
    CHECK(sl_comp_results_load(dir, &r, &e) == SL_OK, "results: %s", e.msg);
    /* b/h: 0.5 / (2 x 1) = 0.25 */
    put(dir, "list.csv", "tag,building,floor,mu,base_m,cg_height_m,clearance_mm,mu_max,"
                         "restitution,orientation_deg\n"
                         "S,,gf,0.2,0.5,1,80,,,\n"      /* mu < b/h: sliding */
                         "R,,gf,0.25,0.5,1,80,,0.7,\n"  /* mu = b/h: rocking */
                         "B,,gf,0.2,0.5,1,80,0.25,,45\n"  /* mu < b/h = mu_max: both */
                         "N,,gf,0.2,0.5,1,80,0.249,,\n");  /* mu_max below b/h: sliding */
    char path[600];
    snprintf(path, sizeof path, "%s/list.csv", dir);
    sl_comp_table t;
    CHECK(sl_comp_table_read(path, &r, &t, NULL, &e) == SL_OK, "list: %s", e.msg);
    if (t.n == 4) {
        const sl_comp_mode m[4] = {SL_COMP_MODE_SLIDING, SL_COMP_MODE_ROCKING, SL_COMP_MODE_BOTH,
                                   SL_COMP_MODE_SLIDING};
        for (int i = 0; i < 4; i++)
            CHECK(t.rows[i].mode == m[i], "row %d: mode %d", i + 1, (int)t.rows[i].mode);
        CHECK(t.rows[1].verdict == SL_COMP_ROCKING && t.rows[2].verdict == SL_COMP_ROCKING &&
                  t.count[SL_COMP_ROCKING] == 2, "rocking rows pending until given results");
        sl_rockf_item it = sl_comp_rock_item(&t.rows[1]);
        CHECK(it.block.b_m == 0.25 && it.block.h_m == 1 && it.block.restitution == 0.7 &&
                  isnan(it.orientation_deg), "block of R: b %g h %g r %g", it.block.b_m,
              it.block.h_m, it.block.restitution);
        it = sl_comp_rock_item(&t.rows[2]);
        CHECK(it.block.restitution < 0 && it.orientation_deg == 45, "block of B");
        /* R stands (decided, excursion 50 mm <= 80 mm); then short at 90 mm */
        sl_rockf_result x;
        memset(&x, 0, sizeof x);
        x.n_sets = 20;
        x.excursion_m = 0.050;
        sl_comp_set_rocking(&t, 1, &x);
        CHECK(t.rows[1].verdict == SL_COMP_STANDS && t.rows[1].rock_verdict == SL_COMP_STANDS,
              "R stands");
        x.excursion_m = 0.090;
        sl_comp_set_rocking(&t, 1, &x);
        CHECK(t.rows[1].verdict == SL_COMP_SHORT, "R short: excursion 90 mm > 80 mm");
        /* B: sliding ok or marginal; rocking overturns at 1.5 x: overturns governs */
        sl_comp_verdict sv = t.rows[2].slide_verdict;
        CHECK(sv == SL_COMP_OK || sv == SL_COMP_MARGINAL, "B slides %d", (int)sv);
        x.level[1].p_tip = 0.2;
        x.level[1].p_tip_se = 0.01;
        sl_comp_set_rocking(&t, 2, &x);
        CHECK(t.rows[2].verdict == SL_COMP_OVERTURNS, "B: the worse (overturns)");
        /* B stands as a rocking block: the sliding verdict governs, as its word */
        memset(&x, 0, sizeof x);
        sl_comp_set_rocking(&t, 2, &x);
        CHECK(t.rows[2].rock_verdict == SL_COMP_STANDS && t.rows[2].verdict == sv,
              "B: stands and slides %s: %s", SL_COMP_VERDICT_NAME[sv],
              SL_COMP_VERDICT_NAME[t.rows[2].verdict]);
        size_t total = 0;
        for (int v = 0; v < SL_COMP_NVERDICTS; v++)
            total += t.count[v];
        CHECK(total == 4 && t.count[SL_COMP_SHORT] >= 1 && t.count[SL_COMP_ROCKING] == 0,
              "counts follow: %zu rows", total);
        /* a sliding row is never given a rocking result */
        sl_comp_verdict s0 = t.rows[0].verdict;
        x.level[0].p_tip = 1;
        sl_comp_set_rocking(&t, 0, &x);
        CHECK(t.rows[0].verdict == s0 && !t.rows[0].has_rock, "sliding row untouched");
        sl_comp_table_free(&t);
    }
    sl_comp_results_free(&r);
    char cmd[700];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    CHECK(system(cmd) == 0, "clean up");
}

int main(void)
{
    RUN(test_names);
    RUN(test_interp_twin);
    RUN(test_table);
    RUN(test_ambiguous_floor);
    RUN(test_rocking_rows);
    return HARNESS_END("components");
}
