/* Structure analysis: the classification of the unknowns from the two Jacobian patterns, and the
 * one maximum matching of the solver (BTF's maxtrans, Duff's algorithm MC21 with a cheap
 * assignment first: Davis, Direct Methods for Sparse Linear Systems, SIAM 2006, sec. 7.2).
 *
 * Classification (dae_classify). A variable whose derivative appears is differential. The
 * algebraic equations (rows without y') are matched against the algebraic variables; the
 * variables reachable from an unmatched variable along alternating paths form the
 * under-determined part of the Dulmage-Mendelsohn decomposition (Duff, Erisman and Reid, Direct
 * Methods for Sparse Matrices, ch. 6), which does not depend on the maximum matching chosen. They
 * cannot be computed from the algebraic equations with the differential variables known: they
 * are fixed only through the time derivative of a constraint, i.e. they are index-2 unknowns
 * (constraint efforts and every algebraic variable that depends on one). The rest are index 1.
 *
 * Names of equations. Messages call an unnamed equation "equation i (the row of x)", x being the
 * unknown matched to row i in a maximum matching of the Newton matrix's pattern (daei_match on
 * it, each column's diagonal entry tried first). */
#include <btf.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "bg_dae_impl.h"

int daei_match(const sp_csc *A, const int *rowmask, const int *colmask, int *rowvar)
{
    int n = A->ncol, m = A->nrow, ret = BG_ERR_MEMORY;
    int *Ap = malloc(((size_t)n + 1) * sizeof *Ap);
    int *Ai = malloc(((size_t)A->nnz + 1) * sizeof *Ai);
    int *work = malloc((5 * (size_t)n + 1) * sizeof *work);
    if (!Ap || !Ai || !work) goto done;
    /* the columns and rows kept, each column's diagonal entry first: maxtrans's cheap
     * assignment takes the first free row of a column */
    int nz = 0;
    for (int j = 0; j < n; j++) {
        Ap[j] = nz;
        if (colmask && !colmask[j]) continue;
        int d = j < m ? sp_csc_find(A, j, j) : -1;
        if (d >= 0 && (!rowmask || rowmask[j])) Ai[nz++] = j;
        for (int p = A->colptr[j]; p < A->colptr[j + 1]; p++) {
            int i = A->rowind[p];
            if (p != d && (!rowmask || rowmask[i])) Ai[nz++] = i;
        }
    }
    Ap[n] = nz;
    double w;
    ret = btf_maxtrans(m, n, Ap, Ai, 0.0, &w, rowvar, work);
done:
    free(Ap);
    free(Ai);
    free(work);
    return ret;
}

int dae_classify(const sp_csc *Jy, const sp_csc *Jyp, int *kind)
{
    if (!Jy || !Jyp || !kind) return BG_ERR_ARGUMENT;
    if (Jy->nrow != Jy->ncol || Jyp->nrow != Jy->nrow || Jyp->ncol != Jy->ncol)
        return BG_ERR_PATTERN;
    int n = Jy->ncol, ret = BG_ERR_MEMORY;
    int *rowalg = malloc(((size_t)n + 1) * sizeof *rowalg);
    int *colalg = calloc((size_t)n + 1, sizeof *colalg);
    int *matchrow = malloc(((size_t)n + 1) * sizeof *matchrow); /* variable matched to row */
    int *matched = calloc((size_t)n + 1, sizeof *matched);
    int *queue = malloc(((size_t)n + 1) * sizeof *queue);
    if (!rowalg || !colalg || !matchrow || !matched || !queue) goto done;
    for (int i = 0; i < n; i++)
        rowalg[i] = 1;
    for (int p = 0; p < Jyp->nnz; p++)
        rowalg[Jyp->rowind[p]] = 0;
    for (int j = 0; j < n; j++) {
        kind[j] = Jyp->colptr[j + 1] > Jyp->colptr[j] ? DAE_DIFF : DAE_ALG;
        colalg[j] = kind[j] == DAE_ALG;
    }
    /* maximum matching of the algebraic rows and the algebraic variables */
    if (daei_match(Jy, rowalg, colalg, matchrow) < 0) goto done;
    for (int i = 0; i < n; i++)
        if (matchrow[i] >= 0) matched[matchrow[i]] = 1;
    /* under-determined part: breadth first from the unmatched algebraic variables */
    int head = 0, tail = 0;
    for (int j = 0; j < n; j++)
        if (kind[j] == DAE_ALG && !matched[j]) {
            kind[j] = DAE_ALG2;
            queue[tail++] = j;
        }
    while (head < tail) {
        int v = queue[head++];
        for (int p = Jy->colptr[v]; p < Jy->colptr[v + 1]; p++) {
            int i = Jy->rowind[p];
            if (!rowalg[i]) continue;
            int w = matchrow[i];
            if (w >= 0 && kind[w] == DAE_ALG) {
                kind[w] = DAE_ALG2;
                queue[tail++] = w;
            }
        }
    }
    ret = tail;
done:
    free(rowalg);
    free(colalg);
    free(matchrow);
    free(matched);
    free(queue);
    return ret;
}

