/* bgsim: runs a bond-graph model described by a model file (docs/model-format.md) and writes the
 * results; the crane program's machinery (runner/rn_run.h) for any model (docs/bgsim.md).
 *
 *   bgsim MODEL [--out DIR] [--set PATH=VALUE]... [--t-end T] [--rtol R] [--atol A]
 *         [--output-step DT] [--max-rows N] [--static] [--modes [T]] [--error-estimate [K]]
 *         [--vtk] [--vtk-step DT] [--quiet]
 *         [--list-types [--markdown]] [--describe TYPE] [--list-unknowns] [--help] [--version]
 *
 * Flow: the model file (mdl_load with the --set replacements: read, checked, built, compiled,
 * its start placed) -> the command line's solver settings -> the output folder made ready
 * (status.txt "running" first) -> model.yaml, model_stats.txt -> the static start with the
 * file's trim (start: static, or --static: static.txt, equilibrium.csv) -> mdl_dae_problem,
 * mdl_dae_options -> consistent initial values -> the runner's loop (rn_loop: dae_step up to
 * each output time, a row of t and the declared outputs there, buffered, whole rows only) ->
 * solver_stats.txt, summary, status.txt at the end. --error-estimate [K]: a companion run at
 * rtol / K, atol / K in lockstep over the rows (the runner's, rn_estimate.c): error_estimate.csv
 * and its lines in status.txt, solver_stats.txt and the summary; a companion that fails makes
 * the estimate "unavailable", never the run fail. --modes [T]: bgr_modes at the start (after
 * the static start when the file asks for it) or at time T of a run: modes.csv. Per step the
 * solver runs the compiled bgr_model's residual and Jacobian only.
 *
 * Writes into DIR (default results/<model name>/): status.txt ("running" with the pid, the
 * model, the command line and the start time; at the end completed, interrupted or failed with
 * the reason), model.yaml (the model as run), model_stats.txt, results.csv, solver_stats.txt;
 * static.txt, equilibrium.csv, modes.csv, error_estimate.csv as asked. The files of an earlier
 * run in DIR are removed first; a DIR whose status.txt names a bgsim still running is refused.
 * Every write is checked; status.txt and the small files are replaced atomically.
 * Signals: SIGINT, SIGTERM and SIGHUP stop the integration between two solver steps (the rows
 * written stay, status.txt says when); during set-up and on a second signal the program writes
 * status.txt and ends at once.
 * Exit status: 0 completed; 1 the model's run or the solver failed, or a file could not be
 * written; 2 bad command line or model file (nothing written: the reader's FILE:LINE:COL
 * message on stderr); 128 + signal number when interrupted. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bgsim.h"

/* The files a run writes into its folder, removed at the start (with their temporary names). */
static const char *const RUN_FILES[] = {
    "status.txt", "model.yaml",      "model_stats.txt", "results.csv", "solver_stats.txt",
    "static.txt", "equilibrium.csv", "modes.csv",       "model.pvd",   "error_estimate.csv",
    NULL};

/* The file's solver settings with the command line's overrides into r->solver; the number of
 * rows checked. 0, or RN_EXIT_USAGE (said on stderr). */
static int solver_settings(bs_run *r, const bs_options *o)
{
    r->solver = *mdl_solver(r->mm);
    if (o->has_t_end) r->solver.t_end = o->t_end;
    if (o->has_rtol) r->solver.rtol = o->rtol;
    if (o->has_atol) r->solver.atol = o->atol;
    if (o->has_output_step) r->solver.output_step = o->output_step;
    if (mdl_solver_override(r->mm, &r->solver) != BG_OK) {
        fprintf(stderr, "bgsim: the solver settings are out of range (t_end %g, output_step %g, "
                        "rtol %g, atol %g)\n", r->solver.t_end, r->solver.output_step,
                r->solver.rtol, r->solver.atol);
        return RN_EXIT_USAGE;
    }
    /* the number of output rows, in floating point before any conversion to an integer */
    double nout = ceil(r->solver.t_end / r->solver.output_step - 1e-9);
    if (!(nout >= 1)) nout = 1;
    if (!(o->static_only || o->modes) && !(nout + 1 <= (double)o->max_rows)) {
        fprintf(stderr,
                "bgsim: t_end = %g s at output_step = %g s makes %.4g output rows, more than the "
                "limit of %lld: choose a longer --output-step or a shorter --t-end, or allow more "
                "rows with --max-rows N\n",
                r->solver.t_end, r->solver.output_step, nout + 1, o->max_rows);
        return RN_EXIT_USAGE;
    }
    r->rn.nout = (long)nout;
    r->rn.t_end = r->solver.t_end;
    return 0;
}

