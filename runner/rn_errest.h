/* An estimate of the global error of a run: a companion run of the same problem at tolerances K
 * times tighter (rtol / K, atol / K; K = 100 by default), advanced in lockstep with the first
 * run over its output times, and per output column the largest |out(tol) - out(tol / K)|.
 *
 * Method: reintegration at a reduced tolerance. Variable-step codes aim at tolerance
 * proportionality, a global error e(tol) roughly proportional to tol; then
 * out(tol) - out(tol/K) = e(tol) - e(tol/K) = e(tol) (1 - 1/K), and the difference estimates the
 * first run's error. Shampine, Gladwell and Thompson (Solving ODEs with MATLAB, Cambridge 2003)
 * recommend this check of a computed solution. It is an estimate, not a bound: it is as good as
 * the proportionality, which BDF codes keep loosely (the order and the steps change with the
 * tolerance) and which fails for what the error test does not control (unknowns excluded from
 * it, index-2 unknowns, an error set by the stability guard's damping or by interpolation).
 * bench/bench_errest.h measures the ratio of the estimate to the true error on the problem
 * collection and the crane.
 *
 * Users: the programs' --error-estimate (crane and bgsim, through rn_estimate.c, rn_run.h) and
 * the bench (bench/bench_errest.c).
 *
 * The companion shares the problem: its residual, Jacobian and user data are called from the
 * companion's solver between the first run's steps, never at the same time, and must not keep a
 * state between calls (a bond-graph model does not). The first run's outputs at each time are
 * handed over by the caller (rn_errest_add); the companion's are computed by the same output
 * function. Nothing is printed; failures are statuses with a message. */
#ifndef RN_ERREST_H
#define RN_ERREST_H

#include <signal.h>

#include "bg_dae.h"

#ifdef __cplusplus
extern "C" {
#endif

#define RN_ERREST_FACTOR 100.0 /* the default K */
#define RN_ERREST_MAX_FACTOR 1e12
/* rn_errest_add: the stop flag was set before the companion reached the time */
#define RN_ERREST_STOPPED 100

/* Output columns of a state: fills out[0 .. nout-1]. */
typedef void (*rn_errest_out_fn)(void *ctx, double t, const double *y, const double *yp,
                                 double *out);

typedef struct rn_errest_spec {
    const dae_problem *p; /* the first run's problem */
    const dae_options *o; /* and options: the companion's are these with rtol, atol and atol_vec
                             divided by factor */
    double factor;        /* K, in (1, RN_ERREST_MAX_FACTOR]; 0: RN_ERREST_FACTOR */
    double t0;            /* the start: t0, y0, yp0 (n values each; yp0 may be NULL: 0) */
    const double *y0, *yp0;
    int consistent;       /* 1: dae_consistent_init from it at the companion's tolerances */
    int nout;             /* output columns (with out NULL: the unknowns, nout = n) */
    rn_errest_out_fn out; /* NULL: the outputs are y itself */
    void *ctx;
    const volatile sig_atomic_t *stop; /* looked at between the companion's steps; NULL: none */
} rn_errest_spec;

/* Per output column, over the times added: the largest |out1 - out2| (NAN when the two were
 * never both finite there) and the time of the first largest, and the largest |out1|. */
typedef struct rn_errest_col {
    double max_err, t_at, max_abs;
} rn_errest_col;

typedef struct rn_errest rn_errest;

/* The companion, started (dae_create, dae_init and, if asked, dae_consistent_init). NULL only
 * for a NULL or bad spec (a factor out of range, no problem, nout < 1; BG_ERR_ARGUMENT) or for
 * memory (BG_ERR_MEMORY), with the reason in err (may be NULL). A companion that cannot start
 * is returned all the same, failed (rn_errest_status < 0): the first run goes on without it. */
rn_errest *rn_errest_create(const rn_errest_spec *spec, bg_error *err);
void rn_errest_free(rn_errest **e);

/* The first run's outputs out1 (nout values) at time t, the times ascending: the companion is
 * advanced to t (step by step, the stop flag looked at between two steps), its outputs there
 * computed and compared. BG_OK; RN_ERREST_STOPPED (t not covered; the companion can go on
 * later); the companion's failure (< 0, the first one again on every later call: the times
 * from then on are not covered) or BG_ERR_ARGUMENT (e or out1 NULL, t behind the last time). */
int rn_errest_add(rn_errest *e, double t, const double *out1);

/* BG_OK while the companion keeps up, else its failure; the message ("" while none). */
int rn_errest_status(const rn_errest *e);
const char *rn_errest_message(const rn_errest *e);
/* Times covered (compared) and the last of them (NAN if none). */
long rn_errest_count(const rn_errest *e);
double rn_errest_last(const rn_errest *e);
/* Column j (0 .. nout-1) over the times covered; NULL out of range. */
const rn_errest_col *rn_errest_column(const rn_errest *e, int j);
/* The companion's tolerances (rtol, atol: the scalar), its factor and its solver's statistics
 * (NULL if it was never created). */
void rn_errest_tolerances(const rn_errest *e, double *rtol, double *atol, double *factor);
const dae_stats *rn_errest_stats(const rn_errest *e);

#ifdef __cplusplus
}
#endif
#endif
