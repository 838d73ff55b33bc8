/* rock_opts.c - the options of `seislide rock` (rock_opts.h): one cli_opt
 * table, parsed by cli_parse() and printed by --help, and the rules across
 * options. */
#include "rock_opts.h"

#include <math.h>
#include <stddef.h>

static const char rock_head[] =
    "usage: seislide rock --h1 FILE [--h2 FILE] [--v FILE] [--units g|m/s2|cm/s2]\n"
    "                     [--dt S] --base-m B --cg-height-m H [--restitution R]\n"
    "                     [--orientation DEG] [--scale-pga G] [--history OUT.csv]\n"
    "                     [--csv] [--truncate] [--rtol R | --substeps N]\n\n"
    "Rocking of a rigid rectangular block on a rigid floor (Housner 1963) under the\n"
    "floor motion H1 [, H2] [, V]: base width B = 2b along the block's weak axis,\n"
    "centre of mass at height H = h, alpha = atan(b/h), p^2 = 3 g / (4 R),\n"
    "R = sqrt(b^2 + h^2):\n"
    "  theta'' = -p^2 [(1 + a_v/g) sin(alpha sgn(theta) - theta)\n"
    "                  + (a_h/g) cos(alpha sgn(theta) - theta)],\n"
    "a_h the floor acceleration along the weak axis. Uplift when |a_h| > (g + a_v)\n"
    "tan(alpha); at impacts theta' <- r theta'. Tipped: |theta| reached alpha;\n"
    "overturned: pi/2. After the record the floor is at rest and the block rocks\n"
    "on until it rests or overturns. Without --orientation the weak axis is turned\n"
    "from H1 toward H2 by 0, 15, ..., 165 degrees (180 repeats 0) and the worst\n"
    "orientation governs (overturns before tips before the largest theta/alpha).\n\n";
static const char rock_tail[] =
    "\nstatus per orientation: stands (never uplifts), rocks, tips (|theta| reached\n"
    "alpha), overturns (pi/2). A warning when g + a_v < 0 somewhere (the block\n"
    "would leave the floor, which the model does not describe).\n"
    "Exit status: 0 success, 1 bad input or failed run, 2 usage error.\n";

enum { O_H1 = CLI_OPT_ID, O_H2, O_V, O_UNITS, O_DT, O_TRUNCATE, O_SCALE, O_BASE, O_CG,
       O_RESTITUTION, O_ORIENT, O_RTOL, O_SUBSTEPS, O_CSV, O_HISTORY };
#define A(f) .off = offsetof(rock_args, f)
static const cli_opt opts[] = {
    {.head = "input:"},
    {"h1", O_H1, "FILE", "motions: PEER .AT2, one column (needs --dt),\ntwo columns time+acc, "
     "or CSV with a header", .show = "--h1 FILE, --h2 FILE, --v FILE", .kind = CLI_STRING,
     A(path[0])},
    {"h2", O_H2, "FILE", NULL, .kind = CLI_STRING, A(path[1])},
    {"v", O_V, "FILE", NULL, .kind = CLI_STRING, A(path[2])},
    {"units", O_UNITS, "U", "g, m/s2 or cm/s2 (= gal) for files that do not name\ntheir unit "
     "(AT2 headers do)", .kind = CLI_UNITS, A(ro.units)},
    {"dt", O_DT, "S", "sample interval for one-column files, s", .kind = CLI_POSITIVE, A(ro.dt_s)},
    {"truncate", O_TRUNCATE, NULL, "cut components of different length to the shortest\n"
     "(default: pad the shorter ones with zeros, said on stderr)", .kind = CLI_FLAG, A(truncate)},
    {"scale-pga", O_SCALE, "G", "scale the whole set so the larger horizontal peak\nacceleration "
     "is G (in g)", .kind = CLI_POSITIVE, A(scale_g), .unit = "g"},
    {.head = "block:"},
    {"base-m", O_BASE, "B", "base width along the weak axis, m (2b)", .kind = CLI_POSITIVE,
     A(base_m), .unit = "m"},
    {"cg-height-m", O_CG, "H", "height of the centre of mass, m (h; the block is 2h tall)",
     .kind = CLI_POSITIVE, A(cg_m), .unit = "m"},
    {"restitution", O_RESTITUTION, "R", "r of the impacts, 0 to 1 (default Housner's\n"
     "1 - 1.5 sin^2(alpha))", .kind = CLI_CALL},
    {"orientation", O_ORIENT, "DEG", "the weak axis turned DEG from H1 toward H2\n"
     "(default: %g orientations, every %g degrees)", {ROCK_N_ORIENT, ROCK_ORIENT_STEP_DEG},
     .kind = CLI_CALL},
    {.head = "integrator:"},
    {"rtol", O_RTOL, "R", "relative accuracy of the peak rotation (default %g,\nfrom %g to %g)",
     {SL_ROCK_DEFAULT_RTOL, SL_ROCK_RTOL_MIN, SL_ROCK_RTOL_MAX}, .kind = CLI_POSITIVE, A(rtol)},
    {"substeps", O_SUBSTEPS, "N", "expert: N fixed sub-steps per sample, no step rule",
     .kind = CLI_CALL},
    {.head = "output:"},
    {"csv", O_CSV, NULL, "one CSV row per orientation on stdout, after '#' lines\n"
     "naming the program and the command: orientation_deg,\npeak_theta_rad, "
     "peak_theta_over_alpha, tipped,\noverturned, impacts, uplifted, uplifts, t_uplift_s,\n"
     "t_peak_s, t_tip_s, t_overturn_s, excursion_mm,\nliftoff_samples, status",
     .kind = CLI_FLAG, A(csv)},
    {"history", O_HISTORY, "OUT.csv", "theta and theta' at every sample and every event,\n"
     "of the governing orientation", .kind = CLI_STRING, A(history)},
};

