/* verify_problems.h - the problem functions of the table in verify.c
 * (library-internal; verify.h describes the contract). */
#ifndef SL_VERIFY_PROBLEMS_H
#define SL_VERIFY_PROBLEMS_H

#include "verify/verify.h"

#define SL_VERIFY_FN(name) \
    sl_status name(const sl_verify_ctx *ctx, sl_verify_value *v, sl_error *err)

SL_VERIFY_FN(sl_verify_e01_pulse);
SL_VERIFY_FN(sl_verify_e02_newmark);
SL_VERIFY_FN(sl_verify_e03_half_sine);
SL_VERIFY_FN(sl_verify_e04_half_sine);
SL_VERIFY_FN(sl_verify_e05_one_way);
SL_VERIFY_FN(sl_verify_e06_45deg);
SL_VERIFY_FN(sl_verify_e07_20deg);
SL_VERIFY_FN(sl_verify_e08_rotation);
SL_VERIFY_FN(sl_verify_e09_vertical);
SL_VERIFY_FN(sl_verify_e10_liftoff);
SL_VERIFY_FN(sl_verify_e11_threshold);
SL_VERIFY_FN(sl_verify_h01_uplift);
SL_VERIFY_FN(sl_verify_h02_uplift_vertical);
SL_VERIFY_FN(sl_verify_h03_restitution);
SL_VERIFY_FN(sl_verify_h04_period_linear);
SL_VERIFY_FN(sl_verify_h05_period_exact);
SL_VERIFY_FN(sl_verify_h06_energy);
SL_VERIFY_FN(sl_verify_h07_pulse_linear);
SL_VERIFY_FN(sl_verify_h08_pulse_exact);
SL_VERIFY_FN(sl_verify_r01_smooth);
SL_VERIFY_FN(sl_verify_r02_plastic);
SL_VERIFY_FN(sl_verify_r03_smooth_vertical);
SL_VERIFY_FN(sl_verify_r04_plastic_vertical);
SL_VERIFY_FN(sl_verify_s01_step5);
SL_VERIFY_FN(sl_verify_s02_step10);
SL_VERIFY_FN(sl_verify_s03_pulse);
SL_VERIFY_FN(sl_verify_s04_resonance);
SL_VERIFY_FN(sl_verify_g01);
SL_VERIFY_FN(sl_verify_g02);
SL_VERIFY_FN(sl_verify_g03);
SL_VERIFY_FN(sl_verify_g04);
SL_VERIFY_FN(sl_verify_g05);
SL_VERIFY_FN(sl_verify_g06);
SL_VERIFY_FN(sl_verify_g07);
SL_VERIFY_FN(sl_verify_g08);
SL_VERIFY_FN(sl_verify_a01);
SL_VERIFY_FN(sl_verify_a02);
SL_VERIFY_FN(sl_verify_a03);
SL_VERIFY_FN(sl_verify_a04);
SL_VERIFY_FN(sl_verify_a05);
SL_VERIFY_FN(sl_verify_a06);
SL_VERIFY_FN(sl_verify_a07);
SL_VERIFY_FN(sl_verify_y01);
SL_VERIFY_FN(sl_verify_y02);
SL_VERIFY_FN(sl_verify_y03);
SL_VERIFY_FN(sl_verify_y04);
SL_VERIFY_FN(sl_verify_y05);
SL_VERIFY_FN(sl_verify_y06);
SL_VERIFY_FN(sl_verify_y07);
SL_VERIFY_FN(sl_verify_t01);
SL_VERIFY_FN(sl_verify_t02);
SL_VERIFY_FN(sl_verify_t03);
SL_VERIFY_FN(sl_verify_t04);
SL_VERIFY_FN(sl_verify_t05);
SL_VERIFY_FN(sl_verify_t06);
SL_VERIFY_FN(sl_verify_i01);
SL_VERIFY_FN(sl_verify_i02);
SL_VERIFY_FN(sl_verify_i03);
SL_VERIFY_FN(sl_verify_i04);
SL_VERIFY_FN(sl_verify_w01);
SL_VERIFY_FN(sl_verify_w02);

/* A cell of column B (row 1-based, as in a formula): a number, or a text
 * when text is not NULL. */
typedef struct sl_verify_cell {
    int row;
    double num;
    const char *text;
} sl_verify_cell;

/* Evaluate a Lookup formula f ("=IF(B5<>\"ok\",...)") over the cells;
 * *num its value, *is_text 1 when it is a text. Returns SL_OK, or SL_EPARSE
 * for a formula outside the subset (verify_formula.c) or a cell not given. */
sl_status sl_verify_formula_eval(const char *f, const sl_verify_cell *cells, size_t n_cells,
                                 double *num, int *is_text, sl_error *err);

#endif
