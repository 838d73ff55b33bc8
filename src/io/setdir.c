/* setdir.c - a three-component set from a folder of motion files, or from
 * up to three named files (setdir.h). */
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

/* A file reader of one agency format; comp (size nc) gets the component
 * name from the header where the format has one. */
typedef sl_motion *(*setdir_reader)(const char *path, char *comp, size_t nc, sl_error *err);

static sl_motion *read_at2(const char *path, char *comp, size_t nc, sl_error *err)
{
    (void)comp, (void)nc;
    sl_read_opts ro;
    memset(&ro, 0, sizeof ro);
    return sl_motion_read(path, &ro, err);
}

static sl_motion *read_acc(const char *path, char *comp, size_t nc, sl_error *err)
{
    (void)comp, (void)nc;
    return sl_cwa_acc_read(path, err);
}

/* How a format's files make a set. */
typedef enum setdir_layout {
    SETDIR_BY_NAME,   /* one file per component, the vertical by its file name */
    SETDIR_BY_HEADER, /* one file per component, the vertical by its header */
    SETDIR_CHANNELS   /* one file holding the three channels */
} setdir_layout;

/* The formats, in the order they are looked for: the first whose `find`
 * patterns match a file of the folder is read (files: `list`). */
static const struct setdir_format {
    const char *find[4]; /* glob patterns, tried in order; NULL-terminated */
    const char *list;    /* the files of the set (one per component) */
    const char *ext;     /* in messages */
    setdir_layout layout;
    setdir_reader read;
} formats[] = {
    {{"*.AT2"}, "*.AT2", ".AT2", SETDIR_BY_NAME, read_at2},
    {{"*.V2A", "*.v2a", "*.V2", "*.v2"}, NULL, NULL, SETDIR_CHANNELS, NULL},
    {{"*.smc", "*.SMC"}, "*.[sS][mM][cC]", ".smc", SETDIR_BY_HEADER, sl_smc_read},
    {{"*.acc"}, "*.acc", ".acc", SETDIR_BY_NAME, read_acc},
};
#define SETDIR_NFORMATS (sizeof formats / sizeof formats[0])

/* glob dir/pat into g (sorted by name). Returns 0 (the caller frees g), or
 * with nothing to free GLOB_NOMATCH, another glob error, or -1 for a name
 * too long. */
static int list_dir(const char *dir, const char *pat, glob_t *g)
{
    char pattern[SETDIR_PATH_MAX];
    if (snprintf(pattern, sizeof pattern, "%s/%s", dir, pat) >= (int)sizeof pattern)
        return -1;
    int gr = glob(pattern, 0, NULL, g);
    if (gr != 0 && gr != GLOB_NOMATCH)
        globfree(g);
    return gr;
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

/* One file per component: the files g of format f. By name, the vertical
 * is told before any file is read; by header, every file is read and the
 * vertical is the (last) one whose component name is vertical. H1, H2: the
 * first two horizontals in name order. */
static sl_status read_per_component(const char *dir, const struct setdir_format *f,
                                    const glob_t *g, sl_set *set, sl_error *err)
{
    sl_motion *h[2] = {NULL, NULL}, *v = NULL;
    const char *hp[2] = {NULL, NULL}, *vp = NULL;
    size_t nh = 0, nv = 0;
    sl_status st = SL_OK;
    for (size_t i = 0; i < g->gl_pathc && st == SL_OK; i++) {
        const char *path = g->gl_pathv[i];
        char comp[SL_COMP_NAME_MAX];
        sl_motion *m = NULL;
        if (f->layout == SETDIR_BY_HEADER && !(m = f->read(path, comp, sizeof comp, err))) {
            st = err ? err->code : SL_EIO;
        } else if (f->layout == SETDIR_BY_HEADER ? sl_component_is_vertical(comp)
                                                 : sl_motion_name_is_vertical(path)) {
            nv++;
            sl_motion_free(v);
            v = m;
            vp = path;
        } else {
            if (nh < 2) {
                h[nh] = m;
                hp[nh] = path;
            } else {
                sl_motion_free(m);
            }
            nh++;
        }
    }
    *set = (sl_set){h[0], h[1], v};
    if (st == SL_OK && (nh != 2 || nv != 1))
        st = sl_error_set(err, SL_EIO, dir, 0,
                          "expected 2 horizontal and 1 vertical %s files, found %zu and %zu",
                          f->ext, nh, nv);
    const char *p3[3] = {hp[0], hp[1], vp};
    sl_motion **slot[3] = {&set->h1, &set->h2, &set->v};
    for (int c = 0; c < 3 && st == SL_OK && f->layout == SETDIR_BY_NAME; c++)
        if (!(*slot[c] = f->read(p3[c], NULL, 0, err)))
            st = err ? err->code : SL_EIO;
    return st;
}

sl_status sl_set_read_dir(const char *dir, sl_set *set, sl_error *err)
{
    memset(set, 0, sizeof *set);
    const struct setdir_format *f = NULL;
    glob_t g;
    size_t count = 0;
    for (size_t i = 0; i < SETDIR_NFORMATS && !f; i++)
        for (size_t k = 0; k < 4 && formats[i].find[k] && !f; k++) {
            int gr = list_dir(dir, formats[i].find[k], &g);
            if (gr == -1)
                return sl_error_set(err, SL_EINVAL, dir, 0, "folder name too long");
            if (gr != 0 && gr != GLOB_NOMATCH)
                return sl_error_set(err, SL_EIO, dir, 0, "cannot list the folder");
            if (gr == 0) {
                f = &formats[i];
                count = g.gl_pathc;
                if (f->list) /* listed again below */
                    globfree(&g);
            }
        }
    if (!f)
        return sl_error_set(err, SL_EIO, dir, 0,
                            "no .AT2, .V2A, .V2, .smc or .acc files in this folder");
    sl_status st;
    if (f->layout == SETDIR_CHANNELS) {
        char path[SETDIR_PATH_MAX];
        snprintf(path, sizeof path, "%s", g.gl_pathv[0]);
        globfree(&g);
        if (count != 1)
            return sl_error_set(err, SL_EIO, dir, 0, "%zu multi-channel files, expected one",
                                count);
        st = read_channels_file(path, set, err);
    } else {
        int gr = list_dir(dir, f->list, &g);
        if (gr == -1)
            return sl_error_set(err, SL_EINVAL, dir, 0, "folder name too long");
        if (gr != 0)
            return sl_error_set(err, SL_EIO, dir, 0, "cannot list the %s files", f->ext);
        st = read_per_component(dir, f, &g, set, err);
        globfree(&g);
    }
    if (st == SL_OK)
        st = sl_set_check(set, 1, err);
    if (st != SL_OK)
        sl_set_free_motions(set);
    return st;
}

sl_status sl_set_read_files(const char *const path[3], const sl_read_opts *ro, int truncate,
                            sl_set *set, sl_set_fit *fit, sl_error *err)
{
    memset(set, 0, sizeof *set);
    sl_motion **slot[3] = {&set->h1, &set->h2, &set->v};
    sl_status st = SL_OK;
    for (int c = 0; c < 3 && st == SL_OK; c++)
        if (path[c] && !(*slot[c] = sl_motion_read(path[c], ro, err)))
            st = err ? err->code : SL_EIO;
    if (st == SL_OK)
        st = sl_set_check_fit(set, truncate, fit, err);
    if (st != SL_OK)
        sl_set_free_motions(set);
    return st;
}
