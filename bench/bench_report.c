/* The bench's report writer (bench_report.h): the work-precision CSV and figures, steps against
 * tolerance and report.md, from the rows of the work-precision series (bench/bench.c). */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/utsname.h>
#include <sys/wait.h>
#include <unistd.h>

#include "bench_cli.h" /* BENCH_MAXRTOL: the tolerances of a series */
#include "bench_report.h"
#include "pu_gnuplot.h"

#include "bench_version.h" /* BENCH_COMMIT, generated at build time */
#ifndef BENCH_BUILD_FLAGS
#define BENCH_BUILD_FLAGS "unknown"
#endif

/* scd is +inf where the error is exactly zero: count it as the 16 digits of double precision. */
static double capped(double scd)
{
    return scd > 16 ? 16 : scd;
}

static int row_ok(const bench_row *r)
{
    return r->r.status >= 0 && !isnan(r->sc.scd);
}

/* log10 of the median CPU time at accuracy target on the curve of (scd, cpu) points of one
 * solver: linear interpolation in (scd, log cpu) between neighbours on the curve (runs at
 * consecutive tolerances, failed runs left out) that bracket the target, the cheapest such pair.
 * Only neighbours: a pair of runs far apart in tolerance would stand for runs in between that
 * were measured and cost more (the crane at rtol 1e-4 is chaotic: one solver's run there can be
 * lucky, three times cheaper and more accurate than its run at 1e-5). When every run of the
 * solver is more accurate than the target (its loosest tolerance already passes it), the cheapest
 * run is taken and *bound set (an upper bound of the cost); NAN if the curve does not reach the
 * target. */
/* A and B (same case and solver) are runs at consecutive tolerances of the curve: no successful
 * run of theirs lies strictly between them in rtol. */
static int neighbours(const bench_row *rows, int nrows, const bench_row *A, const bench_row *B)
{
    double lo = fmin(A->rtol, B->rtol), hi = fmax(A->rtol, B->rtol);
    for (int c = 0; c < nrows; c++) {
        const bench_row *C = &rows[c];
        if (C->ci == A->ci && C->sd == A->sd && row_ok(C) && C->rtol > lo && C->rtol < hi) return 0;
    }
    return 1;
}

static double cpu_at_b(const bench_row *rows, int nrows, int ci, const char *solver, double target,
                       int *bound)
{
    double best = NAN, above = NAN;
    int below = 0;
    *bound = 0;
    for (int a = 0; a < nrows; a++) {
        const bench_row *A = &rows[a];
        double sa = capped(A->sc.scd);
        if (A->ci != ci || strcmp(A->sd->name, solver) || !row_ok(A)) continue;
        if (sa < target) below = 1;
        if (sa >= target && (isnan(above) || log10(A->cpu_med) < above)) above = log10(A->cpu_med);
        for (int b = 0; b < nrows; b++) {
            const bench_row *B = &rows[b];
            double sb = capped(B->sc.scd);
            if (B->ci != ci || strcmp(B->sd->name, solver) || !row_ok(B) ||
                !(sa <= target && sb >= target) || sa == sb || !neighbours(rows, nrows, A, B))
                continue;
            double w = (target - sa) / (sb - sa);
            double lc = (1 - w) * log10(A->cpu_med) + w * log10(B->cpu_med);
            if (isnan(best) || lc < best) best = lc;
        }
    }
    if (isnan(best) && !below && !isnan(above)) {
        best = above;
        *bound = 1;
    }
    return best;
}

static double cpu_at(const bench_row *rows, int nrows, int ci, const char *solver, double target)
{
    int b;
    return cpu_at_b(rows, nrows, ci, solver, target, &b);
}

/* Ratio bgdae-klu / ida-klu at scd target, NAN if either curve does not reach it; *bound set
 * when either side is the cheapest run above the target rather than an interpolation. */
static double ratio_at_b(const bench_row *rows, int n, int ci, double target, int *bound)
{
    int ba, bb;
    double a = cpu_at_b(rows, n, ci, "bgdae-klu", target, &ba),
           b = cpu_at_b(rows, n, ci, "ida-klu", target, &bb);
    *bound = ba || bb;
    return isnan(a) || isnan(b) ? NAN : pow(10, a - b);
}

