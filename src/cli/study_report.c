/* study_report.c - the sections of docs/validation.md from the study's
 * data (study_out.h); every constant comes from study/study_parts.h and
 * the standards, none is retyped. */
#include <errno.h>
#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "method/asce.h"
#include "method/design.h"
#include "method/scatter.h"
#include "rock/rock_floor.h"
#include "study_out.h"

/* A table cell: v in fmt, or `none` where v is not a number. */
static const char *cell(char *buf, size_t n, const char *fmt, double v, const char *none)
{
    if (isnan(v))
        snprintf(buf, n, "%s", none);
    else
        snprintf(buf, n, fmt, v);
    return buf;
}

/* The crossover mu g/PGA of a design comparison, or "none". */
static const char *crossover_cell(const sl_design *d, char *buf, size_t n)
{
    return cell(buf, n, "%.3f", d->has_crossover ? d->crossover_x : NAN, "none");
}

/* ---- Part 1 ---------------------------------------------------------- */

int study_report_part1(study_out *o, const sl_study_part1 *p)
{
    FILE *md = o->md;
    fprintf(md,
            "## 1. Model validation: Rinaldi (Northridge 1994), mu = %.1f\n\n"
            "The study validated its smoothed (Park-Wen) model against an elastic-plastic\n"
            "(Newmark) model (its Figures 3-4 and 3-5). seislide's engine integrates the\n"
            "Coulomb law itself (exact in 1-D, second order in 2-D); here both reference\n"
            "models run with the study's parameters (eta = %g, U_y = %g m; the plastic\n"
            "model with the same U_y) on the unscaled record, component %s alone and then\n"
            "with %s. No vertical component (as in the study's validation).\n\n",
            SL_STUDY_P1_MU, SL_STUDY_SMOOTH_ETA, SL_STUDY_SMOOTH_UY_M, "228", "318");
    fprintf(md, "| excitation | model | peak \\|u\\| (mm) | peak u_x (mm) | peak u_y (mm) | "
                "residual \\|u\\| (mm) | peak vs engine | run time (ms) |\n"
                "|---|---|---|---|---|---|---|---|\n");
    for (int two = 0; two < 2; two++)
        for (int m = 0; m < SL_STUDY_P1_NMODELS; m++) {
            const sl_study_p1_run *x = &p->run[two][m];
            const char *name = sl_study_p1_model_names[m];
            char dev[32];
            snprintf(dev, sizeof dev, m ? "%+.2f %%" : "reference",
                     sl_study_pct(x->r.peak_m, p->run[two][0].r.peak_m));
            fprintf(md, "| %s | %s | %.2f | %.2f | %.2f | %.2f | %s | %.1f |\n",
                    two ? "228 + 318" : "228", name, 1e3 * x->r.peak_m, 1e3 * x->r.peak_x_m,
                    1e3 * x->r.peak_y_m, 1e3 * x->r.residual_m, dev, x->run_ms);
            char file[64], title[128];
            snprintf(file, sizeof file, "p1_%s_%s.tsv", two ? "2d" : "1d",
                     sl_study_p1_model_tags[m]);
            snprintf(title, sizeof title, "Rinaldi %s, mu = %.1f, %s", two ? "228 + 318" : "228",
                     SL_STUDY_P1_MU, name);
            const char *hdr[] = {"t_s", "ux_m", "uy_m", "fx_over_w", "fy_over_w"};
            if (study_write_history(o, file, title, hdr, x->h))
                return -1;
        }
    fprintf(md, "\nRun times are one run on this machine, single-threaded; docs/performance.md gives speed against error.\n\n");
    char uy[16];
    study_sci(SL_STUDY_SMOOTH_UY_M, uy, sizeof uy);
    const char *three =
        "plot [0:12] 'p1_%s_engine.tsv' u 1:($%d*1e3) w l lw 3 lc rgb '#1f77b4' t 'engine%s', \\\n"
        "  'p1_%s_smooth.tsv' u 1:($%d*1e3) w l lw 2 dt 2 lc rgb '#d62728' t 'smoothed%s', \\\n"
        "  'p1_%s_plastic.tsv' u 1:($%d*1e3) w l lw 2 dt 3 lc rgb '#2ca02c' t 'elastic-plastic'\n";
    char l1[600], l2x[600], l2y[600], smooth[64];
    snprintf(smooth, sizeof smooth, " (eta %g, U_y %s m)", SL_STUDY_SMOOTH_ETA, uy);
    snprintf(l1, sizeof l1, three, "1d", 2, " (Coulomb)", "1d", 2, smooth, "1d", 2);
    snprintf(l2x, sizeof l2x, three, "2d", 2, "", "2d", 2, "", "2d", 2);
    snprintf(l2y, sizeof l2y, three, "2d", 3, "", "2d", 3, "", "2d", 3);
    int rc = study_plot(o, "fig1_rinaldi_228",
                        "set title 'Rinaldi 228 alone, mu = %.1f (study Fig. 3-4)'\n"
                        "set xlabel 'time (s)'\nset ylabel 'sliding displacement u (mm)'\n%s",
                        SL_STUDY_P1_MU, l1);
    if (!rc)
        rc = study_plot(o, "fig2_rinaldi_228_318",
                        "set multiplot layout 2,1 title 'Rinaldi 228 + 318, mu = %.1f (study "
                        "Fig. 3-5)'\nset xlabel 'time (s)'\nset ylabel 'u_x (mm)'\n%s"
                        "set ylabel 'u_y (mm)'\n%sunset multiplot\n",
                        SL_STUDY_P1_MU, l2x, l2y);
    fprintf(md,
            "![Rinaldi 228](" STUDY_FIGDIR "/fig1_rinaldi_228.svg)\n\n"
            "![Rinaldi 228 + 318](" STUDY_FIGDIR "/fig2_rinaldi_228_318.svg)\n\n"
            "Largest deviation of a reference model's peak from the engine: %.2f %% (228\n"
            "alone), %.2f %% (228 + 318). The three models solve the same Coulomb problem;\n"
            "what is left is each reference model's own error: the smoothed model's\n"
            "pre-sliding elastic range (U_y) and solver tolerance, the elastic-plastic\n"
            "model's sub-step error at reversals (docs/refmodels.md).\n\n",
            100 * p->dev[0], 100 * p->dev[1]);
    return rc;
}

