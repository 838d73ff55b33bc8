/* report.c - the report's public functions (report.h): floor ids and names,
 * flags and ranges as text, the finite check, and the workbook assembled
 * from one writer per sheet (sheet_*.c; the CSV files: csv.c). */
#include "report/report.h"
#include "io/text.h"

#include <ctype.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "io/atomic.h"
#include "report/sheets.h"

void sl_report_init(sl_report *r)
{
    memset(r, 0, sizeof *r);
    r->lookup_mu = SL_REPORT_LOOKUP_MU;
}

size_t sl_report_utf8_len(const char *s) { return sl_text_utf8_len(s, strnlen(s, 4)); }

char *sl_report_floor_id(const char *path, char *buf, size_t n)
{
    const char *base = path ? path : "";
    const char *slash = strrchr(base, '/');
    if (slash)
        base = slash + 1;
    size_t len = strlen(base);
    if (len > 4 && (!strcasecmp(base + len - 4, ".ini") || !strcasecmp(base + len - 4, ".csv")))
        len -= 4;
    size_t k = 0;
    for (size_t i = 0; i < len;) {
        size_t c = sl_report_utf8_len(base + i);
        if (c > len - i)
            c = 0;
        size_t w = c ? c : 1;
        if (k + w >= n || k + w > SL_RPT_ID_MAX) /* whole characters only */
            break;
        if (c > 1 || (c == 1 && (unsigned char)base[i] >= 0x20 && base[i] != 0x7f))
            memcpy(buf + k, base + i, c);
        else /* a control byte or a byte that is not UTF-8 */
            buf[k] = '_';
        k += w;
        i += w;
    }
    if (k == 0 && n > 1)
        buf[k++] = '_';
    if (n)
        buf[k < n ? k : n - 1] = '\0';
    return buf;
}

char *sl_report_file_name(const char *id, char *buf, size_t n)
{
    size_t k = 0;
    for (const char *p = id; *p && k + 1 < n;) {
        size_t c = sl_report_utf8_len(p);
        if (c > 1 && k + c < n) { /* a letter beyond ASCII: kept */
            memcpy(buf + k, p, c);
            k += c;
            p += c;
            continue;
        }
        buf[k++] = isalnum((unsigned char)*p) || *p == '-' || *p == '_' ? *p : '_';
        p += c > 1 ? c : 1;
    }
    if (n)
        buf[k] = '\0';
    return buf;
}

int sl_report_floor_refs_clash(const char *id_a, const char *name_a, const char *id_b,
                               const char *name_b)
{
    if (!strcasecmp(id_a, id_b))
        return 1;
    if (!strcasecmp(name_a, name_b))
        return 2;
    if (!strcasecmp(id_b, name_a))
        return 3;
    if (!strcasecmp(name_b, id_a))
        return 4;
    return 0;
}

sl_status sl_report_check_floors(const sl_report *r, sl_error *err)
{
    for (size_t i = 0; i < r->n_floors; i++)
        for (size_t j = 0; j < i; j++) {
            const sl_report_floor *a = &r->floors[j], *b = &r->floors[i];
            char fa[4 * SL_RPT_ID_MAX + 1], fb[4 * SL_RPT_ID_MAX + 1];
            switch (sl_report_floor_refs_clash(a->id, a->name, b->id, b->name)) {
            case 1:
                return sl_error_set(err, SL_EINVAL, b->path, 0,
                                    "floor id '%s' (from the file name) is also that of %s%s: "
                                    "rename one file, the outputs are named by it",
                                    b->id, a->path,
                                    strcmp(a->id, b->id) ? " (floor ids are compared without "
                                                           "case)" : "");
            case 2:
                return sl_error_set(err, SL_EINVAL, b->path, 0,
                                    "floor name '%s' is also that of %s: floor names must "
                                    "differ (the workbook's Lookup chooses by name)",
                                    b->name, a->path);
            case 3:
                return sl_error_set(err, SL_EINVAL, b->path, 0,
                                    "floor id '%s' (from the file name) is the name of the floor "
                                    "of %s ('%s', ids and names compared without case): a "
                                    "components list's floor '%s' would name two floors; "
                                    "rename the file or that floor",
                                    b->id, a->path, a->name, b->id);
            case 4:
                return sl_error_set(err, SL_EINVAL, b->path, 0,
                                    "floor name '%s' is the floor id of %s (from its file name; "
                                    "ids and names compared without case): a components list's "
                                    "floor '%s' would name two floors; rename the floor or that "
                                    "file",
                                    b->name, a->path, b->name);
            default:
                break;
            }
            if (!strcmp(sl_report_file_name(a->id, fa, sizeof fa),
                        sl_report_file_name(b->id, fb, sizeof fb)))
                return sl_error_set(err, SL_EINVAL, b->path, 0,
                                    "floor id '%s' (from the file name) gives the output file "
                                    "name floor_%s.csv, as %s does: rename one file",
                                    b->id, fb, a->path);
        }
    return SL_OK;
}