/* ------------------------------------------------------------- detection ---- */

/* A pseudo-random number in [-1, 1] (a fixed sequence: detection is reproducible). */
static double rnd(unsigned long *state)
{
    *state = *state * 6364136223846793005ul + 1442695040888963407ul;
    return (double)((*state >> 11) & 0xfffffffffffffUL) / (double)0xfffffffffffffUL * 2.0 - 1.0;
}

/* Marks in mark[] (stamp) the rows whose residual at (t, yb, ypb) with x[j] += d differs from
 * Fb, trying d / 1e3 when the residual fails there. x is yb or ypb. Returns 0, or 1 if the
 * residual failed at both. */
static int probe_column(dae_solver *s, double t, double *yb, double *ypb, double *x, int j,
                        double d, const double *Fb, double *F1, int *mark, int stamp)
{
    double keep = x[j];
    for (int tries = 0; tries < 2; tries++, d *= 1e-3) {
        x[j] = keep + d;
        int r = daei_call_res(s, t, yb, ypb, F1, 1);
        x[j] = keep;
        s->st.pattern_res_evals++;
        if (r < 0) continue;
        if (r > 0) { /* recoverable: rows left NaN still show what depends on x[j] */
            int any = 0;
            for (int i = 0; i < s->n; i++)
                if (!isfinite(F1[i])) mark[i] = stamp, any = 1;
            if (!any) continue;
            return 0;
        }
        for (int i = 0; i < s->n; i++)
            if (F1[i] != Fb[i]) mark[i] = stamp;
        return 0;
    }
    return 1;
}

