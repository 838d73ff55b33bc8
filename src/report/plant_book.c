/* plant_book.c - plant.csv and plant.xlsx; see plant_book.h. */
#include "report/plant_book.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <strings.h>
#include <xlsxwriter.h>

#include "core/units.h"
#include "io/atomic.h"

const double SL_PLANT_BOOK_MU[SL_PLANT_BOOK_NMU] = {0.05, 0.1, 0.2, 0.3, 0.4, 0.5};

const char *sl_plant_book_governing(const sl_design *d, char *buf, size_t n)
{
    int nl = 0, as = 0, cap = 0;
    for (size_t k = 0; k < d->n; k++) {
        const sl_design_row *r = &d->rows[k];
        if (!(r->clearance_m > 0))
            continue;
        int by_n = r->clearance_m == r->nltha_design_m, by_a = r->clearance_m == r->asce_design_m;
        nl |= by_n;
        as |= by_a && !by_n;
        cap |= r->clearance_m == r->cap_m;
    }
    if (!nl && !as) /* no sliding anywhere: the policy names the method */
        nl = d->policy != SL_CLEARANCE_ASCE, as = d->policy == SL_CLEARANCE_ASCE;
    snprintf(buf, n, "%s%s%s", nl && as ? "NLTHA and ASCE" : nl ? "NLTHA" : "ASCE",
             cap ? " (capped)" : "", "");
    return buf;
}

/* A CSV field: quoted when it holds a comma, quote or line break (RFC 4180). */
static void csv_field(FILE *f, const char *s)
{
    if (!strpbrk(s, ",\"\r\n")) {
        fputs(s, f);
        return;
    }
    fputc('"', f);
    for (; *s; s++) {
        if (*s == '"')
            fputc('"', f);
        fputc(*s, f);
    }
    fputc('"', f);
}

static void csv_comment(FILE *f, const char *key, const char *value)
{
    fprintf(f, "# %s: ", key);
    for (const char *p = value && *value ? value : "-"; *p; p++)
        fputc(*p == '\r' || *p == '\n' ? ' ' : *p, f);
    fputs("\r\n", f);
}

sl_status sl_plant_book_write_csv(const sl_plant_book *b, const char *dir, sl_error *err)
{
    char path[4400], gov[64];
    snprintf(path, sizeof path, "%s/%s", dir, SL_PLANT_BOOK_CSV);
    for (size_t i = 0; i < b->n; i++)
        if (!isfinite(b->rows[i].zpa_h_ms2))
            return sl_error_set(err, SL_EINVAL, path, 0, "floor '%s/%s': ZPA not finite",
                                b->rows[i].building, b->rows[i].id);
    sl_atomic *a = sl_atomic_open(path, err);
    if (!a)
        return err ? err->code : SL_EIO;
    FILE *f = sl_atomic_file(a);
    csv_comment(f, "program", b->version);
    csv_comment(f, "content", "the plant index: one row per floor of every building; the "
                "required clearance at six friction values (linear interpolation in mu on "
                "each floor's grid, empty outside it)");
    csv_comment(f, "project", b->project.project);
    csv_comment(f, "document", b->project.document);
    csv_comment(f, "revision", b->project.revision);
    csv_comment(f, "units", "elevation in m; ZPA in g; clearance in mm");
    fputs("building,floor,floor_name,elevation_m,zpa_g,sets,convergence", f);
    for (int k = 0; k < SL_PLANT_BOOK_NMU; k++)
        fprintf(f, ",clearance_mm_mu_%g", SL_PLANT_BOOK_MU[k]);
    fputs(",governing\r\n", f);
    for (size_t i = 0; i < b->n; i++) {
        const sl_plant_book_row *r = &b->rows[i];
        csv_field(f, r->building);
        fputc(',', f);
        csv_field(f, r->id);
        fputc(',', f);
        csv_field(f, r->name);
        fputc(',', f);
        if (isfinite(r->elevation_m))
            fprintf(f, "%.3f", r->elevation_m);
        fprintf(f, ",%.4f,%zu,%s", r->zpa_h_ms2 / SL_G, r->n_sets, r->stop);
        for (int k = 0; k < SL_PLANT_BOOK_NMU; k++) {
            double c = sl_design_clearance_at(r->design, SL_PLANT_BOOK_MU[k]);
            fputc(',', f);
            if (isfinite(c))
                fprintf(f, "%.3f", 1e3 * c);
        }
        fprintf(f, ",%s\r\n", sl_plant_book_governing(r->design, gov, sizeof gov));
    }
    return sl_atomic_commit(a, err);
}

