/* The benchmark harness: error against run time for our solver and SUNDIALS IDA on the problem
 * collection (bench/problems.c) and the crane, the crane's scaling over its boom elements and its
 * real-time check, and a stability suite of stiff and extreme cases.
 *
 *   bench [--problems LIST|none] [--solvers LIST] [--rtols LIST] [--repeat K] [--stability]
 *         [--quick] [--out DIR] [--crane-horizon T] [--crane-realtime K] [--scaling LIST|none]
 *         [--crane-scene FILE] [--stability-filter TEXT] [--strict] [--crane-full]
 *         [--crane-full-scene FILE] [--crane-full-rtols LIST] [--error-estimate] [--help]
 *         [--newton-dgmax G]
 *
 * Problems (default: all): ap102, pendulum2, robertson, vdp_scaled, hires, lin2, smooth_ode,
 * kinks, the IVP Test Set's crank, pump, transamp, chemakzo, nand, the undamped oscillatory
 * osc_chain and rotating_beam (bench/problems.h), and crane:
 * the paper scene (crane_scene_default, or --crane-scene FILE) from its static equilibrium over
 * [0, T] (--crane-horizon, default 1 s, --quick 0.1 s), reference: our own run at rtol 1e-11
 * checked against IDA-KLU at the same tolerance (bench_crane.h). Solvers (default: all):
 * bgdae-klu, bgdae-klu-scaleh, bgdae-dense, bgdae-dense-scaleh (ours with each index-2 error
 * policy on KLU and on dense LU), ida-klu, ida-dense; dense LU on a model of more than 300
 * unknowns (the crane) runs at the loosest tolerance only. Tolerances: rtol 1e-4 .. 1e-10
 * (--quick: 1e-4, 1e-7), atol = factor * rtol per problem (crank: atol = rtol; pump: the test
 * set's tolerance vector; crane: the scene's atol / rtol, paper 1).
 *
 * Writes to DIR (default results/bench): work_precision.csv (one row per problem, solver and
 * tolerance: accuracy, CPU time median and minimum, counters, and the split of a profiled run into
 * residual, Jacobian, linear algebra and the rest), report.md (targets with their verdicts and,
 * where one is missed, where the time goes; the CPU-time ratio bgdae-klu / ida-klu at equal
 * accuracy interpolated at scd = 4, 6, 8 for every problem; tables per problem; failures; machine,
 * load, commit and build flags), wp_<problem>.png (scd against CPU time and against steps, drawn
 * by gnuplot when it is installed), scaling.csv (crane from its settled start: 8, 16, ..., 512
 * boom elements, --quick: 8 .. 64, or --scaling LIST: CPU time per step, log-log slopes against
 * the boom elements, the target's measure, and against the unknowns),
 * realtime.csv (bench_realtime.h: the paper scene, or --crane-scene FILE, and paper-undamped.ini
 * over their full t_end, 20 s, K = --crane-realtime runs each, default 5, 0 with --quick: CPU
 * time of the integration, real-time factor on it, steps and those at the reference's corners,
 * peak memory; the mesh series, the main scene with the --scaling element counts over 1 s: CPU
 * per step, its log-log slope, the steps' spread) and, with --stability,
 * stability.csv (bench_stab.h; --stability-filter runs the cases whose name contains TEXT),
 * steps_vs_tol.csv (steps of every problem, solver and tolerance, flagged MORE STEPS where a
 * looser tolerance took more than 5 % more steps than a tighter one), mebdfi_compare.csv (the
 * published MEBDFI statistics of docs/mebdfi_stats.md beside runs of bgdae-klu with the
 * drivers' tolerance conventions, bench_mebdfi.h), osc_guard.csv (the undamped oscillatory
 * problems with the usual orders, the stability guard and max order 2, bench_osc.h) and, with
 * --crane-full, crane_wp.csv (the
 * crane scene crane/scenes/paper-undamped.ini, or --crane-full-scene FILE, over its full 20 s:
 * ours and IDA at rtol 1e-4 .. 1e-9, or --crane-full-rtols LIST, against ours at 1e-10, IDA
 * restarted at each breakpoint from consistent values; bench_crane.h; tools/run.sh asks for
 * it, minutes per run) and, with --error-estimate (and --quick), error_estimate.csv (the estimate
 * of crane --error-estimate against the true error on the problems and tolerances of the run,
 * bench_errest.h). --newton-dgmax G runs ours on the collection with options.newton_dgmax = G
 * (the crane keeps its scene's setting), for comparing the Newton matrix refresh.
 * --problems none skips the work-precision runs (and, unless asked for, the crane's scaling and
 * real-time runs).
 *
 * Method (IVP Test Set conventions, docs/testset.md): every solver starts from the same
 * consistent initial values (computed once per problem by dae_consistent_init at rtol 1e-10:
 * IDA's own initialisation handles index 1 only); CPU time of the integration alone; the first
 * run is profiled (residual and Jacobian callbacks and the linear solver timed; our solver's
 * own timers, stats.t_*, run in that run only: options.no_timing in the others) and is a warm-up
 * not counted, except for the crane (its profiled run is the first of its K, and a run of more
 * than 5 s is not repeated), then K timed runs (--repeat, default 3; --quick 1; a run under
 * 10 ms is timed as the mean of a batch of about 20 ms): the report uses the
 * median, the CSV has the minimum beside it; accuracy as scd (scored
 * components) and mescd, index-2 components apart. IDA runs as its guide recommends for index 2:
 * id vector, algebraic variables suppressed from the error test, fed the same residual and
 * Jacobian code (dense, or sparse CSC for KLU); ours with exclude_alg on the crane as
 * crane/crane.c runs it. Problems with breakpoints are integrated segment by segment (IDA is
 * re-initialised at each; its counters are summed).
 *
 * Files: every one is checked (bench_file, bench_util.h: the open, each write, fsync, close;
 * the figures: gnuplot's exit status and a whole PNG). A file that cannot be written is named on
 * stderr with the system's error and removed (no part of it is left to pass for a result), the
 * others are written all the same, and report.md lists it under "Files not written".
 *
 * Exit status: 0 when every file is written (failed runs, missed targets and wrong stability
 * cases are results, reported in the files); 1 if a file (or the output folder, or the standard
 * output) could not be written or a stability case crashed, and with --strict also if a run of
 * our solver or of the crane failed or a stability case ended wrong, at its time limit or
 * without its set-up; 2 for a bad command line (an --out of more than BENCH_OUT_MAX, 3974,
 * characters included: never cut).
 *
 * Parts: this file runs the harness (main, a short driver over the steps below) and writes the
 * report; bench_cli.c is the command line (a table of options, the help generated from it). */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <unistd.h>
#include <sys/utsname.h>
#include <sys/wait.h>

#include "bench_case.h"
#include "bench_cli.h"
#include "bench_crane.h"
#include "bench_errest.h"
#include "bench_realtime.h"
#include "bench_mebdfi.h"
#include "bench_osc.h"
#include "bench_stab.h"
#include "bench_util.h"
#include "crane_gnuplot.h"
#include "problems.h"

#ifdef BENCH_HAVE_SCENES
#include "crane_scene.h"
#endif