int main(int argc, char **argv)
{
    /* signals first: one while the model is read ends the program before it writes anything */
    rn_signals_install("bgsim");

    bs_options o;
    int rc = bs_parse_args(argc, argv, &o);
    if (rc >= 0) {
        if (fflush(stdout) != 0 || ferror(stdout)) {
            fprintf(stderr, "bgsim: cannot write the standard output: %s\n", strerror(errno));
            return RN_EXIT_RUN;
        }
        return rc;
    }

    bs_run r;
    memset(&r, 0, sizeof r);
    rn_init(&r.rn, "bgsim", "model");
    r.rn.owner = &r;
    r.rn.est.on = o.errest; /* --error-estimate: the runner's (rn_estimate.c) */
    r.rn.est.factor = o.errest_factor;
    r.o = &o;
    if (strlen(o.model) > RN_OUT_MAX) {
        fprintf(stderr, "bgsim: the model's path is %zu characters long, more than %d\n",
                strlen(o.model), RN_OUT_MAX);
        return RN_EXIT_USAGE;
    }
    snprintf(r.model_path, sizeof r.model_path, "%s", o.model);
    bg_error err = {0};
    r.mm = mdl_load(o.model, o.sets, o.nsets, &err);
    if (!r.mm) {
        fprintf(stderr, "%s\n", err.message);
        return RN_EXIT_USAGE;
    }
    if (o.list_unknowns) {
        rc = bs_list_unknowns(r.mm, stdout);
        mdl_free(&r.mm);
        if (fflush(stdout) != 0 || ferror(stdout)) rc = RN_EXIT_RUN;
        return rc;
    }
    if ((rc = solver_settings(&r, &o)) != 0) {
        mdl_free(&r.mm);
        return rc;
    }
    snprintf(r.model_name, sizeof r.model_name, "%s", mdl_name(r.mm));
    r.rn.name = r.model_name;
    r.rn.path = r.model_path;
    if ((rc = rn_set_outdir(&r.rn, o.out)) != 0) {
        mdl_free(&r.mm);
        return rc;
    }

    /* status.txt "running" first (it replaces an earlier run's), then the earlier results go */
    rn_format_command(&r.rn, argc, argv);
    if ((rc = rn_prepare_folder(&r.rn, RUN_FILES)) != 0) {
        mdl_free(&r.mm);
        return rc;
    }
    if (!strcmp(r.rn.status, "running") && bs_save_model(&r) == 0)
        (o.static_only || o.modes ? bs_analyse : bs_simulate)(&r);
    rn_set_phase(&r.rn, RN_PHASE_OTHER, NULL);
    rn_arm_finishing(&r.rn);
    if (!strcmp(r.rn.status, "completed") && rn_signal())
        snprintf(r.rn.reason, sizeof r.rn.reason, "the run reached its end; %s received afterwards",
                 rn_signal_name(rn_signal()));
    if (!o.quiet) bs_summary(&r);
    if (fflush(stdout) != 0 || ferror(stdout))
        rn_fail_run(&r.rn, "cannot write the standard output", strerror(errno));
    rn_write_status(&r.rn, 1);
    rn_status_ready(&r.rn, 0);
    rn_estimate_free(&r.rn); /* before the model its problem calls */
    dae_free(&r.rn.s);
    mdl_free(&r.mm);
    free(r.rn.csv_buf);
    free(r.final_out);
    free(r.names);
    return rn_exit_status(&r.rn, 0);
}
