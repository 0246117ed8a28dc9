/* The error estimate of crane --error-estimate (runner/rn_errest.h: a companion run at rtol / K
 * and atol / K, K = 100, compared with the run at every output time) against the true error, on
 * the problems of the collection and on the crane (bench --error-estimate; bench --quick runs a
 * small version).
 *
 * Each run is ours (bgdae-klu, the options of bench_case.h's runs) from the case's consistent
 * start, the companion from the same start with the tolerances of the case's convention at
 * rtol / K (atol = factor * rtol, pump's vector). Measures, with the denominators of the test
 * set's scd so that estimate and truth are compared on one scale:
 *   a problem of the collection: at tend, over the scored components that are not index 2 and
 *     whose reference is not 0, max_i |y_i - y_i(rtol/K)| / |yref_i| (the estimate) and
 *     max_i |y_i - yref_i| / |yref_i| (the true error, against the published reference or the
 *     exact solution);
 *   the crane: over output times every crane_step (0.01 s) up to the case's horizon,
 *     per output column the largest |out - out(rtol/K)| and the largest |out - out_ref|, where
 *     out_ref is our run at rtol_ref (1e-11; only tolerances at least 1000 times looser are
 *     checked), and over the columns of the crane's scd (theta, omega, tip and load positions,
 *     rope force, line pressures) the largest of these relative to the column's largest
 *     |out_ref|, as the crane program's max_rel_error.
 * The ratio estimate / true error is reported per problem and tolerance; within a factor 10 (0.1
 * <= ratio <= 10) is the target, the others are flagged. */
#ifndef BG_BENCH_ERREST_H
#define BG_BENCH_ERREST_H

#include <stdio.h>

#include "bench_case.h"

typedef struct bench_errest_config {
    const double *rtols; /* the tolerances, nr of them */
    int nr;
    double factor;         /* K (0: RN_ERREST_FACTOR, 100) */
    double crane_rtol_ref; /* the crane's reference tolerance (0: 1e-11) */
    double crane_step;     /* the crane's output times: every crane_step s (0: 0.01) */
} bench_errest_config;

/* Runs the check on the cases (the crane is the case whose name is "crane"); writes
 * error_estimate.csv into dir (checked, bench_util.h) and a report section into rep. Returns
 * the number of failed runs (a run of ours that did not reach tend; the companion's failures are
 * rows of the file, not counted). */
int bench_errest(const char *dir, FILE *rep, bench_case **cases, int nc,
                 const bench_errest_config *cfg);

#endif
