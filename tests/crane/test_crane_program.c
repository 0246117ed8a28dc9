/* The crane program end to end: every shipped scene for a short time (exit 0, results.csv with
 * the header of crane_output_names and one complete row per output time, model_stats.txt,
 * solver_stats.txt, scene.ini, status.txt; the figures when gnuplot is installed), the default
 * output folder and bare scene names, bad command lines (exit 2 with a clear message), the
 * catalogue of malformed scene files (exit 2, message naming file, line and key, no crash), a
 * solver failure (exit 1, status.txt with the solver's message), and an interrupted run (SIGTERM:
 * the rows written are kept whole, status.txt says so).
 *
 *   test_crane_program CRANE_EXECUTABLE SCENES_DIR */
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "crane_model.h"
#include "tap.h"

#include "bad_scenes.h"

static char exe[2048], scenes[2048], tmp[1024];

typedef struct result {
    int exited, code, signaled, sig, timed_out;
    char out[8192], err[8192];
} result;

static void sleep_ms(int ms)
{
    struct timespec ts = {ms / 1000, (long)(ms % 1000) * 1000000L};
    nanosleep(&ts, NULL);
}

static void slurp(const char *path, char *buf, size_t size)
{
    buf[0] = '\0';
    FILE *f = fopen(path, "r");
    if (!f) return;
    size_t n = fread(buf, 1, size - 1, f);
    buf[n] = '\0';
    fclose(f);
}

/* Starts the program with args (NULL-terminated) in folder cwd (NULL: here). */
static pid_t start(const char *cwd, const char *const *args, const char *tag)
{
    char so[4200], se[4200];
    snprintf(so, sizeof so, "%s/%s.out", tmp, tag);
    snprintf(se, sizeof se, "%s/%s.err", tmp, tag);
    fflush(stdout);
    pid_t pid = fork();
    if (pid == 0) {
        int fo = open(so, O_WRONLY | O_CREAT | O_TRUNC, 0644);
        int fe = open(se, O_WRONLY | O_CREAT | O_TRUNC, 0644);
        int fi = open("/dev/null", O_RDONLY);
        if (fo < 0 || fe < 0 || fi < 0) _exit(127);
        dup2(fi, 0);
        dup2(fo, 1);
        dup2(fe, 2);
        if (cwd && chdir(cwd) != 0) _exit(127);
        const char *argv[64];
        int n = 0;
        argv[n++] = exe;
        for (int i = 0; args[i] && n < 63; i++)
            argv[n++] = args[i];
        argv[n] = NULL;
        execv(exe, (char *const *)argv);
        _exit(127);
    }
    return pid;
}

static void finish(pid_t pid, double timeout, const char *tag, result *r)
{
    memset(r, 0, sizeof *r);
    int status = 0;
    double waited = 0;
    for (;;) {
        pid_t w = waitpid(pid, &status, WNOHANG);
        if (w == pid) break;
        if (w < 0 && errno != EINTR) break;
        if (waited > timeout) {
            kill(pid, SIGKILL);
            waitpid(pid, &status, 0);
            r->timed_out = 1;
            break;
        }
        sleep_ms(10);
        waited += 0.01;
    }
    r->exited = WIFEXITED(status);
    r->code = r->exited ? WEXITSTATUS(status) : -1;
    r->signaled = WIFSIGNALED(status);
    r->sig = r->signaled ? WTERMSIG(status) : 0;
    char p[8192];
    snprintf(p, sizeof p, "%s/%s.out", tmp, tag);
    slurp(p, r->out, sizeof r->out);
    snprintf(p, sizeof p, "%s/%s.err", tmp, tag);
    slurp(p, r->err, sizeof r->err);
}

static void run(const char *cwd, const char *const *args, const char *tag, double timeout,
                result *r)
{
    finish(start(cwd, args, tag), timeout, tag, r);
}

static int file_nonempty(const char *dir, const char *name)
{
    char p[8192];
    struct stat st;
    snprintf(p, sizeof p, "%s/%s", dir, name);
    return stat(p, &st) == 0 && S_ISREG(st.st_mode) && st.st_size > 0;
}

