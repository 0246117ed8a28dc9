/* bgsim's runs (bgsim.h): the dynamic run on the runner's loop (rn_run.h) with the model's
 * outputs (mdl_outputs of the compiled bgr_model: nothing per step depends on the file) and
 * with --error-estimate the runner's companion run on the same outputs (rn_estimate.c), the
 * static start with the file's trim, the modes; the files model.yaml, model_stats.txt,
 * static.txt, equilibrium.csv, modes.csv, solver_stats.txt; the summary. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "bgr_analysis.h"
#include "bgsim.h"

/* ------------------------------------------------------------------- files ---- */

/* model.yaml: the file as read with the replacements (mdl_write_as_run), and the command line's
 * solver settings as comments. */
static int print_model(rn_run *rn, FILE *f, const void *ctx)
{
    (void)ctx;
    bs_run *r = BS_RUN(rn);
    if (mdl_write_as_run(r->mm, f) != BG_OK) return -1;
    const bs_options *o = r->o;
    if (o->has_t_end || o->has_rtol || o->has_atol || o->has_output_step)
        fprintf(f, "# run with these solver settings from the command line:\n");
    if (o->has_t_end) fprintf(f, "#   t_end: %.17g\n", o->t_end);
    if (o->has_output_step) fprintf(f, "#   output_step: %.17g\n", o->output_step);
    if (o->has_rtol) fprintf(f, "#   rtol: %.17g\n", o->rtol);
    if (o->has_atol) fprintf(f, "#   atol: %.17g\n", o->atol);
    return 0;
}

/* model_stats.txt: bgr_stats_print, then the unknowns by top-level instance (the first segment
 * of their names, in the order first met). */
static int print_model_stats(rn_run *rn, FILE *f, const void *ctx)
{
    (void)ctx;
    bs_run *r = BS_RUN(rn);
    bgr_model *m = mdl_bgr(r->mm);
    fprintf(f, "# bgsim model statistics\nmodel: %s (%s)\n", mdl_name(r->mm), r->model_path);
    if (bgr_stats_print(m, f) != BG_OK) return -1;
    int n = bgr_n(m), ninst = 0;
    const int *kind = bgr_kinds(m);
    char (*inst)[128] = calloc((size_t)n + 1, sizeof *inst);
    int(*cnt)[2] = calloc((size_t)n + 1, sizeof *cnt);
    if (!inst || !cnt) {
        free(inst);
        free(cnt);
        return -1;
    }
    for (int i = 0; i < n; i++) {
        char name[1024];
        bs_unknown_name(r->mm, i, name, sizeof name);
        size_t l = strcspn(name, ".");
        int j = 0;
        while (j < ninst && (strlen(inst[j]) != l || strncmp(inst[j], name, l)))
            j++;
        if (j == ninst)
            snprintf(inst[ninst++], sizeof inst[0], "%.*s", (int)(l < 127 ? l : 127), name);
        cnt[j][kind && kind[i] != 0]++;
    }
    fprintf(f, "\nunknowns by top-level instance (differential, algebraic):\n");
    for (int j = 0; j < ninst; j++)
        fprintf(f, "  %-24s %6d %6d\n", inst[j], cnt[j][0], cnt[j][1]);
    free(inst);
    free(cnt);
    return 0;
}

int bs_save_model(bs_run *r)
{
    if (rn_save_file(&r->rn, "model.yaml", print_model, NULL) != 0) return RN_EXIT_RUN;
    return rn_save_file(&r->rn, "model_stats.txt", print_model_stats, NULL) != 0 ? RN_EXIT_RUN : 0;
}