/* ---- Part 2 ---------------------------------------------------------- */

int study_report_part2(study_out *o, const sl_study_part2 *p)
{
    FILE *md = o->md;
    fprintf(md,
            "## 2. El Centro #9 (1940): the effect of the second horizontal and the vertical\n\n"
            "The three components (x = 180, y = 270, z = up) modified to match RG 1.60 at\n"
            "%.0f %% damping (phases kept, US NRC SRP 3.7.1 checks: %s), PGA\n"
            "%.1f g (vertical ZPA %.1f g), mu = %.1f (the study's Figures 3-7 to 3-9).\n\n",
            100 * SL_STUDY_ZETA, p->matched.pass ? "all passed" : "SOME FAILED, see motion checks",
            SL_STUDY_P2_PGA_G, sl_motion_pga(p->matched.set.v) / SL_G, SL_STUDY_P2_MU);
    fprintf(md, "| excitation | peak u_x (mm) | peak u_y (mm) | peak \\|u\\| (mm) | residual \\|u\\| (mm) | "
                "sliding time (s) |\n|---|---|---|---|---|---|\n");
    for (int i = 0; i < SL_STUDY_P2_NCASES; i++) {
        const sl_study_p2_case *c = &p->c[i];
        char cx[32], cy[32];
        fprintf(md, "| %s | %s | %s | %.1f | %.1f | %.2f |\n", c->name,
                cell(cx, sizeof cx, "%.1f", 1e3 * c->ux_m, "-"),
                cell(cy, sizeof cy, "%.1f", 1e3 * c->uy_m, "-"), 1e3 * c->r.peak_m,
                1e3 * c->r.residual_m, c->r.slide_time_s);
        char file[64], title[160];
        snprintf(file, sizeof file, "p2_%s.tsv", c->tag);
        snprintf(title, sizeof title, "El Centro #9 matched to RG 1.60 at %.1f g, mu = %.1f, %s "
                 "(columns 2-5: first axis = %s)", SL_STUDY_P2_PGA_G, SL_STUDY_P2_MU, c->name,
                 c->y_first ? "y" : "x");
        const char *hdr[] = {"t_s", "u1_m", "u2_m", "f1_over_w", "f2_over_w"};
        if (study_write_history(o, file, title, hdr, c->h))
            return -1;
    }
    fprintf(md,
            "\n| change | seislide | study |\n|---|---|---|\n"
            "| u_x, x -> x+y | %+.0f %% | %+.0f %% |\n"
            "| u_y, y -> x+y | %+.0f %% | %+.0f %% |\n"
            "| u_x, x -> x+z | %+.1f %% | a few %% |\n"
            "| u_y, y -> y+z | %+.1f %% | a few %% |\n"
            "| u_x, x+y -> x+y+z | %+.1f %% | a few %% |\n"
            "| u_y, x+y -> x+y+z | %+.1f %% | a few %% |\n\n",
            p->dux, SL_STUDY_CLAIM_DUX_PCT, p->duy, SL_STUDY_CLAIM_DUY_PCT, p->dvx, p->dvy,
            p->dvx3, p->dvy3);
    char what[96];
    snprintf(what, sizeof what, "El Centro #9, RG 1.60 at %.1f g, mu = %.1f", SL_STUDY_P2_PGA_G,
             SL_STUDY_P2_MU);
    int rc = study_plot(o, "fig3_elcentro_ux",
                        "set title '%s: u_x (study Fig. 3-7)'\n"
                        "set xlabel 'time (s)'\nset ylabel 'u_x (mm)'\n"
                        "plot 'p2_x.tsv' u 1:($2*1e3) w l lw 2 t 'x', 'p2_xy.tsv' u 1:($2*1e3) w l lw 2 t 'x+y', \\\n"
                        "  'p2_xz.tsv' u 1:($2*1e3) w l lw 2 dt 2 t 'x+z', 'p2_xyz.tsv' u 1:($2*1e3) w l lw 2 dt 3 t 'x+y+z'\n",
                        what);
    if (!rc)
        rc = study_plot(o, "fig4_elcentro_uy",
                        "set title '%s: u_y (study Fig. 3-8)'\n"
                        "set xlabel 'time (s)'\nset ylabel 'u_y (mm)'\n"
                        "plot 'p2_y.tsv' u 1:($2*1e3) w l lw 2 t 'y', 'p2_xy.tsv' u 1:($3*1e3) w l lw 2 t 'x+y', \\\n"
                        "  'p2_yz.tsv' u 1:($2*1e3) w l lw 2 dt 2 t 'y+z', 'p2_xyz.tsv' u 1:($3*1e3) w l lw 2 dt 3 t 'x+y+z'\n",
                        what);
    if (!rc)
        rc = study_plot(o, "fig5_elcentro_loops",
                        "set multiplot layout 1,2 title 'Hysteresis loops, El Centro #9 at %.1f g, mu = %.1f (study Fig. 3-9)'\n"
                        "set xlabel 'u_x (mm)'\nset ylabel 'F_x / W'\n"
                        "plot 'p2_x.tsv' u ($2*1e3):4 w l lw 1 t 'x alone', 'p2_xy.tsv' u ($2*1e3):4 w l lw 1 t 'x+y'\n"
                        "set xlabel 'u_y (mm)'\nset ylabel 'F_y / W'\n"
                        "plot 'p2_y.tsv' u ($2*1e3):4 w l lw 1 t 'y alone', 'p2_xy.tsv' u ($3*1e3):5 w l lw 1 t 'x+y'\n"
                        "unset multiplot\n",
                        SL_STUDY_P2_PGA_G, SL_STUDY_P2_MU);
    fprintf(md,
            "![u_x histories](" STUDY_FIGDIR "/fig3_elcentro_ux.svg)\n\n"
            "![u_y histories](" STUDY_FIGDIR "/fig4_elcentro_uy.svg)\n\n"
            "![hysteresis loops](" STUDY_FIGDIR "/fig5_elcentro_loops.svg)\n\n"
            "F/W is the friction force over the weight (= absolute block acceleration / g).\n"
            "Under one horizontal a loop is a rectangle at +-mu; with both, the friction\n"
            "vector is shared between the axes (|F| = mu N while sliding), so each axis's\n"
            "loop stays inside +-mu and its corners round off. With the vertical (data\n"
            "p2_xyz.tsv) mu N follows g + a_v and the plateaus ripple.\n\n");
    return rc;
}

