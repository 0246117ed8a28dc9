/* The stability guard on the undamped oscillatory problems (bench_osc.h). */
#include "bench_osc.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bench_util.h"

enum { OSC_USUAL, OSC_GUARD, OSC_ORDER2, OSC_NMODE };
static const char *const mode_name[OSC_NMODE] = {"usual orders", "stability guard",
                                                 "max order 2"};

static int is_osc(const bench_case *bc)
{
    for (int i = 0; i < bp_osc_count(); i++)
        if (bc->bp == bp_osc_get(i)) return 1;
    return 0;
}

int bench_osc_guard(const char *dir, FILE *rep, bench_case *const *cases, int nc,
                    const double *rtols, int nr)
{
    int any = 0;
    for (int c = 0; c < nc; c++)
        any |= is_osc(cases[c]);
    if (!any || nr <= 0) return 0;
    bench_file bf;
    FILE *csv = bench_file_open(&bf, dir, "osc_guard.csv") == 0 ? bf.f : NULL;
    if (csv)
        fprintf(csv, "problem,rtol,mode,status,steps,rejected,newton,jacobians,scd,flag\n");
    fprintf(rep,
            "## The stability guard on the undamped oscillatory problems\n\n"
            "bgdae-klu with the usual order selection, with the stability guard "
            "(options.stability_guard: orders 3..5 lowered to 2 where a detected undamped "
            "oscillation holds them at their stability limit, solver/dae_stab.c) and with the "
            "order capped at 2 (BDF2 damps every fast mode), from the same consistent start "
            "(osc_guard.csv). GUARD > 2x ORDER 2: the guard took more than twice the steps of "
            "max order 2; MORE STEPS: the guard took more steps than at the next tighter "
            "tolerance.\n\n"
            "| problem | rtol | steps, usual | steps, guard (scd) | steps, max order 2 (scd) | "
            "guard / order 2 | flag |\n|---|---|---|---|---|---|---|\n");
    const solver_def *ours = bench_solver_find("bgdae-klu");
    int fails = 0;
    for (int c = 0; c < nc; c++) {
        bench_case *bc = cases[c];
        if (!is_osc(bc)) continue;
        long prev_guard = -1; /* guard steps at the previous (tighter) tolerance */
        /* tolerances tightest first so that MORE STEPS compares with the tighter one */
        for (int jr = nr - 1; jr >= 0; jr--) {
            double rtol = rtols[jr];
            long steps[OSC_NMODE] = {0};
            double scd[OSC_NMODE] = {0};
            int ok[OSC_NMODE] = {0};
            for (int m = 0; m < OSC_NMODE; m++) {
                char msg[BG_MESSAGE_SIZE];
                run_opts ro = {0};
                ro.rtol = rtol;
                ro.guard = m == OSC_GUARD ? 1 : -1;
                ro.max_order = m == OSC_ORDER2 ? 2 : 0;
                ro.max_steps = 5000000;
                run_out o;
                if (bench_run_alloc(&o, bc->n) != 0) return fails + 1;
                if (bench_case_start(bc, rtol, msg, sizeof msg) == 0) bench_run(bc, ours, &ro, &o);
                else {
                    o.status = -1;
                    snprintf(o.msg, sizeof o.msg, "%s", msg);
                }
                double atol;
                bench_case_atol(bc, rtol, &atol, NULL);
                bp_score sc = {0};
                ok[m] = o.status >= 0;
                if (ok[m] && bc->score) bc->score(bc, o.y, o.yp, rtol, atol, &sc);
                if (!ok[m] && m != OSC_ORDER2) fails++; /* order 2 is the yardstick only */
                steps[m] = o.steps;
                scd[m] = ok[m] ? sc.scd : NAN;
                char flag[64] = "";
                if (m == OSC_GUARD && ok[m]) {
                    if (prev_guard >= 0 && o.steps > prev_guard) snprintf(flag, sizeof flag, "MORE STEPS");
                    prev_guard = o.steps;
                }
                if (csv)
                    fprintf(csv, "%s,%.0e,%s,%d,%ld,%ld,%ld,%ld,%.2f,%s\n", bc->name, rtol,
                            mode_name[m], o.status, o.steps, o.rejected, o.newton, o.jac, scd[m],
                            flag);
                bench_run_free(&o);
            }
            double ratio = ok[OSC_GUARD] && ok[OSC_ORDER2] && steps[OSC_ORDER2] > 0
                               ? (double)steps[OSC_GUARD] / (double)steps[OSC_ORDER2]
                               : NAN;
            fprintf(rep, "| %s | %.0e | %ld%s | %ld (%.2f)%s | %ld (%.2f)%s | %.2f | %s |\n",
                    bc->name, rtol, steps[OSC_USUAL], ok[OSC_USUAL] ? "" : " FAILED",
                    steps[OSC_GUARD], scd[OSC_GUARD], ok[OSC_GUARD] ? "" : " FAILED",
                    steps[OSC_ORDER2], scd[OSC_ORDER2], ok[OSC_ORDER2] ? "" : " FAILED", ratio,
                    ratio > 2 ? "GUARD > 2x ORDER 2" : "");
        }
    }
    fprintf(rep, "\n");
    if (csv) bench_file_close(&bf);
    return fails;
}
