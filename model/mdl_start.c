/* The start configuration (the types' place() in rounds, positions passed through joints), the
 * `initial` values, the outputs and the solver settings of a model file (mdl_priv.h). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mdl_priv.h"
#include "sig_sources.h"

typedef struct place_ctx {
    const mdl_model *mm;
    const double *y; /* the state the positions are taken at (NULL: the start, bgr_y0) */
    int depth;
} place_ctx;

static int leaf_placed(const mdl_inode *l)
{
    return !l->type->place || l->inst.placed;
}

/* the position of port `port` of leaf `l` itself (its own port_position, or through a joint) */
static int own_position(place_ctx *c, const mdl_inode *l, int port, double x[3]);

/* the position at the other end of the bond at port `port` of leaf `self` */
static int locate_neighbour(place_ctx *c, const mdl_inode *self, int port, double x[3])
{
    const mdl_model *mm = c->mm;
    for (int i = 0; i < mm->nbonds; i++)
        for (int s = 0; s < 2; s++)
            if (mm->bonds[i].leaf[s] == self && mm->bonds[i].port[s] == port)
                return own_position(c, mm->bonds[i].leaf[1 - s], mm->bonds[i].port[1 - s], x);
    return BG_ERR_ARGUMENT;
}

static int own_position(place_ctx *c, const mdl_inode *l, int port, double x[3])
{
    if (c->depth > 64) return BG_ERR_ARGUMENT;
    if (l->type->flags & MDL_PASS_POSITION) {
        int got = MDL_NOT_YET + 100;
        c->depth++;
        for (int p = 0; p < l->inst.nports && got != BG_OK; p++) {
            const mdl_iport *ip = mdl_instance_port_at(&l->inst, p);
            if (p == port || (ip->domain != MDL_MECH3 && ip->domain != MDL_MECH6)) continue;
            /* no going back along the same bond: the other side's neighbour */
            int r = locate_neighbour(c, l, p, x);
            if (r == BG_OK || r == MDL_NOT_YET) got = r;
        }
        c->depth--;
        return got == MDL_NOT_YET + 100 ? BG_ERR_ARGUMENT : got;
    }
    if (!l->type->port_position) return BG_ERR_ARGUMENT;
    if (!leaf_placed(l)) return MDL_NOT_YET;
    return l->type->port_position(c->mm->m, &l->inst, port, c->y ? c->y : bgr_y0(c->mm->m), x);
}

static int locate(void *ctx, const mdl_instance *self, int port, double x[3])
{
    place_ctx *c = ctx;
    const mdl_inode *leaf = NULL;
    for (int i = 0; i < c->mm->nleaves && !leaf; i++)
        if (&c->mm->leaves[i]->inst == self) leaf = c->mm->leaves[i];
    if (!leaf || port < 0 || port >= self->nports) return BG_ERR_ARGUMENT;
    c->depth = 0;
    return locate_neighbour(c, leaf, port, x);
}

int mdl_neighbour_position(const mdl_model *mm, const mdl_inode *leaf, int port, const double *y,
                           double x[3])
{
    place_ctx c = {mm, y, 0};
    return locate_neighbour(&c, leaf, port, x);
}

int mdl_place_all(mdl_model *mm)
{
    place_ctx c = {mm, NULL, 0};
    for (int round = 0; round <= mm->nleaves; round++) {
        int left = 0, progress = 0;
        for (int i = 0; i < mm->nleaves; i++) {
            mdl_inode *l = mm->leaves[i];
            if (leaf_placed(l)) continue;
            mdl_locator loc = {&c, &l->inst, locate};
            bg_error e = {0}; /* no handler: place() only records its message */
            bg_error_clear(&e);
            int r = l->type->place(mm->m, &l->inst, &l->inst.args, &loc, &e);
            if (r == BG_OK) {
                l->inst.placed = 1;
                progress = 1;
            } else if (r == MDL_NOT_YET) {
                left++;
            } else if (r == BG_ERR_ARGUMENT && !e.message[0]) {
                return mdl_fail(mm, l->key, l->dotpath, "its start position cannot be found: what "
                                "it is bonded to has no position (give it a position parameter)");
            } else {
                return mdl_fail(mm, l->key, l->dotpath, "%s", e.message[0] ? e.message : bg_status_message(r));
            }
        }
        if (!left) return BG_OK;
        if (!progress) break;
    }
    for (int i = 0; i < mm->nleaves; i++)
        if (!leaf_placed(mm->leaves[i]))
            return mdl_fail(mm, mm->leaves[i]->key, mm->leaves[i]->dotpath,
                            "its start position depends on elements that depend on it in turn: "
                            "give one of them a position");
    return BG_OK;
}

