/* The model reader's common parts: positioned errors, nearest names, scopes and the evaluation of
 * parameters (mdl_priv.h). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mdl_priv.h"

int mdl_fail(mdl_model *mm, const mdl_y_node *at, const char *where, const char *fmt, ...)
{
    char msg[BG_MESSAGE_SIZE], pos[256];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    if (at)
        mdl_y_where(at, pos, sizeof pos);
    else
        snprintf(pos, sizeof pos, "%s", mm->file ? mm->file : "model");
    if (where && *where)
        bg_error_raise(mm->err, BG_ERR_ARGUMENT, "mdl_load", "%s: %s: %s", pos, where, msg);
    else
        bg_error_raise(mm->err, BG_ERR_ARGUMENT, "mdl_load", "%s: %s", pos, msg);
    return BG_ERR_ARGUMENT;
}

/* Levenshtein distance, capped: names longer than 63 characters are never near */
static int distance(const char *a, const char *b)
{
    if (strlen(a) > 63 || strlen(b) > 63) return 99;
    return mdl_expr_edit_distance(a, b, 63);
}

const char *mdl_nearest(const char *name, const char *const *cand, int n)
{
    const char *best = "";
    int bd = 99, len = (int)strlen(name);
    for (int i = 0; i < n; i++) {
        int d = distance(name, cand[i]);
        if (d < bd) bd = d, best = cand[i];
    }
    /* near: at most a third of the name wrong (and at least one letter) */
    return bd <= (len > 3 ? len / 3 : 1) ? best : "";
}

int mdl_scope_add(mdl_scope *s, const char *name, const mdl_y_node *node, const char *text,
                  mdl_scope *eval)
{
    if (s->n == s->cap) {
        int nc = s->cap ? 2 * s->cap : 8;
        mdl_var *v = realloc(s->vars, (size_t)nc * sizeof *v);
        if (!v) return BG_ERR_MEMORY;
        s->vars = v;
        s->cap = nc;
    }
    char *nm = strdup(name);
    if (!nm) return BG_ERR_MEMORY;
    s->vars[s->n++] = (mdl_var){nm, node, text, eval ? eval : s, 0, 0, 0, NULL};
    return BG_OK;
}

mdl_var *mdl_scope_find(mdl_scope *s, const char *name, int outward)
{
    for (; s; s = outward ? s->parent : NULL)
        for (int i = 0; i < s->n; i++)
            if (!strcmp(s->vars[i].name, name)) return &s->vars[i];
    return NULL;
}

void mdl_scope_clear(mdl_scope *s)
{
    for (int i = 0; i < s->n; i++) {
        free(s->vars[i].name);
        free(s->vars[i].vec);
    }
    free(s->vars);
    s->vars = NULL;
    s->n = s->cap = 0;
}

/* ---- evaluation ---- */

typedef struct lookup_ctx {
    mdl_model *mm;
    mdl_scope *s;
    const char *where;
    int failed_inside; /* a referenced parameter failed: its own message stands */
} lookup_ctx;

static int lookup(void *user, const char *name, double *value, char *msg, size_t msz)
{
    lookup_ctx *c = user;
    char base[MDL_EXPR_NAME_MAX];
    long idx = -1;
    snprintf(base, sizeof base, "%s", name);
    char *br = strchr(base, '[');
    if (br) {
        char *end;
        idx = strtol(br + 1, &end, 10);
        if (*end != ']' || end[1] != 0) {
            snprintf(msg, msz, "'%s' is not a parameter (a name, or a vector's entry name[i])", name);
            return -1;
        }
        *br = 0;
    }
    if (strchr(base, '.')) {
        snprintf(msg, msz, "'%s': a path is not a parameter here (paths name unknowns and signals "
                 "in outputs)", name);
        return -1;
    }
    mdl_var *v = mdl_scope_find(c->s, base, 1);
    if (!v) {
        snprintf(msg, msz, "unknown name '%s'", base);
        return -1;
    }
    if (mdl_var_eval(c->mm, v, c->where) != BG_OK) {
        c->failed_inside = 1;
        snprintf(msg, msz, "%s", "(see the parameter's error)");
        return -1;
    }
    if (idx >= 0) {
        if (v->len == 0) {
            snprintf(msg, msz, "'%s' is a number, not a vector", base);
            return -1;
        }
        if (idx >= v->len) {
            snprintf(msg, msz, "'%s' has %d entries, index %ld is out of range", base, v->len, idx);
            return -1;
        }
        *value = v->vec[idx];
        return 0;
    }
    if (v->len > 0) {
        snprintf(msg, msz, "'%s' is a vector of %d: name an entry, %s[0] .. %s[%d]", base, v->len,
                 base, base, v->len - 1);
        return -1;
    }
    *value = v->value;
    return 0;
}

