/* The crane program never reports a success it did not have (issue 21): each class of fault
 * provoked, with the exit status, the message and the files asserted.
 *   - bad numbers and paths: output rows beyond --max-rows (--output-step 1e-300, --t-end 1e9),
 *     hexadecimal numbers, an overlong --out or scene path, a scene file that sets no keys, a
 *     scene that is a directory, a FIFO or a device, an --out that is a file or a device, a
 *     vertical flexible boom; CR-only line ends and --max-rows accepted (exit 2, nothing
 *     written; an unusable folder exit 1);
 *   - write failures: RLIMIT_FSIZE (SIGXFSZ ignored, so that writes fail with EFBIG; it stops
 *     root too, unlike a read-only folder) on status.txt at the start, on scene.ini and on
 *     results.csv mid-run, and a standard output on /dev/full: exit 1, the file and the system's
 *     error named, status.txt whole and saying why, results.csv in whole rows;
 *   - figures: a stand-in gnuplot (first in PATH) that fails or leaves a cut PNG: exit 1 naming
 *     the figure;
 *   - old folders: an earlier run's status, results and figures removed at the start (other files
 *     kept), status.txt "running" with the pid, scene, command line and start time from the start,
 *     a folder in use by a running crane refused, a stale "running" of a dead process taken over,
 *     an old file that cannot be removed refused;
 *   - signals: SIGHUP during set-up (512 elements), SIGTERM in the middle of a 1000 s output step,
 *     two SIGINTs in a row while integrating, SIGTERM after t_end while the figures are drawn:
 *     the program ends within the bound (1 s, 5 s under sanitizers), with 128 + N (0 after t_end:
 *     completed) and a status.txt that says what happened.
 *
 *   test_crane_robust CRANE_EXECUTABLE SCENES_DIR */
#include "crane_spawn.h"
#include "tap.h"

#include <sys/types.h>

static double g_bound = 1.0; /* seconds from a signal to the end of the program */

static void write_text(const char *path, const char *text)
{
    FILE *f = fopen(path, "w");
    if (f) {
        fputs(text, f);
        fclose(f);
    }
}

/* Waits until DIR/name exists with more than min bytes, or the child ends: 1 if it does. */
static int wait_file(pid_t pid, const char *dir, const char *name, long min, double timeout)
{
    char p[8192];
    path2(p, sizeof p, dir, name);
    double t0 = now_s();
    while (now_s() - t0 < timeout) {
        struct stat st;
        if (stat(p, &st) == 0 && st.st_size > min) return 1;
        if (waitpid(pid, NULL, WNOHANG) == pid) return 0;
        sleep_ms(5);
    }
    return 0;
}

/* Waits until DIR/status.txt starts with want. */
static int wait_status(pid_t pid, const char *dir, const char *want, double timeout)
{
    double t0 = now_s();
    while (now_s() - t0 < timeout) {
        if (first_line_is(dir, "status.txt", want)) return 1;
        if (waitpid(pid, NULL, WNOHANG) == pid) return 0;
        sleep_ms(5);
    }
    return 0;
}

static int contains(const char *s, const char *a)
{
    return a == NULL || strstr(s, a) != NULL;
}

/* ------------------------------------------------------------ numbers, paths ---- */

