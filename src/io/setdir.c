/* setdir.c - a three-component set from a folder of .AT2 files (setdir.h). */
#include "io/setdir.h"

#include "io/formats.h"

#include <glob.h>
#include <stdio.h>
#include <string.h>

/* Longest folder pattern accepted. */
#define SETDIR_PATH_MAX 4096

void sl_set_free_motions(sl_set *set)
{
    if (!set)
        return;
    sl_motion_free(set->h1);
    sl_motion_free(set->h2);
    sl_motion_free(set->v);
    memset(set, 0, sizeof *set);
}

/* The first file in dir matching one of the patterns (sorted by name), copied
 * to out; 0 when none. */
static int first_match(const char *dir, const char *const *pats, size_t np, char *out,
                       size_t outn, size_t *count)
{
    for (size_t k = 0; k < np; k++) {
        char pattern[SETDIR_PATH_MAX];
        if (snprintf(pattern, sizeof pattern, "%s/%s", dir, pats[k]) >= (int)sizeof pattern)
            continue;
        glob_t g;
        if (glob(pattern, 0, NULL, &g) != 0)
            continue;
        *count = g.gl_pathc;
        snprintf(out, outn, "%s", g.gl_pathv[0]);
        globfree(&g);
        return 1;
    }
    return 0;
}

/* A GeoNet V2A or CSMIP V2 file holding the three channels: H1, H2 the
 * horizontals in file order, V the channel whose name is vertical. */
static sl_status read_channels_file(const char *path, sl_set *set, sl_error *err)
{
    sl_channels c;
    sl_status st = sl_channels_read(path, &c, err);
    if (st != SL_OK)
        return st;
    size_t hi[2] = {0, 0}, vi = 0, nh = 0, nv = 0;
    for (size_t k = 0; k < c.n; k++) {
        if (sl_component_is_vertical(c.comp[k])) {
            vi = k;
            nv++;
        } else {
            if (nh < 2)
                hi[nh] = k;
            nh++;
        }
    }
    if (nh != 2 || nv != 1) {
        sl_channels_free(&c);
        return sl_error_set(err, SL_EIO, path, 0,
                            "expected 2 horizontal and 1 vertical channels, found %zu and %zu",
                            nh, nv);
    }
    set->h1 = c.m[hi[0]];
    set->h2 = c.m[hi[1]];
    set->v = c.m[vi];
    c.m[hi[0]] = c.m[hi[1]] = c.m[vi] = NULL;
    sl_channels_free(&c);
    return SL_OK;
}

/* Three USGS SMC files, the vertical by its header's component name. */
static sl_status read_smc(const char *dir, sl_set *set, sl_error *err)
{
    char pattern[SETDIR_PATH_MAX];
    if (snprintf(pattern, sizeof pattern, "%s/*.[sS][mM][cC]", dir) >= (int)sizeof pattern)
        return sl_error_set(err, SL_EINVAL, dir, 0, "folder name too long");
    glob_t g;
    if (glob(pattern, 0, NULL, &g) != 0)
        return sl_error_set(err, SL_EIO, dir, 0, "cannot list the .smc files");
    sl_motion *h[2] = {NULL, NULL}, *v = NULL;
    size_t nh = 0, nv = 0;
    sl_status st = SL_OK;
    for (size_t i = 0; i < g.gl_pathc && st == SL_OK; i++) {
        char comp[SL_COMP_NAME_MAX];
        sl_motion *m = sl_smc_read(g.gl_pathv[i], comp, sizeof comp, err);
        if (!m) {
            st = err ? err->code : SL_EIO;
            break;
        }
        if (sl_component_is_vertical(comp)) {
            nv++;
            if (v)
                sl_motion_free(v);
            v = m;
        } else {
            if (nh < 2)
                h[nh] = m;
            else
                sl_motion_free(m);
            nh++;
        }
    }
    globfree(&g);
    set->h1 = h[0];
    set->h2 = h[1];
    set->v = v;
    if (st == SL_OK && (nh != 2 || nv != 1))
        st = sl_error_set(err, SL_EIO, dir, 0,
                          "expected 2 horizontal and 1 vertical .smc files, found %zu and %zu",
                          nh, nv);
    if (st == SL_OK)
        st = sl_set_check(set, 1, err);
    if (st != SL_OK)
        sl_set_free_motions(set);
    return st;
}

/* No .AT2 files: a .V2A / .V2 file with three channels, or three CWA .acc
 * files (_E, _N, _Z). */
