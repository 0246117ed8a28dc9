/* Creation and release of the integrator: default options, the checks of a problem and its
 * options, the copies the solver keeps, the Jacobian patterns and the Newton matrix's structure,
 * the classification of the unknowns when no kinds are given (dae_struct.c) and the matrices of
 * consistent initialisation (dae_ic.c). */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bg_dae_impl.h"
#include "bg_jaceval.h"

int dae_options_default(dae_options *o)
{
    if (!o) return BG_ERR_ARGUMENT;
    memset(o, 0, sizeof *o);
    o->rtol = 1e-6;
    o->atol = 1e-8;
    o->max_order = 0; /* the method's largest (dae_create) */
    o->max_steps = 100000;
    o->index2 = DAE_I2_EXCLUDE;
    o->linsol = LS_KLU;
    o->max_newton = 4;
    return BG_OK;
}

int daei_setup_structure(dae_solver *s, bg_error *err)
{
    const char *w = s->initialized || s->detect ? "dae_init" : "dae_create";
    int n = s->n;
    daei_free_structure(s); /* what an earlier attempt that failed left */
    if (!s->p.kind && dae_classify(s->Jy, s->Jyp, s->kind) < 0) goto nomem;
    sp_csc_zero(s->Jy);
    sp_csc_zero(s->Jyp);
    if (!(s->U = sp_union_create(s->Jy, s->Jyp))) goto nomem;
    if (!s->rowvar && !(s->rowvar = malloc((size_t)n * sizeof *s->rowvar))) goto nomem;
    if (daei_match(s->U->M, NULL, NULL, s->rowvar) < 0) goto nomem;
    if (!s->p.jac) {
        s->fdy = sp_fdjac_create(s->Jy);
        s->fdyp = sp_fdjac_create(s->Jyp);
        if (!s->fdy || !s->fdyp) goto nomem;
    }
    if (!(s->ls = ls_create(s->o.linsol, s->U->M, err))) return err ? err->status : BG_ERR_LIBRARY;
    s->has_alg2 = 0;
    for (int i = 0; i < n; i++)
        s->has_alg2 |= s->kind[i] == DAE_ALG2;
    int r = daei_init_setup(s, err);
    if (r != BG_OK) return r;
    s->structured = 1;
    return BG_OK;
nomem:
    return bg_error_raise(err, BG_ERR_MEMORY, w, "out of memory (n = %d)", n);
}

void daei_free_structure(dae_solver *s)
{
    if (s->structured) { /* the counts of the solvers freed here stay in the statistics */
        daei_sync_stats(s);
        s->fact_off[0] = s->st.factor_symbolic;
        s->fact_off[1] = s->st.factor_full;
        s->fact_off[2] = s->st.factor_refactor;
    }
    sp_union_free(&s->U);
    sp_fdjac_free(&s->fdy);
    sp_fdjac_free(&s->fdyp);
    ls_free(&s->ls);
    daei_init_free(s);
    s->structured = 0;
}

