/*
 * test_atomic.c - an output folder replaced whole (io/atomic.h), under every
 * fault: each file-system call of a commit (open to rename, the walks, the
 * carry, the swap, the removal of the old outputs) made to fail in turn with
 * EXDEV, EBUSY, ENOSPC, EACCES and ENAMETOOLONG (tests/fsfault.h), both ways
 * a folder is replaced (a sibling swapped in; entry by entry in place, as on
 * a mount point). After each: the folder holds the whole old outputs or the
 * whole new ones, every user's byte in place (a snapshot of the whole tree:
 * paths, types, modes, link targets, bytes), the cache in it, nothing left
 * beside or inside it; a failure after the swap says where the old outputs
 * were kept. Then the paths of issue 39: a user's save between the carry
 * and the swap (a rename over the file, a file added, a change in place on
 * a file system without hard links), a mount point inside the folder (a
 * stat that says so), a user's folder nested 300 deep carried on a 256 KiB
 * stack and one deeper than a path may be (an error, nothing changed), a
 * write-protected folder, and what killed runs left.
 */
#define _GNU_SOURCE
#include <pthread.h>
#include <sys/time.h>

#include "fsfault.h"
#include "harness.h"
#include "io/atomic.h"
#include "io/outguard.h"
#include "io/owner.h"

static char ROOT[256], OUT[300];
static const int ERRS[] = {EXDEV, EBUSY, ENOSPC, EACCES, ENAMETOOLONG};
#define NERRS (sizeof ERRS / sizeof ERRS[0])

/* dir/rel written (its folders made). */
static void put(const char *dir, const char *rel, const char *text)
{
    char p[1200];
    snprintf(p, sizeof p, "%s/%s", dir, rel);
    for (char *s = strchr(p + strlen(dir) + 1, '/'); s; s = strchr(s + 1, '/')) {
        *s = '\0';
        mkdir(p, 0755);
        *s = '/';
    }
    fs_put(p, text);
}

/* The older outputs of a run (its manifest, two buildings, the cache) and
 * the user's entries: a note, one inside a building folder, one in a
 * building the next run no longer writes, a folder of its own (mode 0750)
 * and a symbolic link. */
static void build_old(void)
{
    fs_empty_dir(ROOT);
    mkdir(OUT, 0755);
    put(OUT, SL_MANIFEST_NAME, SL_MANIFEST_HEAD "\n# test\n.seislide-cache/\nbldA/\n"
        "bldA/summary.csv\nbldB/\nbldB/summary.csv\nplant.csv\n");
    put(OUT, "plant.csv", "old plant");
    put(OUT, "bldA/summary.csv", "old A");
    put(OUT, "bldB/summary.csv", "old B");
    put(OUT, ".seislide-cache/e1.slr", "entry 1");
    put(OUT, "notes.txt", "my notes");
    put(OUT, "bldA/mine.txt", "mine A");
    put(OUT, "bldB/keep.txt", "keep B");
    put(OUT, "drawings/a/b/c.txt", "deep");
    char p[600];
    snprintf(p, sizeof p, "%s/drawings/a", OUT);
    chmod(p, 0750);
    snprintf(p, sizeof p, "%s/link", OUT);
    if (symlink("notes.txt", p) != 0)
        perror("symlink");
}

/* What the new run writes into its fresh folder. */
static void write_new(const char *fresh)
{
    put(fresh, "plant.csv", "new plant");
    put(fresh, "bldA/summary.csv", "new A");
    put(fresh, "bldC/summary.csv", "new C");
}

/* Called between the carry and the swap (a user's save), or NULL. */
static void (*between)(void);

/* One run into OUT: open, write, take the cache, prepare, commit (as the
 * command line does); msg gets the error. */
static sl_status run_once(sl_atomic_how how, char *msg, size_t nmsg)
{
    sl_error err;
    sl_error_clear(&err);
    msg[0] = '\0';
    sl_atomic_dir *d = sl_atomic_dir_open_how(OUT, "seislide test", how, &err);
    sl_status s = d ? SL_OK : err.code;
    if (d) {
        const sl_fsops *was = sl_fsops_install(NULL); /* the run's own writes: no fault */
        write_new(sl_atomic_dir_path(d));
        sl_fsops_install(was);
        s = sl_atomic_dir_take(d, SL_MANIFEST_CACHE, &err);
        if (!s)
            s = sl_atomic_dir_prepare(d, &err);
        if (!s && between)
            between();
        if (s) {
            char why[2048];
            sl_atomic_dir_abort(d, why, sizeof why);
            snprintf(msg, nmsg, "%.1000s %.1000s", err.msg, why);
            return s;
        }
        s = sl_atomic_dir_commit(d, &err);
    }
    snprintf(msg, nmsg, "%s", err.msg);
    return s;
}