static int eval_text(mdl_model *mm, mdl_scope *s, const mdl_y_node *at, const char *text,
                     const char *where, double *value)
{
    mdl_expr_error e = {0};
    mdl_expr *x = mdl_expr_parse(text, &e);
    if (!x) {
        /* the column within the scalar: exact for plain scalars on one line */
        if (at && !at->quoted) {
            mdl_y_node shifted = *at;
            shifted.column += e.column;
            return mdl_fail(mm, &shifted, where, "%s in '%s'", e.message, text);
        }
        return mdl_fail(mm, at, where, "%s (at column %d of '%s')", e.message, e.column + 1, text);
    }
    lookup_ctx c = {mm, s, where, 0};
    int r = mdl_expr_eval(x, lookup, &c, value, &e);
    mdl_expr_free(x);
    if (r != 0) {
        if (c.failed_inside) return BG_ERR_ARGUMENT;
        return mdl_fail(mm, at, where, "%s in '%s'", e.message, text);
    }
    return BG_OK;
}

int mdl_eval_number(mdl_model *mm, mdl_scope *s, const mdl_y_node *node, const char *text,
                    const char *where, double *value)
{
    if (!text) {
        if (!node || node->kind != MDL_Y_SCALAR || mdl_y_is_null(node))
            return mdl_fail(mm, node, where, "expected a number or an expression, got %s",
                            node ? (node->kind == MDL_Y_SCALAR ? "nothing" : mdl_y_kind_name(node->kind))
                                 : "nothing");
        text = node->text;
    }
    return eval_text(mm, s, node, text, where, value);
}

/* splits "[a, b, c]" (a default written as a list) into its entries, in place */
static int split_list(char *t, char **items, int max)
{
    char *p = strchr(t, '['), *q = strrchr(t, ']');
    if (!p || !q || q < p) return -1;
    *q = 0;
    int n = 0, depth = 0;
    char *start = p + 1;
    for (char *c = start;; c++) {
        if (*c == '(' || *c == '[') depth++;
        if (*c == ')' || *c == ']') depth--;
        if ((*c == ',' && depth == 0) || *c == 0) {
            int end = *c == 0;
            *c = 0;
            if (n == max) return -1;
            items[n++] = start;
            start = c + 1;
            if (end) break;
        }
    }
    if (n == 1 && strspn(items[0], " \t") == strlen(items[0])) n = 0;
    return n;
}

int mdl_eval_vector(mdl_model *mm, mdl_scope *s, const mdl_y_node *node, const char *text,
                    const char *where, double **vec, int *len)
{
    *vec = NULL;
    *len = 0;
    if (!text && node && node->kind == MDL_Y_SEQUENCE) {
        int n = mdl_y_count(node);
        double *v = malloc((size_t)(n > 0 ? n : 1) * sizeof *v);
        if (!v) return BG_ERR_MEMORY;
        for (int i = 0; i < n; i++) {
            char w[512];
            snprintf(w, sizeof w, "%s[%d]", where, i);
            int r = mdl_eval_number(mm, s, mdl_y_item(node, i), NULL, w, &v[i]);
            if (r != BG_OK) {
                free(v);
                return r;
            }
        }
        *vec = v;
        *len = n;
        return BG_OK;
    }
    const char *t = text ? text : node && node->kind == MDL_Y_SCALAR ? node->text : NULL;
    if (!t) return mdl_fail(mm, node, where, "expected a list of numbers [a, b, ...]");
    if (strchr(t, '[') && t[strspn(t, " \t")] == '[') { /* a list written as text (a default, --set) */
        char *copy = strdup(t), *items[1024];
        if (!copy) return BG_ERR_MEMORY;
        int n = split_list(copy, items, 1024);
        if (n < 0) {
            free(copy);
            return mdl_fail(mm, node, where, "expected a list of numbers [a, b, ...], got '%s'", t);
        }
        double *v = malloc((size_t)(n > 0 ? n : 1) * sizeof *v);
        int r = v ? BG_OK : BG_ERR_MEMORY;
        for (int i = 0; r == BG_OK && i < n; i++)
            r = eval_text(mm, s, node, items[i], where, &v[i]);
        free(copy);
        if (r != BG_OK) {
            free(v);
            return r;
        }
        *vec = v;
        *len = n;
        return BG_OK;
    }
    /* the name of a vector parameter */
    const char *b = t + strspn(t, " \t");
    char name[128];
    size_t k = strcspn(b, " \t");
    if (k < sizeof name && b[k + strspn(b + k, " \t")] == 0) {
        memcpy(name, b, k);
        name[k] = 0;
        mdl_var *v = mdl_scope_find(s, name, 1);
        if (v) {
            int r = mdl_var_eval(mm, v, where);
            if (r != BG_OK) return r;
            if (v->len > 0) {
                *vec = malloc((size_t)v->len * sizeof **vec);
                if (!*vec) return BG_ERR_MEMORY;
                memcpy(*vec, v->vec, (size_t)v->len * sizeof **vec);
                *len = v->len;
                return BG_OK;
            }
        }
    }
    return mdl_fail(mm, node, where, "expected a list of numbers [a, b, ...] or the name of a "
                    "vector parameter, got '%s'", t);
}

