/* layout.c - what every sheet shares: formats, row heights that show wrapped
 * text whole, page setup, the title block, chart axes and series, sheet
 * names (sheets.h). */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <strings.h>

#include "report/sheets.h"

/* Header/footer text limit (Excel: 255 characters) and the longest project
 * name the header shows before cutting it with "...". */
#define HF_MAX 255
#define HF_PROJECT_MAX 90
/* Row heights: points per line of the default 11-point font, and the
 * characters per line of a column w units wide. LibreOffice prints a unit
 * about 8 points wide and the font's text averages 5.5-6 points a
 * character (measured on the rendered PDF: 94 characters a line in a
 * column 72 wide); bold is wider. Rounded down, so a row errs tall. */
#define LINE_PT 15.0
/* Chart sizes: libxlsxwriter anchors a chart by its own column model, 7
 * pixels a unit plus 5, and a chart is 480 pixels wide at scale 1. */
#define XLSX_PX_PER_UNIT 7.0
#define XLSX_PX_PAD 5.0
#define XLSX_CHART_PX 480.0
#define CHARS_PER_WIDTH 1.12
#define CHARS_PER_WIDTH_BOLD 1.05
#define HEAD_CHARS_PER_WIDTH 1.1

void sl_rpt_formats(lxw_workbook *wb, sl_rpt_fmts *F)
{
    F->bold = workbook_add_format(wb);
    format_set_bold(F->bold);
    format_set_text_wrap(F->bold);
    format_set_align(F->bold, LXW_ALIGN_VERTICAL_TOP);
    F->label = workbook_add_format(wb);
    format_set_bold(F->label);
    format_set_text_wrap(F->label);
    format_set_align(F->label, LXW_ALIGN_VERTICAL_TOP);
    F->title = workbook_add_format(wb);
    format_set_bold(F->title);
    format_set_font_size(F->title, 14);
    /* numbers at the top of their rows, as the labels beside them (a label
     * wrapped to two lines does not leave its value a line below) */
    F->mm = workbook_add_format(wb);
    format_set_num_format(F->mm, "0.0");
    F->mm0 = workbook_add_format(wb);
    format_set_num_format(F->mm0, "0");
    F->mmbold = workbook_add_format(wb);
    format_set_num_format(F->mmbold, "0.0");
    format_set_bold(F->mmbold);
    F->mm0bold = workbook_add_format(wb);
    format_set_num_format(F->mm0bold, "0");
    format_set_bold(F->mm0bold);
    F->ratio = workbook_add_format(wb);
    format_set_num_format(F->ratio, "0.000");
    F->sci = workbook_add_format(wb);
    format_set_num_format(F->sci, "0.0E+00");
    F->mu = workbook_add_format(wb);
    format_set_num_format(F->mu, "0.00");
    F->dxf_mm0 = workbook_add_format(wb);
    format_set_num_format(F->dxf_mm0, "0");
    lxw_format *top[] = {F->mm, F->mm0, F->mmbold, F->mm0bold, F->ratio, F->sci, F->mu};
    for (size_t k = 0; k < sizeof top / sizeof top[0]; k++)
        format_set_align(top[k], LXW_ALIGN_VERTICAL_TOP);
    F->wrap = workbook_add_format(wb);
    format_set_text_wrap(F->wrap);
    format_set_align(F->wrap, LXW_ALIGN_VERTICAL_TOP);
    F->note = workbook_add_format(wb);
    format_set_text_wrap(F->note);
    format_set_align(F->note, LXW_ALIGN_VERTICAL_TOP);
    F->title_wrap = workbook_add_format(wb);
    format_set_bold(F->title_wrap);
    format_set_font_size(F->title_wrap, 14);
    format_set_text_wrap(F->title_wrap);
    format_set_align(F->title_wrap, LXW_ALIGN_VERTICAL_TOP);
    F->result = workbook_add_format(wb);
    format_set_bold(F->result);
    format_set_font_size(F->result, 14);
    format_set_num_format(F->result, "0.0");
    format_set_bg_color(F->result, 0xE2EFDA);
    format_set_border(F->result, LXW_BORDER_THIN);
    format_set_align(F->result, LXW_ALIGN_LEFT);
    F->input = workbook_add_format(wb);
    format_set_bg_color(F->input, 0xFFF2CC);
    format_set_border(F->input, LXW_BORDER_THIN);
    format_set_unlocked(F->input);
    format_set_align(F->input, LXW_ALIGN_LEFT);
    F->header = workbook_add_format(wb);
    format_set_bold(F->header);
    format_set_text_wrap(F->header);
    format_set_align(F->header, LXW_ALIGN_VERTICAL_TOP);
    format_set_bottom(F->header, LXW_BORDER_THIN);
    F->header_num = workbook_add_format(wb); /* a heading over numbers: at their right */
    format_set_bold(F->header_num);
    format_set_text_wrap(F->header_num);
    format_set_align(F->header_num, LXW_ALIGN_VERTICAL_TOP);
    format_set_align(F->header_num, LXW_ALIGN_RIGHT);
    format_set_bottom(F->header_num, LXW_BORDER_THIN);
    F->header_ind = workbook_add_format(wb); /* a text heading after a number's */
    format_set_bold(F->header_ind);
    format_set_text_wrap(F->header_ind);
    format_set_align(F->header_ind, LXW_ALIGN_VERTICAL_TOP);
    format_set_bottom(F->header_ind, LXW_BORDER_THIN);
    format_set_indent(F->header_ind, 1);
    F->text_right = workbook_add_format(wb);
    format_set_text_wrap(F->text_right);
    format_set_align(F->text_right, LXW_ALIGN_VERTICAL_TOP);
    format_set_align(F->text_right, LXW_ALIGN_RIGHT);
    F->indent = workbook_add_format(wb); /* text after a number: kept off it */
    format_set_text_wrap(F->indent);
    format_set_align(F->indent, LXW_ALIGN_VERTICAL_TOP);
    format_set_indent(F->indent, 1);
    F->warn = workbook_add_format(wb);
    format_set_bold(F->warn);
    format_set_text_wrap(F->warn);
    format_set_align(F->warn, LXW_ALIGN_VERTICAL_TOP);
    format_set_font_color(F->warn, 0xC00000);
}