/* ---- the sources' start ---- */

static int settle(bgr_model *m, int elem, mdl_source_output what, bg_error *err)
{
    bgr_element *el = bgr_element_get(m, elem);
    if (!el || !el->cls->residual || el->neq < 1)
        return bg_error_raise(err, BG_ERR_ARGUMENT, "model", "element %d: not a source", elem);
    double *y = bgr_y0(m), *yp = bgr_yp0(m);
    double *F = calloc(2 * (size_t)el->neq, sizeof *F);
    if (!F) return bg_error_raise(err, BG_ERR_MEMORY, "model", "out of memory");
    int r = BG_OK;
    for (int i = 0; r == BG_OK && i < el->neq; i++) {
        int v = what == MDL_SRC_EFFORT ? bgr_ev(el, m, 0, i)
                : what == MDL_SRC_FLOW ? bgr_fv(el, m, 0, i)
                                       : bgr_av(el, i);
        if (v < 0) {
            r = bg_error_raise(err, BG_ERR_ARGUMENT, "model", "%s: no unknown for equation %d",
                               el->name ? el->name : "source", i);
            break;
        }
        double old = y[v], *F1 = F + el->neq;
        int a = el->cls->residual(el, 0.0, y, yp, F);
        y[v] = old + 1;
        int b = el->cls->residual(el, 0.0, y, yp, F1);
        y[v] = old;
        double slope = F1[i] - F[i]; /* exact: the equation is linear in y[v] */
        if (a < 0 || b < 0 || !(fabs(slope) > 0) || !isfinite(F[i]))
            r = bg_error_raise(err, BG_ERR_ARGUMENT, "model",
                               "%s: its equation %d cannot be solved for its output at t = 0",
                               el->name ? el->name : "source", i);
        else
            y[v] = old - F[i] / slope;
    }
    free(F);
    return r;
}

int mdl_place_source(bgr_model *m, int elem, mdl_source_output what, const bgr_ref *follows,
                     bg_error *err)
{
    if (follows && follows->type == BGR_OWN) {
        const bgr_element *src = bgr_element_get(m, follows->id);
        if (src && src->cls == &sig_class_source) {
            int r = settle(m, follows->id, MDL_SRC_SIGNAL, err);
            if (r != BG_OK) return r;
        }
    }
    return settle(m, elem, what, err);
}

/* ---- unknowns by path ---- */

/* "rod1.body.x0" -> the unknown's id, or a signal's, or a port's bond ("supply.p.f": the
 * flow of the bond at supply's port p, oriented as the bond is written); -1 with the message set */