/* A bench_row of the targets table for a scaling slope (limit 1.1). */
static void slope_row(FILE *f, const char *what, double slope, const char *ok, const char *bad)
{
    fprintf(f, "| crane: %s | %.3f | %s |\n", what, slope,
            isnan(slope)   ? "not measured"
            : slope <= 1.1 ? ok
                           : bad);
}

static double frac_other(const run_out *r)
{
    return r->wall > 0 ? (r->wall - r->t_res - r->t_jac - r->t_lin) / r->wall : NAN;
}

static void write_csv(FILE *f, const bench_row *rows, int n, bench_case **cases)
{
    fprintf(f, "problem,solver,rtol,atol,status,scd,mescd,scd_index2,mescd_index2,cpu_s,"
               "cpu_median_s,steps,rejected,newton,conv_fail,res_evals,jac_evals,factorizations,"
               "solves,max_order,profiled_wall_s,res_s,jac_s,linalg_s,other_fraction,message\n");
    for (int i = 0; i < n; i++) {
        const bench_row *r = &rows[i];
        fprintf(f,
                "%s,%s,%g,%g,%d,%.3f,%.3f,%.3f,%.3f,%.6g,%.6g,%ld,%ld,%ld,%ld,%ld,%ld,%ld,%ld,%d,"
                "%.6g,%.6g,%.6g,%.6g,%.4f,\"%s\"\n",
                cases[r->ci]->name, r->sd->name, r->rtol, r->atol, r->r.status, r->sc.scd,
                r->sc.mescd, r->sc.scd_i2, r->sc.mescd_i2, r->cpu_min, r->cpu_med, r->r.steps,
                r->r.rejected, r->r.newton, r->r.conv_fail, r->r.res, r->r.jac, r->r.fact,
                r->r.solves, r->r.max_order, r->r.wall, r->r.t_res, r->r.t_jac, r->r.t_lin,
                frac_other(&r->r), r->r.status < 0 ? r->r.msg : "");
    }
}

/* Runs gnuplot (exe) in folder dir on the commands of script (pu_gnuplot.h: no shell
 * between, its output discarded). 0 if it ended with exit status 0; else -1 and msg says how it
 * ended, with gnuplot's last message. */
static int run_gnuplot(const char *exe, const char *dir, const char *script, char *msg, size_t msz)
{
    char last[512];
    pu_gnuplot_job job = {exe, dir, NULL, script, NULL, NULL};
    int st = pu_gnuplot_run(&job, last, sizeof last);
    if (st == -1) {
        snprintf(msg, msz, "%s", last);
        return -1;
    }
    if (WIFEXITED(st) && WEXITSTATUS(st) == 0) return 0;
    snprintf(msg, msz, "gnuplot %s %d%s%.300s%s",
             WIFEXITED(st) ? "exited with status" : "ended by signal",
             WIFEXITED(st) ? WEXITSTATUS(st) : WTERMSIG(st), *last ? " (" : "", last,
             *last ? ")" : "");
    return -1;
}

/* wp_<name>.dat (each solver's runs on case ci), then wp_<name>.png drawn from it by gnuplot
 * (its path; NULL when it is not installed: no figure). Each checked: a failure is said and
 * counted (bench_util.h), a figure that gnuplot did not write whole is removed. */
