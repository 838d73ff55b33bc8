/* cmd_run.c - `seislide run`: floor response spectra in, the clearance workbook and CSV
 * tables out (analysis.h; report/deliver.h writes the folder). Options and help: one table. */
#include <errno.h>
#include <getopt.h>
#include <glob.h>
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

#define MAX_FLOORS 256
#define RUN_MU_RANGE "0.05:0.80:0.01"
enum { O_SETS = 256, O_SEED, O_MU_RANGE, O_MU, O_POLICY, O_ACC, O_SUB, O_MOTIONS, O_CREATED,
       O_FORCE, O_PROJECT, O_DOCUMENT, O_REVISION, O_PREPARED, O_CHECKED, O_DATE, O_HELP };
static const struct run_opt { const char *name; int arg, id; const char *help; } opts[] = {
    {"output", 1, 'o', "DIR: output folder (default output/). The run writes a fresh folder and "
     "swaps it in, so DIR must be new, empty or hold only seislide outputs"},
    {"quiet", 0, 'q', ": no progress on stderr"},
    {"sets", 1, O_SETS, "N: motion sets per floor (default 7; ASCE 43-05: >= 5)"},
    {"seed", 1, O_SEED, "S: random seed (default 1); a floor's seed also depends on its name"},
    {"mu-range", 1, O_MU_RANGE, "A:B:S: friction grid (default " RUN_MU_RANGE ")"},
    {"mu", 1, O_MU, "LIST: explicit friction values, increasing"},
    {"policy", 1, O_POLICY, "P: required clearance: nltha (default), asce or envelope"},
    {"accuracy", 1, O_ACC, "E: 2-D integration accuracy 0.01 (1 sub-step), 0.001 (8, default), "
     "0.0001 (32)"},
    {"substeps", 1, O_SUB, "N: set the 2-D sub-steps directly"},
    {"motions", 0, O_MOTIONS, ": also write every motion to DIR/motions/<floor id>/*.AT2"},
    {"created", 1, O_CREATED, "EPOCH: workbook date, s since 1970 (default SOURCE_DATE_EPOCH, "
     "else now)"},
    {"force", 0, O_FORCE, ": run a floor whose ZPA is outside 0.01-5 g (a warning, not an error)"},
    {"project", 1, O_PROJECT, "TEXT: title block: project"},
    {"document", 1, O_DOCUMENT, "TEXT: title block: document number"},
    {"revision", 1, O_REVISION, "TEXT: title block: revision"},
    {"prepared", 1, O_PREPARED, "TEXT: title block: prepared by"},
    {"checked", 1, O_CHECKED, "TEXT: title block: checked by"},
    {"date", 1, O_DATE, "TEXT: title block: date (default: the workbook date)"},
    {"help", 0, O_HELP, ": this text"}};
#define N_OPTS (sizeof opts / sizeof opts[0])

static void help(void)
{
    puts("usage: seislide run [FLOOR.ini ... | DIR] [options]\n\nThe main job: for every floor "
         "response spectrum file (default: every *.ini in floors/),\nsynthesize motion sets, "
         "compute the peak vector sliding displacement of each by\nNLTHA over the friction grid "
         "and the ASCE/SEI 43-05 estimate, the design sliding\nspectra, every range where ASCE "
         "is below NLTHA, and the required clearance; write\nDIR/" SL_DELIVER_WORKBOOK " and "
         "the CSV files (docs/run.md).\n");
    for (size_t i = 0; i < N_OPTS; i++) {
        const char *colon = strchr(opts[i].help, ':');
        printf("  %s--%s%s%.*s\n        %s\n", opts[i].id < 256 ? (opts[i].id == 'o' ? "-o, " : "-q, ")
               : "", opts[i].name, opts[i].arg ? " " : "", (int)(colon - opts[i].help),
               opts[i].help, colon + 2);
    }
    puts("\nExit status: 0 success, 1 bad input or failed run (no output changed), 2 usage error.");
}

typedef struct progress_ctx { int quiet; size_t floor, n; const char *name, *step; int pct; } progress_ctx;
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

