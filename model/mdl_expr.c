/* The parser of the model files' expressions (see mdl_expr.h; the tree in mdl_expr_impl.h).
 *
 * Method: recursive descent, one function per precedence level; a left-associative level loops
 * (a long sum does not recurse), and the parser's own recursion (parse_or and parse_unary) is
 * counted against MDL_EXPR_MAX_DEPTH as the node heights are, so both the parser and the
 * recursive walks of mdl_expr_eval.c use a bounded stack whatever the input. Every node keeps
 * the span [start, end) of its text, for messages. Lone constant names are folded into numbers
 * here. */
#include "mdl_expr_impl.h"

#include <ctype.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const struct {
    const char *name;
    int nargs;
} funcs[F_COUNT] = {{"sqrt", 1},  {"exp", 1},  {"log", 1},  {"log10", 1}, {"sin", 1},
                    {"cos", 1},   {"tan", 1},  {"asin", 1}, {"acos", 1},  {"atan", 1},
                    {"atan2", 2}, {"sinh", 1}, {"cosh", 1}, {"tanh", 1},  {"hypot", 2},
                    {"abs", 1},   {"min", -1}, {"max", -1}, {"floor", 1}, {"ceil", 1},
                    {"round", 1}, {"pow", 2},  {"if", 3}};

static const struct {
    const char *name;
    double value;
} consts[] = {{"pi", 3.14159265358979323846},
              {"deg", 3.14159265358979323846 / 180.0},
              {"bar", 1e5},
              {"MPa", 1e6},
              {"mm", 1e-3},
              {"lpm", 1e-3 / 60.0},
              {"rpm", 2.0 * 3.14159265358979323846 / 60.0},
              {"g0", 9.80665}};
#define N_CONSTS ((int)(sizeof consts / sizeof consts[0]))

/* ---- errors ---- */

void mdl_expri_set_error(mdl_expr_error *e, int column, const char *fmt, ...)
{
    if (!e) return;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(e->message, sizeof e->message, fmt, ap);
    va_end(ap);
    e->column = column;
}

const char *mdl_expri_snippet(const char *text, int start, int end, char *buf, size_t size)
{
    while (start < end && isspace((unsigned char)text[start]))
        start++;
    while (end > start && isspace((unsigned char)text[end - 1]))
        end--;
    int n = end - start;
    if (n > 60 && size > 61) {
        snprintf(buf, size, "%.57s...", text + start);
    } else {
        snprintf(buf, size, "%.*s", n, text + start);
    }
    return buf;
}

int mdl_expr_edit_distance(const char *a, const char *b, int limit)
{
    if (limit > 64) limit = 64;
    int la = (int)strnlen(a, (size_t)limit), lb = (int)strnlen(b, (size_t)limit);
    int row[65];
    for (int j = 0; j <= lb; j++)
        row[j] = j;
    for (int i = 1; i <= la; i++) {
        int diag = row[0];
        row[0] = i;
        for (int j = 1; j <= lb; j++) {
            int up = row[j];
            int best = diag + (a[i - 1] != b[j - 1]);
            if (row[j] + 1 < best) best = row[j] + 1;
            if (row[j - 1] + 1 < best) best = row[j - 1] + 1;
            row[j] = best;
            diag = up;
        }
    }
    return row[lb];
}

/* ---- the parser ---- */

int mdl_expri_fail(parser *p, int column, const char *fmt, ...)
{
    if (p->failed) return -1;
    p->failed = 1;
    if (p->e) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(p->e->message, sizeof p->e->message, fmt, ap);
        va_end(ap);
        p->e->column = column;
    }
    return -1;
}

int mdl_expri_is_id0(int c)
{
    return isalpha(c) || c == '_';
}
static int is_id(int c)
{
    return isalnum(c) || c == '_';
}

void mdl_expri_skip_ws(parser *p)
{
    while (p->s[p->pos] == ' ' || p->s[p->pos] == '\t' || p->s[p->pos] == '\n' ||
           p->s[p->pos] == '\r')
        p->pos++;
}

