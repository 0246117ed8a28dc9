/* The error estimate against the true error (bench_errest.h). */
#include "bench_errest.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bench_util.h"
#include "rn_errest.h"
#include "crane_model.h"

/* the outputs of the crane's scd (as bench_crane.c scores the crane) */
static const char *const SCORED[] = {"theta",  "omega",  "tip_x",      "tip_y",  "tip_z", "load_x",
                                     "load_y", "load_z", "rope_force", "p_high", "p_low"};
#define NSCORED ((int)(sizeof SCORED / sizeof *SCORED))

/* One line of the results: a problem at a tolerance (component "max"), or a crane column. */
typedef struct er_row {
    const char *problem;
    double rtol, atol;
    char component[64];
    double est, truth, ratio;
    double scale; /* a crane column's largest |value| (its errors are absolute); 1 otherwise */
    long steps, steps_tight;
    char msg[BG_MESSAGE_SIZE];
} er_row;

/* Our options for the case at rtol, as bench_case.c's runs have them (bgdae-klu). */
static void options_for(const bench_case *bc, double rtol, double *atolv, dae_options *o)
{
    dae_options_default(o);
    o->rtol = rtol;
    if (bench_case_atol(bc, rtol, &o->atol, atolv)) o->atol_vec = atolv;
    o->exclude_alg = bc->exclude_alg;
    o->stability_guard = bc->stability_guard;
    o->newton_dgmax = bc->newton_dgmax;
    o->newton_jac_age = bc->newton_jac_age;
    o->newton_index2_scale_h = bc->newton_index2_scale_h;
    o->has_t_stop = 1;
    o->t_stop = bc->tend;
    o->max_steps = 1000000;
    o->no_timing = 1;
    int nb = 0;
    while (nb < bc->nbreakpoints && bc->breakpoints[nb] < bc->tend)
        nb++;
    o->breakpoints = bc->breakpoints;
    o->nbreakpoints = nb;
}

static void crane_out(void *ctx, double t, const double *y, const double *yp, double *out)
{
    crane_outputs(ctx, t, y, yp, out);
}

/* A run of the case at rtol over the times tk[0..nt-1], its outputs (fn, or y itself with fn
 * NULL: nout = n) at each into out1[k * nout ...]; with K > 0 the companion at rtol / K beside it
 * (*pe, rn_errest.h). 0, or the run's failure (msg). */
static int run_over(const bench_case *bc, double rtol, double K, const double *tk, int nt,
                    rn_errest_out_fn fn, void *ctx, int nout, double *out1, rn_errest **pe,
                    long *steps, char *msg, size_t msz)
{
    int n = bc->n, rc = 0;
    double *atolv = malloc((size_t)n * sizeof *atolv), *y = malloc(2 * (size_t)n * sizeof *y);
    dae_options o;
    dae_solver *s = NULL;
    *steps = 0;
    if (pe) *pe = NULL;
    if (!atolv || !y) {
        snprintf(msg, msz, "out of memory");
        rc = BG_ERR_MEMORY;
        goto end;
    }
    double *yp = y + n;
    options_for(bc, rtol, atolv, &o);
    bg_error err = {0};
    s = dae_create(&bc->dp, &o, &err);
    if (!s || (rc = dae_init(s, bc->t0, bc->ys, bc->yps)) != 0) {
        snprintf(msg, msz, "%s", s ? dae_get_error(s)->message : err.message);
        rc = rc ? rc : (err.status ? err.status : BG_ERR_ARGUMENT);
        goto end;
    }
    if (K > 0) {
        rn_errest_spec sp = {&bc->dp, &o, K, bc->t0, bc->ys, bc->yps, 0, nout, fn, ctx, NULL};
        *pe = rn_errest_create(&sp, &err);
        if (!*pe) {
            snprintf(msg, msz, "%s", err.message);
            rc = err.status;
            goto end;
        }
    }
    for (int k = 0; k < nt && rc == 0; k++) {
        double t = bc->t0;
        if (tk[k] > bc->t0) {
            while (rc == 0 && t < tk[k]) {
                rc = dae_solve_to(s, tk[k], &t, y, yp);
                if (rc > 0) rc = 0;
            }
        } else {
            rc = dae_dense(s, bc->t0, y, yp);
        }
        if (rc < 0) {
            snprintf(msg, msz, "%.440s (%s)", dae_get_error(s)->message, dae_return_name(rc));
            break;
        }
        double *o1 = out1 + (size_t)k * (size_t)nout;
        if (fn)
            fn(ctx, tk[k], y, yp, o1);
        else
            memcpy(o1, y, (size_t)n * sizeof *o1);
        if (pe && *pe) rn_errest_add(*pe, tk[k], o1); /* its failure: rn_errest_status */
    }
    *steps = dae_get_stats(s)->steps;
end:
    dae_free(&s);
    free(atolv);
    free(y);
    return rc;
}

