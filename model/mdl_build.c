/* Building the bond graph from the instance tree (mdl_priv.h): each leaf's arguments read and
 * checked against its type, the elements built in the order their references need, the bonds
 * joined by path with dimension and domain checked, every port bonded once, then compiled. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mdl_priv.h"

static int build_leaf(mdl_model *mm, mdl_inode *leaf);
static int join_bonds(mdl_model *mm, int all);

static const char *kind_word(mdl_kind k)
{
    static const char *const w[] = {"a number", "a whole number", "true or false", "a list of numbers",
                                    "a word", "an element's path", "a signal's path", "points",
                                    "a list of names", "node ports"};
    return k >= 0 && k <= MDL_NODE_PORTS ? w[k] : "?";
}

static void range_words(const mdl_param_def *d, char *buf, size_t size)
{
    int lo = isfinite(d->lo), hi = isfinite(d->hi);
    if (lo && hi)
        snprintf(buf, size, "%s %g and %s %g", d->flags & MDL_LO_OPEN ? ">" : ">=", d->lo,
                 d->flags & MDL_HI_OPEN ? "<" : "<=", d->hi);
    else if (lo)
        snprintf(buf, size, "%s %g", d->flags & MDL_LO_OPEN ? ">" : ">=", d->lo);
    else if (hi)
        snprintf(buf, size, "%s %g", d->flags & MDL_HI_OPEN ? "<" : "<=", d->hi);
    else
        snprintf(buf, size, "finite");
}

static int in_range(const mdl_param_def *d, double x)
{
    if (!isfinite(x)) return 0;
    if (d->flags & MDL_FINITE) return 1;
    if (isfinite(d->lo) && (d->flags & MDL_LO_OPEN ? !(x > d->lo) : !(x >= d->lo))) return 0;
    if (isfinite(d->hi) && (d->flags & MDL_HI_OPEN ? !(x < d->hi) : !(x <= d->hi))) return 0;
    return 1;
}

static int out_of_range(mdl_model *mm, const mdl_y_node *at, const char *where,
                        const mdl_param_def *d, double x)
{
    char r[96];
    range_words(d, r, sizeof r);
    return mdl_fail(mm, at, where, "%.17g is out of range (expected %s%s%s)", x, r,
                    d->unit && strcmp(d->unit, "1") && strcmp(d->unit, "-") ? ", in " : "",
                    d->unit && strcmp(d->unit, "1") && strcmp(d->unit, "-") ? d->unit : "");
}

static int read_flag(mdl_model *mm, const mdl_y_node *n, const char *text, const char *where,
                     double *v)
{
    const char *t = text ? text : n && n->kind == MDL_Y_SCALAR ? n->text : "";
    static const char *const yes[] = {"true", "True", "TRUE", "yes", "on", "1"};
    static const char *const no[] = {"false", "False", "FALSE", "no", "off", "0"};
    for (int i = 0; i < 6; i++) {
        if (!strcmp(t, yes[i])) return *v = 1, BG_OK;
        if (!strcmp(t, no[i])) return *v = 0, BG_OK;
    }
    return mdl_fail(mm, n, where, "expected true or false, got '%s'", t);
}

/* MDL_POINTS: name: {r: [x, y, z], dim}; MDL_NODE_PORTS: name: {node: k, dim} (k into r[0]) */
static int read_points(mdl_model *mm, mdl_inode *leaf, const mdl_y_node *n, const char *where,
                       mdl_value *v, int nodes)
{
    if (!n || n->kind != MDL_Y_MAPPING)
        return mdl_fail(mm, n, where, nodes ? "expected a mapping name: {node: k, dim: 6}"
                                            : "expected a mapping name: {r: [x, y, z], dim: 6}");
    int np = mdl_y_count(n);
    v->pname = calloc((size_t)(np ? np : 1), sizeof *v->pname);
    v->pr = calloc((size_t)(np ? np : 1) * 3, sizeof *v->pr);
    v->pdim = calloc((size_t)(np ? np : 1), sizeof *v->pdim);
    if (!v->pname || !v->pr || !v->pdim) return BG_ERR_MEMORY;
    static const char *const keys[] = {"r", "dim"}, *const nkeys[] = {"node", "dim"};
    for (int i = 0; i < np; i++) {
        const mdl_y_node *k = mdl_y_key(n, i), *p = mdl_y_value(n, i);
        char w[1100];
        snprintf(w, sizeof w, "%s.%s", where, k->text);
        if (p->kind != MDL_Y_MAPPING)
            return mdl_fail(mm, p, w, nodes ? "expected {node: k, dim: 6 or 3}" : "expected {r: [x, y, z], dim: 6 or 3}");
        int r = mdl_check_keys(mm, p, w, nodes ? nkeys : keys, 2);
        if (r != BG_OK) return r;
        for (int j = 0; j < i; j++)
            if (!strcmp(v->pname[j], k->text)) return mdl_fail(mm, k, w, "a second port named '%s'", k->text);
        v->pname[i] = strdup(k->text);
        if (!v->pname[i]) return BG_ERR_MEMORY;
        v->npts = i + 1;
        double *vec = NULL, dim = 6;
        int len;
        if (nodes) {
            double node;
            if (!mdl_y_get(p, "node")) return mdl_fail(mm, p, w, "node: missing (the node's index, from 0)");
            if ((r = mdl_eval_number(mm, &leaf->scope, mdl_y_get(p, "node"), NULL, w, &node)) != BG_OK)
                return r;
            if (node != floor(node) || node < 0 || node > 1e6)
                return mdl_fail(mm, mdl_y_get(p, "node"), w, "node: expected a node's index (0, 1, ...), got %g", node);
            v->pr[3 * i] = node;
            if (mdl_y_get(p, "dim") &&
                (r = mdl_eval_number(mm, &leaf->scope, mdl_y_get(p, "dim"), NULL, w, &dim)) != BG_OK)
                return r;
            if (dim != 3 && dim != 6) return mdl_fail(mm, mdl_y_get(p, "dim"), w, "dim: expected 3 or 6, got %g", dim);
            v->pdim[i] = (int)dim;
            continue;
        }
        if (!mdl_y_get(p, "r")) return mdl_fail(mm, p, w, "r: missing (the point in the body frame)");
        if ((r = mdl_eval_vector(mm, &leaf->scope, mdl_y_get(p, "r"), NULL, w, &vec, &len)) != BG_OK)
            return r;
        if (len != 3) {
            free(vec);
            return mdl_fail(mm, mdl_y_get(p, "r"), w, "r: expected 3 numbers, got %d", len);
        }
        int bad = 0;
        for (int j = 0; j < 3; j++)
            bad |= !isfinite(vec[j]);
        memcpy(v->pr + 3 * i, vec, 3 * sizeof *vec);
        free(vec);
        if (bad) return mdl_fail(mm, mdl_y_get(p, "r"), w, "r: not finite");
        if (mdl_y_get(p, "dim") &&
            (r = mdl_eval_number(mm, &leaf->scope, mdl_y_get(p, "dim"), NULL, w, &dim)) != BG_OK)
            return r;
        if (dim != 3 && dim != 6)
            return mdl_fail(mm, mdl_y_get(p, "dim"), w, "dim: expected 3 or 6, got %g", dim);
        v->pdim[i] = (int)dim;
    }
    return BG_OK;
}

