/* test_floor.c - floor response spectrum files: the template and the good
 * fixture load with the right values; every bad fixture fails with its
 * file, line and a message that says what is wrong. Run from the
 * repository root (make test does). */
#include <dirent.h>

#include "io/floor.h"
#include "harness.h"
#include "core/units.h"

#define FLOORS "tests/data/floors/"

static void test_template(void)
{
    sl_error e;
    sl_error_clear(&e);
    sl_floor *fl = sl_floor_load("templates/floor.ini", &e);
    char buf[2200];
    CHECK(fl != NULL, "template: %s", sl_error_format(&e, buf, sizeof buf));
    if (!fl)
        return;
    CHECK(!strcmp(fl->name, "Example building, floor at el. 30.0 m"), "name '%s'", fl->name);
    CHECK(fl->elevation_m == 30.0 && fl->units == SL_UNIT_G && !fl->h2_same_as_h1, "header");
    for (int k = 0; k < SL_FLOOR_NCOMP; k++) {
        const sl_floor_component *c = &fl->comp[k];
        CHECK(c->nspec == 2 && c->spec[0].damping == 0.05 && c->spec[1].damping == 0.10,
              "%s dampings", sl_floor_comp_name((sl_floor_comp)k));
        CHECK(c->spec[0].n == 24 && c->spec[0].f_hz[0] == 0.1 && c->spec[0].f_hz[23] == 50,
              "%s frequencies", sl_floor_comp_name((sl_floor_comp)k));
        CHECK(sl_floor_sa10(fl, (sl_floor_comp)k) == &c->spec[1], "sa10");
        CHECK(sl_floor_spectrum(fl, (sl_floor_comp)k, 0.07) == NULL, "no 7 %%");
    }
    /* values converted from g; zpa given for H1, from the end for H2 and V */
    CHECK_CLOSE(fl->comp[SL_FLOOR_H1].spec[1].sa_ms2[12], 1.4299 * SL_G, 0, 1e-15);
    CHECK(fl->comp[SL_FLOOR_H1].zpa_given, "h1 zpa given");
    CHECK_CLOSE(fl->comp[SL_FLOOR_H1].zpa_ms2, 0.36 * SL_G, 0, 1e-15);
    CHECK(!fl->comp[SL_FLOOR_H2].zpa_given, "h2 zpa from the end");
    CHECK_CLOSE(fl->comp[SL_FLOOR_H2].zpa_ms2, 0.3063 * SL_G, 0, 1e-15); /* max(5 %, 10 %) */
    CHECK_CLOSE(fl->comp[SL_FLOOR_V].zpa_ms2, 0.3612 * SL_G, 0, 1e-15);
    sl_floor_free(fl);
}

static void test_good_small(void)
{
    sl_error e;
    sl_floor *fl = sl_floor_load(FLOORS "good-small.ini", &e);
    char buf[2200];
    CHECK(fl != NULL, "%s", sl_error_format(&e, buf, sizeof buf));
    if (!fl)
        return;
    CHECK(fl->h2_same_as_h1 && isnan(fl->elevation_m) && !strcmp(fl->description, ""),
          "header");
    CHECK(!fl->has_seed && fl->seed == 0, "no seed given");
    const sl_spectrum *h1 = sl_floor_sa10(fl, SL_FLOOR_H1), *h2 = sl_floor_sa10(fl, SL_FLOOR_H2);
    CHECK(h1 && h2 && h1 != h2 && h2->n == 6, "H2 is a copy of H1");
    for (size_t j = 0; h1 && h2 && j < 6; j++)
        CHECK(h1->f_hz[j] == h2->f_hz[j] && h1->sa_ms2[j] == h2->sa_ms2[j], "point %zu", j);
    /* m/s2: values unchanged; sorted by damping although given 0.10 first */
    CHECK(fl->comp[SL_FLOOR_H1].spec[0].damping == 0.05, "ascending damping");
    CHECK(fl->comp[SL_FLOOR_H1].spec[0].sa_ms2[3] == 8.0, "value");
    const sl_spectrum *v = sl_floor_sa10(fl, SL_FLOOR_V);
    CHECK(v && v->n == 3 && v->f_hz[1] == 10 && v->sa_ms2[2] == 2, "V by blanks");
    CHECK(sl_floor_spectrum(fl, SL_FLOOR_V, 0.05) == NULL, "V has no 5 %%");
    CHECK(fl->comp[SL_FLOOR_V].zpa_ms2 == 2.5 && fl->comp[SL_FLOOR_V].zpa_given, "zpa");
    CHECK(sl_floor_spectrum(fl, SL_FLOOR_H1, 0.1 + 1e-12) == h1, "damping tolerance");
    sl_floor_free(fl);
    sl_floor_free(NULL);
}