static double ratio_of(double est, double truth)
{
    return truth > 0 ? est / truth : (est == 0 && truth == 0 ? 1 : INFINITY);
}

static int within(double ratio)
{
    return ratio >= 0.1 && ratio <= 10;
}

/* Relative errors both below this are round-off (a few units of the last place): the ratio of
 * two such numbers says nothing about the estimate and is not judged. */
#define ROUNDOFF 1e-13

static int roundoff(const er_row *r)
{
    return !isnan(r->est) && r->est < ROUNDOFF * r->scale && r->truth < ROUNDOFF * r->scale;
}

/* A problem of the collection at each tolerance: rows appended to *rows. */
static int check_problem(const bench_case *bc, const bench_errest_config *cfg, double K,
                         er_row *rows, int *nrows)
{
    int n = bc->n, fails = 0;
    double *y1 = malloc((size_t)n * sizeof *y1);
    if (!y1) return 1;
    const unsigned char *scored = bc->bp ? bc->bp->scored : NULL;
    for (int k = 0; k < cfg->nr; k++) {
        er_row *r = &rows[(*nrows)++];
        memset(r, 0, sizeof *r);
        r->problem = bc->name;
        r->rtol = cfg->rtols[k];
        bench_case_atol(bc, r->rtol, &r->atol, NULL);
        snprintf(r->component, sizeof r->component, "max");
        r->est = r->truth = r->ratio = NAN;
        r->scale = 1;
        rn_errest *e = NULL;
        int rc = run_over(bc, r->rtol, K, &bc->tend, 1, NULL, NULL, n, y1, &e, &r->steps, r->msg,
                          sizeof r->msg);
        const dae_stats *cs = rn_errest_stats(e);
        r->steps_tight = cs ? cs->steps : 0;
        if (rc != 0) {
            fails++;
        } else if (rn_errest_status(e) < 0) {
            snprintf(r->msg, sizeof r->msg, "%s", rn_errest_message(e));
        } else {
            double est = 0, truth = 0;
            int worst = -1, used = 0;
            for (int i = 0; i < n; i++) {
                if ((scored && !scored[i]) || bc->dp.kind[i] == DAE_ALG2 || bc->yref[i] == 0)
                    continue;
                double a = fabs(bc->yref[i]), d2 = fabs(y1[i] - bc->yref[i]);
                const rn_errest_col *c = rn_errest_column(e, i);
                used++;
                if (!(c->max_err / a <= est)) est = c->max_err / a;
                if (!(d2 / a <= truth)) truth = d2 / a, worst = i;
            }
            r->est = used ? est : NAN;
            r->truth = used ? truth : NAN;
            r->ratio = used ? ratio_of(est, truth) : NAN;
            if (!used) snprintf(r->msg, sizeof r->msg, "no scored component with a reference");
            if (worst >= 0)
                snprintf(r->component, sizeof r->component, "max (true at %s)",
                         bc->dp.names ? bc->dp.names[worst] : "?");
        }
        rn_errest_free(&e);
    }
    free(y1);
    return fails;
}

