/* The compilation of a bond-graph model (bgr_model.h): its unknowns and equations numbered and
 * named, the Jacobian patterns and slots the elements declared, and the accessors of the compiled
 * model. The model's building (components, elements, ports, bonds) is in bgr_model.c. */
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include "bgr_model.h"
#include "bgr_model_impl.h"

/* ---- compilation ---- */

static int alloc_compiled(bgr_model *m)
{
    size_t n = (size_t)m->n + 1;
    m->vname = calloc(n, sizeof *m->vname);
    m->ename = calloc(n, sizeof *m->ename);
    m->eq_owner = malloc(n * sizeof *m->eq_owner);
    m->kind = malloc(n * sizeof *m->kind);
    m->declared_i2 = calloc(n, sizeof *m->declared_i2);
    m->y0 = calloc(n, sizeof *m->y0);
    m->yp0 = calloc(n, sizeof *m->yp0);
    m->nominal = calloc(n, sizeof *m->nominal);
    return m->vname && m->ename && m->eq_owner && m->kind && m->declared_i2 && m->y0 && m->yp0 &&
           m->nominal;
}

static int name_variables(bgr_model *m)
{
    for (int b = 0; b < m->nbond; b++) {
        bond_rec *r = &m->bond[b];
        char *bp = bgri_join(m->comp[r->comp].path, r->name);
        if (!bp) return 0;
        for (int i = 0; i < r->d; i++) {
            m->vname[r->var0 + i] = bgri_join(bp, r->elab[i]);
            m->vname[r->var0 + r->d + i] = bgri_join(bp, r->flab[i]);
            if (!m->vname[r->var0 + i] || !m->vname[r->var0 + r->d + i]) {
                free(bp);
                return 0;
            }
        }
        free(bp);
    }
    for (int e = 0; e < m->nel; e++) {
        bgr_element *el = m->el[e];
        char *ep = bgri_elem_path(m, el);
        if (!ep) return 0;
        for (int i = 0; i < el->nstates; i++)
            if (!(m->vname[el->state0 + i] = bgri_join(ep, m->el_state_names[e][i]))) {
                free(ep);
                return 0;
            }
        for (int i = 0; i < el->nalg; i++)
            if (!(m->vname[el->alg0 + i] = bgri_join(ep, m->el_alg_names[e][i]))) {
                free(ep);
                return 0;
            }
        free(ep);
    }
    return 1;
}

static int compile(bgr_model *m);

int bgr_compile(bgr_model *m)
{
    if (!m) return BG_ERR_ARGUMENT;
    if (m->compiled > 0)
        return bgri_fail(m, BG_ERR_STATE, "bgr_compile", "the model is compiled already");
    if (m->compiled < 0)
        return bgri_fail(m, BG_ERR_STATE, "bgr_compile",
                         "an earlier compilation failed; build the model again");
    int st = compile(m);
    m->compiling = 0;
    m->compiled = st == BG_OK ? 1 : -1;
    return st;
}