/* ---- Part 3 ---------------------------------------------------------- */

static void ranges_text(const sl_design *d, char *buf, size_t n)
{
    size_t used = 0;
    buf[0] = '\0';
    if (d->n_ranges == 0) {
        snprintf(buf, n, "none");
        return;
    }
    for (size_t i = 0; i < d->n_ranges && used < n; i++) {
        int w = snprintf(buf + used, n - used, "%s%.3f-%.3f", i ? ", " : "",
                         d->ranges[i].x_from, d->ranges[i].x_to);
        if (w < 0)
            break;
        used += (size_t)w;
    }
}

/* "pass", or the names of the checks some component failed. */
static void failed_checks(const sl_synth_set *m, char *buf, size_t n)
{
    static const struct {
        const char *name;
        size_t off;
    } checks[] = {
        {"below", offsetof(sl_synth_check, ok_below)}, {"above", offsetof(sl_synth_check, ok_above)},
        {"run", offsetof(sl_synth_check, ok_run)},     {"D5-75", offsetof(sl_synth_check, ok_d5_75)},
        {"duration", offsetof(sl_synth_check, ok_duration)},
        {"end", offsetof(sl_synth_check, ok_end)},     {"PGA", offsetof(sl_synth_check, ok_pga)},
        {"correlation", offsetof(sl_synth_check, ok_corr)},
    };
    size_t used = 0;
    buf[0] = '\0';
    for (size_t k = 0; k < sizeof checks / sizeof checks[0]; k++) {
        char comps[16] = "";
        for (int c = 0; c < SL_SYNTH_NCOMP; c++) {
            const int *ok = (const int *)((const char *)&m->check[c] + checks[k].off);
            if (sl_synth_set_motion(m, (sl_synth_comp)c) && !*ok) {
                strncat(comps, comps[0] ? "," : "", sizeof comps - strlen(comps) - 1);
                strncat(comps, sl_synth_comp_name((sl_synth_comp)c), sizeof comps - strlen(comps) - 1);
            }
        }
        if (comps[0] && used < n) {
            int w = snprintf(buf + used, n - used, "%s%s failed (%s)", used ? "; " : "",
                             checks[k].name, comps);
            used += w > 0 ? (size_t)w : 0;
        }
    }
    if (!buf[0])
        snprintf(buf, n, "pass");
}

/* The design-spectrum factors as the figures label them. */
static void factor_labels(char *nl, char *as, char *cap, size_t n)
{
    snprintf(nl, n, "NLTHA %.1f x mean", SL_NLTHA_FS);
    snprintf(as, n, "ASCE %.1f x best", SL_ASCE_FS);
    snprintf(cap, n, "%.1f x PGD cap", SL_CAP_FACTOR);
}

