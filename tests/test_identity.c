/* test_identity.c - a floor's identity (src/plant/identity.h): its cache key
 * and its seed come from one serialisation. Each field of the floor and each
 * setting that changes a result is changed alone and must change the key
 * (and the seed, where the seed depends on it); what must not matter (name,
 * building, path, units as written, lines, other floors, progress) is
 * changed and must leave both alone. The seeds of the example floors are
 * pinned: the identity must not move existing results. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "analysis.h"
#include "core/version.h"
#include "harness.h"
#include "plant/entry.h"
#include "plant/identity.h"

#define VERSION "seislide identity test"
static const double MU[] = {0.05, 0.1, 0.2, 0.3, 0.5};

typedef struct ident {
    sl_entry_key key;
    uint64_t seed;
} ident;

static ident ident_of(const sl_floor *fl, const sl_analysis_opts *o, const char *version)
{
    ident d = {{0}, 0};
    sl_error e;
    if (sl_entry_key_make(fl, o, version, &d.key, &e) != SL_OK)
        d.key.text = NULL;
    d.seed = sl_analysis_floor_seed(o->seed, fl);
    return d;
}

static int same_key(const ident *a, const ident *b)
{
    return a->key.text && b->key.text && a->key.len == b->key.len &&
           memcmp(a->key.text, b->key.text, a->key.len) == 0 && !strcmp(a->key.hash, b->key.hash);
}

/* Compare the identity of (fl, o) with the reference: the key must differ
 * (key_differs) or not, and the seed likewise. */
static void expect(const ident *ref, const sl_floor *fl, const sl_analysis_opts *o,
                   const char *version, int key_differs, int seed_differs, const char *what)
{
    ident d = ident_of(fl, o, version);
    CHECK(d.key.text != NULL, "%s: no key", what);
    CHECK((!same_key(ref, &d)) == key_differs, "%s: the key %s", what,
          key_differs ? "did not change" : "changed");
    CHECK((ref->seed != d.seed) == seed_differs, "%s: the seed %s", what,
          seed_differs ? "did not change" : "changed");
    sl_entry_key_free(&d.key);
}

static sl_floor *load(const char *path)
{
    sl_error e;
    sl_floor *fl = sl_floor_load(path, &e);
    if (!fl)
        fprintf(stderr, "  %s: %s\n", path, e.msg);
    return fl;
}

static void defaults(sl_analysis_opts *o)
{
    sl_analysis_opts_default(o);
    o->mu = MU;
    o->n_mu = sizeof MU / sizeof MU[0];
}

/* Change one double of the floor and put it back: key and seed must change
 * (or only the key when the file gives its own seed). */
#define FLOOR_NUM(lv, what)                                                  \
    do {                                                                     \
        double keep_ = (lv);                                                 \
        (lv) = keep_ * (1.0 + 1e-12);                                        \
        expect(&ref, fl, &o, VERSION, 1, !fl->has_seed, what);               \
        (lv) = keep_;                                                        \
    } while (0)

