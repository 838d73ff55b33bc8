/*
 * test_slide_records.c - convergence of the 2-D integrator on real
 * three-component records from ../shared/records (skipped when absent).
 *
 * For each record and mu the reference is the same integrator at 1024
 * sub-steps per sample, itself checked against 2048 (the difference is
 * must be below 1e-6 relative). The error of the peak vector
 * displacement must fall with the sub-steps, at an observed order near 2,
 * and be below 1e-3 (0.1 %) at 8 sub-steps: the default.
 * Set SEISLIDE_TEST_VERBOSE=1 to print the table that docs/integrators.md
 * quotes.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "harness.h"
#include "slide.h"

typedef struct rec3 {
    const char *dir, *h1, *h2, *v;
} rec3;

static const rec3 records[] = {
    {"RSN1063_NORTHR_RRS", "Rinaldi228.AT2", "Rinaldi318.AT2", "RinaldiUP.AT2"},
    {"RSN6_IMPVALL.I_I-ELC", "RSN6_IMPVALL.I_I-ELC180.AT2", "RSN6_IMPVALL.I_I-ELC270-hor2.AT2",
     "RSN6_IMPVALL.I_I-ELC-UP.AT2"},
    {"RSN77_SFERN_PUL", NULL, NULL, NULL}, /* names found at run time */
};

/* Find the three AT2 files of a directory: vertical by name. */
static int find3(const char *dir, char *h1, char *h2, char *v, size_t n)
{
    char cmd[1024];
    snprintf(cmd, sizeof cmd, "ls '%s' 2>/dev/null", dir);
    FILE *p = popen(cmd, "r");
    if (!p)
        return -1;
    char line[512];
    int nh = 0, nv = 0;
    while (fgets(line, sizeof line, p)) {
        line[strcspn(line, "\r\n")] = 0;
        if (!strstr(line, ".AT2"))
            continue;
        if (strstr(line, "UP") || strstr(line, "-V") || strstr(line, "DWN")) {
            snprintf(v, n, "%s/%s", dir, line);
            nv++;
        } else if (nh == 0) {
            snprintf(h1, n, "%s/%s", dir, line);
            nh++;
        } else if (nh == 1) {
            snprintf(h2, n, "%s/%s", dir, line);
            nh++;
        }
    }
    pclose(p);
    return (nh == 2 && nv == 1) ? 0 : -1;
}

static void test_2d_convergence_records(void)
{
    const char *shared = harness_shared_dir();
    if (!shared)
        SKIP("../shared not found (set SEISLIDE_SHARED): real-record convergence not checked");
    const double mu[] = {0.05, 0.1, 0.2, 0.3};
    const size_t nm = sizeof mu / sizeof mu[0];
    const unsigned subs[] = {1, 2, 4, 8, 16, 32, 64};
    const size_t ns = sizeof subs / sizeof subs[0];
    int verbose = getenv("SEISLIDE_TEST_VERBOSE") != NULL;
    int tested = 0;
    double worst_at8 = 0, order_sum = 0;
    int order_n = 0;
    for (size_t r = 0; r < sizeof records / sizeof records[0]; r++) {
        char dir[600], p1[1200], p2[1200], pv[1200];
        snprintf(dir, sizeof dir, "%s/records/%s", shared, records[r].dir);
        if (records[r].h1) {
            snprintf(p1, sizeof p1, "%s/%s", dir, records[r].h1);
            snprintf(p2, sizeof p2, "%s/%s", dir, records[r].h2);
            snprintf(pv, sizeof pv, "%s/%s", dir, records[r].v);
        } else if (find3(dir, p1, p2, pv, sizeof p1) != 0) {
            CHECK(0, "cannot find three components in %s", dir);
            continue;
        }
        sl_read_opts ro = {SL_FORMAT_AUTO, SL_UNIT_NONE, 0};
        sl_error e;
        sl_motion *m1 = sl_motion_read(p1, &ro, &e), *m2 = sl_motion_read(p2, &ro, &e),
                  *mv = sl_motion_read(pv, &ro, &e);
        CHECK(m1 && m2 && mv, "read %s: %s", records[r].dir, e.msg);
        sl_set set = {m1, m2, mv};
        if (m1 && m2 && mv && sl_set_check(&set, 1, &e) == SL_OK) {
            tested++;
            sl_slide_opts o;
            sl_slide_opts_default(&o);
            sl_slide_result ref[4], ref2[4], res[4];
            o.substeps = 1024;
            sl_slide_run(&set, mu, nm, &o, ref, NULL);
            o.substeps = 2048;
            sl_slide_run(&set, mu, nm, &o, ref2, NULL);
            for (size_t k = 0; k < nm; k++)
                CHECK_CLOSE(ref[k].peak_m, ref2[k].peak_m, 1e-9, 1e-6);
            double prev[4] = {0};
            for (size_t q = 0; q < ns; q++) {
                o.substeps = subs[q];
                sl_slide_run(&set, mu, nm, &o, res, NULL);
                double worst = 0;
                for (size_t k = 0; k < nm; k++) {
                    double err = fabs(res[k].peak_m / ref[k].peak_m - 1);
                    worst = fmax(worst, err);
                    if (q > 0 && prev[k] > 1e-9 && err > 1e-9) {
                        order_sum += log2(prev[k] / err);
                        order_n++;
                    }
                    prev[k] = err;
                }
                if (subs[q] == 8)
                    worst_at8 = fmax(worst_at8, worst);
                if (verbose)
                    fprintf(stderr, "  %-22s substeps %3u  worst rel. error of peak %.2e\n",
                            records[r].dir, subs[q], worst);
            }
        }
        sl_motion_free(m1);
        sl_motion_free(m2);
        sl_motion_free(mv);
    }
    CHECK(tested == 3, "tested %d of 3 records", tested);
    double order = order_n ? order_sum / order_n : 0;
    if (verbose)
        fprintf(stderr, "  mean observed order %.2f, worst error at 8 substeps %.2e\n", order,
                worst_at8);
    CHECK(order > 1.5, "mean observed order %.2f (expected about 2)", order);
    CHECK(worst_at8 < 1e-3, "worst error at the default 8 substeps %.3g", worst_at8);
}

int main(void)
{
    RUN(test_2d_convergence_records);
    return HARNESS_END("slide_records");
}
