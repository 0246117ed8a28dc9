/* The compiled bond-graph model's evaluation (the residual and Jacobian callbacks, the regimes,
 * the dae_problem, the breakpoints), statistics, listings and the Jacobian check (see
 * bgr_model.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bg_fdjac.h"
#include "bgr_model_impl.h"

/* ---- evaluation ---- */

int bgr_residual(void *model, double t, const double *y, const double *yp, double *F)
{
    bgr_model *m = model;
    if (!m) return BG_ERR_ARGUMENT;
    if (m->compiled <= 0) return bgri_need_compiled(m, "bgr_residual");
    if (!y || !yp || !F)
        return bgri_fail(m, BG_ERR_ARGUMENT, "bgr_residual", "y, yp and F must be given");
    for (int e = 0; e < m->nel; e++) {
        const bgr_element *el = m->el[e];
        int r = el->cls->residual(el, t, y, yp, F + el->eq0);
        if (r != 0) return r;
    }
    return 0;
}

int bgr_jacobian(void *model, double t, const double *y, const double *yp, sp_csc *Jy, sp_csc *Jyp)
{
    bgr_model *m = model;
    if (!m) return BG_ERR_ARGUMENT;
    if (m->compiled <= 0) return bgri_need_compiled(m, "bgr_jacobian");
    if (!y || !yp || !Jy || !Jyp)
        return bgri_fail(m, BG_ERR_ARGUMENT, "bgr_jacobian", "y, yp, Jy and Jyp must be given");
    if (Jy->nrow != m->n || Jy->ncol != m->n || Jy->nnz != m->Jy->nnz || Jyp->nrow != m->n ||
        Jyp->ncol != m->n || Jyp->nnz != m->Jyp->nnz)
        return bgri_fail(
            m, BG_ERR_PATTERN, "bgr_jacobian",
            "Jy and Jyp must have the model's patterns (%d x %d with %d and %d entries)", m->n,
            m->n, m->Jy->nnz, m->Jyp->nnz);
    for (int e = 0; e < m->nel; e++) {
        const bgr_element *el = m->el[e];
        int r = el->cls->jacobian(el, t, y, yp, m->vals + el->dep0);
        if (r != 0) return r;
    }
    sp_csc_zero(Jy);
    sp_csc_zero(Jyp);
    for (int k = 0; k < m->ndep; k++)
        (m->dep[k].wrt_yp ? Jyp : Jy)->val[m->slot[k]] += m->vals[k];
    return 0;
}

int bgr_regimes(const bgr_model *m, const double *y, int *r)
{
    if (!m || (r && !y)) return BG_ERR_ARGUMENT;
    if (m->compiled <= 0) return BG_ERR_STATE;
    int k = 0;
    for (int e = 0; e < m->nel; e++)
        if (m->el[e]->cls->regime) {
            if (r) r[k] = m->el[e]->cls->regime(m->el[e], y);
            k++;
        }
    return k;
}

static int model_regimes(void *user, double t, const double *y, int *r)
{
    (void)t;
    int k = bgr_regimes(user, y, r);
    return k < 0 ? k : 0;
}

int bgr_dae_problem(bgr_model *m, dae_problem *p)
{
    if (!m) return BG_ERR_ARGUMENT;
    if (!p) return bgri_fail(m, BG_ERR_ARGUMENT, "bgr_dae_problem", "the problem pointer is NULL");
    if (m->compiled <= 0)
        return bgri_fail(m, BG_ERR_STATE, "bgr_dae_problem", "compile the model first");
    memset(p, 0, sizeof *p);
    p->n = m->n;
    p->res = bgr_residual;
    p->jac = bgr_jacobian;
    p->jac_y_pattern = m->Jy;
    p->jac_yp_pattern = m->Jyp;
    p->kind = m->kind;
    p->names = (const char *const *)m->vname;
    p->eq_names = (const char *const *)m->ename;
    p->nominal = m->nominal;
    p->user = m;
    if (m->ninv > 0) {
        p->ncons = m->ninv;
        p->cons = bgr_invariants;
        p->cons_pattern = m->G;
    }
    p->nregimes = bgr_regimes(m, NULL, NULL);
    if (p->nregimes > 0) p->regimes = model_regimes;
    return BG_OK;
}

