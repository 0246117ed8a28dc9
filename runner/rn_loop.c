/* The run itself (rn_run.h): the solver started from consistent initial values, the loop over
 * the output times that steps the solver one step at a time (a signal stops it between two
 * steps) and writes a row at each, the progress line, solver_stats.txt and modes.csv. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rn_run.h"

int rn_solver_start(rn_run *r, const dae_problem *p, const dae_options *o, const double *y0,
                    const double *yp0)
{
    bg_error err = {0};
    r->s = dae_create(p, o, &err);
    if (!r->s) return rn_fail_run(r, "solver", err.message);
    rn_set_phase(r, RN_PHASE_SETUP, "computing consistent initial values");
    int rc = dae_init(r->s, 0.0, y0, yp0);
    if (rc == BG_OK) rc = dae_consistent_init(r->s);
    if (rc == DAE_WARNING) { /* found, with unknowns far from the values given: said, not fatal */
        fprintf(stderr, "%s: warning: %s\n", r->program, dae_get_warning(r->s));
        rc = BG_OK;
    }
    if (rc != BG_OK)
        return rn_fail_run(r, "consistent initial values", dae_get_error(r->s)->message);
    return 0;
}

static void progress(rn_run *r, double *last)
{
    double now = rn_wall_now();
    if (now - *last < 0.25) return;
    *last = now;
    const dae_stats *st = dae_get_stats(r->s);
    double el = now - r->t_start, frac = r->t / r->t_end;
    char eta[32] = "?";
    if (frac > 1e-3) snprintf(eta, sizeof eta, "%.0f s", el * (1 - frac) / frac);
    fprintf(stderr, "\r  t = %8.4f s  %5.1f %%  steps %7ld  h %9.3e s  left %-10s", r->t,
            100 * frac, st->steps, st->h_last, eta);
    fflush(stderr);
}

/* The outputs at (t, y, yp) and the row. 0, or the failure. */
static int row(rn_run *r, const rn_loop_spec *sp, double t, const double *y, const double *yp,
               double *out)
{
    char msg[BG_MESSAGE_SIZE + 64] = "";
    if (sp->outputs(sp->ctx, t, y, yp, out, msg, sizeof msg) != 0)
        return rn_fail_run(r, "outputs", msg);
    long before = r->rows;
    int rc = rn_csv_row(r, t, out);
    if (sp->watch && r->rows > before) sp->watch(sp->ctx, t, out);
    return rc;
}