int study_report_part3(study_out *o, const sl_study_part3 *p)
{
    FILE *md = o->md;
    fprintf(md,
            "## 3. Design sliding spectra of the ground set matched to RG 1.60\n\n"
            "The study's seven three-component records, modified to match RG 1.60 at\n"
            "%.0f %% damping (0.1-50 Hz; seislide's record matching keeps each record's\n"
            "Fourier phases, docs/synthesis.md) at 1 g and scaled to 0.2, 0.4, 0.6 and\n"
            "0.8 g. Four of them are not in the collection in three components; each stand-in\n"
            "is named with its reason:\n\n"
            "| study record -> used | folder | why | matching checks (SRP 3.7.1) | PGD H1, H2 at 1 g (m) |\n"
            "|---|---|---|---|---|\n",
            100 * SL_STUDY_ZETA);
    for (size_t i = 0; i < SL_STUDY_NGROUND; i++) {
        const sl_study_entry *e = &sl_study_ground.e[i];
        char failed[256];
        failed_checks(&p->matched[i], failed, sizeof failed);
        fprintf(md, "| %s | %s | %s | %s (SA/target %.2f-%.2f) | %.2f, %.2f |\n", e->name, e->dir,
                e->why, failed, p->ratio_lo[i], p->ratio_hi[i], p->pgd_m[i][0], p->pgd_m[i][1]);
    }
    fprintf(md,
            "\nA failed check is kept and named: the study used these records as they are.\n"
            "The matched motions' mean PGD (H1) is %.2f m per g of PGA, against the 36 in =\n"
            "0.91 m per g of RG 1.60's control point D. Matching constrains the spectrum at\n"
            "0.1-50 Hz; below, a zero-phase Butterworth high-pass (order 4, corner 0.07 Hz,\n"
            "docs/synthesis.md 3.2) removes the records' own long-period content, which\n"
            "matching would otherwise scale up with them by up to 5x (mean PGD 4.9 m per g\n"
            "before the high-pass). RG 1.60 itself holds SD at 1.875 m per g down to 0.1 Hz,\n"
            "which a 20-40 s motion can only meet with a PGD above 0.91 m per g. At low\n"
            "mu g/PGA the block barely moves in space, so NLTHA approaches the PGD, while\n"
            "ASCE sees only the spectrum: the low-mu end of this comparison depends on it.\n",
            p->pgd_mean_m);
    fprintf(md, "\nNLTHA: both horizontals and the vertical, %u sub-steps; ASCE/SEI 43-05 on\n"
                "each set's own %.0f %%-damped spectra; both averaged over the seven sets;\n"
                "design = %.1f x NLTHA mean and %.1f x ASCE mean, capped at %.1f x the mean\n"
                "100-40 peak ground displacement. Grid mu g/PGA = %.2f to %.2f step %g\n"
                "(the study: 0.1 to 1, NLTHA every 0.1).\n\n"
                "| PGA (g) | crossover mu g/PGA (study 0.128-0.134) | all ranges with ASCE design < NLTHA design | "
                "%.1f x ASCE best < NLTHA design up to | NLTHA design at %g (mm) | ASCE design at %g (mm) | cap (mm) |\n"
                "|---|---|---|---|---|---|---|\n",
            SL_SLIDE_DEFAULT_SUBSTEPS, 100 * SL_ASCE_DAMPING, SL_NLTHA_FS, SL_ASCE_FS,
            SL_CAP_FACTOR, SL_STUDY_P3_X0,
            SL_STUDY_P3_X0 + SL_STUDY_P3_DX * (SL_STUDY_P3_NX - 1), SL_STUDY_P3_DX,
            SL_STUDY_CLAIM_FS, SL_STUDY_P3_X0 + SL_STUDY_P3_DX * SL_STUDY_P3_K01,
            SL_STUDY_P3_X0 + SL_STUDY_P3_DX * SL_STUDY_P3_K01);
    for (size_t l = 0; l < SL_STUDY_NLEVELS; l++) {
        const sl_design *d = p->level[l]->design;
        char rg[512], cross[32], fs3[32];
        ranges_text(d, rg, sizeof rg);
        const sl_design_row *r01 = &d->rows[SL_STUDY_P3_K01];
        fprintf(md, "| %.1f | %s | %s | %s | %.0f | %.0f | %.0f |\n", sl_study_levels_g[l],
                crossover_cell(d, cross, sizeof cross), rg,
                cell(fs3, sizeof fs3, "%.3f", p->fs3_x[l], "nowhere"), 1e3 * r01->nltha_design_m, 1e3 * r01->asce_design_m, 1e3 * d->cap_m);
        char file[64], title[128];
        snprintf(file, sizeof file, "p3_ground_%.1fg.tsv", sl_study_levels_g[l]);
        snprintf(title, sizeof title, "ground set matched to RG 1.60, PGA %.1f g",
                 sl_study_levels_g[l]);
        if (study_write_spectra(o, file, title, p->level[l]))
            return -1;
    }
    char levels[64] = "", nl[48], as[48], cap[48];
    for (size_t l = 0; l < SL_STUDY_NLEVELS; l++)
        snprintf(levels + strlen(levels), sizeof levels - strlen(levels), "%s%.1f", l ? " " : "",
                 sl_study_levels_g[l]);
    factor_labels(nl, as, cap, sizeof nl);
    int rc = study_plot(o, "fig6_ground_design",
                        "set multiplot layout 2,2 title 'Ground set matched to RG 1.60: design sliding spectra'\n"
                        "set logscale y\nset format y '%%g'\nset xlabel 'mu g / PGA'\nset ylabel 'design displacement (mm)'\n"
                        "set key top right font ',10'\n"
                        "do for [a in '%s'] {\n"
                        "  f = sprintf('p3_ground_%%sg.tsv', a)\n"
                        "  set title sprintf('PGA %%s g', a)\n"
                        "  plot [0:1] f u 2:($5*1e3) w l lw 2 t '%s', f u 2:($6*1e3) w l lw 2 t '%s', \\\n"
                        "    f u 2:($7*1e3) w l dt 2 lc rgb '#777777' t '%s'\n"
                        "}\nunset multiplot\n",
                        levels, nl, as, cap);
    fprintf(md,
            "\n![ground-set design spectra](" STUDY_FIGDIR "/fig6_ground_design.svg)\n\n"
            "\"%.1f x ASCE best < NLTHA design up to\" is the largest mu g/PGA where the\n"
            "study's recommended factor %.1f on the ASCE best estimate still falls below the\n"
            "NLTHA design value (both capped).\n\n",
            SL_STUDY_CLAIM_FS, SL_STUDY_CLAIM_FS);
    return rc;
}

/* ---- Part 4 ---------------------------------------------------------- */