/* Each bad fixture: the error's file, line and a phrase of its message. */
static const struct {
    const char *file;
    long line;
    const char *phrase;
} bad[] = {
    {"bad-count.ini", 10, "has 5 values but f_hz (line 8) has 6"},
    {"bad-damping-high.ini", 10, "damping 1.5 outside (0, 1)"},
    {"bad-damping-zero.ini", 10, "damping 0 outside (0, 1)"},
    {"bad-duplicate-damping.ini", 10, "given twice"},
    {"bad-duplicate-key.ini", 10, "'f_hz' repeated"},
    {"bad-empty-name.ini", 3, "name is empty"},
    {"bad-freq-nonpositive.ini", 8, "must be positive"},
    {"bad-freq-range.ini", 8, "frequency 1e-300 Hz outside 0.001-10000 Hz"},
    {"bad-h2-both.ini", 5, "give one"},
    {"bad-h2-value.ini", 5, "same_as_h1"},
    {"bad-indented-key.ini", 9, "continuation"},
    {"bad-long-line.ini", 9, "line longer than"},
    {"bad-missing-floor.ini", 15, "missing section [floor]"},
    {"bad-missing-v.ini", 15, "missing section [v]"},
    {"bad-no-h2.ini", 2, "H2 not given"},
    {"bad-no-spectrum.ini", 12, "[v] has no spectrum"},
    {"bad-no-units.ini", 2, "no 'units'"},
    {"bad-nonincreasing.ini", 9, "increase strictly"},
    {"bad-number.ini", 8, "'5x' is not a finite number"},
    {"bad-one-point.ini", 13, "at least 2"},
    {"bad-repeated-section.ini", 12, "section [h1] repeated"},
    {"bad-seed.ini", 6, "seed: '-3' is not an integer"},
    {"bad-syntax.ini", 7, "syntax error"},
    {"bad-units.ini", 4, "unknown units 'furlongs/fortnight2'"},
    {"bad-unknown-floor-key.ini", 3, "unknown key 'nmae'"},
    {"bad-unknown-key.ini", 9, "unknown key 'damping' in [h1]"},
    {"bad-unknown-section.ini", 12, "unknown section [h3]"},
    {"bad-value-nan.ini", 10, "'nan' is not a finite number"},
    {"bad-value-nonpositive.ini", 9, "value -4 must be positive"},
    {"bad-value-overflow.ini", 9, "sa_0.1: value 1e+308 g is above 1000 g"},
    {"bad-zpa.ini", 15, "zpa: value -1 must be positive"},
    {"bad-zpa-huge.ini", 15, "zpa: value 2000 g is above 1000 g"},
};
#define N_BAD (sizeof bad / sizeof bad[0])

static void test_bad_files(void)
{
    for (size_t i = 0; i < N_BAD; i++) {
        char path[256];
        snprintf(path, sizeof path, FLOORS "%s", bad[i].file);
        sl_error e;
        sl_error_clear(&e);
        sl_floor *fl = sl_floor_load(path, &e);
        CHECK(fl == NULL, "%s loaded", bad[i].file);
        sl_floor_free(fl);
        CHECK(e.code != SL_OK, "%s: no code", bad[i].file);
        CHECK(!strcmp(e.file, path), "%s: file '%s'", bad[i].file, e.file);
        CHECK(e.line == bad[i].line, "%s: line %ld, expected %ld (%s)", bad[i].file, e.line,
              bad[i].line, e.msg);
        CHECK(strstr(e.msg, bad[i].phrase) != NULL, "%s: message '%s' lacks '%s'",
              bad[i].file, e.msg, bad[i].phrase);
    }
}

/* Every bad-*.ini fixture is in the table above. */
static void test_every_fixture_listed(void)
{
    DIR *d = opendir(FLOORS);
    CHECK(d != NULL, "cannot open " FLOORS);
    if (!d)
        return;
    struct dirent *ent;
    while ((ent = readdir(d))) {
        if (strncmp(ent->d_name, "bad-", 4))
            continue;
        int found = 0;
        for (size_t i = 0; i < N_BAD; i++)
            found |= !strcmp(ent->d_name, bad[i].file);
        CHECK(found, "fixture %s not in the test table", ent->d_name);
    }
    closedir(d);
}

static void test_missing_file(void)
{
    sl_error e;
    sl_error_clear(&e);
    CHECK(sl_floor_load(FLOORS "no-such-file.ini", &e) == NULL, "loaded");
    CHECK(e.code == SL_EIO && strstr(e.file, "no-such-file.ini"), "code %d file '%s'", e.code,
          e.file);
    CHECK(sl_floor_load(NULL, &e) == NULL && e.code == SL_EINVAL, "NULL path");
    CHECK(!strcmp(sl_floor_comp_name(SL_FLOOR_V), "v"), "names");
}

int main(void)
{
    RUN(test_template);
    RUN(test_good_small);
    RUN(test_bad_files);
    RUN(test_every_fixture_listed);
    RUN(test_missing_file);
    return HARNESS_END("floor");
}
