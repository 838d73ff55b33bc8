/* floor_ini.c - the INI reader of floor files (floor_desc.h): inih reads
 * the text, this file records what it says in a sl_floor_desc; the rules
 * are checked once, in floor.c.
 *
 * inih calls a handler for every `key = value` (and again for each indented
 * continuation line of a multi-line value) but, as Debian builds it, does
 * not pass line numbers. The file is therefore fed through our own line
 * reader (ini_parse_stream over the file in memory), which counts lines,
 * remembers whether the current line was indented, sees section headers (so
 * that empty, unknown or repeated sections are caught too) and refuses
 * lines longer than inih's buffer instead of letting them be split. */
#include "io/floor_desc.h"

#include <ini.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Prefix of a spectrum key: sa_<damping ratio>. */
#define FLOOR_SA_PREFIX "sa_"

/* Parsing state shared by the line reader and the handler. */
typedef struct ctx {
    sl_floor_desc *d;
    sl_text *text;      /* the file in memory (io/text.h) */
    long lineno;        /* line just read */
    int indented;       /* the line just read began with a blank */
    int have_prev_key;  /* inih's prev_name is set (a key since the last header) */
    const char *cur_key_section; /* section and key of the last key (for continuations) */
    char cur_key[64];
    sl_floor_vals *cur_list; /* the list an indented line continues */
    long fail_line;     /* line of the first error (0: none) */
} ctx;

static int failed(const ctx *c)
{
    return c->d->failed;
}

static int is_blank(char ch)
{
    return ch == ' ' || ch == '\t';
}

/* Section index for a name: 0 floor, 1 + comp, or -1. */
static int section_index(const char *s)
{
    if (!strcmp(s, "floor"))
        return 0;
    for (int k = 0; k < SL_FLOOR_NCOMP; k++)
        if (!strcmp(s, sl_floor_comp_name((sl_floor_comp)k)))
            return 1 + k;
    return -1;
}

static long *section_line(ctx *c, int idx)
{
    return idx == 0 ? &c->d->floor_line : &c->d->comp[idx - 1].line;
}

/* Look at a section header the way inih will, to catch unknown, empty and
 * repeated sections with their line. */
static void see_section(ctx *c, const char *line)
{
    const char *p = line;
    while (is_blank(*p))
        p++;
    if (*p != '[')
        return;
    if (p > line && c->have_prev_key)
        return; /* inih reads an indented line after a key as a continuation */
    const char *end = strchr(p + 1, ']');
    if (!end)
        return; /* inih reports the syntax error */
    char name[128];
    size_t len = (size_t)(end - p - 1);
    if (len >= sizeof name)
        len = sizeof name - 1;
    memcpy(name, p + 1, len);
    name[len] = '\0';
    c->have_prev_key = 0;
    int idx = section_index(name);
    if (idx < 0) {
        sl_floor_desc_fail(c->d, SL_EPARSE, c->lineno, 0,
                           "unknown section [%s] (expected [floor], [h1], [h2] or [v])", name);
        return;
    }
    long *sl = section_line(c, idx);
    if (*sl) {
        sl_floor_desc_fail(c->d, SL_EPARSE, c->lineno, 0,
                           "section [%s] repeated (first at line %ld)", name, *sl);
        return;
    }
    *sl = c->lineno;
}

/* fgets-style reader for ini_parse_stream over the file in memory: whole
 * lines (at most num - 1 bytes with their line end) or an error. */
static char *reader(char *str, int num, void *stream)
{
    ctx *c = stream;
    if (failed(c))
        return NULL;
    const char *s;
    size_t len;
    size_t before = c->text->pos;
    if (!sl_text_next(c->text, &s, &len))
        return NULL;
    c->lineno = c->text->lineno;
    size_t raw = c->text->pos - before; /* with the line end, as fgets sees it */
    if (raw < len + 1)
        raw = len + 1;
    if (num < 2 || raw > (size_t)num - 1) {
        sl_floor_desc_fail(c->d, SL_EPARSE, c->lineno, 0,
                           "line longer than %d characters; continue long lists on indented "
                           "lines (or use the CSV format, which has no line limit)",
                           num - 3);
        return NULL;
    }
    memcpy(str, s, len);
    str[len] = '\n';
    str[len + 1] = '\0';
    c->indented = is_blank(str[0]);
    see_section(c, str);
    if (failed(c))
        return NULL;
    return str;
}

/* Append the numbers of one line (separated by commas and/or blanks). */
static int append_numbers(ctx *c, sl_floor_vals *l, const char *value, const char *key)
{
    if (strchr(value, '=')) /* an indented "key = value" read as continuation */
        return sl_floor_desc_fail(c->d, SL_EPARSE, c->lineno, 0,
                                  "'%s' is read as a continuation of '%s' because it is "
                                  "indented; start a new key at the beginning of the line",
                                  value, key);
    const char *p = value;
    int commas = 0;
    while (*p) {
        while (is_blank(*p) || *p == ',') {
            if (*p == ',' && ++commas > 1)
                return sl_floor_desc_fail(c->d, SL_EPARSE, c->lineno, 0,
                                          "%s: empty item between commas", key);
            p++;
        }
        if (!*p)
            break;
        commas = 0;
        char tok[128];
        size_t len = strcspn(p, ", \t");
        if (len >= sizeof tok)
            return sl_floor_desc_fail(c->d, SL_EPARSE, c->lineno, 0, "%s: token too long", key);
        memcpy(tok, p, len);
        tok[len] = '\0';
        p += len;
        double x;
        if (!sl_floor_desc_number(c->d, key, tok, c->lineno, 0, &x))
            return 0;
        if (!sl_floor_desc_push(c->d, l, x, c->lineno, 0))
            return 0;
    }
    return 1;
}