char *sl_report_flags(unsigned flags, char *buf, size_t n)
{
    static const struct {
        unsigned bit;
        const char *name;
    } names[] = {{SL_DESIGN_NO_SLIDING, "no_sliding"},
                 {SL_DESIGN_NLTHA_CAPPED, "nltha_capped"},
                 {SL_DESIGN_ASCE_CAPPED, "asce_capped"},
                 {SL_DESIGN_UNCONSERVATIVE, "asce_below_nltha"},
                 {SL_DESIGN_ASCE_UNDEFINED, "asce_undefined"}};
    buf[0] = '\0';
    size_t used = 0;
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++)
        if (flags & names[i].bit) {
            int w = snprintf(buf + used, n > used ? n - used : 0, "%s%s", used ? " " : "",
                             names[i].name);
            if (w > 0)
                used += (size_t)w;
        }
    return buf;
}

char *sl_report_ranges_text(const sl_design *d, char *buf, size_t n)
{
    size_t used = 0;
    buf[0] = '\0';
    if (d->n_ranges == 0) {
        snprintf(buf, n, "none");
        return buf;
    }
    for (size_t q = 0; q < d->n_ranges; q++) {
        const sl_design_range *g = &d->ranges[q];
        int w = snprintf(buf + used, n - used, "%s%s%.3f-%.3f%s", q ? ", " : "",
                         g->open_lo ? "<=" : "", g->mu_lo, g->mu_hi, g->open_hi ? "+" : "");
        if (w < 0 || (size_t)w >= n - used)
            break;
        used += (size_t)w;
    }
    return buf;
}

/* Every number the report writes must be finite: ASCE may be undefined
 * (NAN, written as an empty cell), nothing may be infinite. */
sl_status sl_rpt_check_finite(const sl_report *r, sl_error *err)
{
    if (!r || r->n_floors == 0)
        return sl_error_set(err, SL_EINVAL, NULL, 0, "report: no floors to write");
    for (size_t i = 0; i < r->n_floors; i++) {
        const sl_report_floor *fl = &r->floors[i];
        const sl_design *d = fl->design;
        if (d->n != r->floors[0].design->n)
            return sl_error_set(err, SL_EINVAL, fl->path, 0, "floors do not share the friction grid");
        if (!isfinite(fl->zpa_h_ms2) || !(fl->zpa_h_ms2 > 0))
            return sl_error_set(err, SL_EINVAL, fl->path, 0, "horizontal ZPA %g is not finite and > 0",
                                fl->zpa_h_ms2);
        for (size_t k = 0; k < d->n; k++) {
            const sl_design_row *w = &d->rows[k];
            const double must[] = {w->mu, w->x, w->nltha_mean_m, w->nltha_sd_m, w->nltha_design_m,
                                   w->cap_m};
            const double may[] = {w->asce_best_m, w->asce_design_m, w->clearance_m};
            int bad = 0;
            for (size_t c = 0; c < sizeof must / sizeof must[0]; c++)
                bad |= !isfinite(SL_RPT_MM_PER_M * must[c]);
            for (size_t c = 0; c < sizeof may / sizeof may[0]; c++)
                bad |= isinf(SL_RPT_MM_PER_M * may[c]);
            if (bad)
                return sl_error_set(err, SL_EINVAL, fl->path, 0,
                                    "floor '%s': a result at mu %g is not finite (NLTHA mean %g m, "
                                    "ASCE best %g m): check the file's values and units",
                                    fl->name, w->mu, w->nltha_mean_m, w->asce_best_m);
        }
    }
    return SL_OK;
}

sl_status sl_report_write_xlsx(const sl_report *r, const char *path, sl_error *err)
{
    if (sl_rpt_check_finite(r, err))
        return err ? err->code : SL_EINVAL;
    sl_atomic *a;
    lxw_workbook *wb = sl_rpt_workbook_open(
        path, "Required clearance around unanchored components",
        "Design sliding spectra per floor (NLTHA and ASCE/SEI 43-05)", &r->project, r->created,
        &a, err);
    if (!wb)
        return err ? err->code : SL_EIO;
    char (*names)[SL_RPT_SHEET_NAME_MAX * 4 + 1] = calloc(r->n_floors, sizeof *names);
    if (!names) {
        sl_rpt_workbook_discard(wb, a);
        return sl_error_set(err, SL_ENOMEM, path, 0, "out of memory");
    }
    sl_rpt_sheet_names(r, names);
    sl_rpt_fmts F;
    sl_rpt_formats(wb, &F);
    sl_rpt_axes ax = sl_rpt_shared_axes(r);
    sl_rpt_lookup_sheet(wb, &F, r);
    sl_rpt_summary_sheet(wb, &F, r, &ax);
    for (size_t i = 0; i < r->n_floors; i++)
        sl_rpt_floor_sheet(wb, &F, r, i, names[i], &ax);
    if (sl_rpt_has_rocking(r))
        sl_rpt_rocking_sheet(wb, &F, r);
    sl_rpt_quality_sheet(wb, &F, r);
    sl_rpt_notes_sheet(wb, &F, r);
    sl_rpt_inputs_sheet(wb, &F, r);
    sl_rpt_data_sheet(wb, &F, r, &ax);
    free(names);
    return sl_rpt_workbook_close(wb, a, path, err);
}
