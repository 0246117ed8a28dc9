/* The crane program's runs (crane_program.h): the dynamic run, a loop over the output times
 * that steps the solver one step at a time (a signal stops it between two steps) and writes a
 * row at each; --static and --modes; model_stats.txt, solver_stats.txt and the summary. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "crane_program.h"
#include "crane_setup.h"
#include "crane_static.h"

static void progress(cp_run *r, int tty, double *last)
{
    if (!tty) return;
    double now = cp_wall_now();
    if (now - *last < 0.25) return;
    *last = now;
    const dae_stats *st = dae_get_stats(r->s);
    double el = now - r->t_start, frac = r->t / r->scene.t_end;
    char eta[32] = "?";
    if (frac > 1e-3) snprintf(eta, sizeof eta, "%.0f s", el * (1 - frac) / frac);
    fprintf(stderr, "\r  t = %8.4f s  %5.1f %%  steps %7ld  h %9.3e s  left %-10s", r->t,
            100 * frac, st->steps, st->h_last, eta);
    fflush(stderr);
}

typedef struct solver_stats_ctx {
    const dae_options *dopt;
    int nbk;
    const double *bk;
} solver_stats_ctx;

static int print_solver_stats(cp_run *r, FILE *f, const void *ctx)
{
    const solver_stats_ctx *c = ctx;
    const dae_options *dopt = c->dopt;
    char line[2048], head[2048], row[2048];
    const dae_stats *st = dae_get_stats(r->s);
    double wall = cp_wall_now() - r->wall0;
    dae_stats_line(st, line, sizeof line);
    dae_stats_csv_header(head, sizeof head);
    dae_stats_csv(st, row, sizeof row);
    fprintf(f, "# crane solver statistics\n");
    fprintf(f, "scene: %s (%s)\nstatus: %s\n", r->scene.name, r->scene_path, r->status);
    fprintf(f, "rtol: %g\natol: %g\nt_end: %g s\noutput_step: %g s\n", dopt->rtol, dopt->atol,
            r->scene.t_end, r->scene.output_step);
    fprintf(f, "error test: algebraic and index-2 variables excluded\n");
    fprintf(f, "absolute tolerances: %s\nstability guard: %s\nbreakpoints:",
            r->scene.nominal_scales
                ? "atol times each unknown's nominal magnitude (the scales in model_stats.txt)"
                : "atol in SI units",
            dopt->stability_guard ? "on (order 2 where fast modes hold orders 3..5)" : "off");
    for (int i = 0; i < c->nbk; i++)
        fprintf(f, " %g", c->bk[i]);
    fprintf(f, "%s\n", c->nbk ? "" : " none");
    fprintf(f, "t_reached: %.9g s\nrows: %ld\nwall_time: %.3f s\n", r->t, r->rows_disk, wall);
    cp_errest_stats_lines(r, f);
    fprintf(f, "%s\n\n# CSV\n%s,wall_s\n%s,%.3f\n", line, head, row, wall);
    return 0;
}

static int print_model_stats(cp_run *r, FILE *f, const void *ctx)
{
    (void)ctx;
    fprintf(f, "# crane model statistics\nscene: %s (%s)\n", r->scene.name, r->scene_path);
    crane_stats_print(r->c, f);
    return 0;
}

void cp_summary(cp_run *r)
{
    const dae_stats *st = r->s ? dae_get_stats(r->s) : NULL;
    int th = crane_output_index("theta"), thr = crane_output_index("theta_ref");
    if (r->o->modes) /* an analysis, not a run over [0, t_end] */
        printf("crane: scene %s, the modes at t = %g s: %s\n", r->scene.name, r->o->modes_t,
               r->status);
    else if (r->o->static_only)
        printf("crane: scene %s, the static equilibrium: %s\n", r->scene.name, r->status);
    else
        printf("crane: scene %s, %s at t = %g s (of %g s)\n", r->scene.name, r->status, r->t,
               r->scene.t_end);
    if (r->have_final && th >= 0)
        printf("  final angle     theta = %.6f rad%s", r->final_out[th], thr >= 0 ? "" : "\n");
    if (r->have_final && th >= 0 && thr >= 0) printf(" (reference %.6f rad)\n", r->final_out[thr]);
    if (r->rows > 0 && r->col_d1 >= 0)
        printf("  peak tip deflections  %.6g m (luffing plane), %.6g m (sideways)\n", r->peak[0],
               r->peak[1]);
    if (st)
        printf("  steps %ld (rejected %ld), Newton iterations %ld, Jacobians %ld\n", st->steps,
               st->rejected_error, st->newton_iters, st->jac_evals);
    cp_errest_summary(r);
    printf("  wall time %.2f s; results in %s/\n", cp_wall_now() - r->wall0, r->outdir);
}

