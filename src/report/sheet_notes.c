/* sheet_notes.c - the "Notes" sheet: the assumptions and limits, every
 * number in them that belongs to a floor given for that floor (sheets.h). */
#include <stdio.h>
#include <string.h>

#include "io/floor.h"
#include "method/asce.h"
#include "report/sheets.h"
#include "rock/rock_floor.h"

#define W_TEXT 64.0   /* the one column: a portrait A4 page at 100 % */
#define MAX_NOTES 40
#define NOTE_MAX 3000

typedef struct notes {
    size_t n;
    char t[MAX_NOTES][NOTE_MAX];
    int warn[MAX_NOTES];
} notes;

static char *add(notes *s, int warn)
{
    if (s->n + 1 >= MAX_NOTES)
        return s->t[s->n]; /* further notes overwrite the last slot */
    s->warn[s->n] = warn;
    return s->t[s->n++];
}

/* "01-ground: <shape>, <drops>; 02-el12: ..." of each floor's asce_shape_text
 * and asce_drops_text. */
static void asce_shapes(const sl_report *r, char *buf, size_t n)
{
    size_t used = 0;
    char one[600], drops[800];
    buf[0] = '\0';
    for (size_t i = 0; i < r->n_floors; i++) {
        sl_rpt_asce_drops_text(r->floors[i].design, 1, drops, sizeof drops);
        int w = snprintf(buf + used, n - used, "%s%s: %s%s%s", i ? "; " : "", r->floors[i].id,
                         sl_rpt_asce_shape_text(r->floors[i].design, one, sizeof one),
                         drops[0] ? "; " : "", drops);
        if (w < 0 || (size_t)w >= n - used)
            break;
        used += (size_t)w;
    }
}