static void plot(const char *dir, const char *gnuplot, int ci, const char *name,
                 const bench_row *rows, int n, const char **sol, int ns)
{
    char dat[BENCH_NAME_MAX + 1], png[BENCH_NAME_MAX + 1];
    snprintf(dat, sizeof dat, "wp_%s.dat", name); /* a problem's name: under 64 characters */
    snprintf(png, sizeof png, "wp_%s.png", name);
    bench_file bf;
    if (bench_file_open(&bf, dir, dat) != 0) return;
    for (int s = 0; s < ns; s++) {
        fprintf(bf.f, "# %s\n", sol[s]);
        for (int i = 0; i < n; i++)
            if (rows[i].ci == ci && !strcmp(rows[i].sd->name, sol[s]) && row_ok(&rows[i]))
                fprintf(bf.f, "%.6g %.4f %ld\n", rows[i].cpu_med, capped(rows[i].sc.scd),
                        rows[i].r.steps);
        fprintf(bf.f, "\n\n");
    }
    if (bench_file_close(&bf) != 0 || !gnuplot) return;
    /* the commands, with the files' names only: gnuplot runs in the output folder */
    char *script = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&script, &len);
    if (!f) {
        bench_file_failed(dir, png, strerror(errno));
        return;
    }
    fprintf(f,
            "set terminal png size 1000,420; set output '%s'; "
            "set multiplot layout 1,2 title '%s'; set logscale x; set grid; "
            "set key bottom right; set xlabel 'CPU time [s] (median)'; "
            "set ylabel 'scd'; plot ",
            png, name);
    for (int s = 0; s < ns; s++)
        fprintf(f, "'%s' index %d using 1:2 with linespoints title '%s'%s", dat, s, sol[s],
                s + 1 < ns ? ", " : "; ");
    fprintf(f, "set xlabel 'steps'; plot ");
    for (int s = 0; s < ns; s++)
        fprintf(f, "'%s' index %d using 3:2 with linespoints title '%s'%s", dat, s, sol[s],
                s + 1 < ns ? ", " : "; ");
    fprintf(f, "unset multiplot; set output");
    if (fclose(f) != 0) {
        free(script);
        bench_file_failed(dir, png, strerror(ENOMEM));
        return;
    }
    char msg[512], path[BENCH_PATH_SIZE];
    int rc = run_gnuplot(gnuplot, dir, script, msg, sizeof msg);
    free(script);
    snprintf(path, sizeof path, "%s/%s", dir, png); /* bench_cli has checked that it fits */
    if (rc == 0 && !pu_png_whole(path)) {
        snprintf(msg, sizeof msg, "gnuplot ended without writing it whole");
        rc = -1;
    }
    if (rc != 0) {
        remove(path);
        bench_file_failed(dir, png, msg);
    }
}

/* The ratio at scd target as text: "-" if not measurable, "0.42*" when a side is the cheapest
 * run above the target. Returns the ratio. */
static double fmt_ratio(char *buf, size_t sz, const bench_row *rows, int n, int ci, double target)
{
    int bound;
    double r = ratio_at_b(rows, n, ci, target, &bound);
    if (isnan(r))
        snprintf(buf, sz, "-");
    else
        snprintf(buf, sz, "%.2f%s", r, bound ? "*" : "");
    return r;
}

/* The rows of solver name on case ci nearest to scd target (below and above), for the
 * explanations of missed targets. */
static const bench_row *nearest(const bench_row *rows, int n, int ci, const char *name,
                                double target)
{
    const bench_row *best = NULL;
    for (int i = 0; i < n; i++) {
        const bench_row *r = &rows[i];
        if (r->ci != ci || strcmp(r->sd->name, name) || !row_ok(r)) continue;
        if (!best || fabs(capped(r->sc.scd) - target) < fabs(capped(best->sc.scd) - target))
            best = r;
    }
    return best;
}

static void describe_row(FILE *f, const bench_row *r)
{
    if (!r) {
        fprintf(f, "no successful run");
        return;
    }
    double w = r->r.wall > 0 ? r->r.wall : 1;
    fprintf(f,
            "%s at rtol %g (scd %.2f): %.3g s, %ld steps, %ld Newton iterations, %ld Jacobians, "
            "%ld factorizations, %ld residuals; residual %.0f %%, Jacobian %.0f %%, linear algebra "
            "%.0f %%, the rest %.0f %%",
            r->sd->name, r->rtol, r->sc.scd, r->cpu_med, r->r.steps, r->r.newton, r->r.jac,
            r->r.fact, r->r.res, 100 * r->r.t_res / w, 100 * r->r.t_jac / w, 100 * r->r.t_lin / w,
            100 * frac_other(&r->r));
}

void bench_load_average(char *buf, size_t sz)
{
    snprintf(buf, sz, "unknown");
    FILE *f = fopen("/proc/loadavg", "r");
    if (!f) return;
    if (!fgets(buf, (int)sz, f)) snprintf(buf, sz, "unknown");
    buf[strcspn(buf, "\n")] = '\0';
    fclose(f);
}