int daei_probe_patterns(dae_solver *s, double t, const double *y, const double *yp, int npts,
                        long *added)
{
    const char *w = "dae_init";
    int n = s->n, ret = BG_ERR_MEMORY;
    *added = 0;
    double *yb = malloc(4 * (size_t)n * sizeof *yb);
    int *mark = malloc((size_t)n * sizeof *mark);
    sp_builder *b[2] = {sp_builder_create(n, n, 4 * n), sp_builder_create(n, n, 2 * n)};
    sp_csc *P[2] = {NULL, NULL};
    if (!yb || !mark || !b[0] || !b[1]) goto done;
    double *ypb = yb + n, *Fb = yb + 2 * (size_t)n, *F1 = yb + 3 * (size_t)n;
    const sp_csc *old[2] = {s->Jy ? s->Jy : s->p.jac_y_pattern,
                            s->Jyp ? s->Jyp : s->p.jac_yp_pattern};
    for (int m = 0; m < 2; m++) /* what is known already */
        if (old[m])
            for (int j = 0; j < n; j++)
                for (int p = old[m]->colptr[j]; p < old[m]->colptr[j + 1]; p++)
                    if (sp_builder_add(b[m], old[m]->rowind[p], j, 0.0) < 0) goto done;
    for (int i = 0; i < n; i++)
        mark[i] = -1;
    unsigned long seed = 12345;
    int stamp = 0, done_pts = 0;
    double t0 = daei_clock(s);
    for (int k = 0; k < npts; k++) {
        /* the first point as given, the others moved by 1 % of the unknowns' sizes (entries
         * whose derivative vanishes at the given point, as d(y1 y2)/dy1 at y2 = 0) */
        for (int i = 0; i < n; i++) {
            double a = k ? 1e-2 * rnd(&seed) : 0.0;
            yb[i] = y[i] + a * (fabs(y[i]) + 1.0);
            ypb[i] = (yp ? yp[i] : 0.0) + a * ((yp ? fabs(yp[i]) : 0.0) + 1.0);
        }
        int r = daei_call_res(s, t, yb, ypb, Fb, 1);
        s->st.pattern_res_evals++;
        if (r != 0 || daei_first_nonfinite(Fb, n) >= 0) {
            if (k > 0) continue; /* a moved point the residual does not take: skip it */
            char m[BG_MESSAGE_SIZE];
            snprintf(m, sizeof m, "%s", s->note);
            ret = bg_error_raise(&s->err, r < 0 ? DAE_CALLBACK_FAIL : DAE_RES_FAIL, w,
                                 "finding the Jacobian patterns from the residual (none were "
                                 "given): the residual fails at the initial values: %s",
                                 m);
            goto done;
        }
        done_pts++;
        for (int m = 0; m < 2; m++) {
            double *x = m ? ypb : yb;
            for (int j = 0; j < n; j++) {
                double d = 1e-3 * (fabs(x[j]) + 1.0);
                stamp++;
                probe_column(s, t, yb, ypb, x, j, d, Fb, F1, mark, stamp);
                for (int i = 0; i < n; i++)
                    if (mark[i] == stamp && sp_builder_add(b[m], i, j, 0.0) < 0) goto done;
            }
        }
    }
    s->st.pattern_probes += done_pts;
    s->st.t_pattern += daei_clock(s) - t0;
    for (int m = 0; m < 2; m++) {
        if (!(P[m] = sp_builder_finish(b[m], NULL))) goto done;
        sp_builder_free(&b[m]);
        *added += P[m]->nnz - (old[m] ? old[m]->nnz : 0);
    }
    sp_csc_free(&s->Jy);
    sp_csc_free(&s->Jyp);
    s->Jy = P[0];
    s->Jyp = P[1];
    P[0] = P[1] = NULL;
    s->st.pattern_nnz = (long)s->Jy->nnz + s->Jyp->nnz;
    ret = BG_OK;
done:
    if (ret == BG_ERR_MEMORY)
        bg_error_raise(&s->err, ret, w, "out of memory finding the Jacobian patterns (n = %d)", n);
    free(yb);
    free(mark);
    sp_builder_free(&b[0]);
    sp_builder_free(&b[1]);
    sp_csc_free(&P[0]);
    sp_csc_free(&P[1]);
    return ret;
}

int dae_structure_check(const sp_csc *Jy, const sp_csc *Jyp, int *rows, int *cols, int max)
{
    if (!Jy || !Jyp || max < 0 || (max > 0 && (!rows || !cols))) return BG_ERR_ARGUMENT;
    if (Jy->nrow != Jy->ncol || Jyp->nrow != Jy->nrow || Jyp->ncol != Jy->ncol)
        return BG_ERR_PATTERN;
    int n = Jy->ncol, ret;
    sp_union *u = sp_union_create(Jy, Jyp);
    int *rowvar = malloc(((size_t)n + 1) * sizeof *rowvar);
    int *colrow = malloc(((size_t)n + 1) * sizeof *colrow);
    if (!u || !rowvar || !colrow) {
        ret = BG_ERR_MEMORY;
        goto done;
    }
    int matched = daei_match(u->M, NULL, NULL, rowvar);
    if (matched < 0) {
        ret = BG_ERR_MEMORY;
        goto done;
    }
    for (int j = 0; j < n; j++)
        colrow[j] = -1;
    for (int i = 0; i < n; i++)
        if (rowvar[i] >= 0) colrow[rowvar[i]] = i;
    int nr = 0, nc = 0;
    for (int i = 0; i < n; i++) {
        if (rowvar[i] < 0 && nr < max) rows[nr++] = i;
        if (colrow[i] < 0 && nc < max) cols[nc++] = i;
    }
    for (int k = nr; k < max; k++)
        rows[k] = -1;
    for (int k = nc; k < max; k++)
        cols[k] = -1;
    ret = n - matched;
done:
    sp_union_free(&u);
    free(rowvar);
    free(colrow);
    return ret;
}
