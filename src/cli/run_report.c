/* run_report.c - the messages of `seislide run` (run_report.h). */
#include "run_report.h"

#include <stddef.h>
#include <stdio.h>
#include <string.h>

#include "cli.h"
#include "report/report.h"

void run_progress_cb(void *ctx, const char *step, size_t done, size_t total)
{
    run_progress *p = ctx;
    int pct = total ? (int)(100.0 * (double)done / (double)total) : 0;
    if (p->quiet || total == 0 || (p->step == step && pct < p->pct + 25 && done != total))
        return;
    p->step = step;
    p->pct = pct;
    cli_msg("run: floor %zu/%zu '%s': %s %zu/%zu (%d %%)", p->floor, p->n, p->name, step, done,
            total, pct);
}

static const char *const comp_name[SL_SYNTH_NCOMP] = {"H1", "H2", "V"};

/* The friction values that need no NLTHA, as a reader can use it. */
static void skipped_text(const sl_analysis *q, size_t n_mu, char *buf, size_t n)
{
    const char *how = q->scatter > 0 ? ", even at the highest intensity of the scatter" : "";
    if (q->n_mu_skipped == 0)
        snprintf(buf, n, "every one of the %zu friction values slides (each from NLTHA)", n_mu);
    else if (q->n_mu_skipped == n_mu)
        snprintf(buf, n, "no friction value slides%s: every displacement is 0", how);
    else
        snprintf(buf, n, "%zu of %zu friction values (the largest) never slide%s: their "
                 "displacement is 0; the other %zu are from NLTHA", q->n_mu_skipped, n_mu, how,
                 n_mu - q->n_mu_skipped);
}

/* The other dampings of the file against the motions' own spectra, and what
 * a value outside the limits means for the result. */
static void report_dampings(const char *name, const sl_analysis *q)
{
    if (q->n_dampings == 0) {
        cli_msg("run: floor '%s': other dampings: none (the file gives one)", name);
        return;
    }
    char dt[1536];
    size_t used = 0, n_out = 0;
    dt[0] = '\0';
    for (size_t k = 0; k < q->n_dampings && used < sizeof dt; k++) {
        const sl_analysis_damping *d = &q->dampings[k];
        n_out += !d->ok;
        int w = snprintf(dt + used, sizeof dt - used, "%s%s %g %%: %.2f-%.2f %s", k ? "; " : "",
                         comp_name[d->comp], 100 * d->damping, d->set_min, d->set_max,
                         d->ok ? "ok" : "OUTSIDE");
        used += w > 0 ? (size_t)w : 0;
    }
    double z = q->n_sets ? q->sets[0].check[0].damping : 0;
    cli_msg("run: floor '%s': the motions, matched at %g %% damping, against the file's other "
            "tables (set mean of S/T over %zu sets, lowest-highest; ok within %g-%g): %s", name,
            100 * z, q->n_sets, q->damping_lim_lo, q->damping_lim_hi, dt);
    if (n_out)
        cli_msg("run: floor '%s': OUTSIDE: at that damping the motions' spectrum is not within "
                "%g-%g x the file's table; reported only: the motions are matched and checked "
                "at %g %% and the result rests on that match (NLTHA); the ASCE estimate reads "
                "the file's own 10 %% tables", name, q->damping_lim_lo, q->damping_lim_hi,
                100 * z);
}

void run_report_floor(size_t i, size_t n, const char *name, const sl_analysis *q, size_t n_mu)
{
    char r[512], sk[256];
    skipped_text(q, n_mu, sk, sizeof sk);
    cli_msg("run: floor %zu/%zu '%s': ZPA %.3f g; %s; ASCE below NLTHA for mu in %s%s%s", i, n,
            name, q->zpa_h_ms2 / SL_G, sk, sl_report_ranges_text(q->design, r, sizeof r),
            q->note[0] ? "; note: " : "", q->note);
    char sc[64]; /* the intensity scatter used (the floor's own by default) */
    snprintf(sc, sizeof sc, "; intensity scatter %.3f", q->scatter);
    if (q->stop == SL_ANALYSIS_STOP_FIXED)
        cli_msg("run: floor '%s': %zu motion sets (fixed by --sets)%s", name, q->n_sets, sc);
    else
        cli_msg("run: floor '%s': %zu motion sets in %zu batches: %s (worst standard error "
                "%.1f %% of the design value)%s", name, q->n_sets, q->n_batches,
                q->stop == SL_ANALYSIS_STOP_CONVERGED ? "converged"
                                                      : "NOT converged, --max-sets reached",
                100 * q->worst_rel_se, sc);
    report_dampings(name, q);
    /* thread time (analysis.h): a floor's synthesis and NLTHA overlap */
    cli_msg("run: floor '%s': thread time: synthesis %.2f s (of which the other dampings' "
            "checks %.2f s), NLTHA %.2f s, statistics %.3f s, ASCE and design %.3f s (%.3f s "
            "per set); %.2f extra synthesis attempts per set", name, q->time_synth_s,
            q->time_checks_s, q->time_nltha_s, q->time_stats_s, q->time_asce_s,
            (q->time_synth_s + q->time_nltha_s + q->time_stats_s + q->time_asce_s) /
                (double)q->n_sets,
            q->n_sets ? (double)q->n_extra_attempts / (double)q->n_sets : 0.0);
}