/* Entries beside OUT or inside it that a run left: fresh folders, old ones,
 * temporary manifests. */
static int leftovers(void)
{
    return fs_count_prefix(ROOT, ".out") + fs_count_prefix(OUT, SL_OUTDIR_OWN_PREFIX);
}

static char *OLD_SNAP, *NEW_SNAP;
static int sweep_no_flags; /* the sweep on a file system without renameat2's flags */
static long CLEAN[FS_NOPS];

/* A fault-free run: its snapshot (the new state) and its calls counted. */
static void reference(sl_atomic_how how)
{
    char msg[2048];
    build_old();
    free(OLD_SNAP);
    OLD_SNAP = fs_snapshot(OUT);
    fs_reset();
    fs_no_rename_flags = sweep_no_flags;
    sl_status s = run_once(how, msg, sizeof msg);
    memcpy(CLEAN, fs_count, sizeof CLEAN);
    sl_fsops_install(NULL);
    CHECK(s == SL_OK, "reference run: %s", msg);
    free(NEW_SNAP);
    NEW_SNAP = fs_snapshot(OUT);
    CHECK(!leftovers(), "reference run: %d left", leftovers());
}

/* The new state is the one expected, checked once by hand. */
static void check_new_state(const char *how)
{
    char p[600];
    struct {
        const char *rel, *text;
    } want[] = {{"plant.csv", "new plant"},   {"bldA/summary.csv", "new A"},
                {"bldC/summary.csv", "new C"}, {"notes.txt", "my notes"},
                {"bldA/mine.txt", "mine A"},  {"bldB/keep.txt", "keep B"},
                {"drawings/a/b/c.txt", "deep"}, {".seislide-cache/e1.slr", "entry 1"}};
    for (size_t i = 0; i < sizeof want / sizeof want[0]; i++) {
        snprintf(p, sizeof p, "%s/%s", OUT, want[i].rel);
        CHECK(!strcmp(fs_get(p), want[i].text), "%s: %s holds '%s'", how, want[i].rel, fs_get(p));
    }
    snprintf(p, sizeof p, "%s/bldB/summary.csv", OUT);
    CHECK(access(p, F_OK) != 0, "%s: an output the run no longer writes stayed", how);
    struct stat st;
    snprintf(p, sizeof p, "%s/drawings/a", OUT);
    CHECK(stat(p, &st) == 0 && (st.st_mode & 07777) == 0750, "%s: a user's folder lost its mode",
          how);
    snprintf(p, sizeof p, "%s/link", OUT);
    char t[64] = "";
    ssize_t k = readlink(p, t, sizeof t - 1);
    t[k > 0 ? k : 0] = '\0';
    CHECK(!strcmp(t, "notes.txt"), "%s: the link is '%s'", how, t);
    snprintf(p, sizeof p, "%s/" SL_MANIFEST_NAME, OUT);
    const char *m = fs_get(p);
    CHECK(strstr(m, "\nbldC/summary.csv\n") && strstr(m, "\n.seislide-cache/\n") &&
              !strstr(m, "notes") && !strstr(m, "bldB"),
          "%s: the manifest: %s", how, m);
}

/* The lines of a snapshot under a folder kept inside OUT, taken out. */
static void drop_kept(char *snap)
{
    char *w = snap;
    for (char *r = snap; *r;) {
        char *nl = strchr(r, '\n');
        size_t k = nl ? (size_t)(nl - r) + 1 : strlen(r);
        if (strncmp(r, "/" SL_OUTDIR_OWN_PREFIX, strlen("/" SL_OUTDIR_OWN_PREFIX)) != 0) {
            memmove(w, r, k);
            w += k;
        }
        r += k;
    }
    *w = '\0';
}

