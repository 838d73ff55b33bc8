/* test_plant.c - the plant's pieces (docs/plant.md): a floor result through
 * its byte encoding and back, bit for bit; every truncation and byte flip of
 * a cache entry refused (never used, never a crash: run under ASan by `make
 * asan`); the decoder fed damaged payloads past the checksum; the shard
 * dealing (longest processing time first) against a worked example; and the
 * plant workbook's Lookup recalculated by LibreOffice (headless) against
 * sl_design_clearance_at for 20 (building, floor, mu) cases and the input
 * checks. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <unistd.h>

#include "analysis.h"
#include "core/units.h"
#include "harness.h"
#include "io/owner.h"
#include "method/design.h"
#include "oracle.h"
#include "plant/cache.h"
#include "plant/entry.h"
#include "plant/plant.h"
#include "report/plant_book.h"

static const double MU[] = {0.05, 0.1, 0.2, 0.3, 0.5};
#define N_MU_RUN (sizeof MU / sizeof MU[0])

/* One real floor result (2 sets, 5 friction values: about a second). */
static sl_analysis *real_analysis(sl_floor **fl, sl_analysis_opts *o)
{
    sl_error e;
    *fl = sl_floor_load("floors/04-roof36.ini", &e);
    if (!*fl)
        return NULL;
    sl_analysis_opts_default(o);
    o->n_sets = 2;
    o->mu = MU;
    o->n_mu = N_MU_RUN;
    return sl_analysis_run(*fl, o, &e);
}