static int cmp_dbl(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

int bgr_breakpoints(const bgr_model *m, double t0, double t1, double *t, int max)
{
    if (!m) return BG_ERR_ARGUMENT;
    if (max < 0 || (max > 0 && !t) || isnan(t0) || isnan(t1))
        return bgri_fail_c(m, BG_ERR_ARGUMENT, "bgr_breakpoints",
                           "needs max >= 0, room for max times and t0, t1 not NaN (max %d, t %s)",
                           max, t ? "given" : "NULL");
    int total = 0;
    for (int e = 0; e < m->nel; e++)
        if (m->el[e]->cls->breakpoints)
            total += m->el[e]->cls->breakpoints(m->el[e], t0, t1, NULL, 0);
    double *all = malloc(((size_t)total + 1) * sizeof *all);
    if (!all) return BG_ERR_MEMORY;
    int k = 0;
    for (int e = 0; e < m->nel; e++)
        if (m->el[e]->cls->breakpoints) {
            int c = m->el[e]->cls->breakpoints(m->el[e], t0, t1, all + k, total - k);
            k += c < total - k ? c : total - k;
        }
    qsort(all, (size_t)k, sizeof *all, cmp_dbl);
    int u = 0;
    for (int i = 0; i < k; i++)
        if (all[i] > t0 && all[i] <= t1 && (u == 0 || all[i] != all[u - 1])) all[u++] = all[i];
    for (int i = 0; i < u && i < max; i++)
        t[i] = all[i];
    free(all);
    return u;
}

/* ---- statistics, listing, check ---- */

int bgr_get_stats(const bgr_model *m, bgr_stats *st)
{
    if (!m || !st)
        return bgri_fail_c(m, BG_ERR_ARGUMENT, "bgr_get_stats", "the stats pointer is NULL");
    memset(st, 0, sizeof *st);
    st->elements = m->nel;
    st->bonds = m->nbond;
    st->components = m->ncomp;
    if (m->compiled <= 0) return bgri_need_compiled(m, "bgr_get_stats");
    st->equations = m->n;
    st->nnz_dy = m->Jy->nnz;
    st->nnz_dyp = m->Jyp->nnz;
    for (int v = 0; v < m->n; v++) {
        st->differential += m->kind[v] == DAE_DIFF;
        st->algebraic += m->kind[v] == DAE_ALG;
        st->index2 += m->kind[v] == DAE_ALG2;
    }
    return BG_OK;
}

int bgr_stats_print(const bgr_model *m, FILE *f)
{
    bgr_stats st;
    if (!m || !f) return bgri_fail_c(m, BG_ERR_ARGUMENT, "bgr_stats_print", "the file is NULL");
    int r = bgr_get_stats(m, &st);
    if (r != BG_OK) return r;
    fprintf(f,
            "model %s: %d components, %d elements, %d bonds\n"
            "  equations (= unknowns)                    %d\n"
            "  entries of the partial derivative matrix  %d   (dF/dy)\n"
            "  entries of the time-rate matrix           %d   (dF/dy')\n"
            "  unknowns: %d differential, %d algebraic (index 1), %d index 2\n",
            m->comp[0].path, st.components, st.elements, st.bonds, st.equations, st.nnz_dy,
            st.nnz_dyp, st.differential, st.algebraic, st.index2);
    return ferror(f) ? BG_ERR_IO : BG_OK;
}

int bgr_list_equations(const bgr_model *m, FILE *f)
{
    if (!m || !f) return bgri_fail_c(m, BG_ERR_ARGUMENT, "bgr_list_equations", "the file is NULL");
    if (m->compiled <= 0) return bgri_need_compiled(m, "bgr_list_equations");
    static const char *kname[3] = {"differential", "algebraic", "index 2"};
    fprintf(f, "# unknowns\n");
    for (int v = 0; v < m->n; v++)
        fprintf(f, "%5d  %-40s %s\n", v, m->vname[v], kname[m->kind[v]]);
    fprintf(f, "# equations\n");
    for (int e = 0; e < m->nel; e++) {
        const bgr_element *el = m->el[e];
        for (int k = 0; k < el->neq; k++) {
            int row = el->eq0 + k;
            char text[512] = "";
            if (el->cls->describe) el->cls->describe(el, m, k, text, sizeof text);
            fprintf(f, "%5d  %s  [%s]%s%s\n       depends on:", row, m->ename[row], el->cls->type,
                    text[0] ? "  " : "", text);
            for (int d = el->dep0; d < el->dep0 + el->ndep; d++)
                if (m->dep[d].eq == row)
                    fprintf(f, " %s%s", m->vname[m->dep[d].var], m->dep[d].wrt_yp ? "'" : "");
            fprintf(f, "\n");
        }
    }
    return ferror(f) ? BG_ERR_IO : BG_OK;
}

static int ck_res_y(void *u, const double *y, double *F)
{
    bgr_model *m = u;
    return bgr_residual(m, m->ck_t, y, m->ck_yp, F);
}

static int ck_res_yp(void *u, const double *yp, double *F)
{
    bgr_model *m = u;
    return bgr_residual(m, m->ck_t, m->ck_y, yp, F);
}

int bgr_check_jacobian(bgr_model *m, double t, const double *y, const double *yp, double tol,
                       char *report, size_t size)
{
    const char *w = "bgr_check_jacobian";
    if (!m) return BG_ERR_ARGUMENT;
    if (m->compiled <= 0) return bgri_need_compiled(m, w);
    if (!y || !yp || !(tol > 0) || (!report && size > 0))
        return bgri_fail(m, BG_ERR_ARGUMENT, w,
                         "needs y, yp, tol > 0 and room for the report (y %s, yp %s, tol %g)",
                         y ? "given" : "NULL", yp ? "given" : "NULL", tol);
    sp_csc *Jy = sp_csc_copy(m->Jy), *Jyp = sp_csc_copy(m->Jyp);
    if (!Jy || !Jyp) {
        sp_csc_free(&Jy);
        sp_csc_free(&Jyp);
        return BG_ERR_MEMORY;
    }
    int r = bgr_jacobian(m, t, y, yp, Jy, Jyp);
    m->ck_t = t;
    m->ck_y = y;
    m->ck_yp = yp;
    sp_jac_entry wy = {-1, -1, 0, 0, 0}, wyp = {-1, -1, 0, 0, 0};
    double ey = 0, eyp = 0;
    if (r != 0) {
        sp_csc_free(&Jy);
        sp_csc_free(&Jyp);
        return r < 0 ? r : BG_ERR_CALLBACK;
    }
    /* floor of the relative error: 1e-6, or 1e-9 of the largest entry for stiff models (finite
     * differences of residuals with 1e9-sized terms cannot resolve smaller entries) */
    double jmax = 0;
    for (int p = 0; p < Jy->nnz; p++)
        jmax = fmax(jmax, fabs(Jy->val[p]));
    for (int p = 0; p < Jyp->nnz; p++)
        jmax = fmax(jmax, fabs(Jyp->val[p]));
    double floor_ = fmax(1e-6, 1e-9 * jmax);
    int ny = sp_jac_check(Jy, ck_res_y, m, m->n, y, floor_, tol, &wy, 1, &ey);
    int nyp = ny < 0 ? 0 : sp_jac_check(Jyp, ck_res_yp, m, m->n, yp, floor_, tol, &wyp, 1, &eyp);
    sp_csc_free(&Jy);
    sp_csc_free(&Jyp);
    if (ny < 0) return ny;
    if (nyp < 0) return nyp;
    const sp_jac_entry *wst = ey >= eyp ? &wy : &wyp;
    if (report && size) {
        if (wst->row < 0)
            snprintf(report, size, "all partial derivatives match");
        else {
            const bgr_element *el = m->el[m->eq_owner[wst->row]];
            snprintf(report, size,
                     "%s: element %s/%s (%s), equation %s, d/d%s%s: analytic %.6g, finite "
                     "difference %.6g (relative error %.3g)%s",
                     ny + nyp ? "mismatch" : "all within tolerance; largest difference",
                     m->comp[el->comp].path, el->name, el->cls->type, m->ename[wst->row],
                     m->vname[wst->col], wst == &wyp ? "'" : "", wst->analytic, wst->fd, wst->err,
                     wst->analytic == 0 ? " - not declared?" : "");
        }
    }
    return ny + nyp;
}

/* ---- structure ---- */

int bgr_check_structure(const bgr_model *m, char *report, size_t size)
{
    if (!m || (size > 0 && !report)) return BG_ERR_ARGUMENT;
    if (m->compiled <= 0) return bgri_need_compiled((bgr_model *)m, "bgr_check_structure");
    enum { SHOW = 8 };
    int rows[SHOW], cols[SHOW];
    int d = dae_structure_check(m->Jy, m->Jyp, rows, cols, SHOW);
    if (d <= 0 || size == 0) return d;
    size_t o = (size_t)snprintf(report, size, "%d equation%s and as many unknowns left unmatched "
                                "(the equations do not determine the unknowns): equations ", d,
                                d == 1 ? "" : "s");
    for (int k = 0; k < SHOW && rows[k] >= 0 && o < size; k++)
        o += (size_t)snprintf(report + o, size - o, "%s%s", k ? ", " : "", m->ename[rows[k]]);
    if (d > SHOW && o < size) o += (size_t)snprintf(report + o, size - o, ", ...");
    if (o < size) o += (size_t)snprintf(report + o, size - o, "; unknowns ");
    for (int k = 0; k < SHOW && cols[k] >= 0 && o < size; k++)
        o += (size_t)snprintf(report + o, size - o, "%s%s", k ? ", " : "", m->vname[cols[k]]);
    if (d > SHOW && o < size) snprintf(report + o, size - o, ", ...");
    return d;
}
