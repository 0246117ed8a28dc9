/* The error estimate by a companion run at tighter tolerances (runner/rn_errest.h) and
 * crane --error-estimate:
 *   - on a problem with a closed-form solution (an undamped oscillator, a stiff first-order lag
 *     driven by sin t, an algebraic unknown), over 101 output times at rtol = atol 1e-4, 1e-6,
 *     1e-8: the estimate of each column's largest error within a factor 10 of the true largest
 *     error, and the time and size of the column's largest value;
 *   - the companion's failure (tolerances below round-off), a stop flag, bad arguments;
 *   - the program: error_estimate.csv against two separate runs at rtol and rtol / 100 (the
 *     estimate is their difference), the status and statistics files; a companion that cannot
 *     start (--error-estimate 1e12): the run completes, the estimate is marked unavailable; a
 *     run with the estimate interrupted by SIGINT: results.csv in whole rows, status
 *     interrupted, exit 128 + 2, the estimate over the rows written; bad command lines.
 *
 * Usage: test_crane_errest [CRANE_EXECUTABLE SCENES_DIR] (without them, the library part only). */
#include "rn_errest.h"
#include "crane_spawn.h"
#include "tap.h"

/* y1' = y2, y2' = -y1 (y1 = cos t, y2 = -sin t); y3' = 50 (sin t - y3), y3(0) = 0; 0 = z - y1 y3.
 */
static int res(void *user, double t, const double *y, const double *yp, double *F)
{
    (void)user;
    F[0] = yp[0] - y[1];
    F[1] = yp[1] + y[0];
    F[2] = yp[2] - 50 * (sin(t) - y[2]);
    F[3] = y[3] - y[0] * y[2];
    return 0;
}

static void exact(double t, double *y)
{
    y[0] = cos(t);
    y[1] = -sin(t);
    y[2] = (2500 * sin(t) - 50 * cos(t) + 50 * exp(-50 * t)) / 2501;
    y[3] = y[0] * y[2];
}

#define NT 101
#define TEND 10.0

/* The run at tol with the companion (factor K) over t = 0, 0.1, ..., 10; true largest error
 * per column into truth[4]. The companion, or NULL. */
static rn_errest *run_with_estimate(double tol, double K, const volatile sig_atomic_t *stop,
                                    double *truth, int *rc_out)
{
    dae_problem p = {0};
    p.n = 4;
    p.res = res;
    dae_options o;
    dae_options_default(&o);
    o.rtol = o.atol = tol;
    o.has_t_stop = 1;
    o.t_stop = TEND;
    double y0[4], yp0[4] = {0, -1, 0, 0}, y[4], yp[4], ex[4], t = 0; /* y' at t = 0 */
    exact(0, y0);
    bg_error err = {0};
    dae_solver *s = dae_create(&p, &o, &err);
    rn_errest_spec sp = {&p, &o, K, 0, y0, yp0, 1, 4, NULL, NULL, stop};
    rn_errest *e = rn_errest_create(&sp, &err);
    int rc = s && e ? dae_init(s, 0, y0, yp0) : -1;
    if (rc == 0) rc = dae_consistent_init(s);
    for (int j = 0; j < 4; j++)
        truth[j] = 0;
    for (int k = 0; k < NT && rc >= 0; k++) {
        double tk = TEND * k / (NT - 1);
        rc = k ? dae_solve_to(s, tk, &t, y, yp) : dae_dense(s, 0, y, yp);
        if (rc < 0) break;
        exact(tk, ex);
        for (int j = 0; j < 4; j++)
            truth[j] = fmax(truth[j], fabs(y[j] - ex[j]));
        rc = rn_errest_add(e, tk, y);
        if (rc == RN_ERREST_STOPPED) break;
        if (rc < 0) rc = 0; /* the companion's failure: kept in e */
    }
    *rc_out = rc;
    dae_free(&s);
    return e;
}