static int is_word(const char *s)
{
    if (!s || !(*s == '_' || (*s >= 'A' && *s <= 'Z') || (*s >= 'a' && *s <= 'z'))) return 0;
    for (s++; *s; s++)
        if (!(*s == '_' || (*s >= 'A' && *s <= 'Z') || (*s >= 'a' && *s <= 'z') ||
              (*s >= '0' && *s <= '9')))
            return 0;
    return 1;
}

/* one name of a list: a word, not taken before; kept as entry v->npts */
static int add_name(mdl_model *mm, const mdl_y_node *at, const char *where, mdl_value *v,
                    const char *s, size_t len)
{
    char w[128];
    snprintf(w, sizeof w, "%.*s", (int)len, s);
    if (len >= sizeof w || !is_word(w))
        return mdl_fail(mm, at, where,
                        "entry %d: expected a name ([A-Za-z_][A-Za-z0-9_]*), got '%s'", v->npts, w);
    for (int j = 0; j < v->npts; j++)
        if (!strcmp(v->pname[j], w)) return mdl_fail(mm, at, where, "'%s' is named twice", w);
    if (!(v->pname[v->npts] = strdup(w))) return BG_ERR_MEMORY;
    v->npts++;
    return BG_OK;
}

/* a list of distinct words (port names), kept in v->pname / v->npts: a sequence of the file, or
 * the default's text "[a, b]" */