/* Reports what stands at the current position as unexpected. */
int mdl_expri_unexpected(parser *p)
{
    mdl_expri_skip_ws(p);
    const char *c = p->s + p->pos;
    int n = 0;
    if (!*c) return mdl_expri_fail(p, p->pos, "unexpected end of expression");
    if (mdl_expri_is_id0((unsigned char)*c)) {
        while (is_id((unsigned char)c[n]) && n < 40)
            n++;
        return mdl_expri_fail(p, p->pos, "unexpected name '%.*s'", n, c);
    }
    if (isdigit((unsigned char)*c)) {
        while ((isalnum((unsigned char)c[n]) || c[n] == '.') && n < 40)
            n++;
        return mdl_expri_fail(p, p->pos, "unexpected number '%.*s'", n, c);
    }
    if (!isprint((unsigned char)*c))
        return mdl_expri_fail(p, p->pos, "unexpected character 0x%02x",
                              (unsigned)(unsigned char)*c);
    return mdl_expri_fail(p, p->pos, "unexpected '%c'", *c);
}

int mdl_expri_new_node(parser *p, int kind, int op, int start, int height)
{
    mdl_expr *x = p->x;
    if (height > MDL_EXPR_MAX_DEPTH)
        return mdl_expri_fail(p, start, "expression nested too deeply (more than %d levels)",
                              MDL_EXPR_MAX_DEPTH);
    if (x->nn == x->ncap) {
        int cap = x->ncap ? 2 * x->ncap : 16;
        node *nodes = realloc(x->nodes, (size_t)cap * sizeof *nodes);
        if (!nodes) return mdl_expri_fail(p, start, "out of memory");
        x->nodes = nodes;
        x->ncap = cap;
    }
    node *n = &x->nodes[x->nn];
    memset(n, 0, sizeof *n);
    n->kind = (unsigned char)kind;
    n->op = (unsigned char)op;
    n->height = (short)height;
    n->start = start;
    n->end = p->pos;
    n->a = n->b = n->next = -1;
    return x->nn++;
}

static int height(const parser *p, int id)
{
    return p->x->nodes[id].height;
}

static int parse_or(parser *p);
static int parse_unary(parser *p);

/* A number in C's decimal syntax at the current position. */
static int parse_number(parser *p)
{
    const char *s = p->s;
    int st = p->pos, q = st;
    while (isdigit((unsigned char)s[q]))
        q++;
    if (s[q] == '.') {
        q++;
        while (isdigit((unsigned char)s[q]))
            q++;
    }
    if (s[q] == 'e' || s[q] == 'E') {
        int r = q + 1;
        if (s[r] == '+' || s[r] == '-') r++;
        if (isdigit((unsigned char)s[r])) {
            while (isdigit((unsigned char)s[r]))
                r++;
            q = r;
        } else {
            q = r;
            while (is_id((unsigned char)s[q]) && q - st < 40)
                q++;
            return mdl_expri_fail(p, st, "malformed number '%.*s'", q - st, s + st);
        }
    }
    if (is_id((unsigned char)s[q]) || s[q] == '.') {
        while ((is_id((unsigned char)s[q]) || s[q] == '.') && q - st < 40)
            q++;
        return mdl_expri_fail(p, st, "malformed number '%.*s'", q - st, s + st);
    }
    char *end;
    double v = strtod(s + st, &end);
    if (end != s + q) return mdl_expri_fail(p, st, "malformed number '%.*s'", q - st, s + st);
    if (!isfinite(v)) return mdl_expri_fail(p, st, "number '%.*s' is too large", q - st, s + st);
    p->pos = q;
    int id = mdl_expri_new_node(p, K_NUM, 0, st, 1);
    if (id >= 0) p->x->nodes[id].num = v;
    return id;
}

static int new_seg(parser *p, int start, int len)
{
    mdl_expr *x = p->x;
    if (x->ns == x->scap) {
        int cap = x->scap ? 2 * x->scap : 8;
        seg *segs = realloc(x->segs, (size_t)cap * sizeof *segs);
        if (!segs) return mdl_expri_fail(p, start, "out of memory");
        x->segs = segs;
        x->scap = cap;
    }
    x->segs[x->ns] = (seg){start, len, -1, -1};
    return x->ns++;
}

/* A path at the current position (an identifier there): its first segment in *first, its
 * height (1 + the highest index) in *h. */
