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