static int read_names(mdl_model *mm, const mdl_y_node *n, const char *text, const mdl_y_node *at,
                      const char *where, mdl_value *v)
{
    int r = BG_OK, cap = text                             ? (int)strlen(text) / 2 + 1
                         : n && n->kind == MDL_Y_SEQUENCE ? mdl_y_count(n)
                                                          : 0;
    if (cap < 1 || (text && text[0] != '['))
        return mdl_fail(mm, at, where, "expected a list of one name or more ([a, b])");
    if (!(v->pname = calloc((size_t)cap, sizeof *v->pname))) return BG_ERR_MEMORY;
    if (text) {
        for (const char *s = text + 1; r == BG_OK && *s && *s != ']';) {
            s += strspn(s, " ,");
            size_t k = strcspn(s, " ,]");
            if (k) r = add_name(mm, at, where, v, s, k);
            s += k;
        }
    } else {
        for (int i = 0; r == BG_OK && i < cap; i++) {
            const mdl_y_node *it = mdl_y_item(n, i);
            if (it->kind != MDL_Y_SCALAR)
                return mdl_fail(mm, it, where, "entry %d: expected a name ([A-Za-z_][A-Za-z0-9_]*)",
                                i);
            r = add_name(mm, it, where, v, it->text, strlen(it->text));
        }
    }
    if (r == BG_OK && v->npts == 0)
        return mdl_fail(mm, at, where, "expected a list of one name or more ([a, b])");
    return r;
}

/* an element or signal reference: the leaf it names, built first */
static int read_ref(mdl_model *mm, mdl_inode *leaf, const mdl_y_node *n, const char *text,
                    const char *where, const mdl_param_def *d, mdl_value *v)
{
    char path[512];
    int r;
    if (text)
        snprintf(path, sizeof path, "%s", text);
    else if ((r = mdl_eval_path(mm, &leaf->scope, n, where, path, sizeof path)) != BG_OK)
        return r;
    mdl_inode *t;
    const char *rest;
    if ((r = mdl_resolve(mm, leaf->parent, path, n, where, &t, &rest)) != BG_OK) return r;
    if (!t || !t->type)
        return mdl_fail(mm, n, where, "'%s' names a subsystem, not %s", path, kind_word(d->kind));
    if (t == leaf) return mdl_fail(mm, n, where, "'%s' is the element itself", path);
    if ((r = build_leaf(mm, t)) != BG_OK) return r;
    if (d->kind == MDL_ELEMENT) {
        if (rest) return mdl_fail(mm, n, where, "'%s': an element's path ends at the element", path);
        v->elem = mdl_instance_main(&t->inst);
        return BG_OK;
    }
    const mdl_isignal *s = rest ? mdl_instance_find_signal(&t->inst, rest) : NULL;
    if (!s) {
        const char *cand[32];
        int nc = 0;
        for (int i = 0; i < t->inst.nsigs && nc < 32; i++)
            cand[nc++] = t->inst.sigs[i].name;
        const char *near = rest ? mdl_nearest(rest, cand, nc) : "";
        char list[256] = "";
        size_t o = 0;
        for (int i = 0; i < nc && o < sizeof list; i++)
            o += (size_t)snprintf(list + o, sizeof list - o, "%s%s", i ? ", " : "", cand[i]);
        return mdl_fail(mm, n, where, "'%s': %s (%s) offers no signal '%s'%s%s%s; its signals: %s",
                        path, t->dotpath, t->type->name, rest ? rest : "", *near ? " (did you mean '" : "",
                        near, *near ? "'?)" : "", nc ? list : "none");
    }
    v->sig = s->r;
    return BG_OK;
}