static void test_entry_roundtrip_and_damage(void)
{
    sl_floor *fl = NULL;
    sl_analysis_opts o;
    sl_analysis *a = real_analysis(&fl, &o);
    CHECK(a != NULL, "analysis of floors/04-roof36.ini");
    if (!a) {
        sl_floor_free(fl);
        return;
    }
    /* encode, decode, encode: the same bytes (every double bit for bit) */
    sl_pbuf w1 = {0}, w2 = {0};
    sl_entry_encode(&w1, a);
    sl_preader r = {.b = w1.b, .n = w1.n};
    sl_analysis *b = sl_entry_decode(&r, N_MU_RUN);
    CHECK(b != NULL, "decode: %s", r.why ? r.why : "?");
    if (b) {
        sl_entry_encode(&w2, b);
        CHECK(w1.n == w2.n && memcmp(w1.b, w2.b, w1.n) == 0, "round trip changed the bytes");
        for (size_t k = 0; k < N_MU_RUN; k++)
            CHECK(memcmp(&a->design->rows[k], &b->design->rows[k], sizeof a->design->rows[k]) == 0,
                  "design row %zu differs", k);
        CHECK(!strcmp(a->note, b->note) && a->n_sets == b->n_sets && b->sets[1].check[2].pass ==
              a->sets[1].check[2].pass, "scalars differ");
        /* the variance-reduction diagnostic and a motion's whole check (what
         * run_report_checks says of a failed motion: where, how far) come back */
        CHECK(a->vr_factor && b->vr_factor && a->vr_corr_sa && b->vr_corr_sa &&
                  !memcmp(a->vr_factor, b->vr_factor, N_MU_RUN * sizeof *a->vr_factor) &&
                  !memcmp(a->vr_corr_sa, b->vr_corr_sa, N_MU_RUN * sizeof *a->vr_corr_sa),
              "vr_* arrays lost");
        CHECK(b->sets[1].check[0].npoints == a->sets[1].check[0].npoints &&
                  b->sets[1].check[0].npoints > 0 &&
                  !memcmp(&b->sets[1].check[0].f_min_ratio_hz, &a->sets[1].check[0].f_min_ratio_hz,
                          sizeof(double)) &&
                  b->sets[1].check[0].ok_peaks == a->sets[1].check[0].ok_peaks,
              "a motion's check lost fields");
    }
    sl_analysis_free(b);
    /* the decoder on every truncation and on byte flips (no checksum in front) */
    size_t ok_trunc = 0;
    for (size_t n = 0; n < w1.n; n++) {
        sl_preader t = {.b = w1.b, .n = n};
        sl_analysis *x = sl_entry_decode(&t, N_MU_RUN);
        ok_trunc += x != NULL;
        sl_analysis_free(x);
    }
    CHECK(ok_trunc == 0, "%zu truncations decoded", ok_trunc);
    unsigned char *m = malloc(w1.n);
    for (size_t i = 0; m && i < w1.n; i += 3) {
        memcpy(m, w1.b, w1.n);
        m[i] ^= 0xA5;
        sl_preader t = {.b = m, .n = w1.n};
        sl_analysis_free(sl_entry_decode(&t, N_MU_RUN)); /* anything but a crash or a leak */
    }
    free(m);
    /* a cache entry: read back, then every truncation and every flipped byte refused */
    char dir[] = "/tmp/sl-plant-XXXXXX", path[256], why[256];
    CHECK(mkdtemp(dir) != NULL, "temporary folder");
    sl_entry_key k;
    sl_error e;
    CHECK(sl_entry_key_make(fl, &o, "seislide test", &k, &e) == SL_OK, "key");
    CHECK(sl_cache_open(dir, &e) == SL_OK, "cache open");
    CHECK(sl_cache_write(dir, &k, a, &e) == SL_OK, "cache write: %s", e.msg);
    sl_analysis *c = NULL;
    CHECK(sl_cache_read(dir, &k, N_MU_RUN, &c, why, sizeof why) == SL_CACHE_HIT, "read: %s", why);
    sl_analysis_free(c);
    snprintf(path, sizeof path, "%s/%s" SL_CACHE_SUFFIX, dir, k.hash);
    FILE *f = fopen(path, "rb");
    unsigned char *file = malloc(4 << 20);
    size_t nf = f && file ? fread(file, 1, 4 << 20, f) : 0;
    if (f)
        fclose(f);
    CHECK(nf > 100, "entry file");
    size_t used = 0;
    for (size_t n = 0; n < nf; n += (n < 200 ? 1 : 97)) {
        f = fopen(path, "wb");
        fwrite(file, 1, n, f);
        fclose(f);
        c = NULL;
        used += sl_cache_read_path(path, k.hash, N_MU_RUN, &c, why, sizeof why) == SL_CACHE_HIT;
        sl_analysis_free(c);
    }
    for (size_t i = 0; i < nf; i += (i < 200 ? 1 : 89)) {
        file[i] ^= 0x10;
        f = fopen(path, "wb");
        fwrite(file, 1, nf, f);
        fclose(f);
        file[i] ^= 0x10;
        c = NULL;
        used += sl_cache_read(dir, &k, N_MU_RUN, &c, why, sizeof why) == SL_CACHE_HIT;
        sl_analysis_free(c);
    }
    CHECK(used == 0, "%zu damaged entries were used", used);
    /* another key (another setting) never reads this entry */
    sl_entry_key k2;
    o.seed = 2;
    CHECK(sl_entry_key_make(fl, &o, "seislide test", &k2, &e) == SL_OK, "key 2");
    CHECK(strcmp(k.hash, k2.hash) != 0, "the seed must change the key");
    o.seed = 1;
    /* locks: taken once, busy for a second taker, free again after unlock */
    CHECK(sl_cache_lock(dir, k.hash, &e) == SL_CACHE_LOCKED, "lock");
    CHECK(sl_cache_lock(dir, k.hash, &e) == SL_CACHE_BUSY, "second lock must be busy");
    sl_cache_unlock(dir, k.hash);
    CHECK(sl_cache_lock(dir, k.hash, &e) == SL_CACHE_LOCKED, "lock after unlock");
    sl_cache_unlock(dir, k.hash);
    /* a lock of a dead process of this host is stale */
    char lp[300], host[128];
    snprintf(lp, sizeof lp, "%s/%s.lock", dir, k.hash);
    gethostname(host, sizeof host);
    host[sizeof host - 1] = '\0';
    f = fopen(lp, "w");
    fprintf(f, "%s 999999999 0\n", host);
    fclose(f);
    /* ... and the entry it was writing when it died goes with it (the cache
     * was opened before it died, so only the break can sweep it) */
    char tp[400], oh[128];
    sl_owner_host(oh, sizeof oh);
    snprintf(tp, sizeof tp, "%s/.%s.tmp-%s-999999999-abcdef", dir, k.hash, oh);
    f = fopen(tp, "w");
    CHECK(f != NULL, "%s", tp);
    if (f)
        fclose(f);
    CHECK(sl_cache_lock(dir, k.hash, &e) == SL_CACHE_LOCKED, "a dead process's lock must be broken");
    CHECK(access(tp, F_OK) != 0, "the dead process's temporary entry was left: %s", tp);
    sl_cache_unlock(dir, k.hash);
    char cmd[300];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    CHECK(system(cmd) == 0, "clean up");
    free(file);
    sl_entry_key_free(&k);
    sl_entry_key_free(&k2);
    sl_pbuf_free(&w1);
    sl_pbuf_free(&w2);
    sl_analysis_free(a);
    sl_floor_free(fl);
}

