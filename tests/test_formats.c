/*
 * test_formats.c - the GeoNet V2A, CSMIP V2 and CWA .acc readers (formats.h)
 * on every such file in ../shared/records (skipped when absent): channel
 * count, npts and dt per channel against records/MANIFEST.tsv, the peak
 * accelerations per folder (horizontal and vertical) against
 * records/SUMMARY.tsv, the peak against the file's own header, the set
 * reader sl_set_read_dir() on those folders and on folders that cannot make
 * a set, the set of named files (sl_set_read_files), and bad input.
 */
#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "harness.h"
#include "tsv.h"
#include "io/formats.h"
#include "io/setdir.h"

#define TOL_PGA_G 0.0006 /* g: SUMMARY.tsv rounds PGA to 3 decimals */


static int is_new_format(const char *f)
{
    return !strcmp(f, "GEONET_V2A") || !strcmp(f, "CSMIP_V2") || !strcmp(f, "TWOCOL_MS2") ||
           !strcmp(f, "SMC");
}

static double pga(const sl_motion *m)
{
    double p = 0;
    for (size_t i = 0; i < m->n; i++)
        p = fmax(p, fabs(m->acc_ms2[i]));
    return p;
}

/* The peaks a V2A or CSMIP file prints per channel ("Acceleration:  peak
 * -41.6 mm/s/s at  43.68 sec", "Peak acceleration =  27.114  cm/sec/sec  at
 * 32.570 sec"), in file order, converted to m/s^2 (mm or cm by the unit
 * text); returns the count. */
static size_t header_peaks(const char *path, double *pk, double *tk, size_t max)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return 0;
    char l[512];
    size_t n = 0;
    while (n < max && fgets(l, sizeof l, f)) {
        double v, t;
        char u[32];
        if (sscanf(l, "Acceleration: peak %lf %31s at %lf", &v, u, &t) == 3 ||
            sscanf(l, "Peak acceleration = %lf %31s at %lf", &v, u, &t) == 3 ||
            sscanf(l, "PEAK ACCELERATION = %lf %31s AT %lf", &v, u, &t) == 3) {
            pk[n] = v * (tolower((unsigned char)u[0]) == 'm' ? 1e-3 : 1e-2);
            tk[n++] = t;
        }
    }
    fclose(f);
    return n;
}

