/* cmd_run.c - `seislide run`: floor response spectra in, the clearance workbook and CSV
 * tables out (analysis.h; report/deliver.h writes the folder). Options and help: one table. */
#include <errno.h>
#include <getopt.h>
#include <math.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "analysis.h"
#include "cli.h"
#include "io/atomic.h"
#include "report/deliver.h"

#define RUN_MU_RANGE "0.05:0.80:0.01"
enum { O_SETS = 256, O_SEED, O_MU_RANGE, O_MU, O_POLICY, O_ACC, O_SUB, O_MOTIONS, O_CREATED,
       O_FORCE, O_PROJECT, O_DOCUMENT, O_REVISION, O_PREPARED, O_CHECKED, O_DATE, O_HELP };
static const struct run_opt { const char *name; int arg, id; const char *help; } opts[] = {
    {"output", 1, 'o', "DIR\toutput folder (default output/). The run writes a fresh folder and "
     "swaps it in, so DIR must be new, empty or hold only seislide outputs"},
    {"quiet", 0, 'q', "\tno progress on stderr"},
    {"sets", 1, O_SETS, "N\tmotion sets per floor (default 7; ASCE 43-05: >= 5)"},
    {"seed", 1, O_SEED, "S\trandom seed (default 1); a floor's seed also depends on its name"},
    {"mu-range", 1, O_MU_RANGE, "A:B:S\tfriction grid (default " RUN_MU_RANGE ")"},
    {"mu", 1, O_MU, "LIST\texplicit friction values, increasing"},
    {"policy", 1, O_POLICY, "P\trequired clearance: nltha (default), asce or envelope"},
    {"accuracy", 1, O_ACC, "E\t2-D integration accuracy 0.01 (1 sub-step), 0.001 (8, default), "
     "0.0001 (32)"},
    {"substeps", 1, O_SUB, "N\tset the 2-D sub-steps directly"},
    {"motions", 0, O_MOTIONS, "\talso write every motion to DIR/motions/<floor id>/*.AT2"},
    {"created", 1, O_CREATED, "EPOCH\tworkbook date, s since 1970 (default SOURCE_DATE_EPOCH, "
     "else now)"},
    {"force", 0, O_FORCE, "\trun a floor whose ZPA is outside 0.01-5 g (a warning, not an error)"},
    {"project", 1, O_PROJECT, "TEXT\ttitle block: project"},
    {"document", 1, O_DOCUMENT, "TEXT\ttitle block: document number"},
    {"revision", 1, O_REVISION, "TEXT\ttitle block: revision"},
    {"prepared", 1, O_PREPARED, "TEXT\ttitle block: prepared by"},
    {"checked", 1, O_CHECKED, "TEXT\ttitle block: checked by"},
    {"date", 1, O_DATE, "TEXT\ttitle block: date (default: the workbook date)"},
    {"help", 0, O_HELP, "\tthis text"}};
#define N_OPTS (sizeof opts / sizeof opts[0])

static void help(void)
{
    puts("usage: seislide run [FLOOR.ini ... | DIR] [options]\n\nThe main job: for every floor "
         "response spectrum file (default: every *.ini in floors/),\nsynthesize motion sets, "
         "compute the peak vector sliding displacement of each by\nNLTHA over the friction grid "
         "and the ASCE/SEI 43-05 estimate, the design sliding\nspectra, every range where ASCE "
         "is below NLTHA, and the required clearance; write\nDIR/" SL_DELIVER_WORKBOOK " and "
         "the CSV files (docs/run.md).\n");
    for (size_t i = 0; i < N_OPTS; i++) { /* "  -o, --name ARG" then the help, wrapped */
        const char *t = strchr(opts[i].help, '\t'), *p = t + 1;
        printf("  %s--%s%s%.*s\n", opts[i].id < 256 ? (opts[i].id == 'o' ? "-o, " : "-q, ") : "",
               opts[i].name, opts[i].arg ? " " : "", (int)(t - opts[i].help), opts[i].help);
        while (*p) {
            int w = (int)strlen(p) <= 70 ? (int)strlen(p) : 70;
            while (w < (int)strlen(p) && w > 0 && p[w] != ' ')
                w--;
            printf("        %.*s\n", w, p);
            p += w + (p[w] == ' ');
        }
    }
    puts("\nExit status: 0 success, 1 bad input or failed run (no output changed), 2 usage error.");
}

