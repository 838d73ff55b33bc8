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
#include "outdir.h"
#include "core/clock.h"
#include "method/asce.h"
#include "method/design.h"
#include "study_out.h"

#define STUDY_DEFAULT_OUT "docs"
#define STUDY_NPARTS 5

static const char study_head[] =
    "usage: seislide study [--records DIR] [-o DIR] [--parts LIST] [--no-plots] [-q]\n"
    "\n"
    "Reproduce the source study's evaluation (docs/validation.md) from\n"
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
    "  5  where the crossover of part 3 comes from: one change at a time, one record\n"
    "     left out, random seven-record draws from the records of part 4\n"
    "and a table of every quantitative claim of the study against seislide's value.\n"
    "\n";
static const char study_tail[] =
    "\n"
    "Figures need gnuplot (Debian: gnuplot-nox); without it the report says so.\n"
    "Every file is written whole or not at all. Results are deterministic (record\n"
    "matching keeps the records' phases; part 5 draws records from a fixed seed).\n"
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
    {"parts", OPT_PARTS, "LIST", "parts to run, e.g. 1,2 (default 1,2,3,4,5); the report holds\n"
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
    if ((rc = cli_outdir_apart("study", "output folder", a.out, &a.records, 1)))
        return rc;
    struct stat stt;
    if (stat(a.records, &stt) != 0 || !S_ISDIR(stt.st_mode)) {
        cli_msg("%s: the records folder is missing (--records DIR or SEISLIDE_SHARED)", a.records);
        return CLI_EXIT_ERROR;
    }
    study_out o = {.out = a.out, .plots = !a.no_plots};
    snprintf(o.figdir, sizeof o.figdir, "%s/" STUDY_FIGDIR, a.out);
    if (study_make_dir(a.out) || study_make_dir(o.figdir)) {
        cli_msg("%s: cannot create the output folder: %s", o.figdir, strerror(errno));
        return CLI_EXIT_ERROR;
    }
    char *buf = NULL;
    size_t len = 0;
    if (!(o.md = open_memstream(&buf, &len))) {
        cli_msg("out of memory");
        return CLI_EXIT_ERROR;
    }
    study_report_preamble(&o);
    double t0 = sl_clock_s();
    rc = study_report_run(&o, a.records, a.parts, a.quiet);
    if (!rc && !o.plots)
        fprintf(o.md, "Figures were not drawn in this run (--no-plots).\n\n");
    if (!rc)
        fprintf(o.md, "---\nseislide %s; `seislide study` took %.0f s on this machine.\n",
                SEISLIDE_VERSION, sl_clock_s() - t0);
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
