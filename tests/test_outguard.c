/*
 * test_outguard.c - the output guard's parts on their own (io/outguard.h,
 * io/walk.h), each under injected faults (tests/fsfault.h): the lock (taken
 * only on the file still at its path: a lock file replaced as its holder
 * released it is opened again; every call failed in turn), the output path
 * resolved once ("." and "..", a link followed, a dangling link refused),
 * the manifest written whole or not at all, the walk (order, pruning, a
 * mount point never entered, a folder replaced meanwhile never followed, a
 * path longer than the system takes an error), the carry's refusals, and
 * the removal of a folder that keeps every user's entry.
 */
#define _GNU_SOURCE
#define FSFAULT_NO_SNAPSHOT
#include "fsfault.h"
#include "harness.h"
#include "io/outguard.h"
#include "io/owner.h"
#include "io/walk.h"

static char ROOT[256];
static const int ERRS[] = {EXDEV, EBUSY, ENOSPC, EACCES, ENAMETOOLONG};
#define NERRS (sizeof ERRS / sizeof ERRS[0])

static const char *at(const char *rel)
{
    static char p[8][1200];
    static int k;
    char *s = p[k++ % 8];
    snprintf(s, 1200, "%s/%s", ROOT, rel);
    return s;
}

static void put(const char *rel, const char *text)
{
    char p[1200];
    snprintf(p, sizeof p, "%s", at(rel));
    for (char *s = strchr(p + strlen(ROOT) + 1, '/'); s; s = strchr(s + 1, '/')) {
        *s = '\0';
        mkdir(p, 0755);
        *s = '/';
    }
    fs_put(p, text);
}

/* ---- the lock ------------------------------------------------------------ */

static char lock_file[1200];

/* The holder releasing its lock just as this run locks the file it opened:
 * the file removed and made anew at its path. */
static void replace_lock(int op, long n, const char *path)
{
    (void)path;
    if (op == FS_FLOCK && n == 1) {
        unlink(lock_file);
        fs_put(lock_file, "");
    }
}

static void test_lock_recheck(void)
{
    fs_empty_dir(ROOT);
    mkdir(at("out"), 0755);
    snprintf(lock_file, sizeof lock_file, "%s", at(".out.lock"));
    fs_reset();
    fs_hook = replace_lock;
    sl_error err;
    sl_error_clear(&err);
    sl_outlock *a = sl_outlock_take(at("out"), &err);
    fs_hook = NULL;
    CHECK(a != NULL, "%s", err.msg);
    CHECK(fs_count[FS_OPEN] == 2, "the lock file replaced meanwhile: opened %ld times, not again",
          fs_count[FS_OPEN]);
    /* a second run: refused, naming the first */
    sl_error_clear(&err);
    sl_outlock *b = sl_outlock_take(at("out"), &err);
    CHECK(!b && err.code == SL_EINVAL && strstr(err.msg, "another run is writing"),
          "a second run took the lock the first holds: %s", err.msg);
    sl_outlock_release(b);
    char text[200];
    snprintf(text, sizeof text, "%ld@", (long)getpid());
    CHECK(!strncmp(fs_get(lock_file), text, strlen(text)), "the lock holds '%s'", fs_get(lock_file));
    sl_outlock_release(a);
    CHECK(access(lock_file, F_OK) != 0, "the lock file stayed");
    sl_fsops_install(NULL);
}

/* Each call of taking a lock failed in turn: an error naming the lock, or a
 * lock (one that holds nothing where locks are not supported); never a lock
 * file left by a failure after it was written. */
static void test_lock_faults(void)
{
    fs_empty_dir(ROOT);
    mkdir(at("out"), 0755);
    snprintf(lock_file, sizeof lock_file, "%s", at(".out.lock"));
    sl_error err;
    fs_reset();
    sl_outlock *l = sl_outlock_take(at("out"), &err);
    long clean[FS_NOPS];
    memcpy(clean, fs_count, sizeof clean);
    sl_outlock_release(l);
    int tried = 0;
    for (int op = 0; op < FS_NOPS; op++)
        for (long n = 1; n <= clean[op]; n++)
            for (size_t k = 0; k < NERRS; k++) {
                fs_fail(op, n, ERRS[k]);
                sl_error_clear(&err);
                l = sl_outlock_take(at("out"), &err);
                tried++;
                if (l)
                    CHECK(!sl_outlock_path(l)[0] || !strcmp(sl_outlock_path(l), lock_file),
                          "%s #%ld: %s", fs_op_name[op], n, sl_outlock_path(l));
                else
                    CHECK(err.code && err.msg[0], "%s #%ld (%s): no message", fs_op_name[op], n,
                          strerror(ERRS[k]));
                sl_outlock_release(l);
                unlink(lock_file);
            }
    CHECK(tried > 10, "%d faults", tried);
    sl_fsops_install(NULL);
}