static void floor_fields(sl_floor *fl)
{
    sl_analysis_opts o;
    defaults(&o);
    ident ref = ident_of(fl, &o, VERSION);
    CHECK(ref.key.text != NULL, "reference key");
    char what[96];
    for (int c = 0; c < SL_FLOOR_NCOMP; c++) {
        sl_floor_component *fc = &fl->comp[c];
        const char *cn = sl_floor_comp_name((sl_floor_comp)c);
        snprintf(what, sizeof what, "%s zpa", cn);
        FLOOR_NUM(fc->zpa_ms2, what);
        for (size_t s = 0; s < fc->nspec; s++) {
            sl_spectrum *sp = &fc->spec[s];
            snprintf(what, sizeof what, "%s damping %zu", cn, s);
            FLOOR_NUM(sp->damping, what);
            size_t at[] = {0, sp->n / 2, sp->n - 1};
            for (int j = 0; j < 3; j++) {
                snprintf(what, sizeof what, "%s damping %zu frequency %zu", cn, s, at[j]);
                FLOOR_NUM(sp->f_hz[at[j]], what);
                snprintf(what, sizeof what, "%s damping %zu value %zu", cn, s, at[j]);
                FLOOR_NUM(sp->sa_ms2[at[j]], what);
            }
            /* one frequency fewer */
            sp->n--;
            snprintf(what, sizeof what, "%s damping %zu: a point fewer", cn, s);
            expect(&ref, fl, &o, VERSION, 1, !fl->has_seed, what);
            sp->n++;
        }
        /* one damping fewer */
        fc->nspec--;
        snprintf(what, sizeof what, "%s: a damping fewer", cn);
        expect(&ref, fl, &o, VERSION, 1, !fl->has_seed, what);
        fc->nspec++;
    }
    /* the file's seed: given or not, and its value */
    int had = fl->has_seed;
    uint64_t seed = fl->seed;
    fl->has_seed = !had;
    expect(&ref, fl, &o, VERSION, 1, 1, "seed = given or not");
    fl->has_seed = 1;
    fl->seed = seed + 1;
    expect(&ref, fl, &o, VERSION, 1, 1, "seed = value");
    fl->has_seed = had;
    fl->seed = seed;

    /* what must not matter */
    char *keep_name = fl->name, *keep_b = fl->building, *keep_p = fl->path;
    char *keep_d = fl->description, *keep_u = fl->units_text;
    char name[] = "another name", building[] = "another building",
         path[] = "elsewhere/another-file.csv", desc[] = "another description", units[] = "m/s2";
    fl->name = name;
    fl->building = building;
    fl->path = path;
    fl->description = desc;
    fl->units_text = units;
    sl_unit keep_unit = fl->units;
    fl->units = keep_unit == SL_UNIT_G ? SL_UNIT_MS2 : SL_UNIT_G;
    double keep_el = fl->elevation_m;
    fl->elevation_m = 99.5;
    sl_floor_format keep_fmt = fl->format;
    fl->format = keep_fmt == SL_FLOOR_CSV ? SL_FLOOR_INI : SL_FLOOR_CSV;
    long keep_ul = fl->units_line;
    fl->units_line += 7;
    int keep_h2 = fl->h2_same_as_h1;
    fl->h2_same_as_h1 = !keep_h2;
    fl->comp[SL_FLOOR_V].line += 3;
    fl->comp[SL_FLOOR_H1].zpa_given = !fl->comp[SL_FLOOR_H1].zpa_given;
    expect(&ref, fl, &o, VERSION, 0, 0, "name, building, path, units, lines");
    fl->comp[SL_FLOOR_H1].zpa_given = !fl->comp[SL_FLOOR_H1].zpa_given;
    fl->comp[SL_FLOOR_V].line -= 3;
    fl->h2_same_as_h1 = keep_h2;
    fl->units_line = keep_ul;
    fl->format = keep_fmt;
    fl->elevation_m = keep_el;
    fl->units = keep_unit;
    fl->name = keep_name;
    fl->building = keep_b;
    fl->path = keep_p;
    fl->description = keep_d;
    fl->units_text = keep_u;
    expect(&ref, fl, &o, VERSION, 0, 0, "every field put back");
    sl_entry_key_free(&ref.key);
}

static void test_floor_fields(void)
{
    sl_floor *fl = load("floors/04-roof36.ini");
    CHECK(fl && !fl->has_seed && fl->comp[SL_FLOOR_H1].nspec == 3, "floors/04-roof36.ini");
    if (!fl)
        return;
    floor_fields(fl); /* its seed from its numbers */
    fl->has_seed = 1; /* its own seed: the numbers change the key only */
    fl->seed = 12345;
    floor_fields(fl);
    sl_floor_free(fl);
}

/* Two floors with the same numbers in another arrangement: the counts tell
 * them apart (the seed, made from the numbers alone, may agree). H1 of A:
 * dampings 0.05 {f 1: 3} and 0.1 {f 1: 5}; of B: 0.05 {f 1, 0.1: 3, 1}, then
 * 5 {no points}. Not valid floor files: the identity is of the struct. */