static int var_of_path(mdl_model *mm, const char *path, const mdl_y_node *at, const char *where)
{
    mdl_inode *leaf;
    const char *rest;
    int r = mdl_resolve(mm, &mm->top, path, at, where, &leaf, &rest);
    if (r != BG_OK) return -1;
    if (!leaf || !leaf->type || !rest) {
        mdl_fail(mm, at, where, "'%s' names %s, not an unknown or a signal", path,
                 leaf && leaf->type ? "an element" : "a subsystem");
        return -1;
    }
    const mdl_isignal *s = mdl_instance_find_signal(&leaf->inst, rest);
    if (s) {
        int v = bgr_ref_var(mm->m, s->r);
        if (v < 0) mdl_fail(mm, at, where, "'%s': the signal has no unknown", path);
        return v;
    }
    /* "port.e", "port.f" (1D) or "port.e2" (a vector port's entry): the bond at that port */
    const char *dot = strrchr(rest, '.');
    if (dot && (dot[1] == 'e' || dot[1] == 'f')) {
        char pname[256];
        int len = (int)(dot - rest), idx = 0, nd = 0;
        if (len < (int)sizeof pname && (dot[2] == '\0' || sscanf(dot + 2, "%d%n", &idx, &nd) == 1) &&
            dot[2 + nd] == '\0') {
            memcpy(pname, rest, (size_t)len);
            pname[len] = '\0';
            int k = mdl_instance_find_port(&leaf->inst, pname);
            const mdl_iport *ip = k >= 0 ? mdl_instance_port_at(&leaf->inst, k) : NULL;
            if (ip && idx >= 0 && idx < ip->dim) {
                const bgr_element *el = bgr_element_get(mm->m, ip->p.elem);
                int v = dot[1] == 'e' ? bgr_ev(el, mm->m, ip->p.port, idx)
                                      : bgr_fv(el, mm->m, ip->p.port, idx);
                if (v >= 0) return v;
            }
        }
    }
    char full[1024];
    int o = snprintf(full, sizeof full, "%s/%s/%s", mm->name, leaf->path, rest);
    for (int i = (int)(strlen(mm->name) + strlen(leaf->path)) + 2; i < o && i < (int)sizeof full; i++)
        if (full[i] == '.') full[i] = '/';
    int v = bgr_find_var(mm->m, full);
    if (v < 0)
        mdl_fail(mm, at, where, "'%s': %s (%s) has no signal and no unknown '%s' (unknowns are "
                 "named as bgsim --list-unknowns shows them)", path, leaf->dotpath, leaf->type->name,
                 rest);
    return v;
}

int mdl_read_initial(mdl_model *mm)
{
    const mdl_y_node *ini = mdl_y_get(mm->root, "initial");
    if (!ini) return BG_OK;
    if (ini->kind != MDL_Y_MAPPING) return mdl_fail(mm, ini, "initial", "expected a mapping path: value");
    double *y0 = bgr_y0(mm->m);
    for (int i = 0; i < mdl_y_count(ini); i++) {
        const mdl_y_node *k = mdl_y_key(ini, i);
        int v = var_of_path(mm, k->text, k, "initial");
        if (v < 0) return BG_ERR_ARGUMENT;
        double x;
        int r = mdl_eval_number(mm, &mm->top.scope, mdl_y_value(ini, i), NULL, k->text, &x);
        if (r != BG_OK) return r;
        y0[v] = x;
    }
    return BG_OK;
}

/* ---- outputs ---- */

static int hash_names(mdl_model *mm);

typedef struct names_ctx {
    mdl_model *mm;
    const mdl_y_node *at;
    const char *where;
    int failed;
} names_ctx;

static void add_name(void *user, const char *name)
{
    names_ctx *c = user;
    mdl_model *mm = c->mm;
    if (c->failed) return;
    for (int i = 0; i < mm->nonames; i++)
        if (!strcmp(mm->onames[i].name, name)) return;
    if (strstr(name, "[*]")) {
        c->failed = mdl_fail(mm, c->at, c->where, "'%s': an output's indices are numbers", name);
        return;
    }
    mdl_oname o = {NULL, -1, 0, 0};
    if (!strcmp(name, "t")) {
        o.is_t = 1;
    } else {
        mdl_var *p = strchr(name, '.') ? NULL : mdl_scope_find(&mm->top.scope, name, 0);
        if (p) {
            if (mdl_var_eval(mm, p, c->where) != BG_OK || p->len) {
                c->failed = p->len ? mdl_fail(mm, c->at, c->where, "'%s' is a vector", name)
                                   : BG_ERR_ARGUMENT;
                return;
            }
            o.value = p->value;
        } else if ((o.var = var_of_path(mm, name, c->at, c->where)) < 0) {
            c->failed = BG_ERR_ARGUMENT;
            return;
        }
    }
    if (mm->nonames == mm->caponames) {
        int nc = mm->caponames ? 2 * mm->caponames : 16;
        mdl_oname *q = realloc(mm->onames, (size_t)nc * sizeof *q);
        if (!q) {
            c->failed = BG_ERR_MEMORY;
            return;
        }
        mm->onames = q;
        mm->caponames = nc;
    }
    o.name = strdup(name);
    if (!o.name) {
        c->failed = BG_ERR_MEMORY;
        return;
    }
    mm->onames[mm->nonames++] = o;
}