/* Every call of a commit failed in turn with each errno: the old state or
 * the new one, every user's byte in place, nothing left. no_flags: on a file
 * system without renameat2's flags (the two- and three-rename fallbacks). */
static void sweep(sl_atomic_how how, const char *name)
{
    reference(how);
    check_new_state(name);
    long tried = 0, failed_runs = 0, kept_after = 0;
    char msg[2048];
    for (int op = 0; op < FS_NOPS; op++)
        for (long n = 1; n <= CLEAN[op]; n++)
            for (size_t k = 0; k < NERRS; k++) {
                build_old();
                fs_reset();
                fs_no_rename_flags = sweep_no_flags;
                fs_fail(op, n, ERRS[k]);
                sl_status s = run_once(how, msg, sizeof msg);
                sl_fsops_install(NULL);
                tried++;
                char *snap = fs_snapshot(OUT);
                if (s != SL_OK && strstr(msg, "new outputs are in place"))
                    drop_kept(snap); /* written in place: the old ones kept inside */
                int is_old = !strcmp(snap, OLD_SNAP), is_new = !strcmp(snap, NEW_SNAP);
                const char *what = fs_op_name[op];
                if (s == SL_OK) {
                    CHECK(is_new, "%s: %s #%ld failed (%s), the run succeeded, the folder is "
                          "neither old nor new:\n%s", name, what, n, strerror(ERRS[k]), snap);
                    CHECK(!leftovers(), "%s: %s #%ld (%s): %d left", name, what, n,
                          strerror(ERRS[k]), leftovers());
                } else {
                    failed_runs++;
                    int after = is_new && strstr(msg, "new outputs are in place");
                    kept_after += after;
                    CHECK(is_old || after, "%s: %s #%ld failed (%s): '%s', and the folder is "
                          "%s:\n%s", name, what, n, strerror(ERRS[k]), msg,
                          is_new ? "new (not said)" : "neither old nor new", snap);
                    CHECK(!is_old || !leftovers(), "%s: %s #%ld (%s): the folder as it was, "
                          "but %d left: %s", name, what, n, strerror(ERRS[k]), leftovers(), msg);
                    CHECK(msg[0], "%s: %s #%ld (%s): an error without a message", name, what, n,
                          strerror(ERRS[k]));
                }
                free(snap);
            }
    fprintf(stderr, "  %s: %ld faults injected (%ld calls x %zu errnos), %ld runs failed, %ld "
            "of them after the swap\n", name, tried, tried / (long)NERRS, NERRS, failed_runs,
            kept_after);
    CHECK(failed_runs > tried / 2, "%s: only %ld of %ld faults failed the run", name,
          failed_runs, tried);
}

static void test_faults_swap(void) { sweep(SL_ATOMIC_SWAP, "swap"); }
static void test_faults_in_place(void) { sweep(SL_ATOMIC_IN_PLACE, "in place"); }
static void test_faults_without_rename_flags(void)
{
    sweep_no_flags = 1;
    sweep(SL_ATOMIC_SWAP, "swap, two renames");
    sweep(SL_ATOMIC_IN_PLACE, "in place, three renames an entry");
    sweep_no_flags = 0;
}

/* Item 5 of issue 39: the swap refused (EBUSY): the cache back, the folder as it was. */
static void test_swap_refused_keeps_cache(void)
{
    char msg[2048], p[600];
    build_old();
    char *before = fs_snapshot(OUT);
    fs_reset();
    fs_fail(FS_RENAME, 0, EBUSY); /* every rename: the cache is taken by one */
    sl_status s = run_once(SL_ATOMIC_SWAP, msg, sizeof msg);
    sl_fsops_install(NULL);
    CHECK(s != SL_OK, "the run succeeded");
    /* each rename refused in turn */
    for (long n = 1; n <= 20; n++) {
        build_old();
        fs_reset();
        fs_fail(FS_RENAME, n, EBUSY);
        s = run_once(SL_ATOMIC_SWAP, msg, sizeof msg);
        sl_fsops_install(NULL);
        snprintf(p, sizeof p, "%s/.seislide-cache/e1.slr", OUT);
        char *snap = fs_snapshot(OUT);
        CHECK(!strcmp(fs_get(p), "entry 1"), "rename #%ld refused: the cache is gone (%s)", n, msg);
        CHECK(s == SL_OK || !strcmp(snap, before) || strstr(msg, "new outputs are in place"),
              "rename #%ld refused: %s", n, msg);
        free(snap);
    }
    free(before);
}