int mdl_var_eval(mdl_model *mm, mdl_var *v, const char *where)
{
    (void)where;
    if (v->state == 2) return BG_OK;
    if (v->state == 1) {
        char cyc[BG_MESSAGE_SIZE / 2];
        size_t o = 0;
        int first = 0;
        while (first < mm->nchain && mm->chain[first] != v)
            first++;
        for (int i = first; i < mm->nchain && o < sizeof cyc; i++)
            o += (size_t)snprintf(cyc + o, sizeof cyc - o, "%s -> ", mm->chain[i]->name);
        if (o < sizeof cyc) snprintf(cyc + o, sizeof cyc - o, "%s", v->name);
        return mdl_fail(mm, v->node, v->name, "the parameters refer to each other in a cycle: %s", cyc);
    }
    if (mm->nchain == (int)(sizeof mm->chain / sizeof mm->chain[0]))
        return mdl_fail(mm, v->node, v->name, "parameters nested more than %d deep",
                        (int)(sizeof mm->chain / sizeof mm->chain[0]));
    v->state = 1;
    mm->chain[mm->nchain++] = v;
    int r;
    const char *t = v->text ? v->text : v->node && v->node->kind == MDL_Y_SCALAR ? v->node->text : NULL;
    int is_vec = (!v->text && v->node && v->node->kind == MDL_Y_SEQUENCE) ||
                 (t && t[strspn(t, " \t")] == '[');
    if (is_vec) {
        r = mdl_eval_vector(mm, v->eval, v->node, v->text, v->name, &v->vec, &v->len);
        if (r == BG_OK && v->len == 0) r = mdl_fail(mm, v->node, v->name, "an empty list");
    } else {
        r = mdl_eval_number(mm, v->eval, v->node, v->text, v->name, &v->value);
    }
    mm->nchain--;
    v->state = r == BG_OK ? 2 : 0;
    return r;
}

int mdl_eval_path(mdl_model *mm, mdl_scope *s, const mdl_y_node *node, const char *where,
                  char *out, size_t size)
{
    if (!node || node->kind != MDL_Y_SCALAR || mdl_y_is_null(node))
        return mdl_fail(mm, node, where, "expected a path (instance.port, instance.signal)");
    lookup_ctx c = {mm, s, where, 0};
    mdl_expr_error e = {0};
    if (mdl_expr_subst(node->text, lookup, &c, out, size, &e) != 0) {
        if (c.failed_inside) return BG_ERR_ARGUMENT;
        return mdl_fail(mm, node, where, "%s in the path '%s'", e.message, node->text);
    }
    return BG_OK;
}

int mdl_read_for(mdl_model *mm, mdl_scope *s, const mdl_y_node *forn, const char *where,
                 const char **var, long *first, long *last)
{
    if (!forn || forn->kind != MDL_Y_MAPPING || mdl_y_count(forn) != 1)
        return mdl_fail(mm, forn, where, "for: expected one variable and its range, {k: [first, last]}");
    const mdl_y_node *k = mdl_y_key(forn, 0), *range = mdl_y_value(forn, 0);
    if (mdl_expr_is_reserved(k->text))
        return mdl_fail(mm, k, where, "for: '%s' is a function or constant of the expressions", k->text);
    if (!range || range->kind != MDL_Y_SEQUENCE || mdl_y_count(range) != 2)
        return mdl_fail(mm, range ? range : forn, where, "for: expected the range [first, last]");
    double a, b;
    int r = mdl_eval_number(mm, s, mdl_y_item(range, 0), NULL, where, &a);
    if (r == BG_OK) r = mdl_eval_number(mm, s, mdl_y_item(range, 1), NULL, where, &b);
    if (r != BG_OK) return r;
    if (a != floor(a) || b != floor(b) || fabs(a) > 1e6 || fabs(b) > 1e6)
        return mdl_fail(mm, range, where, "for: the range's ends must be whole numbers within "
                        "+-1e6, got [%g, %g]", a, b);
    if (b - a >= 100000)
        return mdl_fail(mm, range, where, "for: %g repetitions, at most 100000", b - a + 1);
    *var = k->text;
    *first = (long)a;
    *last = (long)b;
    return BG_OK;
}

int mdl_check_keys(mdl_model *mm, const mdl_y_node *map, const char *where,
                   const char *const *allowed, int nallowed)
{
    for (int i = 0; i < mdl_y_count(map); i++) {
        const mdl_y_node *k = mdl_y_key(map, i);
        int ok = 0;
        for (int j = 0; j < nallowed && !ok; j++)
            ok = !strcmp(k->text, allowed[j]);
        if (!ok) {
            const char *near = mdl_nearest(k->text, allowed, nallowed);
            return mdl_fail(mm, k, where, "unknown key '%s'%s%s%s", k->text,
                            *near ? " (did you mean '" : "", near, *near ? "'?)" : "");
        }
    }
    return BG_OK;
}
