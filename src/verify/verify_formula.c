/* verify_formula.c - a small evaluator of the spreadsheet formulas the
 * workbook's Lookup writes (numbers, "text", cells B<row>, + - * /,
 * parentheses, = and <>, IF(c, a, b)), so that `verify` can evaluate the
 * formula text itself against the C function (verify_problems.h). */
#include <ctype.h>
#include <stdlib.h>
#include <string.h>

#include "verify/verify_problems.h"

typedef struct val {
    double num;
    const char *text; /* non-NULL: a text value (its length in len) */
    size_t len;
} val;

typedef struct parser {
    const char *s;
    const sl_verify_cell *cells;
    size_t n_cells;
    int bad;
} parser;

static void skip(parser *p)
{
    while (*p->s == ' ')
        p->s++;
}

static int eat(parser *p, const char *tok)
{
    skip(p);
    size_t n = strlen(tok);
    if (strncmp(p->s, tok, n))
        return 0;
    p->s += n;
    return 1;
}

static val expr(parser *p);

static val num_of(double x)
{
    val v = {x, NULL, 0};
    return v;
}

static val primary(parser *p)
{
    skip(p);
    val v = num_of(0);
    if (eat(p, "IF(")) {
        val c = expr(p);
        if (!eat(p, ","))
            p->bad = 1;
        val a = expr(p);
        if (!eat(p, ","))
            p->bad = 1;
        val b = expr(p);
        if (!eat(p, ")"))
            p->bad = 1;
        int truth = c.text ? c.len > 0 : c.num != 0;
        return truth ? a : b;
    }
    if (eat(p, "(")) {
        v = expr(p);
        if (!eat(p, ")"))
            p->bad = 1;
        return v;
    }
    if (*p->s == '"') {
        const char *q = strchr(p->s + 1, '"');
        if (!q) {
            p->bad = 1;
            return v;
        }
        v.text = p->s + 1;
        v.len = (size_t)(q - p->s - 1);
        p->s = q + 1;
        return v;
    }
    if (*p->s == 'B' && isdigit((unsigned char)p->s[1])) {
        char *end;
        long row = strtol(p->s + 1, &end, 10);
        p->s = end;
        for (size_t i = 0; i < p->n_cells; i++)
            if (p->cells[i].row == row) {
                if (p->cells[i].text) {
                    v.text = p->cells[i].text;
                    v.len = strlen(v.text);
                } else {
                    v.num = p->cells[i].num;
                }
                return v;
            }
        p->bad = 1; /* a cell the caller did not give */
        return v;
    }
    if (isdigit((unsigned char)*p->s) || *p->s == '.') {
        char *end;
        v.num = strtod(p->s, &end);
        p->s = end;
        return v;
    }
    p->bad = 1;
    return v;
}

static val unary(parser *p)
{
    if (eat(p, "-")) {
        val v = unary(p);
        v.num = -v.num;
        p->bad |= v.text != NULL;
        return v;
    }
    return primary(p);
}

static val term(parser *p)
{
    val a = unary(p);
    for (;;) {
        int mul = eat(p, "*");
        if (!mul && !eat(p, "/"))
            return a;
        val b = unary(p);
        p->bad |= a.text != NULL || b.text != NULL;
        a.num = mul ? a.num * b.num : a.num / b.num;
    }
}

static val sum(parser *p)
{
    val a = term(p);
    for (;;) {
        int add = eat(p, "+");
        if (!add && !eat(p, "-"))
            return a;
        val b = term(p);
        p->bad |= a.text != NULL || b.text != NULL;
        a.num = add ? a.num + b.num : a.num - b.num;
    }
}

static val expr(parser *p)
{
    val a = sum(p);
    int ne = eat(p, "<>");
    if (!ne && !eat(p, "="))
        return a;
    val b = sum(p);
    int same = (a.text && b.text) ? a.len == b.len && !strncmp(a.text, b.text, a.len)
               : (!a.text && !b.text) ? a.num == b.num
                                      : 0;
    return num_of(ne ? !same : same);
}

sl_status sl_verify_formula_eval(const char *f, const sl_verify_cell *cells, size_t n_cells,
                                 double *num, int *is_text, sl_error *err)
{
    parser p = {f, cells, n_cells, 0};
    if (!eat(&p, "="))
        return sl_error_set(err, SL_EPARSE, NULL, 0, "formula does not start with '=': %s", f);
    val v = expr(&p);
    skip(&p);
    if (p.bad || *p.s)
        return sl_error_set(err, SL_EPARSE, NULL, 0, "formula not understood near '%s': %s",
                            p.s, f);
    *num = v.num;
    *is_text = v.text != NULL;
    return SL_OK;
}