/* ---- The SRP 3.7.1 checks of a floor's motions -------------------------- */

/* One check: its name (as in motion_quality.csv's failed_checks), what it
 * asks (a printf format over the defaults of sl_synth_params) and its flag. */
typedef struct run_check {
    const char *name, *what;
    size_t ok;    /* offsetof the ok_ flag in sl_synth_check */
} run_check;
#define OK(f) offsetof(sl_synth_check, f)
static const run_check checks[] = {
    {"below", "no point of the spectrum more than %g %% below the target", OK(ok_below)},
    {"above", "no point more than %g %% above the target", OK(ok_above)},
    {"run_below", "at most %g consecutive points below the target", OK(ok_run)},
    {"d5_75", "strong-motion duration D5-75 at least %g s", OK(ok_d5_75)},
    {"duration", "duration at least %g s", OK(ok_duration)},
    {"end_v_d", "velocity and displacement back to about 0 at the end", OK(ok_end)},
    {"pga", "PGA close to the target's ZPA", OK(ok_pga)},
    {"peaks", "at most %g peaks above 0.9 PGA", OK(ok_peaks)},
    {"psd", "SRP 3.7.1 App. B minimum power spectral density", OK(ok_psd)},
    {"correlation", "|correlation| of two components at most %g", OK(ok_corr)},
};
#undef OK
#define N_CHECKS (sizeof checks / sizeof checks[0])

/* Component comp of set s was synthesized: its motion is held, or (a
 * result read back from a plant cache keeps the checks, not the motions)
 * its check has a PGA. */
static int present(const sl_synth_set *s, int comp)
{
    return sl_synth_set_motion(s, (sl_synth_comp)comp) != NULL || s->check[comp].pga_ms2 > 0;
}

/* Motion comp of set s failed check c. Only a failed motion counts (a cached
 * result keeps every flag of the check: plant/entry.c). */
static int failed(const sl_synth_set *s, int comp, const run_check *c)
{
    const sl_synth_check *k = &s->check[comp];
    if (!present(s, comp) || k->pass)
        return 0;
    return !*(const int *)(const void *)((const char *)k + c->ok);
}

/* The limit of check c from the synthesis defaults (the run uses them). */
static double limit(const run_check *c, const sl_synth_params *p)
{
    if (!strcmp(c->name, "below"))
        return 100 * p->tol_below;
    if (!strcmp(c->name, "above"))
        return 100 * p->tol_above;
    if (!strcmp(c->name, "run_below"))
        return (double)p->max_run_below;
    if (!strcmp(c->name, "d5_75"))
        return p->min_d5_75_s;
    if (!strcmp(c->name, "duration"))
        return p->min_duration_s;
    if (!strcmp(c->name, "peaks"))
        return (double)p->max_peaks;
    return p->max_corr;
}

/* The sets of component comp that failed check c, as "1-10,12" into buf
 * (at most n bytes; "..." and the count when it does not fit). Returns how
 * many. */
static size_t failed_sets(const sl_analysis *q, int comp, const run_check *c, char *buf,
                          size_t n)
{
    size_t count = 0, used = 0, s = 0;
    int cut = 0;
    buf[0] = '\0';
    while (s < q->n_sets) {
        if (!failed(&q->sets[s], comp, c)) {
            s++;
            continue;
        }
        size_t e = s;
        while (e + 1 < q->n_sets && failed(&q->sets[e + 1], comp, c))
            e++;
        count += e - s + 1;
        char one[48];
        if (e == s)
            snprintf(one, sizeof one, "%s%zu", used ? "," : "", s + 1);
        else
            snprintf(one, sizeof one, "%s%zu-%zu", used ? "," : "", s + 1, e + 1);
        if (!cut && used + strlen(one) + 8 < n) {
            memcpy(buf + used, one, strlen(one) + 1);
            used += strlen(one);
        } else if (!cut) {
            cut = 1;
            snprintf(buf + used, n - used, ",...");
        }
        s = e + 1;
    }
    return count;
}