void sl_rpt_notes_sheet(lxw_workbook *wb, const sl_rpt_fmts *F, const sl_report *r)
{
    lxw_worksheet *ws = workbook_add_worksheet(wb, "Notes");
    const sl_design *d = r->floors[0].design; /* factors and policy: one per run */
    static _Thread_local notes s; /* 120 kB: off the stack, one per thread */
    char sets[1200], se[1200], shapes[NOTE_MAX - 1000], ids[400];
    memset(&s, 0, sizeof s);
    for (size_t i = 0; i < r->n_floors; i++) { /* what the reader must know first */
        const sl_report_floor *fl = &r->floors[i];
        if (fl->n_failed_motions)
            sl_rpt_failed_text(r, fl, add(&s, 1), NOTE_MAX);
    }
    for (size_t i = 0; i < r->n_floors; i++) { /* its warnings: as the run's stderr said */
        const sl_report_floor *fl = &r->floors[i];
        const char *w = sl_rpt_floor_warnings(fl);
        if (*w)
            snprintf(add(&s, 1), NOTE_MAX, "Floor %s (%s): %s.", fl->id, fl->path, w);
        else if (fl->accepted)
            snprintf(add(&s, 1), NOTE_MAX, "Floor %s (%s): accepted by --accept-floor; its ZPA is "
                     "in line with its building's other floors.", fl->id, fl->path);
    }
    snprintf(add(&s, 0), NOTE_MAX, "Model: a rigid block standing on a level floor, free to "
             "slide in both horizontal directions at once; the floor moves in three components "
             "(two horizontals and the vertical, which changes the normal force). Sliding only: "
             "rocking, overturning, uplift and impact are not modelled.");
    if (sl_rpt_has_rocking(r))
        snprintf(add(&s, 0), NOTE_MAX, "Rocking (the Rocking sheet, run --rocking-lookup): a "
                 "rigid rectangular block of uniform mass rocking about a base edge on a rigid "
                 "floor (Housner 1963), with the vertical; impacts with Housner's restitution; "
                 "tipped when its rotation reaches alpha = atan(b/h). The probability is over "
                 "the floor's own motion sets, each scaled by a log-normal intensity factor of "
                 "log standard deviation %.2f, the rocking axis the worst of every %g degrees. "
                 "Left out: sliding and rocking together (slide-rock; an item rocks when mu >= "
                 "b/h), a centre of mass off the middle of the base or a non-uniform mass, a "
                 "flexible base or floor, rocking on a corner in 3-D, the block leaving the "
                 "floor; the targets (1 %% at the floor motion, 10 %% at 1.5 x it) are ASCE/SEI "
                 "43-05 section 1.3's (docs/rocking.md).", SL_ROCKF_SCATTER,
                 SL_ROCKF_ORIENT_STEP_DEG);
    snprintf(add(&s, 0), NOTE_MAX, "Friction: Coulomb, isotropic in the floor plane, the static "
             "coefficient equal to the kinetic one (mu). The block sticks while the friction "
             "force can hold it; mu g at or above every motion's demand means no sliding.");
    sl_rpt_sets_text(r, "%s: %zu sets", sets, sizeof sets);
    snprintf(add(&s, 0), NOTE_MAX, "Motions: spectrum-compatible three-component sets, "
             "synthesized from each floor's response spectra and checked as in US NRC SRP 3.7.1 "
             "(sheet Motion quality; 'run below target' = the most consecutive frequency "
             "points below the target spectrum, limit 9). Sets per floor (sheet Inputs: why each "
             "floor stopped adding sets): %s.", sets);
    char scat[1600] = "", sig[600] = "";
    size_t used = 0;
    int any = 0;
    for (size_t i = 0; i < r->n_floors && used < sizeof sig; i++) {
        int w = snprintf(sig + used, sizeof sig - used, "%s%s %.3g", i ? ", " : "",
                         r->floors[i].id, r->floors[i].scatter);
        used += w > 0 ? (size_t)w : 0;
        any |= r->floors[i].scatter > 0;
    }
    if (any)
        snprintf(scat, sizeof scat, " Each set's peak is its mean over a record-to-record "
                 "intensity factor of its horizontals (log-normal, mean 1, log standard deviation "
                 "per floor %s: each floor's own from its spectrum unless --scatter gives one "
                 "value): the floor motions behind a spectrum differ in intensity, and sliding near mu "
                 "g = ZPA grows faster than the intensity (docs/run.md, Intensity scatter). This "
                 "goes beyond A.1's mean of spectrum-compatible analyses: --scatter 0 gives that "
                 "procedure. The motions written with --motions carry no factor. Above the ZPA the "
                 "NLTHA value comes from the strongest intensities alone, while the ASCE estimate "
                 "is 0 once mu_e g reaches the ZPA (below): from there on ASCE is listed below "
                 "NLTHA.", sig);
    snprintf(add(&s, 0), NOTE_MAX, "NLTHA design value = %g x the mean over the floor's sets of "
             "the peak vector sliding displacement (ASCE/SEI 43-05 A.1 asks for 3.0 x the mean of "
             "at least 5 analyses).%s", d->fs_nltha, scat);
    asce_shapes(r, shapes, sizeof shapes);
    snprintf(add(&s, 0), NOTE_MAX, "ASCE design value = %g x the ASCE/SEI 43-05 best estimate "
             "delta = c_s / (2 pi f_es)^2 with c_s = 2 mu_e g, mu_e = mu (1 - %g a_v/g) the "
             "effective friction coefficient (a_v the peak vertical acceleration), and f_es the "
             "lowest frequency where the 10 %%-damped spectrum SA_vH reaches c_s: delta is the "
             "spectral displacement SA_vH / (2 pi f)^2 there. Where f_es lies where the spectral "
             "displacement is constant (RG 1.60 below 0.25 Hz) the estimate is flat in mu; on a "
             "flank that grows faster than f^2 (a floor's amplification below its mode) it rises "
             "with mu; where c_s rises past a peak of the spectrum, f_es jumps to the peak's far "
             "side and the estimate steps down between two grid rows. It is 0 once mu_e g "
             "reaches the ZPA, from mu g/ZPA = 1 / (1 - %g a_v/g), a little above 1 (not where "
             "mu g does). Per floor: %s.", d->fs_asce, SL_ASCE_VERTICAL_COEF,
             SL_ASCE_VERTICAL_COEF, shapes);
    for (size_t i = 0; i < r->n_floors; i++)
        if (r->floors[i].sa10_fallback)
            snprintf(add(&s, 1), NOTE_MAX, "Floor %s: %s (docs/run.md).", r->floors[i].id,
                     sl_rpt_sa10_text(&r->floors[i]));
    snprintf(add(&s, 0), NOTE_MAX, "Cap = %g x the mean over the floor's sets of the peak floor "
             "displacement, the horizontals combined by the 100-40 rule: a block cannot "
             "slide much further than the floor moves. Design values are min(value, cap); flags "
             "nltha_capped and asce_capped mark where the cap governs.", d->cap_factor);
    snprintf(add(&s, 0), NOTE_MAX, "Crossover and ranges: every range of mu where the ASCE design "
             "value is below the NLTHA design value is listed (ends interpolated where the "
             "difference changes sign; '<=' or '+' when the range reaches the grid's end). The "
             "crossover, in the source study's sense, is the upper end of such a range when it "
             "starts at the lowest mu of the grid; otherwise 'none'.");
    snprintf(add(&s, 0), NOTE_MAX, "Required clearance: by the policy (%s): nltha = NLTHA design "
             "value (ASCE 43-05 permits NLTHA everywhere), asce = ASCE design value, envelope = "
             "the larger. Between grid values of mu the clearance is interpolated linearly.",
             sl_clearance_policy_name(d->policy));
    sl_rpt_sets_text(r, "%s sd/sqrt(%zu)", se, sizeof se);
    snprintf(add(&s, 0), NOTE_MAX, "Uncertainty: the NLTHA mean of a floor's N sets has a "
             "standard error of sd / sqrt(N): %s. The design value's standard error (design "
             "factor x that; where the cap governs, the cap's: %g x the standard error of the "
             "mean floor displacement) is shown per row and on the Lookup. Another seed gives "
             "values within about two standard errors. The factor %g covers record-to-record "
             "variability, not modelling error.", se, d->cap_factor, d->fs_nltha);
    snprintf(add(&s, 0), NOTE_MAX, "Limits: values at mu outside the table are not extrapolated. "
             "Results apply to the floor spectra given (sheet Inputs: files and CRC-32) and to "
             "components whose base does not rock; anchor components for which this is not "
             "true.");
    worksheet_set_column(ws, 0, 0, W_TEXT, NULL);
    worksheet_write_string(ws, 0, 0, "Assumptions and limits", F->title);
    for (size_t i = 0; i < s.n; i++) {
        lxw_row_t row = (lxw_row_t)(i + 2);
        worksheet_write_string(ws, row, 0, s.t[i], s.warn[i] ? F->warn : F->note);
        /* a little room under each paragraph (the height errs tall already: a
         * long paragraph gets a line or two more than it takes) */
        worksheet_set_row(ws, row, sl_rpt_text_height(s.t[i], W_TEXT, s.warn[i]) + 4, NULL);
    }
    sl_rpt_page_setup(ws, r, 0, sl_rpt_failed_ids(r, ids, sizeof ids));
    worksheet_fit_to_pages(ws, 1, 0);
    sl_rpt_protect(ws);
}