/* Longest processing time first, worked by hand: costs 10 9 8 7 6 5 4 on 3
 * shards: 10->1, 9->2, 8->3, 7->3 (15), 6->2 (15), 5->1 (15), 4->1 (19). */
static void test_shard_lpt(void)
{
    static const double cost[] = {4, 10, 6, 9, 5, 8, 7};
    static const unsigned want[] = {1, 1, 2, 2, 1, 3, 3};
    sl_plant_floor fl[7];
    memset(fl, 0, sizeof fl);
    sl_plant p = {.n = 7, .floors = fl};
    for (int i = 0; i < 7; i++)
        fl[i].cost = cost[i];
    sl_plant_assign(&p, 3);
    for (int i = 0; i < 7; i++)
        CHECK(fl[i].shard == want[i], "floor %d (cost %g): shard %u, expected %u", i, cost[i],
              fl[i].shard, want[i]);
    /* one shard takes everything; more shards than floors leaves some empty */
    sl_plant_assign(&p, 1);
    for (int i = 0; i < 7; i++)
        CHECK(fl[i].shard == 1, "one shard");
    sl_plant_assign(&p, 9);
    for (int i = 0; i < 7; i++)
        CHECK(fl[i].shard >= 1 && fl[i].shard <= 7, "9 shards: floor %d on %u", i, fl[i].shard);
}

#define N_MU 16
static sl_design *make_design(double scale, double zpa_g)
{
    double mu[N_MU], peak[2 * N_MU], asce[N_MU];
    const double pgd[2] = {2.0, 2.4};
    for (int k = 0; k < N_MU; k++) {
        mu[k] = 0.05 * (k + 1);
        double base = scale * exp(-6.0 * mu[k]) * (1.0 + 0.3 * (k % 3));
        peak[k] = 0.9 * base;
        peak[N_MU + k] = 1.1 * base;
        asce[k] = 1.2 * base;
    }
    sl_design_input in = oracle_design_input(N_MU, 2, mu, peak, asce, pgd, zpa_g * SL_G);
    sl_error e;
    return sl_design_compute(&in, &e);
}

/* a building and floor names as written, not ASCII (UTF-8) */
#define RB "Bâtiment réacteur"

typedef struct pcase {
    const char *building, *floor;
    double mu;
    const char *check;
} pcase;

static const pcase cases[] = {
    {RB, "Rez-de-chaussée", 0.30, "ok"},   {RB, "Rez-de-chaussée", 0.05, "ok"},
    {RB, "Rez-de-chaussée", 0.80, "ok"},   {RB, "Rez-de-chaussée", 0.0712, "ok"},
    {RB, "Niveau −3 m", 0.337, "ok"},      {RB, "Niveau −3 m", 0.1234, "ok"},
    {RB, "Niveau −3 m", 0.55, "ok"},       {RB, "niveau −3 M", 0.79, "ok"},
    {"Aux", "Aux ground", 0.30, "ok"},     {"Aux", "Aux ground", 0.2222, "ok"},
    {"Aux", "Aux ground", 0.45, "ok"},     {"aux", "Aux ground", 0.651, "ok"},
    {"Aux", "Aux el. 12 m", 0.05, "ok"},   {"Aux", "Aux el. 12 m", 0.0999, "ok"},
    {"Aux", "Aux el. 12 m", 0.375, "ok"},  {"Aux", "Aux el. 12 m", 0.7001, "ok"},
    {RB, "Niveau −3 m", 0.25, "ok"},       {"Aux", "Aux el. 12 m", 0.2, "ok"},
    {RB, "Rez-de-chaussée", 0.61, "ok"},   {"Aux", "Aux ground", 0.15, "ok"},
    /* the Lookup lists floor names, as the building Lookup does: an id is unknown */
    {"Aux", "el12", 0.3, "unknown floor in this building: choose one from the list"},
    {"Aux", "Niveau −3 m", 0.3, "unknown floor in this building: choose one from the list"},
    {"Turbine", "Aux ground", 0.3, "unknown building: choose one from the list"},
    {"", "Aux ground", 0.3, "choose a building from the list"},
    {"Aux", "", 0.3, "choose a floor from the list"},
    {"Aux", "Aux el. 12 m", 0.9, "mu outside the table"},
    {"Aux", "Aux el. 12 m", NAN, "type mu"},
};
#define N_CASES (sizeof cases / sizeof cases[0])

