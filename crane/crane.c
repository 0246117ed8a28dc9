/* crane: simulates the hydraulically driven rotary crane of the crane paper (docs/crane.md) from a
 * scene file and writes the results.
 *
 *   crane [SCENE] [--out DIR] [--t-end T] [--rtol R] [--atol A] [--elements N]
 *         [--output-step DT] [--max-rows N] [--set SECTION.KEY=VALUE]... [--no-plots]
 *         [--quiet] [--help] [--version] [--vtk] [--vtk-step DT] [--animate]
 *         [--anim-step DT] [--anim-scale K] [--static] [--modes [T]] [--error-estimate [K]]
 *
 * --static and --modes replace the dynamic run by the analyses of crane/crane_static.h: the
 * static equilibrium (equilibrium.csv, static.txt) and the modes at time T (modes.csv, modes.gp,
 * modes.png). A static start whose checks fail (scene keys that cannot be met together) ends
 * with exit status 2, status.txt and static.txt naming the keys. --error-estimate adds a second
 * run at rtol / K, atol / K (K = 100 unless given) beside the first, compared at every row:
 * error_estimate.csv (crane/program/cp_errest.c); a second run that fails leaves the first run's
 * results and status as they are, the estimate marked unavailable.
 *
 * Flow: scene file (crane_scene_load) -> command-line overrides -> crane_build -> static
 * equilibrium (crane_static_start, if the scene asks: the static solver, the ties corrected, the
 * start verified, static.txt) -> bgr_dae_problem -> bg_dae (rtol, atol, stop at
 * t_end, the reference's corners as breakpoints, algebraic variables out of the error test) ->
 * consistent initial values -> dae_step up to each output time, one CSV row there
 * (crane_outputs), buffered -> statistics, figures (gnuplot, skipped when it is missing), summary.
 * The parts are in crane/program/ (crane_program.h lists them); here: the scene and the output
 * folder made ready, the run started and its status.txt written at the end.
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
#include "pu_fs.h"

static int print_scene_copy(cp_run *r, FILE *f, const void *ctx)
{
    (void)ctx;
    fprintf(f, "; the scene as run: %s with the command-line overrides\n", r->scene_path);
    return crane_scene_write(&r->scene, f) == BG_OK ? 0 : -1;
}

/* The command line, quoted for the shell where needed, control characters as '?', cut at the
 * buffer's end with "...". */
static void format_command(cp_run *r, int argc, char **argv)
{
    char *b = r->command;
    size_t n = 0, size = sizeof r->command - 8;
    for (int i = 0; i < argc && n < size; i++) {
        const char *a = argv[i];
        int plain = a[0] && strspn(a, "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz"
                                      "0123456789-_./=:,+@%") == strlen(a);
        if (i) b[n++] = ' ';
        if (!plain) b[n++] = '\'';
        for (; *a && n < size; a++) {
            if (*a == '\'' && n + 4 < size) {
                memcpy(b + n, "'\\''", 4);
                n += 4;
            } else {
                b[n++] = (unsigned char)*a < 32 || *a == 127 ? '?' : *a;
            }
        }
        if (!plain && n < size) b[n++] = '\'';
    }
    if (n >= size) memcpy(b + n, " ...", 4), n += 4;
    b[n] = '\0';
}

/* The status.txt in dir names a crane that is still running (its pid is alive and, where /proc
 * tells, called crane): 1, with its pid and start in msg. */
static int folder_in_use(const cp_run *r, char *msg, size_t size)
{
    char path[CP_PATH_SIZE], text[8192];
    cp_path_in(r, "status.txt", path, sizeof path);
    FILE *f = fopen(path, "r");
    if (!f) return 0;
    size_t len = fread(text, 1, sizeof text - 1, f);
    fclose(f);
    text[len] = '\0';
    const char *p = strstr(text, "\npid: "), *st = strstr(text, "\nstarted: ");
    if (strncmp(text, "status: running\n", 16) || !p) return 0;
    long pid = strtol(p + 6, NULL, 10);
    if (pid <= 0 || pid == (long)getpid() || (kill((pid_t)pid, 0) != 0 && errno != EPERM)) return 0;
    char comm[CP_PATH_SIZE], name[64] = "";
    snprintf(comm, sizeof comm, "/proc/%ld/comm", pid);
    if ((f = fopen(comm, "r")) != NULL) {
        if (!fgets(name, sizeof name, f)) name[0] = '\0';
        fclose(f);
        if (strncmp(name, "crane", 5)) return 0; /* the pid is another program's now */
    }
    char started[64] = "?";
    if (st) snprintf(started, sizeof started, "%.*s", (int)strcspn(st + 10, "\n"), st + 10);
    snprintf(msg, size, "pid %ld, started %s", pid, started);
    return 1;
}