/* one parameter of a leaf: given (or replaced, or its default), evaluated and checked */
static int read_param(mdl_model *mm, mdl_inode *leaf, const mdl_param_def *d, mdl_value *v)
{
    char where[512], setpath[512];
    snprintf(where, sizeof where, "%s.%s", leaf->dotpath, d->name);
    snprintf(setpath, sizeof setpath, "%s.%s", leaf->dotpath, d->name);
    const mdl_y_node *n = mdl_y_get(leaf->entry, d->name);
    const char *text = NULL;
    for (int i = 0; i < mm->nsets; i++)
        if (!strcmp(mm->sets[i].path, setpath)) text = mm->sets[i].value, mm->set_used[i] = 1;
    const mdl_y_node *at = n ? n : leaf->key;
    if (!n && !text) {
        if (!d->dflt) {
            if (d->flags & MDL_OPTIONAL) return BG_OK;
            return mdl_fail(mm, leaf->key, leaf->dotpath, "%s (%s) needs '%s' (%s%s%s: %s)",
                            leaf->type->name, leaf->dotpath, d->name, kind_word(d->kind),
                            d->unit && strcmp(d->unit, "-") && strcmp(d->unit, "1") ? ", in " : "",
                            d->unit && strcmp(d->unit, "-") && strcmp(d->unit, "1") ? d->unit : "",
                            d->meaning);
        }
        text = d->dflt;
    }
    v->has = 1;
    int r = BG_OK;
    switch (d->kind) {
    case MDL_NUMBER:
    case MDL_INTEGER:
        if ((r = mdl_eval_number(mm, &leaf->scope, n, text, where, &v->num)) != BG_OK) return r;
        if (d->kind == MDL_INTEGER && (v->num != floor(v->num) || fabs(v->num) > 1e9))
            return mdl_fail(mm, at, where, "expected a whole number, got %.17g", v->num);
        if (!in_range(d, v->num)) return out_of_range(mm, at, where, d, v->num);
        return BG_OK;
    case MDL_FLAG: return read_flag(mm, n, text, where, &v->num);
    case MDL_VECTOR:
        if ((r = mdl_eval_vector(mm, &leaf->scope, n, text, where, &v->vec, &v->len)) != BG_OK) return r;
        if (d->len > 0 && v->len != d->len)
            return mdl_fail(mm, at, where, "expected %d numbers, got %d", d->len, v->len);
        if (v->len == 0) return mdl_fail(mm, at, where, "expected one number or more, got none");
        for (int i = 0; i < v->len; i++)
            if (!in_range(d, v->vec[i])) {
                char w2[560];
                snprintf(w2, sizeof w2, "%s[%d]", where, i);
                return out_of_range(mm, at, w2, d, v->vec[i]);
            }
        return BG_OK;
    case MDL_CHOICE: {
        const char *t = text ? text : n->kind == MDL_Y_SCALAR ? n->text : "";
        const char *c = d->choices;
        size_t len = strlen(t);
        while (c && *c) {
            size_t k = strcspn(c, "|");
            if (k == len && !strncmp(c, t, len)) {
                v->word = strdup(t);
                return v->word ? BG_OK : BG_ERR_MEMORY;
            }
            c += k + (c[k] ? 1 : 0);
        }
        return mdl_fail(mm, at, where, "expected one of %s, got '%s'", d->choices, t);
    }
    case MDL_ELEMENT:
    case MDL_SIGNAL: return read_ref(mm, leaf, n, text, where, d, v);
    case MDL_POINTS:
        if (text) return mdl_fail(mm, at, where, "points cannot be replaced with --set");
        return read_points(mm, leaf, n, where, v, 0);
    case MDL_NODE_PORTS:
        if (text) return mdl_fail(mm, at, where, "node ports cannot be replaced with --set");
        return read_points(mm, leaf, n, where, v, 1);
    case MDL_NAMES:
        if (text && text != d->dflt) return mdl_fail(mm, at, where, "names cannot be replaced with --set");
        return read_names(mm, n, text, at, where, v);
    }
    return r;
}