/* A user's folder where the run writes one (merged: the user's files kept),
 * and a user's file where the run writes one (refused before the swap,
 * nothing changed), both ways. */
static void test_user_entry_where_run_writes(void)
{
    static const sl_atomic_how how[2] = {SL_ATOMIC_SWAP, SL_ATOMIC_IN_PLACE};
    char msg[2048], p[600];
    for (int i = 0; i < 2; i++) {
        const char *name = i ? "in place" : "swap";
        build_old();
        put(OUT, "bldC/notes.txt", "the user's bldC");
        fs_reset();
        sl_status s = run_once(how[i], msg, sizeof msg);
        sl_fsops_install(NULL);
        snprintf(p, sizeof p, "%s/bldC/notes.txt", OUT);
        CHECK(s == SL_OK && !strcmp(fs_get(p), "the user's bldC"), "%s: a user's folder where the "
              "run writes one: %s, '%s'", name, msg, fs_get(p));
        snprintf(p, sizeof p, "%s/bldC/summary.csv", OUT);
        CHECK(!strcmp(fs_get(p), "new C"), "%s: the run's file: '%s'", name, fs_get(p));
        CHECK(!leftovers(), "%s: %d left", name, leftovers());
        build_old();
        put(OUT, "bldC/summary.csv", "the user's summary");
        put(OUT, "plant.txt", "x");
        char *before = fs_snapshot(OUT);
        fs_reset();
        s = run_once(how[i], msg, sizeof msg);
        sl_fsops_install(NULL);
        char *after = fs_snapshot(OUT);
        CHECK(s == SL_EINVAL && strstr(msg, "seislide did not write this"), "%s: %s", name, msg);
        CHECK(!strcmp(before, after) && !leftovers(), "%s: a user's file where the run writes one: "
              "the folder changed", name);
        free(before);
        free(after);
        /* at the top: the same */
        build_old();
        snprintf(p, sizeof p, "%s/" SL_MANIFEST_NAME, OUT); /* plant.csv no longer the run's */
        fs_put(p, SL_MANIFEST_HEAD "\n.seislide-cache/\nbldA/\nbldA/summary.csv\n");
        before = fs_snapshot(OUT);
        fs_reset();
        s = run_once(how[i], msg, sizeof msg);
        sl_fsops_install(NULL);
        after = fs_snapshot(OUT);
        CHECK(s == SL_EINVAL && strstr(msg, "seislide did not write this"), "%s, top: %s", name, msg);
        CHECK(!strcmp(before, after) && !leftovers(), "%s: a user's plant.csv: the folder changed",
              name);
        free(before);
        free(after);
    }
}

/* Item 7: saved while the run finishes. */
static void save_edits(void)
{
    char p[600], q[600];
    snprintf(p, sizeof p, "%s/notes.txt.tmp", OUT); /* an editor: a new file renamed over */
    snprintf(q, sizeof q, "%s/notes.txt", OUT);
    fs_put(p, "edited");
    rename(p, q);
    put(OUT, "added.txt", "added");
    put(OUT, "bldA/added.txt", "added A");
    put(OUT, "newdir/x/y.txt", "new folder");
    put(OUT, "bldB/later.txt", "later B");
}

static void edits_kept(const char *name)
{
    char p[600];
    struct {
        const char *rel, *text;
    } want[] = {{"notes.txt", "edited"}, {"added.txt", "added"}, {"bldA/added.txt", "added A"},
                {"newdir/x/y.txt", "new folder"}, {"bldB/later.txt", "later B"},
                {"bldA/mine.txt", "mine A"}, {"plant.csv", "new plant"}};
    for (size_t i = 0; i < sizeof want / sizeof want[0]; i++) {
        snprintf(p, sizeof p, "%s/%s", OUT, want[i].rel);
        CHECK(!strcmp(fs_get(p), want[i].text), "%s: %s holds '%s', not '%s'", name, want[i].rel,
              fs_get(p), want[i].text);
    }
    CHECK(!leftovers(), "%s: %d left", name, leftovers());
}