/* static.txt: the static solve's figures and the trim's. */
static int print_static(rn_run *rn, FILE *f, const void *ctx)
{
    const int *status = ctx;
    bs_run *r = BS_RUN(rn);
    const mdl_trim_report *t = &r->trim;
    const dae_static_result *s = &t->last;
    fprintf(f, "# bgsim static start\nmodel: %s (%s)\nstatus: %s\n", mdl_name(r->mm),
            r->model_path, *status == BG_OK ? "found" : dae_return_name(*status));
    fprintf(f, "load_factor: %.9g\nsteps: %ld (rejected %ld)\nnewton_iterations: %ld\n",
            s->lambda, s->steps, s->rejected, s->newton_iters);
    fprintf(f, "scaled_residual: %.3g (<= 1: within the tolerance)\n", s->residual);
    fprintf(f, "seconds: %.3f\n", s->seconds);
    if (t->trimmed)
        fprintf(f,
                "trim: %s adjusted until %s = %.9g\ntrim_value: %s = %.12g\ntrim_achieved: %s = "
                "%.12g\ntrim_solves: %d\n",
                t->parameter, t->output, t->target, t->parameter, t->value, t->output,
                t->achieved, t->solves);
    else
        fprintf(f, "trim: none\n");
    return 0;
}

/* equilibrium.csv: kind,name,value for every unknown, then the outputs at the equilibrium. */
static int print_equilibrium(rn_run *rn, FILE *f, const void *ctx)
{
    (void)ctx;
    bs_run *r = BS_RUN(rn);
    bgr_model *m = mdl_bgr(r->mm);
    const double *y = bgr_y0(m);
    fprintf(f, "kind,name,value\n");
    for (int i = 0; i < bgr_n(m); i++) {
        char name[1024];
        fprintf(f, "unknown,%s,%.17g\n", bs_unknown_name(r->mm, i, name, sizeof name), y[i]);
    }
    int no = mdl_noutputs(r->mm);
    double *out = malloc(((size_t)no + 1) * sizeof *out);
    bg_error err = {0};
    if (!out || mdl_outputs(r->mm, 0.0, y, out, &err) != BG_OK) {
        free(out);
        return -1;
    }
    for (int i = 0; i < no; i++)
        fprintf(f, "output,%s,%.17g\n", mdl_output_name(r->mm, i), out[i]);
    free(out);
    return 0;
}

static int print_modes(rn_run *rn, FILE *f, const void *ctx)
{
    (void)rn;
    return rn_modes_write(ctx, NULL, f) == BG_OK ? 0 : -1;
}

/* ------------------------------------------------------------------- runs ---- */

/* The static start (mdl_static, with the file's trim; the model may be rebuilt), static.txt,
 * and with --static equilibrium.csv. 0, or the exit status. */
static int static_start(bs_run *r)
{
    rn_set_phase(&r->rn, RN_PHASE_SETUP, "finding the static equilibrium");
    dae_static_options so;
    dae_static_options_default(&so);
    bg_error err = {0};
    int st = mdl_static(&r->mm, &so, &r->trim, &err);
    r->static_done = 1;
    rn_set_phase(&r->rn, RN_PHASE_OTHER, NULL);
    if (rn_save_file(&r->rn, "static.txt", print_static, &st) != 0) return RN_EXIT_RUN;
    if (st != BG_OK) return rn_fail_run(&r->rn, "the static start", err.message);
    /* a trim rebuilds the model: the command line's solver settings again */
    if (mdl_solver_override(r->mm, &r->solver) != BG_OK)
        return rn_fail_run(&r->rn, "the solver settings", "out of range");
    if (r->o->static_only &&
        rn_save_file(&r->rn, "equilibrium.csv", print_equilibrium, NULL) != 0)
        return RN_EXIT_RUN;
    return 0;
}

