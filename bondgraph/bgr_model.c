/* The bond-graph model: components, elements, ports and bonds; compilation into numbered,
 * named unknowns and equations with Jacobian patterns and slots (see bgr_model.h). The residual
 * and Jacobian callbacks, statistics, listings and the Jacobian check are in bgr_eval.c, the
 * compilation and the accessors of the compiled model in bgr_compile.c. */
#include "bgr_model.h"

#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include "bgr_model_impl.h"

/* The helpers of bgr_model_impl.h. */
int bgri_fail(bgr_model *m, int status, const char *where, const char *fmt, ...)
{
    if (!m) return status;
    va_list ap;
    va_start(ap, fmt);
    bg_error_vraise(&m->err, status, where, fmt, ap);
    va_end(ap);
    return status;
}

int bgri_fail_c(const bgr_model *m, int status, const char *where, const char *fmt, ...)
{
    if (!m) return status;
    va_list ap;
    va_start(ap, fmt);
    bg_error_vraise((bg_error *)&m->err, status, where, fmt, ap);
    va_end(ap);
    return status;
}

int bgri_need_compiled(const bgr_model *m, const char *where)
{
    if (m->compiled > 0) return BG_OK;
    return bgri_fail_c(m, BG_ERR_STATE, where,
                       m->compiled < 0 ? "the compilation of model %s failed: build it again"
                                       : "model %s is not compiled: call bgr_compile first",
                       m->comp[0].path);
}

static char *dupstr(const char *s)
{
    size_t n = strlen(s) + 1;
    char *d = malloc(n);
    if (d) memcpy(d, s, n);
    return d;
}

char *bgri_join(const char *a, const char *b)
{
    size_t na = strlen(a), nb = strlen(b);
    char *d = malloc(na + nb + 2);
    if (!d) return NULL;
    memcpy(d, a, na);
    d[na] = na ? '/' : '\0';
    memcpy(d + na + (na ? 1 : 0), b, nb + 1);
    return d;
}

/* Grows *arr (elements of size sz) to hold n+1 items. */
static int reserve(void **arr, int *cap, int n, size_t sz)
{
    if (n < *cap) return 1;
    int nc = *cap ? 2 * *cap : 16;
    void *p = realloc(*arr, (size_t)nc * sz);
    if (!p) return 0;
    *arr = p;
    *cap = nc;
    return 1;
}

static int valid_name(const char *s)
{
    return s && *s && !strchr(s, '/');
}

bgr_model *bgr_model_create(const char *name)
{
    bgr_model *m = calloc(1, sizeof *m);
    if (!m) return NULL;
    if (!reserve((void **)&m->comp, &m->capcomp, 0, sizeof *m->comp) ||
        !(m->comp[0].name = dupstr(name && *name ? name : "model")) ||
        !(m->comp[0].path = dupstr(m->comp[0].name))) {
        bgr_model_free(&m);
        return NULL;
    }
    m->comp[0].parent = -1;
    m->ncomp = 1;
    return m;
}

static void free_strs(char **v, int n)
{
    if (!v) return;
    for (int i = 0; i < n; i++)
        free(v[i]);
    free(v);
}

void bgr_model_free(bgr_model **mp)
{
    if (!mp || !*mp) return;
    bgr_model *m = *mp;
    for (int c = 0; c < m->ncomp; c++) {
        free(m->comp[c].name);
        free(m->comp[c].path);
    }
    free(m->comp);
    for (int e = 0; e < m->nexp; e++)
        free(m->exp[e].name);
    free(m->exp);
    for (int i = 0; i < m->nel; i++) {
        bgr_element *el = m->el[i];
        if (el->cls && el->cls->destroy) el->cls->destroy(el->params);
        free(el->bond);
        free(el->sign);
        free(el->dim);
        free(el->name);
        free_strs(m->el_state_names[i], el->nstates);
        free_strs(m->el_alg_names[i], el->nalg);
        free(el);
    }
    free(m->el);
    free(m->el_state_names);
    free(m->el_alg_names);
    for (int b = 0; b < m->nbond; b++) {
        free(m->bond[b].name);
        free_strs(m->bond[b].elab, m->bond[b].d);
        free_strs(m->bond[b].flab, m->bond[b].d);
    }
    free(m->bond);
    free_strs(m->vname, m->n);
    free_strs(m->ename, m->n);
    free(m->eq_owner);
    free(m->kind);
    free(m->declared_i2);
    free(m->nominal);
    free(m->y0);
    free(m->yp0);
    free(m->dep);
    free(m->fgroup);
    free(m->fkind);
    sp_csc_free(&m->Jy);
    sp_csc_free(&m->Jyp);
    free(m->slot);
    free(m->vals);
    bgri_invariants_free(m);
    free(m);
    *mp = NULL;
}

