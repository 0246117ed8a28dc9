/* crane --error-estimate (crane_program.h): the companion run at rtol / K, atol / K
 * (rn_errest.h) beside the dynamic run, compared with it at every row of results.csv, and
 * error_estimate.csv:
 *
 *   column,max_abs_error,t_at_max [s],max_abs_value,max_rel_error,t_covered [s],estimate
 *
 * one line per output column after t: the largest |out(rtol) - out(rtol / K)| over the rows
 * compared, the time of it, the largest |out(rtol)|, their ratio, the last row compared, and
 * "available" (every row of results.csv compared), "partial" (a signal stopped the companion
 * before the last rows: the numbers are over the rows up to t_covered), "unavailable" (the
 * companion failed or could not start: no numbers; solver_stats.txt, status.txt and stderr say
 * why) or "no values" (a column the scene does not have). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "crane_program.h"

/* The companion's outputs: crane_outputs of the same model. */
static void outputs(void *ctx, double t, const double *y, const double *yp, double *out)
{
    crane_outputs(ctx, t, y, yp, out);
}

void cp_errest_open(cp_run *r, const dae_problem *p, const dae_options *dopt, const double *y0,
                    const double *yp0)
{
    if (!r->o->errest) return;
    rn_errest_spec sp = {p,       dopt, r->o->errest_factor, 0.0, y0, yp0, 1, CRANE_NOUT,
                            outputs, r->c, rn_signal_flag()};
    bg_error err = {0};
    r->errest = rn_errest_create(&sp, &err);
    if (!r->errest)
        snprintf(r->errest_note, sizeof r->errest_note, "%s", err.message);
    else if (rn_errest_status(r->errest) < 0)
        snprintf(r->errest_note, sizeof r->errest_note, "%s", rn_errest_message(r->errest));
    if (r->errest_note[0])
        fprintf(stderr, "crane: the error estimate is unavailable: %s\n", r->errest_note);
}

int cp_errest_row(cp_run *r, double t, const double *out)
{
    if (!r->errest || rn_errest_status(r->errest) < 0) return 0;
    int rc = rn_errest_add(r->errest, t, out);
    if (rc == RN_ERREST_STOPPED) return rc;
    if (rc < 0) {
        snprintf(r->errest_note, sizeof r->errest_note, "%s", rn_errest_message(r->errest));
        fprintf(stderr, "\ncrane: the error estimate is unavailable: %s (the run goes on)\n",
                r->errest_note);
    }
    return 0;
}

/* How the estimate stands (OFF: not asked for), and its word in the files. */
enum { OFF, AVAILABLE, PARTIAL, UNAVAILABLE };
static const char *const STATE[] = {"off", "available", "partial", "unavailable"};

static int state(const cp_run *r)
{
    if (!r->o->errest) return OFF;
    if (!r->errest || rn_errest_status(r->errest) < 0) return UNAVAILABLE;
    if (rn_errest_count(r->errest) < r->rn.rows) return PARTIAL;
    return AVAILABLE;
}

/* The column with the largest relative error (-1: none) among the model's quantities: not t,
 * not the references (*_ref, exact functions of t), not the errors against them (*_err) nor the
 * joints' drift (constraint_drift), whose size is the error itself. */
static int worst_column(const cp_run *r, double *rel)
{
    int worst = -1;
    *rel = NAN;
    for (int j = 1; j < CRANE_NOUT; j++) {
        const char *name = crane_output_names[j];
        if (strstr(name, "_ref ") || strstr(name, "_err ") || strstr(name, "drift")) continue;
        const rn_errest_col *c = rn_errest_column(r->errest, j);
        if (!c || isnan(c->max_err) || !(c->max_abs > 0)) continue;
        double q = c->max_err / c->max_abs;
        if (worst < 0 || q > *rel) worst = j, *rel = q;
    }
    return worst;
}