int bs_analyse(bs_run *r)
{
    int rc;
    /* the modes at T = 0 are those of the static equilibrium, as the crane program's: a given
     * start leaves the constraint forces at zero, and the linearisation there misses every
     * stiffness they carry (a pendulum's swing) */
    if ((r->o->static_only || (r->o->modes && r->o->modes_t == 0) ||
         mdl_start_kind(r->mm) == MDL_START_STATIC) &&
        (rc = static_start(r)) != 0)
        return rc;
    if (r->o->modes) {
        rn_set_phase(&r->rn, RN_PHASE_SETUP, "computing the modes");
        bgr_model *m = mdl_bgr(r->mm);
        int n = bgr_n(m);
        double *y = malloc((size_t)n * sizeof *y), *yp = calloc((size_t)n, sizeof *yp);
        double *bk = NULL;
        bg_error err = {0};
        dae_modes *M = NULL;
        if (!y || !yp) {
            free(y);
            free(yp);
            return rn_fail_run(&r->rn, "memory", "out of memory");
        }
        memcpy(y, bgr_y0(m), (size_t)n * sizeof *y);
        rc = BG_OK;
        if (r->o->modes_t > 0) { /* the dynamic run to T, as bgsim sets it up */
            dae_options o;
            dae_problem p;
            double tr;
            rc = mdl_dae_options(r->mm, &o, &bk);
            if (rc == BG_OK) rc = mdl_dae_problem(r->mm, &p);
            o.t_stop = fmax(o.t_stop, r->o->modes_t);
            if (rc == BG_OK && rn_solver_start(&r->rn, &p, &o, bgr_y0(m), bgr_yp0(m)) != 0) {
                free(y), free(yp), free(bk);
                return RN_EXIT_RUN;
            }
            rn_set_phase(&r->rn, RN_PHASE_SETUP, "running to the modes' time");
            if (rc == BG_OK && (rc = dae_solve_to(r->rn.s, r->o->modes_t, &tr, y, yp)) >= 0)
                rc = BG_OK;
            if (rc != BG_OK) {
                char why[BG_MESSAGE_SIZE + 64];
                snprintf(why, sizeof why, "the run to t = %g: %s", r->o->modes_t,
                         dae_get_error(r->rn.s)->message);
                free(y), free(yp), free(bk);
                return rn_fail_run(&r->rn, "the modes", why);
            }
        }
        if (rc == BG_OK) {
            dae_modes_options mo;
            dae_modes_options_default(&mo);
            mo.dense_max = 1200;
            mo.nev = 20;
            /* at T > 0 the state moves: --modes T asks for the frozen linearisation at that
             * instant (as the crane program's; bg_modes.h, frozen) */
            mo.frozen = r->o->modes_t > 0;
            rc = bgr_modes(m, r->o->modes_t, y, yp, &mo, &M, &err);
        }
        free(y), free(yp), free(bk);
        rn_set_phase(&r->rn, RN_PHASE_OTHER, NULL);
        if (rc != BG_OK && rc != DAE_CONV_FAIL) {
            dae_modes_free(&M);
            return rn_fail_run(&r->rn, "the modes", err.message);
        }
        r->rn.t = r->o->modes_t;
        r->nmodes = dae_modes_count(M);
        rc = rn_save_file(&r->rn, "modes.csv", print_modes, M);
        if (rc == 0 && !r->o->quiet)
            for (int k = 0; k < dae_modes_count(M) && k < 5; k++) {
                const dae_mode *md = dae_modes_get(M, k);
                char d[256];
                dae_modes_describe(M, k, 2, 2, 0, d, sizeof d);
                printf("  mode %d: %.6g Hz, damping ratio %.3g, %s %s\n", k + 1, md->freq_hz,
                       md->damping, dae_mode_kind_name(md->kind), d);
            }
        dae_modes_free(&M);
        if (rc != 0) return RN_EXIT_RUN;
    }
    r->rn.status = "completed";
    return 0;
}

/* The loop's outputs: t, then mdl_outputs at (t, y). */
static int outputs(void *ctx, double t, const double *y, const double *yp, double *out,
                   char *msg, size_t size)
{
    (void)yp;
    bs_run *r = ctx;
    bg_error err = {0};
    out[0] = t;
    if (mdl_outputs(r->mm, t, y, out + 1, &err) != BG_OK) {
        snprintf(msg, size, "%s", err.message);
        return -1;
    }
    return 0;
}

/* The companion's outputs (--error-estimate): the loop's, NAN where they cannot be computed
 * (the column then has no values). */
