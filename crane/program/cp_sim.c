/* The crane program's runs (crane_program.h): the dynamic run on the runner's loop (rn_run.h)
 * with the crane's outputs, its watches of the rows (peak deflections, reach), the viz and the
 * error estimate as the loop's hooks; --static and --modes; model_stats.txt and the summary. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "crane_program.h"
#include "crane_setup.h"
#include "crane_static.h"

static int print_model_stats(rn_run *rn, FILE *f, const void *ctx)
{
    (void)ctx;
    cp_run *r = CP_RUN(rn);
    fprintf(f, "# crane model statistics\nscene: %s (%s)\n", r->scene.name, r->scene_path);
    crane_stats_print(r->c, f);
    return 0;
}

void cp_summary(cp_run *r)
{
    const dae_stats *st = r->rn.s ? dae_get_stats(r->rn.s) : NULL;
    int th = crane_output_index("theta"), thr = crane_output_index("theta_ref");
    if (r->o->modes) /* an analysis, not a run over [0, t_end] */
        printf("crane: scene %s, the modes at t = %g s: %s\n", r->scene.name, r->o->modes_t,
               r->rn.status);
    else if (r->o->static_only)
        printf("crane: scene %s, the static equilibrium: %s\n", r->scene.name, r->rn.status);
    else
        printf("crane: scene %s, %s at t = %g s (of %g s)\n", r->scene.name, r->rn.status,
               r->rn.t, r->scene.t_end);
    if (r->have_final && th >= 0)
        printf("  final angle     theta = %.6f rad%s", r->final_out[th], thr >= 0 ? "" : "\n");
    if (r->have_final && th >= 0 && thr >= 0) printf(" (reference %.6f rad)\n", r->final_out[thr]);
    if (r->rn.rows > 0 && r->col_d1 >= 0)
        printf("  peak tip deflections  %.6g m (luffing plane), %.6g m (sideways)\n", r->peak[0],
               r->peak[1]);
    if (st)
        printf("  steps %ld (rejected %ld), Newton iterations %ld, Jacobians %ld\n", st->steps,
               st->rejected_error, st->newton_iters, st->jac_evals);
    rn_estimate_summary(&r->rn);
    printf("  wall time %.2f s; results in %s/\n", rn_wall_now() - r->rn.wall0, r->rn.outdir);
}

static int print_start(rn_run *rn, FILE *f, const void *ctx)
{
    (void)rn;
    return crane_start_print(ctx, f);
}

static int print_equilibrium(rn_run *rn, FILE *f, const void *ctx)
{
    return crane_equilibrium_write(CP_RUN(rn)->c, ctx, f);
}

static int print_modes(rn_run *rn, FILE *f, const void *ctx)
{
    return rn_modes_write_drift(ctx, crane_mode_part, CP_RUN(rn)->drift_hz, f);
}