/* Field col (0-based) of line row (0-based) of a LibreOffice CSV export. */
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
        int c = 0, q = 0;
        size_t k = 0;
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

/* A design on the friction grid mu[0..n-1] (clearance rising from 10 mm). */
static sl_design *grid_design(const double *mu, size_t n)
{
    double peak[2 * 8], asce[8];
    const double pgd[2] = {2.0, 2.4};
    for (size_t k = 0; k < n && k < 8; k++) {
        peak[k] = 0.05 * exp(-6.0 * mu[k]);
        peak[n + k] = 0.06 * exp(-5.0 * mu[k]);
        asce[k] = 0.5 * peak[k];
    }
    sl_design_input in = oracle_design_input(n, 2, mu, peak, asce, pgd, 0.6 * SL_G);
    sl_error e;
    return n <= 8 ? sl_design_compute(&in, &e) : NULL;
}

/* plant.csv's fixed columns are the run's computed points: on a coarse grid
 * (0.04, 0.1, 0.2, 0.35) the columns 0.1 and 0.2 hold those rows' clearance
 * exactly, 0.05 and 0.3 (inside the grid, not on it) and 0.4, 0.5 (outside)
 * are empty, never a straight line between two computed points. On a grid
 * made as --mu-range makes it (A + k S, off by round-off) every column is a
 * row. */
static void test_plant_csv_computed_points(void)
{
    static const double coarse[] = {0.04, 0.1, 0.2, 0.35};
    double fine[6] = {0.05}; /* then 0.1 + k 0.1 as --mu-range makes it: 0.1 + 2 x 0.1 is
                                0.30000000000000004, the grid point of mu 0.3 */
    for (int k = 0; k < 5; k++)
        fine[1 + k] = 0.1 + (double)k * 0.1;
    sl_design *dc = grid_design(coarse, 4), *df = grid_design(fine, 6);
    CHECK(dc && df, "designs");
    char dir[] = "/tmp/sl-plantcsv-XXXXXX", path[300], line[2000];
    CHECK(mkdtemp(dir) != NULL, "temporary folder");
    for (int g = 0; dc && df && g < 2; g++) {
        const sl_design *d = g ? df : dc;
        const sl_plant_book_row rows[1] = {{"B", "f", "floor", 0, 0.6 * SL_G, 2, "fixed", d,
                                            NULL, 0, 0, 0, NULL, NULL}};
        sl_plant_book b = {.version = "seislide test", .command_line = "-", .n = 1, .rows = rows};
        sl_error e;
        CHECK(sl_plant_book_write_csv(&b, dir, &e) == SL_OK, "plant.csv: %s", e.msg);
        snprintf(path, sizeof path, "%s/plant.csv", dir);
        FILE *f = fopen(path, "rb");
        int row = 0, data = -1;
        while (f && fgets(line, sizeof line, f)) {
            if (!strncmp(line, "building,", 9))
                data = row + 1;
            row++;
        }
        if (f)
            fclose(f);
        CHECK(data > 0, "plant.csv header");
        for (int k = 0; k < SL_PLANT_BOOK_NMU; k++) {
            char cell[64] = "?", want[64] = "";
            csv_cell(path, data, 7 + k, cell, sizeof cell);
            for (size_t j = 0; j < d->n; j++) /* the computed row at that mu, if any */
                if (fabs(d->rows[j].mu - SL_PLANT_BOOK_MU[k]) < 1e-12)
                    snprintf(want, sizeof want, "%.3f", 1e3 * d->rows[j].clearance_m);
            if (g) /* every one on the fine grid */
                CHECK(want[0], "mu %g not on the fine grid", SL_PLANT_BOOK_MU[k]);
            /* printed to the digit of its standard error (whole mm at most) */
            CHECK(!cell[0] == !want[0] && (!cell[0] || fabs(atof(cell) - atof(want)) <= 0.5),
                  "%s grid, mu %g: '%s', expected '%s'", g ? "fine" : "coarse",
                  SL_PLANT_BOOK_MU[k], cell, want);
            if (!g && k == 0) /* the case a straight line would have filled */
                CHECK(!isnan(sl_design_clearance_at(d, 0.05)) && !cell[0],
                      "mu 0.05 inside the coarse grid: empty expected");
        }
        remove(path);
    }
    rmdir(dir);
    sl_design_free(dc);
    sl_design_free(df);
}