int study_report_part4(study_out *o, const sl_study_part4 *p)
{
    FILE *md = o->md;
    fprintf(md,
            "## 4. Real three-component record sets\n\n"
            "The study used four standardized PEER sets of 40 records. The collection has no\n"
            "distance, site or pulse metadata, so the groups below are seislide's own, from\n"
            "published classifications (per record; distances Rrup and Vs30 as given by\n"
            "NGA-West2, rounded, to be checked against the flatfile): near-field soil\n"
            "(Rrup < 15 km, Vs30 < 360 m/s, no pulse), far-field soil (FEMA P695 far-field\n"
            "set, as the collection's MANIFEST.tsv notes), near-field rock (Rrup <= 15 km,\n"
            "Vs30 > 450 m/s) and pulse-like (Baker 2007). Unscaled records, mu = %.2f to\n"
            "%.2f step %.2f (the study: every 0.05); NLTHA with both horizontals and the\n"
            "vertical; ASCE on each record's %.0f %%-damped spectra; both averaged.\n\n"
            "| group | records (folder: why) |\n|---|---|\n",
            SL_MU_GRID_FROM, SL_MU_GRID_TO, SL_MU_GRID_STEP, 100 * SL_ASCE_DAMPING);
    for (size_t g = 0; g < SL_STUDY_NGROUPS; g++) {
        const sl_study_group *gr = &sl_study_groups[g];
        fprintf(md, "| %s |", gr->name);
        for (size_t i = 0; i < gr->n; i++)
            fprintf(md, "%s %s (`%s`: %s)", i ? ";" : "", gr->e[i].name, gr->e[i].dir,
                    gr->e[i].why);
        fprintf(md, " |\n");
    }
    fprintf(md, "\n| group | sets | mean PGA (g) | ASCE best < NLTHA mean at | "
                "ASCE design < NLTHA design for mu g/PGA in | crossover mu g/PGA |\n"
                "|---|---|---|---|---|---|\n");
    char tags[96] = "", title_expr[512] = "(";
    for (size_t g = 0; g < SL_STUDY_NGROUPS; g++) {
        const sl_study_group *gr = &sl_study_groups[g];
        const sl_study_spectra *sp = p->group[g];
        char rg[512], bb[96], cross[32];
        ranges_text(sp->design, rg, sizeof rg);
        if (p->below[g])
            snprintf(bb, sizeof bb, "%zu of %zu mu (x %.3f-%.3f)", p->below[g], p->defined[g],
                     p->xb_lo[g], p->xb_hi[g]);
        else
            snprintf(bb, sizeof bb, "none of %zu mu", p->defined[g]);
        fprintf(md, "| %s | %zu | %.3f | %s | %s | %s |\n", gr->name, gr->n, sp->pga_ms2 / SL_G,
                bb, rg, crossover_cell(sp->design, cross, sizeof cross));
        char file[64], title[128];
        snprintf(file, sizeof file, "p4_%s.tsv", gr->tag);
        snprintf(title, sizeof title, "%s records, unscaled", gr->name);
        if (study_write_spectra(o, file, title, sp))
            return -1;
        snprintf(tags + strlen(tags), sizeof tags - strlen(tags), "%s%s", g ? " " : "", gr->tag);
        size_t u = strlen(title_expr);
        if (g + 1 < SL_STUDY_NGROUPS)
            snprintf(title_expr + u, sizeof title_expr - u, "g eq '%s' ? '%s' : ", gr->tag,
                     gr->name);
        else
            snprintf(title_expr + u, sizeof title_expr - u, "'%s')", gr->name);
    }
    int rc = study_plot(o, "fig7_groups",
                        "set multiplot layout 2,2 title 'Real record groups: best-estimate (thin) and design (thick) sliding spectra'\n"
                        "set logscale y\nset format y '%%g'\nset yrange [0.1:*]\nset xlabel 'mu'\nset ylabel 'displacement (mm)'\nset key top right font ',9'\n"
                        "do for [g in '%s'] {\n"
                        "  f = sprintf('p4_%%s.tsv', g)\n"
                        "  set title %s\n"
                        "  plot [0:%.1f] f u 1:($3*1e3) w l lw 1 lc rgb '#1f77b4' t 'NLTHA mean', \\\n"
                        "    f u 1:($4*1e3) w l lw 1 lc rgb '#d62728' t 'ASCE best', \\\n"
                        "    f u 1:($5*1e3) w l lw 3 lc rgb '#1f77b4' t 'NLTHA design', \\\n"
                        "    f u 1:($6*1e3) w l lw 3 lc rgb '#d62728' t 'ASCE design'\n"
                        "}\nunset multiplot\n",
                        tags, title_expr, SL_MU_GRID_TO);
    fprintf(md, "\n![record groups](" STUDY_FIGDIR "/fig7_groups.svg)\n\n");
    return rc;
}

/* ---- Part 5: the claims table ---------------------------------------- */

static void claims_p2(FILE *md, const sl_study_part2 *c)
{
    fprintf(md,
            "| adding the orthogonal horizontal changes peak u_x (El Centro #9, RG 1.60, "
            "%.1f g, mu = %.1f) | %+.0f %% | %+.0f %% | %s |\n"
            "| ... and peak u_y | %+.0f %% | %+.0f %% | %s |\n"
            "| adding the vertical changes the peaks by | a few %% | %+.1f %% (u_x), %+.1f %% "
            "(u_y) | %s |\n",
            SL_STUDY_P2_PGA_G, SL_STUDY_P2_MU, SL_STUDY_CLAIM_DUX_PCT, c->dux,
            (c->dux < 0 && fabs(c->dux - SL_STUDY_CLAIM_DUX_PCT) <= 20)
                ? "same sign and size: the shared friction disk cuts the sliding along x"
                : "differs: the RG 1.60 modification (ours keeps the record's phases; the "
                  "study's method is not given) sets which axis dominates, and peak "
                  "changes of one axis are sensitive to it",
            SL_STUDY_CLAIM_DUY_PCT, c->duy,
            fabs(c->duy - SL_STUDY_CLAIM_DUY_PCT) <= 15 ? "close"
                                                        : "differs for the same reason as u_x",
            c->dvx, c->dvy,
            fmax(fabs(c->dvx), fabs(c->dvy)) <= 10
                ? "agrees: the vertical only modulates mu N about mu g"
                : "larger than the study's: see the vertical ZPA of the matched motion");
}