static int print_csv(rn_run *rn, FILE *f, const void *ctx)
{
    (void)ctx;
    const cp_run *r = CP_RUN(rn);
    int st = state(r), avail = st != UNAVAILABLE;
    double covered = r->errest ? rn_errest_last(r->errest) : NAN;
    fprintf(f, "column,max_abs_error,t_at_max [s],max_abs_value,max_rel_error,t_covered [s],"
               "estimate\n");
    for (int j = 1; j < CRANE_NOUT; j++) {
        const rn_errest_col *c = avail ? rn_errest_column(r->errest, j) : NULL;
        fprintf(f, "%s,", crane_output_names[j]);
        if (c && !isnan(c->max_err)) {
            fprintf(f, "%.6g,%.9g,%.6g,", c->max_err, c->t_at, c->max_abs);
            if (c->max_abs > 0) fprintf(f, "%.6g", c->max_err / c->max_abs);
            fprintf(f, ",");
        } else {
            fprintf(f, ",,,,");
        }
        if (isnan(covered))
            fprintf(f, ",");
        else
            fprintf(f, "%.9g,", covered);
        fprintf(f, "%s\n", c && isnan(c->max_err) ? "no values" : STATE[st]);
    }
    return 0;
}

int cp_errest_write(cp_run *r)
{
    if (!r->o->errest) return 0;
    if (rn_save_file(&r->rn, "error_estimate.csv", print_csv, NULL) != 0) return RN_EXIT_RUN;
    r->errest_written = 1;
    return 0;
}

void cp_errest_status_lines(const rn_run *rn, FILE *f)
{
    const cp_run *r = CP_RUN(rn);
    int st = state(r);
    if (st == OFF) return;
    double covered = r->errest ? rn_errest_last(r->errest) : NAN;
    if (st == UNAVAILABLE)
        fprintf(f, "error_estimate: unavailable: %s\n", r->errest_note);
    else if (rn_errest_count(r->errest) == 0)
        fprintf(f, "error_estimate: %s (no row compared yet)\n", STATE[st]);
    else
        fprintf(f, "error_estimate: %s over %ld rows up to t = %.9g s\n", STATE[st],
                rn_errest_count(r->errest), covered);
}

void cp_errest_stats_lines(const rn_run *rn, FILE *f)
{
    const cp_run *r = CP_RUN(rn);
    int st = state(r);
    if (st == OFF) return;
    double rtol, atol, K, rel;
    rn_errest_tolerances(r->errest, &rtol, &atol, &K);
    if (!r->errest) K = r->o->errest_factor;
    fprintf(f,
            "error_estimate: a second run at rtol / %g and atol / %g (rtol %g, atol %g), "
            "compared at every row: error_estimate.csv\n",
            K, K, rtol, atol);
    cp_errest_status_lines(rn, f);
    const dae_stats *cs = rn_errest_stats(r->errest);
    if (cs) {
        char line[2048];
        dae_stats_line(cs, line, sizeof line);
        fprintf(f, "error_estimate_run: %s\n", line);
    }
    int w = st != UNAVAILABLE ? worst_column(r, &rel) : -1;
    if (w >= 0) {
        const rn_errest_col *c = rn_errest_column(r->errest, w);
        fprintf(f,
                "error_estimate_largest: %s: %.3g relative to its largest value %.6g (%.3g at "
                "t = %.9g s)\n",
                crane_output_names[w], rel, c->max_abs, c->max_err, c->t_at);
    }
}

void cp_errest_summary(const cp_run *r)
{
    int st = state(r);
    if (st == OFF) return;
    if (st == UNAVAILABLE) {
        printf("  error estimate unavailable: %s\n", r->errest_note);
        return;
    }
    double rtol, rel;
    rn_errest_tolerances(r->errest, &rtol, NULL, NULL);
    int w = worst_column(r, &rel);
    printf("  error estimate (%s, against rtol %g): ", STATE[st], rtol);
    if (w < 0) {
        printf("no column compared\n");
        return;
    }
    const rn_errest_col *c = rn_errest_column(r->errest, w);
    printf("largest relative error %.3g in %s (%.3g at t = %g s); error_estimate.csv\n", rel,
           crane_output_names[w], c->max_err, c->t_at);
}
