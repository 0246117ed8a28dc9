/* Greedy column colouring, coloured forward-difference Jacobians and the central-difference
 * Jacobian checker (see bg_fdjac.h for the method and reference). */
#include "bg_fdjac.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

void sp_colouring_free(sp_colouring **c)
{
    if (!c || !*c) return;
    free((*c)->group);
    free((*c)->gptr);
    free((*c)->gcols);
    free(*c);
    *c = NULL;
}

sp_colouring *sp_colour(const sp_csc *P)
{
    if (!P) return NULL;
    int n = P->ncol;
    sp_colouring *c = calloc(1, sizeof *c);
    sp_csc *T = sp_csc_transpose(P); /* rows of P as columns: which columns touch row i */
    int *mark = malloc(((size_t)n + 1) * sizeof *mark);
    if (!c || !T || !mark) goto fail;
    c->ncol = n;
    c->group = malloc(((size_t)n + 1) * sizeof *c->group);
    c->gcols = malloc(((size_t)n + 1) * sizeof *c->gcols);
    if (!c->group || !c->gcols) goto fail;
    for (int g = 0; g <= n; g++)
        mark[g] = -1;
    int ng = 0;
    for (int j = 0; j < n; j++) {
        /* mark[g] == j: group g is taken by a neighbour of j */
        for (int p = P->colptr[j]; p < P->colptr[j + 1]; p++) {
            int i = P->rowind[p];
            for (int q = T->colptr[i]; q < T->colptr[i + 1]; q++) {
                int k = T->rowind[q];
                if (k < j) mark[c->group[k]] = j;
            }
        }
        int g = 0;
        while (mark[g] == j)
            g++;
        c->group[j] = g;
        if (g + 1 > ng) ng = g + 1;
    }
    c->ngroups = ng;
    c->gptr = calloc((size_t)ng + 1, sizeof *c->gptr);
    if (!c->gptr) goto fail;
    for (int j = 0; j < n; j++)
        c->gptr[c->group[j] + 1]++;
    for (int g = 0; g < ng; g++)
        c->gptr[g + 1] += c->gptr[g];
    for (int g = 0; g <= ng; g++)
        mark[g] = c->gptr[g];
    for (int j = 0; j < n; j++)
        c->gcols[mark[c->group[j]]++] = j;
    sp_csc_free(&T);
    free(mark);
    return c;
fail:
    sp_colouring_free(&c);
    sp_csc_free(&T);
    free(mark);
    return NULL;
}

int sp_colouring_valid(const sp_colouring *c, const sp_csc *P)
{
    if (!c || !P || c->ncol != P->ncol) return 0;
    int *owner = malloc(((size_t)P->nrow + 1) * sizeof *owner);
    if (!owner) return 0;
    int ok = 1;
    for (int g = 0; g < c->ngroups && ok; g++) {
        for (int i = 0; i < P->nrow; i++)
            owner[i] = -1;
        for (int t = c->gptr[g]; t < c->gptr[g + 1] && ok; t++) {
            int j = c->gcols[t];
            if (c->group[j] != g) ok = 0;
            for (int p = P->colptr[j]; p < P->colptr[j + 1] && ok; p++) {
                if (owner[P->rowind[p]] >= 0) ok = 0;
                owner[P->rowind[p]] = j;
            }
        }
    }
    free(owner);
    return ok;
}

struct sp_fdjac {
    sp_csc *pattern; /* copy of the pattern */
    sp_colouring *col;
    double *xp, *fp, *h;
    long calls;
};

void sp_fdjac_free(sp_fdjac **d)
{
    if (!d || !*d) return;
    sp_csc_free(&(*d)->pattern);
    sp_colouring_free(&(*d)->col);
    free((*d)->xp);
    free((*d)->fp);
    free((*d)->h);
    free(*d);
    *d = NULL;
}

sp_fdjac *sp_fdjac_create(const sp_csc *P)
{
    if (!P) return NULL;
    sp_fdjac *d = calloc(1, sizeof *d);
    if (!d) return NULL;
    d->pattern = sp_csc_copy(P);
    d->col = sp_colour(P);
    d->xp = malloc(((size_t)P->ncol + 1) * sizeof *d->xp);
    d->h = malloc(((size_t)P->ncol + 1) * sizeof *d->h);
    d->fp = malloc(((size_t)P->nrow + 1) * sizeof *d->fp);
    if (!d->pattern || !d->col || !d->xp || !d->h || !d->fp) sp_fdjac_free(&d);
    return d;
}

int sp_fdjac_ngroups(const sp_fdjac *d)
{
    return d ? d->col->ngroups : BG_ERR_ARGUMENT;
}

long sp_fdjac_calls(const sp_fdjac *d)
{
    return d ? d->calls : BG_ERR_ARGUMENT;
}