static void claims_p3(FILE *md, const sl_study_part3 *c)
{
    fprintf(md, "| crossover mu g/PGA of ASCE vs NLTHA design spectra, ground set | "
                "0.128-0.134 at 0.2-0.8 g | ");
    double lo = INFINITY, hi = -INFINITY, above = 0;
    int none = 1;
    for (size_t l = 0; l < SL_STUDY_NLEVELS; l++) {
        if (isnan(c->cross[l]))
            fprintf(md, "%snone at %.1f g", l ? ", " : "", sl_study_levels_g[l]);
        else
            fprintf(md, "%s%.3f at %.1f g", l ? ", " : "", c->cross[l], sl_study_levels_g[l]);
        if (!isnan(c->cross[l])) {
            lo = fmin(lo, c->cross[l]);
            hi = fmax(hi, c->cross[l]);
        }
        above += c->uncons_hi[l];
        none &= isnan(c->fs3_x[l]);
    }
    fprintf(md, " | %s |\n",
            hi < lo ? "differs: no low-mu crossover, ASCE is conservative at the lowest x"
            : hi <= 0.20
                ? "same finding (ASCE unconservative only at low mu g/PGA, nearly "
                  "independent of the PGA level), at a lower x. The crossover is where 2.0 x "
                  "the ASCE estimate meets 3.0 x the NLTHA mean, two curves that cross at a shallow angle, so it "
                  "moves with the records (four stand-ins here), with how they are matched "
                  "(ours keeps the records' phases; the study's method is not given) and with "
                  "their content below 0.1 Hz (section 3)"
                : "differs: see section 3");
    fprintf(md, "| ASCE design conservative above the crossover (ground set) | yes | %s | %s |\n",
            above == 0 ? "yes, at every level" : "no: see the ranges of section 3",
            above == 0 ? "agrees"
                       : "ranges at high x are where ASCE's no-sliding rule (mu_e g >= PGA) "
                         "ignores the vector sum of the horizontals; NLTHA gives millimetres");
    fprintf(md, "| FS %.1f on the ASCE best estimate covers NLTHA below the crossover | "
                "recommended | ", SL_STUDY_CLAIM_FS);
    if (none) {
        fprintf(md, "%.1f x ASCE best >= NLTHA design at every x of the grid, all four levels "
                    "| agrees |\n", SL_STUDY_CLAIM_FS);
        return;
    }
    fprintf(md, "%.1f x ASCE best < NLTHA design up to x = ", SL_STUDY_CLAIM_FS);
    for (size_t l = 0; l < SL_STUDY_NLEVELS; l++)
        fprintf(md, isnan(c->fs3_x[l]) ? "%snowhere" : "%s%.3f", l ? ", " : "", c->fs3_x[l]);
    fprintf(md, " (0.2-0.8 g) | differs at the lowest x |\n");
}

void study_report_claims(study_out *o, const sl_study_part1 *p1, const sl_study_part2 *p2,
                         const sl_study_part3 *p3, const sl_study_part4 *p4)
{
    FILE *md = o->md;
    fprintf(md, "## 5. The study's quantitative claims against seislide\n\n"
                "| claim of the study | study | seislide | agreement, and the reason for any gap |\n"
                "|---|---|---|---|\n");
    if (p1)
        fprintf(md,
                "| the smoothed model agrees with the elastic-plastic model (Rinaldi, mu = %.1f) | "
                "curves overlap (Figs. 3-4, 3-5) | reference models within %.2f %% (1-D) and "
                "%.2f %% (2-D) of the engine's peak | agrees: all three solve the same Coulomb "
                "law |\n",
                SL_STUDY_P1_MU, 100 * p1->dev[0], 100 * p1->dev[1]);
    if (p2)
        claims_p2(md, p2);
    if (p3)
        claims_p3(md, p3);
    if (p4) {
        fprintf(md, "| ASCE best estimates are conservative for all four real sets | yes | "
                    "ASCE best below the NLTHA mean at ");
        int all = 1;
        for (size_t g = 0; g < SL_STUDY_NGROUPS; g++) {
            fprintf(md, "%s%.0f %% of mu (%s)", g ? ", " : "", 100 * p4->frac_best[g],
                    sl_study_groups[g].name);
            all &= p4->frac_best[g] == 0;
        }
        fprintf(md, " | %s |\n",
                all ? "agrees"
                    : "mostly: where not, it is a few records dominating a small group "
                      "(5-8 records against the study's 40), or the high-mu end where the "
                      "no-sliding rule applies");
    }
    fprintf(md, "\n");
}

/* ---- The whole report ------------------------------------------------ */

void study_report_preamble(study_out *o)
{
    fprintf(o->md,
            "# Validation: seislide against the source study and physical floor motions\n\n"
            "Made by `seislide study` (`make study`) from a collection of recorded motions\n"
            "(`--records DIR`; provenance in the collection's MANIFEST.tsv); every number\n"
            "of sections 1-6 is recomputed by that command (sections 7 and 8 carry the tables\n"
            "of `make rockfloors` and `make tailfloors`, which take longer). The source study\n"
            "(a master's thesis evaluating the ASCE/SEI 43-05 Appendix A.1 method for sliding\n"
            "components) and its findings are restated with each comparison. Data and\n"
            "gnuplot scripts of every figure are in `docs/" STUDY_FIGDIR "/`. Regression tests\n"
            "on the same computations: tests/test_study.c.\n\n");
}