const bg_error *bgr_model_error(const bgr_model *m)
{
    return m ? &m->err : NULL;
}
bg_error *bgr_model_error_mut(bgr_model *m)
{
    return m ? &m->err : NULL;
}

/* BG_OK while the model may be changed: BG_ERR_ARGUMENT for a NULL model, BG_ERR_STATE once it
 * is compiled (or its compilation failed). */
static int check_building(bgr_model *m, const char *where)
{
    if (!m) return BG_ERR_ARGUMENT;
    if (m->compiled > 0)
        return bgri_fail(m, BG_ERR_STATE, where, "the model is compiled: no more changes");
    if (m->compiled < 0)
        return bgri_fail(m, BG_ERR_STATE, where,
                         "an earlier compilation failed: no more changes (build the model again)");
    return BG_OK;
}

bgr_comp bgr_component(bgr_model *m, bgr_comp parent, const char *name)
{
    const char *w = "bgr_component";
    int st = check_building(m, w);
    if (st) return st;
    if (parent < 0 || parent >= m->ncomp)
        return bgri_fail(m, BG_ERR_ARGUMENT, w, "parent component %d does not exist", parent);
    if (!valid_name(name))
        return bgri_fail(m, BG_ERR_ARGUMENT, w,
                         "component name '%s' in %s must be non-empty, no '/'",
                         name ? name : "(null)", m->comp[parent].path);
    for (int c = 1; c < m->ncomp; c++)
        if (m->comp[c].parent == parent && !strcmp(m->comp[c].name, name))
            return bgri_fail(m, BG_ERR_ARGUMENT, w, "component %s/%s exists already",
                             m->comp[parent].path, name);
    if (!reserve((void **)&m->comp, &m->capcomp, m->ncomp, sizeof *m->comp))
        return bgri_fail(m, BG_ERR_MEMORY, w, "out of memory");
    comp_rec *r = &m->comp[m->ncomp];
    r->name = dupstr(name);
    r->path = bgri_join(m->comp[parent].path, name);
    r->parent = parent;
    if (!r->name || !r->path) {
        free(r->name);
        free(r->path);
        return bgri_fail(m, BG_ERR_MEMORY, w, "out of memory");
    }
    return m->ncomp++;
}

const char *bgr_component_path(const bgr_model *m, bgr_comp c)
{
    return m && c >= 0 && c < m->ncomp ? m->comp[c].path : NULL;
}

static char **copy_names(const char *const *src, int n, const char *prefix)
{
    char **v = calloc((size_t)n + 1, sizeof *v);
    if (!v) return NULL;
    for (int i = 0; i < n; i++) {
        char buf[32];
        snprintf(buf, sizeof buf, "%s%d", prefix, i);
        v[i] = dupstr(src && src[i] ? src[i] : buf);
        if (!v[i]) {
            free_strs(v, n);
            return NULL;
        }
    }
    return v;
}