/* Lines of s word-wrapped at cpl characters ('\n' breaks; a word longer
 * than a line takes as many lines as it needs). */
static int wrapped_lines(const char *s, int cpl)
{
    int lines = 1, col = 0;
    if (cpl < 1)
        cpl = 1;
    for (const char *p = s; *p;) {
        if (*p == '\n') {
            lines++;
            col = 0;
            p++;
            continue;
        }
        if (*p == ' ') {
            p++;
            if (col)
                col++;
            continue;
        }
        int len = 0;
        while (p[len] && p[len] != ' ' && p[len] != '\n')
            len++;
        if (col && col + len > cpl) {
            lines++;
            col = 0;
        }
        while (len > cpl) { /* a word longer than the line breaks anywhere */
            lines++;
            len -= cpl;
            p += cpl;
        }
        col += len;
        p += len;
    }
    return lines;
}

double sl_rpt_chart_scale(const double *width, size_t n)
{
    double px = 0;
    for (size_t c = 0; c < n; c++)
        px += XLSX_PX_PER_UNIT * width[c] + XLSX_PX_PAD;
    return 0.98 * px / XLSX_CHART_PX;
}

double sl_rpt_text_height(const char *s, double width, int bold)
{
    int cpl = (int)floor(width * (bold ? CHARS_PER_WIDTH_BOLD : CHARS_PER_WIDTH)) - 1;
    return LINE_PT * wrapped_lines(s ? s : "", cpl) + 1.0;
}

/* Characters (not bytes) of the UTF-8 text s[0..len). */
static size_t utf8_chars(const char *s, size_t len)
{
    size_t c = 0;
    for (size_t k = 0; k < len; k++)
        c += ((unsigned char)s[k] & 0xC0) != 0x80;
    return c;
}

/* s broken at blanks into lines of at most max characters (a longer word
 * alone on its line) into buf (NULL: only counted); returns the lines. */