static void test_saved_while_finishing(void)
{
    static const sl_atomic_how how[2] = {SL_ATOMIC_SWAP, SL_ATOMIC_IN_PLACE};
    char msg[2048];
    for (int i = 0; i < 2; i++) {
        build_old();
        fs_reset();
        between = save_edits;
        sl_status s = run_once(how[i], msg, sizeof msg);
        between = NULL;
        sl_fsops_install(NULL);
        CHECK(s == SL_OK, "%s", msg);
        edits_kept(i ? "in place" : "swap");
    }
}

/* The same on a file system without hard links (copies): a change in place
 * (same file, new time) after the copy wins too. */
static void change_in_place(void)
{
    char p[600];
    snprintf(p, sizeof p, "%s/bldA/mine.txt", OUT);
    fs_put(p, "mine A, changed");
    struct timeval tv[2];
    gettimeofday(&tv[0], NULL);
    tv[0].tv_sec += 5;
    tv[1] = tv[0];
    utimes(p, tv);
    save_edits();
}

static void test_saved_without_hard_links(void)
{
    static const sl_atomic_how how[2] = {SL_ATOMIC_SWAP, SL_ATOMIC_IN_PLACE};
    char msg[2048], p[600];
    for (int i = 0; i < 2; i++) {
        build_old();
        fs_reset();
        fs_fail(FS_LINK, 0, EXDEV); /* every hard link refused: copies */
        between = change_in_place;
        sl_status s = run_once(how[i], msg, sizeof msg);
        between = NULL;
        sl_fsops_install(NULL);
        CHECK(s == SL_OK, "%s", msg);
        snprintf(p, sizeof p, "%s/bldA/mine.txt", OUT);
        CHECK(!strcmp(fs_get(p), "mine A, changed"), "changed in place after the copy: '%s'",
              fs_get(p));
        snprintf(p, sizeof p, "%s/drawings/a/b/c.txt", OUT);
        CHECK(!strcmp(fs_get(p), "deep"), "a copied file: '%s'", fs_get(p));
        CHECK(!leftovers(), "%d left", leftovers());
    }
}

/* Item 3: a mount point inside the folder (a stat that says so): refused,
 * nothing changed; and item 4: the folder itself one: written in place. */
static void test_mount_points(void)
{
    char msg[2048], p[600];
    build_old();
    char *before = fs_snapshot(OUT);
    fs_reset();
    snprintf(p, sizeof p, "%s/drawings/a", OUT);
    fs_mount_path = p;
    sl_status s = run_once(SL_ATOMIC_SWAP, msg, sizeof msg);
    sl_fsops_install(NULL);
    char *after = fs_snapshot(OUT);
    CHECK(s == SL_EINVAL && strstr(msg, "a file system is mounted here"), "%s", msg);
    CHECK(!strcmp(before, after) && !leftovers(), "a mount inside: the folder changed");
    free(after);
    /* the removal never enters a mount: a fresh folder holding one keeps it */
    fs_reset();
    snprintf(p, sizeof p, "%s/drawings", OUT);
    fs_mount_path = p;
    CHECK(sl_remove_tree(OUT) != 0, "a tree with a mount point was removed whole");
    sl_fsops_install(NULL);
    snprintf(p, sizeof p, "%s/drawings/a/b/c.txt", OUT);
    CHECK(!strcmp(fs_get(p), "deep"), "the mount's file: '%s'", fs_get(p));
    /* the folder a mount point: written in place */
    build_old();
    fs_reset();
    fs_mount_path = OUT;
    sl_error err;
    sl_error_clear(&err);
    sl_atomic_dir *d = sl_atomic_dir_open(OUT, "seislide test", &err);
    CHECK(d && sl_atomic_dir_in_place(d), "a mount point not written in place: %s", err.msg);
    CHECK(d && !strncmp(sl_atomic_dir_path(d), OUT, strlen(OUT)), "its fresh folder: %s",
          d ? sl_atomic_dir_path(d) : "");
    sl_atomic_dir_abort(d, NULL, 0);
    sl_fsops_install(NULL);
    free(before);
}