/* Lookup cells (0-based rows, column B). */
enum { LK_BUILDING = 9, LK_FLOOR, LK_MU, LK_RESULT = 13, LK_CHECK, LK_NOTE, LK_HOW = 17, LK_ROW,
       LK_K, LK_MU0, LK_MU1, LK_C0, LK_C1 };

static void col_name(size_t c, char *buf)
{
    char t[8];
    int k = 0;
    c++;
    while (c && k < 7) {
        t[k++] = (char)('A' + (c - 1) % 26);
        c = (c - 1) / 26;
    }
    for (int i = 0; i < k; i++)
        buf[i] = t[k - 1 - i];
    buf[k] = '\0';
}

static void formula(lxw_worksheet *ws, int zero, lxw_row_t row, const char *f, double v,
                    const char *s, lxw_format *fmt)
{
    if (zero)
        worksheet_write_formula_num(ws, row, 1, f, fmt, 0);
    else if (s)
        worksheet_write_formula_str(ws, row, 1, f, fmt, s);
    else
        worksheet_write_formula_num(ws, row, 1, f, fmt, v);
}

static void protect(lxw_worksheet *ws)
{
    lxw_protection p;
    memset(&p, 0, sizeof p);
    worksheet_protect(ws, NULL, &p);
}

static const char *or_dash(const char *s) { return s && *s ? s : "-"; }

typedef struct fmts {
    lxw_format *title, *bold, *input, *mm, *mu, *g, *wrap;
} fmts;

/* Data: A building, B floor, C building|floor, D.. clearance on the grid
 * (row 1: the grid); the building list in the column after the grid. */
static void data_sheet(lxw_workbook *wb, const fmts *F, const sl_plant_book *b, size_t *bcol,
                       size_t *nb)
{
    lxw_worksheet *ws = workbook_add_worksheet(wb, "Data");
    const sl_design *d0 = b->rows[0].design;
    char key[400];
    worksheet_write_string(ws, 0, 0, "building", F->bold);
    worksheet_write_string(ws, 0, 1, "floor", F->bold);
    worksheet_write_string(ws, 0, 2, "building|floor", F->bold);
    for (size_t k = 0; k < d0->n; k++)
        worksheet_write_number(ws, 0, (lxw_col_t)(3 + k), d0->rows[k].mu, F->mu);
    *bcol = 3 + d0->n + 1;
    *nb = 0;
    worksheet_write_string(ws, 0, (lxw_col_t)*bcol, "buildings", F->bold);
    for (size_t i = 0; i < b->n; i++) {
        const sl_plant_book_row *r = &b->rows[i];
        lxw_row_t row = (lxw_row_t)(i + 1);
        worksheet_write_string(ws, row, 0, r->building, NULL);
        worksheet_write_string(ws, row, 1, r->id, NULL);
        snprintf(key, sizeof key, "%s|%s", r->building, r->id);
        worksheet_write_string(ws, row, 2, key, NULL);
        for (size_t k = 0; k < r->design->n; k++)
            worksheet_write_number(ws, row, (lxw_col_t)(3 + k), 1e3 * r->design->rows[k].clearance_m,
                                   F->mm);
        if (i == 0 || strcmp(r->building, b->rows[i - 1].building))
            worksheet_write_string(ws, (lxw_row_t)(1 + (*nb)++), (lxw_col_t)*bcol, r->building,
                                   NULL);
    }
    char c0[8], c1[8], def[200];
    col_name(3, c0);
    col_name(3 + d0->n - 1, c1);
    snprintf(def, sizeof def, "=Data!$%s$1:$%s$1", c0, c1);
    workbook_define_name(wb, "plant_mu_grid", def);
    snprintf(def, sizeof def, "=Data!$%s$2:$%s$%zu", c0, c1, b->n + 1);
    workbook_define_name(wb, "plant_clearance_mm", def);
    snprintf(def, sizeof def, "=Data!$C$2:$C$%zu", b->n + 1);
    workbook_define_name(wb, "plant_floor_keys", def);
    snprintf(def, sizeof def, "=Data!$A$2:$A$%zu", b->n + 1);
    workbook_define_name(wb, "plant_floor_buildings", def);
    col_name(*bcol, c0);
    snprintf(def, sizeof def, "=Data!$%s$2:$%s$%zu", c0, c0, *nb + 1);
    workbook_define_name(wb, "plant_buildings", def);
    worksheet_set_column(ws, 0, 2, 24, NULL);
    protect(ws);
}