/* figdir/name as it is, or how to make it (`make target`) where it is absent. */
static int carry(study_out *o, const char *name, const char *target)
{
    char path[sizeof o->figdir + 64];
    snprintf(path, sizeof path, "%s/%s", o->figdir, name);
    fprintf(o->md, "Not recomputed by `seislide study`: written by `make %s` (tools/%s.c) to\n"
            "`docs/" STUDY_FIGDIR "/%s` and carried here as written.\n\n", target, target, name);
    FILE *f = fopen(path, "r");
    if (!f && errno == ENOENT) {
        fprintf(o->md, "(`" STUDY_FIGDIR "/%s` is not in this output folder: `make %s` makes "
                "it.)\n\n", name, target);
        return 0;
    }
    if (!f) {
        cli_msg("%s: cannot read it: %s", path, strerror(errno));
        return -1;
    }
    char buf[8192];
    size_t n;
    while ((n = fread(buf, 1, sizeof buf, f)) > 0)
        fwrite(buf, 1, n, o->md);
    int bad = ferror(f);
    fclose(f);
    if (bad) {
        cli_msg("%s: cannot read it", path);
        return -1;
    }
    fprintf(o->md, "\n");
    return 0;
}

int study_report_carried(study_out *o)
{
    fprintf(o->md,
            "## 7. Rocking against physical floor motions\n\n"
            "Beyond the source study, which treats sliding only: the probability that a slender\n"
            "rigid block tips (docs/rocking.md, docs/model.md \"Rocking\") on the sets seislide\n"
            "synthesizes from a floor's spectra, with the rocking intensity scatter, against the\n"
            "fraction of the physical floor motions behind those spectra that tip it. The\n"
            "physical floor motions are the records passed through linear three-storey buildings\n"
            "(study/building.h); a floor's spectra are the mean spectra of its physical motions.\n"
            "A row compares, for one block and level, the synthesized p_tip +- its SE with the\n"
            "physical fraction +- its binomial SE: z = (synthesized - physical) / sqrt(SE_s^2 +\n"
            "SE_p^2), within 2 SE where |z| <= 2. The rocking scatter (%.2f, SL_ROCKF_SCATTER)\n"
            "was chosen on the first three buildings; the held-out three test it.\n\n",
            SL_ROCKF_SCATTER);
    if (carry(o, STUDY_ROCKING_MD, "rockfloors"))
        return -1;
    fprintf(o->md,
            "## 8. The intensity tail near the sliding threshold\n\n"
            "A floor spectrum is the mean over floor motions whose intensity scatters; a set\n"
            "matched to it carries none of that scatter, and near the sliding threshold (mu g/ZPA\n"
            "0.5-1.0) it slides less than the physical motions. `seislide run` therefore slides\n"
            "each set with a log-normal intensity factor whose log standard deviation is each\n"
            "floor's own (src/method/scatter.h, (R4)-(R5); docs/run.md, \"Intensity scatter\"):\n\n"
            "    sigma = min(sqrt(sigma_g(f_c)^2 + %.2f^2), %.1f)\n\n"
            "with f_c the centroid, in ln f, of the floor's amplification over its ZPA (both\n"
            "horizontals) and sigma_g(f) the log standard deviation of the records' 5 %% spectra\n"
            "at one ground PGA (%.2f at 1 Hz, %.2f at 2.4 Hz, %.2f at 5.6 Hz). The table: synthesized\n"
            "over physical mean sliding on records passed through shear buildings; the aim is a\n"
            "geometric mean at 0.5-1.0 within 0.85-1.2 and no point below 0.6.\n"
            "docs/synthesis.md section 11 gives 26 buildings (1-7 storeys, 0.9-10 Hz, 2-7 %%)\n"
            "and the cost (sets and time), notes.md section 3.9 the fits behind the rule.\n\n",
            SL_SCATTER_SIGMA_0, SL_SCATTER_SIGMA_MAX, sl_scatter_sigma_ground(1.0),
            sl_scatter_sigma_ground(2.4), sl_scatter_sigma_ground(5.6));
    return carry(o, STUDY_TAIL_MD, "tailfloors");
}

/* A progress line on stderr unless *ctx (quiet) is set. */
static const char *x_text(double x, char *buf, size_t n)
{
    if (isnan(x))
        snprintf(buf, n, "none");
    else
        snprintf(buf, n, "%.3f", x);
    return buf;
}