int mdl_expri_parse_path(parser *p, int *first, int *h)
{
    int st = p->pos, prev = -1;
    *first = -1;
    *h = 1;
    for (;;) {
        int s0 = p->pos;
        if (!mdl_expri_is_id0((unsigned char)p->s[s0]))
            return mdl_expri_fail(p, s0, "expected a name after '.'");
        while (is_id((unsigned char)p->s[p->pos]))
            p->pos++;
        int sg = new_seg(p, s0, p->pos - s0);
        if (sg < 0) return -1;
        if (prev < 0) {
            *first = sg;
        } else {
            p->x->segs[prev].next = sg;
        }
        prev = sg;
        if (p->s[p->pos] == '[') {
            int open = p->pos++;
            int ix = parse_or(p);
            if (ix < 0) return -1;
            mdl_expri_skip_ws(p);
            if (p->s[p->pos] != ']')
                return p->s[p->pos] ? mdl_expri_fail(p, p->pos,
                                                     "expected ']' to close '[' at column %d", open)
                                    : mdl_expri_fail(p, p->pos,
                                                     "expected ']' to close '[' at column %d "
                                                     "before the end of the expression",
                                                     open);
            p->pos++;
            p->x->segs[sg].index = ix;
            if (height(p, ix) + 1 > *h) *h = height(p, ix) + 1;
        }
        if (p->pos - st >= MDL_EXPR_NAME_MAX - 16)
            return mdl_expri_fail(p, st, "name too long (more than %d characters)",
                                  MDL_EXPR_NAME_MAX - 16);
        if (p->s[p->pos] != '.') break;
        p->pos++;
    }
    return 0;
}

static int find_func(const char *s, int len)
{
    for (int f = 0; f < F_COUNT; f++)
        if ((int)strlen(funcs[f].name) == len && !strncmp(funcs[f].name, s, (size_t)len)) return f;
    return -1;
}

static int find_const(const char *s, int len)
{
    for (int c = 0; c < N_CONSTS; c++)
        if ((int)strlen(consts[c].name) == len && !strncmp(consts[c].name, s, (size_t)len))
            return c;
    return -1;
}

/* The call of function f whose name starts at st; the current position is at '('. */
static int parse_call(parser *p, int f, int st)
{
    int open = p->pos++, first = -1, last = -1, nargs = 0, h = 1;
    mdl_expri_skip_ws(p);
    if (p->s[p->pos] != ')') {
        for (;;) {
            int a = parse_or(p);
            if (a < 0) return -1;
            if (last < 0) {
                first = a;
            } else {
                p->x->nodes[last].next = a;
            }
            last = a;
            nargs++;
            if (height(p, a) + 1 > h) h = height(p, a) + 1;
            mdl_expri_skip_ws(p);
            if (p->s[p->pos] != ',') break;
            p->pos++;
        }
        if (p->s[p->pos] != ')') {
            if (!p->s[p->pos])
                return mdl_expri_fail(
                    p, p->pos,
                    "expected ')' to close '(' at column %d before the end of the "
                    "expression",
                    open);
            return mdl_expri_fail(p, p->pos, "expected ',' or ')' to close '(' at column %d", open);
        }
    }
    p->pos++;
    int want = funcs[f].nargs;
    if (want < 0 && nargs < 1)
        return mdl_expri_fail(p, st, "%s takes at least 1 argument, got 0", funcs[f].name);
    if (want >= 0 && nargs != want)
        return mdl_expri_fail(p, st, "%s takes %d argument%s, got %d", funcs[f].name, want,
                              want == 1 ? "" : "s", nargs);
    int id = mdl_expri_new_node(p, K_CALL, f, st, h);
    if (id < 0) return -1;
    p->x->nodes[id].a = first;
    p->x->nodes[id].b = nargs;
    return id;
}

