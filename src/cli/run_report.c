/* run_report.c - the messages of `seislide run` (run_report.h). */
#include "run_report.h"

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

void run_report_floor(size_t i, size_t n, const char *name, const sl_analysis *q, size_t n_mu)
{
    char r[512];
    cli_msg("run: floor %zu/%zu '%s': ZPA %.3f g; %zu of %zu friction values %s; ASCE below "
            "NLTHA for mu in %s%s%s", i, n, name, q->zpa_h_ms2 / SL_G, q->n_mu_skipped, n_mu,
            q->scatter > 0 ? "slide at no intensity of the scatter" : "need no NLTHA",
            sl_report_ranges_text(q->design, r, sizeof r), q->note[0] ? "; note: " : "", q->note);
    if (q->stop == SL_ANALYSIS_STOP_FIXED)
        cli_msg("run: floor '%s': %zu motion sets (fixed by --sets)", name, q->n_sets);
    else
        cli_msg("run: floor '%s': %zu motion sets in %zu batches: %s (worst standard error "
                "%.1f %% of the design value)", name, q->n_sets, q->n_batches,
                q->stop == SL_ANALYSIS_STOP_CONVERGED ? "converged"
                                                      : "NOT converged, --max-sets reached",
                100 * q->worst_rel_se);
    char dt[1024];
    if (q->n_dampings == 0)
        cli_msg("run: floor '%s': other dampings: none (the file gives one)", name);
    else
        cli_msg("run: floor '%s': other dampings against the motions' own spectra (set mean S/T "
                "of %zu sets, limits %g-%g; reported, not a pass condition): %s", name,
                q->n_sets, q->damping_lim_lo, q->damping_lim_hi,
                sl_analysis_dampings_text(q, dt, sizeof dt));
    cli_msg("run: floor '%s': wall time: synthesis %.2f s, NLTHA %.2f s, statistics "
            "%.3f s, ASCE and design %.3f s (%.3f s per set)", name, q->time_synth_s,
            q->time_nltha_s, q->time_stats_s, q->time_asce_s,
            (q->time_synth_s + q->time_nltha_s + q->time_stats_s + q->time_asce_s) /
                (double)q->n_sets);
}
