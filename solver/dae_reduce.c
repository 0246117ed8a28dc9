/* Index reduction of the constraints (options.index2 = DAE_I2_REDUCE).
 *
 * Method. The constraint rows of an index-2 system, the algebraic equations g(t, y) = 0 that a
 * maximum matching of the algebraic equations to the index-1 algebraic unknowns leaves unmatched
 * (the structurally singular part, Pantelides, SIAM J. Sci. Stat. Comput. 9 (1988) 213-231), are
 * replaced by their time derivatives g_t + g_y y' = 0. The system is then of index 1, on which
 * BDF of every order is convergent (Brenan, Campbell and Petzold, Numerical Solution of
 * Initial-Value Problems in DAEs, SIAM 1996, Theorem 3.1.1), whatever the structure of the
 * original index-2 system: BDF applied to the index-2 form is convergent for Hessenberg systems
 * (Theorem 3.2.1 there) but not in general (their example in Section 3.2, y1 + eta t y2 = g,
 * y1' + eta t y2' + (1 + eta) y2 = 0, is unstable for every step at eta < -1/2 with BDF1 and at
 * eta < -1/4 with BDF2). The drift of g away from zero that the reduction allows is removed by a
 * projection of each accepted step (and of interpolated output) onto g = 0, the minimum-norm
 * correction of the solver's position-constraint mechanism (Hairer and Wanner, Solving ODEs II,
 * section VII.2, projection methods; Eich, SIAM J. Numer. Anal. 30 (1993) 1467-1482).
 *
 * Evaluation. The derivative of constraint row i along the iterate (t, y, y') is a fourth-order
 * central difference of the residual along the line (t + s, y + s y'):
 *   D_i = (8 (F_i(+d) - F_i(-d)) - (F_i(+2d) - F_i(-2d))) / (12 d),
 * or the one-sided formula of the same order, (25 F_i(0) - 48 F_i(-d) + 36 F_i(-2d)
 * - 16 F_i(-3d) + 3 F_i(-4d)) / (12 d) and its mirror image, where the central one would reach
 * across a breakpoint (the inputs jump there); four extra residual evaluations per call. d is
 * 1e-3 tau, tau the shortest time scale m_j / |y'_j| of the unknowns the constraint rows
 * contain, m_j the largest |y_j| of the accepted steps so far (a component passing through zero
 * keeps its scale): truncation (d / tau)^4 / 30 ~ 3e-14 and round-off ~ 1e3 eps relative,
 * independent of the step.
 *
 * The problem as given stays with an inner solver (the same problem and options, index-2 policy
 * DAE_I2_EXCLUDE, never stepped): its patterns (given or found from the residual), kinds, the
 * Jacobian (analytic or by finite differences of the residual) and consistent initialisation.
 * The Jacobian of the reduced system is assembled from it: d D_i / dy' = dg_i/dy, and
 * d D_i / dy = g_ty + g_yy y' by forward differences of D (coloured on the pattern of dg/dy).
 * That term cannot be left out: it is O(1) against alpha/h dg/dy, but dF/dy' of the reduced
 * system is singular and the O(1) terms decide the Newton matrix in the algebraic directions
 * (on the example above at eta = -0.8 the iteration diverged at rate 4 without it). The noise
 * of D is about 1e3 eps of the constraint's terms over tau, whatever the step, so that the
 * differences of D are accurate to about 1e-5. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bg_dae_impl.h"
#include "dae_ic_impl.h"

#define RED_DELTA 1e-3 /* d / tau */
/* scratch vectors of dae_reduce.w */
enum { W_YQ, W_FQ /* four */, W_F = W_FQ + 4, W_FD, W_D0, W_ZERO, W_Y, W_N };