/* Item 8: a write-protected folder is refused, nothing changed. */
static void test_write_protected(void)
{
    build_old();
    chmod(OUT, 0555);
    char *before = fs_snapshot(OUT);
    sl_error err;
    sl_error_clear(&err);
    sl_atomic_dir *d = sl_atomic_dir_open(OUT, "seislide test", &err);
    CHECK(!d && err.code == SL_EIO && strstr(err.msg, "write-protected") &&
              !strcmp(err.file, OUT),
          "%s: %s", err.file, err.msg);
    sl_atomic_dir_abort(d, NULL, 0);
    char *after = fs_snapshot(OUT);
    CHECK(!strcmp(before, after) && !leftovers(), "a write-protected folder changed");
    chmod(OUT, 0755);
    free(before);
    free(after);
}

/* Item 2: a user's folder nested deep, carried by a thread with a small stack. */
static int deep_levels;
static sl_status deep_status;
static char deep_msg[2048];

static void *deep_run(void *arg)
{
    (void)arg;
    deep_status = run_once(SL_ATOMIC_SWAP, deep_msg, sizeof deep_msg);
    return NULL;
}

/* A chain of `levels` folders "dd" under OUT/deep, a file at its end. */
static void make_deep(int levels)
{
    char p[600];
    snprintf(p, sizeof p, "%s/deep", OUT);
    mkdir(p, 0755);
    int fd = open(p, O_RDONLY | O_DIRECTORY);
    for (int i = 0; i < levels && fd >= 0; i++) {
        mkdirat(fd, "dd", 0755);
        int next = openat(fd, "dd", O_RDONLY | O_DIRECTORY);
        close(fd);
        fd = next;
    }
    if (fd >= 0) {
        int f = openat(fd, "end.txt", O_WRONLY | O_CREAT, 0644);
        if (f >= 0) {
            if (write(f, "the end", 7) != 7)
                perror("write");
            close(f);
        }
        close(fd);
    }
}

/* The text of OUT/deep/dd/.../end.txt ("" when absent). */
static const char *deep_end(int levels)
{
    static char buf[64];
    char p[600];
    buf[0] = '\0';
    snprintf(p, sizeof p, "%s/deep", OUT);
    int fd = open(p, O_RDONLY | O_DIRECTORY);
    for (int i = 0; i < levels && fd >= 0; i++) {
        int next = openat(fd, "dd", O_RDONLY | O_DIRECTORY);
        close(fd);
        fd = next;
    }
    if (fd >= 0) {
        int f = openat(fd, "end.txt", O_RDONLY);
        ssize_t k = f >= 0 ? read(f, buf, sizeof buf - 1) : 0;
        buf[k > 0 ? k : 0] = '\0';
        if (f >= 0)
            close(f);
        close(fd);
    }
    return buf;
}

static sl_status deep_on_small_stack(void)
{
    pthread_attr_t at;
    pthread_t t;
    pthread_attr_init(&at);
    pthread_attr_setstacksize(&at, 256 * 1024);
    if (pthread_create(&t, &at, deep_run, NULL) != 0)
        deep_run(NULL);
    else
        pthread_join(t, NULL);
    pthread_attr_destroy(&at);
    return deep_status;
}

static void test_nested_deep(void)
{
    deep_levels = 300; /* 300 x 3 = 900 characters: a path the system takes */
    build_old();
    make_deep(deep_levels);
    fs_reset();
    sl_status s = deep_on_small_stack();
    sl_fsops_install(NULL);
    CHECK(s == SL_OK, "300 levels: %s", deep_msg);
    CHECK(!strcmp(deep_end(deep_levels), "the end"), "300 levels: the deepest file: '%s'",
          deep_end(deep_levels));
    /* deeper than a path may be (4096): an error naming it, the folder as it was */
    deep_levels = 1500;
    build_old();
    make_deep(deep_levels);
    char *before = fs_snapshot(OUT);
    fs_reset();
    s = deep_on_small_stack();
    sl_fsops_install(NULL);
    char *after = fs_snapshot(OUT);
    CHECK(s == SL_EIO && strstr(deep_msg, "File name too long") &&
              strstr(deep_msg, "unchanged"),
          "1500 levels: %d %s", s, deep_msg);
    CHECK(!strcmp(before, after), "1500 levels: the folder changed");
    CHECK(!strcmp(deep_end(deep_levels), "the end"), "1500 levels: the deepest file lost");
    CHECK(!leftovers(), "1500 levels: %d left", leftovers());
    free(before);
    free(after);
}

/* What killed runs left: a fresh folder before its manifest (removed), one
 * after its carry (the links removed, the user's files in place), an old
 * folder swapped out holding a file saved after the carry (moved back). */
