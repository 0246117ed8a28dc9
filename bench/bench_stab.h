/* The stability suite of the benchmark harness: extreme tolerances, stiff problems, a start off
 * the constraint manifold, kinks with and without breakpoints, the Brenan-Campbell-Petzold
 * index-2 problem, and the crane at its extremes (tolerances 1e-2 and 1e-12, a boom 1000 times
 * stiffer, 512 boom elements, undamped boom modes over ten times the horizon, a near-zero load
 * mass, the rope going slack, the reference's kinks with and without breakpoints, a step in the
 * reference, a start off the constraint manifold). Every case runs in a child process under a
 * time limit, so that a crash or a hang is reported as such; each ends
 *   "solved": the error against its reference within 1000 tolerances (the global error of long
 *     stiff runs exceeds the local tolerance by some hundreds),
 *   "solved, converging": above 1000 tolerances, but the same run at rtol / 100 cuts the error
 *     at least tenfold (the crane's stiff pressures carry global errors of a few thousand local
 *     tolerances at rtol 1e-6),
 *   "stopped with a diagnostic" (the solver's message), or "WRONG" / "CRASHED" / "TIME LIMIT".
 * Our solver (bgdae-klu) only. --quick leaves out the 512-element crane (its factorizations of
 * 19 000 unknowns take about a second each). */
#ifndef BG_BENCH_STAB_H
#define BG_BENCH_STAB_H

#include <stdio.h>

#include "crane_model.h"

typedef struct stab_config {
    int quick;                /* shorter crane horizons, fewer costly references */
    double crane_horizon;     /* s, the crane cases' horizon (the long case: ten times it) */
    double time_limit;        /* s of wall time per case */
    const crane_scene *scene; /* the crane's base scene (paper) */
    const char *filter;       /* run only the cases whose name contains it (NULL: all) */
} stab_config;

/* Runs the suite: stability.csv into dir (a failure to write it is said and counted by
 * bench_file_close, bench_util.h; the suite runs on), a report section into rep. Returns the
 * number of cases that ended WRONG, CRASHED, at the time limit or could not be set up; *crashed
 * receives the number of crashes (a child ended by a signal other than the time limit's). */
int bench_stability(const char *dir, FILE *rep, const stab_config *cfg, int *crashed);

#endif
