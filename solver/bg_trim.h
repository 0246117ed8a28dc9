/* A trim: the value of one parameter p for which a condition f(p) = 0 holds, where each value
 * of f costs a solve (a static equilibrium of the model built with p, and an output read there:
 * the ties' length of a crane until its tip stands at a radius). Used by the model files'
 * `trim:` (mdl_static) and by the crane's static start (crane_static_start): one algorithm, so
 * that the same model trimmed from the same start reaches the same parameter to the last bit.
 *
 * Method. First the secant method from p0 and p0 + h (h = 1e-4 of the bracket's width, towards
 * its inside): a caller states a value near the answer, and the solves near the answer are
 * cheap. When a secant step leaves the bracket [lo, hi], two values of f are equal, or 12 steps
 * do not meet the tolerance, the bracket itself is used: the Illinois variant of regula falsi
 * (M. Dowell and P. Jarratt, BIT 11 (1971) 168), the secant through the bracket's ends with the
 * value at an end that stays twice halved, which keeps the root bracketed and converges
 * superlinearly. It stops when |f| <= tol, or when the bracket is narrower than 1e-12 of its
 * first width (then DAE_CONV_FAIL). A bracket whose ends give f of one sign is refused
 * (DAE_CONV_FAIL, the two values in the result): the condition cannot be met there.
 *
 * The callback's status other than BG_OK stops the trim with that status (its message is the
 * callback's, through err). The last value of p evaluated is always the answer's (the secant's
 * converged iterate, the bracket's newest end): a caller that keeps what its last evaluation
 * built needs no extra solve. */
#ifndef BG_TRIM_H
#define BG_TRIM_H

#include "bg_api.h"
#include "bg_status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* f(p) into *f: BG_OK, or a status that stops the trim. */
typedef int (*dae_trim_fn)(void *ctx, double p, double *f, bg_error *err);

typedef struct dae_trim_options {
    double p0;     /* the first value tried; outside [lo, hi]: the bracket's middle */
    double lo, hi; /* the bracket, lo < hi, both finite */
    double tol;    /* |f| at most this: met (> 0) */
} dae_trim_options;

typedef struct dae_trim_result {
    double p, f;       /* the last value evaluated and its f (the answer when BG_OK) */
    double f_lo, f_hi; /* f at the bracket's ends, when the bracket was used (else NAN) */
    int evals;         /* evaluations of f */
    int bracketed;     /* 1: the secant gave up and the bracket was used */
} dae_trim_result;

/* BG_OK (|f(p)| <= tol), DAE_CONV_FAIL (f of one sign at the bracket's ends, or the bracket
 * collapsed without meeting tol), BG_ERR_ARGUMENT (no function, lo >= hi, a bound or tol not
 * finite, tol <= 0), or the callback's status. res may not be NULL. */
BG_API int dae_trim_solve(dae_trim_fn fn, void *ctx, const dae_trim_options *o,
                          dae_trim_result *res, bg_error *err);

#ifdef __cplusplus
}
#endif

#endif
