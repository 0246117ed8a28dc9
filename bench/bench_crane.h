/* The crane (crane/crane_model.h) in the benchmark harness: as a case of the work-precision runs
 * (the paper scene over a short horizon, reference from our own run at rtol 1e-11 checked against
 * IDA at the same tolerance), the scaling series over the number of boom elements, and the full
 * horizon against IDA. The real-time check is bench_realtime.h. */
#ifndef BG_BENCH_CRANE_H
#define BG_BENCH_CRANE_H

#include <stdio.h>

#include "bench_case.h"
#include "crane_model.h"

/* The crane of scene s as a case over [0, tend] (the scene's t_end is set to tend): built,
 * settled into its static equilibrium if settle (else the scene's geometric start), the model's
 * residual and Jacobian (bgr_dae_problem), its breakpoints, exclude_alg as crane/crane.c runs
 * it, atol = rtol. Accuracy: scd over the outputs theta, omega, tip and load positions, rope
 * force and line pressures (crane_outputs; relative errors as the test set's scd), mescd over
 * the differential unknowns, the index-2 unknowns apart (scd2 over those above 1e-6 of the
 * largest). Drift: the hinge mismatch (output constraint_drift). No reference yet (yref NULL).
 * Our stability guard off (bc->stability_guard 0): a caller that runs the crane as the crane
 * program does sets it from the scene. The Newton settings (newton_dgmax, newton_jac_age,
 * newton_index2_scale_h) as the scene states them (crane_solver_setup). 0, or a negative
 * status with the message in msg. */
/* settle: 0 the geometric start, 1 the static start (crane_settle), BENCH_SETTLE_DAMPED the
 * damped settling run the crane started from before the static solver (crane_settle_damped) */
#define BENCH_SETTLE_DAMPED 2
int bench_crane_case(bench_case *bc, const crane_scene *s, int settle, double tend,
                     const char *name, char *msg, size_t msz);

/* The model of a crane case (to change its start, e.g. move the load). */
bgr_model *bench_crane_model(const bench_case *bc);

/* Reference of a crane case at rtol_ref: ours (bgdae-klu) from the case's consistent start;
 * with check_ida, IDA-KLU at the same tolerance, scored against it (its scd and mescd written
 * into bc->ref_source with the steps of both). 0, or a negative status (message in msg). */
int bench_crane_reference(bench_case *bc, double rtol_ref, int check_ida, char *msg, size_t msz);

/* Scaling series: for each element count in elems (nel of them), the paper scene from its
 * static start (settled, not timed), ours (bgdae-klu) at rtol = atol = 1e-6 for a warm-up
 * of `skip` steps, then `steps` timed steps (fewer, at least 5, once they have taken cpu_cap
 * seconds of CPU; at most up to t_max): CPU time per step, the wall time per step with its
 * residual, Jacobian and linear-algebra parts, total time, unknowns. Log-log least-squares slopes
 * of the time per step against the unknowns and against the elements. Writes scaling.csv into
 * dir and a report section into rep; *slope_n, *slope_el receive the slopes (NAN if < 2 points).
 * Returns the number of failed runs. The CSV files of these functions are checked (bench_file,
 * bench_util.h): a failure is said and counted there, the runs go on. */
int bench_crane_scaling(const char *dir, FILE *rep, const int *elems, int nel, int skip, int steps,
                        double t_max, double cpu_cap, double *slope_n, double *slope_el);

/* The crane over its scene's full t_end (paper-undamped: 20 s) against IDA: the scene s (named
 * scene_name in the report) from its static equilibrium if it asks for it, consistent start at
 * rtol 1e-10, reference: ours (bgdae-klu) at rtol_ref (atol = the scene's atol / rtol times
 * rtol); then ours and IDA-KLU at each of rtols (nr of them, atol likewise), IDA restarted at
 * each breakpoint from values made consistent by dae_consistent_init (run_opts
 * ida_consistent_restart), one run each: status, time reached, steps, rejected steps, Newton
 * iterations, Jacobians, CPU time, scd over the outputs and mescd over the differential
 * unknowns against the reference. Rows go to the file csv in dir as each run ends (flushed), a
 * report section into rep. Returns the number of failed runs of ours (the reference included). */
/* IDA's Newton iterations per attempt in the full-horizon series (IDASetMaxNonlinIters; IDA's
 * default is 4): the most ours takes (solver/dae_nls.c: options.max_newton, 4, and up to twice
 * that on a matrix of the step itself while the rate, 0.5 or better, says it converges; IDA
 * has no such extension). On the damped paper scene over 20 s (KLU with partial pivoting,
 * bench_ida_klu) 4 takes as many or more steps and CPU: 2 388 steps against 1 862 with 8 at
 * rtol 1e-4, 13 719 against 13 538 at 1e-8. (With KLU's default pivot tolerance and 4, IDA was
 * held at h = 3e-6 s there from rtol 1e-4 on; with 8 from 1e-5 on.) */
#define BENCH_IDA_MAX_NEWTON 8

/* The series' settings: the tolerances (nr of them), the reference's, the runs of each solver
 * and tolerance (reps >= 1: the CPU time their median; the counts are those of one run, the
 * same in each), and IDA's run_opts ida_klu_tol, ida_scalar_atol and ida_newton_diag
 * (bench_case.h; the diagnosis costs IDA time: not for timing). */
typedef struct bench_full_opts {
    const double *rtols;
    int nr;
    double rtol_ref;
    int reps;
    double ida_klu_tol;
    int ida_scalar_atol;
    int ida_newton_diag; /* run_opts.ida_newton_diag: a report line per IDA run */
    int ida_index2_h;    /* run_opts.ida_index2_h */
    int max_order;       /* run_opts.max_order of bgdae-klu's runs (0: the default) */
} bench_full_opts;

int bench_crane_full(const char *dir, const char *csv, FILE *rep, const crane_scene *s,
                     const char *scene_name, const bench_full_opts *fo);

#endif