#include "bench_version.h" /* BENCH_COMMIT, generated at build time */
#ifndef BENCH_BUILD_FLAGS
#define BENCH_BUILD_FLAGS "unknown"
#endif

/* One run of the work-precision series: a case, a solver, a tolerance; its counters (r), the
 * median and minimum CPU time of its timed runs and its accuracy (sc: NAN where it failed or the
 * case has no reference). */
typedef struct bench_row {
    int ci; /* the case: an index into bench_results.cases */
    const solver_def *sd;
    double rtol, atol;
    run_out r;
    double cpu_min, cpu_med;
    bp_score sc;
} bench_row;

/* What the work-precision series measured, as the writers read it. */
typedef struct bench_results {
    bench_case **cases; /* the problems run, nc of them */
    int nc;
    const char **sol; /* the solvers' names, in the order of the command line, ns of them */
    int ns;
    const bench_row *rows; /* every run, n of them */
    int n;
    const double *rtols; /* the tolerances of the series, nr of them */
    int nr;
    double wall; /* wall time of the series, s */
    int repeat;  /* timed runs per row (K) */
} bench_results;

/* The report's head beyond the series: the load at the start and the end, the crane's scaling
 * slopes (with have_scaling), the real-time check (nrt scenes) and its mesh series. */
typedef struct bench_report_extras {
    char load_start[128], load_end[128];
    int have_scaling;
    double slope_n, slope_el;
    int nrt;
    bench_rt_scene rts[2];
    bench_rt_result rt[2];
    bench_mesh_result mesh;
} bench_report_extras;

/* A section of the report written in memory (open_memstream) while the runs go on, put into
 * report.md when it is written at the end. */
typedef struct bench_text {
    FILE *f; /* where to print; NULL once closed */
    char *buf;
    size_t len;
} bench_text;

/* ------------------------------------------------------------- reporting ---- */

/* scd is +inf where the error is exactly zero: count it as the 16 digits of double precision. */
static double capped(double scd)
{
    return scd > 16 ? 16 : scd;
}

static int row_ok(const bench_row *r)
{
    return r->r.status >= 0 && !isnan(r->sc.scd);
}

/* log10 of the median CPU time at accuracy target on the curve of (scd, cpu) points of one
 * solver: linear interpolation in (scd, log cpu) between neighbours on the curve (runs at
 * consecutive tolerances, failed runs left out) that bracket the target, the cheapest such pair.
 * Only neighbours: a pair of runs far apart in tolerance would stand for runs in between that
 * were measured and cost more (the crane at rtol 1e-4 is chaotic: one solver's run there can be
 * lucky, three times cheaper and more accurate than its run at 1e-5). When every run of the
 * solver is more accurate than the target (its loosest tolerance already passes it), the cheapest
 * run is taken and *bound set (an upper bound of the cost); NAN if the curve does not reach the
 * target. */
/* A and B (same case and solver) are runs at consecutive tolerances of the curve: no successful
 * run of theirs lies strictly between them in rtol. */
static int neighbours(const bench_row *rows, int nrows, const bench_row *A, const bench_row *B)
{
    double lo = fmin(A->rtol, B->rtol), hi = fmax(A->rtol, B->rtol);
    for (int c = 0; c < nrows; c++) {
        const bench_row *C = &rows[c];
        if (C->ci == A->ci && C->sd == A->sd && row_ok(C) && C->rtol > lo && C->rtol < hi) return 0;
    }
    return 1;
}

static double cpu_at_b(const bench_row *rows, int nrows, int ci, const char *solver, double target,
                       int *bound)
{
    double best = NAN, above = NAN;
    int below = 0;
    *bound = 0;
    for (int a = 0; a < nrows; a++) {
        const bench_row *A = &rows[a];
        double sa = capped(A->sc.scd);
        if (A->ci != ci || strcmp(A->sd->name, solver) || !row_ok(A)) continue;
        if (sa < target) below = 1;
        if (sa >= target && (isnan(above) || log10(A->cpu_med) < above)) above = log10(A->cpu_med);
        for (int b = 0; b < nrows; b++) {
            const bench_row *B = &rows[b];
            double sb = capped(B->sc.scd);
            if (B->ci != ci || strcmp(B->sd->name, solver) || !row_ok(B) ||
                !(sa <= target && sb >= target) || sa == sb || !neighbours(rows, nrows, A, B))
                continue;
            double w = (target - sa) / (sb - sa);
            double lc = (1 - w) * log10(A->cpu_med) + w * log10(B->cpu_med);
            if (isnan(best) || lc < best) best = lc;
        }
    }
    if (isnan(best) && !below && !isnan(above)) {
        best = above;
        *bound = 1;
    }
    return best;
}

static double cpu_at(const bench_row *rows, int nrows, int ci, const char *solver, double target)
{
    int b;
    return cpu_at_b(rows, nrows, ci, solver, target, &b);
}

/* Ratio bgdae-klu / ida-klu at scd target, NAN if either curve does not reach it; *bound set
 * when either side is the cheapest run above the target rather than an interpolation. */
static double ratio_at_b(const bench_row *rows, int n, int ci, double target, int *bound)
{
    int ba, bb;
    double a = cpu_at_b(rows, n, ci, "bgdae-klu", target, &ba),
           b = cpu_at_b(rows, n, ci, "ida-klu", target, &bb);
    *bound = ba || bb;
    return isnan(a) || isnan(b) ? NAN : pow(10, a - b);
}

/* A bench_row of the targets table for a scaling slope (limit 1.1). */
static void slope_row(FILE *f, const char *what, double slope, const char *ok, const char *bad)
{
    fprintf(f, "| crane: %s | %.3f | %s |\n", what, slope,
            isnan(slope)   ? "not measured"
            : slope <= 1.1 ? ok
                           : bad);
}

static double frac_other(const run_out *r)
{
    return r->wall > 0 ? (r->wall - r->t_res - r->t_jac - r->t_lin) / r->wall : NAN;
}

static void write_csv(FILE *f, const bench_row *rows, int n, bench_case **cases)
{
    fprintf(f, "problem,solver,rtol,atol,status,scd,mescd,scd_index2,mescd_index2,cpu_s,"
               "cpu_median_s,steps,rejected,newton,conv_fail,res_evals,jac_evals,factorizations,"
               "solves,max_order,profiled_wall_s,res_s,jac_s,linalg_s,other_fraction,message\n");
    for (int i = 0; i < n; i++) {
        const bench_row *r = &rows[i];
        fprintf(f,
                "%s,%s,%g,%g,%d,%.3f,%.3f,%.3f,%.3f,%.6g,%.6g,%ld,%ld,%ld,%ld,%ld,%ld,%ld,%ld,%d,"
                "%.6g,%.6g,%.6g,%.6g,%.4f,\"%s\"\n",
                cases[r->ci]->name, r->sd->name, r->rtol, r->atol, r->r.status, r->sc.scd,
                r->sc.mescd, r->sc.scd_i2, r->sc.mescd_i2, r->cpu_min, r->cpu_med, r->r.steps,
                r->r.rejected, r->r.newton, r->r.conv_fail, r->r.res, r->r.jac, r->r.fact,
                r->r.solves, r->r.max_order, r->r.wall, r->r.t_res, r->r.t_jac, r->r.t_lin,
                frac_other(&r->r), r->r.status < 0 ? r->r.msg : "");
    }
}

