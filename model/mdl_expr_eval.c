/* The evaluation of the model files' expressions, the names they refer to and the paths with
 * index expressions (see mdl_expr.h; the tree in mdl_expr_impl.h).
 *
 * Method: a recursive walk of the tree; its depth is bounded by the node heights
 * (<= MDL_EXPR_MAX_DEPTH). Every operation checks that its result is finite (its inputs are,
 * by induction: numbers and looked-up values are checked), so a NaN or an infinity is reported
 * at the operation that made it, with its sub-expression. if, && and || evaluate lazily. */
#include "mdl_expr_impl.h"

#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

/* ---- evaluation ---- */

typedef struct evaluator {
    const mdl_expr *x;
    mdl_expr_lookup fn;
    void *user;
    mdl_expr_error *e;
} evaluator;

static int ev(const evaluator *c, int id, double *v);

static int ev_fail(const evaluator *c, int id, const char *what)
{
    const node *n = &c->x->nodes[id];
    char buf[72];
    mdl_expri_set_error(c->e, n->start, "%s in '%s'", what,
                        mdl_expri_snippet(c->x->text, n->start, n->end, buf, sizeof buf));
    return -1;
}

/* Writes the path of the name node id with its indices evaluated into buf (size
 * MDL_EXPR_NAME_MAX). */
static int ev_path(const evaluator *c, int id, char *buf)
{
    const mdl_expr *x = c->x;
    const node *n = &x->nodes[id];
    size_t len = 0, cut = 0;
    buf[0] = '\0';
    for (int s = n->a; s >= 0; s = x->segs[s].next) {
        const seg *g = &x->segs[s];
        /* the segment copied, not printed: this runs once per name at every evaluation */
        size_t w = (s == n->a ? 0 : 1) + (size_t)g->len;
        if ((cut = w >= MDL_EXPR_NAME_MAX - len)) break;
        if (s != n->a) buf[len++] = '.';
        memcpy(buf + len, x->text + g->start, (size_t)g->len);
        len += (size_t)g->len;
        buf[len] = '\0';
        if (g->index < 0) continue;
        double v;
        if (ev(c, g->index, &v) < 0) return -1;
        const node *ix = &x->nodes[g->index];
        char sbuf[72];
        if (v != floor(v) || v < INT_MIN || v > INT_MAX) {
            mdl_expri_set_error(c->e, ix->start, "index '%s' of '%s' is %s (%.17g)",
                                mdl_expri_snippet(x->text, ix->start, ix->end, sbuf, sizeof sbuf),
                                buf, v != floor(v) ? "not an integer" : "out of range", v);
            return -1;
        }
        int wi = snprintf(buf + len, MDL_EXPR_NAME_MAX - len, "[%d]", (int)v);
        if ((cut = wi < 0 || (size_t)wi >= MDL_EXPR_NAME_MAX - len)) break;
        len += (size_t)wi;
    }
    if (cut) {
        mdl_expri_set_error(c->e, n->start, "name too long (more than %d characters)",
                            MDL_EXPR_NAME_MAX - 2);
        return -1;
    }
    return 0;
}

static int ev_name(const evaluator *c, int id, double *v)
{
    char name[MDL_EXPR_NAME_MAX];
    if (ev_path(c, id, name) < 0) return -1;
    int col = c->x->nodes[id].start;
    if (!c->fn) {
        mdl_expri_set_error(c->e, col, "unknown name '%s'", name);
        return -1;
    }
    char msg[MDL_EXPR_MSG_SIZE] = "";
    if (c->fn(c->user, name, v, msg, sizeof msg) < 0) {
        if (msg[0]) {
            mdl_expri_set_error(c->e, col, "%s", msg);
        } else {
            mdl_expri_set_error(c->e, col, "unknown name '%s'", name);
        }
        return -1;
    }
    if (!isfinite(*v)) {
        mdl_expri_set_error(c->e, col, "'%s' is not a finite number", name);
        return -1;
    }
    return 0;
}

/* A non-finite result r of pow(a, b) (also '^'). */
static int pow_fail(const evaluator *c, int id, double a, double b)
{
    if (a == 0 && b < 0) return ev_fail(c, id, "zero to a negative power");
    if (a < 0 && b != floor(b)) return ev_fail(c, id, "negative number to a non-integer power");
    return ev_fail(c, id, "overflow");
}