struct dae_reduce {
    dae_solver *in;     /* the problem as given */
    dae_res_fn ures;    /* its residual */
    dae_root_fn uroots; /* its event functions */
    dae_regime_fn uregimes; /* and regimes */
    void *uuser;
    int nc, *crow;         /* the constraint rows, listed */
    int *crow_of;          /* row i -> its number among the constraint rows, -1 */
    sp_csc *Jy, *Jyp, *Gp; /* reduced patterns; nc x n pattern of dg/dy */
    int *kind;             /* kinds of the reduced system */
    int *jyp_slot;         /* entry p of in->Jyp -> its entry in the reduced Jyp */
    int *jy_slot;          /* entry p of in->Jy -> entry of the reduced Jyp (constraint rows), -1 */
    int *g_slot;           /* entry p of in->Jy -> entry of Gp, -1 */
    sp_fdjac *fdg;         /* differences of D in y on the pattern of dg/dy */
    sp_csc *DG;            /* and their values */
    double ft;             /* the point of those differences */
    const double *fyp;
    double *w;    /* W_N vectors of n (W_*) */
    double *ymax; /* largest |y_j| of the accepted steps (and the start) */
    int ymax_set;
    int jac_done; /* in->Jy holds values */
};

static void free_build(dae_reduce *R)
{
    free(R->crow);
    free(R->crow_of);
    sp_csc_free(&R->Jy);
    sp_csc_free(&R->Jyp);
    sp_csc_free(&R->Gp);
    free(R->kind);
    free(R->jyp_slot);
    free(R->jy_slot);
    free(R->g_slot);
    sp_fdjac_free(&R->fdg);
    sp_csc_free(&R->DG);
    R->crow = R->crow_of = R->kind = R->jyp_slot = R->jy_slot = R->g_slot = NULL;
    R->nc = 0;
}

void daei_red_free(dae_solver *s)
{
    dae_reduce *R = s->red;
    if (!R) return;
    free_build(R);
    dae_free(&R->in);
    free(R->w);
    free(R->ymax);
    free(R);
    s->red = NULL;
}

/* ---------------------------------------------------------------- callbacks ---- */

/* d for the differences along (1, y'): see the header comment. */
static double red_delta(const dae_solver *s, double t, const double *y, const double *yp)
{
    const dae_reduce *R = s->red;
    const sp_csc *G = R->Gp;
    double tau = INFINITY, rt = fmax(s->o.rtol, 1e-12);
    for (int j = 0; j < G->ncol; j++) {
        if (G->colptr[j + 1] == G->colptr[j] || yp[j] == 0) continue;
        double m = fmax(fmax(fabs(y[j]), R->ymax[j]), s->atol[j] / rt);
        tau = fmin(tau, m / fabs(yp[j]));
    }
    if (!isfinite(tau)) tau = fabs(s->hh) > 0 ? fabs(s->hh) : fmax(fabs(t), 1.0);
    double d = RED_DELTA * tau, floor = 0x1p20 * DBL_EPSILON * fabs(t);
    return fmax(d, floor > 0 ? floor : DBL_MIN);
}