int bgr_element_add(bgr_model *m, bgr_comp c, const char *name, const bgr_element_class *cls,
                    void *params, int nports, const int *dims, int nstates,
                    const char *const *state_names, int nalg, const char *const *alg_names)
{
    const char *w = "bgr_element_add";
    int st = check_building(m, w);
    if (!st && (c < 0 || c >= m->ncomp))
        st = bgri_fail(m, BG_ERR_ARGUMENT, w, "component %d does not exist", c);
    if (!st && !valid_name(name))
        st = bgri_fail(m, BG_ERR_ARGUMENT, w, "element name '%s' in %s must be non-empty, no '/'",
                       name ? name : "(null)", m->comp[c].path);
    if (!st && (!cls || !cls->declare || !cls->residual || !cls->jacobian))
        st = bgri_fail(m, BG_ERR_ARGUMENT, w, "element %s/%s: incomplete element class",
                       m->comp[c].path, name);
    if (!st && (nports < 0 || nstates < 0 || nalg < 0))
        st = bgri_fail(m, BG_ERR_ARGUMENT, w, "element %s/%s: negative count", m->comp[c].path,
                       name);
    for (int k = 0; !st && dims && k < nports; k++)
        if (dims[k] < 0)
            st = bgri_fail(m, BG_ERR_ARGUMENT, w, "element %s/%s: port %d has dimension %d",
                           m->comp[c].path, name, k, dims[k]);
    for (int i = 0; !st && i < m->nel; i++)
        if (m->el[i]->comp == c && !strcmp(m->el[i]->name, name))
            st = bgri_fail(m, BG_ERR_ARGUMENT, w, "element %s/%s exists already", m->comp[c].path,
                           name);
    if (!st) { /* three arrays grown together; a failed realloc keeps the old block */
        int cap = m->capel;
        if (!reserve((void **)&m->el, &cap, m->nel, sizeof *m->el)) {
            st = bgri_fail(m, BG_ERR_MEMORY, w, "out of memory");
        } else if (cap != m->capel || !m->el_state_names) {
            char ***sn = realloc(m->el_state_names, (size_t)cap * sizeof *sn);
            if (sn) m->el_state_names = sn;
            char ***an = sn ? realloc(m->el_alg_names, (size_t)cap * sizeof *an) : NULL;
            if (an) m->el_alg_names = an;
            if (!sn || !an)
                st = bgri_fail(m, BG_ERR_MEMORY, w, "out of memory");
            else
                m->capel = cap;
        }
    }
    bgr_element *el = st ? NULL : calloc(1, sizeof *el);
    if (!st && !el) st = bgri_fail(m, BG_ERR_MEMORY, w, "out of memory");
    if (st) {
        if (cls && cls->destroy) cls->destroy(params);
        return st;
    }
    el->cls = cls;
    el->params = params;
    el->id = m->nel;
    el->comp = c;
    el->nports = nports;
    el->nstates = nstates;
    el->nalg = nalg;
    el->name = dupstr(name);
    el->bond = malloc(((size_t)nports + 1) * sizeof *el->bond);
    el->sign = calloc((size_t)nports + 1, sizeof *el->sign);
    el->dim = calloc((size_t)nports + 1, sizeof *el->dim);
    char **sn = copy_names(state_names, nstates, "x");
    char **an = copy_names(alg_names, nalg, "z");
    if (!el->name || !el->bond || !el->sign || !el->dim || !sn || !an) {
        if (cls->destroy) cls->destroy(params);
        free(el->name);
        free(el->bond);
        free(el->sign);
        free(el->dim);
        free_strs(sn, nstates);
        free_strs(an, nalg);
        free(el);
        return bgri_fail(m, BG_ERR_MEMORY, w, "out of memory");
    }
    for (int k = 0; k < nports; k++) {
        el->bond[k] = -1;
        el->dim[k] = dims ? dims[k] : 0;
    }
    m->el[m->nel] = el;
    m->el_state_names[m->nel] = sn;
    m->el_alg_names[m->nel] = an;
    return m->nel++;
}

bgr_port bgr_port_of(const bgr_model *m, int elem, int port)
{
    bgr_port p = {-1, -1};
    if (m && elem >= 0 && elem < m->nel && port >= 0 && port < m->el[elem]->nports) {
        p.elem = elem;
        p.port = port;
    }
    return p;
}

bgr_element *bgr_element_get(bgr_model *m, int elem)
{
    return m && elem >= 0 && elem < m->nel ? m->el[elem] : NULL;
}

char *bgri_elem_path(const bgr_model *m, const bgr_element *el)
{
    return bgri_join(m->comp[el->comp].path, el->name);
}