static void test_bad_numbers_and_paths(void)
{
    char never[4200], empty[4200], comments[4200], fifo[4200], afile[4200], afile_sub[4300];
    static char long_out[6000], long_scene[6000];
    path2(never, sizeof never, tmp, "never");
    path2(empty, sizeof empty, tmp, "empty.ini");
    path2(comments, sizeof comments, tmp, "comments.ini");
    path2(fifo, sizeof fifo, tmp, "fifo.ini");
    path2(afile, sizeof afile, tmp, "afile");
    snprintf(afile_sub, sizeof afile_sub, "%s/sub", afile);
    write_text(empty, "");
    write_text(comments, "; a scene that says nothing\n[boom]\n# nor here\n\n");
    write_text(afile, "not a folder\n");
    if (mkfifo(fifo, 0644) != 0) tap_diag("mkfifo failed: %s", strerror(errno));
    size_t n = (size_t)snprintf(long_out, sizeof long_out, "%s/", tmp);
    memset(long_out + n, 'x', 5000);
    long_out[n + 5000] = '\0';
    n = (size_t)snprintf(long_scene, sizeof long_scene, "%s/", tmp);
    memset(long_scene + n, 's', 5000);
    long_scene[n + 5000] = '\0';

    static const char *rows_msg = "output rows";
    struct {
        const char *args[8];
        int code;
        const char *want, *also;
    } bad[] = {
        {{"--output-step", "1e-300", NULL}, 2, rows_msg, "--max-rows"},
        {{"--t-end", "1e9", NULL}, 2, "1e+12 output rows", "limit of 1000000"},
        {{"--t-end", "0x10", NULL}, 2, "key 't_end' in [solver]", "numbers are decimal"},
        {{"--elements", "0x10", NULL}, 2, "key 'elements' in [boom]", "numbers are decimal"},
        {{"--set", "boom.length=0x4c", NULL}, 2, "key 'length' in [boom]", "numbers are decimal"},
        {{"--max-rows", "0x10", NULL}, 2, "--max-rows", "decimal integer"},
        {{"--max-rows", "0", NULL}, 2, "--max-rows", "decimal integer"},
        {{"--vtk-step", "0x1", NULL}, 2, "--vtk-step", "decimal"},
        {{"--t-end", "0.05", "--max-rows", "50", NULL}, 2, "51 output rows", "--max-rows"},
        {{"--set", "boom.tip_radius=1.5", NULL}, 2, "key 'tip_radius' in [boom]", "vertical"},
        {{empty, NULL}, 2, "sets no keys", "without a scene file"},
        {{comments, NULL}, 2, "sets no keys", "without a scene file"},
        {{tmp, NULL}, 2, "is a directory, not a scene file", NULL},
        {{fifo, NULL}, 2, "is a FIFO (named pipe), not a scene file", NULL},
        {{"/dev/zero", NULL}, 2, "is a character device, not a scene file", NULL},
        {{long_scene, NULL}, 2, "5", "characters long"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
        char tag[32];
        snprintf(tag, sizeof tag, "num%zu", i);
        const char *args[16];
        int k = 0;
        for (int j = 0; bad[i].args[j]; j++)
            args[k++] = bad[i].args[j];
        args[k++] = "--out";
        args[k++] = never;
        args[k++] = "--quiet";
        args[k] = NULL;
        result r;
        run(NULL, args, tag, 30, &r);
        struct stat st;
        int ok = r.exited && r.code == bad[i].code && contains(r.err, bad[i].want) &&
                 contains(r.err, bad[i].also) && stat(never, &st) != 0;
        const char *a0 = bad[i].args[0];
        tap_ok(ok, "%.40s%s %s: exit %d, the message names '%s' (nothing written)", a0,
               strlen(a0) > 40 ? "..." : "", bad[i].args[1] ? bad[i].args[1] : "", bad[i].code,
               bad[i].want);
        if (!ok) tap_diag("exit %d (%.1f s), stderr: %.600s", r.code, r.seconds, r.err);
    }

    /* an overlong --out is an error, never cut */
    result r;
    run(NULL, (const char *[]){"--out", long_out, "--quiet", NULL}, "longout", 30, &r);
    tap_ok(r.exited && r.code == 2 && strstr(r.err, "--out") && strstr(r.err, "5") &&
               strstr(r.err, "characters long"),
           "an --out of %zu characters: exit 2 naming its length (%.200s)", strlen(long_out),
           r.err);

    /* an output folder that is a file or a device says so */
    struct {
        const char *out, *want;
    } notdir[] = {{afile, "afile is a regular file, not a folder"},
                  {afile_sub, "afile is a regular file, not a folder"},
                  {"/dev/null", "/dev/null is a character device, not a folder"}};
    for (int i = 0; i < 3; i++) {
        char tag[32];
        snprintf(tag, sizeof tag, "notdir%d", i);
        run(NULL, (const char *[]){"--out", notdir[i].out, "--quiet", "--no-plots", NULL}, tag, 30,
            &r);
        tap_ok(r.exited && r.code == 1 && strstr(r.err, notdir[i].want),
               "--out %s: exit 1, '%s' (%.200s)", notdir[i].out, notdir[i].want, r.err);
    }

    /* accepted: CR-only line ends; as many rows as --max-rows allows */
    char cr[4200], out[4200], why[256];
    double tl;
    path2(cr, sizeof cr, tmp, "cr-only.ini");
    path2(out, sizeof out, tmp, "cr-only");
    write_text(cr, "; old Mac line ends\r[solver]\rt_end = 0.02\r[boom]\rlength = 75\r");
    run(NULL, (const char *[]){cr, "--out", out, "--quiet", "--no-plots", NULL}, "cr", 100, &r);
    tap_ok(r.exited && r.code == 0 && check_csv(out, 0, &tl, why, sizeof why) == 21 &&
               file_contains(out, "scene.ini", "length = 75 "),
           "a scene file with CR-only line ends runs as written (exit %d, %s, %.200s)", r.code, why,
           r.err);
    path2(out, sizeof out, tmp, "max-rows");
    run(NULL,
        (const char *[]){"rigid-boom", "--t-end", "0.05", "--max-rows", "51", "--out", out,
                         "--quiet", "--no-plots", NULL},
        "maxrows", 100, &r);
    tap_ok(r.exited && r.code == 0 && check_csv(out, 0, &tl, why, sizeof why) == 51,
           "--max-rows 51 allows the 51 rows of t_end 0.05 s (exit %d, %s)", r.code, why);
}

/* ---------------------------------------------------------- write failures ---- */

static void test_write_failures(void)
{
    char out[4200], why[256], text[8192];
    double tl;
    result r;
    spawn_opts so = {NULL, NULL, NULL, 0};

    /* status.txt at the start (200 bytes allowed: the stderr file still takes the message) */
    path2(out, sizeof out, tmp, "wf-status");
    so.fsize_limit = 200;
    run_with(&so, (const char *[]){"rigid-boom", "--out", out, "--quiet", "--no-plots", NULL},
             "wfstatus", 60, &r);
    tap_ok(r.exited && r.code == 1 && strstr(r.err, "status.txt: File too large") &&
               !file_exists(out, "status.txt") && !file_exists(out, "status.txt.tmp") &&
               !file_exists(out, "results.csv"),
           "status.txt cannot be written at the start: exit 1 naming it and EFBIG, nothing "
           "else written (%.200s)",
           r.err);

    /* ... in a folder of an earlier run: its status.txt stays whole (atomic replacement) */
    path2(out, sizeof out, tmp, "wf-old");
    mkdir(out, 0777);
    char old[8192];
    path2(old, sizeof old, out, "status.txt");
    const char *old_text = "status: completed\nreason: -\npid: 1\n";
    write_text(old, old_text);
    run_with(&so, (const char *[]){"rigid-boom", "--out", out, "--quiet", "--no-plots", NULL},
             "wfold", 60, &r);
    slurp(old, text, sizeof text);
    tap_ok(r.exited && r.code == 1 && !strcmp(text, old_text),
           "... and an earlier status.txt stays as it was, whole (exit %d)", r.code);

    /* scene.ini (about 4.6 kB) */
    path2(out, sizeof out, tmp, "wf-scene");
    so.fsize_limit = 2000;
    run_with(&so, (const char *[]){"rigid-boom", "--out", out, "--quiet", "--no-plots", NULL},
             "wfscene", 60, &r);
    tap_ok(r.exited && r.code == 1 && strstr(r.err, "scene.ini: File too large") &&
               first_line_is(out, "status.txt", "status: failed") &&
               file_contains(out, "status.txt", "reason: cannot write ") &&
               file_contains(out, "status.txt", "scene.ini: File too large") &&
               !file_exists(out, "scene.ini") && !file_exists(out, "scene.ini.tmp"),
           "scene.ini cannot be written: exit 1, status.txt failed with the file and the "
           "error, no partial scene.ini (%.200s)",
           r.err);

    /* results.csv mid-run (about 60 kB for 0.2 s) */
    path2(out, sizeof out, tmp, "wf-results");
    so.fsize_limit = 20000;
    run_with(&so,
             (const char *[]){"rigid-boom", "--t-end", "0.2", "--out", out, "--quiet", "--no-plots",
                              NULL},
             "wfresults", 60, &r);
    long rows = check_csv(out, 0, &tl, why, sizeof why);
    tap_ok(r.exited && r.code == 1 && strstr(r.err, "results.csv: File too large"),
           "results.csv cannot be written: exit 1 naming it and EFBIG (%.200s)", r.err);
    char rows_line[64];
    snprintf(rows_line, sizeof rows_line, "\nrows: %ld\n", rows);
    tap_ok(rows > 1 && rows < 201 && file_contains(out, "status.txt", rows_line),
           "results.csv keeps the whole rows that reached it, as many as status.txt says (%ld "
           "rows, %s)",
           rows, why);
    tap_ok(first_line_is(out, "status.txt", "status: failed") &&
               file_contains(out, "status.txt", "results.csv: File too large") &&
               first_line_is(out, "solver_stats.txt", "# crane solver statistics"),
           "status.txt says failed with the reason; solver_stats.txt is written");

    /* the standard output on a full device */
    so.fsize_limit = 0;
    so.stdout_to = "/dev/full";
    run_with(&so, (const char *[]){"--help", NULL}, "fullhelp", 30, &r);
    tap_ok(r.exited && r.code == 1 && strstr(r.err, "standard output"),
           "--help on /dev/full: exit 1 and a message (%.200s)", r.err);
    path2(out, sizeof out, tmp, "wf-stdout");
    run_with(&so,
             (const char *[]){"rigid-boom", "--t-end", "0.02", "--out", out, "--no-plots", NULL},
             "fullrun", 60, &r);
    tap_ok(r.exited && r.code == 1 && strstr(r.err, "standard output") &&
               first_line_is(out, "status.txt", "status: failed") &&
               file_contains(out, "status.txt", "standard output"),
           "a run whose summary cannot be written: exit 1, status.txt failed (%.200s)", r.err);
}


static void test_figures(void)
{
    char out[4200], path_env[4400];
    result r;
    spawn_opts so = {NULL, NULL, NULL, 0};
    so.path_env = fake_gnuplot("gp-fails", "echo 'plots.gp, line 9: unknown terminal' >&2; exit 1",
                               path_env, sizeof path_env);
    path2(out, sizeof out, tmp, "fig-fails");
    run_with(&so, (const char *[]){"rigid-boom", "--t-end", "0.02", "--out", out, "--quiet", NULL},
             "gpfails", 60, &r);
    tap_ok(r.exited && r.code == 1 && strstr(r.err, "gnuplot exited with 1") &&
               strstr(r.err, "fig5a.png") && strstr(r.err, "unknown terminal") &&
               first_line_is(out, "status.txt", "status: failed") &&
               file_contains(out, "status.txt", "drawing the figures"),
           "gnuplot failing: exit 1, status failed, the figures and gnuplot's message named "
           "(%.300s)",
           r.err);
    so.path_env = fake_gnuplot("gp-cut", "printf '\\211PNG\\r\\n' > fig5a.png; exit 0", path_env,
                               sizeof path_env);
    path2(out, sizeof out, tmp, "fig-cut");
    run_with(&so, (const char *[]){"rigid-boom", "--t-end", "0.02", "--out", out, "--quiet", NULL},
             "gpcut", 60, &r);
    tap_ok(r.exited && r.code == 1 && strstr(r.err, "not written whole: fig5a.png") &&
               first_line_is(out, "status.txt", "status: failed"),
           "a figure cut short (gnuplot exits 0): exit 1 naming it (%.300s)", r.err);
}

/* ---------------------------------------------------------- old folders ---- */

/* An earlier run's files in dir, and a file of the user's. */
static void fill_old_folder(const char *dir)
{
    static const char *const names[] = {
        "results.csv",      "fig5a.png", "fig5f.png",     "plots.gp",
        "solver_stats.txt", "crane.gif", "scene.ini.tmp", NULL};
    char p[8192];
    mkdir(dir, 0777);
    path2(p, sizeof p, dir, "status.txt");
    write_text(p, "status: completed\nreason: -\npid: 1\nscene: old\n");
    for (int i = 0; names[i]; i++) {
        path2(p, sizeof p, dir, names[i]);
        write_text(p, "from an earlier run\n");
    }
    path2(p, sizeof p, dir, "vtk");
    mkdir(p, 0777);
    path2(p, sizeof p, dir, "vtk/frame_00000.vtp");
    write_text(p, "<VTKFile/>\n");
    path2(p, sizeof p, dir, "notes.txt");
    write_text(p, "the user's\n");
}

/* --------------------------------------------------------------- signals ---- */

static void test_signals_and_folders(void)
{
    char out[4200], why[256], text[8192];
    double tl;
    result r;

    /* SIGHUP during set-up (512 elements: seconds of model building and settling) */
    path2(out, sizeof out, tmp, "sig-setup");
    pid_t pid = start(
        NULL,
        (const char *[]){"paper", "--elements", "512", "--out", out, "--quiet", "--no-plots", NULL},
        "sigsetup");
    int running = wait_status(pid, out, "status: running", 60);
    sleep_ms(200);
    double t0 = now_s();
    kill(pid, SIGHUP);
    finish_from(pid, 60, "sigsetup", t0, &r);
    tap_ok(running && r.exited && r.code == 128 + SIGHUP && r.seconds < g_bound,
           "SIGHUP during set-up: exit %d within %.1f s (%.2f s)", 128 + SIGHUP, g_bound,
           r.seconds);
    tap_ok(first_line_is(out, "status.txt", "status: interrupted") &&
               file_contains(out, "status.txt", "reason: SIGHUP received while ") &&
               file_contains(out, "status.txt", "(no results written)") &&
               !file_exists(out, "results.csv") && !file_exists(out, "status.txt.signal.tmp"),
           "status.txt: interrupted by SIGHUP during set-up, no results.csv");

    /* an old folder: the earlier run's status, results and figures go at the start; the run
     * says "running" from the start; a second crane is refused the folder; SIGTERM in the middle
     * of a 1000 s output step (a long one: the paper scene runs some 30 times faster than real
     * time) ends the run at once */
    path2(out, sizeof out, tmp, "sig-step");
    fill_old_folder(out);
    pid = start(NULL,
                (const char *[]){"paper", "--output-step", "1000", "--t-end", "2000", "--out",
                                 out, "--quiet", "--no-plots", NULL},
                "sigstep");
    int looping = wait_file(pid, out, "results.csv", 400, 120); /* the row at t = 0 */
    char p[8192];
    path2(p, sizeof p, out, "status.txt");
    slurp(p, text, sizeof text);
    char pid_line[64];
    snprintf(pid_line, sizeof pid_line, "\npid: %ld\n", (long)pid);
    tap_ok(looping && !strncmp(text, "status: running\n", 16) && strstr(text, pid_line) &&
               strstr(text, "\nscene: paper (") && strstr(text, "\ncommand: ") &&
               strstr(text, "--output-step 1000") && strstr(text, "\nstarted: "),
           "status.txt from the start: running, with the pid, the scene, the command line and "
           "the start time");
    int gone = !file_exists(out, "fig5a.png") && !file_exists(out, "fig5f.png") &&
               !file_exists(out, "plots.gp") && !file_exists(out, "crane.gif") &&
               !file_exists(out, "scene.ini.tmp") && !file_exists(out, "vtk") &&
               !file_contains(out, "results.csv", "from an earlier run") &&
               !file_contains(out, "solver_stats.txt", "from an earlier run");
    tap_ok(gone && file_exists(out, "notes.txt"),
           "the earlier run's results, figures and frames are gone; other files stay");
    result r2;
    run(NULL, (const char *[]){"rigid-boom", "--out", out, "--quiet", "--no-plots", NULL}, "inuse",
        60, &r2);
    tap_ok(r2.exited && r2.code == 1 && strstr(r2.err, "is in use") && strstr(r2.err, "pid ") &&
               first_line_is(out, "status.txt", "status: running"),
           "a second crane is refused the folder of a running one (%.200s)", r2.err);
    sleep_ms(300);
    t0 = now_s();
    kill(pid, SIGTERM);
    finish_from(pid, 60, "sigstep", t0, &r);
    long rows = check_csv(out, 0, &tl, why, sizeof why);
    tap_ok(r.exited && r.code == 128 + SIGTERM && r.seconds < g_bound,
           "SIGTERM in the middle of a 1000 s output step: exit %d within %.1f s (%.2f s)",
           128 + SIGTERM, g_bound, r.seconds);
    tap_ok(first_line_is(out, "status.txt", "status: interrupted") &&
               file_contains(out, "status.txt", "reason: SIGTERM received at t = ") &&
               file_contains(out, "status.txt", "rows: 1\n") && rows == 1 && tl == 0 &&
               first_line_is(out, "solver_stats.txt", "# crane solver statistics"),
           "status.txt: interrupted by SIGTERM before the row at 1000 s; results.csv has the row at "
           "0 (%ld rows, %s)",
           rows, why);

    /* a stale "running" of a process that is gone: the folder is taken over */
    path2(out, sizeof out, tmp, "stale-running");
    mkdir(out, 0777);
    pid_t dead = fork();
    if (dead == 0) _exit(0);
    waitpid(dead, NULL, 0);
    snprintf(text, sizeof text, "status: running\nreason: -\npid: %ld\n", (long)dead);
    path2(p, sizeof p, out, "status.txt");
    write_text(p, text);
    run(NULL,
        (const char *[]){"rigid-boom", "--t-end", "0.02", "--out", out, "--quiet", "--no-plots",
                         NULL},
        "stale", 60, &r);
    tap_ok(r.exited && r.code == 0 && first_line_is(out, "status.txt", "status: completed"),
           "a status.txt 'running' of a process that is gone does not block the folder (exit %d)",
           r.code);

    /* an old file that cannot be removed (a folder named results.csv, not empty) */
    path2(out, sizeof out, tmp, "old-blocked");
    mkdir(out, 0777);
    path2(p, sizeof p, out, "results.csv");
    mkdir(p, 0777);
    path2(p, sizeof p, out, "results.csv/x");
    write_text(p, "x\n");
    run(NULL, (const char *[]){"rigid-boom", "--out", out, "--quiet", "--no-plots", NULL},
        "blocked", 60, &r);
    tap_ok(r.exited && r.code == 1 && strstr(r.err, "cannot remove") &&
               strstr(r.err, "results.csv") && first_line_is(out, "status.txt", "status: failed"),
           "an earlier run's file that cannot be removed: exit 1, refused with the reason "
           "(%.200s)",
           r.err);

    /* two SIGINTs in a row while integrating: the second ends the program at once */
    path2(out, sizeof out, tmp, "sig-twice");
    pid = start(NULL, (const char *[]){"paper", "--out", out, "--quiet", "--no-plots", NULL},
                "sigtwice");
    looping = wait_file(pid, out, "results.csv", 3000, 120);
    t0 = now_s();
    kill(pid, SIGINT);
    kill(pid, SIGINT);
    finish_from(pid, 60, "sigtwice", t0, &r);
    rows = check_csv(out, 0, &tl, why, sizeof why);
    tap_ok(looping && r.exited && r.code == 128 + SIGINT && r.seconds < g_bound,
           "two SIGINTs while integrating: exit %d within %.1f s (%.2f s)", 128 + SIGINT, g_bound,
           r.seconds);
    tap_ok(first_line_is(out, "status.txt", "status: interrupted") &&
               file_contains(out, "status.txt", "SIGINT received") && rows >= 1,
           "status.txt: interrupted by SIGINT; results.csv in whole rows (%ld rows, %s)", rows,
           why);

    /* SIGTERM after t_end, while the figures are drawn (a gnuplot that waits): completed */
    char marker[4200], script[8600], path_env[4400];
    path2(marker, sizeof marker, tmp, "gnuplot-started");
    snprintf(script, sizeof script, "touch '%s'; exec sleep 30", marker);
    path2(out, sizeof out, tmp, "sig-end");
    spawn_opts so = {NULL, NULL, fake_gnuplot("gp-slow", script, path_env, sizeof path_env), 0};
    pid = start_with(
        &so, (const char *[]){"rigid-boom", "--t-end", "0.02", "--out", out, "--quiet", NULL},
        "sigend");
    struct stat st;
    for (t0 = now_s(); now_s() - t0 < 60 && stat(marker, &st) != 0;)
        sleep_ms(5);
    t0 = now_s();
    kill(pid, SIGTERM);
    finish_from(pid, 60, "sigend", t0, &r);
    rows = check_csv(out, 0, &tl, why, sizeof why);
    tap_ok(r.exited && r.code == 0 && r.seconds < g_bound,
           "SIGTERM after t_end, while the figures are drawn: exit 0 within %.1f s (%.2f s)",
           g_bound, r.seconds);
    tap_ok(first_line_is(out, "status.txt", "status: completed") &&
               file_contains(out, "status.txt", "SIGTERM received while drawing the figures") &&
               rows == 21 && !file_exists(out, "fig5a.png"),
           "status.txt: completed (the integration reached t_end), the signal noted, no figures "
           "(%ld rows, %s)",
           rows, why);
}

int main(int argc, char **argv)
{
    if (argc < 3) {
        printf("1..0 # SKIP usage: test_crane_robust CRANE_EXECUTABLE SCENES_DIR\n");
        return 0;
    }
    if (spawn_setup(argc, argv, "crane_robust") != 0) return 1;
    tap_diag("working folder %s", tmp);
    if (getenv("ASAN_OPTIONS") || getenv("UBSAN_OPTIONS") || getenv("VALGRIND_OPTS"))
        g_bound = 5.0; /* instrumented: steps and writes several times slower */

    test_bad_numbers_and_paths();
    test_write_failures();
    test_figures();
    test_signals_and_folders();

    int rc = tap_done();
    if (rc == 0) {
        char cmd[4200];
        snprintf(cmd, sizeof cmd, "rm -rf '%s'", tmp);
        if (system(cmd) != 0) tap_diag("could not remove %s", tmp);
    }
    return rc;
}