static sl_status read_other(const char *dir, sl_set *set, sl_error *err)
{
    static const char *const multi[] = {"*.V2A", "*.v2a", "*.V2", "*.v2"};
    char path[SETDIR_PATH_MAX];
    size_t count = 0;
    sl_status st;
    if (first_match(dir, multi, sizeof multi / sizeof multi[0], path, sizeof path, &count)) {
        if (count != 1)
            return sl_error_set(err, SL_EIO, dir, 0, "%zu multi-channel files, expected one",
                                count);
        st = read_channels_file(path, set, err);
    } else {
        static const char *const smc[] = {"*.smc", "*.SMC"};
        if (first_match(dir, smc, 2, path, sizeof path, &count))
            return read_smc(dir, set, err);
        char pattern[SETDIR_PATH_MAX];
        if (snprintf(pattern, sizeof pattern, "%s/*.acc", dir) >= (int)sizeof pattern)
            return sl_error_set(err, SL_EINVAL, dir, 0, "folder name too long");
        glob_t g;
        int gr = glob(pattern, 0, NULL, &g);
        if (gr != 0) {
            if (gr != GLOB_NOMATCH)
                globfree(&g);
            return sl_error_set(err, SL_EIO, dir, 0,
                                "no .AT2, .V2A, .V2, .smc or .acc files in this folder");
        }
        const char *hor[2] = {NULL, NULL}, *ver = NULL;
        size_t nh = 0, nv = 0;
        for (size_t i = 0; i < g.gl_pathc; i++) {
            if (sl_motion_name_is_vertical(g.gl_pathv[i])) {
                ver = g.gl_pathv[i];
                nv++;
            } else {
                if (nh < 2)
                    hor[nh] = g.gl_pathv[i];
                nh++;
            }
        }
        if (nh != 2 || nv != 1) {
            globfree(&g);
            return sl_error_set(err, SL_EIO, dir, 0,
                                "expected 2 horizontal and 1 vertical .acc files, found %zu and "
                                "%zu", nh, nv);
        }
        const char *p3[3] = {hor[0], hor[1], ver};
        sl_motion **slot[3] = {&set->h1, &set->h2, &set->v};
        st = SL_OK;
        for (int c = 0; c < 3 && st == SL_OK; c++) {
            *slot[c] = sl_cwa_acc_read(p3[c], err);
            if (!*slot[c])
                st = err ? err->code : SL_EIO;
        }
        globfree(&g);
    }
    if (st == SL_OK)
        st = sl_set_check(set, 1, err);
    if (st != SL_OK)
        sl_set_free_motions(set);
    return st;
}

sl_status sl_set_read_dir(const char *dir, sl_set *set, sl_error *err)
{
    memset(set, 0, sizeof *set);
    char pattern[SETDIR_PATH_MAX];
    if (snprintf(pattern, sizeof pattern, "%s/*.AT2", dir) >= (int)sizeof pattern)
        return sl_error_set(err, SL_EINVAL, dir, 0, "folder name too long");
    glob_t g;
    int gr = glob(pattern, 0, NULL, &g); /* sorted by name */
    if (gr != 0) {
        if (gr != GLOB_NOMATCH) {
            globfree(&g);
            return sl_error_set(err, SL_EIO, dir, 0, "cannot list the folder");
        }
        return read_other(dir, set, err);
    }
    const char *hor[2] = {NULL, NULL}, *ver = NULL;
    size_t nh = 0, nv = 0;
    for (size_t i = 0; i < g.gl_pathc; i++) {
        if (sl_motion_name_is_vertical(g.gl_pathv[i])) {
            ver = g.gl_pathv[i];
            nv++;
        } else {
            if (nh < 2)
                hor[nh] = g.gl_pathv[i];
            nh++;
        }
    }
    if (nh != 2 || nv != 1) {
        globfree(&g);
        return sl_error_set(err, SL_EIO, dir, 0,
                            "expected 2 horizontal and 1 vertical .AT2 files, found %zu and %zu",
                            nh, nv);
    }
    const char *path[3] = {hor[0], hor[1], ver};
    sl_motion **slot[3] = {&set->h1, &set->h2, &set->v};
    sl_read_opts ro;
    memset(&ro, 0, sizeof ro);
    sl_status st = SL_OK;
    for (int c = 0; c < 3 && st == SL_OK; c++) {
        *slot[c] = sl_motion_read(path[c], &ro, err);
        if (!*slot[c])
            st = err ? err->code : SL_EIO;
    }
    globfree(&g);
    if (st == SL_OK)
        st = sl_set_check(set, 1, err);
    if (st != SL_OK)
        sl_set_free_motions(set);
    return st;
}