static int red_res(void *u, double t, const double *y, const double *yp, double *F)
{
    dae_solver *s = u;
    dae_reduce *R = s->red;
    int n = s->n, r = R->ures(R->uuser, t, y, yp, F);
    if (r != 0) return r;
    if (!R->ymax_set) { /* the first evaluation: the start */
        for (int j = 0; j < n; j++)
            R->ymax[j] = fabs(y[j]);
        R->ymax_set = 1;
    }
    /* the stencil: central, or one-sided where it would reach across a breakpoint (the
     * inputs jump there): backward before the next one, forward after the last one */
    static const double cc[4] = {1, -1, 2, -2}, wc[4] = {8, -8, -1, 1};
    static const double cb[4] = {-1, -2, -3, -4}, wb[4] = {-48, 36, -16, 3};
    static const double cf[4] = {1, 2, 3, 4}, wf[4] = {48, -36, 16, -3};
    const double *c = cc, *wt = wc;
    double w0 = 0, d = red_delta(s, t, y, yp);
    if (s->nbkpt > 0 && s->hh >= 0) {
        double ahead = s->ibk < s->nbkpt ? s->bkpt[s->ibk] - t : INFINITY;
        double behind = s->ibk > 0 ? t - s->bkpt[s->ibk - 1] : INFINITY;
        if (ahead < 2 * d && behind < 2 * d) d = 0.25 * fmax(ahead, behind);
        if (ahead < 2 * d) {
            c = cb, wt = wb, w0 = 25;
        } else if (behind < 2 * d) {
            c = cf, wt = wf, w0 = -25;
        }
    }
    double *yq = R->w + W_YQ * (size_t)n, *Fq[4];
    for (int m = 0; m < 4; m++) {
        Fq[m] = R->w + (size_t)(W_FQ + m) * n;
        double tm = t + c[m] * d, dm = tm - t;
        for (int j = 0; j < n; j++)
            yq[j] = y[j] + dm * yp[j];
        memset(Fq[m], 0, (size_t)n * sizeof(double));
        if ((r = R->ures(R->uuser, tm, yq, yp, Fq[m])) != 0) return r;
    }
    s->st.res_evals += 4;
    for (int k = 0; k < R->nc; k++) {
        int i = R->crow[k];
        double v = w0 * F[i];
        for (int m = 0; m < 4; m++)
            v += wt[m] * Fq[m][i];
        F[i] = v / (12 * d);
    }
    return 0;
}

/* D, the constraint rows of the reduced residual, at (R->ft, x, R->fyp). */
static int red_dvec(void *u, const double *x, double *f)
{
    dae_solver *s = u;
    dae_reduce *R = s->red;
    double *F = R->w + W_FD * (size_t)s->n;
    memset(F, 0, (size_t)s->n * sizeof *F);
    int r = red_res(s, R->ft, x, R->fyp, F);
    s->st.res_evals++;
    for (int k = 0; k < R->nc && r == 0; k++)
        f[k] = F[R->crow[k]];
    return r;
}

/* The reduced Jacobian from the inner solver's: rows other than the constraints as they are;
 * a constraint row's dF/dy goes to its dF/dy', its dF/dy is 0 (see the header comment). */
static int red_jac(void *u, double t, const double *y, const double *yp, sp_csc *Jy, sp_csc *Jyp)
{
    dae_solver *s = u;
    dae_reduce *R = s->red;
    dae_solver *in = R->in;
    int n = s->n;
    double *F = R->w + W_F * (size_t)n;
    memset(F, 0, (size_t)n * sizeof *F);
    int r = R->ures(R->uuser, t, y, yp, F);
    s->st.res_evals_fd++;
    if (r != 0) return r;
    memcpy(in->ewt, s->ewt, (size_t)n * sizeof *in->ewt);
    in->hh = s->hh;
    long fd0 = in->st.res_evals_fd, w0 = in->st.warnings;
    r = daei_eval_jac(in, t, y, yp, F);
    s->st.res_evals_fd += in->st.res_evals_fd - fd0;
    if (in->st.warnings > w0) { /* options.check_jacobian: the inner solver's warning */
        s->warn = in->warn;
        s->st.warnings += in->st.warnings - w0;
    }
    if (r != 0) {
        snprintf(s->note, sizeof s->note, "%s", in->note);
        return r;
    }
    R->jac_done = 1;
    /* d D / dy on the constraint rows */
    double *D0 = R->w + W_D0 * (size_t)n, *typ = R->w + W_F * (size_t)n;
    R->ft = t;
    R->fyp = yp;
    if ((r = red_dvec(s, y, D0)) != 0) return r;
    for (int j = 0; j < n; j++)
        typ[j] = 1.0 / (s->ewt[j] * fmax(s->o.rtol, 1e-12));
    long e0 = s->st.res_evals;
    r = sp_fdjac_eval(R->fdg, red_dvec, s, y, D0, typ, R->DG);
    s->st.res_evals_fd += s->st.res_evals - e0; /* counted by red_res as res_evals */
    s->st.res_evals = e0;
    if (r != 0) return r;
    const sp_csc *A = in->Jy, *B = in->Jyp;
    memcpy(Jy->val, A->val, (size_t)A->nnz * sizeof *A->val);
    memset(Jyp->val, 0, (size_t)Jyp->nnz * sizeof *Jyp->val);
    for (int p = 0; p < B->nnz; p++)
        Jyp->val[R->jyp_slot[p]] += B->val[p];
    for (int p = 0; p < A->nnz; p++)
        if (R->jy_slot[p] >= 0) {
            Jyp->val[R->jy_slot[p]] += A->val[p];
            Jy->val[p] = R->DG->val[R->g_slot[p]];
        }
    return 0;
}