int bgr_export(bgr_model *m, bgr_comp c, const char *name, bgr_port inner)
{
    const char *w = "bgr_export";
    int st = check_building(m, w);
    if (st) return st;
    if (c < 0 || c >= m->ncomp || !valid_name(name))
        return bgri_fail(m, BG_ERR_ARGUMENT, w, "invalid component %d or port name '%s'", c,
                         name ? name : "(null)");
    if (inner.elem < 0 || inner.elem >= m->nel || inner.port < 0 ||
        inner.port >= m->el[inner.elem]->nports)
        return bgri_fail(m, BG_ERR_ARGUMENT, w, "port %s/%s: the inner port is invalid",
                         m->comp[c].path, name);
    for (int e = 0; e < m->nexp; e++)
        if (m->exp[e].comp == c && !strcmp(m->exp[e].name, name))
            return bgri_fail(m, BG_ERR_ARGUMENT, w, "port %s/%s exists already", m->comp[c].path,
                             name);
    if (!reserve((void **)&m->exp, &m->capexp, m->nexp, sizeof *m->exp))
        return bgri_fail(m, BG_ERR_MEMORY, w, "out of memory");
    m->exp[m->nexp].comp = c;
    m->exp[m->nexp].port = inner;
    if (!(m->exp[m->nexp].name = dupstr(name)))
        return bgri_fail(m, BG_ERR_MEMORY, w, "out of memory");
    m->nexp++;
    return BG_OK;
}

bgr_port bgr_comp_port(const bgr_model *m, bgr_comp c, const char *name)
{
    bgr_port none = {-1, -1};
    for (int e = 0; m && e < m->nexp; e++)
        if (m->exp[e].comp == c && name && !strcmp(m->exp[e].name, name)) return m->exp[e].port;
    return none;
}

const char *bgri_port_desc(const bgr_model *m, bgr_port p, char *buf, size_t size)
{
    if (p.elem < 0 || p.elem >= m->nel) {
        snprintf(buf, size, "(invalid port)");
        return buf;
    }
    const bgr_element *el = m->el[p.elem];
    snprintf(buf, size, "%s/%s port %d", m->comp[el->comp].path, el->name, p.port);
    return buf;
}

int bgr_bond(bgr_model *m, bgr_comp c, const char *name, int d, bgr_port a, bgr_port b,
             const char *const *effort_labels, const char *const *flow_labels)
{
    const char *w = "bgr_bond";
    char ba[256], bb[256];
    int st = check_building(m, w);
    if (st) return st;
    if (c < 0 || c >= m->ncomp || !valid_name(name))
        return bgri_fail(m, BG_ERR_ARGUMENT, w, "invalid component %d or bond name '%s'", c,
                         name ? name : "(null)");
    if (d < 1)
        return bgri_fail(m, BG_ERR_ARGUMENT, w, "bond %s/%s: dimension %d, expected >= 1",
                         m->comp[c].path, name, d);
    bgr_port ends[2] = {a, b};
    for (int k = 0; k < 2; k++) {
        bgr_port p = ends[k];
        if (p.elem < 0 || p.elem >= m->nel || p.port < 0 || p.port >= m->el[p.elem]->nports)
            return bgri_fail(m, BG_ERR_ARGUMENT, w, "bond %s/%s: its %s port is invalid",
                             m->comp[c].path, name, k ? "end" : "start");
        bgr_element *el = m->el[p.elem];
        if (el->bond[p.port] >= 0)
            return bgri_fail(m, BG_ERR_ARGUMENT, w, "bond %s/%s: %s is already joined by bond %s",
                             m->comp[c].path, name, bgri_port_desc(m, p, ba, sizeof ba),
                             m->bond[el->bond[p.port]].name);
        if (el->dim[p.port] && el->dim[p.port] != d)
            return bgri_fail(
                m, BG_ERR_ARGUMENT, w, "bond %s/%s has dimension %d, but %s needs dimension %d",
                m->comp[c].path, name, d, bgri_port_desc(m, p, ba, sizeof ba), el->dim[p.port]);
    }
    if (a.elem == b.elem && a.port == b.port)
        return bgri_fail(m, BG_ERR_ARGUMENT, w, "bond %s/%s joins %s to itself", m->comp[c].path,
                         name, bgri_port_desc(m, a, ba, sizeof ba));
    for (int i = 0; i < m->nbond; i++)
        if (m->bond[i].comp == c && !strcmp(m->bond[i].name, name))
            return bgri_fail(m, BG_ERR_ARGUMENT, w, "bond %s/%s exists already (%s -> %s)",
                             m->comp[c].path, name, bgri_port_desc(m, a, ba, sizeof ba),
                             bgri_port_desc(m, b, bb, sizeof bb));
    if (!reserve((void **)&m->bond, &m->capbond, m->nbond, sizeof *m->bond))
        return bgri_fail(m, BG_ERR_MEMORY, w, "out of memory");
    bond_rec *r = &m->bond[m->nbond];
    memset(r, 0, sizeof *r);
    r->comp = c;
    r->d = d;
    r->a = a;
    r->b = b;
    r->name = dupstr(name);
    r->elab = copy_names(effort_labels, d, d == 1 ? "e" : "e");
    r->flab = copy_names(flow_labels, d, d == 1 ? "f" : "f");
    if (!r->name || !r->elab || !r->flab) {
        free(r->name);
        free_strs(r->elab, d);
        free_strs(r->flab, d);
        return bgri_fail(m, BG_ERR_MEMORY, w, "out of memory");
    }
    if (d == 1) { /* plain "e" and "f" when not labelled */
        if (!effort_labels) r->elab[0][1] = '\0';
        if (!flow_labels) r->flab[0][1] = '\0';
    }
    m->el[a.elem]->bond[a.port] = m->nbond;
    m->el[a.elem]->sign[a.port] = BGR_OUT;
    m->el[b.elem]->bond[b.port] = m->nbond;
    m->el[b.elem]->sign[b.port] = BGR_IN;
    return m->nbond++;
}