static int parse_primary(parser *p)
{
    mdl_expri_skip_ws(p);
    const char *s = p->s;
    int st = p->pos;
    if (isdigit((unsigned char)s[st]) || (s[st] == '.' && isdigit((unsigned char)s[st + 1])))
        return parse_number(p);
    if (s[st] == '(') {
        p->pos++;
        int n = parse_or(p);
        if (n < 0) return -1;
        mdl_expri_skip_ws(p);
        if (s[p->pos] != ')') {
            if (!s[p->pos])
                return mdl_expri_fail(
                    p, p->pos,
                    "expected ')' to close '(' at column %d before the end of the "
                    "expression",
                    st);
            return mdl_expri_fail(p, p->pos, "expected ')' to close '(' at column %d", st);
        }
        p->pos++;
        p->x->nodes[n].start = st; /* the span of a parenthesised node includes them */
        p->x->nodes[n].end = p->pos;
        return n;
    }
    if (!mdl_expri_is_id0((unsigned char)s[st])) return mdl_expri_unexpected(p);
    int first, h;
    if (mdl_expri_parse_path(p, &first, &h) < 0) return -1;
    int end = p->pos;
    const seg *g = &p->x->segs[first];
    int simple = g->next < 0 && g->index < 0;
    mdl_expri_skip_ws(p);
    if (s[p->pos] == '(') {
        int f = simple ? find_func(s + st, g->len) : -1;
        if (f >= 0) return parse_call(p, f, st);
        char name[64];
        snprintf(name, sizeof name, "%.*s", end - st > 40 ? 40 : end - st, s + st);
        /* a suggestion within 1 edit of a short name, 2 of a longer one */
        int best = -1, bd = strlen(name) <= 4 ? 2 : 3;
        for (int k = 0; k < F_COUNT; k++) {
            int d = mdl_expr_edit_distance(name, funcs[k].name, 32);
            if (d < bd) {
                bd = d;
                best = k;
            }
        }
        if (best >= 0)
            return mdl_expri_fail(p, st, "unknown function '%s' (did you mean '%s'?)", name,
                                  funcs[best].name);
        return mdl_expri_fail(p, st, "unknown function '%s'", name);
    }
    p->pos = end;
    if (simple) {
        int c = find_const(s + st, g->len);
        if (c >= 0) {
            p->x->ns--; /* the segment was the last one added */
            int id = mdl_expri_new_node(p, K_NUM, 0, st, 1);
            if (id >= 0) p->x->nodes[id].num = consts[c].value;
            return id;
        }
        int f = find_func(s + st, g->len);
        if (f >= 0)
            return mdl_expri_fail(p, st, "'%s' is a function: call it as %s(...)", funcs[f].name,
                                  funcs[f].name);
    }
    int id = mdl_expri_new_node(p, K_NAME, 0, st, h);
    if (id < 0) return -1;
    p->x->nodes[id].a = first;
    p->x->nnames++;
    return id;
}

/* power := primary ('^' unary)? */
static int parse_power(parser *p)
{
    int st = p->pos;
    int l = parse_primary(p);
    if (l < 0) return -1;
    mdl_expri_skip_ws(p);
    if (p->s[p->pos] != '^') return l;
    p->pos++;
    int r = parse_unary(p);
    if (r < 0) return -1;
    int h = (height(p, l) > height(p, r) ? height(p, l) : height(p, r)) + 1;
    int id = mdl_expri_new_node(p, K_BIN, B_POW, st, h);
    if (id >= 0) {
        p->x->nodes[id].a = l;
        p->x->nodes[id].b = r;
    }
    return id;
}

static int parse_unary(parser *p)
{
    if (++p->depth > MDL_EXPR_MAX_DEPTH)
        return mdl_expri_fail(p, p->pos, "expression nested too deeply (more than %d levels)",
                              MDL_EXPR_MAX_DEPTH);
    mdl_expri_skip_ws(p);
    int st = p->pos, c = p->s[st], id;
    if (c == '-' || c == '+' || (c == '!' && p->s[st + 1] != '=')) {
        p->pos++;
        int a = parse_unary(p);
        if (a < 0) return -1;
        id = mdl_expri_new_node(p,
                                c == '-'   ? K_NEG
                                : c == '+' ? K_POS
                                           : K_NOT,
                                0, st, height(p, a) + 1);
        if (id >= 0) p->x->nodes[id].a = a;
    } else {
        id = parse_power(p);
    }
    p->depth--;
    return id;
}

/* The binary operator at the current position that belongs to precedence level lv (0: ||,
 * 1: &&, 2: == !=, 3: < <= > >=, 4: + -, 5: * /): its B_* code with *len set, or -1. */