int rn_loop(rn_run *r, const rn_loop_spec *sp, double *y, double *yp)
{
    double *out = malloc((size_t)sp->ncols * sizeof *out);
    if (!out) return rn_fail_run(r, "memory", "out of memory");
    int code = 0, rc = 0;
    if (sp->unknowns && sp->nunknowns > 0 &&
        dae_set_output_unknowns(r->s, sp->unknowns, sp->nunknowns) != BG_OK) {
        free(out);
        return rn_fail_run(r, "outputs", dae_get_error(r->s)->message);
    }
    dae_dense(r->s, 0.0, y, yp);
    if ((code = row(r, sp, 0.0, y, yp, out)) != 0 || (code = rn_csv_flush(r)) != 0) goto done;
    if (sp->row) sp->row(sp->ctx, 0, 0.0, y, yp, out);
    rn_estimate_row(r, 0, 0.0, out);

    /* Output times k dt (k < nout) and t_end. The solver steps one step at a time up to each
     * (dae_step), with a look at the signal flag between two steps, so that a signal stops the run
     * within a step whatever the output step; the row is then interpolated in the last step
     * (dae_solve_to without a step: the values dae_solve_to alone would give). The steps return
     * no state (y, yp NULL): only the rows' states are used, and each costs an interpolation. */
    double dt = sp->output_step, tend = sp->t_end, last = 0, tret = 0;
    long nout = r->nout, k;
    r->t_start = rn_wall_now();
    rn_set_phase(r, RN_PHASE_LOOP, NULL);
    for (k = 1; k <= nout; k++) {
        double tout = k == nout ? tend : (double)k * dt;
        if (tout > tend) tout = tend;
        while (dae_current_time(r->s) < tout) {
            if (rn_signal()) goto stopped;
            rc = dae_step(r->s, tout, &tret, NULL, NULL);
            if (rc < 0) goto solver_failed;
            r->t = tret;
            if (sp->progress) progress(r, &last);
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
        if ((code = row(r, sp, tret, y, yp, out)) != 0) goto done;
        /* a companion run stopped by a signal on its way: the row is written, the run ends */
        int stop = sp->row && sp->row(sp->ctx, k, tret, y, yp, out) == RN_LOOP_STOP;
        if (rn_estimate_row(r, k, tret, out) == RN_LOOP_STOP) stop = 1;
        if (stop && k < nout) {
            k++;
            goto stopped;
        }
    }
stopped:
    if (sp->progress) fprintf(stderr, "\r%*s\r", 78, "");
    if (k <= nout) { /* a signal before t_end */
        r->sig = rn_signal();
        r->status = "interrupted";
        snprintf(r->reason, sizeof r->reason,
                 "%s received at t = %.9g s: stopped between two solver steps",
                 rn_signal_name(r->sig), r->t);
        fprintf(stderr, "%s: interrupted (%s) at t = %g s; %ld rows kept in %s/results.csv\n",
                r->program, rn_signal_name(r->sig), r->t, r->rows, r->outdir);
        code = 128 + r->sig;
    } else {
        r->status = "completed";
    }
    goto done;

solver_failed:
    r->t = tret;
    if (sp->progress) fprintf(stderr, "\n");
    {
        char msg[BG_MESSAGE_SIZE + 64];
        snprintf(msg, sizeof msg, "%s (%s)", dae_get_error(r->s)->message, dae_return_name(rc));
        code = rn_fail_run(r, "solver", msg);
    }

done:
    free(out);
    return code;
}

int rn_loop_end(rn_run *r)
{
    int code = 0;
    if (rn_phase() != RN_PHASE_LOOP) { /* a failure during set-up: it stays a failure */
        rn_set_phase(r, RN_PHASE_OTHER, NULL);
        rn_arm_finishing(r);
    }
    if (rn_csv_close(r) != 0) code = RN_EXIT_RUN; /* the last rows, then what a signal leaves */
    rn_set_phase(r, RN_PHASE_OTHER, NULL);
    rn_arm_finishing(r);
    if (r->csv_size > 0 && rn_estimate_write(r) != 0) code = RN_EXIT_RUN;
    return code;
}

int rn_print_solver_stats(rn_run *r, FILE *f, const void *info)
{
    const rn_stats_info *c = info;
    const dae_options *dopt = c->dopt;
    char line[2048], head[2048], row[2048];
    const dae_stats *st = dae_get_stats(r->s);
    double wall = rn_wall_now() - r->wall0;
    dae_stats_line(st, line, sizeof line);
    dae_stats_csv_header(head, sizeof head);
    dae_stats_csv(st, row, sizeof row);
    fprintf(f, "# %s solver statistics\n", r->program);
    fprintf(f, "%s: %s (%s)\nstatus: %s\n", r->subject, r->name, r->path, r->status);
    fprintf(f, "rtol: %g\natol: %g\nt_end: %g s\noutput_step: %g s\n", dopt->rtol, dopt->atol,
            r->t_end, c->output_step);
    fprintf(f, "error test: algebraic and index-2 variables excluded\n");
    fprintf(f, "absolute tolerances: %s\nstability guard: %s\nbreakpoints:",
            c->nominal_scales
                ? "atol times each unknown's nominal magnitude (the scales in model_stats.txt)"
                : "atol in SI units",
            dopt->stability_guard ? "on (order 2 where fast modes hold orders 3..5)" : "off");
    for (int i = 0; i < c->nbk; i++)
        fprintf(f, " %g", c->bk[i]);
    fprintf(f, "%s\n", c->nbk ? "" : " none");
    fprintf(f, "t_reached: %.9g s\nrows: %ld\nwall_time: %.3f s\n", r->t, r->rows_disk, wall);
    rn_estimate_stats_lines(r, f);
    if (c->extra) c->extra(r, f);
    fprintf(f, "%s\n\n# CSV\n%s,wall_s\n%s,%.3f\n", line, head, row, wall);
    return 0;
}

/* The top-level component: the first segment under the model's root ("pendulum/rod1 93%" ->
 * "rod1"), the whole first segment when the name has no root. */
const char *rn_mode_part_top(const dae_modes *M, int k, char *buf, size_t size)
{
    char d[256];
    snprintf(buf, size, "other");
    if (dae_modes_describe(M, k, 2, 1, 0, d, sizeof d) <= 0) return buf;
    const char *a = strchr(d, '/');
    a = a && a < d + strcspn(d, " ") ? a + 1 : d;
    size_t l = strcspn(a, " /");
    if (l > 0) snprintf(buf, size, "%.*s", (int)(l < 63 ? l : 63), a);
    return buf;
}

const char *rn_mode_kind(const dae_modes *M, int k, double drift_hz)
{
    const dae_mode *md = dae_modes_get(M, k);
    if (!md) return "unknown";
    if (md->kind == DAE_MODE_ELASTIC && md->freq_hz < drift_hz) return "drift";
    return dae_mode_kind_name(md->kind);
}

int rn_modes_write(const dae_modes *M, rn_part_fn part, FILE *f)
{
    return rn_modes_write_drift(M, part, 0, f);
}

int rn_modes_write_drift(const dae_modes *M, rn_part_fn part, double drift_hz, FILE *f)
{
    if (!part) part = rn_mode_part_top;
    fprintf(f, "index,frequency_hz,damping_ratio,kind,part,dominant\n");
    char pb[64], d[512];
    for (int k = 0; k < dae_modes_count(M); k++) {
        const dae_mode *md = dae_modes_get(M, k);
        dae_modes_describe(M, k, 2, 4, 3, d, sizeof d);
        for (char *q = d; *q; q++)
            if (*q == '"') *q = '\'';
        fprintf(f, "%d,%.10g,%.6g,%s,%s,\"%s\"\n", k + 1, md->freq_hz, md->damping,
                rn_mode_kind(M, k, drift_hz), part(M, k, pb, sizeof pb), d);
    }
    return ferror(f) ? BG_ERR_IO : BG_OK;
}