int mdl_read_outputs(mdl_model *mm)
{
    const mdl_y_node *outs = mdl_y_get(mm->root, "outputs");
    if (!outs) return BG_OK;
    if (outs->kind != MDL_Y_MAPPING)
        return mdl_fail(mm, outs, "outputs", "expected a mapping column: path or expression");
    int n = mdl_y_count(outs);
    mm->outs = calloc((size_t)(n ? n : 1), sizeof *mm->outs);
    if (!mm->outs) return BG_ERR_MEMORY;
    for (int i = 0; i < n; i++) {
        const mdl_y_node *k = mdl_y_key(outs, i), *v = mdl_y_value(outs, i);
        char where[256];
        snprintf(where, sizeof where, "outputs.%s", k->text);
        if (!strcmp(k->text, "t") || strpbrk(k->text, ",\"\n"))
            return mdl_fail(mm, k, where, "'%s' cannot name a column", k->text);
        if (v->kind != MDL_Y_SCALAR) return mdl_fail(mm, v, where, "expected a path or an expression");
        mdl_expr_error e = {0};
        mdl_expr *x = mdl_expr_parse(v->text, &e);
        if (!x) return mdl_fail(mm, v, where, "%s (at column %d of '%s')", e.message, e.column + 1, v->text);
        mm->outs[i] = (mdl_output){strdup(k->text), x, v};
        mm->nouts = i + 1;
        if (!mm->outs[i].name) return BG_ERR_MEMORY;
        names_ctx c = {mm, v, where, 0};
        mdl_expr_names(x, add_name, &c);
        if (c.failed) return c.failed;
    }
    return hash_names(mm);
}

typedef struct out_ctx {
    const mdl_model *mm;
    double t;
    const double *y;
} out_ctx;

/* FNV-1a: the outputs' names are looked up at every row, by hash rather than one by one */
static unsigned name_hash(const char *s)
{
    unsigned h = 2166136261u;
    for (; *s; s++)
        h = (h ^ (unsigned char)*s) * 16777619u;
    return h;
}

/* the hash of the names read (a power of two, at least twice their number) */
static int hash_names(mdl_model *mm)
{
    int size = 16;
    while (size < 2 * mm->nonames)
        size *= 2;
    mm->ohash = calloc((size_t)size, sizeof *mm->ohash);
    if (!mm->ohash) return BG_ERR_MEMORY;
    mm->nohash = size;
    for (int i = 0; i < mm->nonames; i++) {
        unsigned k = name_hash(mm->onames[i].name) & (unsigned)(size - 1);
        while (mm->ohash[k])
            k = (k + 1) & (unsigned)(size - 1);
        mm->ohash[k] = i + 1;
    }
    return BG_OK;
}

static int out_lookup(void *user, const char *name, double *value, char *msg, size_t msz)
{
    out_ctx *c = user;
    const mdl_model *mm = c->mm;
    if (mm->nohash > 0)
        for (unsigned k = name_hash(name) & (unsigned)(mm->nohash - 1); mm->ohash[k];
             k = (k + 1) & (unsigned)(mm->nohash - 1)) {
            const mdl_oname *o = &mm->onames[mm->ohash[k] - 1];
            if (strcmp(o->name, name)) continue;
            *value = o->is_t ? c->t : o->var >= 0 ? c->y[o->var] : o->value;
            return 0;
        }
    snprintf(msg, msz, "unknown name '%s'", name);
    return -1;
}

int mdl_outputs(const mdl_model *mm, double t, const double *y, double *out, bg_error *err)
{
    if (!mm || !y || (!out && mm->nouts)) return BG_ERR_ARGUMENT;
    out_ctx c = {mm, t, y};
    for (int i = 0; i < mm->nouts; i++) {
        mdl_expr_error e = {0};
        if (mdl_expr_eval(mm->outs[i].x, out_lookup, &c, &out[i], &e) != 0)
            return bg_error_raise(err, BG_ERR_ARGUMENT, "mdl_outputs", "output %s at t = %g: %s",
                                  mm->outs[i].name, t, e.message);
    }
    return BG_OK;
}