static void write_report_head(FILE *f, const bench_row *rows, int n, bench_case **cases, int nc,
                              const char **sol, int ns, double wall, int K,
                              const bench_report_extras *ex)
{
    struct utsname u;
    uname(&u);
    fprintf(f, "# Benchmark report\n\n");
    fprintf(f, "- machine: %s %s %s, %ld cores online (shared: timings are noisy)\n", u.sysname,
            u.release, u.machine, sysconf(_SC_NPROCESSORS_ONLN));
    fprintf(f, "- load average (/proc/loadavg) at the start: %s; at the end: %s\n", ex->load_start,
            ex->load_end);
    fprintf(f, "- commit: %s\n- build: %s\n", BENCH_COMMIT, BENCH_BUILD_FLAGS);
    fprintf(f,
            "- timing: CPU time of the integration alone, median of %d timed runs after a "
            "profiled warm-up (the crane: the profiled run is the first timed one, a run over "
            "5 s is not repeated), a run shorter "
            "than 10 ms timed as the mean of a batch of about 20 ms; minimum beside it in "
            "work_precision.csv\n",
            K);
    fprintf(f,
            "- accuracy: scd over the scored components, index-2 components apart (scd2); "
            "atol = factor * rtol per problem\n- wall time of the work-precision runs: %.1f "
            "s\n\n",
            wall);

    /* targets */
    fprintf(f, "## Targets\n\n| target | measured | verdict |\n|---|---|---|\n");
    static const char *const tprob[] = {"pendulum2", "crank", "pump", "crane"};
    for (int q = 0; q < 4; q++) {
        int ci = -1;
        for (int c = 0; c < nc; c++)
            if (!strcmp(cases[c]->name, tprob[q])) ci = c;
        if (ci < 0) continue;
        for (int target = 4; target <= 6; target += 2) {
            char b[32];
            double r = fmt_ratio(b, sizeof b, rows, n, ci, target);
            fprintf(f, "| %s: CPU bgdae-klu / ida-klu at scd %d <= 0.5 | %s | %s |\n", tprob[q],
                    target, b,
                    isnan(r)   ? "not measurable (a curve does not reach this accuracy)"
                    : r <= 0.5 ? "met"
                               : "MISSED");
        }
    }
    for (int i = 0; i < ex->nrt; i++) {
        const bench_rt_scene *sc = &ex->rts[i];
        const bench_rt_result *r = &ex->rt[i];
        if (r->runs == 0) continue;
        fprintf(f,
                "| crane %s, %g s: simulated / CPU time of the integration >= %g (median of %d) | "
                "%.2f | %s |\n",
                sc->label, sc->s.t_end, sc->target, r->runs, r->rt_factor_cpu,
                r->rt_factor_cpu >= sc->target ? "met" : "MISSED");
        if (sc->max_steps > 0)
            fprintf(f, "| crane %s: steps <= %ld | %ld | %s |\n", sc->label, sc->max_steps,
                    r->steps, r->steps <= sc->max_steps ? "met" : "MISSED");
        fprintf(f, "| crane %s: peak memory < 64 MB | %.1f MB | %s |\n", sc->label, r->peak_mb,
                r->peak_mb < 64 ? "met" : "MISSED");
        fprintf(f,
                "| crane %s: the integrator's bookkeeping (outside residual, Jacobian, linear "
                "algebra and the output rows' crane_outputs) < 10 %% | "
                "%.1f %% | %s |\n",
                sc->label, 100 * r->bookkeeping, r->bookkeeping < 0.1 ? "met" : "MISSED");
    }
    if (ex->mesh.n >= 2) {
        fprintf(f,
                "| crane mesh series (%d .. %d elements): CPU per step against elements, log-log "
                "slope <= 1.1 | %.3f | %s |\n",
                ex->mesh.elements[0], ex->mesh.elements[ex->mesh.n - 1], ex->mesh.slope_el,
                ex->mesh.slope_el <= 1.1 ? "met" : "MISSED");
        fprintf(f,
                "| crane mesh series: steps independent of the mesh within 30 %% (largest / "
                "smallest <= 1.3) | %.2f | %s |\n",
                ex->mesh.steps_spread, ex->mesh.steps_spread <= 1.3 ? "met" : "MISSED");
    }
    if (ex->have_scaling) {
        /* the issue states the target against the boom elements; against the unknowns (which
         * include the platform's, the hydraulics' and the load's, a fixed part) it is stricter
         * and reported beside it */
        slope_row(f, "time per step against boom elements, log-log slope <= 1.1", ex->slope_el,
                  "met", "MISSED");
        slope_row(f, "the same against the unknowns (the fixed non-boom unknowns make it stricter)",
                  ex->slope_n, "within 1.1", "above 1.1");
    }
    fprintf(f, "\n");
    /* where the time goes where a ratio target is missed */
    int said = 0;
    for (int q = 0; q < 4; q++) {
        int ci = -1;
        for (int c = 0; c < nc; c++)
            if (!strcmp(cases[c]->name, tprob[q])) ci = c;
        if (ci < 0) continue;
        for (int target = 4; target <= 6; target += 2) {
            int bound;
            double r = ratio_at_b(rows, n, ci, target, &bound);
            if (!isnan(r) && r <= 0.5) continue;
            if (!said)
                fprintf(f, "Where the time goes where a ratio target is missed (the runs "
                           "nearest to the accuracy, profiled):\n\n");
            said = 1;
            const bench_row *a = nearest(rows, n, ci, "bgdae-klu", target),
                            *b = nearest(rows, n, ci, "ida-klu", target);
            fprintf(f, "- %s, scd %d: ", tprob[q], target);
            describe_row(f, a);
            fprintf(f, "; against ");
            describe_row(f, b);
            if (a && b && b->r.steps > 0 && a->r.steps > 0 && b->r.fact > 0 && b->r.newton > 0)
                fprintf(f,
                        ". Ours / IDA: steps %.2f, Newton iterations %.2f, factorizations %.2f, "
                        "CPU per step %.2f",
                        (double)a->r.steps / (double)b->r.steps,
                        (double)a->r.newton / (double)b->r.newton,
                        (double)a->r.fact / (double)b->r.fact,
                        (a->cpu_med / (double)a->r.steps) / (b->cpu_med / (double)b->r.steps));
            fprintf(f, ".\n");
        }
    }
    if (said) fprintf(f, "\n");

    /* ratio table */
    fprintf(f, "## CPU time of bgdae-klu / ida-klu at equal accuracy\n\n"
               "Interpolated in (scd, log CPU) between runs at neighbouring tolerances of each "
               "solver's curve that bracket the accuracy (the cheapest such pair); '-' where a "
               "curve does not "
               "reach the accuracy; '*' where a solver's loosest run is already more accurate "
               "(its cheapest run stands in). Below 1: ours is faster.\n\n"
               "| problem | n | scd 4 | scd 6 | scd 8 | fastest at scd 4 | fastest at scd 6 | "
               "fastest at scd 8 |\n|---|---|---|---|---|---|---|---|\n");
    for (int c = 0; c < nc; c++) {
        fprintf(f, "| %s | %d |", cases[c]->name, cases[c]->n);
        for (int target = 4; target <= 8; target += 2) {
            char b[32];
            fmt_ratio(b, sizeof b, rows, n, c, target);
            fprintf(f, " %s |", b);
        }
        for (int target = 4; target <= 8; target += 2) {
            double bestv = NAN;
            const char *win = "-";
            for (int s = 0; s < ns; s++) {
                double lc = cpu_at(rows, n, c, sol[s], target);
                if (!isnan(lc) && (isnan(bestv) || lc < bestv)) {
                    bestv = lc;
                    win = sol[s];
                }
            }
            fprintf(f, " %s |", win);
        }
        fprintf(f, "\n");
    }
    fprintf(f, "\n");
    /* the two methods side by side */
    fprintf(f, "## CPU time of bgdae-mebdf / ida-klu and of the better of bgdae-klu and "
               "bgdae-mebdf / ida-klu at equal accuracy\n\n"
               "As above (interpolated, the cheapest bracketing pair); bgdae-mebdf is Cash's "
               "modified extended BDF in our code (options.method = DAE_MEBDF), on the same "
               "linear algebra and the same accounting. '-': a curve does not reach the "
               "accuracy.\n\n"
               "| problem | MEBDF scd 4 | scd 6 | scd 8 | better scd 4 | scd 6 | scd 8 |\n"
               "|---|---|---|---|---|---|---|\n");
    for (int c = 0; c < nc; c++) {
        fprintf(f, "| %s |", cases[c]->name);
        for (int q = 0; q < 2; q++)
            for (int target = 4; target <= 8; target += 2) {
                double lm = cpu_at(rows, n, c, "bgdae-mebdf", target),
                       lb = cpu_at(rows, n, c, "bgdae-klu", target),
                       li = cpu_at(rows, n, c, "ida-klu", target);
                double l = q == 0 ? lm : isnan(lb) ? lm : isnan(lm) ? lb : fmin(lb, lm);
                if (isnan(l) || isnan(li))
                    fprintf(f, " - |");
                else
                    fprintf(f, " %.2f |", pow(10, l - li));
            }
        fprintf(f, "\n");
    }
    fprintf(f, "\n");
}

