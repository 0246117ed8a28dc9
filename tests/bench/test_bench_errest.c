/* bench --error-estimate (bench/bench_errest.h), run as a program:
 *   test_bench_errest BENCH OUTDIR
 * on three problems with closed-form solutions (lin2, smooth_ode, kinks) at rtol 1e-4 and 1e-6:
 * error_estimate.csv has a row per problem and tolerance with the estimate and the true error
 * against the exact solution at tend (both above round-off), their ratio within a factor 10, the
 * companion at rtol / 100 taking more steps than the run; report.md has the section with its
 * count; without the option (and without --quick) no error_estimate.csv is written. */
#include <fcntl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include "tap.h"

static const char *bench;

/* Runs bench with args (NULL-terminated), output to /dev/null; its exit status or -1. */
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

static int contains(const char *path, const char *what)
{
    static char buf[1 << 18];
    FILE *f = fopen(path, "r");
    if (!f) return 0;
    size_t n = fread(buf, 1, sizeof buf - 1, f);
    buf[n] = '\0';
    fclose(f);
    return strstr(buf, what) != NULL;
}

int main(int argc, char **argv)
{
    if (argc != 3) {
        fprintf(stderr, "usage: test_bench_errest BENCH OUTDIR\n");
        return 2;
    }
    bench = argv[1];
    char dir[4096], dir2[4096], csv[4200], rep[4200];
    snprintf(dir, sizeof dir, "%s/errest", argv[2]);
    snprintf(dir2, sizeof dir2, "%s/no-errest", argv[2]);
    snprintf(csv, sizeof csv, "%s/error_estimate.csv", dir);
    snprintf(rep, sizeof rep, "%s/report.md", dir);
    static const char *const problems[3] = {"lin2", "smooth_ode", "kinks"};
    int rc = run((const char *[]){"--problems", "lin2,smooth_ode,kinks", "--solvers", "bgdae-klu",
                                  "--rtols", "1e-4,1e-6", "--repeat", "1", "--scaling", "none",
                                  "--crane-realtime", "0", "--error-estimate", "--out", dir, NULL});
    tap_ok(rc == 0, "bench --error-estimate on lin2, smooth_ode, kinks: exit 0 (%d)", rc);
    FILE *f = fopen(csv, "r");
    char line[4096];
    tap_ok(f && fgets(line, sizeof line, f) &&
               !strcmp(line, "problem,rtol,atol,factor,component,estimate,true_error,ratio,"
                             "within_10x,steps,steps_tight,message\n"),
           "error_estimate.csv with its header");
    int seen[3][2] = {{0}}, good = 0, rows = 0;
    char why[512] = "";
    while (f && fgets(line, sizeof line, f)) {
        char *fld[12], *s = line;
        int k = 0;
        while (k < 12) {
            fld[k++] = s;
            if (k == 12) break;
            char *c = strchr(s, ',');
            if (!c) break;
            *c = '\0';
            s = c + 1;
        }
        rows++;
        if (k < 12) continue;
        double rtol = atof(fld[1]), factor = atof(fld[3]), est = atof(fld[5]), truth = atof(fld[6]),
               ratio = atof(fld[7]);
        long steps = atol(fld[9]), tight = atol(fld[10]);
        int p = -1, t = rtol == 1e-4 ? 0 : (rtol == 1e-6 ? 1 : -1);
        for (int i = 0; i < 3; i++)
            if (!strcmp(fld[0], problems[i])) p = i;
        if (p < 0 || t < 0) continue;
        seen[p][t]++;
        /* both above round-off, the ratio theirs and within 10x, flagged so, the companion at
         * the tighter tolerances doing more work */
        int ok = factor == 100 && est > 1e-12 && truth > 1e-12 &&
                 fabs(ratio - est / truth) <= 1e-3 * ratio && ratio >= 0.1 && ratio <= 10 &&
                 !strcmp(fld[8], "yes") && tight > steps && steps > 0;
        if (ok)
            good++;
        else if (!why[0])
            snprintf(why, sizeof why,
                     "%.40s at %g: estimate %g, true %g, ratio %g, %.20s, steps %ld/%ld", fld[0],
                     rtol, est, truth, ratio, fld[8], steps, tight);
    }
    if (f) fclose(f);
    int all = 1;
    for (int i = 0; i < 3; i++)
        all = all && seen[i][0] == 1 && seen[i][1] == 1;
    tap_ok(all && rows == 6, "one row per problem and tolerance (%d rows)", rows);
    tap_ok(good == 6,
           "each estimate within a factor 10 of the true error against the exact solution (%d of "
           "6%s%s)",
           good, why[0] ? "; " : "", why);
    tap_ok(contains(rep, "## Error estimate against the true error") &&
               contains(rep, "6 of 6 estimates within a factor 10 of the true error"),
           "report.md has the section and its count");

    rc = run((const char *[]){"--problems", "lin2", "--solvers", "bgdae-klu", "--rtols", "1e-4",
                              "--repeat", "1", "--scaling", "none", "--crane-realtime", "0",
                              "--out", dir2, NULL});
    snprintf(csv, sizeof csv, "%s/error_estimate.csv", dir2);
    struct stat st;
    tap_ok(rc == 0 && stat(csv, &st) != 0, "without --error-estimate: no error_estimate.csv");
    return tap_done();
}
