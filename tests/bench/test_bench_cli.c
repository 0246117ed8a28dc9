/* The benchmark harness's command line and outputs (bench/bench.c), run as a program:
 *   test_bench_cli BENCH OUTDIR
 * bad command lines end with exit status 2; a small work-precision run (two problems, two
 * tolerances, every solver) and a filtered stability run write their files with the expected
 * rows; an output folder that cannot be created gives exit status 1. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <fcntl.h>
#include <unistd.h>

#include "tap.h"

static const char *bench;

/* Runs bench with args (NULL-terminated, without argv[0]), output to /dev/null; exit status, or
 * -1 if it did not exit normally. */
static int run(const char *const *args)
{
    char *argv[32];
    int n = 0;
    argv[n++] = (char *)bench;
    for (; *args && n < 31; args++)
        argv[n++] = (char *)*args;
    argv[n] = NULL;
    fflush(NULL);
    pid_t pid = fork();
    if (pid < 0) return -1;
    if (pid == 0) {
        int fd = open("/dev/null", O_WRONLY);
        if (fd >= 0) {
            dup2(fd, STDOUT_FILENO);
            dup2(fd, STDERR_FILENO);
            close(fd);
        }
        execv(bench, argv);
        _exit(127);
    }
    int st = 0;
    if (waitpid(pid, &st, 0) < 0) return -1;
    return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

/* Lines of a file that contain every one of the given strings (NULL-terminated); -1 if the file
 * cannot be read. */
static int count_lines(const char *path, const char *a, const char *b)
{
    FILE *f = fopen(path, "r");
    if (!f) return -1;
    char line[8192];
    int n = 0;
    while (fgets(line, sizeof line, f))
        if ((!a || strstr(line, a)) && (!b || strstr(line, b))) n++;
    fclose(f);
    return n;
}

/* The max_order column of crane_wp.csv over the rows that begin with prefix: their smallest
 * (largest = 0) or largest (largest = 1); -1 if there is none or the file cannot be read. */
static int max_order_of(const char *path, const char *prefix, int largest)
{
    FILE *f = fopen(path, "r");
    if (!f) return -1;
    char line[8192];
    int col = -1, best = -1;
    while (fgets(line, sizeof line, f)) {
        if (col < 0) { /* the header: the column's place */
            int c = 0;
            for (char *p = line; *p; p++) {
                if (!strncmp(p, "max_order,", 10) && (p == line || p[-1] == ',')) col = c;
                if (*p == ',') c++;
            }
            if (col < 0) break;
            continue;
        }
        if (strncmp(line, prefix, strlen(prefix))) continue;
        char *p = line;
        for (int c = 0; c < col && p; c++) {
            p = strchr(p, ',');
            if (p) p++;
        }
        if (!p || *p == ',') continue;
        int k = atoi(p);
        if (best < 0 || (largest ? k > best : k < best)) best = k;
    }
    fclose(f);
    return best;
}

int main(int argc, char **argv)
{
    if (argc != 3) {
        fprintf(stderr, "usage: test_bench_cli BENCH OUTDIR\n");
        return 2;
    }
    bench = argv[1];
    const char *dir = argv[2];

    static const char *const bad[][4] = {
        {"--bogus", NULL},
        {"--rtols", "2", NULL},
        {"--rtols", "1e-4,x", NULL},
        {"--repeat", "0", NULL},
        {"--repeat", NULL},
        {"--problems", "nosuch", NULL},
        {"--solvers", "nosuch", NULL},
        {"--scaling", "1024", NULL},
        {"--crane-horizon", "-1", NULL},
        {"--crane-realtime", "x", NULL},
        {"--solvers", "bgdae-klu,bgdae-klu", NULL},
        {"--crane-full-rtols", "0", NULL},
        {"--crane-full-scene", "/no/such/scene.ini", NULL},
        {"--newton-dgmax", "1", NULL},
        {"--crane-full-max-order", "6", NULL},
        {"--crane-full-max-order", "0", NULL},
    };
    for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
        int r = run(bad[i]);
        tap_ok(r == 2, "bad command line %s %s: exit status %d (want 2)", bad[i][0],
               bad[i][1] ? bad[i][1] : "", r);
    }

    char out[4096], path[4200];
    snprintf(out, sizeof out, "%s/wp", dir);
    const char *small[] = {"--problems", "pendulum2,ap102", "--rtols", "1e-4,1e-6", "--repeat",
                           "1",          "--scaling",       "none",    "--out",     out,
                           NULL};
    int r = run(small);
    tap_ok(r == 0, "small work-precision run: exit status %d", r);
    snprintf(path, sizeof path, "%s/work_precision.csv", out);
    int rows = count_lines(path, NULL, NULL);
    tap_ok(count_lines(path, "problem,solver,rtol", NULL) == 1,
           "work_precision.csv has its header");
    /* every solver at both tolerances on both problems: at least our four */
    int ours_p = count_lines(path, "pendulum2,bgdae-", NULL),
        ours_a = count_lines(path, "ap102,bgdae-", NULL);
    tap_ok(ours_p == 14 && ours_a == 14, "work_precision.csv: 14 rows of ours per problem (%d, %d)",
           ours_p, ours_a);
    tap_ok(rows == 1 + 2 * count_lines(path, "pendulum2,", NULL),
           "work_precision.csv: the same rows for both problems (%d lines)", rows);
    tap_ok(count_lines(path, "pendulum2,bgdae-klu,0.0001,", NULL) == 1 &&
               count_lines(path, "pendulum2,bgdae-klu,0.0001,1e-06,0,", NULL) == 1,
           "work_precision.csv: bgdae-klu on pendulum2 at 1e-4 succeeded (status 0)");
    snprintf(path, sizeof path, "%s/report.md", out);
    tap_ok(count_lines(path, "## Targets", NULL) == 1, "report.md has the targets");
    tap_ok(count_lines(path, "## CPU time of bgdae-klu / ida-klu", NULL) == 1,
           "report.md has the ratio table");
    tap_ok(count_lines(path, "| pendulum2 | 5 |", NULL) == 1,
           "report.md: pendulum2 in the ratio table");
    tap_ok(count_lines(path, "## Steps against tolerance", NULL) == 1 &&
               count_lines(path, "| pendulum2 | bgdae-klu |", NULL) == 1,
           "report.md has the steps against tolerance, pendulum2 with bgdae-klu in it");
    tap_ok(count_lines(path, "## MEBDFI's published run statistics", NULL) == 1 &&
               count_lines(path, "### pendulum2, bgdae-klu (MEBDFDAE", NULL) == 1 &&
               count_lines(path, "### pendulum2, bgdae-mebdf (MEBDFDAE", NULL) == 1 &&
               count_lines(path, "| 0.0001 | 21 |", NULL) == 2,
           "report.md has MEBDFI beside bgdae-klu and bgdae-mebdf: pendulum2 at 1e-4 with "
           "MEBDFDAE's 21 steps");
    snprintf(path, sizeof path, "%s/steps_vs_tol.csv", out);
    tap_ok(count_lines(path, "problem,solver,rtol", NULL) == 1 &&
               count_lines(path, "pendulum2,bgdae-klu,", NULL) == 2 &&
               count_lines(path, "ap102,", NULL) == count_lines(path, "pendulum2,", NULL),
           "steps_vs_tol.csv: header, a row per problem, solver and tolerance");
    snprintf(path, sizeof path, "%s/mebdfi_compare.csv", out);
    tap_ok(count_lines(path, "pendulum2,", NULL) == 6 &&
               count_lines(path, "pendulum2,bgdae-mebdf,", NULL) == 2 &&
               count_lines(path, "ap102,", NULL) == 0,
           "mebdfi_compare.csv: pendulum2 at both tolerances, MEBDFDAE's, bgdae-klu's and "
           "bgdae-mebdf's; no ap102");

    snprintf(out, sizeof out, "%s/stab", dir);
    const char *stab[] = {"--problems", "none",  "--stability", "--stability-filter",
                          "pendulum",   "--out", out,           NULL};
    r = run(stab);
    tap_ok(r == 0, "filtered stability run: exit status %d", r);
    snprintf(path, sizeof path, "%s/stability.csv", out);
    tap_ok(count_lines(path, "\"pendulum", NULL) == 3, "stability.csv: the three pendulum cases");
    tap_ok(count_lines(path, "\"pendulum", ",\"solved\",") == 3, "stability.csv: all three solved");
    snprintf(path, sizeof path, "%s/report.md", out);
    tap_ok(count_lines(path, "## Stability suite", NULL) == 1,
           "report.md has the stability section");

    /* the crane-full series with bgdae-klu's orders capped (a 0.3 s paper scene): its rows
     * take orders up to the cap, the reference's (rtol 1e-10) beyond it */
    char scene[4200];
    snprintf(out, sizeof out, "%s/full", dir);
    snprintf(scene, sizeof scene, "%s/short.ini", dir);
    FILE *sf = fopen(scene, "w");
    if (sf) {
        fputs("[solver]\nt_end = 0.3\n", sf);
        fclose(sf);
    }
    const char *full[] = {"--problems", "none", "--crane-full-scene", scene, "--crane-full-rtols",
                          "1e-4,1e-6", "--crane-full-max-order", "2", "--scaling", "none",
                          "--crane-realtime", "0", "--out", out, NULL};
    r = run(full);
    tap_ok(sf && r == 0, "crane-full series with --crane-full-max-order 2: exit status %d", r);
    snprintf(path, sizeof path, "%s/crane_wp.csv", out);
    int ref_k = max_order_of(path, "bgdae-klu (reference),", 0),
        lo_k = max_order_of(path, "bgdae-klu,", 0), hi_k = max_order_of(path, "bgdae-klu,", 1);
    tap_ok(count_lines(path, "bgdae-klu,", NULL) == 2 && lo_k >= 1 && hi_k <= 2 && ref_k > 2,
           "crane_wp.csv: bgdae-klu's two runs at orders 1 .. 2 (took %d .. %d), the reference "
           "beyond 2 (%d)",
           lo_k, hi_k, ref_k);
    snprintf(path, sizeof path, "%s/report.md", out);
    tap_ok(count_lines(path, "at orders up to 2 (--crane-full-max-order", NULL) == 1,
           "report.md names the cap");

    const char *unwritable[] = {"--problems", "pendulum2",          "--rtols", "1e-4",
                                "--out",      "/proc/bench-test/x", NULL};
    r = run(unwritable);
    tap_ok(r == 1, "output folder that cannot be created: exit status %d (want 1)", r);
    return tap_done();
}