/* The files a run writes into its folder (this program's, crane_vtk.h's and crane_anim.h's,
 * with their temporary names), removed at the start so that nothing of an earlier run stays
 * beside the new results; and vtk/frame_*.vtp with the folder vtk/. 0, or the failure. */
static const char *const RUN_FILES[] = {"results.csv",     "model_stats.txt",    "solver_stats.txt",
                                        "scene.ini",       "plots.gp",           "gnuplot.log",
                                        "fig5a.png",       "fig5b.png",          "fig5c.png",
                                        "fig5d.png",       "fig5e.png",          "fig5f.png",
                                        "crane.pvd",       "anim.dat",           "anim_track.dat",
                                        "anim.gp",         "anim.log",           "crane.gif",
                                        "crane_frame.png", "status.txt",         "static.txt",
                                        "equilibrium.csv", "modes.csv",          "modes.gp",
                                        "modes.png",       "error_estimate.csv", NULL};

static int remove_old_outputs(cp_run *r)
{
    char path[CP_PATH_SIZE + 16], msg[CP_PATH_SIZE + 128];
    for (int i = 0; RUN_FILES[i]; i++)
        for (int tmp = 0; tmp < 3; tmp++) {
            if (!strcmp(RUN_FILES[i], "status.txt") && tmp == 0) continue; /* ours, new */
            cp_path_in(r, RUN_FILES[i], path, sizeof path);
            if (tmp) strcat(path, tmp == 1 ? ".tmp" : ".signal.tmp");
            if (unlink(path) != 0 && errno != ENOENT) {
                snprintf(msg, sizeof msg, "cannot remove %s, left by an earlier run", path);
                return cp_fail_run(r, msg, strerror(errno));
            }
        }
    cp_path_in(r, "vtk", path, sizeof path);
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
            return cp_fail_run(r, msg, strerror(bad));
        }
        rmdir(path); /* if it holds nothing else */
    }
    return 0;
}