/* Every GEONET/CSMIP/CWA file: npts and dt per channel as MANIFEST says. */
static void test_manifest(void)
{
    const char *shared = harness_shared_dir();
    if (!shared)
        SKIP("../shared not found (set SEISLIDE_SHARED): agency formats not checked");
    char path[1200];
    snprintf(path, sizeof path, "%s/records/MANIFEST.tsv", shared);
    tsv t;
    if (tsv_read(path, &t) != 0)
        SKIP("%s: cannot read", path);
    long c_p = tsv_col(&t, "local_path"), c_f = tsv_col(&t, "format"), c_n = tsv_col(&t, "npts"),
         c_dt = tsv_col(&t, "dt");
    CHECK(c_p >= 0 && c_f >= 0 && c_n >= 0 && c_dt >= 0, "MANIFEST columns");
    if (c_p < 0 || c_f < 0 || c_n < 0 || c_dt < 0) {
        tsv_free(&t);
        return;
    }
    size_t files = 0, chans = 0;
    for (size_t r = 1; r < t.nrow; r++) {
        const char *fmt = tsv_get(&t, r, c_f);
        if (!is_new_format(fmt))
            continue;
        snprintf(path, sizeof path, "%s/records/%s", shared, tsv_get(&t, r, c_p));
        /* expected per channel: "8192;8192;8192" and "0.02;0.02;0.02" */
        long en[SL_CHANNELS_MAX];
        double edt[SL_CHANNELS_MAX];
        size_t ne = 0, nd = 0;
        for (const char *s = tsv_get(&t, r, c_n); *s && ne < SL_CHANNELS_MAX; s += strcspn(s, ";"), s += *s == ';')
            en[ne++] = strtol(s, NULL, 10);
        for (const char *s = tsv_get(&t, r, c_dt); *s && nd < SL_CHANNELS_MAX; s += strcspn(s, ";"), s += *s == ';')
            edt[nd++] = strtod(s, NULL);
        sl_error err;
        sl_error_clear(&err);
        sl_channels c;
        memset(&c, 0, sizeof c);
        if (!strcmp(fmt, "TWOCOL_MS2")) {
            c.m[0] = sl_cwa_acc_read(path, &err);
            c.n = c.m[0] != NULL;
            CHECK(c.n == 1, "%s: %s (line %ld)", path, err.msg, err.line);
        } else if (!strcmp(fmt, "SMC")) {
            c.m[0] = sl_smc_read(path, c.comp[0], sizeof c.comp[0], &err);
            c.n = c.m[0] != NULL;
            CHECK(c.n == 1, "%s: %s (line %ld)", path, err.msg, err.line);
            /* text line 7 prints the peak, "pk     =    104.4" (cm/s/s) */
            FILE *sf = fopen(path, "rb");
            char l[256] = "";
            for (int k = 0; sf && k < 7 && fgets(l, sizeof l, sf); k++)
                ;
            if (sf)
                fclose(sf);
            const char *q = strstr(l, "pk");
            double pk = q ? strtod(q + strcspn(q, "=") + 1, NULL) * 1e-2 : -1;
            CHECK(c.n == 0 || fabs(pga(c.m[0]) - pk) <= 6e-4, "%s: peak %.5f m/s2, header %.5f",
                  path, c.n ? pga(c.m[0]) : 0.0, pk);
        } else {
            CHECK(sl_channels_read(path, &c, &err) == SL_OK, "%s: %s (line %ld)", path, err.msg,
                  err.line);
        }
        files++;
        CHECK(c.n == ne && ne == nd, "%s: %zu channels read, MANIFEST lists %zu", path, c.n, ne);
        for (size_t k = 0; k < c.n && k < ne && k < nd; k++) {
            chans++;
            CHECK(c.m[k]->n == (size_t)en[k], "%s channel %zu: npts %zu, MANIFEST %ld", path,
                  k + 1, c.m[k]->n, en[k]);
            CHECK(fabs(c.m[k]->dt_s - edt[k]) < 1e-9, "%s channel %zu: dt %g, MANIFEST %g",
                  path, k + 1, c.m[k]->dt_s, edt[k]);
        }
        /* the peak value and its time as the file's own header prints them
         * (rounded to 0.1 mm/s2 or 0.001 cm/s2, time to 0.01 s) */
        double hp[SL_CHANNELS_MAX], ht[SL_CHANNELS_MAX];
        const int one = !strcmp(fmt, "TWOCOL_MS2") || !strcmp(fmt, "SMC");
        size_t nh = !one ? header_peaks(path, hp, ht, SL_CHANNELS_MAX) : 0;
        CHECK(one || nh == c.n, "%s: %zu header peaks, %zu channels",
              path, nh, c.n);
        for (size_t k = 0; k < nh && k < c.n; k++) {
            size_t im = 0;
            for (size_t i = 0; i < c.m[k]->n; i++)
                if (fabs(c.m[k]->acc_ms2[i]) > fabs(c.m[k]->acc_ms2[im]))
                    im = i;
            const double a = c.m[k]->acc_ms2[im], ta = (double)im * c.m[k]->dt_s;
            CHECK(fabs(a - hp[k]) <= 1e-4 + 1e-4 * fabs(hp[k]),
                  "%s channel %zu: peak %.5f m/s2, header %.5f", path, k + 1, a, hp[k]);
            /* GeoNet prints times from the trigger, 5.00 s after the first
             * sample in these files (the V2A real header, line 3, fields 2-3:
             * "5.00 5.00"); CSMIP from the first sample */
            const double t0 = strcmp(fmt, "GEONET_V2A") ? 0.0 : 5.0;
            CHECK(fabs(ta - t0 - ht[k]) <= 0.5 * c.m[k]->dt_s + 0.006,
                  "%s channel %zu: peak at %.3f s (sample %zu), header %.3f s + %g", path, k + 1, ta,
                  im, ht[k], t0);
        }
        sl_channels_free(&c);
    }
    tsv_free(&t);
    CHECK(files >= 20, "only %zu agency-format files in MANIFEST", files);
    fprintf(stderr, "  %zu agency-format files, %zu channels: npts and dt as MANIFEST says\n",
            files, chans);
}