static void test_counts_separate(void)
{
    double fa1[] = {1}, sa1[] = {3}, fa2[] = {1}, sa2[] = {5};
    double fb1[] = {1, 0.1}, sb1[] = {3, 1};
    sl_spectrum A[2] = {{.n = 1, .damping = 0.05, .f_hz = fa1, .sa_ms2 = sa1},
                        {.n = 1, .damping = 0.1, .f_hz = fa2, .sa_ms2 = sa2}};
    sl_spectrum B[2] = {{.n = 2, .damping = 0.05, .f_hz = fb1, .sa_ms2 = sb1},
                        {.n = 0, .damping = 5, .f_hz = NULL, .sa_ms2 = NULL}};
    sl_floor a, b;
    memset(&a, 0, sizeof a);
    memset(&b, 0, sizeof b);
    a.comp[SL_FLOOR_H1] = (sl_floor_component){.nspec = 2, .spec = A, .zpa_ms2 = 3};
    b.comp[SL_FLOOR_H1] = (sl_floor_component){.nspec = 2, .spec = B, .zpa_ms2 = 3};
    sl_analysis_opts o;
    defaults(&o);
    ident ia = ident_of(&a, &o, VERSION), ib = ident_of(&b, &o, VERSION);
    CHECK(ia.key.text && ib.key.text, "keys");
    CHECK(!same_key(&ia, &ib), "the same numbers in another arrangement gave the same key");
    CHECK(ia.seed == ib.seed, "the seed hashes the numbers alone (its documented definition)");
    sl_entry_key_free(&ia.key);
    sl_entry_key_free(&ib.key);
}

/* Change one setting and put it back: the key changes; the seed only with
 * the run's seed (a setting never changes the motions). */