/* g = the constraint rows of the residual; G = their dF/dy from the last Jacobian (the
 * projection's Gauss-Newton iteration takes it as it is), g and G then scaled by rows. */
static int red_cons(void *u, double t, const double *y, double *g, sp_csc *G)
{
    dae_solver *s = u;
    dae_reduce *R = s->red;
    int n = s->n;
    double *F = R->w + W_F * (size_t)n, *zero = R->w + W_ZERO * (size_t)n;
    memset(zero, 0, (size_t)n * sizeof *zero);
    memset(F, 0, (size_t)n * sizeof *F);
    int r = R->ures(R->uuser, t, y, zero, F);
    s->st.res_evals++;
    if (r != 0) return r;
    for (int k = 0; k < R->nc; k++)
        g[k] = F[R->crow[k]];
    if (!G) /* the drift of an accepted step (daei_project_step): its scales */
        for (int j = 0; j < n; j++)
            R->ymax[j] = fmax(R->ymax[j], fabs(y[j]));
    if (G) {
        if (!R->jac_done) {
            double *yc = R->w + W_Y * (size_t)n; /* G only: any y' */
            memcpy(yc, y, (size_t)n * sizeof *y);
            if ((r = red_jac(s, t, yc, zero, s->Jy, s->Jyp)) != 0) return r;
        }
        const sp_csc *A = R->in->Jy;
        for (int p = 0; p < A->nnz; p++)
            if (R->g_slot[p] >= 0) G->val[R->g_slot[p]] = A->val[p];
        /* rows of unit length: the projection is the same, its matrix G G^T better
         * conditioned (constraint rows of a stiff bar next to rows of order 1) */
        double *rn = R->w + W_D0 * (size_t)n;
        memset(rn, 0, (size_t)R->nc * sizeof *rn);
        for (int p = 0; p < G->nnz; p++)
            rn[G->rowind[p]] += G->val[p] * G->val[p];
        for (int k = 0; k < R->nc; k++)
            rn[k] = rn[k] > 0 ? 1.0 / sqrt(rn[k]) : 1.0;
        for (int p = 0; p < G->nnz; p++)
            G->val[p] *= rn[G->rowind[p]];
        for (int k = 0; k < R->nc; k++)
            g[k] *= rn[k];
    }
    return 0;
}

/* The problem's event functions and regimes with its own user pointer (s->p.user is the
 * solver). */
static int red_roots(void *u, double t, const double *y, const double *yp, double *g)
{
    const dae_reduce *R = ((dae_solver *)u)->red;
    return R->uroots(R->uuser, t, y, yp, g);
}

static int red_regimes(void *u, double t, const double *y, int *r)
{
    const dae_reduce *R = ((dae_solver *)u)->red;
    return R->uregimes(R->uuser, t, y, r);
}

/* ---------------------------------------------------------------- structure ---- */

static int nomem(bg_error *err, int n)
{
    return bg_error_raise(err, BG_ERR_MEMORY, "dae_create", "out of memory (n = %d)", n);
}

/* The constraint rows: the algebraic rows (no y') that a maximum matching to the index-1
 * algebraic unknowns leaves unmatched. */