static int add_leaf(mdl_model *mm, mdl_inode *leaf)
{
    if (mm->nleaves == mm->capleaves) {
        int nc = mm->capleaves ? 2 * mm->capleaves : 32;
        mdl_inode **p = realloc(mm->leaves, (size_t)nc * sizeof *p);
        if (!p) return BG_ERR_MEMORY;
        mm->leaves = p;
        mm->capleaves = nc;
    }
    mm->leaves[mm->nleaves++] = leaf;
    return BG_OK;
}

static int build_leaf(mdl_model *mm, mdl_inode *leaf)
{
    if (leaf->state == 2) return BG_OK;
    if (leaf->state == 1)
        return mdl_fail(mm, leaf->key, leaf->dotpath, "the elements' references (signals, bodies) "
                        "go round in a cycle through %s", leaf->dotpath);
    leaf->state = 1;
    const mdl_type *t = leaf->type;
    mdl_instance *in = &leaf->inst;
    in->type = t;
    in->main = -1;
    in->path = strdup(leaf->path);
    in->args.type = t;
    in->args.path = in->path;
    in->args.v = calloc((size_t)(t->nparams ? t->nparams : 1), sizeof *in->args.v);
    if (!in->path || !in->args.v) return BG_ERR_MEMORY;
    for (int i = 0; i < t->nparams; i++) {
        in->args.v[i].def = &t->params[i];
        int r = read_param(mm, leaf, &t->params[i], &in->args.v[i]);
        if (r != BG_OK) return r;
    }
    bg_error e = {0}; /* no handler: build() only records its message */
    bg_error_clear(&e);
    int r = t->build(mm->m, leaf->comp, leaf->name, &in->args, in, &e);
    if (r != BG_OK)
        return mdl_fail(mm, leaf->key, leaf->dotpath, "%s", e.message[0] ? e.message : bg_status_message(r));
    leaf->state = 2;
    r = add_leaf(mm, leaf);
    return r == BG_OK ? join_bonds(mm, 0) : r;
}

static int build_tree(mdl_model *mm, mdl_inode *n)
{
    for (int i = 0; i < n->nkids; i++) {
        int r = n->kids[i]->type ? build_leaf(mm, n->kids[i]) : build_tree(mm, n->kids[i]);
        if (r != BG_OK) return r;
    }
    return BG_OK;
}

/* ---- bonds ---- */