static void test_analytic(void)
{
    static const char *names[4] = {"y1 = cos t", "y2 = -sin t", "y3 (lag)", "z = y1 y3"};
    for (int q = 0; q < 3; q++) {
        double tol = q == 0 ? 1e-4 : (q == 1 ? 1e-6 : 1e-8), truth[4];
        int rc;
        rn_errest *e = run_with_estimate(tol, 0, NULL, truth, &rc);
        double rtol2, atol2, K;
        rn_errest_tolerances(e, &rtol2, &atol2, &K);
        tap_ok(e && rc >= 0 && rn_errest_status(e) == BG_OK && rn_errest_count(e) == NT &&
                   rn_errest_last(e) == TEND && K == 100 && rtol2 == tol / 100 &&
                   atol2 == tol / 100,
               "tol %g: the companion at rtol = atol = %g covered all %d times to t = %g", tol,
               rtol2, (int)rn_errest_count(e), rn_errest_last(e));
        for (int j = 0; j < 4 && e; j++) {
            const rn_errest_col *c = rn_errest_column(e, j);
            double ratio = c->max_err / truth[j];
            tap_ok(ratio >= 0.1 && ratio <= 10,
                   "tol %g, %s: estimate %.3g of the true largest error %.3g (ratio %.3g, within "
                   "10x)",
                   tol, names[j], c->max_err, truth[j], ratio);
        }
        if (e) {
            /* the largest |y1|, |y2| of the run: 1 (cos t, sin t) within the run's errors and,
             * for y2, the output times' distance from pi/2 + k pi */
            const rn_errest_col *c0 = rn_errest_column(e, 0), *c1 = rn_errest_column(e, 1);
            tap_ok(fabs(c0->max_abs - 1) < 10 * truth[0] + 1e-12 &&
                       fabs(c1->max_abs - 1) < 1e-4 + 10 * truth[1] && c0->t_at >= 0 &&
                       c0->t_at <= TEND && !rn_errest_column(e, 4) && !rn_errest_column(e, -1),
                   "tol %g: the columns' largest values (|y1| %.6g, |y2| %.6g) and times", tol,
                   c0->max_abs, c1->max_abs);
        }
        rn_errest_free(&e);
    }
}

static void test_failures(void)
{
    double truth[4];
    int rc;
    /* rtol 1e-6 / 1e12: tolerances below round-off, the companion fails, the run goes on */
    rn_errest *e = run_with_estimate(1e-6, 1e12, NULL, truth, &rc);
    tap_ok(e && rc >= 0 && rn_errest_status(e) < 0 && rn_errest_count(e) == 1 &&
               rn_errest_last(e) == 0 && strstr(rn_errest_message(e), "round-off") &&
               rn_errest_add(e, 11, truth) == rn_errest_status(e),
           "a companion at tolerances below round-off: failed at its first step (%s: %.160s), "
           "compared at t = 0 only, the first run unharmed",
           bg_status_name(rn_errest_status(e)), rn_errest_message(e));
    rn_errest_free(&e);
    /* a stop flag already set: the companion does not step */
    volatile sig_atomic_t stop = 1;
    e = run_with_estimate(1e-6, 0, &stop, truth, &rc);
    tap_ok(e && rc == RN_ERREST_STOPPED && rn_errest_count(e) == 1 && rn_errest_last(e) == 0 &&
               rn_errest_status(e) == BG_OK,
           "a stop flag: the time 0 compared, then RN_ERREST_STOPPED before the first step");
    rn_errest_free(&e);
    /* bad arguments */
    dae_problem p = {0};
    p.n = 4;
    p.res = res;
    dae_options o;
    dae_options_default(&o);
    double y0[4] = {1, 0, 0, 0};
    bg_error err = {0};
    rn_errest_spec sp = {&p, &o, 0.5, 0, y0, NULL, 0, 4, NULL, NULL, NULL};
    e = rn_errest_create(&sp, &err);
    tap_ok(!e && err.status == BG_ERR_ARGUMENT && strstr(err.message, "(1, 1e+12]"),
           "a factor of 0.5 is refused (%s)", err.message);
    sp.factor = 0;
    sp.p = NULL;
    e = rn_errest_create(&sp, &err);
    tap_ok(!e && err.status == BG_ERR_ARGUMENT && rn_errest_add(NULL, 0, y0) == BG_ERR_ARGUMENT,
           "no problem is refused, a NULL estimate too");
}

/* ------------------------------------------------------------------ the program ---- */

/* results.csv of dir as numbers: rows x CRANE_NOUT into v (at most maxrows); the count. */
static long read_results(const char *dir, double *v, long maxrows)
{
    char p[8192], line[1 << 14];
    snprintf(p, sizeof p, "%s/results.csv", dir);
    FILE *f = fopen(p, "r");
    if (!f || !fgets(line, sizeof line, f)) {
        if (f) fclose(f);
        return -1;
    }
    long n = 0;
    while (n < maxrows && fgets(line, sizeof line, f)) {
        char *s = line;
        for (int j = 0; j < CRANE_NOUT; j++) {
            v[n * CRANE_NOUT + j] = strtod(s, &s);
            if (*s == ',') s++;
        }
        n++;
    }
    fclose(f);
    return n;
}

/* error_estimate.csv: per column (1 .. CRANE_NOUT-1) its fields; the lines read. */
typedef struct est_line {
    char name[64], state[32];
    double err, t_at, max_abs, rel, covered;
} est_line;