static void plant_sheet(lxw_workbook *wb, const fmts *F, const sl_plant_book *b)
{
    lxw_worksheet *ws = workbook_add_worksheet(wb, "Plant");
    static const char *const head[] = {"Building", "Floor", "Floor name", "Elevation, m",
                                       "Horizontal ZPA, g", "Motion sets", "Convergence"};
    char h[64], gov[64];
    for (lxw_col_t c = 0; c < 7; c++)
        worksheet_write_string(ws, 0, c, head[c], F->bold);
    for (int k = 0; k < SL_PLANT_BOOK_NMU; k++) {
        snprintf(h, sizeof h, "Clearance at mu %g, mm", SL_PLANT_BOOK_MU[k]);
        worksheet_write_string(ws, 0, (lxw_col_t)(7 + k), h, F->bold);
    }
    worksheet_write_string(ws, 0, 7 + SL_PLANT_BOOK_NMU, "Governing", F->bold);
    for (size_t i = 0; i < b->n; i++) {
        const sl_plant_book_row *r = &b->rows[i];
        lxw_row_t row = (lxw_row_t)(i + 1);
        worksheet_write_string(ws, row, 0, r->building, NULL);
        worksheet_write_string(ws, row, 1, r->id, NULL);
        worksheet_write_string(ws, row, 2, r->name, NULL);
        if (isfinite(r->elevation_m))
            worksheet_write_number(ws, row, 3, r->elevation_m, NULL);
        worksheet_write_number(ws, row, 4, r->zpa_h_ms2 / SL_G, F->g);
        worksheet_write_number(ws, row, 5, (double)r->n_sets, NULL);
        worksheet_write_string(ws, row, 6, r->stop, NULL);
        for (int k = 0; k < SL_PLANT_BOOK_NMU; k++) {
            double c = sl_design_clearance_at(r->design, SL_PLANT_BOOK_MU[k]);
            if (isfinite(c))
                worksheet_write_number(ws, row, (lxw_col_t)(7 + k), 1e3 * c, F->mm);
        }
        worksheet_write_string(ws, row, 7 + SL_PLANT_BOOK_NMU,
                               sl_plant_book_governing(r->design, gov, sizeof gov), NULL);
    }
    worksheet_set_column(ws, 0, 2, 22, NULL);
    worksheet_set_column(ws, 3, 7 + SL_PLANT_BOOK_NMU, 14, F->wrap);
    worksheet_freeze_panes(ws, 1, 2);
    worksheet_set_landscape(ws);
    worksheet_fit_to_pages(ws, 1, 0);
    worksheet_repeat_rows(ws, 0, 0);
    protect(ws);
}