static int take(void *dst, int key, const char *arg)
{
    rock_args *a = dst;
    unsigned long ul;
    double v;
    if (key == O_SUBSTEPS) {
        if (cli_parse_ulong(arg, &ul) || ul < 1 || ul > SL_ROCK_SUBSTEPS_MAX)
            return cli_usage("rock", "--substeps '%s' must be an integer from 1 to %u", arg,
                             SL_ROCK_SUBSTEPS_MAX);
        a->o.substeps = (unsigned)ul;
    } else if (key == O_RESTITUTION) {
        if (cli_parse_double(arg, &v) || !(v >= 0 && v <= 1))
            return cli_usage("rock", "--restitution '%s' must be a number from 0 to 1", arg);
        a->restitution = v;
        a->has_restitution = 1;
    } else { /* O_ORIENT */
        if (cli_parse_double(arg, &v) || !(fabs(v) <= 360))
            return cli_usage("rock", "--orientation '%s' must be a number of degrees from "
                             "-360 to 360", arg);
        a->orientation_deg = v;
        a->has_orientation = 1;
    }
    return CLI_EXIT_OK;
}

static int check_args(void *dst)
{
    rock_args *a = dst;
    if (!a->path[0])
        return cli_usage("rock", "--h1 FILE is required");
    if (!(a->base_m > 0) || !(a->cg_m > 0))
        return cli_usage("rock", "give the block with --base-m B and --cg-height-m H");
    if (a->rtol > 0 && a->o.substeps)
        return cli_usage("rock", "--substeps replaces the step rule that --rtol sets: give one "
                         "of them");
    if (a->rtol > 0 && !(a->rtol >= SL_ROCK_RTOL_MIN && a->rtol <= SL_ROCK_RTOL_MAX))
        return cli_usage("rock", "--rtol %g must be in [%g, %g]", a->rtol, SL_ROCK_RTOL_MIN,
                         SL_ROCK_RTOL_MAX);
    if (a->rtol > 0)
        a->o.rtol = a->rtol;
    return CLI_EXIT_OK;
}

int rock_parse(int argc, char **argv, rock_args *a)
{
    static const cli_command cmd = {"rock", rock_head, rock_tail, opts, CLI_NOPTS(opts), 25,
                                    take, check_args, 0};
    *a = (rock_args){.ro = {SL_FORMAT_AUTO, SL_UNIT_NONE, 0.0}, .restitution = -1.0};
    sl_rock_opts_default(&a->o);
    return cli_command_parse(&cmd, argc, argv, a);
}
