/* crane: simulates the hydraulically driven rotary crane of the crane paper (docs/crane.md) from a
 * scene file and writes the results.
 *
 *   crane [SCENE] [--out DIR] [--t-end T] [--rtol R] [--atol A] [--elements N]
 *         [--output-step DT] [--max-rows N] [--set SECTION.KEY=VALUE]... [--no-plots]
 *         [--quiet] [--help] [--version] [--vtk] [--vtk-step DT] [--animate]
 *         [--anim-step DT] [--anim-scale K] [--static] [--modes [T]] [--error-estimate [K]]
 *
 * --static and --modes replace the dynamic run by the analyses of crane/crane_static.h: the
 * static equilibrium (equilibrium.csv, static.txt) and the modes at time T, 0 <= T <= t_end
 * (modes.csv, modes.gp, modes.png; the drift modes of a state in motion apart). The options of
 * the dynamic run (--vtk, --animate and their steps, --error-estimate) are refused with them. A static start whose checks fail (scene keys that cannot be met together) ends
 * with exit status 2, status.txt and static.txt naming the keys. --error-estimate adds a second
 * run at rtol / K, atol / K (K = 100 unless given) beside the first, compared at every row:
 * error_estimate.csv (crane/program/cp_errest.c); a second run that fails leaves the first run's
 * results and status as they are, the estimate marked unavailable.
 *
 * A SCENE ending in .yaml is a model file (docs/model-format.md): it is run by bgsim's run of a
 * model file (bgsim.h: bs_run_file, the same code path as bgsim's; its files, statuses and
 * signals) with the crane's own on top, Fig. 5 and the summary's lines from results.csv's
 * columns (crane/program/cp_model.c); the options of INI scenes only are refused (exit 2).
 *
 * Flow: scene file (crane_scene_load) -> command-line overrides -> crane_build -> static
 * equilibrium (crane_static_start, if the scene asks: the static solver, the ties corrected, the
 * start verified, static.txt) -> bgr_dae_problem -> bg_dae (rtol, atol, stop at
 * t_end, the reference's corners as breakpoints, algebraic variables out of the error test) ->
 * consistent initial values -> dae_step up to each output time, one CSV row there
 * (crane_outputs), buffered -> statistics, figures (gnuplot, skipped when it is missing), summary.
 * The parts are in crane/program/ (crane_program.h lists them), on the run machinery shared with
 * bgsim (runner/rn_run.h: signals, status.txt, results.csv, the output folder, the run loop);
 * here: the scene and the output folder made ready, the run started and its status.txt written
 * at the end.
 *
 * Writes into DIR (default results/<scene name>/): status.txt first ("running", with the pid, the
 * scene, the command line and the start time), then scene.ini (the scene as run, overrides
 * included), model_stats.txt, results.csv (one row per output time, buffered, whole rows only),
 * solver_stats.txt, plots.gp and fig5a.png .. fig5f.png, error_estimate.csv (--error-estimate), and
 * status.txt again when the run ends
 * (completed, interrupted or failed, with the reason). The results and figures of an earlier run
 * in DIR are removed first; a DIR whose status.txt names a crane still running is refused. Every
 * write is checked: a failure names the file and the system's error and ends the run (exit 1,
 * status failed); status.txt and the other small files are replaced atomically (a temporary file
 * in DIR, fsync, rename), results.csv is cut back to its last whole row. The number of output rows
 * is limited (--max-rows, default 1000000).
 * Signals: SIGINT, SIGTERM and SIGHUP stop the integration between two solver steps (within a
 * second whatever the output step or the model size): the rows written stay, status.txt says
 * when. During set-up (model, static equilibrium, consistent initial values: long library calls)
 * and on a second signal the program writes status.txt and ends at once. A run that reached t_end
 * is completed, whenever a signal comes (the figures are then not drawn). SIGKILL leaves
 * "running" with a pid that no longer exists.
 * Exit status: 0 completed; 1 the model or the solver failed, or a file could not be written; 2
 * bad command line or scene file (nothing is written then); 128 + signal number when interrupted.
 */
#include <dirent.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "crane_program.h"
#include "crane_scene.h"

static int print_scene_copy(rn_run *rn, FILE *f, const void *ctx)
{
    (void)ctx;
    cp_run *r = CP_RUN(rn);
    fprintf(f, "; the scene as run: %s with the command-line overrides\n", r->scene_path);
    return crane_scene_write(&r->scene, f) == BG_OK ? 0 : -1;
}