static int ev_call(const evaluator *c, int id, double *v)
{
    const node *n = &c->x->nodes[id];
    const node *nodes = c->x->nodes;
    double a[2] = {0, 0}, r;
    if (n->op == F_IF) {
        int cond = n->a;
        if (ev(c, cond, &r) < 0) return -1;
        int arg = r != 0 ? nodes[cond].next : nodes[nodes[cond].next].next;
        return ev(c, arg, v);
    }
    if (n->op == F_MIN || n->op == F_MAX) {
        if (ev(c, n->a, &r) < 0) return -1;
        for (int k = nodes[n->a].next; k >= 0; k = nodes[k].next) {
            if (ev(c, k, &a[0]) < 0) return -1;
            r = n->op == F_MIN ? fmin(r, a[0]) : fmax(r, a[0]);
        }
        *v = r;
        return 0;
    }
    int k = n->a;
    for (int i = 0; i < n->b && i < 2; i++, k = nodes[k].next)
        if (ev(c, k, &a[i]) < 0) return -1;
    switch (n->op) {
    case F_SQRT:
        r = sqrt(a[0]);
        break;
    case F_EXP:
        r = exp(a[0]);
        break;
    case F_LOG:
        r = log(a[0]);
        break;
    case F_LOG10:
        r = log10(a[0]);
        break;
    case F_SIN:
        r = sin(a[0]);
        break;
    case F_COS:
        r = cos(a[0]);
        break;
    case F_TAN:
        r = tan(a[0]);
        break;
    case F_ASIN:
        r = asin(a[0]);
        break;
    case F_ACOS:
        r = acos(a[0]);
        break;
    case F_ATAN:
        r = atan(a[0]);
        break;
    case F_ATAN2:
        r = atan2(a[0], a[1]);
        break;
    case F_SINH:
        r = sinh(a[0]);
        break;
    case F_COSH:
        r = cosh(a[0]);
        break;
    case F_TANH:
        r = tanh(a[0]);
        break;
    case F_HYPOT:
        r = hypot(a[0], a[1]);
        break;
    case F_ABS:
        r = fabs(a[0]);
        break;
    case F_FLOOR:
        r = floor(a[0]);
        break;
    case F_CEIL:
        r = ceil(a[0]);
        break;
    case F_ROUND:
        r = round(a[0]);
        break;
    default:
        r = pow(a[0], a[1]);
        break; /* F_POW */
    }
    if (!isfinite(r)) {
        switch (n->op) {
        case F_SQRT:
            return ev_fail(c, id, "square root of a negative number");
        case F_LOG:
        case F_LOG10:
            return ev_fail(c, id,
                           a[0] == 0 ? "logarithm of zero" : "logarithm of a negative number");
        case F_ASIN:
        case F_ACOS:
            return ev_fail(c, id, "argument outside [-1, 1]");
        case F_POW:
            return pow_fail(c, id, a[0], a[1]);
        default:
            return ev_fail(c, id, isnan(r) ? "undefined result" : "overflow");
        }
    }
    *v = r;
    return 0;
}

static int ev_bin(const evaluator *c, int id, double *v)
{
    const node *n = &c->x->nodes[id];
    double l, r;
    if (ev(c, n->a, &l) < 0) return -1;
    if (n->op == B_AND || n->op == B_OR) {
        if ((n->op == B_AND) == (l == 0)) { /* decided by the left side */
            *v = n->op == B_OR;
            return 0;
        }
        if (ev(c, n->b, &r) < 0) return -1;
        *v = r != 0;
        return 0;
    }
    if (ev(c, n->b, &r) < 0) return -1;
    double x;
    switch (n->op) {
    case B_ADD:
        x = l + r;
        break;
    case B_SUB:
        x = l - r;
        break;
    case B_MUL:
        x = l * r;
        break;
    case B_DIV:
        if (r == 0) return ev_fail(c, id, "division by zero");
        x = l / r;
        break;
    case B_POW:
        x = pow(l, r);
        break;
    case B_LT:
        x = l < r;
        break;
    case B_LE:
        x = l <= r;
        break;
    case B_GT:
        x = l > r;
        break;
    case B_GE:
        x = l >= r;
        break;
    case B_EQ:
        x = l == r;
        break;
    default:
        x = l != r;
        break; /* B_NE */
    }
    if (!isfinite(x)) return n->op == B_POW ? pow_fail(c, id, l, r) : ev_fail(c, id, "overflow");
    *v = x;
    return 0;
}

/* Recursion depth <= the node heights <= MDL_EXPR_MAX_DEPTH. */
static int ev(const evaluator *c, int id, double *v)
{
    const node *n = &c->x->nodes[id];
    switch (n->kind) {
    case K_NUM:
        *v = n->num;
        return 0;
    case K_NAME:
        return ev_name(c, id, v);
    case K_BIN:
        return ev_bin(c, id, v);
    case K_CALL:
        return ev_call(c, id, v);
    default:
        break;
    }
    double a;
    if (ev(c, n->a, &a) < 0) return -1;
    *v = n->kind == K_NEG ? -a : n->kind == K_POS ? a : (double)(a == 0);
    return 0;
}