static int break_lines(const char *s, size_t max, char *buf, size_t n)
{
    size_t k = 0, col = 0;
    int lines = 1;
    for (const char *p = s; *p;) {
        if (*p == ' ') {
            p++;
            continue;
        }
        size_t len = strcspn(p, " "), w = utf8_chars(p, len);
        if (buf && len + 2 > n - k)
            break;
        char sep = col ? (col + 1 + w > max ? '\n' : ' ') : 0;
        if (sep) {
            lines += sep == '\n';
            col = sep == '\n' ? 0 : col + 1;
            if (buf)
                buf[k++] = sep;
        }
        if (buf)
            memcpy(buf + k, p, len);
        k += len;
        col += w;
        p += len;
    }
    if (buf && n)
        buf[k < n ? k : n - 1] = '\0';
    return lines;
}

char *sl_rpt_header_text(const char *s, double width, char *buf, size_t n)
{
    /* a line a character short of what LibreOffice fits in bold (measured:
     * "cap (1.5 x" fits in a column 8.5 wide, "ASCE best" and "clearance,"
     * do not: letters are wider than blanks and brackets), then as short as
     * the same number of lines allows: balanced lines, no word left alone */
    size_t max = (size_t)fmax(1, floor(HEAD_CHARS_PER_WIDTH * width) - 1);
    char kept[1200]; /* a number and its unit: one word */
    sl_rpt_keep_units(s, kept, sizeof kept);
    int lines = break_lines(kept, max, NULL, 0);
    while (max > 1 && break_lines(kept, max - 1, NULL, 0) == lines)
        max--;
    break_lines(kept, max, buf, n);
    return buf;
}

/* Text for a header/footer: '&' doubled (Excel's escape), cut to max
 * characters (UTF-8: whole characters) with "..." (buf of size n > 4 max + 4). */
static void hf_escape(const char *s, size_t max, char *buf, size_t n)
{
    size_t k = 0, shown = 0;
    for (; s && *s && k + 5 < n; s++) {
        if ((*s & 0xC0) != 0x80 && shown++ == max) { /* not inside a character */
            strcpy(buf + k, "...");
            return;
        }
        if (*s == '&')
            buf[k++] = '&';
        buf[k++] = *s == '\n' || *s == '\r' ? ' ' : *s;
    }
    buf[k] = '\0';
}

void sl_rpt_page_setup(lxw_worksheet *ws, const sl_report *r, int landscape,
                       const char *failed_ids)
{
    char proj[4 * HF_PROJECT_MAX + 8], doc[140], rev[120], ids[180], h[4 * HF_MAX + 260], ver[260],
        bld[4 * HF_PROJECT_MAX + 32] = "";
    const sl_report_project *p = &r->project;
    hf_escape(p->project && *p->project ? p->project : "not given",
              HF_PROJECT_MAX, proj, sizeof proj);
    hf_escape(p->document && *p->document ? p->document : "not given", 30, doc,
              sizeof doc);
    hf_escape(p->revision && *p->revision ? p->revision : "not given", 24, rev,
              sizeof rev);
    hf_escape(failed_ids, 40, ids, sizeof ids);
    hf_escape(r->version, 60, ver, sizeof ver);
    if (r->building && *r->building) { /* a plant's building: on every page, beside the sheet */
        char b[4 * HF_PROJECT_MAX + 8];
        hf_escape(r->building, HF_PROJECT_MAX / 2, b, sizeof b);
        snprintf(bld, sizeof bld, "Building %s: ", b);
    }
    worksheet_set_paper(ws, 9); /* A4 */
    worksheet_set_margins(ws, 0.5, 0.5, 0.85, 0.75);
    if (landscape)
        worksheet_set_landscape(ws);
    else
        worksheet_set_portrait(ws);
    /* left: who and what (two lines), right: the sheet, and the floors whose
     * motions failed their checks; nothing in the centre to run into */
    snprintf(h, sizeof h, "&L&8Project: %s\nDocument %s, revision %s&R&8%s&A%s%s", proj, doc, rev,
             bld, ids[0] ? "\n&\"-,Bold\"checks failed: " : "", ids);
    worksheet_set_header(ws, h);
    snprintf(h, sizeof h, "&L&8%s&C&8&F&R&8Page &P of &N", ver);
    worksheet_set_footer(ws, h);
}