static int print_start(cp_run *r, FILE *f, const void *ctx)
{
    (void)r;
    return crane_start_print(ctx, f);
}

static int print_equilibrium(cp_run *r, FILE *f, const void *ctx)
{
    return crane_equilibrium_write(r->c, ctx, f);
}

static int print_modes(cp_run *r, FILE *f, const void *ctx)
{
    (void)r;
    return crane_modes_write(ctx, f);
}

static int print_modes_plot(cp_run *r, FILE *f, const void *ctx)
{
    return crane_modes_plot_script(ctx, r->scene.name, r->o->modes_t, f);
}

/* The static start (crane_static_start) with its checks in static.txt, and with --static
 * equilibrium.csv. Scene keys that cannot be met together end the run with exit 2. 0 or an exit
 * status. */
static int static_start(cp_run *r)
{
    static crane_start_report rep;
    bg_error err = {0};
    int rc = crane_static_start(r->c, &rep, &err);
    if (rc != BG_OK && rc != CRANE_ERR_START)
        return cp_fail_run(r, "the static start", err.message);
    if (cp_save_file(r, "static.txt", print_start, &rep) != 0) return CP_EXIT_RUN;
    if (r->o->static_only && cp_save_file(r, "equilibrium.csv", print_equilibrium, &rep) != 0)
        return CP_EXIT_RUN;
    if (rc == CRANE_ERR_START) {
        r->bad_scene = 1;
        cp_fail_run(r, "the static start", err.message);
        return CP_EXIT_USAGE;
    }
    if (!r->o->quiet && (r->o->static_only || r->o->modes))
        printf("crane: static start verified in %.3f s (%d static solves): tip radius %.9g m, "
               "ties' unstretched length %.9g m, kinetic energy %.2g J\n",
               rep.seconds, rep.solves, rep.radius, rep.tie_L0, rep.kinetic);
    return 0;
}

/* crane --static, crane --modes [T]: the analyses instead of the dynamic run. */
int cp_analyse(cp_run *r)
{
    bg_error err = {0};
    r->c = crane_build(&r->scene, &err);
    if (!r->c) return cp_fail_run(r, "building the model", err.message);
    if (cp_save_file(r, "model_stats.txt", print_model_stats, NULL) != 0) return CP_EXIT_RUN;
    cp_set_phase(r, CP_PHASE_SETUP, "finding the static equilibrium");
    int rc = static_start(r);
    if (rc != 0) return rc;
    if (r->o->modes) {
        cp_set_phase(r, CP_PHASE_SETUP, "computing the modes");
        dae_modes *M = NULL;
        double t0 = cp_wall_now();
        rc = crane_modes(r->c, r->o->modes_t, &M, NULL, &err);
        if (rc != BG_OK && rc != DAE_CONV_FAIL) {
            dae_modes_free(&M);
            return cp_fail_run(r, "the modes", err.message);
        }
        r->t = r->o->modes_t;
        int ne = 0, nr = 0, nc = 0, method = 0;
        dae_modes_info(M, &ne, &nr, &nc, NULL, NULL, &method);
        if (cp_save_file(r, "modes.csv", print_modes, M) != 0 ||
            cp_save_file(r, "modes.gp", print_modes_plot, M) != 0) {
            dae_modes_free(&M);
            return CP_EXIT_RUN;
        }
        if (!r->o->quiet) {
            printf("crane: %d elastic, %d rigid, %d constraint modes at t = %g s (%s, %.3f s)\n",
                   ne, nr, nc, r->o->modes_t,
                   method == DAE_MODES_DENSE ? "dense" : "lowest 20 by ARPACK", cp_wall_now() - t0);
            for (int k = 0; k < dae_modes_count(M) && k < 5; k++) {
                const dae_mode *md = dae_modes_get(M, k);
                char d[256];
                dae_modes_describe(M, k, 2, 2, 0, d, sizeof d);
                printf("  mode %d: %.6g Hz, damping ratio %.3g, %s\n", k + 1, md->freq_hz,
                       md->damping, d);
            }
        }
        dae_modes_free(&M);
        if (cp_draw_modes(r) != 0) return CP_EXIT_RUN;
    }
    r->status = "completed";
    return 0;
}