/* The crane at each tolerance at least 1000 times looser than the reference's. */
static int check_crane(const bench_case *bc, const bench_errest_config *cfg, double K, er_row *rows,
                       int *nrows, double *ref_steps)
{
    double dt = cfg->crane_step > 0 ? cfg->crane_step : 0.01;
    double rref = cfg->crane_rtol_ref > 0 ? cfg->crane_rtol_ref : 1e-11;
    int nt = (int)ceil((bc->tend - bc->t0) / dt - 1e-9) + 1, fails = 0;
    double *tk = malloc((size_t)nt * sizeof *tk);
    double *ref = malloc((size_t)nt * CRANE_NOUT * sizeof *ref);
    double *o1 = malloc((size_t)nt * CRANE_NOUT * sizeof *o1);
    if (!tk || !ref || !o1) {
        free(tk);
        free(ref);
        free(o1);
        return 1;
    }
    for (int k = 0; k < nt; k++)
        tk[k] = k + 1 < nt ? bc->t0 + k * dt : bc->tend;
    char msg[BG_MESSAGE_SIZE];
    long st = 0;
    fprintf(stderr, "crane: error estimate, reference at rtol %g over %d output times\n", rref, nt);
    if (run_over(bc, rref, 0, tk, nt, crane_out, bc->ext, CRANE_NOUT, ref, NULL, &st, msg,
                 sizeof msg) != 0) {
        fprintf(stderr, "bench: crane: the error estimate's reference failed: %s\n", msg);
        free(tk);
        free(ref);
        free(o1);
        return 1;
    }
    *ref_steps = (double)st;
    double scale[CRANE_NOUT], truth[CRANE_NOUT];
    for (int j = 0; j < CRANE_NOUT; j++) {
        scale[j] = 0;
        for (int k = 0; k < nt; k++)
            if (isfinite(ref[k * CRANE_NOUT + j]))
                scale[j] = fmax(scale[j], fabs(ref[k * CRANE_NOUT + j]));
    }
    for (int q = 0; q < cfg->nr; q++) {
        double rtol = cfg->rtols[q];
        if (rtol < 1000 * rref) continue;
        er_row *head = &rows[(*nrows)++];
        memset(head, 0, sizeof *head);
        head->problem = bc->name;
        head->rtol = rtol;
        bench_case_atol(bc, rtol, &head->atol, NULL);
        snprintf(head->component, sizeof head->component, "max relative (scd outputs)");
        head->est = head->truth = head->ratio = NAN;
        head->scale = 1;
        rn_errest *e = NULL;
        int rc = run_over(bc, rtol, K, tk, nt, crane_out, bc->ext, CRANE_NOUT, o1, &e, &head->steps,
                          head->msg, sizeof head->msg);
        const dae_stats *cs = rn_errest_stats(e);
        head->steps_tight = cs ? cs->steps : 0;
        if (rc != 0 || rn_errest_status(e) < 0) {
            if (rc != 0)
                fails++;
            else
                snprintf(head->msg, sizeof head->msg, "%s", rn_errest_message(e));
            rn_errest_free(&e);
            continue;
        }
        for (int j = 0; j < CRANE_NOUT; j++) {
            truth[j] = NAN;
            for (int k = 0; k < nt; k++) {
                double d = fabs(o1[k * CRANE_NOUT + j] - ref[k * CRANE_NOUT + j]);
                if (isfinite(d) && !(d <= truth[j])) truth[j] = d;
            }
        }
        double est = 0, tru = 0;
        for (int i = 0; i < NSCORED; i++) {
            int j = crane_output_index(SCORED[i]);
            const rn_errest_col *c = rn_errest_column(e, j);
            if (j < 0 || !(scale[j] > 0) || isnan(c->max_err) || isnan(truth[j])) continue;
            est = fmax(est, c->max_err / scale[j]);
            tru = fmax(tru, truth[j] / scale[j]);
        }
        head->est = est;
        head->truth = tru;
        head->ratio = ratio_of(est, tru);
        /* every column: absolute errors */
        for (int j = 1; j < CRANE_NOUT; j++) {
            const rn_errest_col *c = rn_errest_column(e, j);
            if (isnan(c->max_err) || isnan(truth[j])) continue;
            er_row *r = &rows[(*nrows)++];
            *r = *head;
            r->msg[0] = '\0';
            snprintf(r->component, sizeof r->component, "%s", crane_output_names[j]);
            r->est = c->max_err;
            r->truth = truth[j];
            r->ratio = ratio_of(r->est, r->truth);
            r->scale = scale[j];
        }
        rn_errest_free(&e);
    }
    free(tk);
    free(ref);
    free(o1);
    return fails;
}

static const char *flag(const er_row *r)
{
    if (isnan(r->ratio)) return "no estimate";
    if (roundoff(r)) return "round-off";
    return within(r->ratio) ? "yes" : (r->ratio > 10 ? "NO (over 10x)" : "NO (under 1/10)");
}

