/* The error estimate by a companion run at tighter tolerances (rn_errest.h). */
#include "rn_errest.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

struct rn_errest {
    dae_solver *s;
    int n, nout;
    rn_errest_out_fn out;
    void *ctx;
    const volatile sig_atomic_t *stop;
    double rtol, atol, factor;
    double *y, *yp, *out2, *atolv;
    rn_errest_col *col;
    long count;
    double last;
    int status;
    char message[BG_MESSAGE_SIZE + 64];
};

static int fail(rn_errest *e, int status, const char *what, const char *msg)
{
    e->status = status;
    snprintf(e->message, sizeof e->message, "%s: %.*s", what, BG_MESSAGE_SIZE, msg);
    return status;
}

rn_errest *rn_errest_create(const rn_errest_spec *sp, bg_error *err)
{
    if (!sp || !sp->p || !sp->o || !sp->y0 || sp->p->n < 1 || (sp->out && sp->nout < 1)) {
        bg_error_raise(err, BG_ERR_ARGUMENT, "rn_errest_create",
                       "a problem, its options, a start and nout >= 1 outputs are needed");
        return NULL;
    }
    double K = sp->factor == 0 ? RN_ERREST_FACTOR : sp->factor;
    if (!(K > 1 && K <= RN_ERREST_MAX_FACTOR)) {
        bg_error_raise(err, BG_ERR_ARGUMENT, "rn_errest_create",
                       "the factor of the tolerances is %g: it must lie in (1, %g]", K,
                       RN_ERREST_MAX_FACTOR);
        return NULL;
    }
    rn_errest *e = calloc(1, sizeof *e);
    int n = sp->p->n, nout = sp->out ? sp->nout : n;
    if (e) {
        e->y = malloc(2 * (size_t)n * sizeof *e->y);
        e->out2 = malloc((size_t)nout * sizeof *e->out2);
        e->col = malloc((size_t)nout * sizeof *e->col);
        e->atolv = sp->o->atol_vec ? malloc((size_t)n * sizeof *e->atolv) : NULL;
    }
    if (!e || !e->y || !e->out2 || !e->col || (sp->o->atol_vec && !e->atolv)) {
        rn_errest_free(&e);
        bg_error_raise(err, BG_ERR_MEMORY, "rn_errest_create", "out of memory");
        return NULL;
    }
    e->yp = e->y + n;
    e->n = n;
    e->nout = nout;
    e->out = sp->out;
    e->ctx = sp->ctx;
    e->stop = sp->stop;
    e->factor = K;
    e->last = NAN;
    for (int j = 0; j < nout; j++)
        e->col[j] = (rn_errest_col){NAN, NAN, 0};
    dae_options o = *sp->o;
    o.rtol /= K;
    o.atol /= K;
    if (sp->o->atol_vec) {
        for (int i = 0; i < n; i++)
            e->atolv[i] = sp->o->atol_vec[i] / K;
        o.atol_vec = e->atolv;
    }
    e->rtol = o.rtol;
    e->atol = o.atol;
    bg_error cerr = {0};
    e->s = dae_create(sp->p, &o, &cerr);
    if (!e->s) {
        fail(e, cerr.status < 0 ? cerr.status : BG_ERR_ARGUMENT, "creating the solver",
             cerr.message);
        return e;
    }
    int rc = dae_init(e->s, sp->t0, sp->y0, sp->yp0);
    if (rc == BG_OK && sp->consistent) rc = dae_consistent_init(e->s);
    if (rc == DAE_WARNING) rc = BG_OK; /* found; the warning stays in dae_get_warning */
    if (rc != BG_OK)
        fail(e, rc, sp->consistent ? "consistent initial values" : "the start",
             dae_get_error(e->s)->message);
    return e;
}

void rn_errest_free(rn_errest **e)
{
    if (!e || !*e) return;
    dae_free(&(*e)->s);
    free((*e)->y);
    free((*e)->out2);
    free((*e)->col);
    free((*e)->atolv);
    free(*e);
    *e = NULL;
}