int cp_simulate(cp_run *r)
{
    const cp_options *o = r->o;
    bg_error err = {0};
    int tty = isatty(STDERR_FILENO) && !o->quiet;
    double *bk = NULL, *y = NULL, *yp = NULL;
    int code = CP_EXIT_OK;
    dae_options dopt;
    dae_options_default(&dopt);

    if (tty) fprintf(stderr, "crane: building the model (scene %s)\n", r->scene.name);
    cp_set_phase(r, CP_PHASE_SETUP, "building the model");
    r->c = crane_build(&r->scene, &err);
    if (!r->c) return cp_fail_run(r, "building the model", err.message);
    if (cp_save_file(r, "model_stats.txt", print_model_stats, NULL) != 0) return CP_EXIT_RUN;
    if (r->scene.static_start) {
        if (tty) fprintf(stderr, "crane: static equilibrium under gravity\n");
        cp_set_phase(r, CP_PHASE_SETUP, "finding the static equilibrium");
        int rc = static_start(r);
        if (rc != 0) return rc;
    }
    bgr_model *m = crane_model(r->c);
    dae_problem p;
    if (crane_dae_problem(r->c, &p) != BG_OK)
        return cp_fail_run(r, "problem", bgr_model_error(m)->message);
    int n = p.n;

    y = malloc((size_t)n * sizeof *y);
    yp = malloc((size_t)n * sizeof *yp);
    if (!y || !yp || crane_solver_setup(&r->scene, r->c, &dopt, &bk, &err) != BG_OK) {
        code = cp_fail_run(r, "memory", "out of memory");
        goto done;
    }
    bg_error_clear(&err);
    r->s = dae_create(&p, &dopt, &err);
    if (!r->s) {
        code = cp_fail_run(r, "solver", err.message);
        goto done;
    }
    cp_set_phase(r, CP_PHASE_SETUP, "computing consistent initial values");
    int rc = dae_init(r->s, 0.0, bgr_y0(m), bgr_yp0(m));
    if (rc == BG_OK) rc = dae_consistent_init(r->s);
    if (rc == DAE_WARNING) { /* found, with unknowns far from the values given: said, not fatal */
        fprintf(stderr, "crane: warning: %s\n", dae_get_warning(r->s));
        rc = BG_OK;
    }
    if (rc != BG_OK) {
        code = cp_fail_run(r, "consistent initial values", dae_get_error(r->s)->message);
        goto done;
    }

    /* --error-estimate: the companion from the same start (crane_errest.h) */
    cp_set_phase(r, CP_PHASE_SETUP,
                 "starting the run at the tighter tolerances (--error-estimate)");
    cp_errest_open(r, &p, &dopt, bgr_y0(m), bgr_yp0(m));
    cp_set_phase(r, CP_PHASE_OTHER, NULL);
    if ((code = cp_csv_open(r)) != 0) goto done;
    r->viz = crane_viz_open(&o->viz, r->c, r->outdir, r->scene.name, o->quiet);

    double out[CRANE_NOUT];
    dae_dense(r->s, 0.0, y, yp);
    crane_outputs(r->c, 0.0, y, yp, out);
    if ((code = cp_csv_row(r, 0.0, out)) != 0 || (code = cp_csv_flush(r)) != 0) goto done;
    if (r->viz) crane_viz_row(r->viz, 0.0, y, yp);
    cp_errest_row(r, 0.0, out);

    /* Output times k dt (k < nout) and t_end. The solver steps one step at a time up to each
     * (dae_step), with a look at the signal flag between two steps, so that a signal stops the run
     * within a step whatever the output step; the row is then interpolated in the last step
     * (dae_solve_to without a step: the values dae_solve_to alone would give). */
    double dt = r->scene.output_step, tend = r->scene.t_end, last = 0, tret = 0;
    long nout = r->nout, k;
    r->t_start = cp_wall_now();
    cp_set_phase(r, CP_PHASE_LOOP, NULL);
    for (k = 1; k <= nout; k++) {
        double tout = k == nout ? tend : (double)k * dt;
        if (tout > tend) tout = tend;
        while (dae_current_time(r->s) < tout) {
            if (cp_signal()) goto stopped;
            rc = dae_step(r->s, tout, &tret, y, yp);
            if (rc < 0) goto solver_failed;
            r->t = tret;
            progress(r, tty, &last);
        }
        rc = dae_solve_to(r->s, tout, &tret, y, yp);
        if (rc == BG_ERR_ARGUMENT) {
            /* tout within the round-off gap of a restart at a jump, just behind the last step:
             * the values where that step starts */
            double t0 = dae_current_time(r->s) - dae_get_stats(r->s)->h_last;
            if (t0 > tout && t0 - tout <= 1e-9 * fmax(1.0, fabs(tout)) &&
                dae_dense(r->s, t0, y, yp) == BG_OK) {
                tret = t0;
                rc = DAE_SUCCESS;
            }
        }
        if (rc < 0) goto solver_failed;
        if (tret > r->t) r->t = tret;
        crane_outputs(r->c, tret, y, yp, out);
        if ((code = cp_csv_row(r, tret, out)) != 0) goto done;
        if (r->viz) crane_viz_row(r->viz, tret, y, yp);
        /* the companion to the same time (a signal on its way: stopped, the row is written) */
        if (cp_errest_row(r, tret, out) == CRANE_ERREST_STOPPED && k < nout) {
            k++;
            goto stopped;
        }
    }
stopped:
    if (tty) fprintf(stderr, "\r%*s\r", 78, "");
    if (k <= nout) { /* a signal before t_end */
        r->sig = cp_signal();
        r->status = "interrupted";
        snprintf(r->reason, sizeof r->reason,
                 "%s received at t = %.9g s: stopped between two solver steps",
                 cp_signal_name(r->sig), r->t);
        fprintf(stderr, "crane: interrupted (%s) at t = %g s; %ld rows kept in %s/results.csv\n",
                cp_signal_name(r->sig), r->t, r->rows, r->outdir);
        code = 128 + r->sig;
    } else {
        r->status = "completed";
    }
    goto done;

solver_failed:
    r->t = tret;
    if (tty) fprintf(stderr, "\n");
    {
        char msg[BG_MESSAGE_SIZE + 64];
        snprintf(msg, sizeof msg, "%s (%s)", dae_get_error(r->s)->message, dae_return_name(rc));
        code = cp_fail_run(r, "solver", msg);
    }

done:
    if (cp_phase() != CP_PHASE_LOOP) { /* a failure during set-up: it stays a failure */
        cp_set_phase(r, CP_PHASE_OTHER, NULL);
        cp_arm_finishing(r);
    }
    if (cp_csv_close(r) != 0) code = CP_EXIT_RUN; /* the last rows, then what a signal leaves */
    cp_set_phase(r, CP_PHASE_OTHER, NULL);
    cp_arm_finishing(r);
    if (r->csv_size > 0 && cp_errest_write(r) != 0) code = CP_EXIT_RUN;
    /* the animation is rendered only for a run that reached t_end with no signal pending */
    if (crane_viz_close(&r->viz, !strcmp(r->status, "completed") && !cp_signal()) != 0 &&
        !strcmp(r->status, "completed"))
        code = cp_fail_run(r, "writing the ParaView series or the animation", "see above");
    if (r->s) {
        solver_stats_ctx ctx = {&dopt, dopt.nbreakpoints, bk};
        if (cp_save_file(r, "solver_stats.txt", print_solver_stats, &ctx) != 0) code = CP_EXIT_RUN;
    }
    free(bk);
    free(y);
    free(yp);
    return code;
}