static int print_modes_plot(rn_run *rn, FILE *f, const void *ctx)
{
    cp_run *r = CP_RUN(rn);
    return crane_modes_plot_script(ctx, r->scene.name, r->o->modes_t, r->drift_hz, f);
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
        return rn_fail_run(&r->rn, "the static start", err.message);
    if (rn_save_file(&r->rn, "static.txt", print_start, &rep) != 0) return RN_EXIT_RUN;
    if (r->o->static_only &&
        rn_save_file(&r->rn, "equilibrium.csv", print_equilibrium, &rep) != 0)
        return RN_EXIT_RUN;
    if (rc == CRANE_ERR_START) {
        r->bad_scene = 1;
        rn_fail_run(&r->rn, "the static start", err.message);
        return RN_EXIT_USAGE;
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
    if (!r->c) return rn_fail_run(&r->rn, "building the model", err.message);
    if (rn_save_file(&r->rn, "model_stats.txt", print_model_stats, NULL) != 0) return RN_EXIT_RUN;
    rn_set_phase(&r->rn, RN_PHASE_SETUP, "finding the static equilibrium");
    int rc = static_start(r);
    if (rc != 0) return rc;
    if (r->o->modes) {
        rn_set_phase(&r->rn, RN_PHASE_SETUP, "computing the modes");
        dae_modes *M = NULL;
        double t0 = rn_wall_now();
        /* the drift modes' bound from the static start first (crane_static.h) */
        rc = crane_modes_drift(r->c, r->o->modes_t, &r->drift_hz, &err);
        if (rc == BG_OK) rc = crane_modes(r->c, r->o->modes_t, &M, NULL, &err);
        if (rc != BG_OK && rc != DAE_CONV_FAIL) {
            dae_modes_free(&M);
            return rn_fail_run(&r->rn, "the modes", err.message);
        }
        r->rn.t = r->o->modes_t;
        int ne = 0, nr = 0, nc = 0, nd = 0, method = 0;
        dae_modes_info(M, &ne, &nr, &nc, NULL, NULL, &method);
        for (int k = 0; k < dae_modes_count(M); k++)
            nd += !strcmp(rn_mode_kind(M, k, r->drift_hz), "drift");
        if (rn_save_file(&r->rn, "modes.csv", print_modes, M) != 0 ||
            rn_save_file(&r->rn, "modes.gp", print_modes_plot, M) != 0) {
            dae_modes_free(&M);
            return RN_EXIT_RUN;
        }
        if (!r->o->quiet) {
            char drift[160] = "";
            if (nd)
                snprintf(drift, sizeof drift,
                         "; %d drift modes below %.3g Hz, the invariants of the constraints "
                         "moving at a state in motion, not listed",
                         nd, r->drift_hz);
            printf("crane: %d elastic, %d rigid, %d constraint modes at t = %g s (%s, %.3f s)%s\n",
                   ne - nd, nr, nc, r->o->modes_t,
                   method == DAE_MODES_DENSE ? "dense" : "lowest 20 by ARPACK", rn_wall_now() - t0,
                   drift);
            for (int k = 0, shown = 0; k < dae_modes_count(M) && shown < 5; k++) {
                const dae_mode *md = dae_modes_get(M, k);
                if (nd && !strcmp(rn_mode_kind(M, k, r->drift_hz), "drift")) continue;
                char d[256];
                dae_modes_describe(M, k, 2, 2, 0, d, sizeof d);
                printf("  mode %d: %.6g Hz, damping ratio %.3g, %s\n", k + 1, md->freq_hz,
                       md->damping, d);
                shown++;
            }
        }
        dae_modes_free(&M);
        if (cp_draw_modes(r) != 0) return RN_EXIT_RUN;
    }
    r->rn.status = "completed";
    return 0;
}

/* ------------------------------------------------------ the run loop's hooks ---- */

/* Column of output a, or of b if the model has no a (-1: neither). */
static int col_any(const char *a, const char *b)
{
    int c = crane_output_index(a);
    return c >= 0 || !b ? c : crane_output_index(b);
}

static int outputs(void *ctx, double t, const double *y, const double *yp, double *out,
                   char *msg, size_t size)
{
    (void)msg, (void)size;
    crane_outputs(((cp_run *)ctx)->c, t, y, yp, out);
    return 0;
}

/* The peaks and reach the figures and the summary use, the first and last rows. */
static void watch(void *ctx, double t, const double *out)
{
    cp_run *r = ctx;
    int d1 = r->col_d1, d2 = r->col_d2, tx = r->col_tx, ty = r->col_ty;
    if (d1 >= 0 && fabs(out[d1]) > r->peak[0]) r->peak[0] = fabs(out[d1]);
    if (d2 >= 0 && fabs(out[d2]) > r->peak[1]) r->peak[1] = fabs(out[d2]);
    if (tx >= 0 && ty >= 0) {
        double ex = fabs(out[tx] - r->scene.joint_A[0]), ey = fabs(out[ty] - r->scene.joint_A[1]);
        if (isfinite(ex) && ex > r->reach) r->reach = ex;
        if (isfinite(ey) && ey > r->reach) r->reach = ey;
    }
    if (r->rn.rows == 1) memcpy(r->first_out, out, sizeof r->first_out);
    memcpy(r->final_out, out, sizeof r->final_out);
    r->final_out[0] = t;
    r->have_final = 1;
}

/* The viz's frame (the loop then advances the error estimate's companion to the same time). */
static int row(void *ctx, long k, double t, const double *y, const double *yp, const double *out)
{
    (void)k, (void)out;
    cp_run *r = ctx;
    if (r->viz) crane_viz_row(r->viz, t, y, yp);
    return 0;
}

int cp_simulate(cp_run *r)
{
    const cp_options *o = r->o;
    bg_error err = {0};
    int tty = isatty(STDERR_FILENO) && !o->quiet;
    double *bk = NULL, *y = NULL, *yp = NULL;
    int code = RN_EXIT_OK;
    dae_options dopt;
    dae_options_default(&dopt);

    if (tty) fprintf(stderr, "crane: building the model (scene %s)\n", r->scene.name);
    rn_set_phase(&r->rn, RN_PHASE_SETUP, "building the model");
    r->c = crane_build(&r->scene, &err);
    if (!r->c) return rn_fail_run(&r->rn, "building the model", err.message);
    if (rn_save_file(&r->rn, "model_stats.txt", print_model_stats, NULL) != 0) return RN_EXIT_RUN;
    if (r->scene.static_start) {
        if (tty) fprintf(stderr, "crane: static equilibrium under gravity\n");
        rn_set_phase(&r->rn, RN_PHASE_SETUP, "finding the static equilibrium");
        int rc = static_start(r);
        if (rc != 0) return rc;
    }
    bgr_model *m = crane_model(r->c);
    dae_problem p;
    if (crane_dae_problem(r->c, &p) != BG_OK)
        return rn_fail_run(&r->rn, "problem", bgr_model_error(m)->message);
    int n = p.n;

    y = malloc((size_t)n * sizeof *y);
    yp = malloc((size_t)n * sizeof *yp);
    if (!y || !yp || crane_solver_setup(&r->scene, r->c, &dopt, &bk, &err) != BG_OK) {
        code = rn_fail_run(&r->rn, "memory", "out of memory");
        goto done;
    }
    if ((code = rn_solver_start(&r->rn, &p, &dopt, bgr_y0(m), bgr_yp0(m))) != 0) goto done;

    /* --error-estimate: the companion from the same start (rn_estimate_open) */
    cp_errest_open(r, &p, &dopt, bgr_y0(m), bgr_yp0(m));
    rn_set_phase(&r->rn, RN_PHASE_OTHER, NULL);
    r->col_d1 = col_any("tip_defl_1", "defl_luff");
    r->col_d2 = col_any("tip_defl_2", "defl_side");
    r->col_tx = crane_output_index("tip_x");
    r->col_ty = crane_output_index("tip_y");
    if ((code = rn_csv_open(&r->rn, crane_output_names, CRANE_NOUT)) != 0) goto done;
    r->viz = crane_viz_open(&o->viz, r->c, r->rn.outdir, r->scene.name, o->quiet);

    rn_loop_spec sp = {.output_step = r->scene.output_step,
                       .t_end = r->scene.t_end,
                       .ncols = CRANE_NOUT,
                       .outputs = outputs,
                       .watch = watch,
                       .row = row,
                       .ctx = r,
                       .progress = tty};
    /* the rows interpolate the unknowns the outputs read, unless the viz's frames need the
     * whole state */
    int ounk[CRANE_MAX_OUTPUT_UNKNOWNS];
    if (!r->viz) {
        sp.unknowns = ounk;
        sp.nunknowns = crane_output_unknowns(r->c, ounk);
    }
    code = rn_loop(&r->rn, &sp, y, yp);

done:
    if (rn_loop_end(&r->rn) != 0) code = RN_EXIT_RUN; /* with error_estimate.csv */
    /* the animation is rendered only for a run that reached t_end with no signal pending */
    char why[1024] = "";
    if (crane_viz_close(&r->viz, !strcmp(r->rn.status, "completed") && !rn_signal(), why,
                        sizeof why) != 0 &&
        !strcmp(r->rn.status, "completed") && !rn_signal()) {
        r->rn.status = "failed"; /* said on stderr already: the reason only for status.txt */
        snprintf(r->rn.reason, sizeof r->rn.reason, "%s", why);
        code = RN_EXIT_RUN;
    }
    if (r->rn.s) {
        rn_stats_info info = {&dopt, dopt.nbreakpoints, bk, r->scene.output_step,
                              r->scene.nominal_scales, NULL};
        if (rn_save_file(&r->rn, "solver_stats.txt", rn_print_solver_stats, &info) != 0)
            code = RN_EXIT_RUN;
    }
    free(bk);
    free(y);
    free(yp);
    return code;
}