/* Where the spectrum was hardest to match: the lowest and highest S/T of
 * any failed motion, with set, component and frequency. */
static void worst_ratio(const sl_analysis *q, char *buf, size_t n)
{
    const sl_synth_check *lo = NULL, *hi = NULL;
    size_t slo = 0, shi = 0;
    int clo = 0, chi = 0;
    for (size_t s = 0; s < q->n_sets; s++)
        for (int c = 0; c < SL_SYNTH_NCOMP; c++) {
            const sl_synth_check *k = &q->sets[s].check[c];
            if (!present(&q->sets[s], c) || k->pass)
                continue;
            if (!lo || k->min_ratio < lo->min_ratio)
                lo = k, slo = s, clo = c;
            if (!hi || k->max_ratio > hi->max_ratio)
                hi = k, shi = s, chi = c;
        }
    if (!lo) {
        buf[0] = '\0';
        return;
    }
    /* a result read back from a plant cache keeps the ratios, not where */
    char flo[48] = "", fhi[48] = "", z[48] = "";
    if (lo->f_min_ratio_hz > 0)
        snprintf(flo, sizeof flo, " at %.3g Hz", lo->f_min_ratio_hz);
    if (hi->f_max_ratio_hz > 0)
        snprintf(fhi, sizeof fhi, " at %.3g Hz", hi->f_max_ratio_hz);
    if (lo->damping > 0)
        snprintf(z, sizeof z, " at %g %% damping", 100 * lo->damping);
    snprintf(buf, n, "lowest S/T %.3g%s (set %zu %s), highest %.3g%s (set %zu %s), S the "
             "motion's spectrum and T the target%s", lo->min_ratio, flo, slo + 1, comp_name[clo],
             hi->max_ratio, fhi, shi + 1, comp_name[chi], z);
}

int run_report_checks(size_t i, size_t n, const sl_floor *fl, const sl_analysis *q, int accept)
{
    const char *path = fl->path ? fl->path : fl->name;
    if (q->sa10_fallback)
        cli_msg("run: warning: %s: no 10 %%-damped table for H1 and H2: the ASCE estimate of "
                "floor '%s' uses the mean 10 %% spectrum of its %zu synthesized sets instead "
                "(docs/run.md)", path, fl->name, q->n_sets);
    if (q->n_failed_motions == 0)
        return CLI_EXIT_OK;
    size_t total = 0;
    for (size_t s = 0; s < q->n_sets; s++)
        for (int c = 0; c < SL_SYNTH_NCOMP; c++)
            total += present(&q->sets[s], c) != 0;
    cli_msg("run: %s%s (floor %zu/%zu '%s'): %zu of %zu motions (%zu sets) failed their SRP 3.7.1 "
            "checks:", accept ? "warning (--accept-failed-checks): " : "", path, i, n, fl->name,
            q->n_failed_motions, total, q->n_sets);
    sl_synth_params p;
    sl_synth_params_default(&p);
    for (size_t k = 0; k < N_CHECKS; k++) {
        char where[512] = "", sets[160], what[160];
        size_t count = 0, used = 0;
        for (int c = 0; c < SL_SYNTH_NCOMP; c++) {
            size_t m = failed_sets(q, c, &checks[k], sets, sizeof sets);
            if (!m || used >= sizeof where)
                continue;
            count += m;
            int w = snprintf(where + used, sizeof where - used, "%s%s set%s %s", used ? "; " : "",
                             comp_name[c], m > 1 ? "s" : "", sets);
            used += w > 0 ? (size_t)w : 0;
        }
        if (!count)
            continue;
        snprintf(what, sizeof what, checks[k].what, limit(&checks[k], &p));
        cli_msg("run:   %s (%s): %zu motion%s: %s", checks[k].name, what, count,
                count > 1 ? "s" : "", where);
    }
    char wr[320];
    worst_ratio(q, wr, sizeof wr);
    if (wr[0])
        cli_msg("run:   %s", wr);
    if (accept) {
        cli_msg("run: warning: floor '%s' is written with these failures (Motion quality, "
                "motion_quality.csv)", fl->name);
        return CLI_EXIT_OK;
    }
    cli_msg("run: no output written (the output folder's outputs are unchanged). A target the "
            "synthesis cannot match (a spike, a ZPA far from the spectrum's high-frequency end) "
            "is the usual cause: check %s; --accept-failed-checks writes the outputs anyway",
            path);
    return CLI_EXIT_ERROR;
}