static void estimate_outputs(void *ctx, double t, const double *y, const double *yp, double *out)
{
    bs_run *r = ctx;
    char msg[BG_MESSAGE_SIZE + 64];
    if (outputs(ctx, t, y, yp, out, msg, sizeof msg) != 0)
        for (int i = 0; i < mdl_noutputs(r->mm); i++)
            out[i + 1] = NAN;
}

static void watch(void *ctx, double t, const double *out)
{
    bs_run *r = ctx;
    memcpy(r->final_out, out, ((size_t)mdl_noutputs(r->mm) + 1) * sizeof *out);
    r->final_out[0] = t;
    r->have_final = 1;
}

/* --vtk: the model drawn at a row (mdl_geometry) as the series' next frame, every vtk_every rows
 * and at the last; a frame that cannot be drawn or written stops the series, its reason kept
 * for status.txt (the run goes on: its results do not depend on the pictures) */
static int vtk_row(void *ctx, long k, double t, const double *y, const double *yp,
                   const double *out)
{
    (void)yp, (void)out;
    bs_run *r = ctx;
    if (!r->vtk || (k % r->vtk_every != 0 && k != r->rn.nout)) return 0;
    bg_error err = {0};
    char msg[BG_MESSAGE_SIZE + 64];
    int bad = mdl_geometry(r->mm, y, &r->geom, &err) != BG_OK;
    if (bad) snprintf(msg, sizeof msg, "the drawing at t = %g s: %s", t, err.message);
    if (!bad) {
        pu_vtk_frame f = {t, mdl_name(r->mm), r->geom.npoints, r->geom.x, r->geom.point_part,
                          r->geom.nmarks, r->geom.mark_point, r->geom.mark_part, r->geom.nlines,
                          r->geom.line_start, r->geom.line_conn, r->geom.line_part,
                          r->geom.nparts, r->geom.part_path};
        bad = pu_vtk_write(r->vtk, &f, msg, sizeof msg) != 0;
    }
    if (bad) {
        snprintf(r->vtk_error, sizeof r->vtk_error, "%s", msg);
        fprintf(stderr, "%s: ParaView series stopped: %s\n", r->rn.program, msg);
        pu_vtk_close(&r->vtk);
    }
    return 0;
}

/* --vtk: the series opened in the output folder; a frame every vtk_step (whole output steps) */
static int vtk_open(bs_run *r)
{
    if (!r->o->vtk) return 0;
    double dt = r->solver.output_step, step = r->o->has_vtk_step ? r->o->vtk_step : dt;
    double every = step / dt;
    r->vtk_every = every < 1 ? 1 : every > 1e15 ? (long)1e15 : (long)(every + 0.5);
    char comment[RN_PATH_SIZE + 512], msg[900];
    snprintf(comment, sizeof comment,
             "model %s (%s): the motion as a time series, one PolyData file per frame; global "
             "frame; SI units; see docs/bgsim.md",
             mdl_name(r->mm), r->model_path);
    r->vtk = pu_vtk_open(r->rn.outdir, "model.pvd", comment, msg, sizeof msg);
    if (!r->vtk) return rn_fail_run(&r->rn, "the ParaView series", msg);
    return 0;
}

