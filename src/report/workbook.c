/* workbook.c - a workbook written through sl_atomic (io/atomic.h: a hidden
 * temporary file renamed over the final name, so that a failed run leaves
 * no half-written workbook), with its document properties; shared by the
 * building workbook (report.c) and the plant workbook (plant_book.c). */
#include <stdint.h>
#include <string.h>

#include "report/sheets.h"

lxw_workbook *sl_rpt_workbook_open(const char *path, const char *title, const char *subject,
                                   const sl_report_project *project, time_t created,
                                   sl_atomic **a, sl_error *err)
{
    *a = sl_atomic_open(path, err);
    if (!*a)
        return NULL;
    lxw_workbook_options wo = {.constant_memory = LXW_FALSE, .tmpdir = NULL,
                               .use_zip64 = LXW_FALSE};
    lxw_workbook *wb = workbook_new_opt(sl_atomic_tmpname(*a), &wo);
    if (!wb) {
        sl_atomic_abort(*a);
        *a = NULL;
        sl_error_set(err, SL_EIO, path, 0, "cannot create the workbook");
        return NULL;
    }
    lxw_doc_properties props;
    memset(&props, 0, sizeof props);
    props.title = (char *)(uintptr_t)title;
    props.subject = (char *)(uintptr_t)subject;
    props.author = "seislide";
    props.company = (char *)(uintptr_t)project->project;
    props.keywords = (char *)(uintptr_t)project->document;
    /* libxlsxwriter reads created = 0 as "now": the epoch itself is written
     * as one second after it, so --created 0 still gives identical files */
    props.created = created > 0 ? created : 1;
    workbook_set_properties(wb, &props);
    return wb;
}

sl_status sl_rpt_workbook_close(lxw_workbook *wb, sl_atomic *a, const char *path, sl_error *err)
{
    lxw_error le = workbook_close(wb);
    if (le != LXW_NO_ERROR) {
        sl_atomic_abort(a);
        return sl_error_set(err, SL_EIO, path, 0, "cannot write the workbook: %s",
                            lxw_strerror(le));
    }
    return sl_atomic_commit(a, err);
}