/* The files a run writes into its folder (this program's, crane_vtk.h's and crane_anim.h's;
 * bgsim's for a model file: model.yaml, model.pvd), removed at the start (rn_prepare_folder,
 * with their temporary names) so that nothing of an earlier run stays beside the new results;
 * and vtk/frame_*.vtp with the folder vtk/. */
const char *const cp_run_files[] = {"results.csv",     "model_stats.txt",    "solver_stats.txt",
                                    "scene.ini",       "plots.gp",           "gnuplot.log",
                                    "fig5a.png",       "fig5b.png",          "fig5c.png",
                                    "fig5d.png",       "fig5e.png",          "fig5f.png",
                                    "crane.pvd",       "anim.dat",           "anim_track.dat",
                                    "anim.gp",         "anim.log",           "crane.gif",
                                    "crane_frame.png", "status.txt",         "static.txt",
                                    "equilibrium.csv", "modes.csv",          "modes.gp",
                                    "modes.png",       "error_estimate.csv", "model.yaml",
                                    "model.pvd",       NULL};

/* vtk/frame_*.vtp of an earlier run, and vtk/ if it then holds nothing else. 0, or the
 * failure. */
static int remove_old_frames(cp_run *r)
{
    char path[RN_PATH_SIZE + 16], msg[RN_PATH_SIZE + 128];
    rn_path_in(&r->rn, "vtk", path, sizeof path);
    DIR *d = opendir(path);
    if (d) {
        struct dirent *e;
        int bad = 0;
        while (!bad && (e = readdir(d)) != NULL) {
            size_t l = strlen(e->d_name);
            if (strncmp(e->d_name, "frame_", 6) || l < 10 || strcmp(e->d_name + l - 4, ".vtp"))
                continue;
            snprintf(msg, sizeof msg, "%s/%s", path, e->d_name);
            if (unlink(msg) != 0 && errno != ENOENT) bad = errno;
        }
        closedir(d);
        if (bad) {
            snprintf(msg, sizeof msg, "cannot remove the frames in %s, left by an earlier run",
                     path);
            return rn_fail_run(&r->rn, msg, strerror(bad));
        }
        rmdir(path); /* if it holds nothing else */
    }
    return 0;
}

