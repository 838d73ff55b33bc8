/* workbook.c - a workbook written through sl_atomic (io/atomic.h: a hidden
 * temporary file renamed over the final name, so that a failed run leaves
 * no half-written workbook), with its document properties; shared by the
 * building workbook (report.c) and the plant workbook (plant_book.c). */
#include <errno.h>
#include <fcntl.h>
#include <pthread.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "report/sheets.h"

/* ---- libxlsxwriter's own messages ---------------------------------------
 * libxlsxwriter prints its errors itself before it returns an error code
 * (LXW_ERROR in its common.h: fprintf(stderr, "[ERROR][packager.c:1541]:
 * ...")), e.g. when a full disk or a file size limit stops the zip; the
 * library prints nothing (seislide.h). So while libxlsxwriter writes a
 * workbook (workbook_close, where every file is written), the process's
 * standard error (file descriptor 2) is the write end of a pipe of ours,
 * non-blocking (a full pipe drops text, never blocks). Afterwards fd 2 is
 * put back, and what libxlsxwriter said ("[ERROR]" and "[WARNING]" lines)
 * goes into our own error message; any other line (another thread's)
 * written meanwhile is passed on to the standard error as it was. One
 * workbook at a time holds fd 2 (a mutex). */
static pthread_mutex_t hold_lock = PTHREAD_MUTEX_INITIALIZER;

typedef struct held {
    int saved; /* fd 2 as it was, or -1: not held */
    int rd;    /* the pipe's read end, or -1 */
} held;

static void hold_stderr(held *h)
{
    pthread_mutex_lock(&hold_lock);
    h->saved = h->rd = -1;
    int p[2];
    fflush(stderr);
    if (pipe(p) != 0)
        return; /* not held: libxlsxwriter may print */
    fcntl(p[0], F_SETFD, FD_CLOEXEC);
    fcntl(p[0], F_SETFL, O_NONBLOCK);
    fcntl(p[1], F_SETFL, O_NONBLOCK);
    h->saved = fcntl(2, F_DUPFD_CLOEXEC, 3);
    if (h->saved < 0 || dup2(p[1], 2) < 0) {
        if (h->saved >= 0)
            close(h->saved);
        h->saved = -1;
        close(p[0]);
    } else {
        h->rd = p[0];
    }
    close(p[1]);
}

/* Put fd 2 back; libxlsxwriter's lines, "; "-joined and without their
 * "[ERROR][file:line]: " prefixes, into said (size n). */
static void release_stderr(held *h, char *said, size_t n)
{
    char buf[8192];
    size_t got = 0;
    said[0] = '\0';
    fflush(stderr);
    if (h->saved >= 0) {
        while (dup2(h->saved, 2) < 0 && errno == EINTR)
            ;
        close(h->saved);
    }
    for (ssize_t k; h->rd >= 0 && got < sizeof buf - 1 &&
                    ((k = read(h->rd, buf + got, sizeof buf - 1 - got)) > 0 ||
                     (k < 0 && errno == EINTR));)
        got += k > 0 ? (size_t)k : 0;
    if (h->rd >= 0)
        close(h->rd);
    buf[got] = '\0';
    size_t used = 0;
    for (char *line = buf, *end; *line; line = *end ? end + 1 : end) {
        end = line + strcspn(line, "\n");
        int lxw = !strncmp(line, "[ERROR]", 7) || !strncmp(line, "[WARNING]", 9);
        if (!lxw) { /* not libxlsxwriter's: passed on */
            if (end > line || *end)
                (void)!write(2, line, (size_t)(end - line) + (*end ? 1 : 0));
            continue;
        }
        const char *text = strchr(line, ' ');
        text = text && text < end ? text + 1 : line;
        int w = snprintf(said + used, n > used ? n - used : 0, "%s%.*s", used ? "; " : "",
                         (int)(end - text), text);
        if (w > 0 && (size_t)w < n - used)
            used += (size_t)w;
    }
    pthread_mutex_unlock(&hold_lock);
}

/* workbook_close with fd 2 held: libxlsxwriter's error code, its words in said. */
static lxw_error close_quietly(lxw_workbook *wb, char *said, size_t n)
{
    held h;
    hold_stderr(&h);
    lxw_error le = workbook_close(wb);
    release_stderr(&h, said, n);
    return le;
}

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
    char said[600];
    lxw_error le = close_quietly(wb, said, sizeof said);
    if (le != LXW_NO_ERROR) {
        sl_atomic_abort(a);
        /* the system's reason when libxlsxwriter gave it ("... System error = File
         * too large"), else its own words; never its temporary file's name */
        const char *sys = strstr(said, "System error = ");
        if (sys)
            return sl_error_set(err, SL_EIO, path, 0, "cannot write the workbook: %.*s "
                                "(libxlsxwriter: %s)", (int)strcspn(sys + 15, ";"), sys + 15,
                                lxw_strerror(le));
        return sl_error_set(err, SL_EIO, path, 0, "cannot write the workbook: %s%s%.300s%s",
                            lxw_strerror(le), said[0] ? " (libxlsxwriter: " : "", said,
                            said[0] ? ")" : "");
    }
    return sl_atomic_commit(a, err);
}

void sl_rpt_workbook_discard(lxw_workbook *wb, sl_atomic *a)
{
    char said[8];
    close_quietly(wb, said, sizeof said);
    sl_atomic_abort(a);
}
