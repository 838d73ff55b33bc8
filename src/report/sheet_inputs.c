/* sheet_inputs.c - the "Inputs" sheet: what reproduces the workbook (program,
 * command, creation time, seed and settings, floor files with CRC-32). */
#include <stdio.h>
#include <time.h>

#include "report/sheets.h"

/* 96 units: a landscape A4 page at 100 % (about 8 points a unit) */
#define W_NAME 24.0
#define W_VALUE 36.0
#define W_REST 36.0 /* id 12, units 6, bytes 8, CRC-32 10 */
/* Characters of a line of the command (the value's 72 units: no line
 * wraps again, so no option is broken at its hyphens) */
#define CMD_CHARS 70

void sl_rpt_inputs_sheet(lxw_workbook *wb, const sl_rpt_fmts *F, const sl_report *r)
{
    lxw_worksheet *ws = workbook_add_worksheet(wb, "Inputs");
    worksheet_set_column(ws, 0, 0, W_NAME, NULL);
    worksheet_set_column(ws, 1, 1, W_VALUE, NULL);
    worksheet_set_column(ws, 2, 2, 12, NULL);
    worksheet_set_column(ws, 3, 3, 6, NULL);
    worksheet_set_column(ws, 4, 4, 8, NULL);
    worksheet_set_column(ws, 5, 5, 10, NULL);
    char buf[1200], ids[400];
    lxw_row_t row = 0;
    worksheet_write_string(ws, row++, 0, "What reproduces this workbook", F->title);
    for (size_t i = 0; i < r->n_floors; i++)
        if (r->floors[i].n_failed_motions) {
            sl_rpt_failed_text(r, &r->floors[i], buf, sizeof buf);
            worksheet_merge_range(ws, row, 0, row, 5, buf, F->warn);
            worksheet_set_row(ws, row++, sl_rpt_text_height(buf, W_NAME + W_VALUE + W_REST, 1), NULL);
        }
    char created[64];
    struct tm tmv;
    gmtime_r(&r->created, &tmv);
    strftime(created, sizeof created, "%Y-%m-%dT%H:%M:%SZ", &tmv);
    const sl_report_setting fixed[] = {{"program", r->version},
                                       {"command", r->command_line ? r->command_line : ""},
                                       {"created (UTC)", created}};
    /* the command as lines broken between its words, each but the last
     * ending in " \\": copied from the cell it runs as one command */
    char cmd[6000];
    sl_rpt_command_lines(r->command_line ? r->command_line : "", CMD_CHARS, cmd, sizeof cmd);
    if (r->building && *r->building) { /* a plant's building: named before the record */
        worksheet_write_string(ws, row, 0, "building", F->label);
        worksheet_merge_range(ws, row, 1, row, 5, r->building, F->note);
        worksheet_set_row(ws, row++, sl_rpt_text_height(r->building, W_VALUE + W_REST, 0), NULL);
    }
    for (size_t s = 0; s < 3 + r->n_settings; s++) {
        const sl_report_setting *e = s < 3 ? &fixed[s] : &r->settings[s - 3];
        const char *v = s == 1 ? cmd : sl_rpt_or_dash(e->value);
        worksheet_write_string(ws, row, 0, e->name, F->label);
        worksheet_merge_range(ws, row, 1, row, 5, v, F->note);
        worksheet_set_row(ws, row++, sl_rpt_text_height(v, W_VALUE + W_REST, 0), NULL);
    }
    row++;
    static const char *const head[] = {"floor", "file", "id", "units", "bytes", "CRC-32"};
    for (lxw_col_t c = 0; c < 6; c++) /* bytes at its numbers' right, CRC-32 kept off it */
        worksheet_write_string(ws, row, c, head[c], c == 4 ? F->header_num : c == 5
                               ? F->header_ind : F->header);
    row++;
    for (size_t i = 0; i < r->n_floors; i++) {
        const sl_report_floor *fl = &r->floors[i];
        char name[600];
        worksheet_write_string(ws, row, 0, sl_rpt_keep_units(fl->name, name, sizeof name),
                               F->wrap);
        char path[1100];
        sl_rpt_shown_path(fl->path, path, sizeof path);
        worksheet_write_string(ws, row, 1, path, F->wrap);
        worksheet_write_string(ws, row, 2, fl->id, F->wrap);
        worksheet_write_string(ws, row, 3, sl_rpt_or_dash(fl->units), F->wrap); /* all at the top */
        worksheet_write_number(ws, row, 4, (double)fl->size_bytes, F->wrap);
        snprintf(buf, sizeof buf, "%08lx", fl->crc32 & 0xffffffffUL);
        worksheet_write_string(ws, row, 5, buf, F->indent);
        double h = sl_rpt_text_height(fl->name, W_NAME, 0);
        h = h > sl_rpt_text_height(path, W_VALUE, 0) ? h : sl_rpt_text_height(path, W_VALUE, 0);
        h = h > sl_rpt_text_height(fl->id, 12, 0) ? h : sl_rpt_text_height(fl->id, 12, 0);
        worksheet_set_row(ws, row++, h, NULL);
    }
    sl_rpt_page_setup(ws, r, 1, sl_rpt_failed_ids(r, ids, sizeof ids));
    worksheet_fit_to_pages(ws, 1, 0);
    sl_rpt_protect(ws);
}