int bench_errest(const char *dir, FILE *rep, bench_case **cases, int nc,
                 const bench_errest_config *cfg)
{
    double K = cfg->factor > 0 ? cfg->factor : RN_ERREST_FACTOR, ref_steps = 0;
    size_t cap = (size_t)(nc + 1) * (size_t)(cfg->nr + 1) * (CRANE_NOUT + 1);
    er_row *rows = calloc(cap, sizeof *rows);
    if (!rows) {
        fprintf(stderr, "bench: error estimate: out of memory\n");
        return 1;
    }
    int nrows = 0, fails = 0, have_crane = 0;
    double w0 = bench_wall_now();
    for (int c = 0; c < nc; c++) {
        const bench_case *bc = cases[c];
        if (!strcmp(bc->name, "crane") && bc->ext) {
            fails += check_crane(bc, cfg, K, rows, &nrows, &ref_steps);
            have_crane = 1;
        } else if (bc->yref) {
            fails += check_problem(bc, cfg, K, rows, &nrows);
        }
    }
    double wall = bench_wall_now() - w0;
    bench_file bf;
    if (bench_file_open(&bf, dir, "error_estimate.csv") == 0) {
        fprintf(bf.f, "problem,rtol,atol,factor,component,estimate,true_error,ratio,within_10x,"
                      "steps,steps_tight,message\n");
        for (int i = 0; i < nrows; i++) {
            const er_row *r = &rows[i];
            fprintf(bf.f, "%s,%g,%g,%g,\"%s\",%.4g,%.4g,%.4g,%s,%ld,%ld,\"%s\"\n", r->problem,
                    r->rtol, r->atol, K, r->component, r->est, r->truth, r->ratio,
                    isnan(r->ratio)    ? ""
                    : roundoff(r)      ? "round-off"
                    : within(r->ratio) ? "yes"
                                       : "no",
                    r->steps, r->steps_tight, r->msg);
        }
        bench_file_close(&bf);
    }
    /* the report: one line per problem and tolerance, the outliers listed */
    int total = 0, inside = 0;
    fprintf(rep, "\n## Error estimate against the true error\n\n");
    fprintf(rep,
            "`crane --error-estimate` estimates a run's error by a second run at rtol / %g and "
            "atol / %g (runner/rn_errest.h). Here the same estimate (ours, bgdae-klu, from each "
            "case's consistent start) against the true error: for the collection at tend over "
            "the components of scd (relative to |yref|), for the crane over its outputs every "
            "%g s (relative to each column's largest value; reference: ours at rtol %g, %.0f "
            "steps, tolerances at least 1000 times looser). Target: ratio estimate / true "
            "error within a factor 10. %.1f s. File: `error_estimate.csv` (the crane's columns "
            "one by one too).\n\n",
            K, K, cfg->crane_step > 0 ? cfg->crane_step : 0.01,
            cfg->crane_rtol_ref > 0 ? cfg->crane_rtol_ref : 1e-11, ref_steps, wall);
    fprintf(rep, "| problem | rtol | estimate | true error | ratio | within 10x | steps | steps "
                 "at rtol/K |\n|---|---|---|---|---|---|---|---|\n");
    for (int i = 0; i < nrows; i++) {
        const er_row *r = &rows[i];
        if (strncmp(r->component, "max", 3)) continue;
        fprintf(rep, "| %s | %g | %.3g | %.3g | %.3g | %s | %ld | %ld |\n", r->problem, r->rtol,
                r->est, r->truth, r->ratio, flag(r), r->steps, r->steps_tight);
        if (!isnan(r->ratio) && !roundoff(r)) {
            total++;
            inside += within(r->ratio);
        }
    }
    fprintf(rep,
            "\n%d of %d estimates within a factor 10 of the true error (estimates where both are "
            "below %g, round-off, not counted).",
            inside, total, ROUNDOFF);
    int first = 1;
    for (int i = 0; i < nrows; i++) {
        const er_row *r = &rows[i];
        if (strncmp(r->component, "max", 3) || roundoff(r) ||
            (!isnan(r->ratio) && within(r->ratio)))
            continue;
        fprintf(rep, "%s%s at rtol %g: %s%s%s", first ? " Outside or without an estimate: " : "; ",
                r->problem, r->rtol, flag(r), r->msg[0] ? ", " : "", r->msg);
        first = 0;
    }
    fprintf(rep, "%s\n", first ? "" : ".");
    if (have_crane) {
        fprintf(rep,
                "\nThe crane's columns (absolute errors, the estimate / the truth; round-off: "
                "both below %g of the column's largest value):\n\n"
                "| rtol | column | estimate | true error | ratio |\n|---|---|---|---|---|\n",
                ROUNDOFF);
        for (int i = 0; i < nrows; i++) {
            const er_row *r = &rows[i];
            if (strcmp(r->problem, "crane") || !strncmp(r->component, "max", 3)) continue;
            fprintf(rep, "| %g | %s | %.3g | %.3g | %.3g%s |\n", r->rtol, r->component, r->est,
                    r->truth, r->ratio,
                    roundoff(r)        ? " (round-off)"
                    : within(r->ratio) ? ""
                                       : " (outside 10x)");
        }
    }
    free(rows);
    return fails;
}