int bs_simulate(bs_run *r)
{
    int code = 0, tty = isatty(STDERR_FILENO) && !r->o->quiet;
    if (mdl_start_kind(r->mm) == MDL_START_STATIC && (code = static_start(r)) != 0) return code;
    bgr_model *m = mdl_bgr(r->mm);
    int n = bgr_n(m), no = mdl_noutputs(r->mm);
    dae_problem p;
    dae_options dopt;
    double *bk = NULL, *y = malloc((size_t)n * sizeof *y), *yp = malloc((size_t)n * sizeof *yp);
    const char **names = r->names = malloc(((size_t)no + 1) * sizeof *names);
    r->final_out = malloc(((size_t)no + 1) * sizeof *r->final_out);
    if (!y || !yp || !names || !r->final_out || mdl_dae_options(r->mm, &dopt, &bk) != BG_OK ||
        mdl_dae_problem(r->mm, &p) != BG_OK) {
        code = rn_fail_run(&r->rn, "memory", "out of memory");
        goto done;
    }
    if ((code = rn_solver_start(&r->rn, &p, &dopt, bgr_y0(m), bgr_yp0(m))) != 0) goto done;
    names[0] = "t";
    for (int i = 0; i < no; i++)
        names[i + 1] = mdl_output_name(r->mm, i);
    /* --error-estimate: the companion from the same start, on the same outputs */
    rn_estimate_spec es = {&p, &dopt, bgr_y0(m), bgr_yp0(m), names, no + 1, estimate_outputs, r,
                           NULL};
    rn_estimate_open(&r->rn, &es);
    rn_set_phase(&r->rn, RN_PHASE_OTHER, NULL);
    if ((code = rn_csv_open(&r->rn, names, no + 1)) != 0) goto done;
    if ((code = vtk_open(r)) != 0) goto done;
    rn_loop_spec sp = {.output_step = r->solver.output_step,
                       .t_end = r->solver.t_end,
                       .ncols = no + 1,
                       .outputs = outputs,
                       .watch = watch,
                       .row = vtk_row,
                       .ctx = r,
                       .progress = tty};
    code = rn_loop(&r->rn, &sp, y, yp);
done:
    if (rn_loop_end(&r->rn) != 0) code = RN_EXIT_RUN;
    if (r->vtk && pu_vtk_close(&r->vtk) < 0 && !r->vtk_error[0])
        snprintf(r->vtk_error, sizeof r->vtk_error, "model.pvd could not be completed");
    if (r->vtk_error[0] && !strcmp(r->rn.status, "completed"))
        code = rn_fail_run(&r->rn, "writing the ParaView series", r->vtk_error);
    mdl_geom_clear(&r->geom);
    if (r->rn.s) {
        rn_stats_info info = {&dopt, dopt.nbreakpoints, bk, r->solver.output_step,
                              r->solver.nominal_scales, NULL};
        if (rn_save_file(&r->rn, "solver_stats.txt", rn_print_solver_stats, &info) != 0)
            code = RN_EXIT_RUN;
    }
    free(bk);
    free(y);
    free(yp);
    return code;
}

void bs_summary(const bs_run *r)
{
    const dae_stats *st = r->rn.s ? dae_get_stats(r->rn.s) : NULL;
    if (r->o->modes)
        printf("%s: model %s, the modes at t = %g s: %s (%d modes)\n", r->rn.program,
               r->rn.name, r->o->modes_t, r->rn.status, r->nmodes);
    else if (r->o->static_only)
        printf("%s: model %s, the static equilibrium: %s\n", r->rn.program, r->rn.name,
               r->rn.status);
    else
        printf("%s: model %s, %s at t = %g s (of %g s), %ld rows\n", r->rn.program,
               r->rn.name, r->rn.status, r->rn.t, r->rn.t_end, r->rn.rows_disk);
    if (r->static_done)
        printf("  static start: load factor %.6g, %ld steps, %ld Newton iterations%s\n",
               r->trim.last.lambda, r->trim.last.steps, r->trim.last.newton_iters,
               r->trim.trimmed ? " (trimmed: static.txt)" : "");
    if (r->have_final && !r->o->static_only && !r->o->modes) {
        int no = mdl_noutputs(r->mm);
        printf("  final row:");
        for (int i = 0; i < no && i < 8; i++)
            printf(" %s = %.6g", mdl_output_name(r->mm, i), r->final_out[i + 1]);
        printf("%s\n", no > 8 ? " ..." : "");
    }
    if (st)
        printf("  steps %ld (rejected %ld), Newton iterations %ld, Jacobians %ld\n", st->steps,
               st->rejected_error, st->newton_iters, st->jac_evals);
    rn_estimate_summary(&r->rn);
    if (r->extras && r->extras->summary) r->extras->summary(r, r->extras->ctx);
    printf("  wall time %.2f s; results in %s/\n", rn_wall_now() - r->rn.wall0, r->rn.outdir);
}