/* Runs gnuplot (exe) in folder dir on the commands of script (crane_gnuplot.h: no shell
 * between, its output discarded). 0 if it ended with exit status 0; else -1 and msg says how it
 * ended, with gnuplot's last message. */
static int run_gnuplot(const char *exe, const char *dir, const char *script, char *msg, size_t msz)
{
    char last[512];
    crane_gnuplot_job job = {exe, dir, NULL, script, NULL, NULL};
    int st = crane_gnuplot_run(&job, last, sizeof last);
    if (st == -1) {
        snprintf(msg, msz, "%s", last);
        return -1;
    }
    if (WIFEXITED(st) && WEXITSTATUS(st) == 0) return 0;
    snprintf(msg, msz, "gnuplot %s %d%s%.300s%s",
             WIFEXITED(st) ? "exited with status" : "ended by signal",
             WIFEXITED(st) ? WEXITSTATUS(st) : WTERMSIG(st), *last ? " (" : "", last,
             *last ? ")" : "");
    return -1;
}

/* wp_<name>.dat (each solver's runs on case ci), then wp_<name>.png drawn from it by gnuplot
 * (its path; NULL when it is not installed: no figure). Each checked: a failure is said and
 * counted (bench_util.h), a figure that gnuplot did not write whole is removed. */
static void plot(const char *dir, const char *gnuplot, int ci, const char *name,
                 const bench_row *rows, int n, const char **sol, int ns)
{
    char dat[BENCH_NAME_MAX + 1], png[BENCH_NAME_MAX + 1];
    snprintf(dat, sizeof dat, "wp_%s.dat", name); /* a problem's name: under 64 characters */
    snprintf(png, sizeof png, "wp_%s.png", name);
    bench_file bf;
    if (bench_file_open(&bf, dir, dat) != 0) return;
    for (int s = 0; s < ns; s++) {
        fprintf(bf.f, "# %s\n", sol[s]);
        for (int i = 0; i < n; i++)
            if (rows[i].ci == ci && !strcmp(rows[i].sd->name, sol[s]) && row_ok(&rows[i]))
                fprintf(bf.f, "%.6g %.4f %ld\n", rows[i].cpu_med, capped(rows[i].sc.scd),
                        rows[i].r.steps);
        fprintf(bf.f, "\n\n");
    }
    if (bench_file_close(&bf) != 0 || !gnuplot) return;
    /* the commands, with the files' names only: gnuplot runs in the output folder */
    char *script = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&script, &len);
    if (!f) {
        bench_file_failed(dir, png, strerror(errno));
        return;
    }
    fprintf(f,
            "set terminal png size 1000,420; set output '%s'; "
            "set multiplot layout 1,2 title '%s'; set logscale x; set grid; "
            "set key bottom right; set xlabel 'CPU time [s] (median)'; "
            "set ylabel 'scd'; plot ",
            png, name);
    for (int s = 0; s < ns; s++)
        fprintf(f, "'%s' index %d using 1:2 with linespoints title '%s'%s", dat, s, sol[s],
                s + 1 < ns ? ", " : "; ");
    fprintf(f, "set xlabel 'steps'; plot ");
    for (int s = 0; s < ns; s++)
        fprintf(f, "'%s' index %d using 3:2 with linespoints title '%s'%s", dat, s, sol[s],
                s + 1 < ns ? ", " : "; ");
    fprintf(f, "unset multiplot; set output");
    if (fclose(f) != 0) {
        free(script);
        bench_file_failed(dir, png, strerror(ENOMEM));
        return;
    }
    char msg[512], path[BENCH_PATH_SIZE];
    int rc = run_gnuplot(gnuplot, dir, script, msg, sizeof msg);
    free(script);
    snprintf(path, sizeof path, "%s/%s", dir, png); /* bench_cli has checked that it fits */
    if (rc == 0 && !crane_png_whole(path)) {
        snprintf(msg, sizeof msg, "gnuplot ended without writing it whole");
        rc = -1;
    }
    if (rc != 0) {
        remove(path);
        bench_file_failed(dir, png, msg);
    }
}

/* The ratio at scd target as text: "-" if not measurable, "0.42*" when a side is the cheapest
 * run above the target. Returns the ratio. */
static double fmt_ratio(char *buf, size_t sz, const bench_row *rows, int n, int ci, double target)
{
    int bound;
    double r = ratio_at_b(rows, n, ci, target, &bound);
    if (isnan(r))
        snprintf(buf, sz, "-");
    else
        snprintf(buf, sz, "%.2f%s", r, bound ? "*" : "");
    return r;
}

/* The rows of solver name on case ci nearest to scd target (below and above), for the
 * explanations of missed targets. */
static const bench_row *nearest(const bench_row *rows, int n, int ci, const char *name,
                                double target)
{
    const bench_row *best = NULL;
    for (int i = 0; i < n; i++) {
        const bench_row *r = &rows[i];
        if (r->ci != ci || strcmp(r->sd->name, name) || !row_ok(r)) continue;
        if (!best || fabs(capped(r->sc.scd) - target) < fabs(capped(best->sc.scd) - target))
            best = r;
    }
    return best;
}

static void describe_row(FILE *f, const bench_row *r)
{
    if (!r) {
        fprintf(f, "no successful run");
        return;
    }
    double w = r->r.wall > 0 ? r->r.wall : 1;
    fprintf(f,
            "%s at rtol %g (scd %.2f): %.3g s, %ld steps, %ld Newton iterations, %ld Jacobians, "
            "%ld factorizations, %ld residuals; residual %.0f %%, Jacobian %.0f %%, linear algebra "
            "%.0f %%, the rest %.0f %%",
            r->sd->name, r->rtol, r->sc.scd, r->cpu_med, r->r.steps, r->r.newton, r->r.jac,
            r->r.fact, r->r.res, 100 * r->r.t_res / w, 100 * r->r.t_jac / w, 100 * r->r.t_lin / w,
            100 * frac_other(&r->r));
}

void bench_load_average(char *buf, size_t sz)
{
    snprintf(buf, sz, "unknown");
    FILE *f = fopen("/proc/loadavg", "r");
    if (!f) return;
    if (!fgets(buf, (int)sz, f)) snprintf(buf, sz, "unknown");
    buf[strcspn(buf, "\n")] = '\0';
    fclose(f);
}

