/* study_files.c - the data files, scripts and figures of `seislide study`
 * (study_out.h). */
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "cli.h"
#include "io/atomic.h"
#include "study_out.h"

int study_write_text(study_out *o, const char *dir, const char *name, const char *text,
                     size_t len)
{
    char path[4200];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    sl_atomic *a = sl_atomic_open(path, &o->err);
    if (!a) {
        cli_print_error(&o->err);
        return -1;
    }
    if (fwrite(text, 1, len, sl_atomic_file(a)) != len) {
        sl_atomic_abort(a);
        cli_msg("%s: cannot write", path);
        return -1;
    }
    if (sl_atomic_commit(a, &o->err)) {
        cli_print_error(&o->err);
        return -1;
    }
    return 0;
}

/* A text built in memory (a stream f over buf, len), then written out. */
typedef struct mem_text {
    char *buf;
    size_t len;
    FILE *f;
} mem_text;

/* Open t (which stays where it is until mem_text_write). Its stream, or
 * NULL (message printed). */
static FILE *mem_text_open(mem_text *t)
{
    t->buf = NULL;
    t->len = 0;
    if (!(t->f = open_memstream(&t->buf, &t->len)))
        cli_msg("out of memory");
    return t->f;
}

/* Close t and write its text to figdir/name; frees the text. 0 or -1
 * (message printed). */
static int mem_text_write(study_out *o, const char *name, mem_text *t)
{
    int rc = -1;
    if (fclose(t->f))
        cli_msg("out of memory");
    else
        rc = study_write_text(o, o->figdir, name, t->buf, t->len);
    free(t->buf);
    return rc;
}

int study_write_tsv(study_out *o, const char *name, const char *title, const char *const *hdr,
                    const double *const *col, size_t ncol, size_t nrow)
{
    mem_text t;
    FILE *f = mem_text_open(&t);
    if (!f)
        return -1;
    fprintf(f, "# %s (seislide study)\n#", title);
    for (size_t j = 0; j < ncol; j++)
        fprintf(f, "%s%s", j ? "\t" : " ", hdr[j]);
    fputc('\n', f);
    for (size_t i = 0; i < nrow; i++)
        for (size_t j = 0; j < ncol; j++) {
            double v = col[j][i];
            if (isnan(v))
                fprintf(f, "NaN%c", j + 1 < ncol ? '\t' : '\n');
            else
                fprintf(f, "%.9g%c", v, j + 1 < ncol ? '\t' : '\n');
        }
    return mem_text_write(o, name, &t);
}

int study_write_history(study_out *o, const char *name, const char *title,
                        const char *const hdr[5], const sl_history *h)
{
    const double *col[] = {h->t_s, h->ux_m, h->uy_m, h->fx_w, h->fy_w};
    return study_write_tsv(o, name, title, hdr, col, 5, h->n);
}

int study_write_spectra(study_out *o, const char *name, const char *title,
                        const sl_study_spectra *sp)
{
    size_t n = sp->n_mu;
    double *c[8];
    for (int j = 0; j < 8; j++)
        if (!(c[j] = malloc(n * sizeof(double)))) {
            for (int i = 0; i < j; i++)
                free(c[i]);
            cli_msg("out of memory");
            return -1;
        }
    for (size_t k = 0; k < n; k++) {
        const sl_design_row *r = &sp->design->rows[k];
        const double v[8] = {r->mu, r->x, r->nltha_mean_m, r->asce_best_m, r->nltha_design_m,
                             r->asce_design_m, r->cap_m, r->nltha_sd_m};
        for (int j = 0; j < 8; j++)
            c[j][k] = v[j];
    }
    const char *hdr[] = {"mu", "mu_g_over_pga", "nltha_mean_m", "asce_best_m",
                         "nltha_design_m", "asce_design_m", "cap_m", "nltha_sd_m"};
    int rc = study_write_tsv(o, name, title, hdr, (const double *const *)c, 8, n);
    for (int j = 0; j < 8; j++)
        free(c[j]);
    return rc;
}

/* Run gnuplot on figdir/name. 0 or -1 (message printed). */
static int run_gnuplot(const study_out *o, const char *name)
{
    pid_t pid = fork();
    if (pid < 0) {
        cli_msg("cannot start gnuplot: %s", strerror(errno));
        return -1;
    }
    if (pid == 0) {
        if (chdir(o->figdir) != 0)
            _exit(127);
        execlp("gnuplot", "gnuplot", name, (char *)NULL);
        _exit(127);
    }
    int status = 0;
    if (waitpid(pid, &status, 0) != pid || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
        cli_msg("%s/%s: gnuplot failed (exit %d); is gnuplot installed (Debian: gnuplot-nox)?",
                o->figdir, name, WIFEXITED(status) ? WEXITSTATUS(status) : -1);
        return -1;
    }
    return 0;
}

int study_plot(study_out *o, const char *base, const char *fmt, ...)
{
    mem_text t;
    FILE *f = mem_text_open(&t);
    if (!f)
        return -1;
    fprintf(f,
            "# %s.gp - drawn by 'seislide study'; run in this folder: gnuplot %s.gp\n"
            "set terminal svg size 900,560 font 'Helvetica,13' background '#ffffff'\n"
            "set output '%s.svg'\n"
            "set grid lc rgb '#dddddd'\nset key box opaque\nset datafile missing 'NaN'\n",
            base, base, base);
    va_list ap;
    va_start(ap, fmt);
    vfprintf(f, fmt, ap);
    va_end(ap);
    char name[256];
    snprintf(name, sizeof name, "%s.gp", base);
    int rc = mem_text_write(o, name, &t);
    if (rc || !o->plots)
        return rc;
    return run_gnuplot(o, name);
}

const char *study_sci(double v, char *buf, size_t n)
{
    char tmp[32];
    snprintf(tmp, sizeof tmp, "%.0e", v); /* 1e-07 */
    char *e = strchr(tmp, 'e');
    size_t k = 0;
    for (const char *p = tmp; *p && k + 1 < n; p++) {
        buf[k++] = *p;
        if (e && p > e && (*p == '-' || *p == '+'))
            while (p[1] == '0' && p[2])
                p++;
    }
    buf[k] = '\0';
    return buf;
}

int study_make_dir(const char *path)
{
    return mkdir(path, 0777) == 0 || errno == EEXIST ? 0 : -1;
}

