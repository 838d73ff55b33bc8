/* test_report.c - report.h: floor ids, the names an output folder may hold,
 * the ranges text, the convergence band placeholders in the CSV, and the
 * refusal to write a non-finite result. */
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

static void test_floor_id(void)
{
    char b[80];
    CHECK(!strcmp(sl_report_floor_id("floors/04-roof36.ini", b, sizeof b), "04-roof36"), "%s", b);
    /* names as written (UTF-8); only file names made safe */
    CHECK(!strcmp(sl_report_floor_id("a/b/Aux bldg, el. 12.INI", b, sizeof b),
                  "Aux bldg, el. 12"), "%s", b);
    CHECK(!strcmp(sl_report_floor_id("x.txt", b, sizeof b), "x.txt"), "%s", b);
    CHECK(!strcmp(sl_report_floor_id("dir/.ini", b, sizeof b), ".ini"), "%s", b);
    CHECK(!strcmp(sl_report_floor_id("p/Bâtiment réacteur", b, sizeof b), "Bâtiment réacteur"),
          "%s", b);
    CHECK(!strcmp(sl_report_floor_id("Niveau −3 m.ini", b, sizeof b), "Niveau −3 m"), "%s", b);
    /* a byte that is not UTF-8 (Latin-1 e acute), a control byte, a cut sequence */
    CHECK(!strcmp(sl_report_floor_id("caf\xe9\x01.ini", b, sizeof b), "caf__"), "%s", b);
    CHECK(!strcmp(sl_report_floor_id("a\xe2\x88.ini", b, sizeof b), "a__"), "%s", b);
    /* 64 bytes at most, cut at a whole character: 63 'x' then a 2-byte letter */
    char longp[80];
    memset(longp, 'x', 63);
    strcpy(longp + 63, "éé.ini");
    CHECK(strlen(sl_report_floor_id(longp, b, sizeof b)) == 63 && b[62] == 'x', "%s", b);
    char f[80];
    CHECK(!strcmp(sl_report_file_name("Bâtiment réacteur", f, sizeof f), "Bâtiment_réacteur"),
          "%s", f);
    CHECK(!strcmp(sl_report_file_name("Niveau −3 m", f, sizeof f), "Niveau_−3_m"), "%s", f);
    CHECK(!strcmp(sl_report_file_name("Aux bldg, el. 12", f, sizeof f), "Aux_bldg__el__12"), "%s",
          f);
    CHECK(!strcmp(sl_report_file_name("a:b\\c\xe9", f, sizeof f), "a_b_c_"), "%s", f);
}

/* One set, mu 0.1..0.4; peaks chosen so the design values are hand numbers. */
static sl_design *design(double peak0)
{
    const double mu[4] = {0.1, 0.2, 0.3, 0.4};
    const double peak[4] = {peak0, 0.1, 0.05, 0.0};
    const double asce[4] = {0.25, 0.02, 0.01, 0.0};
    const double pgd[1] = {10.0};
    sl_design_input in = oracle_design_input(4, 1, mu, peak, asce, pgd, 0.5 * SL_G);
    sl_error e;
    return sl_design_compute(&in, &e);
}

/* Sheet names: the ids as written, Excel's forbidden characters made '_',
 * cut at 31 characters (not bytes); "F1", "F2", ... when two collide. */
static void test_sheet_names(void)
{
    sl_report_floor fl[3] = {{.id = "Bâtiment réacteur: niveau −3 m [sous-sol]"},
                             {.id = "a/b?c*"}, {.id = "'x'"}};
    sl_report r;
    sl_report_init(&r);
    r.floors = fl;
    r.n_floors = 3;
    char names[3][SL_RPT_SHEET_NAME_MAX * 4 + 1];
    sl_rpt_sheet_names(&r, names);
    CHECK(!strcmp(names[0], "Bâtiment réacteur_ niveau −3 m "), "'%s'", names[0]);
    CHECK(!strcmp(names[1], "a_b_c_") && !strcmp(names[2], "_x_"), "'%s' '%s'", names[1],
          names[2]);
    fl[2].id = "A/B?C*"; /* the same sheet name as floor 2, without case */
    sl_rpt_sheet_names(&r, names);
    CHECK(!strcmp(names[0], "F1") && !strcmp(names[2], "F3"), "'%s' '%s'", names[0], names[2]);
}

static void test_ranges_text(void)
{
    sl_design *d = design(0.2);
    CHECK(d != NULL, "design");
    if (!d)
        return;
    /* N = 0.6, 0.3, 0.15, 0; A = 0.5, 0.04, 0.02, 0: below at rows 0-2, from the grid's
     * start (open) to where A - N reaches 0 at row 3 (mu 0.4) */
    char b[256];
    sl_report_ranges_text(d, b, sizeof b);
    CHECK(!strcmp(b, "<=0.100-0.400"), "ranges '%s'", b);
    sl_design_free(d);
}