static void lookup_sheet(lxw_workbook *wb, const fmts *F, const sl_plant_book *b, size_t nb)
{
    lxw_worksheet *ws = workbook_add_worksheet(wb, "Lookup");
    const sl_design *d0 = b->rows[0].design;
    size_t n = d0->n;
    double mu_min = d0->rows[0].mu, mu_max = d0->rows[n - 1].mu;
    char f[1600], msg[160];
    int z = b->lookup_zero_cache;
    worksheet_set_column(ws, 0, 1, 46, F->wrap);
    worksheet_write_string(ws, 0, 0, "Required clearance around an unanchored component, "
                           "whole plant", F->title);
    const char *const label[] = {"Project", "Document no.", "Revision", "Prepared by",
                                 "Checked by", "Date", "Program"};
    const char *const value[] = {b->project.project, b->project.document, b->project.revision,
                                 b->project.prepared, b->project.checked, b->project.date,
                                 b->version};
    for (lxw_row_t i = 0; i < 7; i++) {
        worksheet_write_string(ws, i + 1, 0, label[i], F->bold);
        worksheet_write_string(ws, i + 1, 1, or_dash(value[i]), NULL);
    }
    const char *b0 = b->lookup_building ? b->lookup_building : b->rows[0].building;
    const char *f0 = b->lookup_floor ? b->lookup_floor : b->rows[0].id;
    double mu0 = b->lookup_mu;
    worksheet_write_string(ws, LK_BUILDING, 0, "Building (choose from the list)", F->bold);
    worksheet_write_string(ws, LK_FLOOR, 0, "Floor (choose from the building's list)", F->bold);
    worksheet_write_string(ws, LK_MU, 0, "Friction coefficient mu (type it)", F->bold);
    if (*b0)
        worksheet_write_string(ws, LK_BUILDING, 1, b0, F->input);
    else
        worksheet_write_blank(ws, LK_BUILDING, 1, F->input);
    if (*f0)
        worksheet_write_string(ws, LK_FLOOR, 1, f0, F->input);
    else
        worksheet_write_blank(ws, LK_FLOOR, 1, F->input);
    if (isfinite(mu0))
        worksheet_write_number(ws, LK_MU, 1, mu0, F->input);
    else
        worksheet_write_blank(ws, LK_MU, 1, F->input);
    lxw_data_validation dv;
    memset(&dv, 0, sizeof dv);
    dv.validate = LXW_VALIDATION_TYPE_LIST_FORMULA;
    dv.value_formula = "=plant_buildings";
    dv.input_title = "Building";
    dv.input_message = "Choose the building.";
    dv.error_title = "Unknown building";
    dv.error_message = "Choose a building from the list.";
    worksheet_data_validation_cell(ws, LK_BUILDING, 1, &dv);
    lxw_data_validation dfl;
    memset(&dfl, 0, sizeof dfl);
    dfl.validate = LXW_VALIDATION_TYPE_LIST_FORMULA;
    char lf[200];
    snprintf(lf, sizeof lf, "=OFFSET(Data!$B$1,MATCH($B$%d,plant_floor_buildings,0),0,"
             "COUNTIF(plant_floor_buildings,$B$%d),1)", LK_BUILDING + 1, LK_BUILDING + 1);
    dfl.value_formula = lf;
    dfl.input_title = "Floor";
    dfl.input_message = "Choose the floor the component stands on (the building's floors).";
    dfl.error_title = "Unknown floor";
    dfl.error_message = "Choose a floor of the chosen building from the list.";
    worksheet_data_validation_cell(ws, LK_FLOOR, 1, &dfl);
    lxw_data_validation dm;
    memset(&dm, 0, sizeof dm);
    dm.validate = LXW_VALIDATION_TYPE_DECIMAL;
    dm.criteria = LXW_VALIDATION_CRITERIA_BETWEEN;
    dm.minimum_number = mu_min;
    dm.maximum_number = mu_max;
    snprintf(msg, sizeof msg, "A number from %.2f to %.2f (static = kinetic friction).", mu_min,
             mu_max);
    dm.input_title = "Friction coefficient";
    dm.input_message = msg;
    dm.error_title = "mu outside the table";
    dm.error_message = msg;
    worksheet_data_validation_cell(ws, LK_MU, 1, &dm);

    /* the C twin of the formulas, for the cached values */
    size_t fi = b->n;
    int bknown = 0;
    for (size_t i = 0; i < b->n; i++) {
        bknown |= !strcasecmp(b0, b->rows[i].building);
        if (fi == b->n && !strcasecmp(b0, b->rows[i].building) && !strcasecmp(f0, b->rows[i].id))
            fi = i;
    }
    const char *check = !*b0 ? "choose a building from the list"
                        : !bknown ? "unknown building: choose one from the list"
                        : !*f0 ? "choose a floor from the list"
                        : fi == b->n ? "unknown floor in this building: choose one from the list"
                        : !isfinite(mu0) ? "type mu"
                        : (mu0 < mu_min || mu0 > mu_max) ? "mu outside the table" : "ok";
    int ok = !strcmp(check, "ok");
    size_t k0 = 0;
    while (ok && k0 + 1 < n && d0->rows[k0 + 1].mu <= mu0)
        k0++;
    size_t k1 = k0 + 1 < n ? k0 + 1 : k0;
    const sl_design *ds = ok ? b->rows[fi].design : d0;
    double res = ok ? 1e3 * sl_design_clearance_at(ds, mu0) : NAN;

    worksheet_write_string(ws, LK_RESULT, 0, "Required clearance, mm", F->title);
    snprintf(f, sizeof f, "=IF(B%d<>\"ok\",\"-\",IF(B%d=B%d,B%d,B%d+(B%d-B%d)*(B%d-B%d)/(B%d-B%d)))",
             LK_CHECK + 1, LK_MU1 + 1, LK_MU0 + 1, LK_C0 + 1, LK_C0 + 1, LK_MU + 1, LK_MU0 + 1,
             LK_C1 + 1, LK_C0 + 1, LK_MU1 + 1, LK_MU0 + 1);
    formula(ws, z, LK_RESULT, f, res, ok ? NULL : "-", F->mm);
    worksheet_write_string(ws, LK_CHECK, 0, "Input check", F->bold);
    snprintf(f, sizeof f,
             "=IF(B%d=\"\",\"choose a building from the list\",IF(ISNA(MATCH(B%d,plant_buildings,0)),"
             "\"unknown building: choose one from the list\",IF(B%d=\"\",\"choose a floor from the "
             "list\",IF(ISNA(MATCH(B%d&\"|\"&B%d,plant_floor_keys,0)),\"unknown floor in this "
             "building: choose one from the list\",IF(B%d=\"\",\"type mu\",IF(NOT(ISNUMBER(B%d)),"
             "\"mu must be a number\",IF(OR(B%d<%.10g,B%d>%.10g),\"mu outside the table\","
             "\"ok\")))))))",
             LK_BUILDING + 1, LK_BUILDING + 1, LK_FLOOR + 1, LK_BUILDING + 1, LK_FLOOR + 1,
             LK_MU + 1, LK_MU + 1, LK_MU + 1, mu_min, LK_MU + 1, mu_max);
    formula(ws, z, LK_CHECK, f, 0, check, F->bold);
    snprintf(msg, sizeof msg, "the table covers mu %.2f to %.2f", mu_min, mu_max);
    worksheet_write_string(ws, LK_CHECK, 2, msg, NULL);
    worksheet_write_string(ws, LK_NOTE, 0, "Note", F->bold);
    snprintf(f, sizeof f, "=IF(B%d<>\"ok\",\"\",IF(B%d=0,\"no sliding predicted: mu g is at or "
             "above what every motion demands\",\"\"))", LK_CHECK + 1, LK_RESULT + 1);
    formula(ws, z, LK_NOTE, f, 0, ok && res == 0 ? "no sliding predicted: mu g is at or above "
            "what every motion demands" : "", NULL);

    worksheet_write_string(ws, LK_HOW, 0, "How it is computed (linear interpolation in mu, as "
                           "sl_design_clearance_at in the program):", F->bold);
    worksheet_write_string(ws, LK_ROW, 0, "row of the floor in Data", NULL);
    snprintf(f, sizeof f, "=IF(B%d<>\"ok\",\"\",MATCH(B%d&\"|\"&B%d,plant_floor_keys,0))",
             LK_CHECK + 1, LK_BUILDING + 1, LK_FLOOR + 1);
    formula(ws, z, LK_ROW, f, (double)(fi + 1), ok ? NULL : "", NULL);
    worksheet_write_string(ws, LK_K, 0, "column of the mu at or below", NULL);
    snprintf(f, sizeof f, "=IF(B%d<>\"ok\",\"\",MATCH(B%d,plant_mu_grid,1))", LK_CHECK + 1,
             LK_MU + 1);
    formula(ws, z, LK_K, f, (double)(k0 + 1), ok ? NULL : "", NULL);
    worksheet_write_string(ws, LK_MU0, 0, "mu at or below", NULL);
    snprintf(f, sizeof f, "=IF(B%d<>\"ok\",\"\",INDEX(plant_mu_grid,1,B%d))", LK_CHECK + 1, LK_K + 1);
    formula(ws, z, LK_MU0, f, ds->rows[k0].mu, ok ? NULL : "", F->mu);
    worksheet_write_string(ws, LK_MU1, 0, "mu above", NULL);
    snprintf(f, sizeof f, "=IF(B%d<>\"ok\",\"\",INDEX(plant_mu_grid,1,MIN(B%d+1,%zu)))",
             LK_CHECK + 1, LK_K + 1, n);
    formula(ws, z, LK_MU1, f, ds->rows[k1].mu, ok ? NULL : "", F->mu);
    worksheet_write_string(ws, LK_C0, 0, "clearance at the mu at or below, mm", NULL);
    snprintf(f, sizeof f, "=IF(B%d<>\"ok\",\"\",INDEX(plant_clearance_mm,B%d,B%d))", LK_CHECK + 1,
             LK_ROW + 1, LK_K + 1);
    formula(ws, z, LK_C0, f, 1e3 * ds->rows[k0].clearance_m, ok ? NULL : "", F->mm);
    worksheet_write_string(ws, LK_C1, 0, "clearance at the mu above, mm", NULL);
    snprintf(f, sizeof f, "=IF(B%d<>\"ok\",\"\",INDEX(plant_clearance_mm,B%d,MIN(B%d+1,%zu)))",
             LK_CHECK + 1, LK_ROW + 1, LK_K + 1, n);
    formula(ws, z, LK_C1, f, 1e3 * ds->rows[k1].clearance_m, ok ? NULL : "", F->mm);
    snprintf(f, sizeof f, "%zu buildings, %zu floors; clearance policy %s. Each building's own "
             "workbook (<building>/seislide-clearance.xlsx) shows every floor's curves, their "
             "standard errors, flags and the assumptions.", nb, b->n,
             sl_clearance_policy_name(d0->policy));
    worksheet_merge_range(ws, LK_C1 + 2, 0, LK_C1 + 2, 1, f, F->wrap);
    worksheet_set_row(ws, LK_C1 + 2, 45, NULL);
    worksheet_set_portrait(ws);
    worksheet_fit_to_pages(ws, 1, 1);
    worksheet_activate(ws);
    protect(ws);
}