static int port_of(mdl_model *mm, mdl_inode *scope, const char *path, const mdl_y_node *at,
                   mdl_inode **leaf, int *port)
{
    const char *rest;
    int r = mdl_resolve(mm, scope, path, at, "bonds", leaf, &rest);
    if (r != BG_OK) return r;
    if (!*leaf || !(*leaf)->type)
        return mdl_fail(mm, at, "bonds", "'%s' names a subsystem, not a port: add the port's name "
                        "(its outer ports: its definition's 'ports')", path);
    if (!rest) return mdl_fail(mm, at, "bonds", "'%s' names an element, not a port: add the port's name", path);
    *port = mdl_instance_find_port(&(*leaf)->inst, rest);
    if (*port < 0) {
        const mdl_instance *in = &(*leaf)->inst;
        const char *cand[64];
        int nc = 0;
        for (int i = 0; i < in->nports && nc < 64; i++)
            cand[nc++] = in->ports[i].name;
        const char *near = mdl_nearest(rest, cand, nc);
        char list[256] = "";
        size_t o = 0;
        for (int i = 0; i < nc && o < sizeof list; i++)
            o += (size_t)snprintf(list + o, sizeof list - o, "%s%s", i ? ", " : "", cand[i]);
        return mdl_fail(mm, at, "bonds", "'%s': %s (%s) has no port '%s'%s%s%s; its ports: %s", path,
                        (*leaf)->dotpath, (*leaf)->type->name, rest, *near ? " (did you mean '" : "",
                        near, *near ? "'?)" : "", nc ? list : "none");
    }
    return BG_OK;
}

static const char *domain_word(mdl_domain d)
{
    static const char *const w[] = {"generic", "mechanical 6D", "mechanical 3D", "hydraulic",
                                    "rotational"};
    return d >= 0 && d <= MDL_ROTATIONAL ? w[d] : "?";
}

static int bonded_at(const mdl_model *mm, const mdl_inode *leaf, int port)
{
    for (int i = 0; i < mm->nbonds; i++)
        for (int s = 0; s < 2; s++)
            if (mm->bonds[i].leaf[s] == leaf && mm->bonds[i].port[s] == port) return i;
    return -1;
}

static int one_bond(mdl_model *mm, mdl_inode *scope, const mdl_y_node *b, const char *from,
                    const char *to, const mdl_y_node *name_node)
{
    mdl_inode *la, *lb;
    int pa, pb, r;
    if ((r = port_of(mm, scope, from, b, &la, &pa)) != BG_OK) return r;
    if ((r = port_of(mm, scope, to, b, &lb, &pb)) != BG_OK) return r;
    const mdl_iport *A = mdl_instance_port_at(&la->inst, pa), *B = mdl_instance_port_at(&lb->inst, pb);
    if (A->dim != B->dim)
        return mdl_fail(mm, b, "bonds", "%s -> %s joins a %dD port (%s) and a %dD port (%s)", from, to,
                        A->dim, domain_word(A->domain), B->dim, domain_word(B->domain));
    if (A->domain != MDL_GENERIC && B->domain != MDL_GENERIC && A->domain != B->domain)
        return mdl_fail(mm, b, "bonds", "%s -> %s joins a %s port and a %s port", from, to,
                        domain_word(A->domain), domain_word(B->domain));
    for (int s = 0; s < 2; s++) {
        mdl_inode *l = s ? lb : la;
        int i = bonded_at(mm, l, s ? pb : pa);
        if (i >= 0) {
            char pos[256];
            return mdl_fail(mm, b, "bonds", "port %s.%s is bonded already (at %s)", l->dotpath,
                            (s ? B : A)->name, mdl_y_where(mm->bonds[i].at, pos, sizeof pos));
        }
    }
    if (la == lb && pa == pb) return mdl_fail(mm, b, "bonds", "%s -> %s joins a port to itself", from, to);
    char nm[512];
    if (name_node && name_node->kind == MDL_Y_SCALAR)
        snprintf(nm, sizeof nm, "%s", name_node->text);
    else
        snprintf(nm, sizeof nm, "%s->%s", from, to);
    for (char *c = nm; *c; c++)
        if (*c == '/') *c = '.';
    bgr_comp comp = scope == &mm->top ? 0 : scope->comp;
    if (bgr_bond(mm->m, comp, nm, A->dim, A->p, B->p, NULL, NULL) < 0)
        return mdl_fail(mm, b, "bonds", "%s", bgr_model_error(mm->m)->message);
    if (mm->nbonds == mm->capbonds) {
        int nc = mm->capbonds ? 2 * mm->capbonds : 32;
        mdl_bond *p = realloc(mm->bonds, (size_t)nc * sizeof *p);
        if (!p) return BG_ERR_MEMORY;
        mm->bonds = p;
        mm->capbonds = nc;
    }
    mm->bonds[mm->nbonds++] = (mdl_bond){{la, lb}, {pa, pb}, b};
    return BG_OK;
}

