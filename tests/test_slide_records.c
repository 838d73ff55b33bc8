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
#include "slide/slide.h"
#include "io/setdir.h"

/* Three-component records with sliding in every friction range tested. */
static const char *const records[] = {"RSN1063_NORTHR_RRS", "RSN6_IMPVALL.I_I-ELC",
                                      "RSN77_SFERN_PUL"};

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
        char dir[600];
        snprintf(dir, sizeof dir, "%s/records/%s", shared, records[r]);
        sl_set set;
        sl_error e;
        sl_error_clear(&e);
        sl_status rs = sl_set_read_dir(dir, &set, &e);
        CHECK(rs == SL_OK, "read %s: %s", records[r], e.msg);
        if (rs == SL_OK) {
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
                            records[r], subs[q], worst);
            }
        }
        sl_set_free_motions(&set);
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
