/* setdir.c - a three-component set from a folder of .AT2 files (setdir.h). */
#include "io/setdir.h"

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

sl_status sl_set_read_dir(const char *dir, sl_set *set, sl_error *err)
{
    memset(set, 0, sizeof *set);
    char pattern[SETDIR_PATH_MAX];
    if (snprintf(pattern, sizeof pattern, "%s/*.AT2", dir) >= (int)sizeof pattern)
        return sl_error_set(err, SL_EINVAL, dir, 0, "folder name too long");
    glob_t g;
    int gr = glob(pattern, 0, NULL, &g); /* sorted by name */
    if (gr != 0) {
        if (gr != GLOB_NOMATCH)
            globfree(&g);
        return sl_error_set(err, SL_EIO, dir, 0, "no .AT2 files in this folder");
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