int mdl_expr_eval(const mdl_expr *x, mdl_expr_lookup fn, void *user, double *value,
                  mdl_expr_error *e)
{
    if (!x || !value || x->root < 0) {
        mdl_expri_set_error(e, 0, "no expression or no place for the value");
        return -1;
    }
    evaluator c = {x, fn, user, e};
    return ev(&c, x->root, value) < 0 ? -1 : 0;
}

/* ---- names ---- */

static int has_names(const mdl_expr *x, int id)
{
    const node *n = &x->nodes[id];
    switch (n->kind) {
    case K_NUM:
        return 0;
    case K_NAME:
        return 1;
    case K_BIN:
        return has_names(x, n->a) || has_names(x, n->b);
    case K_CALL:
        for (int k = n->a; k >= 0; k = x->nodes[k].next)
            if (has_names(x, k)) return 1;
        return 0;
    default:
        return has_names(x, n->a);
    }
}

static int visit_names(const mdl_expr *x, int id, void (*visit)(void *, const char *), void *user)
{
    const node *n = &x->nodes[id];
    int count = 0;
    switch (n->kind) {
    case K_NUM:
        return 0;
    case K_BIN:
        return visit_names(x, n->a, visit, user) + visit_names(x, n->b, visit, user);
    case K_CALL:
        for (int k = n->a; k >= 0; k = x->nodes[k].next)
            count += visit_names(x, k, visit, user);
        return count;
    case K_NAME:
        break;
    default:
        return visit_names(x, n->a, visit, user);
    }
    char buf[MDL_EXPR_NAME_MAX];
    size_t len = 0;
    buf[0] = '\0';
    for (int s = n->a; s >= 0; s = x->segs[s].next) {
        const seg *g = &x->segs[s];
        char ix[16] = "";
        if (g->index >= 0) {
            double v;
            evaluator c = {x, NULL, NULL, NULL};
            count += visit_names(x, g->index, visit, user);
            if (!has_names(x, g->index) && ev(&c, g->index, &v) == 0 && v == floor(v) &&
                v >= INT_MIN && v <= INT_MAX) {
                snprintf(ix, sizeof ix, "[%d]", (int)v);
            } else {
                strcpy(ix, "[*]");
            }
        }
        int w = snprintf(buf + len, sizeof buf - len, "%s%.*s%s", s == n->a ? "" : ".", g->len,
                         x->text + g->start, ix);
        if (w < 0 || (size_t)w >= sizeof buf - len) break; /* cut (parse limits the length) */
        len += (size_t)w;
    }
    if (visit) visit(user, buf);
    return count + 1;
}

int mdl_expr_names(const mdl_expr *x, void (*visit)(void *user, const char *name_pattern),
                   void *user)
{
    if (!x || x->root < 0) return 0;
    return visit_names(x, x->root, visit, user);
}

/* ---- paths ---- */

int mdl_expr_subst(const char *path_text, mdl_expr_lookup fn, void *user, char *out, size_t osz,
                   mdl_expr_error *e)
{
    mdl_expr *x = mdl_expri_new_expr(path_text, e);
    if (!x) return -1;
    parser p = {x, x->text, 0, 0, e, 0};
    int first = -1, h, r = -1;
    mdl_expri_skip_ws(&p);
    int st = p.pos;
    if (!mdl_expri_is_id0((unsigned char)x->text[st])) {
        if (x->text[st])
            mdl_expri_fail(&p, st, "expected a path (name.name[index]...)");
        else
            mdl_expri_fail(&p, st, "empty path");
    } else if (mdl_expri_parse_path(&p, &first, &h) == 0) {
        mdl_expri_skip_ws(&p);
        if (x->text[p.pos]) mdl_expri_unexpected(&p);
    }
    if (!p.failed) {
        int id = mdl_expri_new_node(&p, K_NAME, 0, st, h);
        if (id >= 0) {
            x->nodes[id].a = first;
            char buf[MDL_EXPR_NAME_MAX];
            evaluator c = {x, fn, user, e};
            if (ev_path(&c, id, buf) == 0) {
                if (!out || strlen(buf) >= osz) {
                    mdl_expri_set_error(e, st, "path '%s' too long for its buffer (%zu bytes)", buf,
                                        osz);
                } else {
                    strcpy(out, buf);
                    r = 0;
                }
            }
        }
    }
    mdl_expr_free(x);
    return r;
}
