/* The stability guard (options.stability_guard, solver/dae_stab.c) on the collection's undamped
 * oscillatory problems, by exact step counts. Step counts on these problems swing by factors of
 * 2 to 8 when rtol changes by 1 % (the guard's choices, and the trap itself, depend on the
 * path), so each figure is the median over rtol x {1, 1.01, 1.02, 1.03, 1.05}:
 *   - rotating_beam (free axial modes, excited by the spin-up, that hold BDF orders 3..5 at their
 *     stability limit): with the guard, steps within a factor 2 of what max order 2 takes (BDF2
 *     damps every fast mode: the yardstick of what dissipation can gain) at rtol 1e-4 .. 1e-8
 *     (before order 2 was the guard's floor, it took 3 times order 2's steps at 1e-5, half of
 *     them at order 1);
 *   - osc_chain (fast modes that carry 1 to 2 % of the answer and must be resolved: lowering does
 *     not pay): with the guard, steps within a factor 2 of the usual order selection, where max
 *     order 2 takes 5 to 25 times as many (the guard measures which policy covers time faster
 *     and keeps the usual orders).
 * The runs go through the benchmark's runner (bench/bench_case.c). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_case.h"
#include "problems.h"
#include "tap.h"

/* steps of bgdae-klu on p at rtol: guard 1 on, -1 off; max_order 0 the default */
static long run(const bp_problem *p, double rtol, int guard, int max_order)
{
    bench_case bc;
    if (bench_case_from_problem(&bc, p) != 0) return -1;
    char msg[BG_MESSAGE_SIZE];
    long steps = -1;
    run_out o;
    if (bench_case_start(&bc, rtol, msg, sizeof msg) == 0 && bench_run_alloc(&o, bc.n) == 0) {
        run_opts ro = {0};
        ro.rtol = rtol;
        ro.guard = guard;
        ro.max_order = max_order;
        ro.max_steps = 3000000;
        bench_run(&bc, bench_solver_find("bgdae-klu"), &ro, &o);
        if (o.status >= 0) steps = o.steps;
        bench_run_free(&o);
    }
    bench_case_free(&bc);
    return steps;
}

static int cmp_long(const void *a, const void *b)
{
    long x = *(const long *)a, y = *(const long *)b;
    return (x > y) - (x < y);
}

/* median steps over the rtol factors; -1 if a run failed */
static long median_steps(const bp_problem *p, double rtol, int guard, int max_order)
{
    static const double f[5] = {1.0, 1.01, 1.02, 1.03, 1.05};
    long v[5];
    for (int i = 0; i < 5; i++)
        if ((v[i] = run(p, rtol * f[i], guard, max_order)) < 0) return -1;
    qsort(v, 5, sizeof *v, cmp_long);
    return v[2];
}

int main(void)
{
    const bp_problem *beam = bp_find("rotating_beam"), *chain = bp_find("osc_chain");
    if (!tap_ok(beam && chain, "the problems are in the collection")) return tap_done();
    const double rt[] = {1e-4, 1e-5, 1e-6, 1e-7, 1e-8};
    for (int i = 0; i < 5; i++) {
        long g = median_steps(beam, rt[i], 1, 0), o2 = median_steps(beam, rt[i], -1, 2),
             usual = median_steps(beam, rt[i], -1, 0);
        tap_ok(g > 0 && o2 > 0 && g <= 2 * o2,
               "rotating_beam, rtol %g: median steps with the guard %ld, max order 2 %ld (usual "
               "orders %ld)",
               rt[i], g, o2, usual);
    }
    for (int i = 1; i < 3; i++) {
        long g = median_steps(chain, rt[i], 1, 0), usual = median_steps(chain, rt[i], -1, 0);
        tap_ok(g > 0 && usual > 0 && g <= 2 * usual,
               "osc_chain, rtol %g: lowering does not pay and the guard keeps the usual orders: "
               "median steps %ld against %ld",
               rt[i], g, usual);
    }
    return tap_done();
}