static int read_estimate(const char *dir, est_line *L)
{
    char p[8192], line[4096];
    snprintf(p, sizeof p, "%s/error_estimate.csv", dir);
    FILE *f = fopen(p, "r");
    if (!f) return -1;
    int n = 0;
    if (!fgets(line, sizeof line, f) ||
        strcmp(line, "column,max_abs_error,t_at_max [s],max_abs_value,max_rel_error,t_covered "
                     "[s],estimate\n")) {
        fclose(f);
        return -2;
    }
    while (n + 1 < CRANE_NOUT && fgets(line, sizeof line, f)) {
        est_line *e = &L[n + 1];
        char *fld[8] = {0}, *s = line;
        int k = 0;
        line[strcspn(line, "\n")] = '\0';
        while (k < 8) {
            fld[k++] = s;
            char *c = strchr(s, ',');
            if (!c) break;
            *c = '\0';
            s = c + 1;
        }
        if (k != 7) break;
        snprintf(e->name, sizeof e->name, "%.63s", fld[0]);
        snprintf(e->state, sizeof e->state, "%.31s", fld[6]);
        double *num[5] = {&e->err, &e->t_at, &e->max_abs, &e->rel, &e->covered};
        for (int i = 0; i < 5; i++)
            *num[i] = *fld[i + 1] ? strtod(fld[i + 1], NULL) : NAN;
        n++;
    }
    fclose(f);
    return n;
}