/* ---- used by the element classes ---- */

/* The bond at port k of el, or NULL (no model, no element, port out of range or unconnected,
 * unknowns not numbered yet). */
static const bond_rec *port_bond(const bgr_element *el, const bgr_model *m, int k)
{
    if (!el || !m || m->n == 0 || m->compiled < 0 || k < 0 || k >= el->nports || el->bond[k] < 0 ||
        el->bond[k] >= m->nbond)
        return NULL;
    return &m->bond[el->bond[k]];
}

int bgr_ev(const bgr_element *el, const bgr_model *m, int k, int i)
{
    const bond_rec *b = port_bond(el, m, k);
    return b && i >= 0 && i < b->d ? b->var0 + i : -1;
}

int bgr_fv(const bgr_element *el, const bgr_model *m, int k, int i)
{
    const bond_rec *b = port_bond(el, m, k);
    return b && i >= 0 && i < b->d ? b->var0 + b->d + i : -1;
}

int bgr_ref_var(const bgr_model *m, bgr_ref r)
{
    if (!m || m->n == 0 || m->compiled < 0) return -1; /* not numbered yet, or failed */
    switch (r.type) {
    case BGR_EFFORT:
    case BGR_FLOW:
        if (r.id < 0 || r.id >= m->nbond || r.i < 0 || r.i >= m->bond[r.id].d) return -1;
        return m->bond[r.id].var0 + (r.type == BGR_FLOW ? m->bond[r.id].d : 0) + r.i;
    case BGR_STATE:
        if (r.id < 0 || r.id >= m->nel || r.i < 0 || r.i >= m->el[r.id]->nstates) return -1;
        return m->el[r.id]->state0 + r.i;
    case BGR_OWN:
        if (r.id < 0 || r.id >= m->nel || r.i < 0 || r.i >= m->el[r.id]->nalg) return -1;
        return m->el[r.id]->alg0 + r.i;
    }
    return -1;
}

int bgr_port_dim(const bgr_element *el, const bgr_model *m, int k)
{
    if (!el || !m || k < 0 || k >= el->nports) return BG_ERR_ARGUMENT;
    return el->bond[k] >= 0 && el->bond[k] < m->nbond ? m->bond[el->bond[k]].d : el->dim[k];
}

/* The checks of the bgr_declare_* functions: a model in compilation and one of its elements. */
int bgri_check_declare(const bgr_element *el, bgr_model *m, const char *what)
{
    if (!m) return BG_ERR_ARGUMENT;
    if (!el || el->id < 0 || el->id >= m->nel || m->el[el->id] != el)
        return bgri_fail(m, BG_ERR_ARGUMENT, what, "the element is not one of model %s",
                         m->comp[0].path);
    if (!m->compiling)
        return bgri_fail(m, BG_ERR_STATE, what,
                         "element %s/%s: %s is called only from the element's declare() during "
                         "bgr_compile",
                         m->comp[el->comp].path, el->name, what);
    return BG_OK;
}