static int find_constraints(dae_reduce *R, int n, bg_error *err)
{
    const dae_solver *in = R->in;
    int *rowmask = malloc((size_t)n * sizeof *rowmask),
        *colmask = malloc((size_t)n * sizeof *colmask), *rv = malloc((size_t)n * sizeof *rv);
    R->crow_of = malloc((size_t)n * sizeof *R->crow_of);
    R->crow = malloc((size_t)n * sizeof *R->crow);
    int r = BG_OK;
    if (!rowmask || !colmask || !rv || !R->crow_of || !R->crow) {
        r = nomem(err, n);
        goto done;
    }
    for (int i = 0; i < n; i++)
        rowmask[i] = 1;
    for (int p = 0; p < in->Jyp->nnz; p++)
        rowmask[in->Jyp->rowind[p]] = 0;
    for (int j = 0; j < n; j++)
        colmask[j] = in->kind[j] == DAE_ALG;
    if (daei_match(in->Jy, rowmask, colmask, rv) < 0) {
        r = nomem(err, n);
        goto done;
    }
    for (int i = 0; i < n; i++) {
        R->crow_of[i] = rowmask[i] && rv[i] < 0 ? R->nc : -1;
        if (R->crow_of[i] >= 0) R->crow[R->nc++] = i;
    }
    if (R->nc == 0)
        r = bg_error_raise(err, BG_ERR_ARGUMENT, "dae_create",
                           "index2 = DAE_I2_REDUCE: no constraint to differentiate (every "
                           "algebraic equation determines an index-1 algebraic unknown: the "
                           "system is of index 1 or less)");
done:
    free(rowmask);
    free(colmask);
    free(rv);
    return r;
}

/* The reduced patterns (dF/dy' with the constraint rows of dF/dy added; dF/dy as it is), the
 * pattern of dg/dy, the maps of the inner solver's entries into them, the reduced kinds. */
static int build_patterns(dae_reduce *R, int n, bg_error *err)
{
    const sp_csc *A = R->in->Jy, *B = R->in->Jyp;
    sp_builder *bp = sp_builder_create(n, n, B->nnz + A->nnz),
               *bg = sp_builder_create(R->nc, n, A->nnz);
    int *sb = malloc(((size_t)B->nnz + A->nnz + 1) * sizeof *sb),
        *sg = malloc(((size_t)A->nnz + 1) * sizeof *sg);
    R->kind = malloc((size_t)n * sizeof *R->kind);
    R->jyp_slot = malloc(((size_t)B->nnz + 1) * sizeof *R->jyp_slot);
    R->jy_slot = malloc(((size_t)A->nnz + 1) * sizeof *R->jy_slot);
    R->g_slot = malloc(((size_t)A->nnz + 1) * sizeof *R->g_slot);
    int r = BG_ERR_MEMORY;
    if (!bp || !bg || !sb || !sg || !R->kind || !R->jyp_slot || !R->jy_slot || !R->g_slot)
        goto done;
    /* entry numbers of the builders first, their slots after finishing */
    for (int j = 0; j < n; j++) {
        for (int p = B->colptr[j]; p < B->colptr[j + 1]; p++)
            if ((R->jyp_slot[p] = sp_builder_add(bp, B->rowind[p], j, 0.0)) < 0) goto done;
        for (int p = A->colptr[j]; p < A->colptr[j + 1]; p++) {
            int k = R->crow_of[A->rowind[p]];
            R->jy_slot[p] = R->g_slot[p] = -1;
            if (k < 0) continue;
            if ((R->jy_slot[p] = sp_builder_add(bp, A->rowind[p], j, 0.0)) < 0 ||
                (R->g_slot[p] = sp_builder_add(bg, k, j, 0.0)) < 0)
                goto done;
        }
    }
    R->Jyp = sp_builder_finish(bp, sb);
    R->Gp = sp_builder_finish(bg, sg);
    if (!R->Jyp || !R->Gp || !(R->Jy = sp_csc_copy(A)) || !(R->DG = sp_csc_copy(R->Gp)) ||
        !(R->fdg = sp_fdjac_create(R->Gp)))
        goto done;
    for (int p = 0; p < B->nnz; p++)
        R->jyp_slot[p] = sb[R->jyp_slot[p]];
    for (int p = 0; p < A->nnz; p++)
        if (R->jy_slot[p] >= 0) {
            R->jy_slot[p] = sb[R->jy_slot[p]];
            R->g_slot[p] = sg[R->g_slot[p]];
        }
    for (int j = 0; j < n; j++)
        R->kind[j] = R->Jyp->colptr[j + 1] > R->Jyp->colptr[j] ? DAE_DIFF : DAE_ALG;
    r = BG_OK;
done:
    sp_builder_free(&bp);
    sp_builder_free(&bg);
    free(sb);
    free(sg);
    return r == BG_OK ? r : nomem(err, n);
}