/* The folder's set: PGA of H (max of the two) and V against SUMMARY, and
 * each channel's PGA against the peak its V2A / CSMIP header prints. */
static void test_summary_and_sets(void)
{
    const char *shared = harness_shared_dir();
    if (!shared)
        SKIP("../shared not found (set SEISLIDE_SHARED): agency formats not checked");
    char path[1200];
    snprintf(path, sizeof path, "%s/records/SUMMARY.tsv", shared);
    tsv s;
    if (tsv_read(path, &s) != 0)
        SKIP("%s: cannot read", path);
    long c_dir = tsv_col(&s, "dir"), c_h = tsv_col(&s, "pga_h_g"), c_v = tsv_col(&s, "pga_v_g"),
         c_f = tsv_col(&s, "formats");
    CHECK(c_dir >= 0 && c_h >= 0 && c_v >= 0 && c_f >= 0, "SUMMARY columns");
    if (c_dir < 0 || c_h < 0 || c_v < 0 || c_f < 0) {
        tsv_free(&s);
        return;
    }
    size_t sets = 0;
    for (size_t r = 1; r < s.nrow; r++) {
        if (!is_new_format(tsv_get(&s, r, c_f)))
            continue;
        char dir[1200];
        snprintf(dir, sizeof dir, "%s/records/%s", shared, tsv_get(&s, r, c_dir));
        sl_set set;
        sl_error err;
        sl_error_clear(&err);
        if (sl_set_read_dir(dir, &set, &err) != SL_OK) {
            CHECK(0, "%s: %s", dir, err.msg);
            continue;
        }
        sets++;
        const double h = fmax(pga(set.h1), pga(set.h2)) / SL_G, v = pga(set.v) / SL_G;
        const double eh = strtod(tsv_get(&s, r, c_h), NULL), ev = strtod(tsv_get(&s, r, c_v), NULL);
        CHECK(fabs(h - eh) <= TOL_PGA_G, "%s: horizontal PGA %.4f g, SUMMARY %.3f", dir, h, eh);
        CHECK(fabs(v - ev) <= TOL_PGA_G, "%s: vertical PGA %.4f g, SUMMARY %.3f", dir, v, ev);
        CHECK(set.h1->n == set.v->n && set.h2->n == set.v->n, "%s: lengths", dir);
        sl_set_free_motions(&set);
    }
    tsv_free(&s);
    CHECK(sets >= 15, "only %zu agency-format sets in SUMMARY", sets);
    fprintf(stderr, "  %zu agency-format sets read as H1 + H2 + V; PGA as SUMMARY says\n", sets);
}