/* ---- solver settings ---- */

int mdl_read_solver(mdl_model *mm)
{
    mdl_solver_settings *s = &mm->solver;
    *s = (mdl_solver_settings){10, 0, 1e-6, 1e-6, 1, 5, 0, 0, 0, 0};
    mm->start = MDL_START_GIVEN;
    const mdl_y_node *st = mdl_y_get(mm->root, "start");
    if (st) {
        if (st->kind == MDL_Y_SCALAR && !strcmp(st->text, "static"))
            mm->start = MDL_START_STATIC;
        else if (!(st->kind == MDL_Y_SCALAR && !strcmp(st->text, "given")))
            return mdl_fail(mm, st, "start", "expected given or static");
    }
    const mdl_y_node *sv = mdl_y_get(mm->root, "solver");
    static const char *const keys[] = {"t_end", "output_step", "rtol", "atol", "nominal_scales",
                                       "max_order", "stability_guard", "newton_dgmax",
                                       "newton_jac_age", "newton_index2_scale_h"};
    if (sv && sv->kind != MDL_Y_MAPPING) return mdl_fail(mm, sv, "solver", "expected a mapping key: value");
    int r = mdl_check_keys(mm, sv, "solver", keys, 10);
    if (r != BG_OK) return r;
    double v[10] = {s->t_end, -1, s->rtol, s->atol, 1, 5, 0, 0, 0, 0};
    for (int i = 0; i < 10; i++) {
        const mdl_y_node *n = mdl_y_get(sv, keys[i]);
        if (!n) continue;
        char w[64];
        snprintf(w, sizeof w, "solver.%s", keys[i]);
        if (i == 4 || i == 6 || i == 9) {
            const char *t = n->kind == MDL_Y_SCALAR ? n->text : "";
            if (!strcmp(t, "true")) v[i] = 1;
            else if (!strcmp(t, "false")) v[i] = 0;
            else return mdl_fail(mm, n, w, "expected true or false, got '%s'", t);
            continue;
        }
        if ((r = mdl_eval_number(mm, &mm->top.scope, n, NULL, w, &v[i])) != BG_OK) return r;
    }
    static const char *const what[] = {"t_end > 0", "output_step > 0", "0 < rtol < 1",
                                       "atol > 0", "", "max_order 1 .. 5", "", "newton_dgmax >= 0",
                                       "newton_jac_age >= 0 (a whole number)", ""};
    int bad = -1;
    if (!(v[0] > 0 && v[0] < 1e12)) bad = 0;
    else if (v[1] != -1 && !(v[1] > 0 && v[1] <= v[0])) bad = 1;
    else if (!(v[2] > 0 && v[2] < 1)) bad = 2;
    else if (!(v[3] > 0 && isfinite(v[3]))) bad = 3;
    else if (!(v[5] >= 1 && v[5] <= 5 && v[5] == floor(v[5]))) bad = 5;
    else if (!(v[7] >= 0 && isfinite(v[7]))) bad = 7;
    else if (!(v[8] >= 0 && v[8] == floor(v[8]) && v[8] < 1e9)) bad = 8;
    if (bad >= 0) {
        const mdl_y_node *n = mdl_y_get(sv, keys[bad]);
        return mdl_fail(mm, n ? n : sv, "solver", "%s: %g is out of range (expected %s%s)", keys[bad],
                        v[bad], what[bad], bad == 1 ? " and <= t_end" : "");
    }
    s->t_end = v[0];
    s->output_step = v[1] > 0 ? v[1] : v[0] / 1000;
    s->rtol = v[2];
    s->atol = v[3];
    s->nominal_scales = (int)v[4];
    s->max_order = (int)v[5];
    s->stability_guard = (int)v[6];
    s->newton_dgmax = v[7];
    s->newton_jac_age = (int)v[8];
    s->newton_index2_scale_h = (int)v[9];
    return BG_OK;
}