/* The solver takes the reduced problem: callbacks, patterns, kinds, the constraints to project
 * onto, then the structure. */
static int take_reduced(dae_solver *s, bg_error *err)
{
    dae_reduce *R = s->red;
    int n = s->n, r;
    s->p.res = red_res;
    s->p.jac = red_jac;
    s->p.user = s; /* every callback of s->p takes the solver: */
    if (R->uroots) s->p.roots = red_roots;
    if (R->uregimes) s->p.regimes = red_regimes;
    s->p.kind = R->kind;
    s->p.jac_y_pattern = R->Jy;
    s->p.jac_yp_pattern = R->Jyp;
    s->p.ncons = R->nc;
    s->p.cons = red_cons;
    s->p.cons_pattern = R->Gp;
    s->o.projection = 1;
    s->o.check_jacobian = -1; /* the inner solver checks the Jacobian as given */
    memcpy(s->kind, R->kind, (size_t)n * sizeof *s->kind);
    sp_csc_free(&s->Jy);
    sp_csc_free(&s->Jyp);
    sp_csc_free(&s->G);
    aat_free(&s->aat_proj);
    free(s->gv);
    free(s->gw);
    s->gv = malloc((size_t)R->nc * sizeof *s->gv);
    s->gw = malloc((size_t)R->nc * sizeof *s->gw);
    if (!s->gv || !s->gw || !(s->Jy = sp_csc_copy(R->Jy)) || !(s->Jyp = sp_csc_copy(R->Jyp)) ||
        !(s->G = sp_csc_copy(R->Gp)))
        return nomem(err, n);
    if (!(s->aat_proj = aat_create(s->G, err))) return err ? err->status : BG_ERR_LIBRARY;
    if ((r = daei_setup_structure(s, err)) != BG_OK) return r;
    /* index 1 or less: the reduced Newton matrix is structurally nonsingular */
    int matched = 0;
    for (int i = 0; i < n; i++)
        matched += s->rowvar[i] >= 0;
    if (matched < n)
        return bg_error_raise(err, BG_ERR_ARGUMENT, "dae_create",
                              "index2 = DAE_I2_REDUCE: after differentiating the %d constraint "
                              "row(s), %d equation(s) still match no unknown: the system is not "
                              "of index 2 in the form the reduction handles",
                              R->nc, n - matched);
    return BG_OK;
}

/* The reduced problem from the inner solver's patterns and kinds, then the structure. */
static int red_build(dae_solver *s, bg_error *err)
{
    int r;
    free_build(s->red);
    if ((r = find_constraints(s->red, s->n, err)) != BG_OK) return r;
    if ((r = build_patterns(s->red, s->n, err)) != BG_OK) return r;
    return take_reduced(s, err);
}

