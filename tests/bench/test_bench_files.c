/* The benchmark harness's checked writes (bench/bench.c, bench_file of bench/bench_util.h), run as
 * a program:
 *   test_bench_files BENCH OUTDIR
 * an --out longer than the bench's paths is a bad command line (exit status 2, the option named,
 * nothing created); an --out that names a regular file ends with exit status 1 and names it with
 * the system's error; a write that fails part way (a file size limit, RLIMIT_FSIZE, with SIGXFSZ
 * ignored) ends with exit status 1, names each file with the system's error, leaves no part of
 * those files and says in its summary that the results are incomplete; a file that cannot be
 * written (/dev/full in its place) leaves the others written and the report listing it; --help
 * into /dev/full ends with exit status 1. Each run: one small problem, --quick, no scaling.
 * Then one real-time run of each crane scene (--crane-realtime 1): each completes (the child's
 * line read back whole) and its parts add up to its wall time. */
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include "tap.h"

static const char *bench;

/* What a run of bench printed (the first parts of its standard output and error). */
typedef struct ran {
    int status; /* exit status, -1 if it did not exit normally */
    char out[4096], err[16384];
} ran;

/* Reads fd to its end, keeping the first size - 1 bytes in buf. */
static void drain(int fd, char *buf, size_t size)
{
    size_t len = 0;
    char drop[512];
    for (;;) {
        ssize_t k =
            len + 1 < size ? read(fd, buf + len, size - 1 - len) : read(fd, drop, sizeof drop);
        if (k < 0 && errno == EINTR) continue;
        if (k <= 0) break;
        if (len + 1 < size) len += (size_t)k;
    }
    buf[len] = '\0';
}

/* Runs bench with args (NULL-terminated, without argv[0]); fsize > 0: under a file size limit of
 * fsize bytes with SIGXFSZ ignored (writes beyond it fail with EFBIG); stdout_path: its standard
 * output goes there instead of into r->out. Its standard error into r->err (a pipe, free of the
 * limit). */