/* ---- the output path resolved once ------------------------------------------- */

static void test_resolve(void)
{
    fs_empty_dir(ROOT);
    mkdir(at("out"), 0755);
    mkdir(at("out/sub"), 0755);
    CHECK(symlink("out", at("link")) == 0, "symlink");
    CHECK(symlink("nowhere", at("dangling")) == 0, "symlink");
    char want[1200], got[4096];
    CHECK(realpath(at("out"), want) != NULL, "realpath");
    const char *same[] = {"out/.", "out/", "out/sub/..", "link", "link/.", "out/./sub/../."};
    for (size_t i = 0; i < sizeof same / sizeof same[0]; i++) {
        sl_error err;
        sl_error_clear(&err);
        CHECK(sl_outdir_resolve(at(same[i]), got, sizeof got, &err) == SL_OK && !strcmp(got, want),
              "%s resolved to %s, not %s (%s)", same[i], got, want, err.msg);
    }
    sl_error err;
    sl_error_clear(&err);
    CHECK(sl_outdir_resolve(at("dangling"), got, sizeof got, &err) == SL_EINVAL &&
              strstr(err.msg, "'nowhere', which does not exist"),
          "a dangling link: %s", err.msg);
    CHECK(sl_outdir_resolve(at("new/deeper/.."), got, sizeof got, &err) == SL_OK &&
              !strcmp(got + strlen(got) - 4, "/new"),
          "a path not made yet: %s", got);
}

/* ---- the manifest ---------------------------------------------------------- */

static void test_manifest_save_faults(void)
{
    fs_empty_dir(ROOT);
    mkdir(at("out"), 0755);
    put("out/" SL_MANIFEST_NAME, SL_MANIFEST_HEAD "\n# old\nplant.csv\n");
    put("out/plant.csv", "p");
    put("out/bld/a.csv", "a");
    const char *old = SL_MANIFEST_HEAD "\n# old\nplant.csv\n";
    sl_error err;
    sl_manifest *m;
    fs_reset();
    CHECK(sl_manifest_list(at("out"), &m, &err) == SL_OK, "%s", err.msg);
    CHECK(sl_manifest_count(m) == 3 && !strcmp(sl_manifest_path(m, 0), "bld/") &&
              !strcmp(sl_manifest_path(m, 1), "bld/a.csv") &&
              !strcmp(sl_manifest_path(m, 2), "plant.csv"),
          "listed %zu", sl_manifest_count(m));
    memset(fs_count, 0, sizeof fs_count);
    CHECK(sl_manifest_save(at("out"), m, "v", &err) == SL_OK, "%s", err.msg);
    long clean[FS_NOPS];
    memcpy(clean, fs_count, sizeof clean);
    char saved[4096];
    snprintf(saved, sizeof saved, "%s", fs_get(at("out/" SL_MANIFEST_NAME)));
    for (int op = 0; op < FS_NOPS; op++)
        for (long n = 1; n <= clean[op]; n++)
            for (size_t k = 0; k < NERRS; k++) {
                sl_fsops_install(NULL);
                put("out/" SL_MANIFEST_NAME, old);
                fs_reset();
                fs_fail(op, n, ERRS[k]);
                sl_error_clear(&err);
                sl_status s = sl_manifest_save(at("out"), m, "v", &err);
                sl_fsops_install(NULL);
                const char *now = fs_get(at("out/" SL_MANIFEST_NAME));
                CHECK(s ? !strcmp(now, old) && strstr(err.msg, "cannot write") : !strcmp(now, saved),
                      "%s #%ld (%s): exit %d, the manifest '%s'", fs_op_name[op], n,
                      strerror(ERRS[k]), s, now);
                CHECK(!fs_count_prefix(at("out"), SL_OUTDIR_TMP_INSIDE), "%s #%ld: a temporary left",
                      fs_op_name[op], n);
            }
    /* read back: the union of two; a restore writes the bytes as read */
    sl_manifest *r, *u;
    put("out/" SL_MANIFEST_NAME, old);
    CHECK(sl_manifest_read(at("out"), &r, &err) == SL_OK && r, "%s", err.msg);
    u = sl_manifest_union(m, r);
    CHECK(sl_manifest_count(u) == 3 && sl_manifest_has(u, "bld/") && sl_manifest_has(u, "plant.csv"),
          "union %zu", sl_manifest_count(u));
    CHECK(sl_manifest_save(at("out"), u, "v", &err) == SL_OK, "%s", err.msg);
    CHECK(sl_manifest_restore(at("out"), r, "v", &err) == SL_OK &&
              !strcmp(fs_get(at("out/" SL_MANIFEST_NAME)), old),
          "restored: '%s'", fs_get(at("out/" SL_MANIFEST_NAME)));
    sl_manifest_free(m);
    sl_manifest_free(r);
    sl_manifest_free(u);
}