#define OPT(field, value, seed_too)                                          \
    do {                                                                     \
        sl_analysis_opts o2_ = o;                                            \
        o2_.field = (value);                                                 \
        expect(&ref, fl, &o2_, VERSION, 1, seed_too, #field);                \
    } while (0)

static void progress(void *ctx, const char *step, size_t done, size_t total)
{
    (void)ctx, (void)step, (void)done, (void)total;
}

static void test_settings(void)
{
    sl_floor *fl = load("floors/02-el12.ini");
    if (!fl)
        SKIP("floors/02-el12.ini");
    sl_analysis_opts o;
    defaults(&o);
    ident ref = ident_of(fl, &o, VERSION);
    OPT(n_sets, 12, 0);
    OPT(rel_se, 0.03, 0);
    OPT(abs_se_m, 0.002, 0);
    OPT(max_sets, 100, 0);
    OPT(first_batch, 12, 0);
    OPT(min_batch, 5, 0);
    OPT(plan_margin, 1.2, 0);
    OPT(plan_growth, 3.0, 0);
    OPT(boot_resamples, o.boot_resamples + 1, 0);
    OPT(band_level, 0.95, 0);
    OPT(band_method, o.band_method == SL_STATS_BAND_STUDENT ? SL_STATS_BAND_PERCENTILE
                                                           : SL_STATS_BAND_STUDENT, 0);
    OPT(seed, 2, 1);
    OPT(substeps, 8, 0);
    OPT(rtol, o.rtol * 2, 0);
    OPT(scatter, 0.2, 0);
    OPT(policy, SL_CLEARANCE_ENVELOPE, 0);
    OPT(fs_nltha, o.fs_nltha * 1.1, 0);
    OPT(fs_asce, o.fs_asce * 1.1, 0);
    /* the friction grid: one value, and one value fewer */
    double mu2[] = {0.05, 0.1, 0.2, 0.3, 0.55};
    OPT(mu, mu2, 0);
    OPT(n_mu, o.n_mu - 1, 0);
    /* the program version */
    expect(&ref, fl, &o, "seislide another version", 1, 0, "version");
    /* the library's own source fingerprint, whatever version text the caller
     * gives (core/version.h): another build's key differs even under the
     * same text (tests/cli/test_build_id.sh builds one) */
    const char *sid = sl_source_id();
    CHECK(strlen(sid) == 64 && strspn(sid, "0123456789abcdef") == 64, "source id '%s'", sid);
    int in_key = 0;
    for (size_t i = 0; ref.key.text && i + 64 <= ref.key.len && !in_key; i++)
        in_key = !memcmp(ref.key.text + i, sid, 64);
    CHECK(in_key, "the key does not hold the source fingerprint");
    CHECK(!strncmp(sl_build_id(), "seislide ", 9) && strstr(sl_build_id(), sl_version()) &&
              strstr(sl_build_id(), "(source ") && !strncmp(strstr(sl_build_id(), "(source ") + 8,
                                                             sid, 12),
          "build id '%s'", sl_build_id());
    /* progress (-q) must not matter */
    sl_analysis_opts q = o;
    q.progress = progress;
    q.progress_ctx = &q;
    expect(&ref, fl, &q, VERSION, 0, 0, "progress");
    /* nor another floor loaded and keyed before it */
    sl_floor *other = load("floors/03-el24.ini");
    ident io = other ? ident_of(other, &o, VERSION) : ref;
    CHECK(other && !same_key(&io, &ref) && io.seed != ref.seed, "another floor, another key");
    expect(&ref, fl, &o, VERSION, 0, 0, "another floor keyed first");
    if (other)
        sl_entry_key_free(&io.key);
    sl_floor_free(other);
    sl_entry_key_free(&ref.key);
    sl_floor_free(fl);
}

/* The seeds the example floors had before the identity was one walk (run
 * seed 1): unchanged, so that their motions and results do not move. A
 * floor in CSV with the numbers of the INI template has the same seed. */
static void test_seeds_pinned(void)
{
    static const struct {
        const char *path;
        uint64_t seed;
    } pin[] = {{"floors/01-ground.ini", 0x43a33455410a83e0ULL},
               {"floors/02-el12.ini", 0xa0953af43335ac24ULL},
               {"floors/03-el24.ini", 0xf8a356894f5136a1ULL},
               {"floors/04-roof36.ini", 0x8c7b18b295144f38ULL},
               {"templates/floor.ini", 0x38e50f76d1e16813ULL},
               {"templates/floor.csv", 0x38e50f76d1e16813ULL}};
    for (size_t i = 0; i < sizeof pin / sizeof pin[0]; i++) {
        sl_floor *fl = load(pin[i].path);
        CHECK(fl != NULL, "%s", pin[i].path);
        if (!fl)
            continue;
        uint64_t s = sl_analysis_floor_seed(1, fl);
        CHECK(s == pin[i].seed, "%s: seed 0x%016llx, was 0x%016llx", pin[i].path,
              (unsigned long long)s, (unsigned long long)pin[i].seed);
        CHECK(sl_identity_seed(1, fl) == s, "%s: two seeds", pin[i].path);
        sl_floor_free(fl);
    }
}

/* ---- every field of the structs is in the identity or listed as not ----- */

/* The whole text of a file (malloc'd), NULL when unreadable. */
static char *slurp(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    char *b = NULL;
    size_t n = 0, cap = 0, got;
    do {
        if (n + 4096 + 1 > cap) {
            char *g = realloc(b, cap = 2 * cap + 8192);
            if (!g) {
                free(b);
                fclose(f);
                return NULL;
            }
            b = g;
        }
        got = fread(b + n, 1, 4096, f);
        n += got;
    } while (got > 0);
    fclose(f);
    b[n] = '\0';
    return b;
}

static int ident_char(char c)
{
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
}

/* Does text hold `pre` immediately followed by the whole word `word`? */
static int has_word_after(const char *text, const char *pre, const char *word)
{
    size_t lp = strlen(pre), lw = strlen(word);
    for (const char *p = strstr(text, pre); p; p = strstr(p + 1, pre))
        if (!strncmp(p + lp, word, lw) && !ident_char(p[lp + lw]))
            return 1;
    return 0;
}

/* The member names of `typedef struct TYPE { ... } TYPE;` in header text h
 * (comments removed; several declarators on a line; arrays; function
 * pointers), into names[max][64]; their count, or -1 when not found. */
static int struct_fields(const char *h, const char *type, char names[][64], int max)
{
    char open[128];
    snprintf(open, sizeof open, "typedef struct %s {", type);
    const char *s = strstr(h, open);
    if (!s)
        return -1;
    s += strlen(open);
    const char *e = strchr(s, '}');
    if (!e)
        return -1;
    char body[8192];
    size_t k = 0;
    for (const char *p = s; p < e && k + 1 < sizeof body; p++) {
        if (p[0] == '/' && p[1] == '*') { /* comments out */
            const char *q = strstr(p + 2, "*/");
            if (!q || q > e)
                break;
            p = q + 1;
            continue;
        }
        body[k++] = *p;
    }
    body[k] = '\0';
    int n = 0;
    for (char *decl = strtok(body, ";"); decl; decl = strtok(NULL, ";")) {
        char *fp = strstr(decl, "(*");
        if (fp) { /* a function pointer: the name inside (*name) */
            char *q = fp + 2, *r = q;
            while (ident_char(*r))
                r++;
            if (r > q && n < max)
                snprintf(names[n++], 64, "%.*s", (int)(r - q), q);
            continue;
        }
        /* declarators separated by commas; the name is each one's last word
         * before any [size] */
        for (char *d = decl; d && *d;) {
            char *comma = strchr(d, ',');
            if (comma)
                *comma = '\0';
            char *br = strchr(d, '[');
            if (br)
                *br = '\0';
            char *end = d + strlen(d);
            while (end > d && !ident_char(end[-1]))
                end--;
            char *beg = end;
            while (beg > d && ident_char(beg[-1]))
                beg--;
            if (end > beg && n < max)
                snprintf(names[n++], 64, "%.*s", (int)(end - beg), beg);
            d = comma ? comma + 1 : NULL;
        }
    }
    return n;
}

/* issue 39: a field of the options or of a floor that changes results and is
 * missing from the identity would let the cache serve another setting's
 * result. Every member of each struct, read from its header, is walked by
 * identity.c (o->, fl->, fc->, sp->) or named in its list of fields no result
 * depends on ("sl_floor.path"). A new field fails here until it is one or
 * the other. */
static void test_struct_fields_covered(void)
{
    static const struct {
        const char *header, *type, *walked_as;
        int min_fields; /* the parse found the struct whole */
    } st[] = {{"src/analysis.h", "sl_analysis_opts", "o->", 22},
              {"src/io/floor.h", "sl_floor", "fl->", 13},
              {"src/io/floor.h", "sl_floor_component", "fc->", 5},
              {"src/core/spectrum_type.h", "sl_spectrum", "sp->", 4}};
    char *id = slurp("src/plant/identity.c");
    CHECK(id != NULL, "src/plant/identity.c not readable (run from the source tree)");
    for (size_t i = 0; id && i < sizeof st / sizeof st[0]; i++) {
        char *h = slurp(st[i].header);
        char names[64][64];
        int n = h ? struct_fields(h, st[i].type, names, 64) : -1;
        CHECK(n >= st[i].min_fields, "%s: %d fields of %s read, at least %d expected", st[i].header,
              n, st[i].type, st[i].min_fields);
        for (int f = 0; f < n; f++) {
            char listed[140];
            snprintf(listed, sizeof listed, "%s.", st[i].type);
            int walked = has_word_after(id, st[i].walked_as, names[f]);
            int named = has_word_after(id, listed, names[f]);
            CHECK(walked != named, "%s.%s is %s in src/plant/identity.c: a field that changes a "
                  "result goes into the walk (identity.h), one that changes none into the list "
                  "of fields not in it", st[i].type, names[f],
                  walked ? "both walked and listed as not" : "neither walked nor listed");
        }
        free(h);
    }
    free(id);
}

int main(void)
{
    RUN(test_floor_fields);
    RUN(test_counts_separate);
    RUN(test_settings);
    RUN(test_seeds_pinned);
    RUN(test_struct_fields_covered);
    return HARNESS_END("test_identity");
}