void sl_rpt_protect(lxw_worksheet *ws)
{
    lxw_protection p;
    memset(&p, 0, sizeof p);
    worksheet_protect(ws, NULL, &p); /* no password: a guard against typing over, not a lock */
}

void sl_rpt_title_block(lxw_worksheet *ws, const sl_rpt_fmts *F, const sl_report *r,
                        const char *title, lxw_col_t c, lxw_col_t c_last, double width)
{
    char full[1200];
    if (r->building && *r->building) { /* a plant's building names its workbook: a second
                                        * line of the title (14 points), wrapped over the
                                        * printed columns when it is long */
        snprintf(full, sizeof full, "%s\nBuilding %s", title, r->building);
        worksheet_merge_range(ws, 0, c, 0, c_last, full, F->title_wrap);
        snprintf(full, sizeof full, "Building %s", r->building);
        worksheet_set_row(ws, 0, (LINE_PT + sl_rpt_text_height(full, width * 11.0 / 14.0, 1)) *
                          14.0 / 11.0, NULL);
    } else {
        worksheet_write_string(ws, 0, c, title, F->title);
    }
    const char *const label[] = {"Project", "Document no.", "Revision", "Prepared by",
                                 "Checked by", "Date", "Units"};
    const char *const value[] = {r->project.project, r->project.document, r->project.revision,
                                 r->project.prepared, r->project.checked, r->project.date,
                                 "displacements and clearances in mm, accelerations in g, "
                                 "mu dimensionless"};
    for (lxw_row_t i = 0; i < SL_RPT_TB_ROWS - 1; i++) {
        const char *v = sl_rpt_or_dash(value[i]);
        worksheet_write_string(ws, i + 1, c, label[i], F->label);
        if (c_last > c + 1)
            worksheet_merge_range(ws, i + 1, c + 1, i + 1, c_last, v, F->note);
        else
            worksheet_write_string(ws, i + 1, c + 1, v, F->note);
        worksheet_set_row(ws, i + 1, sl_rpt_text_height(v, width, 0), NULL);
    }
}

void sl_rpt_warn_row(lxw_worksheet *ws, const sl_rpt_fmts *F, const char *ids,
                     const char *where, const char *wl, lxw_col_t c_last, double width)
{
    char buf[2400];
    if (ids[0])
        snprintf(buf, sizeof buf, "CHECKS FAILED: motions of floor(s) %s failed their SRP 3.7.1 "
                 "checks; their results were kept by --accept-failed-checks (%s)%s%s", ids,
                 where, wl[0] ? ". " : "", wl);
    else if (wl[0])
        snprintf(buf, sizeof buf, "%s", wl);
    else
        return;
    worksheet_merge_range(ws, SL_RPT_WARN_ROW, 0, SL_RPT_WARN_ROW, c_last, buf, F->warn);
    worksheet_set_row(ws, SL_RPT_WARN_ROW, sl_rpt_text_height(buf, width, 1), NULL);
}

void sl_rpt_col_name(size_t c, char *buf)
{
    char tmp[8];
    int k = 0;
    c++;
    while (c > 0) {
        tmp[k++] = (char)('A' + (c - 1) % 26);
        c = (c - 1) / 26;
    }
    for (int i = 0; i < k; i++)
        buf[i] = tmp[k - 1 - i];
    buf[k] = '\0';
}

void sl_rpt_num_or_blank(lxw_worksheet *ws, lxw_row_t row, lxw_col_t col, double v,
                         lxw_format *f)
{
    if (isfinite(v))
        worksheet_write_number(ws, row, col, v, f);
    else
        worksheet_write_blank(ws, row, col, f);
}