static void write_report_head(FILE *f, const bench_row *rows, int n, bench_case **cases, int nc,
                              const char **sol, int ns, double wall, int K,
                              const bench_report_extras *ex)
{
    struct utsname u;
    uname(&u);
    fprintf(f, "# Benchmark report\n\n");
    fprintf(f, "- machine: %s %s %s, %ld cores online (shared: timings are noisy)\n", u.sysname,
            u.release, u.machine, sysconf(_SC_NPROCESSORS_ONLN));
    fprintf(f, "- load average (/proc/loadavg) at the start: %s; at the end: %s\n", ex->load_start,
            ex->load_end);
    fprintf(f, "- commit: %s\n- build: %s\n", BENCH_COMMIT, BENCH_BUILD_FLAGS);
    fprintf(f,
            "- timing: CPU time of the integration alone, median of %d timed runs after a "
            "profiled warm-up (the crane: the profiled run is the first timed one, a run over "
            "5 s is not repeated), a run shorter "
            "than 10 ms timed as the mean of a batch of about 20 ms; minimum beside it in "
            "work_precision.csv\n",
            K);
    fprintf(f,
            "- accuracy: scd over the scored components, index-2 components apart (scd2); "
            "atol = factor * rtol per problem\n- wall time of the work-precision runs: %.1f "
            "s\n\n",
            wall);

    /* targets */
    fprintf(f, "## Targets\n\n| target | measured | verdict |\n|---|---|---|\n");
    static const char *const tprob[] = {"pendulum2", "crank", "pump", "crane"};
    for (int q = 0; q < 4; q++) {
        int ci = -1;
        for (int c = 0; c < nc; c++)
            if (!strcmp(cases[c]->name, tprob[q])) ci = c;
        if (ci < 0) continue;
        for (int target = 4; target <= 6; target += 2) {
            char b[32];
            double r = fmt_ratio(b, sizeof b, rows, n, ci, target);
            fprintf(f, "| %s: CPU bgdae-klu / ida-klu at scd %d <= 0.5 | %s | %s |\n", tprob[q],
                    target, b,
                    isnan(r)   ? "not measurable (a curve does not reach this accuracy)"
                    : r <= 0.5 ? "met"
                               : "MISSED");
        }
    }
    for (int i = 0; i < ex->nrt; i++) {
        const bench_rt_scene *sc = &ex->rts[i];
        const bench_rt_result *r = &ex->rt[i];
        if (r->runs == 0) continue;
        fprintf(f,
                "| crane %s, %g s: simulated / CPU time of the integration >= %g (median of %d) | "
                "%.2f | %s |\n",
                sc->label, sc->s.t_end, sc->target, r->runs, r->rt_factor_cpu,
                r->rt_factor_cpu >= sc->target ? "met" : "MISSED");
        if (sc->max_steps > 0)
            fprintf(f, "| crane %s: steps <= %ld | %ld | %s |\n", sc->label, sc->max_steps,
                    r->steps, r->steps <= sc->max_steps ? "met" : "MISSED");
        fprintf(f, "| crane %s: peak memory < 64 MB | %.1f MB | %s |\n", sc->label, r->peak_mb,
                r->peak_mb < 64 ? "met" : "MISSED");
        fprintf(f,
                "| crane %s: bookkeeping outside residual, Jacobian and linear algebra < 10 %% | "
                "%.1f %% | %s |\n",
                sc->label, 100 * r->bookkeeping, r->bookkeeping < 0.1 ? "met" : "MISSED");
    }
    if (ex->mesh.n >= 2) {
        fprintf(f,
                "| crane mesh series (%d .. %d elements): CPU per step against elements, log-log "
                "slope <= 1.1 | %.3f | %s |\n",
                ex->mesh.elements[0], ex->mesh.elements[ex->mesh.n - 1], ex->mesh.slope_el,
                ex->mesh.slope_el <= 1.1 ? "met" : "MISSED");
        fprintf(f,
                "| crane mesh series: steps independent of the mesh within 30 %% (largest / "
                "smallest <= 1.3) | %.2f | %s |\n",
                ex->mesh.steps_spread, ex->mesh.steps_spread <= 1.3 ? "met" : "MISSED");
    }
    if (ex->have_scaling) {
        /* the issue states the target against the boom elements; against the unknowns (which
         * include the platform's, the hydraulics' and the load's, a fixed part) it is stricter
         * and reported beside it */
        slope_row(f, "time per step against boom elements, log-log slope <= 1.1", ex->slope_el,
                  "met", "MISSED");
        slope_row(f, "the same against the unknowns (the fixed non-boom unknowns make it stricter)",
                  ex->slope_n, "within 1.1", "above 1.1");
    }
    fprintf(f, "\n");
    /* where the time goes where a ratio target is missed */
    int said = 0;
    for (int q = 0; q < 4; q++) {
        int ci = -1;
        for (int c = 0; c < nc; c++)
            if (!strcmp(cases[c]->name, tprob[q])) ci = c;
        if (ci < 0) continue;
        for (int target = 4; target <= 6; target += 2) {
            int bound;
            double r = ratio_at_b(rows, n, ci, target, &bound);
            if (!isnan(r) && r <= 0.5) continue;
            if (!said)
                fprintf(f, "Where the time goes where a ratio target is missed (the runs "
                           "nearest to the accuracy, profiled):\n\n");
            said = 1;
            const bench_row *a = nearest(rows, n, ci, "bgdae-klu", target),
                            *b = nearest(rows, n, ci, "ida-klu", target);
            fprintf(f, "- %s, scd %d: ", tprob[q], target);
            describe_row(f, a);
            fprintf(f, "; against ");
            describe_row(f, b);
            if (a && b && b->r.steps > 0 && a->r.steps > 0 && b->r.fact > 0 && b->r.newton > 0)
                fprintf(f,
                        ". Ours / IDA: steps %.2f, Newton iterations %.2f, factorizations %.2f, "
                        "CPU per step %.2f",
                        (double)a->r.steps / (double)b->r.steps,
                        (double)a->r.newton / (double)b->r.newton,
                        (double)a->r.fact / (double)b->r.fact,
                        (a->cpu_med / (double)a->r.steps) / (b->cpu_med / (double)b->r.steps));
            fprintf(f, ".\n");
        }
    }
    if (said) fprintf(f, "\n");

    /* ratio table */
    fprintf(f, "## CPU time of bgdae-klu / ida-klu at equal accuracy\n\n"
               "Interpolated in (scd, log CPU) between runs at neighbouring tolerances of each "
               "solver's curve that bracket the accuracy (the cheapest such pair); '-' where a "
               "curve does not "
               "reach the accuracy; '*' where a solver's loosest run is already more accurate "
               "(its cheapest run stands in). Below 1: ours is faster.\n\n"
               "| problem | n | scd 4 | scd 6 | scd 8 | fastest at scd 4 | fastest at scd 6 | "
               "fastest at scd 8 |\n|---|---|---|---|---|---|---|---|\n");
    for (int c = 0; c < nc; c++) {
        fprintf(f, "| %s | %d |", cases[c]->name, cases[c]->n);
        for (int target = 4; target <= 8; target += 2) {
            char b[32];
            fmt_ratio(b, sizeof b, rows, n, c, target);
            fprintf(f, " %s |", b);
        }
        for (int target = 4; target <= 8; target += 2) {
            double bestv = NAN;
            const char *win = "-";
            for (int s = 0; s < ns; s++) {
                double lc = cpu_at(rows, n, c, sol[s], target);
                if (!isnan(lc) && (isnan(bestv) || lc < bestv)) {
                    bestv = lc;
                    win = sol[s];
                }
            }
            fprintf(f, " %s |", win);
        }
        fprintf(f, "\n");
    }
    fprintf(f, "\n");
}