static void test_killed_runs(void)
{
    char host[80], p[700], q[800], msg[2048];
    sl_owner_host(host, sizeof host);
    build_old();
    snprintf(p, sizeof p, "%s/.out.tmp-4194999@%s-aaaaaa", ROOT, host);
    mkdir(p, 0755);
    put(p, "plant.csv", "half written");
    snprintf(p, sizeof p, "%s/.out.tmp-4194998@%s-bbbbbb", ROOT, host);
    mkdir(p, 0755);
    put(p, SL_MANIFEST_NAME, SL_MANIFEST_HEAD "\nplant.csv\n");
    put(p, "plant.csv", "whole");
    snprintf(q, sizeof q, "%s/notes.txt", p);
    char src[600];
    snprintf(src, sizeof src, "%s/notes.txt", OUT);
    CHECK(link(src, q) == 0, "link");
    snprintf(p, sizeof p, "%s/.out.tmp-4194997@%s-cccccc", ROOT, host);
    mkdir(p, 0755);
    put(p, SL_MANIFEST_NAME, SL_MANIFEST_HEAD "\nplant.csv\n");
    put(p, "plant.csv", "older");
    put(p, "saved-late.txt", "saved after the carry");
    snprintf(p, sizeof p, "%s/.out.tmp-4194996@%s-dddddd", ROOT, host);
    mkdir(p, 0755);
    put(p, SL_MANIFEST_NAME, SL_MANIFEST_HEAD "\n");
    put(p, "notes.txt", "an older version of the notes");
    fs_reset();
    sl_error err;
    sl_error_clear(&err);
    sl_atomic_dir *d = sl_atomic_dir_open(OUT, "seislide test", &err);
    sl_fsops_install(NULL);
    CHECK(d != NULL, "%s", err.msg);
    const char *said = sl_atomic_dir_stale(d);
    CHECK(strstr(said, "removed .out.tmp-4194999@") && strstr(said, "removed .out.tmp-4194998@") &&
              strstr(said, "removed .out.tmp-4194997@") && strstr(said, "kept .out.tmp-4194996@"),
          "said: %s", said);
    CHECK(strstr(said, "notes.txt: differs"), "said: %s", said);
    snprintf(p, sizeof p, "%s/saved-late.txt", OUT);
    CHECK(!strcmp(fs_get(p), "saved after the carry"), "a file saved after the carry: '%s'",
          fs_get(p));
    snprintf(p, sizeof p, "%s/notes.txt", OUT);
    CHECK(!strcmp(fs_get(p), "my notes"), "notes: '%s'", fs_get(p));
    snprintf(p, sizeof p, "%s/.out.tmp-4194996@%s-dddddd/notes.txt", ROOT, host);
    CHECK(!strcmp(fs_get(p), "an older version of the notes"), "the kept folder's file");
    sl_atomic_dir_abort(d, msg, sizeof msg);
}

int main(void)
{
    /* $TMPDIR, else a memory file system where there is one: the sweep makes
     * and removes some 30,000 small files, and a disk's write-back on rename
     * (ext4) makes that minutes instead of seconds */
    const char *t = getenv("TMPDIR");
    if (!t || !*t)
        t = access("/dev/shm", W_OK | X_OK) == 0 ? "/dev/shm" : "/tmp";
    snprintf(ROOT, sizeof ROOT, "%s/seislide-atomic-XXXXXX", t);
    if (!mkdtemp(ROOT)) {
        perror("mkdtemp");
        return 1;
    }
    snprintf(OUT, sizeof OUT, "%s/out", ROOT);
    RUN(test_faults_swap);
    RUN(test_faults_in_place);
    RUN(test_faults_without_rename_flags);
    RUN(test_swap_refused_keeps_cache);
    RUN(test_user_entry_where_run_writes);
    RUN(test_saved_while_finishing);
    RUN(test_saved_without_hard_links);
    RUN(test_mount_points);
    RUN(test_write_protected);
    RUN(test_nested_deep);
    RUN(test_killed_runs);
    sl_fsops_install(NULL);
    fs_empty_dir(ROOT);
    rmdir(ROOT);
    free(OLD_SNAP);
    free(NEW_SNAP);
    return HARNESS_END("test_atomic");
}