sl_rpt_axes sl_rpt_shared_axes(const sl_report *r)
{
    sl_rpt_axes a = {r->floors[0].design->rows[0].mu, 0, HUGE_VAL, 0};
    size_t n = r->floors[0].design->n;
    a.mu_max = r->floors[0].design->rows[n - 1].mu;
    for (size_t i = 0; i < r->n_floors; i++)
        for (size_t k = 0; k < n; k++) {
            const sl_design_row *w = &r->floors[i].design->rows[k];
            const double v[] = {w->nltha_design_m, w->asce_design_m, w->nltha_mean_m, w->cap_m};
            for (size_t c = 0; c < 4; c++)
                if (isfinite(v[c]) && v[c] > 0) {
                    a.y_min = fmin(a.y_min, SL_RPT_MM_PER_M * v[c]);
                    a.y_max = fmax(a.y_max, SL_RPT_MM_PER_M * v[c]);
                }
        }
    if (!(a.y_max > 0)) {
        a.y_min = 1;
        a.y_max = 10;
    }
    a.y_min = fmax(SL_RPT_CHART_MIN_MM, pow(10, floor(log10(a.y_min))));
    /* a power of ten at least twice the largest value: a cap of 987 mm is
     * drawn a third of a decade below the 1,000 mm line, not along the top
     * edge of a 1,000 mm axis */
    a.y_max = pow(10, ceil(log10(SL_RPT_CHART_HEADROOM * a.y_max)));
    if (a.y_max <= a.y_min)
        a.y_max = 10 * a.y_min;
    return a;
}

void sl_rpt_chart_axes(lxw_chart *ch, const sl_rpt_axes *ax, const char *quantity)
{
    char y[200];
    snprintf(y, sizeof y, "%s, mm (log scale)", quantity);
    chart_axis_set_name(ch->x_axis, "friction coefficient mu");
    chart_axis_set_name(ch->y_axis, y);
    chart_axis_set_min(ch->x_axis, ax->mu_min);
    chart_axis_set_max(ch->x_axis, ax->mu_max);
    chart_axis_set_num_format(ch->x_axis, "0.00");
    chart_axis_set_log_base(ch->y_axis, 10);
    chart_axis_set_min(ch->y_axis, ax->y_min);
    chart_axis_set_max(ch->y_axis, ax->y_max);
    chart_axis_set_num_format(ch->y_axis, "#,##0.#");
    chart_axis_set_crossing(ch->y_axis, ax->y_min); /* x axis at the bottom */
    /* thin light gridlines, under the curves: a curve on one stays visible */
    lxw_chart_line grid = {.color = 0xD9D9D9, .width = 0.5f};
    chart_axis_major_gridlines_set_visible(ch->y_axis, LXW_TRUE);
    chart_axis_major_gridlines_set_line(ch->y_axis, &grid);
    chart_legend_set_position(ch, LXW_CHART_LEGEND_BOTTOM);
}

void sl_rpt_add_series(lxw_chart *ch, const char *sheet, lxw_col_t xc, lxw_col_t yc,
                       lxw_row_t r0, lxw_row_t r1, const char *name, lxw_color_t color,
                       float width, uint8_t dash, uint8_t transparency)
{
    char xr[128], yr[128], a[8], b[8];
    sl_rpt_col_name(xc, a);
    sl_rpt_col_name(yc, b);
    snprintf(xr, sizeof xr, "='%s'!$%s$%u:$%s$%u", sheet, a, (unsigned)r0 + 1, a, (unsigned)r1 + 1);
    snprintf(yr, sizeof yr, "='%s'!$%s$%u:$%s$%u", sheet, b, (unsigned)r0 + 1, b, (unsigned)r1 + 1);
    lxw_chart_series *s = chart_add_series(ch, xr, yr);
    chart_series_set_name(s, name);
    lxw_chart_line line = {.color = color, .width = width, .dash_type = dash,
                           .transparency = transparency};
    chart_series_set_line(s, &line);
    chart_series_set_marker_type(s, LXW_CHART_MARKER_NONE);
}

/* The units a number is kept with (sl_rpt_keep_units). */
static const char *const UNITS[] = {"g", "m", "mm", "cm", "km", "s", "ms", "Hz", "%", "kg", "t",
                                    "kN", "N", "m/s", "m/s2", "cm/s2", "in", "ft", "Gal"};