static int add_inputs(const char *arg, char **paths, size_t *n)
{
    struct stat st;
    glob_t g = {0};
    char pat[4096];
    if (stat(arg, &st) != 0)
        return cli_msg("%s: %s", arg, strerror(errno)), -1;
    snprintf(pat, sizeof pat, S_ISDIR(st.st_mode) ? "%s/*.ini" : "%s", arg);
    if (glob(pat, S_ISDIR(st.st_mode) ? 0 : GLOB_NOCHECK | GLOB_NOESCAPE, NULL, &g) != 0)
        return cli_msg("%s: no floor files (*.ini) in this folder", arg), -1;
    for (size_t i = 0; i < g.gl_pathc; i++)
        if (*n < MAX_FLOORS)
            paths[(*n)++] = strdup(g.gl_pathv[i]);
    size_t total = g.gl_pathc;
    globfree(&g);
    return total > MAX_FLOORS ? cli_msg("%s: more than %d floor files", arg, MAX_FLOORS), -1 : 0;
}

int cmd_run(int argc, char **argv)
{
    struct option lo[N_OPTS + 1] = {{0}};
    for (size_t i = 0; i < N_OPTS; i++)
        lo[i] = (struct option){opts[i].name, opts[i].arg ? required_argument : no_argument, 0, opts[i].id};
    sl_analysis_opts ao;
    sl_analysis_opts_default(&ao);
    sl_deliver_opts dop = {.version = "seislide " SEISLIDE_VERSION, .seed = 1, .accuracy = 1e-3};
    const char *outdir = "output", *sde = getenv("SOURCE_DATE_EPOCH");
    int quiet = 0, force = 0, rc = CLI_EXIT_USAGE, c;
    unsigned long ul, n_sets = SL_ANALYSIS_DEFAULT_SETS;
    double v, *mu = NULL, created = (sde && !cli_parse_double(sde, &v) && v >= 0) ? v : (double)time(NULL);
    size_t n_mu = 0, np = 0;
    char *paths[MAX_FLOORS], ids[MAX_FLOORS][80], *idp[MAX_FLOORS], cmdline[8192] = "seislide", date[32];
    sl_floor *floors[MAX_FLOORS] = {NULL};
    sl_analysis *an[MAX_FLOORS] = {NULL};
    sl_atomic_dir *out = NULL;
    sl_error err;
    sl_error_clear(&err);
    optind = 1;
    opterr = 0;
    int li = -1;
    while ((c = getopt_long(argc, argv, ":o:q", lo, &li)) != -1) {
        const char *a = optarg;
        int bad = 0;
        switch (c) {
        case 'o': outdir = a; break;
        case 'q': quiet = 1; break;
        case O_SETS: bad = cli_parse_ulong(a, &n_sets) || n_sets < 1 || n_sets > 1000; break;
        case O_SEED: bad = cli_parse_ulong(a, &ul); dop.seed = ul; break;
        case O_MU: case O_MU_RANGE: if (cli_friction("run", c == O_MU_RANGE, a, &mu, &n_mu)) goto done; break;
        case O_POLICY: bad = (c = sl_clearance_policy_parse(a)) < 0; ao.policy = bad ? 0 : (sl_clearance_policy)c; break;
        case O_ACC: if (cli_positive("run", "--accuracy", a, NULL, &dop.accuracy)) goto done; break;
        case O_SUB: bad = cli_parse_ulong(a, &ul) || ul < 1 || ul > 100000; dop.substeps = (unsigned)ul; break;
        case O_MOTIONS: dop.write_motions = 1; break;
        case O_CREATED: bad = cli_parse_double(a, &created) || created < 0 || created > 4e12; break;
        case O_FORCE: force = 1; break;
        case O_PROJECT: dop.project.project = a; break;
        case O_DOCUMENT: dop.project.document = a; break;
        case O_REVISION: dop.project.revision = a; break;
        case O_PREPARED: dop.project.prepared = a; break;
        case O_CHECKED: dop.project.checked = a; break;
        case O_DATE: dop.project.date = a; break;
        case O_HELP: help(); rc = CLI_EXIT_OK; goto done;
        case ':': cli_usage("run", "option '%s' needs a value", argv[optind - 1]); goto done;
        default: cli_usage("run", "unknown option '%s'", argv[optind - 1]); goto done;
        }
        if (bad) {
            cli_usage("run", "bad value '%s' for --%s (see seislide run --help)", a, lo[li].name);
            goto done;
        }
    }
    if (!mu && cli_parse_range(RUN_MU_RANGE, &mu, &n_mu))
        goto done;
    rc = CLI_EXIT_ERROR;
    if (optind == argc && add_inputs("floors", paths, &np))
        goto done;
    for (int i = optind; i < argc; i++)
        if (add_inputs(argv[i], paths, &np))
            goto done;
    /* every floor read and checked, and the output folder made, before any long work */
    sl_report_floor rf[MAX_FLOORS];
    for (size_t i = 0; i < np; i++) {
        if (!(floors[i] = sl_floor_load(paths[i], &err)))
            goto fail;
        if (sl_floor_check_plausible(floors[i], &err)) {
            cli_print_error(&err);
            if (!force)
                goto done_msg;
            cli_msg("run: warning: --force given: running this floor anyway");
        }
        rf[i] = (sl_report_floor){.id = idp[i] = sl_report_floor_id(paths[i], ids[i], sizeof ids[i]),
                                  .name = floors[i]->name, .path = paths[i]};
    }
    sl_report chk;
    sl_report_init(&chk);
    chk.n_floors = np;
    chk.floors = rf;
    if (sl_report_check_floors(&chk, &err) || !(out = sl_atomic_dir_open(outdir, sl_report_owns_name, &err)))
        goto fail;
    snprintf(sig_dir, sizeof sig_dir, "%s", sl_atomic_dir_path(out));
    snprintf(sig_keep[0], sizeof sig_keep[0], "%s/.keep", sig_dir);
    snprintf(sig_keep[1], sizeof sig_keep[1], "%s/.gitkeep", sig_dir);
    signal(SIGINT, on_signal);
    signal(SIGTERM, on_signal);
    signal(SIGHUP, on_signal);
    ao.n_sets = n_sets;
    ao.seed = dop.seed;
    ao.mu = mu;
    ao.n_mu = n_mu;
    ao.substeps = dop.substeps ? dop.substeps : dop.accuracy >= 1e-2 ? 1 : dop.accuracy >= 1e-3 ? 8 : dop.accuracy >= 1e-4 ? 32 : 128;
    dop.substeps = ao.substeps;
    progress_ctx pc = {quiet, 0, np, "", NULL, -100};
    ao.progress = progress;
    ao.progress_ctx = &pc;
    if (n_sets < SL_NLTHA_MIN_SETS && !quiet)
        cli_msg("run: warning: %lu motion sets per floor; ASCE/SEI 43-05 asks for at least %d", n_sets, SL_NLTHA_MIN_SETS);
    for (size_t i = 0; i < np; i++) {
        pc = (progress_ctx){quiet, i + 1, np, floors[i]->name, NULL, -100};
        if (!(an[i] = sl_analysis_run(floors[i], &ao, &err)))
            goto fail;
        if (!quiet) {
            char r[512] = "";
            for (size_t q = 0; q < an[i]->design->n_ranges; q++)
                snprintf(r + strlen(r), sizeof r - strlen(r), "%s%.3f-%.3f", q ? ", " : "", an[i]->design->ranges[q].mu_lo, an[i]->design->ranges[q].mu_hi);
            cli_msg("run: floor %zu/%zu '%s': ZPA %.3f g; %zu of %zu friction values need no NLTHA; ASCE below NLTHA for mu in %s",
                    i + 1, np, floors[i]->name, an[i]->zpa_h_ms2 / SL_G, an[i]->n_mu_skipped, n_mu, r[0] ? r : "none");
            if (an[i]->note[0])
                cli_msg("run: floor '%s': note: %s", floors[i]->name, an[i]->note);
        }
    }
    for (int i = 0; i < argc && strlen(cmdline) + strlen(argv[i]) + 2 < sizeof cmdline; i++)
        strcat(strcat(cmdline, " "), argv[i]);
    dop.command_line = cmdline;
    dop.created = (time_t)created;
    if (!dop.project.date)
        strftime(date, sizeof date, "%Y-%m-%d", gmtime(&dop.created)), dop.project.date = date;
    writing = 1;
    if (sl_deliver_write(sl_atomic_dir_path(out), np, (const sl_floor *const *)floors, (const char *const *)idp,
                         (const sl_analysis *const *)an, &dop, &err) || interrupted || sl_atomic_dir_commit(out, &err))
        goto fail;
    out = NULL;
    if (!quiet)
        cli_msg("run: wrote %s/%s and the CSV files", outdir, SL_DELIVER_WORKBOOK);
    rc = CLI_EXIT_OK;
    goto done;
fail:
    if (!interrupted)
        cli_print_error(&err);
done_msg:
    rc = CLI_EXIT_ERROR;
done:
    sl_atomic_dir_abort(out);
    free(mu);
    for (size_t i = 0; i < np; i++) {
        sl_analysis_free(an[i]);
        sl_floor_free(floors[i]);
        free(paths[i]);
    }
    if (interrupted) {
        signal((int)interrupted, SIG_DFL);
        raise((int)interrupted);
    }
    return rc;
}