sl_status sl_plant_book_write_xlsx(const sl_plant_book *b, const char *dir, sl_error *err)
{
    char path[4400];
    snprintf(path, sizeof path, "%s/%s", dir, SL_PLANT_BOOK_XLSX);
    if (b->n == 0)
        return sl_error_set(err, SL_EINVAL, path, 0, "no floors");
    for (size_t i = 1; i < b->n; i++) {
        const sl_design *d = b->rows[i].design, *d0 = b->rows[0].design;
        int same = d->n == d0->n;
        for (size_t k = 0; same && k < d->n; k++)
            same = d->rows[k].mu == d0->rows[k].mu;
        if (!same)
            return sl_error_set(err, SL_EINVAL, path, 0, "floor '%s/%s': another friction grid",
                                b->rows[i].building, b->rows[i].id);
    }
    sl_atomic *a = sl_atomic_open(path, err);
    if (!a)
        return err ? err->code : SL_EIO;
    lxw_workbook_options wo = {.constant_memory = LXW_FALSE, .tmpdir = NULL, .use_zip64 = LXW_FALSE};
    lxw_workbook *wb = workbook_new_opt(sl_atomic_tmpname(a), &wo);
    if (!wb) {
        sl_atomic_abort(a);
        return sl_error_set(err, SL_EIO, path, 0, "cannot create the workbook");
    }
    lxw_doc_properties props;
    memset(&props, 0, sizeof props);
    props.title = "Required clearance around unanchored components, whole plant";
    props.author = "seislide";
    props.company = (char *)(uintptr_t)b->project.project;
    props.keywords = (char *)(uintptr_t)b->project.document;
    props.created = b->created > 0 ? b->created : 1; /* 0 would mean "now" */
    workbook_set_properties(wb, &props);
    fmts F;
    F.title = workbook_add_format(wb);
    format_set_bold(F.title);
    format_set_font_size(F.title, 13);
    F.bold = workbook_add_format(wb);
    format_set_bold(F.bold);
    format_set_text_wrap(F.bold);
    F.input = workbook_add_format(wb);
    format_set_unlocked(F.input);
    format_set_bg_color(F.input, 0xFFF2CC);
    format_set_border(F.input, LXW_BORDER_THIN);
    F.mm = workbook_add_format(wb);
    format_set_num_format(F.mm, "0.0");
    F.mu = workbook_add_format(wb);
    format_set_num_format(F.mu, "0.000");
    F.g = workbook_add_format(wb);
    format_set_num_format(F.g, "0.000");
    F.wrap = workbook_add_format(wb);
    format_set_text_wrap(F.wrap);
    size_t bcol, nb = 0;
    for (size_t i = 0; i < b->n; i++)
        nb += i == 0 || strcmp(b->rows[i].building, b->rows[i - 1].building) != 0;
    /* Lookup first (the sheet that opens), then the tables */
    lookup_sheet(wb, &F, b, nb);
    plant_sheet(wb, &F, b);
    data_sheet(wb, &F, b, &bcol, &nb);
    lxw_error le = workbook_close(wb);
    if (le != LXW_NO_ERROR) {
        sl_atomic_abort(a);
        return sl_error_set(err, SL_EIO, path, 0, "cannot write the workbook: %s",
                            lxw_strerror(le));
    }
    return sl_atomic_commit(a, err);
}