/* ---- the walk ------------------------------------------------------------------ */

/* Every entry of a walk of ROOT/rel as "pre:REL" / "post:REL" / "mount:REL". */
static int walk_text(const char *rel, char *buf, size_t n, const char *prune)
{
    int fd = open(at(rel), O_RDONLY | O_DIRECTORY);
    sl_walk *w = sl_walk_open(fd);
    const sl_walk_entry *e;
    int r;
    buf[0] = '\0';
    while ((r = sl_walk_next(w, &e)) == 1) {
        if (n < 64)
            continue; /* only the error */
        size_t used = strlen(buf);
        snprintf(buf + used, n - used, "%s:%s ", e->post ? "post" : e->mount ? "mount" : "pre",
                 e->rel);
        if (prune && !e->post && !strcmp(e->rel, prune))
            sl_walk_prune(w);
    }
    if (r < 0) {
        size_t used = strlen(buf);
        snprintf(buf + used, n - used, "error:%s:%s", strerror(errno), sl_walk_where(w));
    }
    sl_walk_close(w);
    close(fd);
    return r;
}

static const char *replaced_rel;
static void replace_dir(int op, long n, const char *path)
{
    (void)n;
    if (op == FS_OPEN && path && !strcmp(path, replaced_rel)) {
        rename(at("t/b"), at("t/b-old"));
        mkdir(at("t/b"), 0755);
        replaced_rel = "";
    }
}

static void test_walk(void)
{
    fs_empty_dir(ROOT);
    put("t/b/x", "x");
    put("t/a", "a");
    put("t/b/c/y", "y");
    put("t/d/z", "z");
    char text[4096];
    CHECK(walk_text("t", text, sizeof text, NULL) == 0 &&
              !strcmp(text, "pre:a pre:b pre:b/c pre:b/c/y post:b/c pre:b/x post:b pre:d pre:d/z "
                            "post:d "),
          "walk: %s", text);
    CHECK(walk_text("t", text, sizeof text, "b") == 0 &&
              !strcmp(text, "pre:a pre:b pre:d pre:d/z post:d "),
          "pruned: %s", text);
    /* a mount point (as stat says): reported, never entered */
    char mp[1200];
    snprintf(mp, sizeof mp, "%s", at("t/b"));
    fs_reset();
    fs_mount_path = mp;
    CHECK(walk_text("t", text, sizeof text, NULL) == 0 &&
              !strcmp(text, "pre:a mount:b pre:d pre:d/z post:d "),
          "a mount: %s", text);
    /* a folder replaced between its listing and its entering: an error, not followed */
    fs_reset();
    replaced_rel = "b";
    fs_hook = replace_dir;
    CHECK(walk_text("t", text, sizeof text, NULL) < 0 && strstr(text, "error:Stale file handle:b"),
          "replaced: %s", text);
    sl_fsops_install(NULL);
    /* deeper than a path may be: an error naming where, on a small stack */
    int fd = open(at("t"), O_RDONLY | O_DIRECTORY);
    for (int i = 0; i < 2100 && fd >= 0; i++) {
        mkdirat(fd, "d", 0755);
        int next = openat(fd, "d", O_RDONLY | O_DIRECTORY);
        close(fd);
        fd = next;
    }
    if (fd >= 0)
        close(fd);
    char small[60];
    int r = walk_text("t/d", small, sizeof small, NULL);
    CHECK(r < 0 && strstr(small, "error:File name too long:d/d/d"), "2100 deep: %s", small);
}