int main(int argc, char **argv)
{
    /* signals first: one during the scene's checks ends the program before it writes anything */
    rn_signals_install("crane");

    cp_options o;
    int rc = cp_parse_args(argc, argv, &o);
    if (rc >= 0) {
        if (fflush(stdout) != 0 || ferror(stdout)) {
            fprintf(stderr, "crane: cannot write the standard output: %s\n", strerror(errno));
            return RN_EXIT_RUN;
        }
        return rc;
    }

    /* a model file: bgsim's run of it with the crane's own on top (cp_model.c) */
    if (o.scene && cp_is_model_file(o.scene)) return cp_run_model(&o, argc, argv);

    cp_run r;
    memset(&r, 0, sizeof r);
    rn_init(&r.rn, "crane", "scene");
    r.rn.owner = &r;
    r.rn.est.on = o.errest; /* --error-estimate: the runner's (rn_estimate.c, cp_errest.c) */
    r.rn.est.factor = o.errest_factor;
    r.o = &o;
    o.viz.stop = rn_signal_flag(); /* a signal stops gnuplot on the animation */

    char tried[2048], odd[RN_PATH_SIZE + 128];
    const char *arg = o.scene ? o.scene : CP_DEFAULT_SCENE;
    if (strlen(arg) > RN_OUT_MAX) {
        fprintf(stderr, "crane: the scene's path is %zu characters long, more than %d\n",
                strlen(arg), RN_OUT_MAX);
        return RN_EXIT_USAGE;
    }
    if (!cp_find_scene(arg, r.scene_path, sizeof r.scene_path, tried, sizeof tried, odd,
                       sizeof odd)) {
        if (odd[0])
            fprintf(stderr, "crane: scene '%s': %s\n", arg, odd);
        else
            fprintf(stderr, "crane: scene file '%s' not found (tried %s)\n", arg, tried);
        return RN_EXIT_USAGE;
    }
    bg_error err = {0};
    int nkeys = 0;
    if (crane_scene_load_counted(&r.scene, r.scene_path, &nkeys, &err) != BG_OK) {
        fprintf(stderr, "%s\n", err.message);
        return RN_EXIT_USAGE;
    }
    if (o.scene && nkeys == 0) {
        fprintf(stderr,
                "crane: the scene file %s sets no keys (it is empty or holds only comments and "
                "section headers): refused, as it is likely not the file meant. To run the default "
                "scene, run crane without a scene file (or with 'paper'); --set and the other "
                "options change it\n",
                r.scene_path);
        return RN_EXIT_USAGE;
    }
    for (int i = 0; i < o.nsets; i++) {
        cp_set_item *it = &o.sets[i];
        if (crane_scene_set(&r.scene, it->section, it->key, it->value, it->origin, &err) != BG_OK) {
            fprintf(stderr, "crane: %s\n", err.message);
            return RN_EXIT_USAGE;
        }
    }
    if (o.nsets && crane_scene_check(&r.scene, "command line", &err) != BG_OK) {
        fprintf(stderr, "crane: %s\n", err.message);
        return RN_EXIT_USAGE;
    }
    /* --modes T: the modes at a time of the run, T within [0, t_end] (a T beyond it would
     * integrate past the scene's end, without end for a huge T) */
    if (o.modes && !(o.modes_t <= r.scene.t_end)) {
        fprintf(stderr,
                "crane: option --modes %g: T must be within [0, t_end] = [0, %g] s (the scene's "
                "[solver] t_end; --t-end sets it)\n",
                o.modes_t, r.scene.t_end);
        return RN_EXIT_USAGE;
    }
    /* the number of output rows, in floating point before any conversion to an integer */
    double nout = ceil(r.scene.t_end / r.scene.output_step - 1e-9);
    if (!(nout >= 1)) nout = 1;
    if (!(nout + 1 <= (double)o.max_rows)) {
        fprintf(stderr,
                "crane: t_end = %g s at output_step = %g s makes %.4g output rows, more than the "
                "limit of %lld: choose a longer --output-step or a shorter --t-end, or allow more "
                "rows with --max-rows N\n",
                r.scene.t_end, r.scene.output_step, nout + 1, o.max_rows);
        return RN_EXIT_USAGE;
    }
    r.rn.nout = (long)nout;
    r.rn.name = r.scene.name;
    r.rn.path = r.scene_path;
    r.rn.t_end = r.scene.t_end;
    if ((rc = rn_set_outdir(&r.rn, o.out)) != 0) return rc;

    /* status.txt "running" first (it replaces an earlier run's), then the earlier results go */
    rn_format_command(&r.rn, argc, argv);
    if ((rc = rn_prepare_folder(&r.rn, cp_run_files)) != 0) return rc;
    if (!strcmp(r.rn.status, "running") && remove_old_frames(&r) == 0 &&
        rn_save_file(&r.rn, "scene.ini", print_scene_copy, NULL) == 0)
        (o.static_only || o.modes ? cp_analyse : cp_simulate)(&r);
    rn_set_phase(&r.rn, RN_PHASE_OTHER, NULL);
    rn_arm_finishing(&r.rn);

    int completed = !strcmp(r.rn.status, "completed");
    if (completed && rn_signal()) {
        int figs = r.rn.rows > 1 && !o.no_plots;
        snprintf(r.rn.reason, sizeof r.rn.reason,
                 "the integration reached t_end; %s received afterwards%s%s%s",
                 rn_signal_name(rn_signal()), figs || o.viz.animate ? ": " : "",
                 figs ? "the figures were not drawn" : "",
                 o.viz.animate ? (figs ? ", nor the animation" : "the animation was not drawn")
                               : "");
    } else if (completed && r.rn.rows > 1 && !o.no_plots) {
        cp_draw_figures(&r);
        if (rn_signal() && !strcmp(r.rn.status, "completed"))
            snprintf(r.rn.reason, sizeof r.rn.reason,
                     "the integration reached t_end; %s received while drawing the figures: "
                     "they were not drawn",
                     rn_signal_name(rn_signal()));
    }
    if (!o.quiet) cp_summary(&r);
    if (fflush(stdout) != 0 || ferror(stdout))
        rn_fail_run(&r.rn, "cannot write the standard output", strerror(errno));
    rn_write_status(&r.rn, 1);
    rn_status_ready(&r.rn, 0);
    rn_estimate_free(&r.rn); /* before the model its problem calls */
    dae_free(&r.rn.s);
    crane_free(&r.c);
    free(r.rn.csv_buf);
    return rn_exit_status(&r.rn, r.bad_scene);
}
