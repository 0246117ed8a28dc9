/* Position invariants of the bond-graph model (bgr_model.h, "Position invariants"): their
 * declaration by the elements, the pattern of their gradient, and their evaluation as the
 * solver's position constraints (a dae_cons_fn). Rows are numbered in element order, as the
 * equations are; the gradient's entries are scattered through slots fixed at compilation, as
 * the Jacobian's are. */
#include <stdlib.h>
#include <string.h>

#include "bgr_model_impl.h"

static int grow(void **arr, int *cap, int n, size_t sz)
{
    if (n < *cap) return 1;
    int nc = *cap ? 2 * *cap : 8;
    void *p = realloc(*arr, (size_t)nc * sz);
    if (!p) return 0;
    *arr = p;
    *cap = nc;
    return 1;
}

int bgr_declare_invariants(bgr_element *el, bgr_model *m, int ninv, const char *const *labels)
{
    int st = bgri_check_declare(el, m, "bgr_declare_invariants");
    if (st) return st;
    if (ninv < 0 || el->ninv > 0 || !el->cls->invariant)
        return bgri_fail(m, BG_ERR_ARGUMENT, "bgr_compile",
                         "element %s/%s (%s) declares %d invariants%s", m->comp[el->comp].path,
                         el->name, el->cls->type, ninv,
                         ninv < 0       ? ""
                         : el->ninv > 0 ? " a second time"
                                        : " but its class has no invariant() function");
    char *path = bgri_elem_path(m, el);
    if (!path) return bgri_fail(m, BG_ERR_MEMORY, "bgr_compile", "out of memory");
    el->inv0 = m->ninv;
    for (int k = 0; k < ninv; k++) {
        if (!grow((void **)&m->iname, &m->capinv, m->ninv, sizeof *m->iname)) {
            free(path);
            return bgri_fail(m, BG_ERR_MEMORY, "bgr_compile", "out of memory");
        }
        char buf[32];
        snprintf(buf, sizeof buf, "inv%d", k);
        const char *lab = labels && labels[k] ? labels[k] : buf;
        size_t size = strlen(path) + strlen(lab) + 2;
        char *name = malloc(size);
        if (name) snprintf(name, size, "%s/%s", path, lab);
        if (!name) {
            free(path);
            return bgri_fail(m, BG_ERR_MEMORY, "bgr_compile", "out of memory");
        }
        m->iname[m->ninv++] = name;
        el->ninv++;
    }
    free(path);
    return BG_OK;
}

int bgr_declare_invariant_dep(bgr_element *el, bgr_model *m, int k, int var)
{
    int st = bgri_check_declare(el, m, "bgr_declare_invariant_dep");
    if (st) return st;
    if (k < 0 || k >= el->ninv || var < 0 || var >= m->n)
        return bgri_fail(m, BG_ERR_ARGUMENT, "bgr_compile",
                         "element %s/%s declares a dependency of invariant %d (of %d) on variable "
                         "%d (of %d): out of range",
                         m->comp[el->comp].path, el->name, k, el->ninv, var, m->n);
    if (!grow((void **)&m->idep, &m->capidep, m->nidep, sizeof *m->idep))
        return bgri_fail(m, BG_ERR_MEMORY, "bgr_compile", "out of memory");
    m->idep[m->nidep].eq = el->inv0 + k;
    m->idep[m->nidep].var = var;
    m->idep[m->nidep].wrt_yp = 0;
    m->nidep++;
    el->nidep++;
    return BG_OK;
}

int bgri_invariants_finish(bgr_model *m)
{
    if (m->ninv == 0) return BG_OK;
    for (int e = 0; e < m->nel; e++) {
        const bgr_element *el = m->el[e];
        for (int k = 0; k < el->ninv; k++) {
            int any = 0;
            for (int d = el->idep0; d < el->idep0 + el->nidep; d++)
                any |= m->idep[d].eq == el->inv0 + k;
            if (!any)
                return bgri_fail(m, BG_ERR_PATTERN, "bgr_compile",
                                 "invariant %s depends on no unknown", m->iname[el->inv0 + k]);
        }
    }
    sp_builder *b = sp_builder_create(m->ninv, m->n, m->nidep);
    int *key = malloc(((size_t)m->nidep + 1) * sizeof *key), *slot = NULL;
    m->islot = malloc(((size_t)m->nidep + 1) * sizeof *m->islot);
    m->ivals = calloc((size_t)m->nidep + 1, sizeof *m->ivals);
    int ok = b && key && m->islot && m->ivals;
    for (int k = 0; ok && k < m->nidep; k++)
        ok = (key[k] = sp_builder_add(b, m->idep[k].eq, m->idep[k].var, 0.0)) >= 0;
    if (ok) {
        slot = malloc(((size_t)sp_builder_count(b) + 1) * sizeof *slot);
        ok = slot && (m->G = sp_builder_finish(b, slot));
    }
    for (int k = 0; ok && k < m->nidep; k++)
        m->islot[k] = slot[key[k]];
    sp_builder_free(&b);
    free(key);
    free(slot);
    return ok ? BG_OK : bgri_fail(m, BG_ERR_MEMORY, "bgr_compile", "out of memory");
}

void bgri_invariants_free(bgr_model *m)
{
    for (int k = 0; k < m->ninv; k++)
        free(m->iname[k]);
    free(m->iname);
    free(m->idep);
    sp_csc_free(&m->G);
    free(m->islot);
    free(m->ivals);
}

int bgr_ninvariants(const bgr_model *m)
{
    return m && m->compiled > 0 ? m->ninv : 0;
}

const char *bgr_invariant_name(const bgr_model *m, int k)
{
    return m && m->compiled > 0 && k >= 0 && k < m->ninv ? m->iname[k] : NULL;
}

const sp_csc *bgr_invariant_pattern(const bgr_model *m)
{
    return m && m->compiled > 0 && m->ninv > 0 ? m->G : NULL;
}

int bgr_invariants(void *model, double t, const double *y, double *g, sp_csc *G)
{
    bgr_model *m = model;
    if (!m) return BG_ERR_ARGUMENT;
    if (m->compiled <= 0) return bgri_need_compiled(m, "bgr_invariants");
    if (!y || !g) return bgri_fail(m, BG_ERR_ARGUMENT, "bgr_invariants", "y and g must be given");
    if (G && (!m->G || G->nrow != m->ninv || G->ncol != m->n || G->nnz != m->G->nnz))
        return bgri_fail(m, BG_ERR_ARGUMENT, "bgr_invariants",
                         "G must have the invariants' pattern (%d x %d with %d entries)", m->ninv,
                         m->n, m->G ? m->G->nnz : 0);
    for (int e = 0; e < m->nel; e++) {
        const bgr_element *el = m->el[e];
        if (el->ninv == 0) continue;
        int r = el->cls->invariant(el, t, y, g + el->inv0, G ? m->ivals + el->idep0 : NULL);
        if (r != 0) return r;
    }
    if (G) {
        sp_csc_zero(G);
        for (int k = 0; k < m->nidep; k++)
            G->val[m->islot[k]] += m->ivals[k];
    }
    return BG_OK;
}