/* A bond read: recorded with the elements its paths name, joined by join_bonds in the file's
 * order, each as soon as its elements and the bonds before it are in the graph. So the bonds'
 * unknowns are numbered in the file's order, with the inner bonds of an element that has them
 * (a beam chain) where that element is built, as a program creating the parts and bonds one by
 * one numbers them: the same model written in the same order gets the same numbering, and with
 * it the same Jacobian structure, ordering and rounding. */
static int pend_bond(mdl_model *mm, mdl_inode *scope, const mdl_y_node *b, const char *from,
                     const char *to, const mdl_y_node *name_node)
{
    if (mm->npend == mm->cappend) {
        int nc = mm->cappend ? 2 * mm->cappend : 32;
        mdl_pending_bond *p = realloc(mm->pend, (size_t)nc * sizeof *p);
        if (!p) return BG_ERR_MEMORY;
        mm->pend = p;
        mm->cappend = nc;
    }
    mdl_pending_bond *q = &mm->pend[mm->npend];
    *q = (mdl_pending_bond){scope, {NULL, NULL}, b, name_node, strdup(from), strdup(to), 0};
    if (!q->from || !q->to) {
        free(q->from), free(q->to);
        return BG_ERR_MEMORY;
    }
    mm->npend++;
    for (int s = 0; s < 2; s++) {
        const char *rest;
        mdl_inode *l = NULL;
        int r = mdl_resolve(mm, scope, s ? to : from, b, "bonds", &l, &rest);
        if (r != BG_OK) return r;
        q->leaf[s] = l && l->type && rest ? l : NULL;
    }
    return BG_OK;
}

/* the bonds read, in the file's order, up to the first whose elements are not both built; at
 * the end (all) every bond left, including those whose paths name no element's port: one_bond
 * says why */
static int join_bonds(mdl_model *mm, int all)
{
    for (int i = 0; i < mm->npend; i++) {
        mdl_pending_bond *q = &mm->pend[i];
        if (q->done) continue;
        if (!all && !(q->leaf[0] && q->leaf[1] && q->leaf[0]->state == 2 && q->leaf[1]->state == 2))
            break; /* the bonds after it wait for it: the file's order is kept */
        q->done = 1;
        int r = one_bond(mm, q->scope, q->at, q->from, q->to, q->name);
        if (r != BG_OK) return r;
    }
    return BG_OK;
}

