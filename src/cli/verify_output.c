/* verify_output.c - the record of `seislide verify` (verify_output.h):
 * verification.csv, one row per problem, and verification.xlsx, one A4
 * landscape sheet fitted to the page width with the table's header on every
 * page, the run's identity above it and signature lines below. */
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "io/atomic.h"
#include "report/sheets.h"
#include "verify_output.h"

static const char *const columns[] = {"area",     "problem",  "checks",          "reference",
                                      "reference_source", "computed", "error", "tolerance",
                                      "tolerance_basis",  "verdict"};
#define NCOL 10
/* column widths of the sheet, characters: at least these, and wide enough
 * for the longest word of the column (a number or a hash is one word:
 * printed whole, never broken across lines) */
static const double widths_min[NCOL] = {8, 7, 34, 13, 38, 13, 10, 10, 34, 7};
#define WORD_WIDTH(len) (0.95 * (double)(len) + 1.5) /* LibreOffice's 11-point text */

/* The longest run of characters without a blank in s. */
static size_t longest_word(const char *s)
{
    size_t best = 0, cur = 0;
    for (; *s; s++) {
        if (*s == ' ' || *s == '\n') {
            cur = 0;
            continue;
        }
        if ((*s & 0xC0) != 0x80 && ++cur > best) /* characters, not bytes */
            best = cur;
    }
    return best;
}

/* One RFC 4180 field (sl_rpt_csv_field), then ',' or, after the last, CRLF
 * (as every CSV of the project). */
static void csv_field(FILE *f, const char *s, int last)
{
    sl_rpt_csv_field(f, s);
    fputs(last ? "\r\n" : ",", f);
}

/* The explanations installed by `make install` (Makefile), relative to the
 * program's PREFIX/bin. */
#define DOCS_INSTALLED "share/doc/seislide/verification.md"

static int is_file(const char *path)
{
    struct stat sb;
    return stat(path, &sb) == 0 && S_ISREG(sb.st_mode);
}

void verify_docs_path(char *buf, size_t n)
{
    char exe[1024], cand[1300];
    ssize_t len = readlink("/proc/self/exe", exe, sizeof exe - 1);
    if (len > 0) {
        exe[len] = '\0';
        char *slash = strrchr(exe, '/');
        if (slash) {
            *slash = '\0'; /* the program's folder */
            const char *bin = strrchr(exe, '/');
            if (bin && !strcmp(bin + 1, "bin")) { /* PREFIX/bin/seislide */
                snprintf(cand, sizeof cand, "%.*s/%s", (int)(bin - exe), exe, DOCS_INSTALLED);
                if (is_file(cand)) {
                    snprintf(buf, n, "%s", cand);
                    return;
                }
            }
            snprintf(cand, sizeof cand, "%s/docs/verification.md", exe); /* a source tree */
            if (is_file(cand)) {
                snprintf(buf, n, "%s", cand);
                return;
            }
        }
    }
    snprintf(buf, n, "docs/verification.md of the program's source (not installed beside this "
             "program: make install puts it in PREFIX/" DOCS_INSTALLED ")");
}

static void row_texts(const sl_verify_result *r, const char *t[NCOL])
{
    const sl_verify_problem *p = r->problem;
    t[0] = p->area;
    t[1] = p->id;
    t[2] = p->checks;
    t[3] = r->reference;
    t[4] = p->reference_source;
    t[5] = r->computed;
    t[6] = r->error_text;
    t[7] = r->tolerance_text;
    t[8] = p->tolerance_basis;
    t[9] = r->pass ? "pass" : "fail";
}

static sl_status write_csv(const char *path, const verify_info *info,
                           const sl_verify_result *res, size_t n, sl_error *err)
{
    sl_atomic *a = sl_atomic_open(path, err);
    if (!a)
        return err->code;
    FILE *f = sl_atomic_file(a);
    /* the trace lines every CSV of the project starts with (csv.c), then the build */
    sl_report rep;
    sl_report_init(&rep);
    rep.version = info->version;
    rep.command_line = info->command;
    rep.created = info->created;
    sl_rpt_csv_head(f, &rep, "the verification of this installed program: one row per "
                    "problem, its independent reference, the computed value and the verdict");
    char buf[1400];
    snprintf(buf, sizeof buf, "%s; flags %s", info->compiler, info->flags);
    sl_rpt_csv_comment(f, "build", buf);
    sl_rpt_csv_comment(f, "vector_instances", info->vector);
    sl_rpt_csv_comment(f, "host", info->host);
    sl_rpt_csv_comment(f, "checked_by", info->checked_by);
    snprintf(buf, sizeof buf, "%zu passed, %zu failed%s", info->n_pass, info->n_fail,
             info->quick ? " (the quick subset, --quick)" : "");
    sl_rpt_csv_comment(f, "result", buf);
    sl_rpt_csv_comment(f, "explanations", info->docs);
    for (int c = 0; c < NCOL; c++)
        csv_field(f, columns[c], c == NCOL - 1);
    for (size_t i = 0; i < n; i++) {
        const char *t[NCOL];
        row_texts(&res[i], t);
        for (int c = 0; c < NCOL; c++)
            csv_field(f, t[c], c == NCOL - 1);
    }
    return sl_atomic_commit(a, err);
}

