/* A program's --error-estimate [K] (rn_run.h): the companion run at rtol / K, atol / K
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
 * why) or "no values" (a column without a finite value in both runs at any row compared).
 *
 * Invariant: the estimate never makes the run fail; its state is read from r->est and r->rows
 * only, so that status.txt (written at any moment, also by the signal handler's prepared text)
 * says how it stands. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rn_run.h"

void rn_estimate_open(rn_run *r, const rn_estimate_spec *sp)
{
    rn_estimate *es = &r->est;
    if (!es->on) return;
    rn_set_phase(r, RN_PHASE_SETUP,
                 "starting the run at the tighter tolerances (--error-estimate)");
    es->names = sp->names;
    es->ncols = sp->ncols;
    es->ranked = sp->ranked;
    rn_errest_spec e = {sp->p, sp->o,     es->factor, 0.0,     sp->y0,          sp->yp0,
                        1,     sp->ncols, sp->out,    sp->ctx, rn_signal_flag()};
    bg_error err = {0};
    es->e = rn_errest_create(&e, &err);
    if (!es->e)
        snprintf(es->note, sizeof es->note, "%s", err.message);
    else if (rn_errest_status(es->e) < 0)
        snprintf(es->note, sizeof es->note, "%s", rn_errest_message(es->e));
    if (es->note[0])
        fprintf(stderr, "%s: the error estimate is unavailable: %s\n", r->program, es->note);
}

int rn_estimate_row(rn_run *r, long k, double t, const double *out)
{
    rn_estimate *es = &r->est;
    if (!es->e || rn_errest_status(es->e) < 0) return 0;
    int rc = rn_errest_add(es->e, t, out);
    if (rc == RN_ERREST_STOPPED) return k > 0 ? RN_LOOP_STOP : 0;
    if (rc < 0) {
        snprintf(es->note, sizeof es->note, "%s", rn_errest_message(es->e));
        fprintf(stderr, "\n%s: the error estimate is unavailable: %s (the run goes on)\n",
                r->program, es->note);
    }
    return 0;
}

void rn_estimate_free(rn_run *r)
{
    rn_errest_free(&r->est.e);
}

/* How the estimate stands (OFF: not asked for), and its word in the files. */
enum { OFF, AVAILABLE, PARTIAL, UNAVAILABLE };
static const char *const STATE[] = {"off", "available", "partial", "unavailable"};

static int state(const rn_run *r)
{
    if (!r->est.on) return OFF;
    if (!r->est.e || rn_errest_status(r->est.e) < 0) return UNAVAILABLE;
    if (rn_errest_count(r->est.e) < r->rows) return PARTIAL;
    return AVAILABLE;
}

/* The column with the largest relative error (-1: none) among those the program ranks (not t;
 * the crane passes over its references and the errors against them, whose size is the error
 * itself). */
static int worst_column(const rn_run *r, double *rel)
{
    int worst = -1;
    *rel = NAN;
    for (int j = 1; j < r->est.ncols; j++) {
        if (r->est.ranked && !r->est.ranked(r->est.names[j])) continue;
        const rn_errest_col *c = rn_errest_column(r->est.e, j);
        if (!c || isnan(c->max_err) || !(c->max_abs > 0)) continue;
        double q = c->max_err / c->max_abs;
        if (worst < 0 || q > *rel) worst = j, *rel = q;
    }
    return worst;
}

static int print_csv(rn_run *r, FILE *f, const void *ctx)
{
    (void)ctx;
    int st = state(r), avail = st != UNAVAILABLE;
    double covered = r->est.e ? rn_errest_last(r->est.e) : NAN;
    fprintf(f, "column,max_abs_error,t_at_max [s],max_abs_value,max_rel_error,t_covered [s],"
               "estimate\n");
    for (int j = 1; j < r->est.ncols; j++) {
        const rn_errest_col *c = avail ? rn_errest_column(r->est.e, j) : NULL;
        fprintf(f, "%s,", r->est.names[j]);
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

int rn_estimate_write(rn_run *r)
{
    if (!r->est.on || !r->est.names) return 0;
    return rn_save_file(r, "error_estimate.csv", print_csv, NULL) != 0 ? RN_EXIT_RUN : 0;
}

void rn_estimate_status_lines(const rn_run *r, FILE *f)
{
    int st = state(r);
    if (st == OFF) return;
    double covered = r->est.e ? rn_errest_last(r->est.e) : NAN;
    if (st == UNAVAILABLE)
        fprintf(f, "error_estimate: unavailable: %s\n", r->est.note);
    else if (rn_errest_count(r->est.e) == 0)
        fprintf(f, "error_estimate: %s (no row compared yet)\n", STATE[st]);
    else
        fprintf(f, "error_estimate: %s over %ld rows up to t = %.9g s\n", STATE[st],
                rn_errest_count(r->est.e), covered);
}

void rn_estimate_stats_lines(const rn_run *r, FILE *f)
{
    int st = state(r);
    if (st == OFF) return;
    double rtol, atol, K, rel;
    rn_errest_tolerances(r->est.e, &rtol, &atol, &K);
    if (!r->est.e) K = r->est.factor;
    fprintf(f,
            "error_estimate: a second run at rtol / %g and atol / %g (rtol %g, atol %g), "
            "compared at every row: error_estimate.csv\n",
            K, K, rtol, atol);
    rn_estimate_status_lines(r, f);
    const dae_stats *cs = rn_errest_stats(r->est.e);
    if (cs) {
        char line[2048];
        dae_stats_line(cs, line, sizeof line);
        fprintf(f, "error_estimate_run: %s\n", line);
    }
    int w = st != UNAVAILABLE ? worst_column(r, &rel) : -1;
    if (w >= 0) {
        const rn_errest_col *c = rn_errest_column(r->est.e, w);
        fprintf(f,
                "error_estimate_largest: %s: %.3g relative to its largest value %.6g (%.3g at "
                "t = %.9g s)\n",
                r->est.names[w], rel, c->max_abs, c->max_err, c->t_at);
    }
}

void rn_estimate_summary(const rn_run *r)
{
    int st = state(r);
    if (st == OFF) return;
    if (st == UNAVAILABLE) {
        printf("  error estimate unavailable: %s\n", r->est.note);
        return;
    }
    double rtol, rel;
    rn_errest_tolerances(r->est.e, &rtol, NULL, NULL);
    int w = worst_column(r, &rel);
    printf("  error estimate (%s, against rtol %g): ", STATE[st], rtol);
    if (w < 0) {
        printf("no column compared\n");
        return;
    }
    const rn_errest_col *c = rn_errest_column(r->est.e, w);
    printf("largest relative error %.3g in %s (%.3g at t = %g s); error_estimate.csv\n", rel,
           r->est.names[w], c->max_err, c->t_at);
}
