/* synth_output.h - the files of `seislide synth`: the output folder, the
 * motion files (AT2 or CSV) and report.csv (one row per motion with every
 * check, docs/synthesis.md). */
#ifndef SL_CLI_SYNTH_OUTPUT_H
#define SL_CLI_SYNTH_OUTPUT_H

#include <stddef.h>

#include "io/floor.h"
#include "synth/synth.h"

/* Longest path built for an output file. */
#define SYNTH_PATH_MAX 4096

/* What the files say besides the motions. */
typedef struct synth_output {
    const char *outdir;                    /* the folder */
    int csv;                               /* 1: CSV motion files, 0: AT2 */
    unsigned long long seed;               /* of generated sets */
    const char *const *match;              /* --match paths (H1, H2, V), NULL when generated */
    const char (*desc)[512];               /* each component's target, for report and title */
    const sl_synth_params *p;              /* the limits, repeated in the report */
} synth_output;

/* Write every motion of the nsets sets and DIR/report.csv (each atomic).
 * Returns CLI_EXIT_OK or CLI_EXIT_ERROR (message printed). */
int synth_write_outputs(const synth_output *o, const sl_synth_set *sets, size_t nsets);

/* Print (stderr) the set-mean check of every other damping of a floor file
 * (sl_synth_check_dampings) of sets[0..nsets-1]: one line per component
 * and damping. Reported, not part of the exit status (docs/synthesis.md 4). */
void synth_print_dampings(const sl_synth_set *sets, size_t nsets, const sl_synth_params *p);

/* Describe each component's target for the report and the AT2 title: the
 * floor file fl, or (fl NULL) RG 1.60 at rg_pga_g, g. */
void synth_describe_targets(const sl_floor *fl, double rg_pga_g,
                            const sl_synth_target tgt[SL_SYNTH_NCOMP],
                            char desc[SL_SYNTH_NCOMP][512]);

#endif