int sp_fdjac_eval(sp_fdjac *d, sp_vecfn f, void *user, const double *x, const double *f0,
                  const double *typ, sp_csc *J)
{
    if (!d || !f || !x || !f0 || !J) return BG_ERR_ARGUMENT;
    const sp_csc *P = d->pattern;
    const sp_colouring *c = d->col;
    if (!sp_csc_same_pattern(P, J)) return BG_ERR_PATTERN;
    double sq = sqrt(DBL_EPSILON);
    memcpy(d->xp, x, (size_t)P->ncol * sizeof *x);
    for (int g = 0; g < c->ngroups; g++) {
        for (int t = c->gptr[g]; t < c->gptr[g + 1]; t++) {
            int j = c->gcols[t];
            double s = typ ? fabs(typ[j]) : 1.0;
            double h = sq * (fabs(x[j]) > s ? fabs(x[j]) : s);
            if (x[j] < 0) h = -h;
            d->xp[j] = x[j] + h;
            d->h[j] = d->xp[j] - x[j]; /* the step actually taken */
        }
        d->calls++;
        int st = f(user, d->xp, d->fp);
        for (int t = c->gptr[g]; t < c->gptr[g + 1]; t++)
            d->xp[c->gcols[t]] = x[c->gcols[t]];
        if (st != 0) return st;
        for (int t = c->gptr[g]; t < c->gptr[g + 1]; t++) {
            int j = c->gcols[t];
            double inv = 1.0 / d->h[j];
            for (int p = P->colptr[j]; p < P->colptr[j + 1]; p++) {
                int i = P->rowind[p];
                J->val[p] = (d->fp[i] - f0[i]) * inv;
            }
        }
    }
    return 0;
}

/* Keeps the nw largest errors seen so far in w[0..*nk), largest first. */
static void keep_worst(sp_jac_entry *w, int nw, int *nk, sp_jac_entry e)
{
    int k;
    if (nw <= 0) return;
    if (*nk < nw)
        k = (*nk)++;
    else if (w[nw - 1].err < e.err)
        k = nw - 1;
    else
        return;
    w[k] = e;
    for (; k > 0 && w[k - 1].err < w[k].err; k--) {
        sp_jac_entry t = w[k - 1];
        w[k - 1] = w[k];
        w[k] = t;
    }
}

int sp_jac_check(const sp_csc *J, sp_vecfn f, void *user, int m, const double *x, double floor,
                 double tol, sp_jac_entry *worst, int nworst, double *max_err)
{
    if (!J || !f || !x || nworst < 0 || (nworst > 0 && !worst)) return BG_ERR_ARGUMENT;
    int n = J->ncol;
    if (m != J->nrow || !(floor > 0)) return BG_ERR_ARGUMENT;
    double *xp = malloc(((size_t)n + 1) * sizeof *xp);
    double *fp = malloc(((size_t)m + 1) * sizeof *fp);
    double *fm = malloc(((size_t)m + 1) * sizeof *fm);
    double *col = malloc(((size_t)m + 1) * sizeof *col);
    int st = 0, nbad = 0, nkept = 0;
    double emax = 0.0;
    if (!xp || !fp || !fm || !col) {
        st = BG_ERR_MEMORY;
        goto done;
    }
    memcpy(xp, x, (size_t)n * sizeof *x);
    double h0 = cbrt(DBL_EPSILON); /* optimal for central differences */
    for (int j = 0; j < n; j++) {
        double h = h0 * (fabs(x[j]) > 1.0 ? fabs(x[j]) : 1.0);
        xp[j] = x[j] + h;
        double hp = xp[j] - x[j];
        if ((st = f(user, xp, fp)) != 0) goto done;
        xp[j] = x[j] - h;
        double hm = x[j] - xp[j];
        if ((st = f(user, xp, fm)) != 0) goto done;
        xp[j] = x[j];
        for (int i = 0; i < m; i++)
            col[i] = 0.0;
        for (int p = J->colptr[j]; p < J->colptr[j + 1]; p++)
            col[J->rowind[p]] = J->val[p];
        for (int i = 0; i < m; i++) {
            double fd = (fp[i] - fm[i]) / (hp + hm);
            double e = fabs(col[i] - fd) / (fabs(fd) + floor);
            if (isnan(e)) e = INFINITY; /* a NaN on either side is the worst error */
            if (e > emax) emax = e;
            if (e > tol) nbad++;
            if (e > 0) {
                sp_jac_entry en = {i, j, col[i], fd, e};
                keep_worst(worst, nworst, &nkept, en);
            }
        }
    }
done:
    free(xp);
    free(fp);
    free(fm);
    free(col);
    if (max_err) *max_err = emax;
    if (st != 0) return st < 0 ? st : BG_ERR_CALLBACK;
    return nbad;
}