static void test_csv_band_and_finite(void)
{
    char dir[] = "/tmp/sl-report-XXXXXX";
    CHECK(mkdtemp(dir) != NULL, "temporary folder");
    sl_design *d = design(0.2);
    CHECK(d != NULL, "design");
    if (!d)
        return;
    const double lo[4] = {0.5, 0.25, 0.1, 0.0}, hi[4] = {0.7, 0.35, 0.2, 0.0};
    sl_report_floor fl = {.id = "f1", .name = "Floor 1", .path = "f1.ini", .elevation_m = NAN,
                          .units = "g", .zpa_h_ms2 = 0.5 * SL_G, .design = d, .note = "",
                          .design_lo_m = lo, .design_hi_m = hi};
    sl_report r;
    sl_report_init(&r);
    r.version = "seislide test";
    r.n_floors = 1;
    r.floors = &fl;
    sl_error e;
    CHECK(sl_report_write_csv(&r, dir, &e) == SL_OK, "csv: %s", e.msg);
    char path[512], line[1024];
    snprintf(path, sizeof path, "%s/floor_f1.csv", dir);
    FILE *f = fopen(path, "r");
    CHECK(f != NULL, "floor_f1.csv");
    int found = 0;
    while (f && fgets(line, sizeof line, f))
        if (!strncmp(line, "0.2,", 4)) {
            /* mu, x, mean, sd, design, se, lo, hi, ... */
            CHECK(strstr(line, ",300.0000,0.0000,250.0000,350.0000,") != NULL, "band: %s", line);
            found = 1;
        }
    if (f)
        fclose(f);
    CHECK(found, "row mu 0.2");
    /* a non-finite result is an error, not a file */
    d->rows[1].nltha_mean_m = INFINITY;
    char sub[300];
    snprintf(sub, sizeof sub, "%s/inf", dir);
    CHECK(system("true") == 0, "shell");
    snprintf(line, sizeof line, "mkdir -p '%s'", sub);
    CHECK(system(line) == 0, "mkdir");
    CHECK(sl_report_write_csv(&r, sub, &e) == SL_EINVAL && strstr(e.msg, "not finite"),
          "inf refused: %s", e.msg);
    snprintf(path, sizeof path, "%s/x.xlsx", sub);
    CHECK(sl_report_write_xlsx(&r, path, &e) == SL_EINVAL, "xlsx refused");
    CHECK(access(path, F_OK) != 0, "no workbook written");
    snprintf(path, sizeof path, "%s/floor_f1.csv", sub);
    CHECK(access(path, F_OK) != 0, "no CSV written");
    snprintf(line, sizeof line, "rm -rf '%s'", dir);
    CHECK(system(line) == 0, "clean up");
    sl_design_free(d);
}

/* The standard error of the NLTHA design value: two sets with peaks 0.1 and
 * 0.3 m: mean 0.2, sample sd sqrt(0.02) = 0.141421 m, design 3 x 0.2 = 0.6 m,
 * its standard error 3 x sd / sqrt(2) = 0.3 m exactly. */
static void test_design_se(void)
{
    const double mu[2] = {0.1, 0.2};
    const double peak[4] = {0.1, 0.0, 0.3, 0.0};
    const double pgd[2] = {10.0, 10.0};
    sl_design_input in = oracle_design_input(2, 2, mu, peak, NULL, pgd, 0.5 * SL_G);
    sl_error e;
    sl_design *d = sl_design_compute(&in, &e);
    CHECK(d != NULL, "design: %s", e.msg);
    if (!d)
        return;
    char dir[] = "/tmp/sl-report-se-XXXXXX", path[256], line[1024];
    CHECK(mkdtemp(dir) != NULL, "temporary folder");
    sl_report_floor fl = {.id = "f", .name = "F", .path = "f.ini", .elevation_m = NAN,
                          .units = "g", .zpa_h_ms2 = 0.5 * SL_G, .design = d, .note = ""};
    sl_report r;
    sl_report_init(&r);
    r.version = "seislide test";
    r.n_floors = 1;
    r.floors = &fl;
    CHECK(sl_report_write_csv(&r, dir, &e) == SL_OK, "csv: %s", e.msg);
    snprintf(path, sizeof path, "%s/floor_f.csv", dir);
    FILE *f = fopen(path, "r");
    int found = 0;
    while (f && fgets(line, sizeof line, f))
        if (!strncmp(line, "0.1,", 4))
            found = strstr(line, ",200.0000,141.4214,600.0000,300.0000,,,") != NULL;
    if (f)
        fclose(f);
    CHECK(found, "row mu 0.1 with mean 200, sd 141.4214, design 600, se 300: %s", line);
    snprintf(line, sizeof line, "rm -rf '%s'", dir);
    CHECK(system(line) == 0, "clean up");
    sl_design_free(d);
}

/* A floor whose motions failed their checks says so in the first line of
 * every CSV that holds it; every CSV traces its run (command, created, seed,
 * the floor file's CRC-32). */