/* Bad input: a V2A cut inside its data, a bad value, an unknown unit. */
static void test_bad_input(void)
{
    const char *shared = harness_shared_dir();
    if (!shared)
        SKIP("../shared not found (set SEISLIDE_SHARED): agency formats not checked");
    char path[1200];
    snprintf(path, sizeof path, "%s/records/GEONET_2018_WPWS/20180212_211557_WPWS_20.V2A", shared);
    FILE *f = fopen(path, "rb");
    if (!f)
        SKIP("%s: cannot open", path);
    char *buf = calloc(1, 1 << 16);
    size_t n = fread(buf, 1, (1 << 16) - 1, f);
    fclose(f);
    /* the first 40 lines: header + 14 data lines of channel 1 */
    size_t cut = 0;
    for (int l = 0; l < 40 && cut < n; cut++)
        l += buf[cut] == '\n';
    buf[cut] = '\0';
    sl_error err;
    sl_channels c;
    const char *p = harness_tmpfile("cut.V2A", buf);
    sl_error_clear(&err);
    CHECK(sl_channels_read(p, &c, &err) == SL_EPARSE && err.line == 40 && strstr(err.msg, "140 of 5800"),
          "cut V2A: %ld %s", err.line, err.msg);
    CHECK(c.n == 0, "nothing left after a failure");
    /* a letter in data line 30 */
    char *l30 = buf;
    for (int l = 0; l < 29; l++)
        l30 = strchr(l30, '\n') + 1;
    l30[5] = 'x';
    p = harness_tmpfile("bad.V2A", buf);
    sl_error_clear(&err);
    CHECK(sl_channels_read(p, &c, &err) == SL_EPARSE && err.line == 30 &&
              strstr(err.msg, "x") != NULL,
          "bad value: %ld %s", err.line, err.msg);
    /* the same file behind a UTF-8 byte-order mark: read the same, the same line named */
    size_t nb = strlen(buf);
    char *bom = malloc(nb + 4);
    memcpy(bom, "\xef\xbb\xbf", 3);
    memcpy(bom + 3, buf, nb + 1);
    p = harness_tmpfile("bom.V2A", bom);
    sl_error_clear(&err);
    CHECK(sl_channels_read(p, &c, &err) == SL_EPARSE && err.line == 30 &&
              strstr(err.msg, "x") != NULL,
          "bad value behind a BOM: %ld %s", err.line, err.msg);
    free(bom);
    l30[5] = ' ';
    /* unit changed to cm/s/s */
    char *u = strstr(buf, "mm/s/s");
    u[0] = 'c';
    p = harness_tmpfile("unit.V2A", buf);
    sl_error_clear(&err);
    CHECK(sl_channels_read(p, &c, &err) == SL_EINVAL && err.line == 14 &&
              strstr(err.msg, "cm/s/s") != NULL,
          "unit: %ld %s", err.line, err.msg);
    /* CSMIP: an unknown unit on the "points of accel data" line (line 46) */
    snprintf(path, sizeof path, "%s/records/CSMIP_2014Napa_58667_Concord/CE58667.V2", shared);
    f = fopen(path, "rb");
    n = f ? fread(buf, 1, (1 << 16) - 1, f) : 0;
    if (f)
        fclose(f);
    buf[n] = '\0';
    u = strstr(buf, "in cm/sec2");
    CHECK(u != NULL, "%s: no 'in cm/sec2'", path);
    if (u) {
        memcpy(u + 3, "ft/", 3);
        p = harness_tmpfile("unit.V2", buf);
        sl_error_clear(&err);
        CHECK(sl_channels_read(p, &c, &err) == SL_EINVAL && err.line == 46 &&
                  strstr(err.msg, "ft/sec2") != NULL,
              "CSMIP unit: %ld %s", err.line, err.msg);
    }
    /* SMC: not a corrected accelerogram */
    p = harness_tmpfile("x.smc", "1 UNCORRECTED ACCELEROGRAM\n");
    sl_error_clear(&err);
    CHECK(sl_smc_read(p, NULL, 0, &err) == NULL && err.code == SL_EPARSE && err.line == 1,
          "SMC type: %ld %s", err.line, err.msg);
    free(buf);
    CHECK(sl_component_is_vertical("Up") && sl_component_is_vertical(" UP ") &&
              sl_component_is_vertical("Z") && !sl_component_is_vertical("90 Deg") &&
              !sl_component_is_vertical("N10E") && !sl_component_is_vertical("H1"),
          "component names");
}

/* A file name in a fresh folder below TMPDIR (made on first use). */
static const char *tmp_path(const char *sub, const char *name)
{
    static char dir[512], path[1024];
    const char *t = getenv("TMPDIR");
    snprintf(dir, sizeof dir, "%s/seislide-setdir-%ld-%s", t && *t ? t : "/tmp", (long)getpid(),
             sub);
    mkdir(dir, 0755);
    snprintf(path, sizeof path, "%s/%s", dir, name ? name : "");
    return name ? path : dir;
}

/* sl_set_read_dir on folders that cannot make a set: which format it takes
 * (.AT2 before .V2A/.V2 before .smc before .acc), the component count, the
 * message naming the folder or file; nothing left allocated. */