static void test_plant_lookup_libreoffice(void)
{
    if (system("command -v soffice >/dev/null 2>&1") != 0)
        SKIP("soffice (LibreOffice) not found: the plant Lookup is not recalculated; install "
             "libreoffice-calc-nogui");
    char dir[] = "/tmp/sl-plantbook-XXXXXX", cmd[8192], sub[256], prof[300], xcu[400];
    CHECK(mkdtemp(dir) != NULL, "temporary folder");
    /* Aux: ground, el12; RB: ground, Niveau_-3 (the same floor id in two buildings) */
    sl_design *d[4] = {make_design(0.8, 0.3), make_design(0.5, 0.39), make_design(1.0, 0.3),
                       make_design(0.6, 0.63)};
    CHECK(d[0] && d[1] && d[2] && d[3], "designs");
    if (!d[0] || !d[1] || !d[2] || !d[3])
        return;
    const sl_plant_book_row rows[4] = {
        {"Aux", "ground", "Aux ground", 0, 0.3 * SL_G, 2, "fixed", d[0], "p/Aux/ground.ini",
         0x1a2b3c4dUL, 1001, 0, NULL, NULL},
        {"Aux", "el12", "Aux el. 12 m", 12, 0.39 * SL_G, 2, "fixed", d[1], "p/Aux/el12.ini",
         0xdeadbeefUL, 1002, 0, NULL, NULL},
        {RB, "ground", "Rez-de-chaussée", 0, 0.3 * SL_G, 2, "fixed", d[2],
         "p/" RB "/ground.ini", 0x0000beefUL, 1003, 0, NULL, NULL},
        {RB, "Niveau_-3", "Niveau −3 m", -3, 0.63 * SL_G, 2, "fixed", d[3], NULL, 0, 0, 0, NULL,
         NULL}};
    /* plant.csv: the building CSVs' trace lines, # program: first, a CRC
     * line per floor named building/id (a floor without a path: "-") */
    {
        sl_plant_book b = {.version = "seislide test", .command_line = "seislide run p -o o",
                           .seed = "7", .created = 86400, .n = 4, .rows = rows};
        sl_error e;
        CHECK(sl_plant_book_write_csv(&b, dir, &e) == SL_OK, "plant.csv: %s", e.msg);
        static const char *const want[] = {
            "# program: seislide test\r\n", "# content: ", "# command: seislide run p -o o\r\n",
            "# created: 1970-01-02T00:00:00Z\r\n", "# seed: 7\r\n",
            "# floor_file_crc32: 1a2b3c4d Aux/ground (p/Aux/ground.ini, 1001 bytes)\r\n",
            "# floor_file_crc32: deadbeef Aux/el12 (p/Aux/el12.ini, 1002 bytes)\r\n",
            "# floor_file_crc32: 0000beef " RB "/ground (p/" RB "/ground.ini, 1003 bytes)\r\n",
            "# floor_file_crc32: 00000000 " RB "/Niveau_-3 (-, 0 bytes)\r\n", "# project: -\r\n",
            "# document: -\r\n", "# revision: -\r\n", "# units: ", "# asce_design_mm_mu_X: ",
            "# warnings: ",
            "building,floor,"};
        char path[300], line[2000];
        snprintf(path, sizeof path, "%s/plant.csv", dir);
        FILE *pf = fopen(path, "rb");
        CHECK(pf != NULL, "%s", path);
        for (size_t k = 0; pf && k < sizeof want / sizeof want[0]; k++) {
            int got = fgets(line, sizeof line, pf) != NULL;
            CHECK(got && !strncmp(line, want[k], strlen(want[k])), "plant.csv line %zu: '%s', "
                  "expected '%s'", k + 1, got ? line : "(end)", want[k]);
        }
        if (pf)
            fclose(pf);
        remove(path);
    }
    snprintf(prof, sizeof prof, "%s/profile/user", dir);
    snprintf(cmd, sizeof cmd, "mkdir -p '%s'", prof);
    CHECK(system(cmd) == 0, "profile folder");
    snprintf(xcu, sizeof xcu, "%s/registrymodifications.xcu", prof);
    FILE *x = fopen(xcu, "w"); /* recalculate every formula on load */
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
    int n = snprintf(cmd, sizeof cmd, "cd '%s' && timeout 300 soffice -env:UserInstallation="
                     "file://%s/profile --headless --convert-to 'csv:Text - txt - csv (StarCalc)"
                     ":44,34,76,1,,0,false,true,false,false' --outdir csv", dir, dir);
    for (size_t c = 0; c < N_CASES; c++) {
        sl_plant_book b = {.version = "seislide test", .created = 1, .n = 4, .rows = rows,
                           .lookup_building = cases[c].building, .lookup_floor = cases[c].floor,
                           .lookup_mu = cases[c].mu, .lookup_zero_cache = 1};
        sl_error e;
        snprintf(sub, sizeof sub, "%s/c%02zu", dir, c);
        char mk[300];
        snprintf(mk, sizeof mk, "mkdir -p '%s'", sub);
        CHECK(system(mk) == 0, "case folder");
        CHECK(sl_plant_book_write_xlsx(&b, sub, &e) == SL_OK, "case %zu: %s", c, e.msg);
        char mv[700];
        snprintf(mv, sizeof mv, "mv '%s/plant.xlsx' '%s/case%02zu.xlsx'", sub, dir, c);
        CHECK(system(mv) == 0, "rename");
        n += snprintf(cmd + n, sizeof cmd - (size_t)n, " case%02zu.xlsx", c);
    }
    snprintf(cmd + n, sizeof cmd - (size_t)n, " >/dev/null 2>&1");
    CHECK(system(cmd) == 0, "soffice conversion: %s", cmd);
    size_t n_ok = 0;
    for (size_t c = 0; c < N_CASES; c++) {
        char csv[400], check[256] = "", result[256] = "";
        snprintf(csv, sizeof csv, "%s/csv/case%02zu.csv", dir, c);
        /* Lookup!B15: the input check; B14: the clearance */
        CHECK(csv_cell(csv, 14, 1, check, sizeof check) == 0, "case %zu: no B15 in %s", c, csv);
        CHECK(csv_cell(csv, 13, 1, result, sizeof result) == 0, "case %zu: no B14", c);
        CHECK(!strcmp(check, cases[c].check), "case %zu (%s, %s, %g): check '%s', expected '%s'",
              c, cases[c].building, cases[c].floor, cases[c].mu, check, cases[c].check);
        if (strcmp(cases[c].check, "ok") != 0) {
            CHECK(!strcmp(result, "-"), "case %zu: result '%s', expected '-'", c, result);
            continue;
        }
        const sl_design *dd = NULL;
        for (int i = 0; i < 4; i++)
            if (!strcasecmp(rows[i].building, cases[c].building) &&
                !strcasecmp(rows[i].name, cases[c].floor)) /* MATCH ignores ASCII case */
                dd = rows[i].design;
        double want = 1000.0 * sl_design_clearance_at(dd, cases[c].mu);
        char *end;
        double got = strtod(result, &end);
        CHECK(end != result, "case %zu: result '%s' is not a number", c, result);
        CHECK_CLOSE(got, want, 1e-9, 1e-9);
        n_ok++;
    }
    CHECK(n_ok == 20, "%zu ok cases", n_ok);
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    CHECK(system(cmd) == 0, "clean up");
    for (int i = 0; i < 4; i++)
        sl_design_free(d[i]);
}

int main(void)
{
    RUN(test_entry_roundtrip_and_damage);
    RUN(test_shard_lpt);
    RUN(test_plant_lookup_libreoffice);
    RUN(test_plant_csv_computed_points);
    return HARNESS_END("plant");
}