int daei_red_create(dae_solver *s, const dae_problem *p, const dae_options *o, bg_error *err)
{
    dae_reduce *R = s->red = calloc(1, sizeof *R);
    if (!R || !(R->w = malloc(W_N * (size_t)s->n * sizeof *R->w)) ||
        !(R->ymax = calloc((size_t)s->n, sizeof *R->ymax)))
        return bg_error_raise(err, BG_ERR_MEMORY, "dae_create", "out of memory (n = %d)", s->n);
    dae_options oi = *o;
    oi.index2 = DAE_I2_EXCLUDE;
    oi.projection = 0;
    if (!(R->in = dae_create(p, &oi, err))) return err ? err->status : BG_ERR_ARGUMENT;
    R->ures = p->res;
    R->uroots = p->roots;
    R->uregimes = p->regimes;
    R->uuser = p->user;
    if (!R->in->structured) {
        s->detect = 1; /* patterns found from the residual by the inner solver at dae_init */
        return BG_OK;
    }
    return red_build(s, err);
}

int daei_red_by_fd(const dae_solver *s)
{
    return s->red->in->p.jac == NULL;
}

int daei_red_probe(dae_solver *s, double t, const double *y, const double *yp, long *added)
{
    dae_solver *in = s->red->in;
    long e0 = in->st.res_evals_fd;
    int r = daei_probe_patterns(in, t, y, yp, 1, added);
    s->st.res_evals_fd += in->st.res_evals_fd - e0;
    if (r != BG_OK) {
        s->err = in->err;
        return r;
    }
    if (*added == 0) return BG_OK;
    daei_free_structure(in);
    if ((r = daei_setup_structure(in, &s->err)) != BG_OK) return r;
    s->red->jac_done = 0;
    return red_build(s, &s->err);
}

void daei_red_reset(dae_solver *s)
{
    s->red->ymax_set = 0;
    s->red->jac_done = 0;
}

int daei_red_detect(dae_solver *s, double t0, const double *y0, const double *yp0)
{
    dae_solver *in = s->red->in;
    int r = dae_init(in, t0, y0, yp0);
    s->st.pattern_nnz = in->st.pattern_nnz;
    s->st.pattern_probes = in->st.pattern_probes;
    s->st.pattern_res_evals = in->st.pattern_res_evals;
    s->st.res_evals_fd += in->st.res_evals_fd;
    s->st.t_pattern = in->st.t_pattern;
    if (r != BG_OK) {
        s->err = in->err;
        return r;
    }
    return red_build(s, &s->err);
}

int daei_red_consistent_init(dae_solver *s)
{
    dae_solver *in = s->red->in;
    int n = s->n;
    in->tn = s->tn;
    in->init_side = s->init_side;
    in->ibk = s->ibk;
    memcpy(in->phi[0], s->phi[0], (size_t)n * sizeof(double));
    memcpy(in->phi[1], s->phi[1], (size_t)n * sizeof(double));
    long e0 = in->st.res_evals, f0 = in->st.res_evals_fd;
    int r = daei_consistent_init(in);
    s->st.res_evals += in->st.res_evals - e0;
    s->st.res_evals_fd += in->st.res_evals_fd - f0;
    s->ic_res = in->ic_res;
    s->ic_err = in->ic_err;
    if (r != BG_OK) {
        s->err = in->err;
        return r;
    }
    /* the inner solver's scratch (the correction of stage A for the warning) but not its
     * IC_GUESS, IC_GUESSP: the values given are the outer solver's (dae_consistent_init keeps
     * them there to compare; the inner ones were never set, and every unknown "went from 0") */
    memcpy(daei_icw(s, IC_DA1), daei_icw(in, IC_DA1),
           (size_t)(IC_NWORK - IC_DA1) * (size_t)n * sizeof *s->ic_w);
    memcpy(s->phi[0], in->phi[0], (size_t)n * sizeof(double));
    memcpy(s->phi[1], in->phi[1], (size_t)n * sizeof(double));
    memcpy(s->y, s->phi[0], (size_t)n * sizeof(double));
    memcpy(s->yp, s->phi[1], (size_t)n * sizeof(double));
    s->hh = 0;
    daei_set_weights(s, s->y);
    s->need_setup = 1;
    return BG_OK;
}
