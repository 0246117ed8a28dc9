/* The crane program end to end: every shipped scene for a short time (exit 0, results.csv with
 * the header of crane_output_names and one complete row per output time, model_stats.txt,
 * solver_stats.txt, scene.ini, status.txt; the figures when gnuplot is installed), the default
 * output folder and bare scene names, bad command lines (exit 2 with a clear message), the
 * catalogue of malformed scene files (exit 2, message naming file, line and key, no crash), a
 * solver failure (exit 1, status.txt with the solver's message), and an interrupted run (SIGTERM:
 * the rows written are kept whole, status.txt says so). test_crane_robust.c provokes the faults
 * (write failures, signals at every stage, old folders, bad numbers and paths); crane_spawn.h
 * starts the program for both.
 *
 *   test_crane_program CRANE_EXECUTABLE SCENES_DIR */
#include "crane_spawn.h"
#include "tap.h"

#include "bad_scenes.h"

static void test_help_and_bad_command_lines(void)
{
    result r;
    run(NULL, (const char *[]){"--help", NULL}, "help", 30, &r);
    tap_ok(r.exited && r.code == 0 && strstr(r.out, "usage: crane"), "--help: exit 0 and usage");
    run(NULL, (const char *[]){"--version", NULL}, "version", 30, &r);
    tap_ok(r.exited && r.code == 0 && strstr(r.out, "crane (bgdae)"), "--version: exit 0");

    struct {
        const char *args[6], *want;
    } bad[] = {
        {{"--rtoll", "1e-6", NULL}, "--rtol"},
        {{"--rtol", "abc", NULL}, "got 'abc'"},
        {{"--rtol", "2", NULL}, "key 'rtol' in [solver]"},
        {{"--elements", "513", NULL}, "key 'elements' in [boom]"},
        {{"--elements=-1", NULL}, "got '-1'"},
        {{"--t-end", NULL}, "needs a value"},
        {{"--t-end", "0", NULL}, "key 't_end'"},
        {{"--atol", "nan", NULL}, "key 'atol'"},
        {{"--t-end", "1", "--output-step", "5", NULL}, "output_step"},
        {{"--set", "boom.lenght=3", NULL}, "'length'"},
        {{"--set", "nonsense", NULL}, "SECTION.KEY=VALUE"},
        {{"--quiet=1", NULL}, "takes no value"},
        {{"a.ini", "b.ini", NULL}, "more than one scene"},
        {{"no-such-scene-file.ini", NULL}, "not found"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
        char tag[32];
        snprintf(tag, sizeof tag, "badcl%zu", i);
        const char *args[10];
        int n = 0;
        for (int k = 0; bad[i].args[k]; k++)
            args[n++] = bad[i].args[k];
        args[n++] = "--out";
        args[n++] = tmp; /* never written: the run stops before */
        args[n++] = "--quiet";
        args[n] = NULL;
        run(NULL, args, tag, 30, &r);
        int ok = r.exited && r.code == 2 && strstr(r.err, bad[i].want);
        tap_ok(ok, "bad command line %s %s: exit 2, message names '%s'", bad[i].args[0],
               bad[i].args[1] ? bad[i].args[1] : "", bad[i].want);
        if (!ok) tap_diag("exit %d, stderr: %s", r.code, r.err);
    }
}

static void test_scene_runs(int gnuplot)
{
    /* scene, end time, rows expected, NaN allowed (outputs of parts not built) */
    static const struct {
        const char *name, *t_end;
        long rows;
        int allow_nan;
    } sc[] = {{"paper", "0.2", 201, 0},
              {"rigid-boom", "0.2", 201, 0},
              {"prescribed-rotation", "0.2", 201, 1},
              {"fine-mesh", "0.05", 51, 0},
              {"table-kg", "0.2", 201, 0}};
    for (int i = 0; i < 5; i++) {
        const char *name = sc[i].name;
        char scene[4200], out[4200], why[256];
        snprintf(scene, sizeof scene, "%s/%s.ini", scenes, name);
        snprintf(out, sizeof out, "%s/run-%s", tmp, name);
        int plots = gnuplot && i == 0;
        const char *args[] = {
            scene, "--out", out, "--t-end", sc[i].t_end, "--quiet", plots ? NULL : "--no-plots",
            NULL};
        result r;
        run(NULL, args, name, 100, &r);
        int ok = r.exited && r.code == 0 && !r.timed_out;
        tap_ok(ok, "%s: exit 0 (--t-end %s)", name, sc[i].t_end);
        if (!ok)
            tap_diag("exit %d, signal %d, timed out %d, stderr: %s", r.code, r.sig, r.timed_out,
                     r.err);
        double tl, want_t = atof(sc[i].t_end);
        long rows = check_csv(out, sc[i].allow_nan, &tl, why, sizeof why);
        tap_ok(rows == sc[i].rows && fabs(tl - want_t) < 1e-12,
               "%s: results.csv has the header and %ld complete rows up to t = %s (%ld rows, "
               "%s)",
               name, sc[i].rows, sc[i].t_end, rows, why);
        tap_ok(first_line_is(out, "model_stats.txt", "# crane model statistics") &&
                   file_contains(out, "model_stats.txt", "equations") &&
                   file_contains(out, "model_stats.txt", "nominal scales by quantity") &&
                   file_contains(out, "model_stats.txt", "force [N]"),
               "%s: model_stats.txt (with the nominal scales by quantity)", name);
        tap_ok(first_line_is(out, "solver_stats.txt", "# crane solver statistics") &&
                   file_contains(out, "solver_stats.txt", "steps=") &&
                   file_contains(out, "solver_stats.txt",
                                 "absolute tolerances: atol times each unknown's nominal"),
               "%s: solver_stats.txt", name);
        tap_ok(first_line_is(out, "status.txt", "status: completed"), "%s: status.txt completed",
               name);
        char t_line[64];
        snprintf(t_line, sizeof t_line, "t_end = %s ", sc[i].t_end);
        tap_ok(file_contains(out, "scene.ini", t_line), "%s: scene.ini holds the scene as run",
               name);
        if (plots) {
            int all = 1;
            for (char c = 'a'; c <= 'f'; c++) {
                char png[32];
                snprintf(png, sizeof png, "fig5%c.png", c);
                all = all && file_nonempty(out, png);
            }
            tap_ok(all, "%s: figures fig5a..f.png drawn by gnuplot", name);
        }
    }
    if (!gnuplot) tap_diag("gnuplot not installed: figures not checked");

    /* a bare scene name, the default output folder results/<scene>/, the summary */
    result r;
    char cwd[4200];
    snprintf(cwd, sizeof cwd, "%s/cwd", tmp);
    mkdir(cwd, 0777);
    run(cwd, (const char *[]){"rigid-boom", "--t-end", "0.05", "--no-plots", NULL}, "bare", 100,
        &r);
    char out[4300], why[256];
    double tl;
    snprintf(out, sizeof out, "%s/results/rigid-boom", cwd);
    tap_ok(r.exited && r.code == 0 && check_csv(out, 0, &tl, why, sizeof why) == 51,
           "a bare scene name is found and the results go to results/<scene>/ (%s)", why);
    tap_ok(strstr(r.out, "final angle") && strstr(r.out, "wall time"),
           "the summary names the final angle and the wall time");
    if (gnuplot) { /* the figures into that relative folder: gnuplot's log opened there */
        run(cwd, (const char *[]){"rigid-boom", "--t-end", "0.05", NULL}, "bare-plots", 100, &r);
        tap_ok(r.exited && r.code == 0 && file_nonempty(out, "fig5a.png"),
               "figures into the relative default folder results/<scene>/ (exit %d): %.200s",
               r.code, r.err);
    }
}

static void test_malformed_files(void)
{
    char dir[4200];
    snprintf(dir, sizeof dir, "%s/bad", tmp);
    mkdir(dir, 0777);
    for (int i = 0; i < NBAD; i++) {
        const bad_scene *b = &BAD_SCENES[i];
        char path[4400], out[4400], where[4500];
        snprintf(path, sizeof path, "%s/%s.ini", dir, b->what);
        snprintf(out, sizeof out, "%s/out-%s", dir, b->what);
        FILE *f = fopen(path, "w");
        if (f) {
            fputs(b->text, f);
            fclose(f);
        }
        result r;
        run(NULL, (const char *[]){path, "--out", out, "--quiet", NULL}, b->what, 30, &r);
        snprintf(where, sizeof where, "%s:%d:", path, b->line);
        int ok = r.exited && r.code == 2 && strstr(r.err, where) && strstr(r.err, b->key);
        tap_ok(ok, "malformed %s.ini: exit 2, message names %s:%d and %s", b->what, b->what,
               b->line, b->key);
        if (!ok) tap_diag("exit %d signal %d: %s", r.code, r.sig, r.err);
    }
}

/* A run the solver cannot do (atol = 1e-300 fails at t = 0 at the time of writing): exit 1 and
 * status.txt "failed" with the solver's message; should the solver cope one day, the exit status
 * and status.txt must still agree. */
static void test_failure(void)
{
    char scene[4200], out[4200];
    snprintf(scene, sizeof scene, "%s/rigid-boom.ini", scenes);
    snprintf(out, sizeof out, "%s/failure", tmp);
    result r;
    run(NULL,
        (const char *[]){scene, "--out", out, "--t-end", "0.05", "--no-plots", "--quiet", "--set",
                         "solver.atol=1e-300", NULL},
        "failure", 100, &r);
    if (r.exited && r.code == 0) {
        tap_diag("the solver coped with atol = 1e-300: failure path not exercised");
        tap_ok(first_line_is(out, "status.txt", "status: completed"),
               "exit 0 and status.txt agree");
        return;
    }
    tap_ok(r.exited && r.code == 1 && strstr(r.err, "crane: solver"),
           "a solver failure: exit 1 with the solver's message (exit %d: %.200s)", r.code, r.err);
    tap_ok(first_line_is(out, "status.txt", "status: failed") &&
               file_contains(out, "status.txt", "reason: solver: "),
           "status.txt says failed, with the solver's message");
    tap_ok(first_line_is(out, "solver_stats.txt", "# crane solver statistics") &&
               file_contains(out, "solver_stats.txt", "status: failed"),
           "solver_stats.txt is written after a failure");
}

static void test_interrupt(void)
{
    char scene[4200], out[4200], csv[4300];
    snprintf(scene, sizeof scene, "%s/paper.ini", scenes);
    snprintf(out, sizeof out, "%s/interrupted", tmp);
    snprintf(csv, sizeof csv, "%s/results.csv", out);
    pid_t pid = start(NULL, (const char *[]){scene, "--out", out, "--quiet", NULL}, "intr");
    /* wait for some rows, then stop it */
    struct stat st;
    for (int i = 0; i < 12000; i++) {
        if (stat(csv, &st) == 0 && st.st_size > 20000) break;
        if (waitpid(pid, NULL, WNOHANG) == pid) break;
        sleep_ms(10);
    }
    kill(pid, SIGTERM);
    result r;
    finish(pid, 120, "intr", &r);
    char why[256];
    double tl;
    long rows = check_csv(out, 0, &tl, why, sizeof why);
    tap_ok(r.exited && r.code == 128 + SIGTERM, "SIGTERM: the program stops with exit %d (%d)",
           128 + SIGTERM, r.code);
    tap_ok(rows > 1 && tl < 20, "the rows written are kept whole (%ld rows to t = %g, %s)", rows,
           tl, why);
    tap_ok(first_line_is(out, "status.txt", "status: interrupted") &&
               file_contains(out, "status.txt", "SIGTERM"),
           "status.txt says the run was interrupted by SIGTERM");
    tap_ok(first_line_is(out, "solver_stats.txt", "# crane solver statistics"),
           "solver_stats.txt is written after an interruption");
}

/* The steps at orders 1..5 from solver_stats.txt of the run in dir ("orders=a/b/c/d/e"); 0 if
 * they are not there. */
static int orders_of(const char *dir, long k[5])
{
    char p[4300], buf[8192];
    snprintf(p, sizeof p, "%s/solver_stats.txt", dir);
    slurp(p, buf, sizeof buf);
    const char *o = strstr(buf, " orders=");
    return o && sscanf(o, " orders=%ld/%ld/%ld/%ld/%ld", &k[0], &k[1], &k[2], &k[3], &k[4]) == 5;
}

/* [solver] max_order reaches the integrator: the paper scene's 0.2 s, which takes orders 3 to
 * 5 (the run of test_scene_runs), with max_order = 2 takes none of them. */
static void test_max_order(void)
{
    char scene[4200], out[4200], def[4200];
    snprintf(scene, sizeof scene, "%s/paper.ini", scenes);
    snprintf(out, sizeof out, "%s/run-paper-k2", tmp);
    snprintf(def, sizeof def, "%s/run-paper", tmp);
    const char *args[] = {scene,   "--out",   out, "--t-end", "0.2", "--quiet", "--no-plots",
                          "--set", "solver.max_order=2", NULL};
    result r;
    run(NULL, args, "max_order", 100, &r);
    long k2[5], k5[5];
    int ok2 = r.exited && r.code == 0 && orders_of(out, k2),
        ok5 = orders_of(def, k5);
    tap_ok(ok2 && ok5 && k5[2] + k5[3] + k5[4] > 0 && k2[2] + k2[3] + k2[4] == 0 && k2[1] > 0,
           "[solver] max_order = 2: steps at orders 1..5 %ld/%ld/%ld/%ld/%ld (max_order = 5: "
           "%ld/%ld/%ld/%ld/%ld)",
           ok2 ? k2[0] : -1, ok2 ? k2[1] : -1, ok2 ? k2[2] : -1, ok2 ? k2[3] : -1,
           ok2 ? k2[4] : -1, ok5 ? k5[0] : -1, ok5 ? k5[1] : -1, ok5 ? k5[2] : -1,
           ok5 ? k5[3] : -1, ok5 ? k5[4] : -1);
}

int main(int argc, char **argv)
{
    if (argc < 3) {
        printf("1..0 # SKIP usage: test_crane_program CRANE_EXECUTABLE SCENES_DIR\n");
        return 0;
    }
    if (spawn_setup(argc, argv, "crane_test") != 0) return 1;
    tap_diag("working folder %s", tmp);
    int gnuplot = system("command -v gnuplot >/dev/null 2>&1") == 0;

    test_help_and_bad_command_lines();
    test_malformed_files();
    test_scene_runs(gnuplot);
    test_max_order();
    test_failure();
    test_interrupt();

    int rc = tap_done();
    if (rc == 0) {
        char cmd[4200];
        snprintf(cmd, sizeof cmd, "rm -rf '%s'", tmp);
        if (system(cmd) != 0) tap_diag("could not remove %s", tmp);
    }
    return rc;
}