static int first_line_is(const char *dir, const char *name, const char *want)
{
    char p[8192], line[4096];
    snprintf(p, sizeof p, "%s/%s", dir, name);
    FILE *f = fopen(p, "r");
    if (!f) return 0;
    int ok = fgets(line, sizeof line, f) && !strncmp(line, want, strlen(want));
    fclose(f);
    return ok;
}

static int file_contains(const char *dir, const char *name, const char *want)
{
    char p[8192];
    static char buf[1 << 16];
    snprintf(p, sizeof p, "%s/%s", dir, name);
    slurp(p, buf, sizeof buf);
    return strstr(buf, want) != NULL;
}

/* results.csv: the header of crane_output_names, then rows of CRANE_NOUT numbers with
 * increasing t, all finite (allow_nan: or NaN, which the model writes for the parts a scene does
 * not build). Returns the number of rows (< 0: malformed) and the last t. */
static long check_csv(const char *dir, int allow_nan, double *t_last, char *why, size_t wsize)
{
    char p[8192], header[4096] = "";
    size_t len = 0;
    for (int i = 0; i < CRANE_NOUT; i++)
        len += (size_t)snprintf(header + len, sizeof header - len, "%s%s", i ? "," : "",
                                crane_output_names[i]);
    snprintf(p, sizeof p, "%s/results.csv", dir);
    FILE *f = fopen(p, "r");
    snprintf(why, wsize, "ok");
    if (!f) {
        snprintf(why, wsize, "no results.csv");
        return -1;
    }
    static char line[1 << 14];
    long rows = 0;
    double tprev = -1;
    *t_last = NAN;
    if (!fgets(line, sizeof line, f) || strncmp(line, header, strlen(header)) ||
        line[strlen(header)] != '\n') {
        snprintf(why, wsize, "header is not crane_output_names");
        fclose(f);
        return -1;
    }
    while (fgets(line, sizeof line, f)) {
        size_t n = strlen(line);
        if (n == 0 || line[n - 1] != '\n') {
            snprintf(why, wsize, "row %ld is cut short", rows + 1);
            fclose(f);
            return -1;
        }
        char *s = line, *end;
        int fields = 0, finite = 1;
        double t = NAN;
        for (;;) {
            double v = strtod(s, &end);
            if (end == s) break;
            if (fields == 0) t = v;
            finite = finite && (isfinite(v) || (allow_nan && isnan(v) && fields > 0));
            fields++;
            if (*end != ',') break;
            s = end + 1;
        }
        if (fields != CRANE_NOUT || *end != '\n' || !finite || !(t > tprev)) {
            snprintf(why, wsize, "row %ld: %d fields, finite %d, t %g after %g", rows + 1, fields,
                     finite, t, tprev);
            fclose(f);
            return -1;
        }
        tprev = t;
        rows++;
    }
    fclose(f);
    *t_last = tprev;
    return rows;
}

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

/* path made absolute (the program runs in other folders too) */
static int absolute(const char *path, char *buf, size_t size)
{
    char cwd[1024];
    int n;
    if (path[0] == '/')
        n = snprintf(buf, size, "%s", path);
    else if (getcwd(cwd, sizeof cwd))
        n = snprintf(buf, size, "%s/%s", cwd, path);
    else
        return 0;
    return n > 0 && (size_t)n < size;
}

int main(int argc, char **argv)
{
    if (argc < 3) {
        printf("1..0 # SKIP usage: test_crane_program CRANE_EXECUTABLE SCENES_DIR\n");
        return 0;
    }
    if (!absolute(argv[1], exe, sizeof exe) || !absolute(argv[2], scenes, sizeof scenes)) {
        printf("Bail out! cannot resolve %s or %s\n", argv[1], argv[2]);
        return 1;
    }
    const char *tdir = getenv("TMPDIR");
    snprintf(tmp, sizeof tmp, "%s/crane_test_XXXXXX", tdir && *tdir ? tdir : "/tmp");
    if (!mkdtemp(tmp)) {
        printf("Bail out! mkdtemp failed\n");
        return 1;
    }
    tap_diag("working folder %s", tmp);
    int gnuplot = system("command -v gnuplot >/dev/null 2>&1") == 0;

    test_help_and_bad_command_lines();
    test_malformed_files();
    test_scene_runs(gnuplot);
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