int main(int argc, char **argv)
{
    /* signals first: one during the scene's checks ends the program before it writes anything */
    cp_signals_install();

    cp_options o;
    int rc = cp_parse_args(argc, argv, &o);
    if (rc >= 0) {
        if (fflush(stdout) != 0 || ferror(stdout)) {
            fprintf(stderr, "crane: cannot write the standard output: %s\n", strerror(errno));
            return CP_EXIT_RUN;
        }
        return rc;
    }

    cp_run r;
    memset(&r, 0, sizeof r);
    r.o = &o;
    r.wall0 = cp_wall_now();
    r.status = "running";
    r.csv_fd = -1;

    char tried[2048], odd[CP_PATH_SIZE + 128];
    const char *arg = o.scene ? o.scene : CP_DEFAULT_SCENE;
    if (strlen(arg) > CP_OUT_MAX) {
        fprintf(stderr, "crane: the scene's path is %zu characters long, more than %d\n",
                strlen(arg), CP_OUT_MAX);
        return CP_EXIT_USAGE;
    }
    if (!cp_find_scene(arg, r.scene_path, sizeof r.scene_path, tried, sizeof tried, odd,
                       sizeof odd)) {
        if (odd[0])
            fprintf(stderr, "crane: scene '%s': %s\n", arg, odd);
        else
            fprintf(stderr, "crane: scene file '%s' not found (tried %s)\n", arg, tried);
        return CP_EXIT_USAGE;
    }
    bg_error err = {0};
    int nkeys = 0;
    if (crane_scene_load_counted(&r.scene, r.scene_path, &nkeys, &err) != BG_OK) {
        fprintf(stderr, "%s\n", err.message);
        return CP_EXIT_USAGE;
    }
    if (o.scene && nkeys == 0) {
        fprintf(stderr,
                "crane: the scene file %s sets no keys (it is empty or holds only comments and "
                "section headers): refused, as it is likely not the file meant. To run the default "
                "scene, run crane without a scene file (or with 'paper'); --set and the other "
                "options change it\n",
                r.scene_path);
        return CP_EXIT_USAGE;
    }
    for (int i = 0; i < o.nsets; i++) {
        cp_set_item *it = &o.sets[i];
        if (crane_scene_set(&r.scene, it->section, it->key, it->value, it->origin, &err) != BG_OK) {
            fprintf(stderr, "crane: %s\n", err.message);
            return CP_EXIT_USAGE;
        }
    }
    if (o.nsets && crane_scene_check(&r.scene, "command line", &err) != BG_OK) {
        fprintf(stderr, "crane: %s\n", err.message);
        return CP_EXIT_USAGE;
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
        return CP_EXIT_USAGE;
    }
    r.nout = (long)nout;

    if (o.out && strlen(o.out) > CP_OUT_MAX) {
        fprintf(stderr, "crane: --out: the folder's name is %zu characters long, more than %d\n",
                strlen(o.out), CP_OUT_MAX);
        return CP_EXIT_USAGE;
    }
    if (o.out)
        snprintf(r.outdir, sizeof r.outdir, "%s", o.out);
    else
        snprintf(r.outdir, sizeof r.outdir, "results/%s", r.scene.name);
    size_t ol = strlen(r.outdir);
    while (ol > 1 && r.outdir[ol - 1] == '/')
        r.outdir[--ol] = '\0';
    if (cp_signal()) {
        fprintf(stderr, "crane: %s received before the run started: nothing written\n",
                cp_signal_name(cp_signal()));
        return 128 + cp_signal();
    }
    char msg[CP_PATH_SIZE + 256];
    if (pu_mkdir_p(r.outdir, 0777, msg, sizeof msg) != 0) {
        fprintf(stderr, "crane: cannot use the output folder %s: %s\n", r.outdir, msg);
        return CP_EXIT_RUN;
    }
    if (folder_in_use(&r, msg, sizeof msg)) {
        fprintf(stderr,
                "crane: the output folder %s is in use: its status.txt names a crane still "
                "running there (%s). Choose another --out, or stop that run (if it is gone, "
                "remove %s/status.txt)\n",
                r.outdir, msg, r.outdir);
        return CP_EXIT_RUN;
    }

    /* status.txt "running" first (it replaces an earlier run's), then the earlier results go */
    format_command(&r, argc, argv);
    cp_local_time(r.started, sizeof r.started);
    if (cp_write_status(&r, 0) != 0) return CP_EXIT_RUN;
    cp_status_ready(&r, 1);
    cp_set_phase(&r, CP_PHASE_SETUP, "preparing the output folder");
    if (remove_old_outputs(&r) == 0 && cp_save_file(&r, "scene.ini", print_scene_copy, NULL) == 0)
        (o.static_only || o.modes ? cp_analyse : cp_simulate)(&r);
    cp_set_phase(&r, CP_PHASE_OTHER, NULL);
    cp_arm_finishing(&r);

    int completed = !strcmp(r.status, "completed");
    if (completed && cp_signal()) {
        snprintf(r.reason, sizeof r.reason,
                 "the integration reached t_end; %s received afterwards%s",
                 cp_signal_name(cp_signal()),
                 r.rows > 1 && !o.no_plots ? ": the figures were not drawn" : "");
    } else if (completed && r.rows > 1 && !o.no_plots) {
        cp_draw_figures(&r);
        if (cp_signal() && !strcmp(r.status, "completed"))
            snprintf(r.reason, sizeof r.reason,
                     "the integration reached t_end; %s received while drawing the figures: "
                     "they were not drawn",
                     cp_signal_name(cp_signal()));
    }
    if (!o.quiet) cp_summary(&r);
    if (fflush(stdout) != 0 || ferror(stdout))
        cp_fail_run(&r, "cannot write the standard output", strerror(errno));
    cp_write_status(&r, 1);
    cp_status_ready(&r, 0);
    crane_errest_free(&r.errest); /* before the model its problem calls */
    dae_free(&r.s);
    crane_free(&r.c);
    free(r.csv_buf);
    return !strcmp(r.status, "completed")     ? CP_EXIT_OK
           : !strcmp(r.status, "interrupted") ? 128 + r.sig
           : r.bad_scene                      ? CP_EXIT_USAGE
                                              : CP_EXIT_RUN;
}