typedef struct progress_ctx {
    int quiet;
    size_t floor, n;
    const char *name, *step;
    int pct;
} progress_ctx;
static void progress(void *ctx, const char *step, size_t done, size_t total)
{
    progress_ctx *p = ctx;
    int pct = total ? (int)(100.0 * (double)done / (double)total) : 0;
    if (p->quiet || total == 0 || (p->step == step && pct < p->pct + 25 && done != total))
        return;
    p->step = step;
    p->pct = pct;
    cli_msg("run: floor %zu/%zu '%s': %s %zu/%zu (%d %%)", p->floor, p->n, p->name, step, done,
            total, pct);
}

/* Interrupted while computing: the fresh folder is still empty (but for a
 * placeholder): remove it and die of the signal. While writing: note it. */
static char sig_dir[4096], sig_keep[2][4200];
static volatile sig_atomic_t writing, interrupted;
static void on_signal(int s)
{
    interrupted = s;
    if (writing)
        return;
    unlink(sig_keep[0]);
    unlink(sig_keep[1]);
    rmdir(sig_dir);
    signal(s, SIG_DFL);
    raise(s);
}

int cmd_run(int argc, char **argv)
{
    struct option lo[N_OPTS + 1] = {{0}};
    for (size_t i = 0; i < N_OPTS; i++)
        lo[i] = (struct option){opts[i].name, opts[i].arg ? required_argument : no_argument, 0,
                                opts[i].id};
    sl_analysis_opts ao;
    sl_analysis_opts_default(&ao);
    sl_deliver_opts dop = {.version = "seislide " SEISLIDE_VERSION, .seed = 1, .accuracy = 1e-3};
    const char **text[] = {&dop.project.project, &dop.project.document, &dop.project.revision,
                           &dop.project.prepared, &dop.project.checked, &dop.project.date};
    const char *outdir = "output", *sde = getenv("SOURCE_DATE_EPOCH"), *dflt[] = {"floors"};
    int quiet = 0, force = 0, rc = CLI_EXIT_USAGE, c, li = -1;
    unsigned long ul, n_sets = SL_ANALYSIS_DEFAULT_SETS;
    double v, *mu = NULL;
    double created = (sde && !cli_parse_double(sde, &v) && v >= 0) ? v : (double)time(NULL);
    char cmdline[8192] = "seislide", date[32], warn[4096], r[512];
    static sl_deliver_inputs in; /* large: not on the stack */
    sl_analysis *an[SL_DELIVER_MAX_FLOORS] = {NULL};
    sl_atomic_dir *out = NULL;
    sl_error err;
    sl_error_clear(&err);
    optind = 1;
    opterr = 0;
    while ((c = getopt_long(argc, argv, ":o:q", lo, &li)) != -1) {
        const char *a = optarg;
        int bad = 0;
        switch (c) {
        case 'o': outdir = a; break;
        case 'q': quiet = 1; break;
        case O_SETS: bad = cli_parse_ulong(a, &n_sets) || n_sets < 1 || n_sets > 1000; break;
        case O_SEED: bad = cli_parse_ulong(a, &ul); dop.seed = ul; break;
        case O_MU: case O_MU_RANGE:
            if (cli_friction("run", c == O_MU_RANGE, a, &mu, &ao.n_mu))
                goto done;
            break;
        case O_POLICY: bad = (c = sl_clearance_policy_parse(a)) < 0; ao.policy = bad ? 0 : c; break;
        case O_ACC: bad = cli_parse_double(a, &dop.accuracy) || !(dop.accuracy > 0); break;
        case O_SUB: bad = cli_parse_ulong(a, &ul) || ul < 1 || ul > 100000; dop.substeps = ul; break;
        case O_MOTIONS: dop.write_motions = 1; break;
        case O_CREATED: bad = cli_parse_double(a, &created) || created < 0 || created > 4e12; break;
        case O_FORCE: force = 1; break;
        case O_HELP: help(); rc = CLI_EXIT_OK; goto done;
        case ':': cli_usage("run", "option '%s' needs a value", argv[optind - 1]); goto done;
        case '?': cli_usage("run", "unknown option '%s'", argv[optind - 1]); goto done;
        default: *text[c - O_PROJECT] = a; break; /* the title block */
        }
        if (bad) {
            cli_usage("run", "bad value '%s' for --%s (see seislide run --help)", a, lo[li].name);
            goto done;
        }
    }
    if (!mu && cli_parse_range(RUN_MU_RANGE, &mu, &ao.n_mu))
        goto done;
    rc = CLI_EXIT_ERROR;
    /* every floor read and checked, and the output folder made, before any long work */
    int nargs = optind < argc ? argc - optind : 1;
    if (sl_deliver_inputs_load(&in, optind < argc ? (const char *const *)argv + optind : dflt,
                               (size_t)nargs, force, warn, sizeof warn, &err))
        goto fail;
    if (warn[0])
        cli_msg("run: warning (--force): %s", warn);
    if (!(out = sl_atomic_dir_open(outdir, sl_report_owns_name, &err)))
        goto fail;
    snprintf(sig_dir, sizeof sig_dir, "%s", sl_atomic_dir_path(out));
    snprintf(sig_keep[0], sizeof sig_keep[0], "%s/.keep", sig_dir);
    snprintf(sig_keep[1], sizeof sig_keep[1], "%s/.gitkeep", sig_dir);
    signal(SIGINT, on_signal);
    signal(SIGTERM, on_signal);
    signal(SIGHUP, on_signal);
    double e = dop.accuracy; /* measured sub-steps per accuracy: docs/performance.md */
    ao.substeps = dop.substeps ? dop.substeps : e >= 1e-2 ? 1 : e >= 1e-3 ? 8 : e >= 1e-4 ? 32 : 128;
    dop.substeps = ao.substeps;
    ao.n_sets = n_sets;
    ao.seed = dop.seed;
    ao.mu = mu;
    progress_ctx pc;
    ao.progress = progress;
    ao.progress_ctx = &pc;
    if (n_sets < SL_NLTHA_MIN_SETS && !quiet)
        cli_msg("run: warning: %lu motion sets per floor; ASCE/SEI 43-05 asks for at least %d",
                n_sets, SL_NLTHA_MIN_SETS);
    for (size_t i = 0; i < in.n; i++) {
        pc = (progress_ctx){quiet, i + 1, in.n, in.floors[i]->name, NULL, -100};
        if (!(an[i] = sl_analysis_run(in.floors[i], &ao, &err)))
            goto fail;
        if (!quiet)
            cli_msg("run: floor %zu/%zu '%s': ZPA %.3f g; %zu of %zu friction values need no "
                    "NLTHA; ASCE below NLTHA for mu in %s%s%s", i + 1, in.n, in.floors[i]->name,
                    an[i]->zpa_h_ms2 / SL_G, an[i]->n_mu_skipped, ao.n_mu,
                    sl_report_ranges_text(an[i]->design, r, sizeof r),
                    an[i]->note[0] ? "; note: " : "", an[i]->note);
    }
    for (int i = 0; i < argc && strlen(cmdline) + strlen(argv[i]) + 2 < sizeof cmdline; i++)
        strcat(strcat(cmdline, " "), argv[i]);
    dop.command_line = cmdline;
    dop.created = (time_t)created;
    if (!dop.project.date && strftime(date, sizeof date, "%Y-%m-%d", gmtime(&dop.created)))
        dop.project.date = date;
    writing = 1; /* a signal now is noted, and the fresh folder dropped */
    if (sl_deliver_write(sl_atomic_dir_path(out), in.n, (const sl_floor *const *)in.floors,
                         in.idp, (const sl_analysis *const *)an, &dop, &err) ||
        interrupted || sl_atomic_dir_commit(out, &err))
        goto fail;
    out = NULL;
    if (!quiet)
        cli_msg("run: wrote %s/%s and the CSV files", outdir, SL_DELIVER_WORKBOOK);
    rc = CLI_EXIT_OK;
    goto done;
fail:
    if (!interrupted)
        cli_print_error(&err);
done:
    sl_atomic_dir_abort(out);
    free(mu);
    for (size_t i = 0; i < in.n; i++)
        sl_analysis_free(an[i]);
    sl_deliver_inputs_free(&in);
    if (interrupted)
        signal((int)interrupted, SIG_DFL), raise((int)interrupted);
    return rc;
}