char *sl_rpt_keep_units(const char *s, char *buf, size_t n)
{
    size_t k = 0;
    if (!n)
        return buf;
    for (const char *p = s ? s : ""; *p && k + 3 < n; p++) {
        int nb = 0;
        if (*p == ' ' && p > s && p[-1] >= '0' && p[-1] <= '9') {
            size_t len = strcspn(p + 1, " ,;:)]\n");
            for (size_t u = 0; !nb && u < sizeof UNITS / sizeof UNITS[0]; u++)
                nb = len == strlen(UNITS[u]) && !strncmp(p + 1, UNITS[u], len);
        }
        if (nb) { /* U+00A0 */
            buf[k++] = (char)0xC2;
            buf[k++] = (char)0xA0;
        } else {
            buf[k++] = *p;
        }
    }
    buf[k] = '\0';
    return buf;
}

char *sl_rpt_shown_path(const char *path, char *buf, size_t n)
{
    if (!path || path[0] != '/') {
        snprintf(buf, n, "%s", path ? path : "-");
        return buf;
    }
    const char *p = path + strlen(path);
    for (int parts = 0; p > path; p--) /* the start of the last two parts */
        if (p[-1] == '/' && ++parts == 2)
            break;
    snprintf(buf, n, p > path ? ".../%s" : "%s", p > path ? p : path);
    return buf;
}

int sl_rpt_command_lines(const char *cmd, size_t width, char *buf, size_t n)
{
    size_t k = 0, col = 0;
    int lines = 1;
    if (!n)
        return 0;
    buf[0] = '\0';
    for (const char *p = cmd ? cmd : ""; *p;) {
        while (*p == ' ')
            p++;
        if (!*p)
            break;
        const char *e = p; /* a word: up to a blank outside single quotes */
        for (int q = 0; *e && (q || *e != ' '); e++)
            q ^= *e == '\'';
        size_t len = (size_t)(e - p), w = utf8_chars(p, len);
        if (col && col + 1 + w + 2 > width) { /* " \" ends the line */
            if (k + 3 >= n)
                break;
            memcpy(buf + k, " \\\n", 3);
            k += 3;
            col = 0;
            lines++;
        } else if (col) {
            if (k + 1 >= n)
                break;
            buf[k++] = ' ';
            col++;
        }
        if (k + len >= n)
            break;
        memcpy(buf + k, p, len);
        k += len;
        col += w;
        p = e;
    }
    buf[k < n ? k : n - 1] = '\0';
    return lines;
}

/* The sheet name of an id: Excel's forbidden characters []:*?/\ and an
 * apostrophe at either end made '_', cut at 31 characters (counted as
 * Excel counts them: a character beyond U+FFFF is two). */
static void sheet_name(const char *id, char *buf)
{
    size_t k = 0, chars = 0;
    for (const char *p = id; *p;) {
        size_t c = sl_report_utf8_len(p), w = c > 3 ? 2 : 1;
        if (chars + w > SL_RPT_SHEET_NAME_MAX)
            break;
        if (c > 1) {
            memcpy(buf + k, p, c);
            k += c;
            p += c;
        } else {
            buf[k++] = c && !strchr("[]:*?/\\", *p) ? *p : '_';
            p++;
        }
        chars += w;
    }
    buf[k] = '\0';
    if (buf[0] == '\'')
        buf[0] = '_';
    if (k && buf[k - 1] == '\'')
        buf[k - 1] = '_';
}

void sl_rpt_sheet_names(const sl_report *r, char (*names)[SL_RPT_SHEET_NAME_MAX * 4 + 1])
{
    static const char *const other[] = {"Lookup", "Summary", "Motion quality", "Notes",
                                        "Inputs", "Data", "History"};
    int use_ids = 1;
    for (size_t i = 0; i < r->n_floors; i++)
        sheet_name(r->floors[i].id, names[i]);
    for (size_t i = 0; i < r->n_floors && use_ids; i++) {
        use_ids = names[i][0] != '\0';
        for (size_t k = 0; k < sizeof other / sizeof other[0] && use_ids; k++)
            use_ids = strcasecmp(names[i], other[k]) != 0;
        for (size_t j = 0; j < i && use_ids; j++) /* Excel compares without case */
            use_ids = strcasecmp(names[i], names[j]) != 0;
    }
    for (size_t i = 0; i < r->n_floors && !use_ids; i++)
        snprintf(names[i], SL_RPT_SHEET_NAME_MAX + 1, "F%zu", i + 1);
}