void dae_free(dae_solver **sp)
{
    if (!sp || !*sp) return;
    dae_solver *s = *sp;
    free(s->out_idx);
    free(s->kind);
    if (s->names) {
        for (int i = 0; i < s->n; i++)
            free(s->names[i]);
        free(s->names);
    }
    if (s->enames) {
        for (int i = 0; i < s->n; i++)
            free(s->enames[i]);
        free(s->enames);
    }
    free(s->rowvar);
    free(s->atol);
    free(s->bkpt);
    sp_csc_free(&s->Jy);
    sp_csc_free(&s->Jyp);
    daei_free_structure(s);
    sp_csc_free(&s->G);
    aat_free(&s->aat_proj);
    free(s->gv);
    free(s->gw);
    for (int j = 0; j < NPHI; j++)
        free(s->phi[j]);
    if (s->wnewt != s->ewt) free(s->wnewt); /* (else it is ewt) */
    free(s->ewt);
    free(s->werr);
    free(s->wdiff);
    free(s->y);
    free(s->yp);
    free(s->ee);
    free(s->delta);
    free(s->res);
    free(s->tmp);
    free(s->tmp2);
    free(s->typ);
    free(s->yc);
    for (int j = 0; j < STAB_WIN; j++)
        free(s->stab_e[j]);
    free(s->mb);
    free(s->reg_jac);
    free(s->reg_now);
    free(s->glo);
    free(s->ghi);
    free(s->gmid);
    free(s->rfound);
    daei_red_free(s);
    free(s);
    *sp = NULL;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The checks of dae_create that need no allocation: sizes, options, patterns. */
static int check_problem(const dae_problem *p, const dae_options *o, bg_error *err)
{
    const char *w = "dae_create";
    int n = p->n;
    bg_error perr = {0};
    const char *hname[3] = {"h_init", "h_min", "h_max"};
    const double hval[3] = {o->h_init, o->h_min, o->h_max};
    for (int k = 0; k < 3; k++)
        if (!(hval[k] >= 0) || !isfinite(hval[k]))
            return bg_error_raise(err, BG_ERR_ARGUMENT, w, "%s = %g: must be finite and >= 0",
                                  hname[k], hval[k]);
    if (o->index2 != DAE_I2_EXCLUDE && o->index2 != DAE_I2_SCALE_H && o->index2 != DAE_I2_REDUCE)
        return bg_error_raise(err, BG_ERR_ARGUMENT, w, "index2 = %d is not a dae_index2_policy",
                              (int)o->index2);
    if (o->linsol != LS_KLU && o->linsol != LS_DENSE)
        return bg_error_raise(err, BG_ERR_ARGUMENT, w, "linsol = %d is not LS_KLU or LS_DENSE",
                              (int)o->linsol);
    if (o->has_t_stop && !isfinite(o->t_stop))
        return bg_error_raise(err, BG_ERR_ARGUMENT, w, "t_stop = %g is not finite", o->t_stop);
    if (o->nbreakpoints < 0 || (o->nbreakpoints > 0 && !o->breakpoints))
        return bg_error_raise(err, BG_ERR_ARGUMENT, w,
                              "nbreakpoints = %d needs that many breakpoints (array %s)",
                              o->nbreakpoints, o->breakpoints ? "given" : "NULL");
    for (int k = 0; k < o->nbreakpoints; k++)
        if (!isfinite(o->breakpoints[k]))
            return bg_error_raise(err, BG_ERR_ARGUMENT, w, "breakpoint %d is %g", k,
                                  o->breakpoints[k]);
    if (o->stability_guard != 0 && o->stability_guard != 1)
        return bg_error_raise(err, BG_ERR_ARGUMENT, w, "stability_guard = %d: must be 0 or 1",
                              o->stability_guard);
    if (o->check_jacobian < -1 || o->check_jacobian > 1)
        return bg_error_raise(err, BG_ERR_ARGUMENT, w,
                              "check_jacobian = %d: must be -1, 0 or 1 (never, when the Newton "
                              "rate calls for it, at the first Jacobian)",
                              o->check_jacobian);
    if (p->ncons < 0 || p->nroots < 0 || p->nregimes < 0)
        return bg_error_raise(err, BG_ERR_ARGUMENT, w,
                              "ncons = %d, nroots = %d and nregimes = %d must be >= 0", p->ncons,
                              p->nroots, p->nregimes);
    if (p->nregimes > 0 && !p->regimes)
        return bg_error_raise(err, BG_ERR_ARGUMENT, w,
                              "nregimes = %d needs a regime function (regimes NULL)",
                              p->nregimes);
    if (p->ncons > 0 && (!p->cons || !p->cons_pattern))
        return bg_error_raise(err, BG_ERR_ARGUMENT, w,
                              "ncons = %d needs a constraint function and its pattern (cons %s, "
                              "cons_pattern %s)",
                              p->ncons, p->cons ? "given" : "NULL",
                              p->cons_pattern ? "given" : "NULL");
    if (o->index2 == DAE_I2_REDUCE && p->ncons > 0)
        return bg_error_raise(err, BG_ERR_ARGUMENT, w,
                              "index2 = DAE_I2_REDUCE projects onto the constraints it "
                              "differentiates and takes no position constraints of its own "
                              "(ncons = %d)",
                              p->ncons);
    if (p->nroots > 0 && !p->roots)
        return bg_error_raise(err, BG_ERR_ARGUMENT, w, "nroots = %d but no root function",
                              p->nroots);
    const sp_csc *pat[2] = {p->jac_y_pattern, p->jac_yp_pattern};
    for (int k = 0; k < 2; k++) {
        if (!pat[k]) continue;
        if (sp_csc_check(pat[k], &perr) != BG_OK)
            return bg_error_raise(err, BG_ERR_PATTERN, w, "the pattern of dF/dy%s: %s",
                                  k ? "'" : "", perr.message);
        if (pat[k]->nrow != n || pat[k]->ncol != n)
            return bg_error_raise(err, BG_ERR_PATTERN, w,
                                  "the pattern of dF/dy%s is %d x %d, the problem has n = %d",
                                  k ? "'" : "", pat[k]->nrow, pat[k]->ncol, n);
    }
    if (p->ncons > 0) {
        if (sp_csc_check(p->cons_pattern, &perr) != BG_OK)
            return bg_error_raise(err, BG_ERR_PATTERN, w, "the constraint pattern: %s",
                                  perr.message);
        if (p->cons_pattern->nrow != p->ncons || p->cons_pattern->ncol != n)
            return bg_error_raise(err, BG_ERR_PATTERN, w,
                                  "the constraint pattern is %d x %d, expected ncons x n = %d x %d",
                                  p->cons_pattern->nrow, p->cons_pattern->ncol, p->ncons, n);
    }
    return BG_OK;
}

dae_solver *dae_create(const dae_problem *p, const dae_options *o, bg_error *err)
{
    const char *w = "dae_create";
    dae_options def;
    if (!o) {
        dae_options_default(&def);
        o = &def;
    }
    if (!p || p->n < 1 || !p->res) {
        bg_error_raise(err, BG_ERR_ARGUMENT, w, "problem needs n >= 1 and a residual function");
        return NULL;
    }
    int n = p->n;
    if (check_problem(p, o, err) != BG_OK) return NULL;
    if (!(o->rtol >= 0) || (!o->atol_vec && !(o->atol >= 0)) ||
        (o->rtol == 0 && o->atol == 0 && !o->atol_vec)) {
        bg_error_raise(err, BG_ERR_ARGUMENT, w,
                       "tolerances must be >= 0 and not both zero (rtol %g, atol %g)", o->rtol,
                       o->atol);
        return NULL;
    }
    if (!(o->rtol < 1) || (!o->atol_vec && !isfinite(o->atol))) {
        bg_error_raise(err, BG_ERR_ARGUMENT, w,
                       "rtol must be below 1 and atol finite (rtol %g, atol %g)", o->rtol, o->atol);
        return NULL;
    }
    if (o->max_order < 0 || o->max_order > (o->method == DAE_MEBDF ? MAXORD : BDF_MAXORD)) {
        bg_error_raise(err, BG_ERR_ARGUMENT, w,
                       "max_order must be 0 (the method's largest) or 1..%d for %s (got %d)",
                       o->method == DAE_MEBDF ? MAXORD : BDF_MAXORD,
                       o->method == DAE_MEBDF ? "DAE_MEBDF" : "DAE_BDF", o->max_order);
        return NULL;
    }
    if (o->method != DAE_BDF && o->method != DAE_MEBDF) {
        bg_error_raise(err, BG_ERR_ARGUMENT, w,
                       "method must be DAE_BDF (0) or DAE_MEBDF (1) (got %d)", (int)o->method);
        return NULL;
    }
    if (o->mebdf_error < DAE_MEBDF_ERR_BDF || o->mebdf_error > DAE_MEBDF_ERR_KP1) {
        bg_error_raise(err, BG_ERR_ARGUMENT, w, "mebdf_error must be 0..2 (got %d)",
                       (int)o->mebdf_error);
        return NULL;
    }
    if (o->method == DAE_MEBDF && o->mebdf_error == DAE_MEBDF_ERR_KP1 && o->max_order > 5) {
        bg_error_raise(err, BG_ERR_ARGUMENT, w,
                       "mebdf_error = DAE_MEBDF_ERR_KP1 needs max_order <= 5 (got %d): its "
                       "error constants are known to k = 5",
                       o->max_order);
        return NULL;
    }
    if (o->newton_jac_age < 0 || (o->newton_jac_age > 0 && !(o->newton_dgmax > 0))) {
        bg_error_raise(err, BG_ERR_ARGUMENT, w,
                       "newton_jac_age = %d: must be >= 0, and > 0 only with newton_dgmax > 0 "
                       "(newton_dgmax = %g: the Newton matrix would not follow cj between "
                       "Jacobians)",
                       o->newton_jac_age, o->newton_dgmax);
        return NULL;
    }
    if (!(o->newton_dgmax >= 0 && o->newton_dgmax < 1)) {
        bg_error_raise(err, BG_ERR_ARGUMENT, w, "newton_dgmax = %g: must be in [0, 1)",
                       o->newton_dgmax);
        return NULL;
    }
    if (o->projection && (!p->cons || p->ncons < 1 || !p->cons_pattern)) {
        bg_error_raise(err, BG_ERR_ARGUMENT, w,
                       "projection needs position constraints (cons, ncons, cons_pattern)");
        return NULL;
    }
    if (o->h_max > 0 && o->h_min > o->h_max) {
        bg_error_raise(err, BG_ERR_ARGUMENT, w, "h_min = %g exceeds h_max = %g", o->h_min,
                       o->h_max);
        return NULL;
    }
    if (o->fixed_step && !(o->h_init > 0)) {
        bg_error_raise(err, BG_ERR_ARGUMENT, w, "fixed_step needs h_init > 0");
        return NULL;
    }
    if (p->jac && (!p->jac_y_pattern || !p->jac_yp_pattern)) {
        bg_error_raise(err, BG_ERR_ARGUMENT, w,
                       "an analytic Jacobian needs both its patterns (jac_y_pattern %s, "
                       "jac_yp_pattern %s); without a Jacobian the patterns are found from the "
                       "residual",
                       p->jac_y_pattern ? "given" : "NULL", p->jac_yp_pattern ? "given" : "NULL");
        return NULL;
    }
    /* nominal magnitudes scale atol, unless atol_vec is given (the one rule: bg_jaceval.c) */
    if (!o->atol_vec && bg_check_nominal(p, w, err) != BG_OK) return NULL;
    dae_solver *s = calloc(1, sizeof *s);
    if (!s) goto nomem;
    s->n = n;
    s->p = *p;
    s->o = *o;
    s->o.atol_vec = NULL;
    s->o.breakpoints = NULL;
    if (s->o.max_newton < 1) s->o.max_newton = 4;
    if (s->o.max_order == 0) /* the method's largest: MEBDF's as MEBDFI's drivers */
        s->o.max_order = s->o.method != DAE_MEBDF ? BDF_MAXORD
                         : s->o.mebdf_error == DAE_MEBDF_ERR_KP1 ? 5
                                                                 : MAXORD;
    if (s->o.max_steps < 1) s->o.max_steps = 100000;
    s->kind = malloc((size_t)n * sizeof *s->kind);
    s->atol = malloc((size_t)n * sizeof *s->atol);
    if (!s->kind || !s->atol) goto nomem;
    for (int i = 0; i < n; i++) {
        s->kind[i] = p->kind ? p->kind[i] : DAE_DIFF;
        if (p->kind && (s->kind[i] < DAE_DIFF || s->kind[i] > DAE_ALG2)) {
            bg_error_raise(err, BG_ERR_ARGUMENT, w, "kind[%d] = %d is not a dae_var_kind", i,
                           s->kind[i]);
            dae_free(&s);
            return NULL;
        }
        s->atol[i] = o->atol_vec ? o->atol_vec[i] : o->atol * (p->nominal ? p->nominal[i] : 1.0);
        if (!(s->atol[i] >= 0) || !isfinite(s->atol[i]) || (s->atol[i] == 0 && o->rtol == 0)) {
            bg_error_raise(err, BG_ERR_ARGUMENT, w,
                           "atol[%d] = %g: must be >= 0 (and > 0 if rtol = 0)", i, s->atol[i]);
            dae_free(&s);
            return NULL;
        }
        /* a tolerance that underflowed (atol times a tiny nominal) or is subnormal is no
         * tolerance: the weights 1 / (rtol |y| + atol) of an unknown at 0 become 1e100 */
        int under = o->atol_vec ? s->atol[i] > 0 && s->atol[i] < DBL_MIN
                                : o->atol > 0 && s->atol[i] < DBL_MIN;
        if (under) {
            char nb[32];
            if (o->atol_vec)
                bg_error_raise(err, BG_ERR_ARGUMENT, w,
                               "atol_vec[%d] = %g (%s) is below the smallest normal number "
                               "%g: give 0 or a normal number",
                               i, s->atol[i], bg_var_label(p, i, nb, sizeof nb), DBL_MIN);
            else if (p->nominal)
                bg_error_raise(err, BG_ERR_ARGUMENT, w,
                               "the nominal magnitude of %s is %g: atol * nominal = %g is below "
                               "the smallest normal number %g",
                               bg_var_label(p, i, nb, sizeof nb), p->nominal[i], s->atol[i],
                               DBL_MIN);
            else
                bg_error_raise(err, BG_ERR_ARGUMENT, w,
                               "atol = %g is below the smallest normal number %g: give 0 or a "
                               "normal number", o->atol, DBL_MIN);
            dae_free(&s);
            return NULL;
        }
    }
    if (p->names) {
        s->names = calloc((size_t)n, sizeof *s->names);
        if (!s->names) goto nomem;
        for (int i = 0; i < n; i++)
            if (p->names[i] && !(s->names[i] = strdup(p->names[i]))) goto nomem;
    }
    if (p->eq_names) {
        s->enames = calloc((size_t)n, sizeof *s->enames);
        if (!s->enames) goto nomem;
        for (int i = 0; i < n; i++)
            if (p->eq_names[i] && !(s->enames[i] = strdup(p->eq_names[i]))) goto nomem;
    }
    if (o->nbreakpoints > 0) {
        s->bkpt = malloc((size_t)o->nbreakpoints * sizeof *s->bkpt);
        if (!s->bkpt) goto nomem;
        memcpy(s->bkpt, o->breakpoints, (size_t)o->nbreakpoints * sizeof *s->bkpt);
        qsort(s->bkpt, (size_t)o->nbreakpoints, sizeof *s->bkpt, cmp_double);
        /* a time given twice is one breakpoint (the step lands there once) */
        s->nbkpt = 1;
        for (int k = 1; k < o->nbreakpoints; k++)
            if (s->bkpt[k] != s->bkpt[s->nbkpt - 1]) s->bkpt[s->nbkpt++] = s->bkpt[k];
    }
    /* Jacobian patterns: as given, or found from the residual at dae_init (dae_struct.c) */
    if (o->index2 == DAE_I2_REDUCE) {
        if (daei_red_create(s, p, o, err) != BG_OK) {
            dae_free(&s);
            return NULL;
        }
    } else if (p->jac_y_pattern && p->jac_yp_pattern) {
        s->Jy = sp_csc_copy(p->jac_y_pattern);
        s->Jyp = sp_csc_copy(p->jac_yp_pattern);
        if (!s->Jy || !s->Jyp) goto nomem;
        int r = daei_setup_structure(s, err);
        if (r != BG_OK) {
            dae_free(&s);
            return NULL;
        }
    } else {
        s->detect = 1; /* the given pattern, if any, joins the detected one */
    }
    if (p->cons && p->ncons > 0) {
        s->G = sp_csc_copy(p->cons_pattern);
        s->gv = malloc((size_t)p->ncons * sizeof *s->gv);
        s->gw = malloc((size_t)p->ncons * sizeof *s->gw);
        if (!s->G || !s->gv || !s->gw) goto nomem;
        s->aat_proj = aat_create(s->G, err);
        if (!s->aat_proj) {
            dae_free(&s);
            return NULL;
        }
    }
    for (int j = 0; j < NPHI; j++)
        if (!(s->phi[j] = calloc((size_t)n, sizeof(double)))) goto nomem;
    double **vecs[] = {&s->ewt,    &s->werr, &s->wdiff, &s->y,   &s->yp,
                       &s->ee,   &s->delta, &s->res,   &s->tmp, &s->tmp2, &s->typ,
                       &s->stab_e[0], &s->stab_e[1], &s->stab_e[2], &s->stab_e[3], &s->stab_e[4]};
    for (size_t v = 0; v < sizeof vecs / sizeof *vecs; v++)
        if (!(*vecs[v] = calloc((size_t)n, sizeof(double)))) goto nomem;
    /* the Newton weights are the error weights unless the index-2 ones are scaled by |h| */
    s->wnewt = s->o.newton_index2_scale_h ? calloc((size_t)n, sizeof(double)) : s->ewt;
    if (!s->wnewt) goto nomem;
    if (s->o.method == DAE_MEBDF && !(s->mb = calloc((size_t)MB_NVEC * n, sizeof(double))))
        goto nomem;
    if (p->nregimes > 0) {
        s->reg_jac = calloc((size_t)p->nregimes, sizeof(int));
        s->reg_now = calloc((size_t)p->nregimes, sizeof(int));
        if (!s->reg_jac || !s->reg_now) goto nomem;
    }
    if (p->nroots > 0) {
        s->glo = calloc((size_t)p->nroots, sizeof(double));
        s->ghi = calloc((size_t)p->nroots, sizeof(double));
        s->gmid = calloc((size_t)p->nroots, sizeof(double));
        s->rfound = calloc((size_t)p->nroots, sizeof(int));
        if (!s->glo || !s->ghi || !s->gmid || !s->rfound) goto nomem;
    }
    return s;
nomem:
    dae_free(&s);
    bg_error_raise(err, BG_ERR_MEMORY, w, "out of memory (n = %d)", n);
    return NULL;
}