static void test_setdir_layouts(void)
{
    static const char *const cases[][5] = {
        {"a_H1.AT2", "b_H2.AT2", "c_H3.AT2", "d_UP.AT2", NULL},
        {"x.V2A", "y.V2A", NULL},
        {"a_E.acc", "b_N.acc", NULL},
        {"a_E.acc", "b_N.acc", "c_Z.acc", "d.smc", NULL},
        {"a_H1.AT2", "b_H2.AT2", "c_UP.AT2", "x.V2A", "a_E.acc"},
        {NULL},
    };
    static const char *const expect[] = {
        "expected 2 horizontal and 1 vertical .AT2 files, found 3 and 1",
        "2 multi-channel files, expected one",
        "expected 2 horizontal and 1 vertical .acc files, found 2 and 0",
        "not an SMC corrected accelerogram",
        "empty file", /* a_H1.AT2: the .AT2 files are read, not the others */
        "no .AT2, .V2A, .V2, .smc or .acc files in this folder",
    };
    for (size_t i = 0; i < sizeof expect / sizeof expect[0]; i++) {
        char sub[16];
        snprintf(sub, sizeof sub, "%zu", i);
        for (int k = 0; k < 5 && cases[i][k]; k++) {
            FILE *f = fopen(tmp_path(sub, cases[i][k]), "w");
            if (f)
                fclose(f);
        }
        sl_set set;
        sl_error err;
        sl_error_clear(&err);
        const char *dir = tmp_path(sub, NULL);
        sl_status st = sl_set_read_dir(dir, &set, &err);
        CHECK(st != SL_OK && strstr(err.msg, expect[i]) && !set.h1 && !set.h2 && !set.v &&
                  !strncmp(err.file, dir, strlen(dir)) && (i != 4 || strstr(err.file, "a_H1.AT2")),
              "case %zu: %d %s: %s", i, (int)st, err.file, err.msg);
        for (int k = 0; k < 5 && cases[i][k]; k++)
            remove(tmp_path(sub, cases[i][k]));
        rmdir(dir);
    }
}

/* sl_set_read_files: H1 and H2 of different length (H2 padded with zeros to
 * H1's 4 samples, said in fit), no V; a missing file named, nothing left. */
static void test_set_read_files(void)
{
    const char *h1 = harness_tmpfile("h1.txt", "0 0.1\n0.01 -0.2\n0.02 0.3\n0.03 0.05\n");
    const char *h2 = harness_tmpfile("h2.txt", "0 0.4\n0.01 0.1\n0.02 -0.5\n");
    sl_read_opts ro = {SL_FORMAT_AUTO, SL_UNIT_G, 0.0};
    sl_set set;
    sl_set_fit fit;
    sl_error err;
    const char *p[3] = {h1, h2, NULL};
    CHECK(sl_set_read_files(p, &ro, 0, &set, &fit, &err) == SL_OK, "%s", err.msg);
    if (set.h1 && set.h2) {
        CHECK(set.h1->n == 4 && set.h2->n == 4 && !set.v && fit.changed && !fit.truncated &&
                  fit.n_in[0] == 4 && fit.n_in[1] == 3 && fit.n_in[2] == 0,
              "n %zu %zu, fit %zu %zu %zu", set.h1->n, set.h2->n, fit.n_in[0], fit.n_in[1],
              fit.n_in[2]);
        CHECK_CLOSE(set.h2->acc_ms2[2], -0.5 * SL_G, 0, 1e-12);
        CHECK(set.h2->acc_ms2[3] == 0.0, "padded with %g", set.h2->acc_ms2[3]);
        CHECK_CLOSE(sl_set_pga_h(&set), 0.5 * SL_G, 0, 1e-12);
    }
    sl_set_free_motions(&set);
    const char *q[3] = {h1, "/nonexistent/h2.AT2", NULL};
    CHECK(sl_set_read_files(q, &ro, 1, &set, NULL, &err) != SL_OK && !set.h1 && !set.h2 &&
              strstr(err.file, "/nonexistent/h2.AT2"),
          "missing H2: %s %s", err.file, err.msg);
    remove(h1);
    remove(h2);
}

int main(void)
{
    RUN(test_manifest);
    RUN(test_summary_and_sets);
    RUN(test_bad_input);
    RUN(test_setdir_layouts);
    RUN(test_set_read_files);
    return HARNESS_END("formats");
}