static void test_failed_checks_and_trace(void)
{
    sl_design *d = design(0.2);
    CHECK(d != NULL, "design");
    if (!d)
        return;
    char dir[] = "/tmp/sl-report-fail-XXXXXX", path[512], line[2048];
    CHECK(mkdtemp(dir) != NULL, "temporary folder");
    sl_report_floor fl[2] = {
        {.id = "f1", .name = "Floor 1", .path = "f1.ini", .elevation_m = NAN, .units = "g",
         .zpa_h_ms2 = 0.5 * SL_G, .design = d, .note = "", .crc32 = 0xfbca2e0fUL,
         .size_bytes = 3623, .n_failed_motions = 2, .sa10_fallback = 1},
        {.id = "f2", .name = "Floor 2", .path = "f2.ini", .elevation_m = NAN, .units = "g",
         .zpa_h_ms2 = 0.5 * SL_G, .design = d, .note = "", .crc32 = 0x1234abcdUL}};
    const sl_report_quality q[] = {
        {.floor = "f1", .set = 1, .component = "H1", .pass = 0, .why = "below run_below "},
        {.floor = "f1", .set = 1, .component = "H2", .pass = 1, .why = ""},
        {.floor = "f1", .set = 1, .component = "V", .pass = 0, .why = "pga"},
        {.floor = "f2", .set = 1, .component = "H1", .pass = 1, .why = ""}};
    sl_report r;
    sl_report_init(&r);
    r.version = "seislide test";
    r.command_line = "seislide run floors --seed 7";
    r.seed = "7";
    r.created = 1700000000;
    r.n_floors = 2;
    r.floors = fl;
    r.n_quality = 4;
    r.quality = q;
    sl_error e;
    CHECK(sl_report_write_csv(&r, dir, &e) == SL_OK, "csv: %s", e.msg);
    static const char *const files[] = {"floor_f1.csv", "floor_f2.csv", "summary.csv",
                                        "floors.csv", "motion_quality.csv"};
    for (size_t k = 0; k < 5; k++) {
        snprintf(path, sizeof path, "%s/%s", dir, files[k]);
        FILE *f = fopen(path, "r");
        CHECK(f != NULL, "%s", files[k]);
        if (!f)
            continue;
        int first = 1, warned = 0, cmd = 0, created = 0, seed = 0, crc1 = 0, crc2 = 0;
        while (fgets(line, sizeof line, f) && line[0] == '#') {
            if (first)
                warned = !strncmp(line, "# WARNING: CHECKS FAILED: 2 of 3 motion components of "
                                  "floor f1 failed their SRP 3.7.1 checks (below 1, run_below 1, "
                                  "pga 1;", 120);
            first = 0;
            cmd |= !strcmp(line, "# command: seislide run floors --seed 7\r\n");
            created |= !strcmp(line, "# created: 2023-11-14T22:13:20Z\r\n");
            seed |= !strcmp(line, "# seed: 7\r\n");
            crc1 |= !strcmp(line, "# floor_file_crc32: fbca2e0f f1 (f1.ini, 3623 bytes)\r\n");
            crc2 |= !strncmp(line, "# floor_file_crc32: 1234abcd f2 ", 32);
        }
        fclose(f);
        int has_f1 = k != 1, has_f2 = k != 0;
        CHECK(warned == has_f1, "%s: first line warns of f1's failed checks: %d", files[k], warned);
        CHECK(cmd && created && seed, "%s: command %d, created %d, seed %d", files[k], cmd, created,
              seed);
        CHECK(crc1 == has_f1 && crc2 == has_f2, "%s: CRC-32 lines %d %d", files[k], crc1, crc2);
    }
    snprintf(path, sizeof path, "%s/x.xlsx", dir);
    CHECK(sl_report_write_xlsx(&r, path, &e) == SL_OK, "xlsx: %s", e.msg);
    /* the workbook's text is compressed: unzip -p when present */
    snprintf(line, sizeof line, "command -v unzip >/dev/null && unzip -p '%s' "
             "xl/sharedStrings.xml | grep -q 'Floor f1: the floor file gives no 10 %%-damped' && "
             "unzip -p '%s' xl/sharedStrings.xml | grep -q 'CHECKS FAILED: 2 of 3'", path, path);
    if (system("command -v unzip >/dev/null 2>&1") == 0)
        CHECK(system(line) == 0, "workbook: Notes entry for the 10 %% fallback and the failed checks");
    snprintf(line, sizeof line, "rm -rf '%s'", dir);
    CHECK(system(line) == 0, "clean up");
    sl_design_free(d);
}

int main(void)
{
    RUN(test_floor_id);
    RUN(test_sheet_names);
    RUN(test_ranges_text);
    RUN(test_csv_band_and_finite);
    RUN(test_design_se);
    RUN(test_failed_checks_and_trace);
    return HARNESS_END("report");
}
