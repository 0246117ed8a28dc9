/* The run of a model file (bgsim.h: bs_run_file), as bgsim does it and as the crane program does
 * it for a model file SCENE: the model read with the --set replacements (mdl_load), the solver
 * settings with the command line's overrides, the output folder made ready (status.txt
 * "running" first, the files of an earlier run removed), model.yaml and model_stats.txt, the run
 * (bs_simulate, or bs_analyse for --static and --modes), the program's extras after a run that
 * reached its end (the crane's figures), the summary and status.txt at the end. The contract
 * (files, signals, exit statuses) is bgsim.c's. */
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
#define BS_MAX_RUN_FILES 64

/* The file's solver settings with the command line's overrides into r->solver; the number of
 * rows checked. 0, or RN_EXIT_USAGE (said on stderr). */
static int solver_settings(bs_run *r, const bs_options *o)
{
    const char *prog = r->rn.program;
    r->solver = *mdl_solver(r->mm);
    if (o->has_t_end) r->solver.t_end = o->t_end;
    if (o->has_rtol) r->solver.rtol = o->rtol;
    if (o->has_atol) r->solver.atol = o->atol;
    if (o->has_output_step) r->solver.output_step = o->output_step;
    if (mdl_solver_override(r->mm, &r->solver) != BG_OK) {
        fprintf(stderr,
                "%s: the solver settings are out of range (t_end %g, output_step %g, "
                "rtol %g, atol %g)\n",
                prog, r->solver.t_end, r->solver.output_step, r->solver.rtol, r->solver.atol);
        return RN_EXIT_USAGE;
    }
    /* the modes at T: a time of the run, as the crane program's --modes T */
    if (o->modes && !(o->modes_t <= r->solver.t_end)) {
        fprintf(stderr,
                "%s: --modes %g: the time must lie in the run, 0 .. t_end = %g s (a longer run: "
                "--t-end)\n",
                prog, o->modes_t, r->solver.t_end);
        return RN_EXIT_USAGE;
    }
    /* the number of output rows, in floating point before any conversion to an integer */
    double nout = ceil(r->solver.t_end / r->solver.output_step - 1e-9);
    if (!(nout >= 1)) nout = 1;
    if (!(o->static_only || o->modes) && !(nout + 1 <= (double)o->max_rows)) {
        fprintf(stderr,
                "%s: t_end = %g s at output_step = %g s makes %.4g output rows, more than the "
                "limit of %lld: choose a longer --output-step or a shorter --t-end, or allow more "
                "rows with --max-rows N\n",
                prog, r->solver.t_end, r->solver.output_step, nout + 1, o->max_rows);
        return RN_EXIT_USAGE;
    }
    r->rn.nout = (long)nout;
    r->rn.t_end = r->solver.t_end;
    return 0;
}

/* RUN_FILES and the program's extra files (x->files) into list (NULL-terminated). */
static void run_files(const bs_extras *x, const char **list)
{
    int n = 0;
    for (int i = 0; RUN_FILES[i]; i++)
        list[n++] = RUN_FILES[i];
    for (int i = 0; x && x->files && x->files[i] && n < BS_MAX_RUN_FILES; i++)
        list[n++] = x->files[i];
    list[n] = NULL;
}

/* The run after the folder is ready; the model is freed by the caller. */
static void run_in_folder(bs_run *r, const bs_options *o, const bs_extras *x)
{
    if (!strcmp(r->rn.status, "running") && bs_save_model(r) == 0)
        (o->static_only || o->modes ? bs_analyse : bs_simulate)(r);
    rn_set_phase(&r->rn, RN_PHASE_OTHER, NULL);
    rn_arm_finishing(&r->rn);
    int completed = !strcmp(r->rn.status, "completed");
    if (completed && rn_signal())
        snprintf(r->rn.reason, sizeof r->rn.reason,
                 "the run reached its end; %s received afterwards%s", rn_signal_name(rn_signal()),
                 x && x->not_done ? x->not_done : "");
    else if (completed && x && x->finish)
        x->finish(r, x->ctx);
    if (!o->quiet) bs_summary(r);
    if (fflush(stdout) != 0 || ferror(stdout))
        rn_fail_run(&r->rn, "cannot write the standard output", strerror(errno));
    rn_write_status(&r->rn, 1);
    rn_status_ready(&r->rn, 0);
}

int bs_run_file(const char *program, const bs_options *o, int argc, char **argv, const bs_extras *x)
{
    bs_run r;
    memset(&r, 0, sizeof r);
    rn_init(&r.rn, program, "model");
    r.rn.owner = &r;
    r.rn.est.on = o->errest; /* --error-estimate: the runner's (rn_estimate.c) */
    r.rn.est.factor = o->errest_factor;
    r.o = o;
    r.extras = x;
    if (strlen(o->model) > RN_OUT_MAX) {
        fprintf(stderr, "%s: the model's path is %zu characters long, more than %d\n", program,
                strlen(o->model), RN_OUT_MAX);
        return RN_EXIT_USAGE;
    }
    snprintf(r.model_path, sizeof r.model_path, "%s", o->model);
    bg_error err = {0};
    r.mm = mdl_load(o->model, o->sets, o->nsets, &err);
    if (!r.mm) {
        fprintf(stderr, "%s\n", err.message);
        return RN_EXIT_USAGE;
    }
    int rc;
    if (o->list_unknowns) {
        rc = bs_list_unknowns(r.mm, stdout);
        mdl_free(&r.mm);
        if (fflush(stdout) != 0 || ferror(stdout)) rc = RN_EXIT_RUN;
        return rc;
    }
    if ((rc = solver_settings(&r, o)) != 0) {
        mdl_free(&r.mm);
        return rc;
    }
    snprintf(r.model_name, sizeof r.model_name, "%s", mdl_name(r.mm));
    r.rn.name = r.model_name;
    r.rn.path = r.model_path;
    const char *files[BS_MAX_RUN_FILES + 1];
    run_files(x, files);
    if ((rc = rn_set_outdir(&r.rn, o->out)) != 0) {
        mdl_free(&r.mm);
        return rc;
    }
    /* status.txt "running" first (it replaces an earlier run's), then the earlier results go */
    rn_format_command(&r.rn, argc, argv);
    if ((rc = rn_prepare_folder(&r.rn, files)) != 0) {
        mdl_free(&r.mm);
        return rc;
    }
    run_in_folder(&r, o, x);
    rn_estimate_free(&r.rn); /* before the model its problem calls */
    dae_free(&r.rn.s);
    mdl_free(&r.mm);
    free(r.rn.csv_buf);
    free(r.final_out);
    free(r.names);
    return rn_exit_status(&r.rn, 0);
}
