/* The stability guard on the collection's undamped oscillatory problems (osc_chain,
 * rotating_beam): steps of bgdae-klu with the usual order selection, with the stability guard
 * (options.stability_guard, solver/dae_stab.c) and with the order capped at 2 (BDF2, A-stable:
 * what damping every fast mode costs), at each tolerance of the run. */
#ifndef BG_BENCH_OSC_H
#define BG_BENCH_OSC_H

#include <stdio.h>

#include "bench_case.h"

/* For each case of cases[0..nc-1] that is one of the oscillatory problems, three runs per rtol:
 * writes osc_guard.csv into dir and a section into rep, flagging a guard run that takes more
 * than twice the steps of the order-2 run ("GUARD > 2x ORDER 2") and a guard series whose steps
 * grow as the tolerance loosens. Returns the number of failed runs with the usual orders or the
 * guard (max order 2 is the yardstick: it may reach the step limit on problems whose fast modes
 * must be resolved). */
int bench_osc_guard(const char *dir, FILE *rep, bench_case *const *cases, int nc,
                    const double *rtols, int nr);

#endif
