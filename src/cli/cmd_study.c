/* cmd_study.c - `seislide study`: reproduce the source study's evaluation
 * from recorded motions (study/study_parts.h computes; study_report.c and
 * study_files.c write docs/validation.md, its data and figures). */
#include <errno.h>
#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "cli.h"
#include "method/asce.h"
#include "method/design.h"
#include "study_out.h"

#define STUDY_DEFAULT_OUT "docs"
#define STUDY_NPARTS 4

static const char study_head[] =
    "usage: seislide study [--records DIR] [-o DIR] [--parts LIST] [--no-plots] [-q]\n"
    "\n"
    "Reproduce the source study's evaluation (../shared/docs/REFERENCE.md 1) from\n"
    "recorded three-component motions and write DIR/validation.md with its tables,\n"
    "and DIR/" STUDY_FIGDIR "/ with the data (TSV, units in the headers), the gnuplot\n"
    "scripts and the figures (SVG):\n"
    "  1  model validation: Rinaldi 228, then 228 + 318, mu = %.1f: the engine against\n"
    "     the smoothed (eta %g, U_y %s m) and elastic-plastic models\n"
    "  2  El Centro #9 matched to RG 1.60 (%.0f %%) at %.1f g, mu = %.1f: u_x, u_y under\n"
    "     x, y, x+y, x+z, y+z, x+y+z; hysteresis loops F/W against u\n"
    "  3  the seven-record ground set matched to RG 1.60 at 0.2-0.8 g: NLTHA (FS %.1f)\n"
    "     against ASCE (FS %.1f), %.1f x PGD cap, the mu g/PGA crossover\n"
    "  4  real record sets grouped as near-field soil, far-field soil, near-field\n"
    "     rock and pulse-like, mu %.2f-%.2f\n"
    "and a table of every quantitative claim of the study against seislide's value.\n"
    "\n";
static const char study_tail[] =
    "\n"
    "Figures need gnuplot (Debian: gnuplot-nox); without it the report says so.\n"
    "Every file is written whole or not at all. Results are deterministic (record\n"
    "matching keeps the records' phases; no random numbers).\n"
    "Exit status: 0 success, 1 missing records or failed run, 2 usage error.\n";

typedef struct study_args {
    const char *records, *out;
    int no_plots, quiet, parts;
} study_args;

enum { OPT_RECORDS = CLI_OPT_ID, OPT_PARTS, OPT_NOPLOTS };
#define A(f) .off = offsetof(study_args, f)
static const cli_opt study_opts[] = {
    {"records", OPT_RECORDS, "DIR", "the recorded motions (default: $SEISLIDE_SHARED/records, "
     "else\n../shared/records)", .kind = CLI_STRING, A(records)},
    {"output", 'o', "DIR", "where validation.md goes (default " STUDY_DEFAULT_OUT "/)",
     .kind = CLI_STRING, A(out)},
    {"parts", OPT_PARTS, "LIST", "parts to run, e.g. 1,2 (default 1,2,3,4); the report holds\n"
     "only those", .kind = CLI_CALL},
    {"no-plots", OPT_NOPLOTS, NULL, "write the data and scripts but do not run gnuplot",
     .kind = CLI_FLAG, A(no_plots)},
    {"quiet", 'q', NULL, "no progress on stderr", .kind = CLI_FLAG, A(quiet)},
};

static void print_help(void)
{
    char uy[16];
    printf(study_head, SL_STUDY_P1_MU, SL_STUDY_SMOOTH_ETA,
           study_sci(SL_STUDY_SMOOTH_UY_M, uy, sizeof uy), 100 * SL_STUDY_ZETA,
           SL_STUDY_P2_PGA_G, SL_STUDY_P2_MU, SL_NLTHA_FS, SL_ASCE_FS, SL_CAP_FACTOR,
           SL_MU_GRID_FROM, SL_MU_GRID_TO);
    cli_help_options(stdout, study_opts, CLI_NOPTS(study_opts), 18);
    fputs(study_tail, stdout);
}

/* --parts 1,2: bit k set for part k + 1. */
static int parse_parts(void *dst, int key, const char *arg)
{
    (void)key;
    int *parts = &((study_args *)dst)->parts;
    double *v = NULL;
    size_t n = 0;
    int bad = cli_parse_list(arg, &v, &n) || n == 0;
    *parts = 0;
    for (size_t i = 0; i < n && !bad; i++) {
        bad = v[i] != floor(v[i]) || v[i] < 1 || v[i] > STUDY_NPARTS;
        *parts |= bad ? 0 : 1 << ((int)v[i] - 1);
    }
    free(v);
    if (bad)
        return cli_usage("study", "--parts '%s': give a list of 1-%d, e.g. 1,2", arg,
                         STUDY_NPARTS);
    return CLI_EXIT_OK;
}