static void write_report_problems(FILE *f, const bench_row *rows, int n, bench_case **cases, int nc,
                                  const char **sol, int ns)
{
    for (int c = 0; c < nc; c++) {
        const bench_case *bc = cases[c];
        fprintf(f, "## %s (n = %d): %s\n\nReference: %s.\n\n", bc->name, bc->n, bc->title,
                bc->ref_source);
        fprintf(f, "| solver | rtol | status | scd | mescd | scd2 | CPU s (median) | steps | "
                   "rejected | Newton | Jacobians | factorizations | res/jac/lin/rest %% |\n"
                   "|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
        for (int i = 0; i < n; i++) {
            const bench_row *r = &rows[i];
            if (r->ci != c) continue;
            double w = r->r.wall > 0 ? r->r.wall : 1;
            fprintf(f,
                    "| %s | %g | %s | %.2f | %.2f | %.2f | %.4g | %ld | %ld | %ld | %ld | %ld | "
                    "%.0f/%.0f/%.0f/%.0f |\n",
                    r->sd->name, r->rtol, r->r.status < 0 ? "FAIL" : "ok", r->sc.scd, r->sc.mescd,
                    r->sc.scd_i2, r->cpu_med, r->r.steps, r->r.rejected, r->r.newton, r->r.jac,
                    r->r.fact, 100 * r->r.t_res / w, 100 * r->r.t_jac / w, 100 * r->r.t_lin / w,
                    100 * frac_other(&r->r));
        }
        fprintf(f,
                "\nCPU time at equal accuracy (median, interpolated on the scd axis):\n\n| scd |");
        for (int s = 0; s < ns; s++)
            fprintf(f, " %s |", sol[s]);
        fprintf(f, " winner | bgdae-klu / ida-klu |\n|---|");
        for (int s = 0; s <= ns + 1; s++)
            fprintf(f, "---|");
        fprintf(f, "\n");
        for (int target = 4; target <= 8; target += 2) {
            fprintf(f, "| %d |", target);
            double bestv = NAN;
            const char *win = "-";
            for (int s = 0; s < ns; s++) {
                double lc = cpu_at(rows, n, c, sol[s], target);
                if (isnan(lc))
                    fprintf(f, " - |");
                else
                    fprintf(f, " %.3g s |", pow(10, lc));
                if (!isnan(lc) && (isnan(bestv) || lc < bestv)) {
                    bestv = lc;
                    win = sol[s];
                }
            }
            char b[32];
            fmt_ratio(b, sizeof b, rows, n, c, target);
            fprintf(f, " %s | %s |\n", win, b);
        }
        fprintf(f, "\n![work-precision %s](wp_%s.png)\n\n", bc->name, bc->name);
    }
    fprintf(f, "## Failures\n\n");
    int nf = 0;
    for (int i = 0; i < n; i++)
        if (rows[i].r.status < 0) {
            fprintf(f, "- %s, %s, rtol %g: status %d at t = %.9g: %s\n", cases[rows[i].ci]->name,
                    rows[i].sd->name, rows[i].rtol, rows[i].r.status, rows[i].r.t, rows[i].r.msg);
            nf++;
        }
    if (!nf) fprintf(f, "none\n");
    fprintf(f, "\n");
}

/* ---------------------------------------------------- steps against tolerance ---- */

/* The tighter run of the same case and solver with the fewest steps relative to A's: the
 * largest steps(A) / steps(B) over successful runs B at a smaller rtol; NULL if none. */
static const bench_row *fewest_tighter(const bench_row *rows, int n, const bench_row *A,
                                       double *ratio)
{
    const bench_row *best = NULL;
    *ratio = 0;
    if (!row_ok(A) || A->r.steps <= 0) return NULL;
    for (int i = 0; i < n; i++) {
        const bench_row *B = &rows[i];
        if (B->ci != A->ci || B->sd != A->sd || !row_ok(B) || !(B->rtol < A->rtol) ||
            B->r.steps <= 0)
            continue;
        double q = (double)A->r.steps / (double)B->r.steps;
        if (q > *ratio) {
            *ratio = q;
            best = B;
        }
    }
    return best;
}

#define MORE_STEPS_LIMIT 1.05

/* steps_vs_tol.csv and the report's section: steps (rejected) of every problem and solver at
 * each tolerance, "MORE STEPS" where a looser tolerance took more than 5 % more steps than a
 * tighter one (failed runs left out: their counts stop where they failed). Returns the number
 * of flagged (problem, solver) pairs (a CSV that cannot be written is said and counted by
 * bench_file_close; the section is written all the same). */
static int write_steps_vs_tol(const char *dir, FILE *f, const bench_row *rows, int n,
                              bench_case **cases, int nc, const char **sol, int ns,
                              const double *rtols, int nr)
{
    bench_file bf;
    FILE *c = bench_file_open(&bf, dir, "steps_vs_tol.csv") == 0 ? bf.f : NULL;
    if (c)
        fprintf(c, "problem,solver,rtol,atol,status,steps,rejected,max_order,flag,"
                   "tighter_rtol_fewer_steps,tighter_steps,excess_percent\n");
    for (int i = 0; i < n && c; i++) {
        const bench_row *A = &rows[i];
        double q;
        const bench_row *B = fewest_tighter(rows, n, A, &q);
        int flag = B && q > MORE_STEPS_LIMIT;
        fprintf(c, "%s,%s,%g,%g,%d,%ld,%ld,%d,%s,", cases[A->ci]->name, A->sd->name, A->rtol,
                A->atol, A->r.status, A->r.steps, A->r.rejected, A->r.max_order,
                flag ? "MORE STEPS" : "");
        if (flag)
            fprintf(c, "%g,%ld,%.1f\n", B->rtol, B->r.steps, 100 * (q - 1));
        else
            fprintf(c, ",,\n");
    }
    if (c) bench_file_close(&bf);
    /* tolerances loosest first */
    double rt[BENCH_MAXRTOL];
    int k = 0;
    for (int i = 0; i < nr; i++)
        rt[k++] = rtols[i];
    for (int i = 1; i < k; i++)
        for (int j = i; j > 0 && rt[j] > rt[j - 1]; j--) {
            double t = rt[j];
            rt[j] = rt[j - 1];
            rt[j - 1] = t;
        }
    fprintf(f, "## Steps against tolerance\n\n"
               "Accepted steps (rejected steps in brackets) of every run of the work-precision "
               "series, loosest tolerance first (steps_vs_tol.csv). MORE STEPS: a looser "
               "tolerance took more than 5 %% more steps than a tighter one of the same problem "
               "and solver (the worst pair is named; failed runs are left out, their counts stop "
               "where they failed). Step counts should fall as the tolerance loosens: where they "
               "do not, the step size is not set by the accuracy asked for (an order held down "
               "by a stability limit, a fail/grow cycle of the step size, restarts).\n\n");
    int nflag = 0;
    /* the flagged pairs first */
    for (int ci = 0; ci < nc; ci++)
        for (int s = 0; s < ns; s++) {
            const bench_row *worst = NULL, *wb = NULL;
            double wq = 0;
            for (int i = 0; i < n; i++) {
                const bench_row *A = &rows[i];
                if (A->ci != ci || strcmp(A->sd->name, sol[s])) continue;
                double q;
                const bench_row *B = fewest_tighter(rows, n, A, &q);
                if (B && q > MORE_STEPS_LIMIT && q > wq) {
                    wq = q;
                    worst = A;
                    wb = B;
                }
            }
            if (!worst) continue;
            if (!nflag) fprintf(f, "Flagged:\n\n");
            nflag++;
            fprintf(f,
                    "- MORE STEPS: %s, %s: %ld steps at rtol %g against %ld at rtol %g (+%.0f "
                    "%%)\n",
                    cases[ci]->name, sol[s], worst->r.steps, worst->rtol, wb->r.steps, wb->rtol,
                    100 * (wq - 1));
        }
    fprintf(f, nflag ? "\n" : "No problem and solver took more steps at a looser tolerance.\n\n");
    fprintf(f, "| problem | solver |");
    for (int i = 0; i < k; i++)
        fprintf(f, " %g |", rt[i]);
    fprintf(f, " flag |\n|---|---|");
    for (int i = 0; i <= k; i++)
        fprintf(f, "---|");
    fprintf(f, "\n");
    for (int ci = 0; ci < nc; ci++)
        for (int s = 0; s < ns; s++) {
            int any = 0, flag = 0;
            for (int i = 0; i < n; i++)
                any |= rows[i].ci == ci && !strcmp(rows[i].sd->name, sol[s]);
            if (!any) continue;
            fprintf(f, "| %s | %s |", cases[ci]->name, sol[s]);
            for (int j = 0; j < k; j++) {
                const bench_row *A = NULL;
                for (int i = 0; i < n; i++)
                    if (rows[i].ci == ci && !strcmp(rows[i].sd->name, sol[s]) &&
                        rows[i].rtol == rt[j])
                        A = &rows[i];
                if (!A) {
                    fprintf(f, " |");
                    continue;
                }
                double q;
                const bench_row *B = fewest_tighter(rows, n, A, &q);
                int fl = B && q > MORE_STEPS_LIMIT;
                flag |= fl;
                if (A->r.status < 0)
                    fprintf(f, " FAIL (%ld) |", A->r.steps);
                else
                    fprintf(f, " %s%ld (%ld)%s |", fl ? "**" : "", A->r.steps, A->r.rejected,
                            fl ? "**" : "");
            }
            fprintf(f, " %s |\n", flag ? "MORE STEPS" : "");
        }
    fprintf(f, "\n");
    return nflag;
}

/* The report's list of the files that could not be written (none: nothing), placed after its
 * head: the report itself is written last. */
static void write_report_failed_files(FILE *f)
{
    int k = bench_file_failures();
    if (k == 0) return;
    fprintf(f, "## Files not written\n\n"
               "These files of the run could not be written (the bench ends with exit status 1); "
               "none of them is left in the folder:\n\n");
    for (int i = 0; i < k; i++) {
        const char *msg, *name = bench_file_failure(i, &msg);
        if (!name) {
            fprintf(f, "- and %d more (named in the bench's messages)\n", k - i);
            break;
        }
        fprintf(f, "- %s: %s\n", name, msg);
    }
    fprintf(f, "\n");
}

/* ---------------------------------------------------------------- entry points ---- */

int bench_text_open(bench_text *t)
{
    t->buf = NULL;
    t->len = 0;
    t->f = open_memstream(&t->buf, &t->len);
    return t->f ? 0 : -1;
}

void bench_text_free(bench_text *t)
{
    if (t->f) fclose(t->f);
    t->f = NULL;
    free(t->buf);
    t->buf = NULL;
}

/* Closes t and appends its text to the report (a failure to finish it: rep's, ENOMEM). */
static void append_text(bench_file *rep, bench_text *t)
{
    int rc = fclose(t->f);
    t->f = NULL;
    if (rc != 0)
        bench_file_fail(rep, ENOMEM);
    else
        fwrite(t->buf, 1, t->len, rep->f);
}

void bench_report_csv(const char *dir, const bench_results *res)
{
    bench_file wp;
    if (bench_file_open(&wp, dir, "work_precision.csv") == 0) {
        write_csv(wp.f, res->rows, res->n, res->cases);
        bench_file_close(&wp);
    }
}

void bench_report_plots(const char *dir, const bench_results *res)
{
    char gnuplot[BENCH_PATH_SIZE];
    int have_gnuplot = res->nc > 0 && pu_gnuplot_find(gnuplot, sizeof gnuplot);
    if (res->nc > 0 && !have_gnuplot)
        fprintf(stderr, "bench: gnuplot not found: no figures (the wp_*.dat files are written)\n");
    for (int c = 0; c < res->nc; c++)
        plot(dir, have_gnuplot ? gnuplot : NULL, c, res->cases[c]->name, res->rows, res->n,
             res->sol, res->ns);
}

int bench_report_steps_vs_tol(const char *dir, FILE *f, const bench_results *res)
{
    return write_steps_vs_tol(dir, f, res->rows, res->n, res->cases, res->nc, res->sol, res->ns,
                              res->rtols, res->nr);
}

void bench_report_write(bench_file *rep, const bench_results *res, const bench_report_extras *ex,
                        bench_text *mid, bench_text *tail)
{
    write_report_head(rep->f, res->rows, res->n, res->cases, res->nc, res->sol, res->ns, res->wall,
                      res->repeat, ex);
    write_report_failed_files(rep->f);
    append_text(rep, mid);
    write_report_problems(rep->f, res->rows, res->n, res->cases, res->nc, res->sol, res->ns);
    append_text(rep, tail);
    bench_file_close(rep);
}