static void test_program(void)
{
    char a[4200], b[4200], scene[4200];
    snprintf(scene, sizeof scene, "%s/paper.ini", scenes);
    snprintf(a, sizeof a, "%s/estimate", tmp);
    snprintf(b, sizeof b, "%s/tight", tmp);
    result r, r2;
    run(NULL,
        (const char *[]){scene, "--out", a, "--t-end", "0.1", "--no-plots", "--error-estimate",
                         NULL},
        "est", 300, &r);
    run(NULL,
        (const char *[]){scene, "--out", b, "--t-end", "0.1", "--no-plots", "--quiet", "--rtol",
                         "1e-8", "--atol", "1e-8", NULL},
        "tight", 300, &r2);
    tap_ok(r.exited && r.code == 0 && r2.exited && r2.code == 0 &&
               first_line_is(a, "status.txt", "status: completed") &&
               file_contains(a, "status.txt",
                             "error_estimate: available over 101 rows up to t = "
                             "0.1 s") &&
               strstr(r.out, "error estimate (available, against rtol 1e-08)"),
           "--error-estimate: completed, status.txt and the summary say the estimate is available "
           "(exit %d, %d)",
           r.code, r2.code);
    tap_ok(file_contains(a, "solver_stats.txt",
                         "error_estimate: a second run at rtol / 100 and atol / 100 (rtol 1e-08, "
                         "atol 1e-08)") &&
               file_contains(a, "solver_stats.txt", "error_estimate_run: steps="),
           "solver_stats.txt names the second run's tolerances and its statistics");
    static double va[200 * CRANE_NOUT], vb[200 * CRANE_NOUT];
    est_line L[CRANE_NOUT];
    long na = read_results(a, va, 200), nb = read_results(b, vb, 200);
    int nl = read_estimate(a, L);
    tap_ok(na == 101 && nb == 101 && nl == CRANE_NOUT - 1,
           "101 rows in each run, %d lines of error_estimate.csv", nl);
    /* the estimate is max |run(1e-6) - run(1e-8)| per column: two separate runs say the same,
     * to the 12 digits of results.csv and the 6 of error_estimate.csv */
    int agree = nl == CRANE_NOUT - 1 && na == 101 && nb == 101, worst = 0;
    double worst_d = 0;
    for (int j = 1; j < CRANE_NOUT && agree; j++) {
        double m = 0, big = 0;
        for (long k = 0; k < na; k++) {
            m = fmax(m, fabs(va[k * CRANE_NOUT + j] - vb[k * CRANE_NOUT + j]));
            big = fmax(big, fabs(va[k * CRANE_NOUT + j]));
        }
        double d = fabs(m - L[j].err), allow = 1e-11 * big + 6e-6 * L[j].err + 1e-15;
        if (!(d <= allow) || strcmp(L[j].state, "available") || L[j].covered != 0.1 ||
            fabs(L[j].max_abs - big) > 1e-5 * big || strcmp(L[j].name, crane_output_names[j])) {
            agree = 0;
            worst = j;
            worst_d = d;
        }
    }
    tap_ok(agree,
           "error_estimate.csv: each column's max_abs_error is the largest difference of the runs "
           "at rtol 1e-6 and 1e-8 (column %d off by %.3g)",
           worst, worst_d);

    /* the companion cannot start: the run completes, the estimate is unavailable */
    snprintf(a, sizeof a, "%s/unavailable", tmp);
    run(NULL,
        (const char *[]){scene, "--out", a, "--t-end", "0.05", "--no-plots", "--quiet",
                         "--error-estimate", "1e12", NULL},
        "unavail", 300, &r);
    char why[256];
    double tl;
    long rows = check_csv(a, 0, &tl, why, sizeof why);
    nl = read_estimate(a, L);
    int marked = nl == CRANE_NOUT - 1;
    for (int j = 1; j < CRANE_NOUT && marked; j++)
        marked = !strcmp(L[j].state, "unavailable") && isnan(L[j].err) && isnan(L[j].rel);
    tap_ok(r.exited && r.code == 0 && first_line_is(a, "status.txt", "status: completed") &&
               file_contains(a, "status.txt", "error_estimate: unavailable: ") &&
               file_contains(a, "solver_stats.txt", "error_estimate: unavailable: ") &&
               strstr(r.err, "the error estimate is unavailable") && rows == 51 && tl == 0.05,
           "a second run that cannot start: the run completes with its 51 rows (%s), status.txt, "
           "solver_stats.txt and stderr say the estimate is unavailable (exit %d: %.200s)",
           why, r.code, r.err);
    tap_ok(marked, "error_estimate.csv marks every column unavailable, without numbers");

    /* interrupted: whole rows, status interrupted, exit 130, the estimate over the rows */
    snprintf(a, sizeof a, "%s/interrupted", tmp);
    char csv[4300];
    snprintf(csv, sizeof csv, "%s/results.csv", a);
    pid_t pid = start(
        NULL,
        (const char *[]){scene, "--out", a, "--no-plots", "--quiet", "--error-estimate", NULL},
        "intr");
    struct stat st;
    for (int i = 0; i < 12000; i++) {
        if (stat(csv, &st) == 0 && st.st_size > 20000) break;
        if (waitpid(pid, NULL, WNOHANG) == pid) break;
        sleep_ms(10);
    }
    kill(pid, SIGINT);
    finish(pid, 120, "intr", &r);
    rows = check_csv(a, 0, &tl, why, sizeof why);
    nl = read_estimate(a, L);
    int consistent = nl == CRANE_NOUT - 1;
    for (int j = 1; j < CRANE_NOUT && consistent; j++)
        consistent = (!strcmp(L[j].state, "available") && L[j].covered == tl) ||
                     (!strcmp(L[j].state, "partial") && L[j].covered < tl);
    tap_ok(r.exited && r.code == 128 + SIGINT &&
               first_line_is(a, "status.txt", "status: interrupted"),
           "SIGINT with --error-estimate: exit %d, status.txt interrupted (exit %d)", 128 + SIGINT,
           r.code);
    tap_ok(rows > 1 && tl < 20,
           "results.csv holds whole rows only, each of %d numbers (%ld rows to t = %g: %s)",
           CRANE_NOUT, rows, tl, why);
    tap_ok(consistent && file_contains(a, "status.txt", "error_estimate: "),
           "error_estimate.csv covers the rows written (t_covered %g, last row %g, %s)",
           nl > 1 ? L[1].covered : NAN, tl, nl > 1 ? L[1].state : "-");

    /* bad command lines */
    run(NULL, (const char *[]){scene, "--out", a, "--error-estimate", "1", NULL}, "bad1", 60, &r);
    run(NULL, (const char *[]){scene, "--out", a, "--static", "--error-estimate", NULL}, "bad2", 60,
        &r2);
    tap_ok(r.exited && r.code == 2 && strstr(r.err, "--error-estimate needs a factor K") &&
               r2.exited && r2.code == 2 && strstr(r2.err, "not to --static"),
           "--error-estimate 1 and --static --error-estimate are refused with exit 2 (%.100s | "
           "%.100s)",
           r.err, r2.err);
}

int main(int argc, char **argv)
{
    test_analytic();
    test_failures();
    if (argc >= 3) {
        if (spawn_setup(argc, argv, "rn_errest") != 0) return 1;
        test_program();
    } else {
        tap_diag("no crane program given: its tests skipped");
    }
    int rc = tap_done();
    if (rc == 0 && argc >= 3) {
        char cmd[4200];
        snprintf(cmd, sizeof cmd, "rm -rf '%s'", tmp);
        if (system(cmd) != 0) tap_diag("could not remove %s", tmp);
    }
    return rc;
}