/* A folder looked up without making "rel/": against sl_manifest_has on the
 * string it stands for, over names that sort next to "a/" ('-' and '.' before
 * '/', a letter after it) and a file of the folder's name. */
static void test_manifest_has_dir(void)
{
    fs_empty_dir(ROOT);
    put("out/" SL_MANIFEST_NAME, SL_MANIFEST_HEAD "\na-b/\na.txt\na/\na/b\nab/\nc\nd/e/\n");
    sl_manifest *m;
    sl_error err;
    CHECK(sl_manifest_read(at("out"), &m, &err) == SL_OK && m, "%s", err.msg);
    const char *q[] = {"a", "a-b", "a.txt", "ab", "a/b", "b", "c", "d", "d/e", "", "a-", "ab/"};
    for (size_t i = 0; m && i < sizeof q / sizeof *q; i++) {
        char slash[16];
        snprintf(slash, sizeof slash, "%s/", q[i]);
        CHECK(!sl_manifest_has_dir(m, q[i]) == !sl_manifest_has(m, slash),
              "'%s': as a folder %d, '%s' listed %d", q[i], sl_manifest_has_dir(m, q[i]), slash,
              sl_manifest_has(m, slash));
    }
    CHECK(m && sl_manifest_has_dir(m, "a") && sl_manifest_has_dir(m, "d/e") &&
              !sl_manifest_has_dir(m, "a.txt") && !sl_manifest_has_dir(m, "d"),
          "folders a, d/e listed; a.txt, d not");
    sl_manifest_free(m);
}

/* ---- carrying and dropping ------------------------------------------------------ */

static void test_carry_refusals(void)
{
    fs_empty_dir(ROOT);
    put("out/" SL_MANIFEST_NAME, SL_MANIFEST_HEAD "\nplant.csv\n");
    put("out/plant.csv", "old");
    put("out/summary.csv", "the user's");
    put("fresh/summary.csv", "the run's");
    sl_manifest *m;
    sl_error err;
    sl_error_clear(&err);
    CHECK(sl_manifest_read(at("out"), &m, &err) == SL_OK, "%s", err.msg);
    sl_carried *c;
    CHECK(sl_manifest_carry(at("out"), at("fresh"), m, 0, &c, &err) == SL_EINVAL &&
              strstr(err.file, "out/summary.csv") && strstr(err.msg, "seislide did not write this"),
          "%s: %s", err.file, err.msg);
    /* a pipe where hard links are refused: an error, not a silent loss */
    fs_empty_dir(ROOT);
    put("out/" SL_MANIFEST_NAME, SL_MANIFEST_HEAD "\n");
    mkdir(at("fresh"), 0755);
    CHECK(mkfifo(at("out/pipe"), 0644) == 0, "mkfifo");
    sl_manifest_free(m);
    sl_manifest_read(at("out"), &m, &err);
    fs_reset();
    fs_fail(FS_LINK, 0, EXDEV);
    sl_error_clear(&err);
    CHECK(sl_manifest_carry(at("out"), at("fresh"), m, 0, &c, &err) == SL_EIO &&
              strstr(err.msg, "cannot keep it"),
          "a pipe: %s", err.msg);
    sl_fsops_install(NULL);
    sl_manifest_free(m);
}