static void note(void *ctx, const char *msg)
{
    if (!*(const int *)ctx)
        fprintf(stderr, "seislide study: %s\n", msg);
}

/* Compute and write the parts asked for. 0 or -1 (message printed). */
static int run_parts(study_out *o, const study_args *a)
{
    sl_study_part1 p1 = {0};
    sl_study_part2 p2 = {0};
    sl_study_part3 p3 = {0};
    sl_study_part4 p4 = {0};
    sl_error *e = &o->err;
    int q = a->quiet, rc = 0;
    if (a->parts & 1) {
        note(&q, "part 1: model validation");
        rc = sl_study_part1_run(a->records, &p1, e) ? -2 : study_report_part1(o, &p1);
    }
    if (!rc && (a->parts & 2)) {
        note(&q, "part 2: El Centro #9");
        rc = sl_study_part2_run(a->records, &p2, e) ? -2 : study_report_part2(o, &p2);
    }
    if (!rc && (a->parts & 4))
        rc = sl_study_part3_run(a->records, &p3, note, &q, e) ? -2 : study_report_part3(o, &p3);
    if (!rc && (a->parts & 8))
        rc = sl_study_part4_run(a->records, &p4, note, &q, e) ? -2 : study_report_part4(o, &p4);
    if (!rc)
        study_report_claims(o, a->parts & 1 ? &p1 : NULL, a->parts & 2 ? &p2 : NULL,
                            a->parts & 4 ? &p3 : NULL, a->parts & 8 ? &p4 : NULL);
    if (rc == -2)
        cli_print_error(e);
    sl_study_part1_free(&p1);
    sl_study_part2_free(&p2);
    sl_study_part3_free(&p3);
    sl_study_part4_free(&p4);
    return rc ? -1 : 0;
}

static int make_dir(const char *path)
{
    return mkdir(path, 0777) == 0 || errno == EEXIST ? 0 : -1;
}

int cmd_study(int argc, char **argv)
{
    char recdef[4096];
    const char *shared = getenv("SEISLIDE_SHARED");
    snprintf(recdef, sizeof recdef, "%s/records", shared && *shared ? shared : "../shared");
    study_args a = {recdef, STUDY_DEFAULT_OUT, 0, 0, (1 << STUDY_NPARTS) - 1};
    int rc = cli_parse("study", study_opts, CLI_NOPTS(study_opts), argc, argv, &a, parse_parts);
    if (rc == CLI_OPT_HELP) {
        print_help();
        return CLI_EXIT_OK;
    }
    if (rc || (rc = cli_no_operands("study", argc, argv)))
        return rc;
    struct stat stt;
    if (stat(a.records, &stt) != 0 || !S_ISDIR(stt.st_mode)) {
        cli_msg("%s: the records folder is missing (--records DIR or SEISLIDE_SHARED)", a.records);
        return CLI_EXIT_ERROR;
    }
    study_out o = {.out = a.out, .plots = !a.no_plots};
    snprintf(o.figdir, sizeof o.figdir, "%s/" STUDY_FIGDIR, a.out);
    if (make_dir(a.out) || make_dir(o.figdir)) {
        cli_msg("%s: cannot create the output folder: %s", o.figdir, strerror(errno));
        return CLI_EXIT_ERROR;
    }
    char *buf = NULL;
    size_t len = 0;
    if (!(o.md = open_memstream(&buf, &len))) {
        cli_msg("out of memory");
        return CLI_EXIT_ERROR;
    }
    fprintf(o.md,
            "# Validation: seislide against the source study\n\n"
            "Made by `seislide study` (`make study`) from the recorded motions in\n"
            "../shared/records (provenance: ../shared/records/MANIFEST.tsv); every number\n"
            "below is recomputed by that command. The study and its findings are summarised\n"
            "in ../shared/docs/REFERENCE.md, section 1. Data and gnuplot scripts of every\n"
            "figure are in `docs/" STUDY_FIGDIR "/`. Regression tests on the same\n"
            "computations: tests/test_study.c.\n\n");
    double t0 = cli_now_s();
    rc = run_parts(&o, &a);
    if (!rc && !o.plots)
        fprintf(o.md, "Figures were not drawn in this run (--no-plots).\n\n");
    if (!rc)
        fprintf(o.md, "---\nseislide %s; `seislide study` took %.0f s on this machine.\n",
                SEISLIDE_VERSION, cli_now_s() - t0);
    if (fclose(o.md) && !rc) {
        cli_msg("out of memory");
        rc = -1;
    }
    if (!rc)
        rc = study_write_text(&o, a.out, "validation.md", buf, len);
    free(buf);
    if (!rc && !a.quiet)
        fprintf(stderr, "seislide study: wrote %s/validation.md and %s/\n", a.out, o.figdir);
    return rc ? CLI_EXIT_ERROR : CLI_EXIT_OK;
}