static void write_report_problems(FILE *f, const bench_row *rows, int n, bench_case **cases, int nc,
                                  const char **sol, int ns)
{
    for (int c = 0; c < nc; c++) {
        const bench_case *bc = cases[c];
        fprintf(f, "## %s (n = %d): %s\n\nReference: %s.\n\n", bc->name, bc->n, bc->title,
                bc->ref_source);
        fprintf(f, "| solver | rtol | status | scd | mescd | scd2 | CPU s (median) | steps | "
                   "rejected | Newton | Jacobians | factorizations | res/jac/lin/rest %% |\n"
                   "|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
        for (int i = 0; i < n; i++) {
            const bench_row *r = &rows[i];
            if (r->ci != c) continue;
            double w = r->r.wall > 0 ? r->r.wall : 1;
            fprintf(f,
                    "| %s | %g | %s | %.2f | %.2f | %.2f | %.4g | %ld | %ld | %ld | %ld | %ld | "
                    "%.0f/%.0f/%.0f/%.0f |\n",
                    r->sd->name, r->rtol, r->r.status < 0 ? "FAIL" : "ok", r->sc.scd, r->sc.mescd,
                    r->sc.scd_i2, r->cpu_med, r->r.steps, r->r.rejected, r->r.newton, r->r.jac,
                    r->r.fact, 100 * r->r.t_res / w, 100 * r->r.t_jac / w, 100 * r->r.t_lin / w,
                    100 * frac_other(&r->r));
        }
        fprintf(f,
                "\nCPU time at equal accuracy (median, interpolated on the scd axis):\n\n| scd |");
        for (int s = 0; s < ns; s++)
            fprintf(f, " %s |", sol[s]);
        fprintf(f, " winner | bgdae-klu / ida-klu |\n|---|");
        for (int s = 0; s <= ns + 1; s++)
            fprintf(f, "---|");
        fprintf(f, "\n");
        for (int target = 4; target <= 8; target += 2) {
            fprintf(f, "| %d |", target);
            double bestv = NAN;
            const char *win = "-";
            for (int s = 0; s < ns; s++) {
                double lc = cpu_at(rows, n, c, sol[s], target);
                if (isnan(lc))
                    fprintf(f, " - |");
                else
                    fprintf(f, " %.3g s |", pow(10, lc));
                if (!isnan(lc) && (isnan(bestv) || lc < bestv)) {
                    bestv = lc;
                    win = sol[s];
                }
            }
            char b[32];
            fmt_ratio(b, sizeof b, rows, n, c, target);
            fprintf(f, " %s | %s |\n", win, b);
        }
        fprintf(f, "\n![work-precision %s](wp_%s.png)\n\n", bc->name, bc->name);
    }
    fprintf(f, "## Failures\n\n");
    int nf = 0;
    for (int i = 0; i < n; i++)
        if (rows[i].r.status < 0) {
            fprintf(f, "- %s, %s, rtol %g: status %d at t = %.9g: %s\n", cases[rows[i].ci]->name,
                    rows[i].sd->name, rows[i].rtol, rows[i].r.status, rows[i].r.t, rows[i].r.msg);
            nf++;
        }
    if (!nf) fprintf(f, "none\n");
    fprintf(f, "\n");
}

/* ---------------------------------------------------- steps against tolerance ---- */

/* The tighter run of the same case and solver with the fewest steps relative to A's: the
 * largest steps(A) / steps(B) over successful runs B at a smaller rtol; NULL if none. */
static const bench_row *fewest_tighter(const bench_row *rows, int n, const bench_row *A,
                                       double *ratio)
{
    const bench_row *best = NULL;
    *ratio = 0;
    if (!row_ok(A) || A->r.steps <= 0) return NULL;
    for (int i = 0; i < n; i++) {
        const bench_row *B = &rows[i];
        if (B->ci != A->ci || B->sd != A->sd || !row_ok(B) || !(B->rtol < A->rtol) ||
            B->r.steps <= 0)
            continue;
        double q = (double)A->r.steps / (double)B->r.steps;
        if (q > *ratio) {
            *ratio = q;
            best = B;
        }
    }
    return best;
}

#define MORE_STEPS_LIMIT 1.05

/* steps_vs_tol.csv and the report's section: steps (rejected) of every problem and solver at
 * each tolerance, "MORE STEPS" where a looser tolerance took more than 5 % more steps than a
 * tighter one (failed runs left out: their counts stop where they failed). Returns the number
 * of flagged (problem, solver) pairs (a CSV that cannot be written is said and counted by
 * bench_file_close; the section is written all the same). */
static int write_steps_vs_tol(const char *dir, FILE *f, const bench_row *rows, int n,
                              bench_case **cases, int nc, const char **sol, int ns,
                              const double *rtols, int nr)
{
    bench_file bf;
    FILE *c = bench_file_open(&bf, dir, "steps_vs_tol.csv") == 0 ? bf.f : NULL;
    if (c)
        fprintf(c, "problem,solver,rtol,atol,status,steps,rejected,max_order,flag,"
                   "tighter_rtol_fewer_steps,tighter_steps,excess_percent\n");
    for (int i = 0; i < n && c; i++) {
        const bench_row *A = &rows[i];
        double q;
        const bench_row *B = fewest_tighter(rows, n, A, &q);
        int flag = B && q > MORE_STEPS_LIMIT;
        fprintf(c, "%s,%s,%g,%g,%d,%ld,%ld,%d,%s,", cases[A->ci]->name, A->sd->name, A->rtol,
                A->atol, A->r.status, A->r.steps, A->r.rejected, A->r.max_order,
                flag ? "MORE STEPS" : "");
        if (flag)
            fprintf(c, "%g,%ld,%.1f\n", B->rtol, B->r.steps, 100 * (q - 1));
        else
            fprintf(c, ",,\n");
    }
    if (c) bench_file_close(&bf);
    /* tolerances loosest first */
    double rt[BENCH_MAXRTOL];
    int k = 0;
    for (int i = 0; i < nr; i++)
        rt[k++] = rtols[i];
    for (int i = 1; i < k; i++)
        for (int j = i; j > 0 && rt[j] > rt[j - 1]; j--) {
            double t = rt[j];
            rt[j] = rt[j - 1];
            rt[j - 1] = t;
        }
    fprintf(f, "## Steps against tolerance\n\n"
               "Accepted steps (rejected steps in brackets) of every run of the work-precision "
               "series, loosest tolerance first (steps_vs_tol.csv). MORE STEPS: a looser "
               "tolerance took more than 5 %% more steps than a tighter one of the same problem "
               "and solver (the worst pair is named; failed runs are left out, their counts stop "
               "where they failed). Step counts should fall as the tolerance loosens: where they "
               "do not, the step size is not set by the accuracy asked for (an order held down "
               "by a stability limit, a fail/grow cycle of the step size, restarts).\n\n");
    int nflag = 0;
    /* the flagged pairs first */
    for (int ci = 0; ci < nc; ci++)
        for (int s = 0; s < ns; s++) {
            const bench_row *worst = NULL, *wb = NULL;
            double wq = 0;
            for (int i = 0; i < n; i++) {
                const bench_row *A = &rows[i];
                if (A->ci != ci || strcmp(A->sd->name, sol[s])) continue;
                double q;
                const bench_row *B = fewest_tighter(rows, n, A, &q);
                if (B && q > MORE_STEPS_LIMIT && q > wq) {
                    wq = q;
                    worst = A;
                    wb = B;
                }
            }
            if (!worst) continue;
            if (!nflag) fprintf(f, "Flagged:\n\n");
            nflag++;
            fprintf(f,
                    "- MORE STEPS: %s, %s: %ld steps at rtol %g against %ld at rtol %g (+%.0f "
                    "%%)\n",
                    cases[ci]->name, sol[s], worst->r.steps, worst->rtol, wb->r.steps, wb->rtol,
                    100 * (wq - 1));
        }
    fprintf(f, nflag ? "\n" : "No problem and solver took more steps at a looser tolerance.\n\n");
    fprintf(f, "| problem | solver |");
    for (int i = 0; i < k; i++)
        fprintf(f, " %g |", rt[i]);
    fprintf(f, " flag |\n|---|---|");
    for (int i = 0; i <= k; i++)
        fprintf(f, "---|");
    fprintf(f, "\n");
    for (int ci = 0; ci < nc; ci++)
        for (int s = 0; s < ns; s++) {
            int any = 0, flag = 0;
            for (int i = 0; i < n; i++)
                any |= rows[i].ci == ci && !strcmp(rows[i].sd->name, sol[s]);
            if (!any) continue;
            fprintf(f, "| %s | %s |", cases[ci]->name, sol[s]);
            for (int j = 0; j < k; j++) {
                const bench_row *A = NULL;
                for (int i = 0; i < n; i++)
                    if (rows[i].ci == ci && !strcmp(rows[i].sd->name, sol[s]) &&
                        rows[i].rtol == rt[j])
                        A = &rows[i];
                if (!A) {
                    fprintf(f, " |");
                    continue;
                }
                double q;
                const bench_row *B = fewest_tighter(rows, n, A, &q);
                int fl = B && q > MORE_STEPS_LIMIT;
                flag |= fl;
                if (A->r.status < 0)
                    fprintf(f, " FAIL (%ld) |", A->r.steps);
                else
                    fprintf(f, " %s%ld (%ld)%s |", fl ? "**" : "", A->r.steps, A->r.rejected,
                            fl ? "**" : "");
            }
            fprintf(f, " %s |\n", flag ? "MORE STEPS" : "");
        }
    fprintf(f, "\n");
    return nflag;
}

/* The report's list of the files that could not be written (none: nothing), placed after its
 * head: the report itself is written last. */
static void write_report_failed_files(FILE *f)
{
    int k = bench_file_failures();
    if (k == 0) return;
    fprintf(f, "## Files not written\n\n"
               "These files of the run could not be written (the bench ends with exit status 1); "
               "none of them is left in the folder:\n\n");
    for (int i = 0; i < k; i++) {
        const char *msg, *name = bench_file_failure(i, &msg);
        if (!name) {
            fprintf(f, "- and %d more (named in the bench's messages)\n", k - i);
            break;
        }
        fprintf(f, "- %s: %s\n", name, msg);
    }
    fprintf(f, "\n");
}

/* ---------------------------------------------------------------- entry points ---- */

int bench_text_open(bench_text *t)
{
    t->buf = NULL;
    t->len = 0;
    t->f = open_memstream(&t->buf, &t->len);
    return t->f ? 0 : -1;
}

void bench_text_free(bench_text *t)
{
    if (t->f) fclose(t->f);
    t->f = NULL;
    free(t->buf);
    t->buf = NULL;
}

/* Closes t and appends its text to the report (a failure to finish it: rep's, ENOMEM). */
static void append_text(bench_file *rep, bench_text *t)
{
    int rc = fclose(t->f);
    t->f = NULL;
    if (rc != 0)
        bench_file_fail(rep, ENOMEM);
    else
        fwrite(t->buf, 1, t->len, rep->f);
}

void bench_report_csv(const char *dir, const bench_results *res)
{
    bench_file wp;
    if (bench_file_open(&wp, dir, "work_precision.csv") == 0) {
        write_csv(wp.f, res->rows, res->n, res->cases);
        bench_file_close(&wp);
    }
}

void bench_report_plots(const char *dir, const bench_results *res)
{
    char gnuplot[BENCH_PATH_SIZE];
    int have_gnuplot = res->nc > 0 && crane_gnuplot_find(gnuplot, sizeof gnuplot);
    if (res->nc > 0 && !have_gnuplot)
        fprintf(stderr, "bench: gnuplot not found: no figures (the wp_*.dat files are written)\n");
    for (int c = 0; c < res->nc; c++)
        plot(dir, have_gnuplot ? gnuplot : NULL, c, res->cases[c]->name, res->rows, res->n,
             res->sol, res->ns);
}

int bench_report_steps_vs_tol(const char *dir, FILE *f, const bench_results *res)
{
    return write_steps_vs_tol(dir, f, res->rows, res->n, res->cases, res->nc, res->sol, res->ns,
                              res->rtols, res->nr);
}

void bench_report_write(bench_file *rep, const bench_results *res, const bench_report_extras *ex,
                        bench_text *mid, bench_text *tail)
{
    write_report_head(rep->f, res->rows, res->n, res->cases, res->nc, res->sol, res->ns, res->wall,
                      res->repeat, ex);
    write_report_failed_files(rep->f);
    append_text(rep, mid);
    write_report_problems(rep->f, res->rows, res->n, res->cases, res->nc, res->sol, res->ns);
    append_text(rep, tail);
    bench_file_close(rep);
}

/* -------------------------------------------------------------------- main ---- */

/* larger cases run dense LU at the loosest tolerance only */
#define DENSE_MAX_N 300

/* The run's state, main's own: the command line, the crane's scenes, the cases and the rows of
 * the work-precision series, the report's texts in memory (tail: the real-time check, the error
 * estimate, scaling, stability and crane-full sections; mid: steps against tolerance, MEBDFI,
 * the oscillatory guard) and the count of what went wrong. */
typedef struct harness {
    bench_cli cli;
    crane_scene scene; /* the paper scene, or --crane-scene */
    crane_scene full;  /* --crane-full's */
    char full_name[600];
    bench_case *cases[BENCH_MAXPROB];
    int nc;
    bench_row *rows; /* nc * ns * nr at most */
    int n;
    double wall; /* of the work-precision series */
    bench_report_extras ex;
    bench_text mid, tail;
    int failures, crashed, stab_bad, oom;
} harness;

/* The crane's scene: the paper scene, or --crane-scene FILE. BENCH_CLI_RUN, or the exit status
 * (said). */
static int load_scene(harness *b)
{
    crane_scene_default(&b->scene);
    if (!b->cli.scene_file) return BENCH_CLI_RUN;
#ifdef BENCH_HAVE_SCENES
    bg_error err = {0};
    if (crane_scene_load(&b->scene, b->cli.scene_file, &err) != BG_OK) {
        fprintf(stderr, "bench: %s\n", err.message);
        return 2;
    }
    return BENCH_CLI_RUN;
#else
    return bench_cli_usage("--crane-scene: built without scene files (libinih-dev)");
#endif
}

/* --crane-full's scene: --crane-full-scene FILE or paper-undamped.ini, and its name for the
 * report. BENCH_CLI_RUN, or the exit status (said). */
static int load_full_scene(harness *b)
{
    if (!b->cli.crane_full) return BENCH_CLI_RUN;
#ifdef BENCH_HAVE_SCENES
    const char *file =
        b->cli.full_scene ? b->cli.full_scene : BENCH_SCENES_DIR "/paper-undamped.ini";
    bg_error err = {0};
    if (crane_scene_load(&b->full, file, &err) != BG_OK) {
        fprintf(stderr, "bench: --crane-full: %s\n", err.message);
        return 2;
    }
    const char *base = strrchr(file, '/');
    snprintf(b->full_name, sizeof b->full_name, "%s", base ? base + 1 : file);
    return BENCH_CLI_RUN;
#else
    return bench_cli_usage("--crane-full: built without scene files (libinih-dev)");
#endif
}

/* Creates folder dir and its parents. 0, or -1 with errno (ENOTDIR: dir or a parent is a file). */
static int mkdirs(const char *dir)
{
    char buf[BENCH_PATH_SIZE];
    if (snprintf(buf, sizeof buf, "%s", dir) >= (int)sizeof buf) {
        errno = ENAMETOOLONG; /* bench_cli refuses such a name first */
        return -1;
    }
    for (char *q = buf + 1; *q; q++)
        if (*q == '/') {
            *q = '\0';
            if (mkdir(buf, 0755) != 0 && errno != EEXIST) return -1;
            *q = '/';
        }
    if (mkdir(buf, 0755) != 0 && errno != EEXIST) return -1;
    struct stat st;
    if (stat(buf, &st) != 0) return -1;
    if (!S_ISDIR(st.st_mode)) {
        errno = ENOTDIR;
        return -1;
    }
    return 0;
}

/* The crane's real-time check (bench_realtime.h), into tail: the main scene (paper, or
 * --crane-scene) and, with scene files, paper-undamped; the mesh series on the main scene over
 * 1 s (--quick: none). Run first, while this process is small: a child's ru_maxrss includes the
 * resident size it was forked with (Linux keeps the high-water mark across execve). */
static void realtime_check(harness *b)
{
    const bench_cli *c = &b->cli;
    bench_report_extras *ex = &b->ex;
    char exe[4096];
    ssize_t len = readlink("/proc/self/exe", exe, sizeof exe);
    if (len <= 0 || (size_t)len >= sizeof exe) {
        fprintf(stderr, "bench: cannot find this program for the real-time runs\n");
        b->failures++;
        return;
    }
    exe[len] = '\0';
    ex->rts[0].file = c->scene_file;
    ex->rts[0].label = c->scene_file ? b->scene.name : "paper";
    ex->rts[0].s = b->scene;
    ex->rts[0].target = 50;
    ex->rts[0].max_steps = c->scene_file ? 0 : 8000;
    ex->nrt = 1;
#ifdef BENCH_HAVE_SCENES
    bg_error err = {0};
    bench_rt_scene *u = &ex->rts[1];
    u->file = BENCH_SCENES_DIR "/paper-undamped.ini";
    u->label = "paper-undamped";
    u->target = 7.5;
    if (crane_scene_load(&u->s, u->file, &err) == BG_OK)
        ex->nrt = 2;
    else
        fprintf(stderr, "bench: the real-time check without paper-undamped: %s\n", err.message);
#endif
    b->failures +=
        bench_crane_realtime(exe, ex->rts, ex->nrt, c->realtime_runs, c->scale,
                             c->quick ? 0 : c->nscale, 1.0, c->out, b->tail.f, ex->rt, &ex->mesh);
}

/* The cases of the problems asked for, each from its consistent start (the crane: built,
 * settled, its reference computed). A case that cannot be built is said and counted. 0, or -1
 * out of memory. */
static int make_cases(harness *b)
{
    const bench_cli *c = &b->cli;
    for (int q = 0; q < c->np; q++) {
        bench_case *bc = calloc(1, sizeof *bc);
        char msg[BG_MESSAGE_SIZE] = "";
        int r, crane = !strcmp(c->pnames[q], "crane");
        if (!bc) return -1;
        if (crane) {
            fprintf(stderr, "crane: building and settling the model\n");
            r = bench_crane_case(bc, &b->scene, b->scene.static_start, c->horizon, "crane", msg,
                                 sizeof msg);
            if (r == 0 && b->scene.stability_guard) { /* as the crane program runs the scene */
                bc->stability_guard = 1;
                size_t len = strlen(bc->title);
                snprintf(bc->title + len, sizeof bc->title - len, ", our stability guard on");
            }
        } else {
            r = bench_case_from_problem(bc, bp_find(c->pnames[q]));
            if (r == 0) bc->newton_dgmax = c->newton_dgmax;
            if (r) snprintf(msg, sizeof msg, "out of memory");
        }
        if (r != 0) {
            fprintf(stderr, "bench: %s: %s\n", c->pnames[q], msg);
            free(bc);
            b->failures++;
            continue;
        }
        b->cases[b->nc++] = bc;
        if (bench_case_start(bc, 1e-10, msg, sizeof msg) != 0)
            fprintf(stderr, "bench: %s: no consistent start (the given values are used): %s\n",
                    bc->name, msg);
        if (crane) {
            fprintf(stderr, "crane: reference at rtol 1e-11\n");
            if (bench_crane_reference(bc, 1e-11, 1, msg, sizeof msg) != 0)
                fprintf(stderr, "bench: crane: %s\n", msg);
            fprintf(stderr, "crane: reference: %s\n", bc->ref_source);
        }
    }
    return 0;
}

/* One row: case c, solver sd at r->rtol, K timed runs (bench_run_timed), scored, said on stderr.
 * 0, or -1 out of memory (the row not counted). */
static int run_row(harness *b, bench_row *r, int c, const solver_def *sd, double rtol)
{
    bench_case *bc = b->cases[c];
    double cpu[BENCH_MAXREP + 1];
    r->ci = c;
    r->sd = sd;
    r->rtol = rtol;
    bench_case_atol(bc, r->rtol, &r->atol, NULL);
    if (bench_run_alloc(&r->r, bc->n) != 0) return -1;
    b->n++;
    run_opts ro = {0};
    ro.rtol = r->rtol;
    int m = bench_run_timed(bc, sd, &ro, b->cli.repeat, &r->r, cpu);
    r->cpu_min = cpu[0];
    r->cpu_med = bench_median(cpu, m);
    if (r->r.status >= 0 && bc->yref)
        bc->score(bc, r->r.y, r->r.yp, r->rtol, r->atol, &r->sc);
    else
        r->sc.scd = r->sc.mescd = r->sc.scd_i2 = r->sc.mescd_i2 = NAN;
    bench_run_free(&r->r);
    if (r->r.status < 0) b->failures += !sd->ida;
    fprintf(stderr, "%-10s %-18s rtol %-6g %s scd %6.2f  cpu %.4g s  steps %ld%s%s\n", bc->name,
            sd->name, r->rtol, r->r.status < 0 ? "FAIL" : "ok  ", r->sc.scd, r->cpu_med, r->r.steps,
            r->r.status < 0 ? ": " : "", r->r.status < 0 ? r->r.msg : "");
    return 0;
}

/* The work-precision series: the cases, then every case, tolerance and solver (dense LU on a
 * large model, the crane, O(n^3) per factorization: at the loosest tolerance only); its wall
 * time. 0, or -1 out of memory. */
static int work_precision(harness *b)
{
    const bench_cli *c = &b->cli;
    double wt0 = bench_wall_now();
    if (make_cases(b) != 0) return -1;
    b->rows = calloc((size_t)b->nc * (size_t)c->ns * (size_t)c->nr + 1, sizeof *b->rows);
    if (!b->rows) return -1;
    double rtol_max = 0;
    for (int k = 0; k < c->nr; k++)
        rtol_max = fmax(rtol_max, c->rtols[k]);
    for (int ci = 0; ci < b->nc; ci++)
        for (int k = 0; k < c->nr; k++)
            for (int s = 0; s < c->ns; s++) {
                if (c->sols[s]->ls == LS_DENSE && b->cases[ci]->n > DENSE_MAX_N &&
                    c->rtols[k] != rtol_max)
                    continue;
                if (run_row(b, &b->rows[b->n], ci, c->sols[s], c->rtols[k]) != 0) return -1;
            }
    b->wall = bench_wall_now() - wt0;
    return 0;
}

/* The series beyond the work-precision runs, their sections into the report's texts: the error
 * estimate (with --error-estimate or --quick), the crane's scaling, the stability suite, the
 * crane over its full horizon against IDA (last: minutes per run; its rows reach crane_wp.csv as
 * they are measured), steps against tolerance, MEBDFI, the oscillatory guard. */
static void more_series(harness *b, const bench_results *res)
{
    const bench_cli *c = &b->cli;
    if ((c->errest || c->quick) && b->nc > 0) {
        bench_errest_config ec = {c->rtols, c->nr, 0, 0, 0};
        b->failures += bench_errest(c->out, b->tail.f, b->cases, b->nc, &ec);
    }
    if ((c->want_crane || c->scaling_text) && c->nscale > 0) {
        b->failures +=
            bench_crane_scaling(c->out, b->tail.f, c->scale, c->nscale, 10, c->quick ? 60 : 200,
                                1.0, c->quick ? 3 : 20, &b->ex.slope_n, &b->ex.slope_el);
        b->ex.have_scaling = 1;
    }
    if (c->stability) {
        stab_config sc;
        sc.quick = c->quick;
        sc.crane_horizon = c->quick ? 0.05 : 0.25;
        sc.time_limit = c->quick ? 60 : 600;
        sc.scene = &b->scene;
        sc.filter = c->stab_filter;
        b->stab_bad = bench_stability(c->out, b->tail.f, &sc, &b->crashed);
    }
    if (c->crane_full)
        b->failures += bench_crane_full(c->out, b->tail.f, &b->full, b->full_name, c->full_rtols,
                                        c->full_nr, 1e-10);
    if (b->n > 0) bench_report_steps_vs_tol(c->out, b->mid.f, res);
    if (b->nc > 0)
        b->failures += bench_mebdfi_compare(c->out, b->mid.f, b->cases, b->nc, c->rtols, c->nr);
    if (b->nc > 0)
        b->failures += bench_osc_guard(c->out, b->mid.f, b->cases, b->nc, c->rtols, c->nr);
}

/* The files of the work-precision series, the other series, and the report (rep, closed). */
static void write_results(harness *b, bench_file *rep)
{
    bench_results res = {.cases = b->cases,
                         .nc = b->nc,
                         .sol = b->cli.solnames,
                         .ns = b->cli.ns,
                         .rows = b->rows,
                         .n = b->n,
                         .rtols = b->cli.rtols,
                         .nr = b->cli.nr,
                         .wall = b->wall,
                         .repeat = b->cli.repeat};
    bench_report_csv(b->cli.out, &res);
    bench_report_plots(b->cli.out, &res);
    more_series(b, &res);
    bench_load_average(b->ex.load_end, sizeof b->ex.load_end);
    bench_report_write(rep, &res, &b->ex, &b->mid, &b->tail);
}

/* The summary on stdout and the exit status (the header's "Exit status"). */
static int summary(const harness *b)
{
    int nfiles = bench_file_failures();
    printf("bench: %d runs; %d failed runs of our solver or the crane's; %d stability cases wrong, "
           "crashed, at the time limit or not set up (%d crashed); ",
           b->n, b->failures, b->stab_bad, b->crashed);
    if (nfiles)
        printf("%d file%s not written (named above): the results in %s are incomplete\n", nfiles,
               nfiles > 1 ? "s" : "", b->cli.out);
    else
        printf("results in %s\n", b->cli.out);
    if (fflush(stdout) != 0 || ferror(stdout)) {
        fprintf(stderr, "bench: cannot write the standard output: %s\n", strerror(errno));
        return 1;
    }
    if (nfiles || b->crashed) return 1;
    return b->cli.strict && (b->failures || b->stab_bad) ? 1 : 0;
}

static void free_run(harness *b)
{
    bench_text_free(&b->tail);
    bench_text_free(&b->mid);
    for (int c = 0; c < b->nc; c++) {
        bench_case_free(b->cases[c]);
        free(b->cases[c]);
    }
    free(b->rows); /* their solutions are freed after each run (bench_run_free) */
}

/* The command line, the scenes, the output folder. BENCH_CLI_RUN, or the exit status (said). */
static int start(harness *b, int argc, char **argv)
{
    int rc = bench_cli_parse(&b->cli, argc, argv);
    if (rc == BENCH_CLI_RUN) rc = load_scene(b);
    if (rc != BENCH_CLI_RUN || b->cli.child) return rc;
    if ((rc = bench_cli_resolve(&b->cli)) != BENCH_CLI_RUN) return rc;
    if ((rc = load_full_scene(b)) != BENCH_CLI_RUN) return rc;
    if (mkdirs(b->cli.out) != 0) {
        fprintf(stderr, "bench: cannot create the output folder '%s': %s\n", b->cli.out,
                strerror(errno));
        return 1;
    }
    return BENCH_CLI_RUN;
}

int main(int argc, char **argv)
{
    harness b;
    memset(&b, 0, sizeof b);
    int rc = start(&b, argc, argv);
    if (rc != BENCH_CLI_RUN) return rc;
    if (b.cli.child) return bench_crane_realtime_child(&b.scene);
    /* a file that cannot be written fails now, not after the runs (said by bench_file_open) */
    bench_file rep;
    if (bench_file_open(&rep, b.cli.out, "report.md") != 0) return 1;
    bench_load_average(b.ex.load_start, sizeof b.ex.load_start);
    b.oom = bench_text_open(&b.tail) != 0 || bench_text_open(&b.mid) != 0;
    if (!b.oom && (b.cli.want_crane || b.cli.realtime_asked) && b.cli.realtime_runs > 0)
        realtime_check(&b);
    if (!b.oom) b.oom = work_precision(&b) != 0;
    if (!b.oom)
        write_results(&b, &rep);
    else {
        fprintf(stderr, "bench: out of memory\n");
        bench_file_discard(&rep);
    }
    rc = b.oom ? 1 : summary(&b);
    free_run(&b);
    return rc;
}