static void test_drop_rules(void)
{
    fs_empty_dir(ROOT);
    put("x/" SL_MANIFEST_NAME, SL_MANIFEST_HEAD "\nout.csv\nbld/\nbld/s.csv\n.seislide-cache/\n");
    put("x/out.csv", "seislide's");
    put("x/bld/s.csv", "seislide's");
    put("x/bld/mine.txt", "mine");       /* dest has the same file (a link): removed */
    put("x/equal.txt", "equal bytes");   /* dest has equal bytes: removed */
    put("x/differs.txt", "version 2");   /* dest differs: kept */
    put("x/only/here.txt", "only here"); /* dest lacks it: moved */
    put("x/.seislide-cache/e.slr", "e"); /* the cache without SL_DROP_CACHE: moved back */
    put("dest/equal.txt", "equal bytes");
    put("dest/differs.txt", "version 1");
    mkdir(at("dest/bld"), 0755);
    CHECK(link(at("x/bld/mine.txt"), at("dest/bld/mine.txt")) == 0, "link");
    char why[2048];
    fs_reset();
    size_t kept = sl_outdir_drop(at("x"), at("dest"), NULL, 0, why, sizeof why);
    sl_fsops_install(NULL);
    CHECK(kept == 1 && strstr(why, "differs.txt: differs"), "kept %zu: %s", kept, why);
    CHECK(!strcmp(fs_get(at("x/differs.txt")), "version 2") &&
              !strcmp(fs_get(at("dest/differs.txt")), "version 1"),
          "the differing file");
    CHECK(access(at("x/" SL_MANIFEST_NAME), F_OK) == 0, "a folder kept without its manifest");
    CHECK(access(at("x/out.csv"), F_OK) != 0 && access(at("x/bld"), F_OK) != 0 &&
              access(at("x/equal.txt"), F_OK) != 0,
          "seislide's or duplicates stayed");
    CHECK(!strcmp(fs_get(at("dest/only/here.txt")), "only here") &&
              !strcmp(fs_get(at("dest/.seislide-cache/e.slr")), "e") &&
              !strcmp(fs_get(at("dest/bld/mine.txt")), "mine"),
          "moved or kept in dest");
    /* once the difference is settled the folder goes */
    unlink(at("x/differs.txt"));
    CHECK(sl_outdir_drop(at("x"), at("dest"), NULL, 0, why, sizeof why) == 0 &&
              access(at("x"), F_OK) != 0,
          "then: %s", why);
    /* a mount point inside (as stat says) is never entered nor removed */
    put("y/m/file", "on the mount");
    char mp[1200];
    snprintf(mp, sizeof mp, "%s", at("y/m"));
    fs_reset();
    fs_mount_path = mp;
    kept = sl_outdir_drop(at("y"), NULL, NULL, SL_DROP_OURS, why, sizeof why);
    sl_fsops_install(NULL);
    CHECK(kept == 1 && strstr(why, "m: a file system is mounted there") &&
              !strcmp(fs_get(at("y/m/file")), "on the mount"),
          "a mount: %zu %s", kept, why);
}

/* ---- mounts ------------------------------------------------------------------ */

static void test_mounts(void)
{
    char first[4096];
    CHECK(sl_path_mount_inside("/", first, sizeof first) || access("/proc/self/mountinfo", R_OK),
          "no mount found under /");
    CHECK(!sl_path_mount_inside(ROOT, first, sizeof first), "a mount inside %s: %s", ROOT, first);
    CHECK(!sl_path_is_mount(ROOT), "%s taken for a mount point", ROOT);
    CHECK(sl_outdir_own_name(SL_MANIFEST_NAME) && sl_outdir_own_name(SL_MANIFEST_CACHE) &&
              sl_outdir_own_name(SL_OUTDIR_LOCK_INSIDE) && sl_outdir_own_name(".seislide.tmp-1@h-abcdef") &&
              !sl_outdir_own_name("seislide-clearance.xlsx") && !sl_outdir_own_name(".seislidex"),
          "own names");
}

int main(void)
{
    const char *t = getenv("TMPDIR");
    if (!t || !*t)
        t = access("/dev/shm", W_OK | X_OK) == 0 ? "/dev/shm" : "/tmp";
    snprintf(ROOT, sizeof ROOT, "%s/seislide-outguard-XXXXXX", t);
    if (!mkdtemp(ROOT)) {
        perror("mkdtemp");
        return 1;
    }
    RUN(test_lock_recheck);
    RUN(test_lock_faults);
    RUN(test_resolve);
    RUN(test_manifest_save_faults);
    RUN(test_walk);
    RUN(test_manifest_has_dir);
    RUN(test_carry_refusals);
    RUN(test_drop_rules);
    RUN(test_mounts);
    sl_fsops_install(NULL);
    fs_empty_dir(ROOT);
    rmdir(ROOT);
    return HARNESS_END("test_outguard");
}
