/* J. R. Cash's MEBDFI (and MEBDFDAE, the pendulum) beside our solver: the published end
 * statistics of the codes' test drivers (docs/mebdfi_stats.md has the figures, their source and
 * the drivers' conventions) in a table, and runs of our solver (bgdae-klu) with the drivers'
 * tolerance conventions at the tolerances where both exist. */
#ifndef BG_BENCH_MEBDFI_H
#define BG_BENCH_MEBDFI_H

#include <stdio.h>

#include "bench_case.h"

/* One published run: the driver's rtol and (printed) atol, the code's counters and its own
 * "number of correct digits" (see docs/mebdfi_stats.md for what each driver measures). */
typedef struct mebdfi_stat {
    const char *problem; /* our name of the problem */
    double rtol, atol;
    long steps, failed, res, jac, lu, backsolves;
    int max_order;
    double scd;
} mebdfi_stat;

/* The published rows (runs that failed are not in it); *n receives their number. */
const mebdfi_stat *bench_mebdfi_table(int *n);

/* For each case of cases[0..nc-1] with published figures and each rtol of rtols[0..nr-1] that
 * has a published row (equal to 1e-6 relative), one run of bgdae-klu with the driver's tolerances
 * (atol = rtol, pump: its vector) from the case's consistent start; writes mebdfi_compare.csv
 * into dir and a report section into rep (the published and our steps, failed steps, residual
 * evaluations and Jacobians with their ratios). Returns the number of failed runs of ours (a CSV
 * that cannot be written is said and counted by bench_file_close, bench_util.h). */
int bench_mebdfi_compare(const char *dir, FILE *rep, bench_case *const *cases, int nc,
                         const double *rtols, int nr);

#endif