static int compile(bgr_model *m)
{
    const char *w = "bgr_compile";
    char buf[256];
    /* every port joined, with the dimension it needs */
    for (int e = 0; e < m->nel; e++)
        for (int k = 0; k < m->el[e]->nports; k++)
            if (m->el[e]->bond[k] < 0)
                return bgri_fail(m, BG_ERR_PATTERN, w, "%s is not joined by any bond",
                                 bgri_port_desc(m, bgr_port_of(m, e, k), buf, sizeof buf));
    /* number the unknowns: bonds (e then f), then states, then own algebraic unknowns */
    int n = 0;
    for (int b = 0; b < m->nbond; b++) {
        m->bond[b].var0 = n;
        n += 2 * m->bond[b].d;
    }
    for (int e = 0; e < m->nel; e++) {
        m->el[e]->state0 = n;
        n += m->el[e]->nstates;
    }
    for (int e = 0; e < m->nel; e++) {
        m->el[e]->alg0 = n;
        n += m->el[e]->nalg;
    }
    if (n == 0)
        return bgri_fail(m, BG_ERR_ARGUMENT, w, "model %s has no unknowns", m->comp[0].path);
    m->n = n;
    if (!alloc_compiled(m) || !name_variables(m))
        return bgri_fail(m, BG_ERR_MEMORY, w, "out of memory");
    /* equations and dependencies */
    for (int e = 0; e < m->nel; e++) {
        bgr_element *el = m->el[e];
        int expect = el->nstates + el->nalg;
        for (int k = 0; k < el->nports; k++)
            expect += bgr_port_dim(el, m, k);
        el->dep0 = m->ndep;
        el->ndep = 0;
        el->idep0 = m->nidep;
        m->compiling = 1;
        int st = el->cls->declare(el, m);
        m->compiling = 0;
        if (st != BG_OK) return st;
        if (el->neq != expect)
            return bgri_fail(m, BG_ERR_PATTERN, w,
                             "element %s/%s (%s) declares %d equations; it needs one per port "
                             "component and one per own unknown: %d",
                             m->comp[el->comp].path, el->name, el->cls->type, el->neq, expect);
    }
    if (m->neq_declared != n)
        return bgri_fail(m, BG_ERR_PATTERN, w, "%d equations for %d unknowns", m->neq_declared, n);
    int sti = bgri_invariants_finish(m);
    if (sti != BG_OK) return sti;
    for (int v = 0; v < n; v++) /* undeclared nominal magnitudes: 1 (SI units) */
        if (m->nominal[v] == 0) m->nominal[v] = 1.0;
    /* patterns and slots */
    sp_builder *by = sp_builder_create(n, n, m->ndep), *byp = sp_builder_create(n, n, n);
    int *ky = malloc(((size_t)m->ndep + 1) * sizeof *ky);
    int *sy = NULL, *syp = NULL;
    m->slot = malloc(((size_t)m->ndep + 1) * sizeof *m->slot);
    m->vals = calloc((size_t)m->ndep + 1, sizeof *m->vals);
    int ok = by && byp && ky && m->slot && m->vals;
    for (int k = 0; ok && k < m->ndep; k++)
        ky[k] = sp_builder_add(m->dep[k].wrt_yp ? byp : by, m->dep[k].eq, m->dep[k].var, 0.0);
    if (ok) {
        sy = malloc(((size_t)sp_builder_count(by) + 1) * sizeof *sy);
        syp = malloc(((size_t)sp_builder_count(byp) + 1) * sizeof *syp);
        ok = sy && syp && (m->Jy = sp_builder_finish(by, sy)) &&
             (m->Jyp = sp_builder_finish(byp, syp));
    }
    for (int k = 0; ok && k < m->ndep; k++)
        m->slot[k] = (m->dep[k].wrt_yp ? syp : sy)[ky[k]];
    sp_builder_free(&by);
    sp_builder_free(&byp);
    free(ky);
    free(sy);
    free(syp);
    if (!ok) return bgri_fail(m, BG_ERR_MEMORY, w, "out of memory");
    /* kinds: from the structure, with the declarations on top */
    if (dae_classify(m->Jy, m->Jyp, m->kind) < 0)
        return bgri_fail(m, BG_ERR_MEMORY, w, "out of memory");
    for (int v = 0; v < n; v++)
        if (m->declared_i2[v]) {
            if (m->kind[v] == DAE_DIFF)
                return bgri_fail(
                    m, BG_ERR_PATTERN, w,
                    "%s is declared index 2, but its derivative appears in an equation",
                    m->vname[v]);
            m->kind[v] = DAE_ALG2;
        }
    /* a variable no equation depends on */
    for (int v = 0; v < n; v++)
        if (m->Jy->colptr[v + 1] == m->Jy->colptr[v] && m->Jyp->colptr[v + 1] == m->Jyp->colptr[v])
            return bgri_fail(m, BG_ERR_PATTERN, w, "no equation depends on %s", m->vname[v]);
    return BG_OK;
}

int bgr_nvars(const bgr_model *m)
{
    return m && m->compiled >= 0 ? m->n : 0;
}
int bgr_n(const bgr_model *m)
{
    return m && m->compiled > 0 ? m->n : 0;
}
const char *bgr_var_name(const bgr_model *m, int v)
{
    return m && m->compiled > 0 && v >= 0 && v < m->n ? m->vname[v] : NULL;
}
const char *bgr_eq_name(const bgr_model *m, int e)
{
    return m && m->compiled > 0 && e >= 0 && e < m->n ? m->ename[e] : NULL;
}
const int *bgr_kinds(const bgr_model *m)
{
    return m && m->compiled > 0 ? m->kind : NULL;
}
double *bgr_y0(bgr_model *m)
{
    return m && m->compiled > 0 ? m->y0 : NULL;
}
double *bgr_yp0(bgr_model *m)
{
    return m && m->compiled > 0 ? m->yp0 : NULL;
}
const double *bgr_nominals(const bgr_model *m)
{
    return m && m->compiled > 0 ? m->nominal : NULL;
}

int bgr_set_nominal(bgr_model *m, int var, double nominal)
{
    const char *w = "bgr_set_nominal";
    if (!m) return BG_ERR_ARGUMENT;
    if (m->compiled <= 0) return bgri_need_compiled(m, w);
    if (var < 0 || var >= m->n)
        return bgri_fail(m, BG_ERR_ARGUMENT, w, "variable %d out of range (0 .. %d)", var,
                         m->n - 1);
    if (!(nominal > 0) || !isfinite(nominal))
        return bgri_fail(m, BG_ERR_ARGUMENT, w,
                         "the nominal magnitude of %s is %g: it must be finite and > 0",
                         m->vname[var], nominal);
    m->nominal[var] = nominal;
    return BG_OK;
}

int bgr_find_var(const bgr_model *m, const char *path)
{
    if (!m || m->compiled <= 0 || !path) return -1;
    for (int v = 0; v < m->n; v++)
        if (!strcmp(m->vname[v], path)) return v;
    return -1;
}

int bgr_find_eq(const bgr_model *m, const char *path)
{
    if (!m || m->compiled <= 0 || !path) return -1;
    for (int e = 0; e < m->n; e++)
        if (!strcmp(m->ename[e], path)) return e;
    return -1;
}