/* The companion's state at t, once it has stepped to t or beyond: interpolated in its last step
 * (dae_solve_to without a step). Where t falls in the round-off gap just behind a restart at a
 * jump (the last step starts after t by at most 1e-9 |t|), the values where that step starts,
 * as the crane program takes them for its rows. */
static int state_at(rn_errest *e, double t, double *tret)
{
    if (dae_get_stats(e->s)->steps == 0) { /* the start itself */
        *tret = t;
        return dae_dense(e->s, t, e->y, e->yp);
    }
    int rc = dae_solve_to(e->s, t, tret, e->y, e->yp);
    if (rc == BG_ERR_ARGUMENT) {
        double t0 = dae_current_time(e->s) - dae_get_stats(e->s)->h_last;
        if (t0 > t && t0 - t <= 1e-9 * fmax(1.0, fabs(t)) &&
            dae_dense(e->s, t0, e->y, e->yp) == 0) {
            *tret = t0;
            rc = DAE_SUCCESS;
        }
    }
    return rc < 0 ? rc : BG_OK;
}

int rn_errest_add(rn_errest *e, double t, const double *out1)
{
    if (!e || !out1 || !(t >= e->last || isnan(e->last))) return BG_ERR_ARGUMENT;
    if (e->status < 0) return e->status;
    double tret = t;
    while (dae_current_time(e->s) < t) {
        if (e->stop && *e->stop) return RN_ERREST_STOPPED;
        int rc = dae_step(e->s, t, &tret, NULL, NULL); /* the state: state_at */
        if (rc < 0) {
            char msg[BG_MESSAGE_SIZE + 64];
            snprintf(msg, sizeof msg, "%.*s (%s)", BG_MESSAGE_SIZE, dae_get_error(e->s)->message,
                     dae_return_name(rc));
            return fail(e, rc, "the run at the tighter tolerances", msg);
        }
    }
    int rc = state_at(e, t, &tret);
    if (rc < 0)
        return fail(e, rc, "the run at the tighter tolerances", dae_get_error(e->s)->message);
    if (e->out)
        e->out(e->ctx, tret, e->y, e->yp, e->out2);
    else
        memcpy(e->out2, e->y, (size_t)e->n * sizeof *e->out2);
    for (int j = 0; j < e->nout; j++) {
        rn_errest_col *c = &e->col[j];
        double a = out1[j], b = e->out2[j];
        if (isfinite(a) && fabs(a) > c->max_abs) c->max_abs = fabs(a);
        if (!isfinite(a) || !isfinite(b)) continue;
        double d = fabs(a - b);
        if (isnan(c->max_err) || d > c->max_err) {
            c->max_err = d;
            c->t_at = t;
        }
    }
    e->count++;
    e->last = t;
    return BG_OK;
}

int rn_errest_status(const rn_errest *e)
{
    return e ? e->status : BG_ERR_ARGUMENT;
}

const char *rn_errest_message(const rn_errest *e)
{
    return e ? e->message : "";
}

long rn_errest_count(const rn_errest *e)
{
    return e ? e->count : 0;
}

double rn_errest_last(const rn_errest *e)
{
    return e ? e->last : NAN;
}

const rn_errest_col *rn_errest_column(const rn_errest *e, int j)
{
    return e && j >= 0 && j < e->nout ? &e->col[j] : NULL;
}

void rn_errest_tolerances(const rn_errest *e, double *rtol, double *atol, double *factor)
{
    if (rtol) *rtol = e ? e->rtol : NAN;
    if (atol) *atol = e ? e->atol : NAN;
    if (factor) *factor = e ? e->factor : NAN;
}

const dae_stats *rn_errest_stats(const rn_errest *e)
{
    return e ? dae_get_stats(e->s) : NULL;
}