static int handle_floor(ctx *c, const char *name, const char *value)
{
    sl_floor_key k = sl_floor_desc_key(name);
    if (k == SL_FK_COUNT) {
        char known[256] = "";
        for (int i = 0; i < SL_FK_COUNT; i++) {
            strncat(known, i ? ", " : "", sizeof known - strlen(known) - 1);
            strncat(known, sl_floor_key_names[i], sizeof known - strlen(known) - 1);
        }
        return sl_floor_desc_fail(c->d, SL_EPARSE, c->lineno, 0,
                                  "unknown key '%s' in [floor] (expected %s)", name, known);
    }
    if (c->indented && c->d->key_line[k])
        return sl_floor_desc_fail(c->d, SL_EPARSE, c->lineno, 0,
                                  "'%s' takes one value; this indented line would continue it",
                                  name);
    return sl_floor_desc_set(c->d, k, value, c->lineno, 0);
}

static int handle_comp(ctx *c, sl_floor_comp k, const char *sec, const char *name,
                       const char *value)
{
    sl_floor_comp_desc *rc = &c->d->comp[k];
    int cont = c->indented && c->have_prev_key && c->cur_key_section == sec &&
               !strcmp(c->cur_key, name) && c->cur_list;
    if (cont)
        return append_numbers(c, c->cur_list, value, name);
    c->cur_list = NULL;
    if (!strcmp(name, "f_hz")) {
        if (rc->f_line)
            return sl_floor_desc_fail(c->d, SL_EPARSE, c->lineno, 0,
                                      "[%s] key 'f_hz' repeated (first at line %ld)", sec,
                                      rc->f_line);
        rc->f_line = c->lineno;
        c->cur_list = &rc->f;
        return append_numbers(c, &rc->f, value, "f_hz");
    }
    if (!strcmp(name, "zpa")) {
        if (c->indented && c->have_prev_key && c->cur_key_section == sec &&
            !strcmp(c->cur_key, name))
            return sl_floor_desc_fail(c->d, SL_EPARSE, c->lineno, 0,
                                      "'zpa' takes one value; this indented line would "
                                      "continue it");
        if (rc->zpa_line)
            return sl_floor_desc_fail(c->d, SL_EPARSE, c->lineno, 0,
                                      "[%s] key 'zpa' repeated (first at line %ld)", sec,
                                      rc->zpa_line);
        return sl_floor_desc_set_zpa(c->d, k, "zpa", value, c->lineno, 0);
    }
    size_t plen = strlen(FLOOR_SA_PREFIX);
    if (!strncmp(name, FLOOR_SA_PREFIX, plen)) {
        double dmp;
        if (!*(name + plen) || sl_text_parse_num(name + plen, strlen(name + plen), &dmp) != SL_NUM_OK)
            return sl_floor_desc_fail(c->d, SL_EPARSE, c->lineno, 0,
                                      "key '%s': expected sa_<damping ratio>, e.g. sa_0.05",
                                      name);
        sl_floor_sa_desc *sa = sl_floor_desc_add_sa(c->d, k, dmp, name, c->lineno, 0);
        if (!sa)
            return 0;
        c->cur_list = &sa->sa;
        return append_numbers(c, &sa->sa, value, name);
    }
    return sl_floor_desc_fail(c->d, SL_EPARSE, c->lineno, 0,
                              "unknown key '%s' in [%s] (expected f_hz, sa_<damping>, zpa)",
                              name, sec);
}

static int handler(void *user, const char *section, const char *name, const char *value)
{
    ctx *c = user;
    if (failed(c))
        return 0;
    int idx = section_index(section);
    if (!*section)
        return sl_floor_desc_fail(c->d, SL_EPARSE, c->lineno, 0, "key '%s' before any section",
                                  name);
    if (idx < 0) /* an indented header see_section() did not count */
        return sl_floor_desc_fail(c->d, SL_EPARSE, c->lineno, 0, "unknown section [%s]",
                                  section);
    const char *sec = idx == 0 ? "floor" : sl_floor_comp_name((sl_floor_comp)(idx - 1));
    int ok = idx == 0 ? handle_floor(c, name, value)
                      : handle_comp(c, (sl_floor_comp)(idx - 1), sec, name, value);
    c->have_prev_key = 1;
    c->cur_key_section = sec;
    snprintf(c->cur_key, sizeof c->cur_key, "%s", name);
    return ok;
}

int sl_floor_read_ini(sl_floor_desc *d, sl_text *t)
{
    ctx c;
    memset(&c, 0, sizeof c);
    c.d = d;
    c.text = t;
    int rc = ini_parse_stream(reader, &c, handler, &c);
    d->eof_line = c.lineno;
    if (!d->failed && rc == -2) {
        sl_floor_desc_fail(d, SL_ENOMEM, 0, 0, "out of memory");
    } else if (rc > 0 && (!d->failed || rc < d->fail_line)) {
        /* inih keeps going after a syntax error: report whichever came first */
        d->failed = 0;
        sl_floor_desc_fail(d, SL_EPARSE, rc, 0,
                           "syntax error: expected '[section]', 'key = value' or a comment");
    }
    return !d->failed;
}