int study_report_part5(study_out *o, const sl_study_part5 *p)
{
    FILE *md = o->md;
    char b[32], c[32];
    const double base = p->cross[SL_STUDY_P5_BASE];
    fprintf(md, "## 6. Where the crossover comes from\n\n");
    fprintf(md,
            "The crossover of section 3 (x = mu g/PGA where the ASCE design, 2.0 x the ASCE "
            "mean, reaches the NLTHA design, 3.0 x the NLTHA mean) is %s here against the "
            "study's 0.128-0.134. Below x = %.1f the ASCE mean hardly moves "
            "(%.0f-%.0f mm at %.1f g): f_es lies on RG 1.60's constant-displacement branch, "
            "where delta_s = SD_vH whatever mu. The crossover is therefore where the falling "
            "NLTHA mean reaches two thirds of that level (NLTHA mean / ASCE mean = %.3f at the "
            "first grid point past it). Its place is set by how fast the NLTHA mean falls "
            "at low mu, that is by the records' long-period content.\n\n",
            x_text(base, b, sizeof b), SL_STUDY_P5_FLAT_X, 1e3 * p->asce_lo_m,
            1e3 * p->asce_hi_m, SL_STUDY_P5_PGA_G, p->ratio_at_cross);
    fprintf(md, "One change at a time from section 3's setting (the seven records matched "
                "at 1 g, scaled to %.1f g):\n\n"
                "| change | crossover mu g/PGA | against none |\n|---|---|---|\n",
            SL_STUDY_P5_PGA_G);
    for (int k = 0; k < SL_STUDY_P5_NCHANGES; k++) {
        double x = p->cross[k];
        if (k == SL_STUDY_P5_BASE)
            snprintf(c, sizeof c, "-");
        else if (isnan(x) || isnan(base))
            snprintf(c, sizeof c, "%s", isnan(x) == isnan(base) ? "none either way"
                                                                : "decides whether one exists");
        else
            snprintf(c, sizeof c, "%+.3f", x - base);
        fprintf(md, "| %s | %s | %s |\n", sl_study_p5_change_names[k], x_text(x, b, sizeof b), c);
    }
    fprintf(md, "\nLeaving one record out:");
    for (size_t i = 0; i < SL_STUDY_NGROUND; i++)
        fprintf(md, "%s %s %s", i ? "," : "", sl_study_ground.e[i].dir,
                x_text(p->loo[i], b, sizeof b));
    fprintf(md, " (range %s-", x_text(p->loo_lo, b, sizeof b));
    fprintf(md, "%s).\n\n", x_text(p->loo_hi, b, sizeof b));
    fprintf(md, "%d random seven-record draws (seed %u) from the %zu records of section 4's "
                "groups, each matched to RG 1.60 as in section 3: no crossover in %zu",
            SL_STUDY_P5_NDRAWS, SL_STUDY_P5_SEED, p->n_pool, p->draws_none);
    if (p->draws_none < SL_STUDY_P5_NDRAWS) {
        fprintf(md, ", %s-", x_text(p->draw_lo, b, sizeof b));
        fprintf(md, "%s in the others", x_text(p->draw_hi, b, sizeof b));
    }
    fprintf(md, " (without one: ASCE conservative from the lowest x in %zu, below NLTHA "
                "throughout in %zu; each:",
            p->draws_cons, p->draws_none - p->draws_cons);
    for (size_t d = 0; d < SL_STUDY_P5_NDRAWS; d++)
        fprintf(md, "%s %s", d ? "," : "", x_text(p->draw[d], b, sizeof b));
    fprintf(md, ").\n\n");
    double lo = fmin(p->loo_lo, isnan(p->draw_lo) ? INFINITY : p->draw_lo);
    double hi = fmax(p->loo_hi, isnan(p->draw_hi) ? -INFINITY : p->draw_hi);
    const double hp = p->cross[SL_STUDY_P5_NO_HP];
    int inside = 0.128 >= lo && 0.134 <= hi, hp_reach = !isnan(hp) && hp >= 0.128;
    fprintf(md, "Conclusion: the crossover is set by the records' long-period content: the "
                "choice of records and the high-pass before matching move it (the records "
                "decide whether there is one at all, and so does the cap's definition), while "
                "the vertical, the scaling, the matching aim and the friction model move it by "
                "0.001 or less. The crossovers measured here span %.3f-%.3f; the study's "
                "0.128-0.134 %s, %s.\n\n",
            lo, hi, inside ? "lies within that record-to-record scatter" : "lies above it",
            inside ? "so the difference is the records' and their processing's"
            : hp_reach ? "within reach of the high-pass alone"
                       : "a difference left to the study's records and their processing "
                         "(four of them stand-ins here; its filtering and matching are not "
                         "given in the study)");
    return 0;
}

static void note(void *ctx, const char *msg)
{
    if (!*(const int *)ctx)
        fprintf(stderr, "seislide study: %s\n", msg);
}

int study_report_run(study_out *o, const char *records, int parts, int quiet)
{
    sl_study_part1 p1 = {0};
    sl_study_part2 p2 = {0};
    sl_study_part3 p3 = {0};
    sl_study_part4 p4 = {0};
    sl_error *e = &o->err;
    int q = quiet, rc = 0;
    if (parts & 1) {
        note(&q, "part 1: model validation");
        rc = sl_study_part1_run(records, &p1, e) ? -2 : study_report_part1(o, &p1);
    }
    if (!rc && (parts & 2)) {
        note(&q, "part 2: El Centro #9");
        rc = sl_study_part2_run(records, &p2, e) ? -2 : study_report_part2(o, &p2);
    }
    if (!rc && (parts & 4))
        rc = sl_study_part3_run(records, &p3, note, &q, e) ? -2 : study_report_part3(o, &p3);
    if (!rc && (parts & 8))
        rc = sl_study_part4_run(records, &p4, note, &q, e) ? -2 : study_report_part4(o, &p4);
    if (!rc)
        study_report_claims(o, parts & 1 ? &p1 : NULL, parts & 2 ? &p2 : NULL,
                            parts & 4 ? &p3 : NULL, parts & 8 ? &p4 : NULL);
    if (!rc && (parts & 16)) { /* on part 3's matched sets (computed here without it) */
        sl_study_part5 p5;
        note(&q, "part 5: where the crossover comes from");
        if (!(parts & 4) && sl_study_part3_run(records, &p3, note, &q, e))
            rc = -2;
        else
            rc = sl_study_part5_run(records, &p3, &p5, note, &q, e) ? -2
                                                                   : study_report_part5(o, &p5);
    }
    if (!rc)
        rc = study_report_carried(o);
    if (rc == -2)
        cli_print_error(e);
    sl_study_part1_free(&p1);
    sl_study_part2_free(&p2);
    sl_study_part3_free(&p3);
    sl_study_part4_free(&p4);
    return rc ? -1 : 0;
}