static sl_status write_xlsx(const char *path, const verify_info *info,
                            const sl_verify_result *res, size_t n, sl_error *err)
{
    sl_atomic *a = NULL;
    const sl_report_project project = {NULL, NULL, NULL, NULL, info->checked_by, NULL};
    lxw_workbook *wb = sl_rpt_workbook_open(path, "seislide verification record",
                                            "installation verification", &project, time(NULL),
                                            &a, err);
    if (!wb)
        return err->code;
    lxw_worksheet *ws = workbook_add_worksheet(wb, "Verification");
    lxw_format *title = workbook_add_format(wb), *bold = workbook_add_format(wb),
               *head = workbook_add_format(wb), *cell = workbook_add_format(wb),
               *fail = workbook_add_format(wb), *line = workbook_add_format(wb);
    format_set_bold(title);
    format_set_font_size(title, 14);
    format_set_bold(bold);
    format_set_bold(head);
    format_set_text_wrap(head);
    format_set_bg_color(head, 0xDDDDDD);
    format_set_border(head, LXW_BORDER_THIN);
    format_set_align(head, LXW_ALIGN_VERTICAL_TOP);
    format_set_text_wrap(cell);
    format_set_border(cell, LXW_BORDER_THIN);
    format_set_align(cell, LXW_ALIGN_VERTICAL_TOP);
    format_set_text_wrap(fail);
    format_set_border(fail, LXW_BORDER_THIN);
    format_set_align(fail, LXW_ALIGN_VERTICAL_TOP);
    format_set_bold(fail);
    format_set_font_color(fail, LXW_COLOR_RED);
    format_set_bottom(line, LXW_BORDER_THIN);
    lxw_format *wrap = workbook_add_format(wb);
    format_set_text_wrap(wrap);
    format_set_align(wrap, LXW_ALIGN_VERTICAL_TOP);
    double widths[NCOL], total_width = 0;
    for (int c = 0; c < NCOL; c++) {
        widths[c] = widths_min[c];
        if (WORD_WIDTH(longest_word(columns[c])) > widths[c])
            widths[c] = WORD_WIDTH(longest_word(columns[c]));
        for (size_t i = 0; i < n; i++) {
            const char *t[NCOL];
            row_texts(&res[i], t);
            double w = WORD_WIDTH(longest_word(t[c]));
            widths[c] = w > widths[c] ? w : widths[c];
        }
        total_width += widths[c];
    }

    for (int c = 0; c < NCOL; c++)
        worksheet_set_column(ws, (lxw_col_t)c, (lxw_col_t)c, widths[c], NULL);
    worksheet_set_paper(ws, 9); /* A4 */
    worksheet_set_landscape(ws);
    worksheet_set_margins(ws, 0.4, 0.4, 0.6, 0.6);
    worksheet_fit_to_pages(ws, 1, 0);
    char footer[200];
    snprintf(footer, sizeof footer, "&L&8 %s verify&C&8 %s&R&8 Page &P of &N", info->version,
             info->date);
    worksheet_set_footer(ws, footer);

    lxw_row_t r = 0;
    worksheet_write_string(ws, r++, 0, "Verification of seislide on this machine", title);
    char result[96];
    snprintf(result, sizeof result, "%zu passed, %zu failed%s", info->n_pass, info->n_fail,
             info->quick ? " (the quick subset, --quick)" : "");
    const char *keys[] = {"Program", "Build", "Flags", "Vector instances", "Host", "Date",
                          "Checked by", "Command", "Result"};
    const char *vals[] = {info->version, info->compiler, info->flags, info->vector, info->host,
                          info->date, info->checked_by, info->command, result};
    for (size_t k = 0; k < sizeof keys / sizeof keys[0]; k++, r++) {
        worksheet_merge_range(ws, r, 2, r, NCOL - 1, vals[k], NULL);
        worksheet_merge_range(ws, r, 0, r, 1, keys[k], bold);
    }
    r++;
    const lxw_row_t head_row = r;
    for (int c = 0; c < NCOL; c++)
        worksheet_write_string(ws, r, (lxw_col_t)c, columns[c], head);
    worksheet_repeat_rows(ws, head_row, head_row);
    r++;
    for (size_t i = 0; i < n; i++, r++) {
        const char *t[NCOL];
        row_texts(&res[i], t);
        double h = 15;
        for (int c = 0; c < NCOL; c++) {
            worksheet_write_string(ws, r, (lxw_col_t)c, t[c],
                                   c == NCOL - 1 && !res[i].pass ? fail : cell);
            double hc = sl_rpt_text_height(t[c], widths[c], 0);
            h = hc > h ? hc : h;
        }
        worksheet_set_row(ws, r, h, NULL);
    }
    r += 2;
    char expl[1400];
    snprintf(expl, sizeof expl, "Every problem's reference and tolerance is explained in %s.",
             info->docs);
    worksheet_merge_range(ws, r, 0, r, NCOL - 1, expl, wrap);
    worksheet_set_row(ws, r++, sl_rpt_text_height(expl, total_width, 0), NULL);
    r++;
    const char *sig[] = {"Run and checked by (name, signature, date):",
                         "Reviewed by (name, signature, date):"};
    for (int k = 0; k < 2; k++, r += 2) {
        worksheet_merge_range(ws, r, 0, r, 2, sig[k], bold);
        worksheet_merge_range(ws, r, 3, r, 7, "", line);
    }
    worksheet_print_area(ws, 0, 0, r, NCOL - 1);
    return sl_rpt_workbook_close(wb, a, path, err);
}

sl_status verify_write_record(const char *dir, const verify_info *info,
                              const sl_verify_result *res, size_t n, sl_error *err)
{
    char path[1200];
    snprintf(path, sizeof path, "%s/verification.csv", dir);
    sl_status st = write_csv(path, info, res, n, err);
    if (st != SL_OK)
        return st;
    snprintf(path, sizeof path, "%s/verification.xlsx", dir);
    return write_xlsx(path, info, res, n, err);
}
