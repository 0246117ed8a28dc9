/* The benchmark harness: error against run time for our solver and SUNDIALS IDA on the problem
 * collection (bench/problems.c) and the crane, the crane's scaling over its boom elements and its
 * real-time check, and a stability suite of stiff and extreme cases.
 *
 *   bench [--problems LIST|none] [--solvers LIST] [--rtols LIST] [--repeat K] [--stability]
 *         [--quick] [--out DIR] [--crane-horizon T] [--crane-realtime K] [--scaling LIST|none]
 *         [--crane-scene FILE] [--stability-filter TEXT] [--strict] [--crane-full]
 *         [--crane-full-scene FILE] [--crane-full-rtols LIST] [--error-estimate] [--help]
 *         [--newton-dgmax G] [--crane-full-max-order K]
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
 * it, minutes per run), crane_wp_paper.csv (the same on the damped paper.ini, unless
 * --crane-full-scene is given) and, with --error-estimate (and --quick), error_estimate.csv (the estimate
 * of crane --error-estimate against the true error on the problems and tolerances of the run,
 * bench_errest.h). --newton-dgmax G runs ours on the collection with options.newton_dgmax = G
 * (the crane keeps its scene's setting), for comparing the Newton matrix refresh.
 * --crane-full-repeat K: the series' CPU times as medians of K runs; --crane-full-max-order K:
 * bgdae-klu's largest order there (the reference's stays 5). IDA's settings (bench_case.h
 * run_opts, docs/bench.md): --ida-klu-pivot-tol T (KLU's pivot tolerance in ida-klu, default 1),
 * --ida-scalar-atol (no nominal magnitudes in IDA's atol), --ida-index2-h (IDA's index-2
 * weights times |h|), --ida-newton-diag (the series' report: IDA's Newton corrections by kind).
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
 * Jacobian code (dense, or sparse CSC for KLU, whose failed refactorizations are redone with
 * fresh pivots as ours are: bench_ida_klu, bench_util.h); ours with exclude_alg on the crane as
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
 * Parts: this file runs the harness (main, a short driver over the steps below); bench_cli.c is
 * the command line (a table of options, the help generated from it), bench_report.c writes
 * work_precision.csv, the figures, steps_vs_tol.csv and report.md. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <unistd.h>

#include "bench_case.h"
#include "bench_cli.h"
#include "bench_crane.h"
#include "bench_errest.h"
#include "bench_model.h"
#include "bench_realtime.h"
#include "bench_mebdfi.h"
#include "bench_osc.h"
#include "bench_report.h"
#include "bench_stab.h"
#include "bench_util.h"
#include "problems.h"
#include "pu_fs.h"

#include "crane_scene.h"

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
    crane_scene full2; /* --crane-full's second scene, the damped paper.ini (have_full2) */
    int have_full2;
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
    bg_error err = {0};
    if (crane_scene_load(&b->scene, b->cli.scene_file, &err) != BG_OK) {
        fprintf(stderr, "bench: %s\n", err.message);
        return 2;
    }
    return BENCH_CLI_RUN;
}

/* --crane-full's scenes: --crane-full-scene FILE, or paper-undamped.ini and the damped
 * paper.ini, and the first one's name for the report. BENCH_CLI_RUN, or the exit status
 * (said). */
static int load_full_scene(harness *b)
{
    if (!b->cli.crane_full) return BENCH_CLI_RUN;
    if (!b->cli.full_scene) {
        bg_error e2 = {0};
        if (crane_scene_load(&b->full2, BENCH_SCENES_DIR "/paper.ini", &e2) != BG_OK) {
            fprintf(stderr, "bench: --crane-full: %s\n", e2.message);
            return 2;
        }
        b->have_full2 = 1;
    }
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
}

/* The crane's real-time check (bench_realtime.h), into tail: the main scene (paper, or
 * --crane-scene) and paper-undamped; the mesh series on the main scene over 1 s (--quick:
 * none). Run first, while this process is small: a child's ru_maxrss includes the
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
    bg_error err = {0};
    bench_rt_scene *u = &ex->rts[1];
    u->file = BENCH_SCENES_DIR "/paper-undamped.ini";
    u->label = "paper-undamped";
    u->target = 7.5;
    if (crane_scene_load(&u->s, u->file, &err) == BG_OK)
        ex->nrt = 2;
    else
        fprintf(stderr, "bench: the real-time check without paper-undamped: %s\n", err.message);
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
    ro.ida_klu_tol = b->cli.ida_klu_tol;
    ro.ida_scalar_atol = b->cli.ida_scalar_atol;
    ro.ida_index2_h = b->cli.ida_index2_h;
    /* IDA on a large case (the crane) is capped at twice our steps at this tolerance (those of
     * the row of bgdae-klu before it) plus 1 000: a run beyond that count has lost (with KLU's
     * default pivot tolerance, --ida-klu-pivot-tol 0.001, it was held at h = 3.5e-6 s at order 1
     * on the crane, 2.3 ms a step; bench_util.h, bench_ida_klu); the small cases keep the 10^6
     * of every run (IDA took up to 41 times our steps there and completed) */
    if (sd->ida && bc->large)
        for (int k = b->n - 2; k >= 0; k--)
            if (b->rows[k].ci == c && b->rows[k].rtol == rtol &&
                !strcmp(b->rows[k].sd->name, "bgdae-klu") && b->rows[k].r.status >= 0) {
                ro.max_steps = 2 * b->rows[k].r.steps + 1000;
                break;
            }
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
    bench_full_opts fo = {c->full_rtols, c->full_nr, 1e-10, c->full_repeat, c->ida_klu_tol,
                          c->ida_scalar_atol, c->ida_newton_diag, c->ida_index2_h,
                          c->full_max_order};
    if (c->crane_full)
        b->failures +=
            bench_crane_full(c->out, "crane_wp.csv", b->tail.f, &b->full, b->full_name, &fo);
    if (c->crane_full && b->have_full2)
        b->failures += bench_crane_full(c->out, "crane_wp_paper.csv", b->tail.f, &b->full2,
                                        "paper.ini", &fo);
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
    if (pu_mkdir_p(b->cli.out, 0755, NULL, 0) != 0) { /* errno says why */
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
    if (!b.oom && (b.cli.want_crane || b.cli.realtime_asked) && b.cli.realtime_runs > 0) {
        realtime_check(&b);
        b.failures += bench_model_files(BENCH_MODELS_DIR, b.cli.realtime_runs, b.cli.out, b.tail.f);
    }
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