/* "a.p -> b.q" or {from: a.p, to: b.q, name: ..., for: {k: [i, j]}} */
static int bond_entry(mdl_model *mm, mdl_inode *scope, const mdl_y_node *b)
{
    static const char *const keys[] = {"from", "to", "name", "for"};
    if (b->kind == MDL_Y_SCALAR) {
        const char *arrow = strstr(b->text, "->");
        if (!arrow) return mdl_fail(mm, b, "bonds", "expected 'from.port -> to.port', got '%s'", b->text);
        char from[512], to[512];
        snprintf(from, sizeof from, "%.*s", (int)(arrow - b->text), b->text);
        snprintf(to, sizeof to, "%s", arrow + 2);
        mdl_y_node fn = *b, tn = *b;
        fn.text = from, tn.text = to;
        char pf[512], pt[512];
        int r = mdl_eval_path(mm, &scope->scope, &fn, "bonds", pf, sizeof pf);
        if (r == BG_OK) r = mdl_eval_path(mm, &scope->scope, &tn, "bonds", pt, sizeof pt);
        return r == BG_OK ? pend_bond(mm, scope, b, pf, pt, NULL) : r;
    }
    if (b->kind != MDL_Y_MAPPING)
        return mdl_fail(mm, b, "bonds", "expected 'from.port -> to.port' or {from: ..., to: ...}");
    int r = mdl_check_keys(mm, b, "bonds", keys, 4);
    if (r != BG_OK) return r;
    if (!mdl_y_get(b, "from") || !mdl_y_get(b, "to"))
        return mdl_fail(mm, b, "bonds", "a bond needs from and to");
    const mdl_y_node *forn = mdl_y_get(b, "for");
    const char *var = NULL;
    long first = 0, last = 0;
    if (forn && (r = mdl_read_for(mm, &scope->scope, forn, "bonds", &var, &first, &last)) != BG_OK)
        return r;
    for (long k = first; k <= last; k++) {
        mdl_scope loop = {&scope->scope, NULL, 0, 0};
        if (var) {
            if ((r = mdl_scope_add(&loop, var, NULL, NULL, NULL)) != BG_OK) return r;
            loop.vars[0].state = 2;
            loop.vars[0].value = (double)k;
        }
        char pf[512], pt[512];
        r = mdl_eval_path(mm, &loop, mdl_y_get(b, "from"), "bonds.from", pf, sizeof pf);
        if (r == BG_OK) r = mdl_eval_path(mm, &loop, mdl_y_get(b, "to"), "bonds.to", pt, sizeof pt);
        mdl_scope_clear(&loop);
        if (r == BG_OK) r = pend_bond(mm, scope, b, pf, pt, var ? NULL : mdl_y_get(b, "name"));
        if (r != BG_OK) return r;
    }
    return BG_OK;
}

static int bonds_of(mdl_model *mm, mdl_inode *n)
{
    const mdl_y_node *list = n == &mm->top ? mdl_y_get(mm->root, "bonds") : mdl_y_get(n->sub->def, "bonds");
    if (list && list->kind != MDL_Y_SEQUENCE)
        return mdl_fail(mm, list, "bonds", "expected a list of bonds");
    for (int i = 0; i < mdl_y_count(list); i++) {
        int r = bond_entry(mm, n, mdl_y_item(list, i));
        if (r != BG_OK) return r;
    }
    for (int i = 0; i < n->nkids; i++)
        if (!n->kids[i]->type) {
            int r = bonds_of(mm, n->kids[i]);
            if (r != BG_OK) return r;
        }
    return BG_OK;
}

int mdl_build_all(mdl_model *mm)
{
    int r = bonds_of(mm, &mm->top);
    if (r == BG_OK) r = build_tree(mm, &mm->top);
    if (r == BG_OK) r = join_bonds(mm, 1);
    if (r != BG_OK) return r;
    for (int i = 0; i < mm->nsets; i++)
        if (!mm->set_used[i])
            return mdl_fail(mm, NULL, "--set", "'%s' names no parameter of the model or of a "
                            "component (PARAM or PATH.PARAM)", mm->sets[i].path);
    for (int i = 0; i < mm->nleaves; i++) {
        mdl_inode *l = mm->leaves[i];
        for (int p = 0; p < l->inst.nports; p++)
            if (bonded_at(mm, l, p) < 0)
                return mdl_fail(mm, l->key, l->dotpath, "port '%s' (%s) is not bonded: every port "
                                "of the model takes one bond (a free end: mech.free)",
                                l->inst.ports[p].name, domain_word(l->inst.ports[p].domain));
    }
    if (bgr_compile(mm->m) != BG_OK)
        return mdl_fail(mm, NULL, NULL, "the bond graph does not compile: %s",
                        bgr_model_error(mm->m)->message);
    char report[BG_MESSAGE_SIZE - 128];
    int d = bgr_check_structure(mm->m, report, sizeof report);
    if (d < 0) return d == BG_ERR_MEMORY ? d : mdl_fail(mm, NULL, NULL, "%s", bgr_model_error(mm->m)->message);
    if (d > 0) return mdl_fail(mm, NULL, NULL, "the model is structurally singular: %s", report);
    return BG_OK;
}