static void run(ran *r, const char *const *args, long fsize, const char *stdout_path)
{
    char *argv[32];
    int n = 0;
    argv[n++] = (char *)bench;
    for (; *args && n < 31; args++)
        argv[n++] = (char *)*args;
    argv[n] = NULL;
    memset(r, 0, sizeof *r);
    r->status = -1;
    int po[2], pe[2];
    if (pipe(po) != 0 || pipe(pe) != 0) return;
    fflush(NULL);
    pid_t pid = fork();
    if (pid < 0) return;
    if (pid == 0) {
        close(po[0]);
        close(pe[0]);
        int fo = stdout_path ? open(stdout_path, O_WRONLY) : po[1];
        if (fo < 0 || dup2(fo, STDOUT_FILENO) < 0 || dup2(pe[1], STDERR_FILENO) < 0) _exit(126);
        if (fsize > 0) {
            struct rlimit rl = {(rlim_t)fsize, (rlim_t)fsize};
            signal(SIGXFSZ, SIG_IGN); /* ignored across exec: writes fail with EFBIG instead */
            if (setrlimit(RLIMIT_FSIZE, &rl) != 0) _exit(125);
        }
        execv(bench, argv);
        _exit(127);
    }
    close(po[1]);
    close(pe[1]);
    /* stdout is short (a summary line): read it first, then stderr (the pipes hold 64 kB) */
    drain(po[0], r->out, sizeof r->out);
    drain(pe[0], r->err, sizeof r->err);
    close(po[0]);
    close(pe[0]);
    int st = 0;
    while (waitpid(pid, &st, 0) < 0)
        if (errno != EINTR) return;
    r->status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

static int exists(const char *path)
{
    struct stat st;
    return lstat(path, &st) == 0;
}

/* path/name exists */
static int has(const char *dir, const char *name)
{
    char p[8192];
    snprintf(p, sizeof p, "%s/%s", dir, name);
    return exists(p);
}

/* The whole of a small file (up to size - 1 bytes) into buf; -1 if it cannot be read. */
static int slurp(const char *dir, const char *name, char *buf, size_t size)
{
    char p[8192];
    snprintf(p, sizeof p, "%s/%s", dir, name);
    FILE *f = fopen(p, "r");
    if (!f) return -1;
    size_t n = fread(buf, 1, size - 1, f);
    buf[n] = '\0';
    fclose(f);
    return 0;
}

/* stderr has the line "bench: cannot write DIR/NAME: ERROR" */
static int says(const ran *r, const char *dir, const char *name, const char *error)
{
    char line[8400];
    snprintf(line, sizeof line, "bench: cannot write %s/%s: %s\n", dir, name, error);
    return strstr(r->err, line) != NULL;
}

int main(int argc, char **argv)
{
    if (argc != 3) {
        fprintf(stderr, "usage: test_bench_files BENCH OUTDIR\n");
        return 2;
    }
    bench = argv[1];
    const char *base = argv[2];
    char dir[8192], path[8300];
    ran r;
    /* the bench creates its folder's parents: base itself may not exist yet */
    snprintf(dir, sizeof dir, "%s", base);
    for (char *q = dir + 1; *q; q++)
        if (*q == '/') {
            *q = '\0';
            mkdir(dir, 0755);
            *q = '/';
        }
    mkdir(dir, 0755);

    /* 1. an --out longer than the paths the bench builds: a bad command line, nothing created
     * (BASE/long/yyy.../yyy...: 20 folders of 199 characters, each one a valid name) */
    {
        size_t bl = strlen(base), len = bl + 5 + 20 * 200;
        char *longdir = malloc(len + 1);
        if (!longdir) return 1;
        snprintf(longdir, len + 1, "%s/long", base);
        for (int k = 0; k < 20; k++) {
            char *p = longdir + bl + 5 + 200 * k;
            p[0] = '/';
            memset(p + 1, 'y', 199);
        }
        longdir[len] = '\0';
        const char *args[] = {"--quick", "--problems", "ap102", "--scaling",
                              "none",    "--out",      longdir, NULL};
        run(&r, args, 0, NULL);
        tap_ok(r.status == 2, "overlong --out: exit status %d (want 2)", r.status);
        tap_ok(strstr(r.err, "bench: --out:") != NULL && !strstr(r.err, "Success"),
               "overlong --out: the option named, no 'Success'");
        tap_ok(!strstr(r.out, "results in"), "overlong --out: no summary of results");
        longdir[bl + 5] = '\0';
        tap_ok(!exists(longdir), "overlong --out: no folder created");
        free(longdir);
    }

    /* 2. an --out that names a regular file */
    {
        snprintf(path, sizeof path, "%s/plain_file", base);
        FILE *f = fopen(path, "w");
        if (f) {
            fputs("keep\n", f);
            fclose(f);
        }
        const char *args[] = {"--quick", "--problems", "ap102", "--scaling",
                              "none",    "--out",      path,    NULL};
        run(&r, args, 0, NULL);
        tap_ok(r.status == 1, "--out naming a regular file: exit status %d (want 1)", r.status);
        char want[8400];
        snprintf(want, sizeof want, "'%s': %s\n", path, strerror(ENOTDIR));
        tap_ok(strstr(r.err, want) != NULL, "--out naming a regular file: named with '%s'",
               strerror(ENOTDIR));
        char text[64] = "";
        tap_ok(slurp(base, "plain_file", text, sizeof text) == 0 && !strcmp(text, "keep\n"),
               "--out naming a regular file: the file untouched");
        tap_ok(!strstr(r.out, "results in"), "--out naming a regular file: no summary of results");
    }

    /* 3. writes failing part way: a file size limit of 1 kB (work_precision.csv and report.md
     * are larger, with or without IDA; steps_vs_tol.csv and mebdfi_compare.csv smaller) */
    {
        snprintf(dir, sizeof dir, "%s/fsize", base);
        const char *args[] = {"--quick", "--problems", "ap102", "--scaling",
                              "none",    "--out",      dir,     NULL};
        run(&r, args, 1024, NULL);
        const char *efbig = strerror(EFBIG);
        tap_ok(r.status == 1, "file size limit: exit status %d (want 1)", r.status);
        tap_ok(says(&r, dir, "work_precision.csv", efbig),
               "file size limit: work_precision.csv named with '%s'", efbig);
        tap_ok(says(&r, dir, "report.md", efbig), "file size limit: report.md named with '%s'",
               efbig);
        tap_ok(!has(dir, "work_precision.csv") && !has(dir, "report.md"),
               "file size limit: no part of work_precision.csv or report.md left");
        tap_ok(has(dir, "steps_vs_tol.csv") && has(dir, "mebdfi_compare.csv"),
               "file size limit: the smaller files written");
        tap_ok(strstr(r.out, "not written") && strstr(r.out, "incomplete") &&
                   !strstr(r.out, "; results in"),
               "file size limit: the summary says the results are incomplete");
        tap_ok(!strstr(r.err, "Success"), "file size limit: no 'Success' said");
        if (r.status != 1) tap_diag("stderr: %.2000s", r.err);
    }

    /* 4. a file that cannot be written at all (/dev/full in its place): the others written, the
     * report lists it */
    if (exists("/dev/full")) {
        snprintf(dir, sizeof dir, "%s/full", base);
        mkdir(dir, 0755);
        snprintf(path, sizeof path, "%s/work_precision.csv", dir);
        unlink(path);
        int linked = symlink("/dev/full", path) == 0;
        const char *args[] = {"--quick", "--problems", "ap102", "--scaling",
                              "none",    "--out",      dir,     NULL};
        run(&r, args, 0, NULL);
        const char *enospc = strerror(ENOSPC);
        tap_ok(linked && r.status == 1, "/dev/full as work_precision.csv: exit status %d (want 1)",
               r.status);
        tap_ok(says(&r, dir, "work_precision.csv", enospc),
               "/dev/full as work_precision.csv: named with '%s'", enospc);
        tap_ok(!has(dir, "work_precision.csv"), "/dev/full as work_precision.csv: not left");
        static char rep[1 << 16];
        char item[256];
        snprintf(item, sizeof item, "- work_precision.csv: %s\n", enospc);
        tap_ok(slurp(dir, "report.md", rep, sizeof rep) == 0 &&
                   strstr(rep, "## Files not written") && strstr(rep, item) &&
                   strstr(rep, "## Steps against tolerance"),
               "/dev/full as work_precision.csv: report.md written, listing it");
        tap_ok(has(dir, "steps_vs_tol.csv") && has(dir, "wp_ap102.dat"),
               "/dev/full as work_precision.csv: the other files written");
    } else {
        tap_diag("no /dev/full: its test points skipped");
    }

    /* 5. --help into a full standard output */
    if (exists("/dev/full")) {
        const char *args[] = {"--help", NULL};
        run(&r, args, 0, "/dev/full");
        tap_ok(r.status == 1 && strstr(r.err, "cannot write the standard output"),
               "--help into /dev/full: exit status %d (want 1), said", r.status);
    }

    /* 6. the real-time runs: each child's line read back whole (a field added to the child's
     * line and not to the parent's reading failed every run): one run of each scene completes,
     * and its parts (residual, Jacobian, linear algebra, the rest) add up to its wall time */
    {
        snprintf(dir, sizeof dir, "%s/realtime", base);
        const char *args[] = {"--problems", "none", "--scaling", "none", "--crane-realtime", "1",
                              "--out", dir, NULL};
        run(&r, args, 0, NULL);
        char text[16384];
        int rows = 0, good = 0;
        if (slurp(dir, "realtime.csv", text, sizeof text) == 0)
            for (char *line = strstr(text, "\nscene,"); line; line = strstr(line + 1, "\nscene,")) {
                char sc[64];
                int el, run_no, st, n;
                double tend, sw, iw, ic, rs, js, ls, os;
                long steps, corners, rej, newton, jac;
                rows++;
                if (sscanf(line + 1,
                           "scene,%63[^,],%d,%lf,%d,%d,%d,%lf,%lf,%lf,%ld,%ld,%ld,%ld,%ld,%lf,%lf,"
                           "%lf,%lf",
                           sc, &el, &tend, &run_no, &st, &n, &sw, &iw, &ic, &steps, &corners, &rej,
                           &newton, &jac, &rs, &js, &ls, &os) == 18 &&
                    st == 0 && steps > 0 && fabs(rs + js + ls + os - iw) <= 1e-3 * iw + 2e-4)
                    good++;
            }
        tap_ok(r.status == 0 && good == 2,
               "--crane-realtime 1: %d runs of the two scenes completed with their parts adding "
               "up to the wall time (want 2; %d scene rows with the medians; exit status %d)",
               good, rows, r.status);
    }
    return tap_done();
}