int bgr_declare_equations(bgr_element *el, bgr_model *m, int neq, const char *const *labels)
{
    int st = bgri_check_declare(el, m, "bgr_declare_equations");
    if (st) return st;
    if (neq < 0)
        return bgri_fail(m, BG_ERR_ARGUMENT, "bgr_compile", "element %s/%s declares %d equations",
                         m->comp[el->comp].path, el->name, neq);
    char *path = bgri_elem_path(m, el);
    if (!path) return bgri_fail(m, BG_ERR_MEMORY, "bgr_compile", "out of memory");
    el->neq = neq;
    el->eq0 = m->neq_declared;
    for (int k = 0; k < neq; k++) {
        int row = m->neq_declared + k;
        if (row >= m->n) {
            bgri_fail(m, BG_ERR_PATTERN, "bgr_compile",
                      "element %s declares more equations than there are unknowns", path);
            free(path);
            return BG_ERR_PATTERN;
        }
        char buf[32];
        snprintf(buf, sizeof buf, "eq%d", k);
        m->ename[row] = bgri_join(path, labels && labels[k] ? labels[k] : buf);
        m->eq_owner[row] = el->id;
        if (!m->ename[row]) {
            free(path);
            return bgri_fail(m, BG_ERR_MEMORY, "bgr_compile", "out of memory");
        }
    }
    m->neq_declared += neq;
    free(path);
    return BG_OK;
}

int bgr_declare_dep(bgr_element *el, bgr_model *m, int k, int var, int wrt_yp)
{
    int st = bgri_check_declare(el, m, "bgr_declare_dep");
    if (st) return st;
    if (k < 0 || k >= el->neq || var < 0 || var >= m->n)
        return bgri_fail(
            m, BG_ERR_ARGUMENT, "bgr_compile",
            "element %s/%s declares a dependency of equation %d on variable %d: out of "
            "range",
            m->comp[el->comp].path, el->name, k, var);
    if (!reserve((void **)&m->dep, &m->capdep, m->ndep, sizeof *m->dep))
        return bgri_fail(m, BG_ERR_MEMORY, "bgr_compile", "out of memory");
    m->dep[m->ndep].eq = el->eq0 + k;
    m->dep[m->ndep].var = var;
    m->dep[m->ndep].wrt_yp = wrt_yp != 0;
    m->ndep++;
    el->ndep++;
    return BG_OK;
}

int bgr_declare_index2(bgr_element *el, bgr_model *m, int var)
{
    int st = bgri_check_declare(el, m, "bgr_declare_index2");
    if (st) return st;
    if (var < el->alg0 || var >= el->alg0 + el->nalg)
        return bgri_fail(m, BG_ERR_ARGUMENT, "bgr_compile",
                         "element %s/%s: only its own algebraic unknowns can be declared index 2",
                         m->comp[el->comp].path, el->name);
    m->declared_i2[var] = 1;
    return BG_OK;
}

int bgr_declare_nominal(bgr_element *el, bgr_model *m, int var, double nominal)
{
    int st = bgri_check_declare(el, m, "bgr_declare_nominal");
    if (st) return st;
    if (var < 0 || var >= m->n)
        return bgri_fail(m, BG_ERR_ARGUMENT, "bgr_compile",
                         "element %s/%s (%s) declares the nominal magnitude of variable %d: out of "
                         "range (0 .. %d)",
                         m->comp[el->comp].path, el->name, el->cls->type, var, m->n - 1);
    if (!(nominal > 0) || !isfinite(nominal))
        return bgri_fail(
            m, BG_ERR_ARGUMENT, "bgr_compile",
            "element %s/%s (%s) declares the nominal magnitude of %s as %g: it must be "
            "finite and > 0",
            m->comp[el->comp].path, el->name, el->cls->type, m->vname[var], nominal);
    /* several declarations of one unknown (a bond's effort seen from both ends): the largest */
    if (nominal > m->nominal[var]) m->nominal[var] = nominal;
    return BG_OK;
}