static int binop_at(const char *s, int lv, int *len)
{
    *len = 2;
    switch (lv) {
    case 0:
        return s[0] == '|' && s[1] == '|' ? B_OR : -1;
    case 1:
        return s[0] == '&' && s[1] == '&' ? B_AND : -1;
    case 2:
        if (s[0] == '=' && s[1] == '=') return B_EQ;
        return s[0] == '!' && s[1] == '=' ? B_NE : -1;
    case 3:
        if (s[0] == '<' && s[1] == '=') return B_LE;
        if (s[0] == '>' && s[1] == '=') return B_GE;
        *len = 1;
        return s[0] == '<' ? B_LT : s[0] == '>' ? B_GT : -1;
    case 4:
        *len = 1;
        return s[0] == '+' ? B_ADD : s[0] == '-' ? B_SUB : -1;
    default:
        *len = 1;
        return s[0] == '*' ? B_MUL : s[0] == '/' ? B_DIV : -1;
    }
}

/* Left-associative levels 0..5; level 6 is unary. Iterative along a level (a long sum does not
 * recurse), so only the node heights bound a chain. */
static int parse_level(parser *p, int lv)
{
    mdl_expri_skip_ws(p);
    int st = p->pos;
    int l = lv == 5 ? parse_unary(p) : parse_level(p, lv + 1);
    while (l >= 0) {
        mdl_expri_skip_ws(p);
        int len, op = binop_at(p->s + p->pos, lv, &len);
        if (op < 0) break;
        p->pos += len;
        int r = lv == 5 ? parse_unary(p) : parse_level(p, lv + 1);
        if (r < 0) return -1;
        int h = (height(p, l) > height(p, r) ? height(p, l) : height(p, r)) + 1;
        int id = mdl_expri_new_node(p, K_BIN, op, st, h);
        if (id < 0) return -1;
        p->x->nodes[id].a = l;
        p->x->nodes[id].b = r;
        l = id;
    }
    return l;
}

static int parse_or(parser *p)
{
    if (++p->depth > MDL_EXPR_MAX_DEPTH)
        return mdl_expri_fail(p, p->pos, "expression nested too deeply (more than %d levels)",
                              MDL_EXPR_MAX_DEPTH);
    int id = parse_level(p, 0);
    p->depth--;
    return id;
}

/* A new empty expression holding a copy of text (NULL with e filled). */
mdl_expr *mdl_expri_new_expr(const char *text, mdl_expr_error *e)
{
    if (!text) {
        mdl_expri_set_error(e, 0, "no expression given");
        return NULL;
    }
    size_t len = strnlen(text, MDL_EXPR_MAX_TEXT + 1);
    if (len > MDL_EXPR_MAX_TEXT) {
        mdl_expri_set_error(e, 0, "expression too long (more than %d characters)",
                            MDL_EXPR_MAX_TEXT);
        return NULL;
    }
    mdl_expr *x = calloc(1, sizeof *x);
    if (x) x->text = malloc(len + 1);
    if (!x || !x->text) {
        free(x);
        mdl_expri_set_error(e, 0, "out of memory");
        return NULL;
    }
    memcpy(x->text, text, len + 1);
    x->root = -1;
    return x;
}

mdl_expr *mdl_expr_parse(const char *text, mdl_expr_error *e)
{
    mdl_expr *x = mdl_expri_new_expr(text, e);
    if (!x) return NULL;
    parser p = {x, x->text, 0, 0, e, 0};
    mdl_expri_skip_ws(&p);
    if (!x->text[p.pos]) {
        mdl_expri_fail(&p, p.pos, "empty expression");
    } else {
        x->root = parse_or(&p);
        if (x->root >= 0) {
            mdl_expri_skip_ws(&p);
            if (x->text[p.pos]) mdl_expri_unexpected(&p);
        }
    }
    if (p.failed) {
        mdl_expr_free(x);
        return NULL;
    }
    return x;
}

void mdl_expr_free(mdl_expr *x)
{
    if (!x) return;
    free(x->text);
    free(x->nodes);
    free(x->segs);
    free(x);
}

const char *mdl_expr_text(const mdl_expr *x)
{
    return x ? x->text : NULL;
}

int mdl_expr_is_constant(const mdl_expr *x)
{
    return x && x->nnames == 0;
}

int mdl_expr_is_reserved(const char *name)
{
    if (!name) return 0;
    int len = (int)strlen(name);
    return find_func(name, len) >= 0 || find_const(name, len) >= 0;
}
