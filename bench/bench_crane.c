/* The crane in the benchmark harness (bench_crane.h). */
#include "bench_crane.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_util.h"
#include "crane_setup.h"

/* The outputs that enter the crane's scd. */
static const char *const SCORED[] = {"theta",  "omega",  "tip_x",      "tip_y",  "tip_z", "load_x",
                                     "load_y", "load_z", "rope_force", "p_high", "p_low"};
#define NSCORED ((int)(sizeof SCORED / sizeof *SCORED))

static void free_crane(void *ext)
{
    crane *c = ext;
    crane_free(&c);
}

bgr_model *bench_crane_model(const bench_case *bc)
{
    return crane_model((crane *)bc->ext);
}

static double digits(double e)
{
    return e > 0 ? -log10(e) : (e == 0 ? INFINITY : NAN);
}

static void crane_score(const bench_case *bc, const double *y, const double *yp, double rtol,
                        double atol, bp_score *s)
{
    s->scd = s->mescd = s->scd_i2 = s->mescd_i2 = NAN;
    s->worst = -1;
    if (!bc->yref) return;
    const crane *c = bc->ext;
    double o[CRANE_NOUT], oref[CRANE_NOUT];
    crane_outputs(c, bc->tend, y, yp, o);
    crane_outputs(c, bc->tend, bc->yref, bc->ypref, oref);
    double e = -1, em = -1, e2 = -1, em2 = -1, big2 = 0, ratio = atol / rtol;
    for (int k = 0; k < NSCORED; k++) {
        int j = crane_output_index(SCORED[k]);
        if (j < 0 || !isfinite(oref[j]) || oref[j] == 0) continue;
        double r = fabs(o[j] - oref[j]) / fabs(oref[j]);
        if (!(r <= e)) e = r; /* NaN wins */
    }
    const int *kind = bc->dp.kind;
    for (int i = 0; i < bc->n; i++)
        if (kind[i] == DAE_ALG2) big2 = fmax(big2, fabs(bc->yref[i]));
    for (int i = 0; i < bc->n; i++) {
        double d = fabs(y[i] - bc->yref[i]), a = fabs(bc->yref[i]);
        if (kind[i] == DAE_DIFF) {
            double r = d / (ratio + a);
            if (!(r <= em)) em = r;
        } else if (kind[i] == DAE_ALG2) {
            double r = d / (ratio + a);
            if (!(r <= em2)) em2 = r;
            if (a > 1e-6 * big2) {
                r = d / a;
                if (!(r <= e2)) e2 = r;
            }
        }
    }
    if (e != -1) s->scd = digits(e);
    if (em != -1) s->mescd = digits(em);
    if (e2 != -1) s->scd_i2 = digits(e2);
    if (em2 != -1) s->mescd_i2 = digits(em2);
}

static double crane_drift(const bench_case *bc, double t, const double *y, const double *yp)
{
    double o[CRANE_NOUT];
    int j = crane_output_index("constraint_drift");
    if (j < 0) return 0;
    crane_outputs(bc->ext, t, y, yp, o);
    return o[j];
}

int bench_crane_case(bench_case *bc, const crane_scene *s0, int settle, double tend,
                     const char *name, char *msg, size_t msz)
{
    memset(bc, 0, sizeof *bc);
    crane_scene s = *s0;
    s.t_end = tend;
    if (s.output_step > tend) s.output_step = tend;
    bg_error err = {0};
    crane *c = crane_build(&s, &err);
    if (!c) {
        snprintf(msg, msz, "building the crane: %s", err.message);
        return err.status < 0 ? err.status : BG_ERR_ARGUMENT;
    }
    bc->ext = c;
    bc->ext_free = free_crane;
    if (settle) {
        bg_error_clear(&err);
        int r = settle == BENCH_SETTLE_DAMPED ? crane_settle_damped(c, &err) : crane_settle(c, &err);
        if (r != BG_OK) {
            snprintf(msg, msz, "settling the crane: %s", err.message);
            bench_case_free(bc);
            return r < 0 ? r : BG_ERR_ARGUMENT;
        }
    }
    bgr_model *m = crane_model(c);
    int r = crane_dae_problem(c, &bc->dp);
    if (r != BG_OK) {
        snprintf(msg, msz, "crane problem: %s", bgr_model_error(m)->message);
        bench_case_free(bc);
        return r < 0 ? r : BG_ERR_ARGUMENT;
    }
    int n = bc->n = bc->dp.n;
    snprintf(bc->name, sizeof bc->name, "%s", name);
    bgr_stats st;
    bgr_get_stats(m, &st);
    snprintf(bc->title, sizeof bc->title,
             "rotary crane, scene %s, %d boom elements, %s start, [0, %g] s (%d differential, %d "
             "index-1, %d index-2 unknowns)",
             s.name, s.boom_elements, settle ? "static-equilibrium" : "geometric", tend,
             st.differential, st.algebraic, st.index2);
    snprintf(bc->ref_source, sizeof bc->ref_source, "none");
    bc->t0 = 0;
    bc->tend = tend;
    size_t sz = (size_t)(n > 0 ? n : 1) * sizeof(double);
    bc->y0 = malloc(sz);
    bc->yp0 = malloc(sz);
    bc->ys = malloc(sz);
    bc->yps = malloc(sz);
    /* the options as the crane program runs the scene (crane_setup.h): the Newton settings,
     * and the breakpoints, of which the harness keeps those inside (0, tend) */
    dae_options so;
    double *bk = NULL;
    int okb = crane_solver_setup(&s, c, &so, &bk, &err) == BG_OK;
    bc->newton_dgmax = so.newton_dgmax;
    bc->newton_jac_age = so.newton_jac_age;
    bc->newton_index2_scale_h = so.newton_index2_scale_h;
    int nb = so.nbreakpoints;
    bc->breakpoints = malloc((size_t)(nb > 0 ? nb : 1) * sizeof *bc->breakpoints);
    if (!okb || !bc->y0 || !bc->yp0 || !bc->ys || !bc->yps || !bc->breakpoints) {
        free(bk);
        snprintf(msg, msz, "out of memory");
        bench_case_free(bc);
        return BG_ERR_MEMORY;
    }
    for (int i = 0; i < nb; i++)
        if (bk[i] > 0 && bk[i] < tend) bc->breakpoints[bc->nbreakpoints++] = bk[i];
    free(bk);
    memcpy(bc->y0, bgr_y0(m), sz);
    memcpy(bc->yp0, bgr_yp0(m), sz);
    memcpy(bc->ys, bc->y0, sz);
    memcpy(bc->yps, bc->yp0, sz);
    bc->exclude_alg = 1;
    bc->atol_factor = s.rtol > 0 ? s.atol / s.rtol : 1.0;
    bc->score = crane_score;
    bc->drift = crane_drift;
    bc->large = 1;
    return 0;
}

int bench_crane_reference(bench_case *bc, double rtol_ref, int check_ida, char *msg, size_t msz)
{
    run_out a, b;
    if (bench_run_alloc(&a, bc->n) || bench_run_alloc(&b, bc->n)) {
        bench_run_free(&a);
        snprintf(msg, msz, "out of memory");
        return BG_ERR_MEMORY;
    }
    run_opts ro = {0};
    ro.rtol = rtol_ref;
    ro.max_steps = 5000000;
    bench_case b0 = *bc; /* the reference resolves every mode: no stability guard */
    b0.stability_guard = 0;
    bench_run(&b0, bench_solver_find("bgdae-klu"), &ro, &a);
    int r = a.status;
    if (r < 0) {
        snprintf(msg, msz, "reference run (bgdae-klu, rtol %g) failed: %s", rtol_ref, a.msg);
        snprintf(bc->ref_source, sizeof bc->ref_source, "none: %s", msg);
        goto done;
    }
    free(bc->yref);
    free(bc->ypref);
    bc->yref = a.y;
    bc->ypref = a.yp;
    a.y = a.yp = NULL;
    double atol = bc->atol_factor * rtol_ref;
    int len = snprintf(bc->ref_source, sizeof bc->ref_source,
                       "bgdae-klu at rtol %g, atol %g, no stability guard (%ld steps, %.1f s)",
                       rtol_ref, atol, a.steps, a.cpu);
    const solver_def *ida = bench_solver_find("ida-klu");
#ifndef BENCH_HAVE_IDA
    check_ida = 0;
#endif
    if (check_ida && ida) {
        bench_run(bc, ida, &ro, &b);
        if (b.status < 0) {
            snprintf(bc->ref_source + len, sizeof bc->ref_source - (size_t)len,
                     "; IDA-KLU at the same tolerance failed: %.200s", b.msg);
        } else {
            bp_score sc;
            bc->score(bc, b.y, b.yp, rtol_ref, atol, &sc);
            snprintf(bc->ref_source + len, sizeof bc->ref_source - (size_t)len,
                     "; IDA-KLU at the same tolerance (%ld steps) agrees to scd %.2f, mescd "
                     "%.2f, index-2 scd %.2f",
                     b.steps, sc.scd, sc.mescd, sc.scd_i2);
        }
    } else {
        snprintf(bc->ref_source + len, sizeof bc->ref_source - (size_t)len,
                 "; not checked against IDA in this run");
    }
done:
    bench_run_free(&a);
    bench_run_free(&b);
    return r;
}

/* ------------------------------------------------------------------- scaling ---- */

int bench_crane_scaling(const char *dir, FILE *rep, const int *elems, int nel, int skip, int steps,
                        double t_max, double cpu_cap, double *slope_n, double *slope_el)
{
    bench_file bf;
    FILE *f = bench_file_open(&bf, dir, "scaling.csv") == 0 ? bf.f : NULL;
    if (f)
        fprintf(f, "elements,unknowns,status,t_reached,steps_total,steps_timed,newton_per_step,"
                   "jac_per_step,fact_per_step,full_fact_per_step,cpu_total_s,cpu_per_step_s,wall_"
                   "per_step_s,"
                   "res_per_step_s,jac_per_step_s,linalg_per_step_s,other_per_step_s,message\n");
    fprintf(rep, "## Crane scaling series\n\n");
    fprintf(
        rep,
        "Paper scene (stability guard as the scene sets it, as the crane program runs it) from "
        "its static start (settled under gravity, as the paper scene runs; "
        "the settling is not timed: from the boom's geometric shape the start is violent, and "
        "from 256 elements on its Newton iterations failed on every third step, which measured "
        "the start rather than the mesh), bgdae-klu at rtol = atol = 1e-6: %d warm-up steps, "
        "then %d timed "
        "steps (fewer when they take more than %g s of CPU, at least 5; at most to t = %g "
        "s). CPU per step is what the slope is fitted to; the parts are shares of the wall "
        "time (the machine is shared: wall exceeds CPU when other work runs), residual and "
        "Jacobian of the callbacks, linear algebra by the solver's own timer (assembly of "
        "the Newton matrix, KLU factorization and solves), other = the rest (the "
        "integrator's own work); linear algebra per factorization: its CPU share divided by the "
        "factorizations (solves included). scaling.csv has the rows, the parts in wall "
        "seconds.\n\n",
        skip, steps, cpu_cap, t_max);
    fprintf(rep, "| elements | unknowns | steps timed | Newton/step | Jacobians/step | "
                 "factorizations/step (full) | CPU/step | wall/step | residual %% | Jacobian %% | "
                 "linear algebra %% | other %% | linear algebra per factorization | total CPU "
                 "|\n|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    double *xn = malloc((size_t)nel * sizeof *xn), *xe = malloc((size_t)nel * sizeof *xe);
    double *yt = malloc((size_t)nel * sizeof *yt);
    /* residual, Jacobian, linear algebra, other: CPU per step estimated as their share of the
     * wall time times the CPU per step; then CPU per Newton iteration, Newton iterations and
     * Jacobians per step */
    enum { NPART = 7 };
    double *part[NPART];
    int part_ok = 1;
    for (int k = 0; k < NPART; k++)
        part_ok &= (part[k] = malloc((size_t)nel * sizeof *part[k])) != NULL;
    int np = 0, fails = 0;
    for (int e = 0; e < nel && xn && xe && yt && part_ok; e++) {
        crane_scene s;
        crane_scene_default(&s);
        s.boom_elements = elems[e];
        s.static_start = 1;
        bench_case bc;
        char msg[BG_MESSAGE_SIZE] = "";
        double *y = NULL, *yp = NULL;
        dae_solver *sv = NULL;
        int r = bench_crane_case(&bc, &s, 1, t_max, "crane", msg, sizeof msg);
        long n_st = 0, n_nt = 0, n_jt = 0, n_ft = 0, n_ff = 0, tot_steps = 0;
        double cpu_tot = 0, cpu_t = 0, wall_t = 0, tr = 0, tj = 0, tl = 0, t = 0;
        if (r == 0) r = bench_case_start(&bc, 1e-6, msg, sizeof msg);
        if (r == 0) {
            bench_prof pw;
            dae_problem dp;
            bench_prof_wrap(&pw, &bc.dp, &dp);
            dae_options o; /* as the crane program, at 1e-6, to t_max, no breakpoints */
            crane_solver_setup(&s, NULL, &o, NULL, NULL);
            o.rtol = o.atol = 1e-6;
            o.t_stop = t_max;
            o.max_steps = 10000000;
            y = malloc((size_t)bc.n * sizeof *y);
            yp = malloc((size_t)bc.n * sizeof *yp);
            bg_error err = {0};
            double c0 = bench_cpu_now();
            sv = y && yp ? dae_create(&dp, &o, &err) : NULL;
            r = sv ? dae_init(sv, 0.0, bc.ys, bc.yps) : BG_ERR_MEMORY;
            if (!sv) snprintf(msg, sizeof msg, "%s", y && yp ? err.message : "out of memory");
            double c1 = -1, w1 = 0, r1 = 0, j1 = 0, l1 = 0;
            long s1 = 0, nt1 = 0, jt1 = 0, ft1 = 0, ff1 = 0;
            const dae_stats *st = sv ? dae_get_stats(sv) : NULL;
            while (r == 0 && t < t_max && st && st->steps < skip + steps) {
                if (c1 >= 0 && st->steps - s1 >= 5 && bench_cpu_now() - c1 > cpu_cap) break;
                r = dae_step(sv, t_max, &t, y, yp);
                if (r > 0) r = 0;
                if (st->steps == skip && c1 < 0) { /* start of the timed window */
                    c1 = bench_cpu_now();
                    w1 = bench_wall_now();
                    r1 = pw.t_res;
                    j1 = pw.t_jac;
                    l1 = st->t_linalg;
                    s1 = st->steps;
                    nt1 = st->newton_iters;
                    jt1 = st->jac_evals;
                    ft1 = st->factor_full + st->factor_refactor;
                    ff1 = st->factor_full;
                }
            }
            double c2 = bench_cpu_now(), w2 = bench_wall_now();
            if (r < 0) snprintf(msg, sizeof msg, "%s", dae_get_error(sv)->message);
            if (st) {
                tot_steps = st->steps;
                cpu_tot = c2 - c0;
                if (c1 >= 0 && st->steps > s1) {
                    n_st = st->steps - s1;
                    cpu_t = (c2 - c1) / (double)n_st;
                    wall_t = (w2 - w1) / (double)n_st;
                    tr = (pw.t_res - r1) / (double)n_st;
                    tj = (pw.t_jac - j1) / (double)n_st;
                    tl = (st->t_linalg - l1) / (double)n_st;
                    n_nt = st->newton_iters - nt1;
                    n_jt = st->jac_evals - jt1;
                    n_ft = st->factor_full + st->factor_refactor - ft1;
                    n_ff = st->factor_full - ff1;
                }
            }
        }
        if (r < 0) fails++;
        int n = bc.n;
        double other = wall_t - tr - tj - tl;
        if (n_st > 0 && wall_t > 0) {
            xn[np] = n;
            xe[np] = elems[e];
            yt[np] = cpu_t;
            part[0][np] = fmax(cpu_t * tr / wall_t, 1e-12);
            part[1][np] = fmax(cpu_t * tj / wall_t, 1e-12);
            part[2][np] = fmax(cpu_t * tl / wall_t, 1e-12);
            part[3][np] = fmax(cpu_t * other / wall_t, 1e-12);
            part[4][np] = n_nt > 0 ? cpu_t * (double)n_st / (double)n_nt : 1e-12;
            part[5][np] = fmax((double)n_nt / (double)n_st, 1e-12);
            part[6][np] = fmax((double)n_jt / (double)n_st, 1e-12);
            np++;
        }
        fprintf(stderr,
                "crane scaling: %4d elements, %6d unknowns: %s, %ld steps timed, %.3g ms "
                "CPU per step\n",
                elems[e], n, r < 0 ? "FAILED" : "ok", n_st, 1e3 * cpu_t);
        double d = n_st > 0 ? (double)n_st : 1;
        if (f)
            fprintf(f,
                    "%d,%d,%d,%.6g,%ld,%ld,%.3f,%.4f,%.4f,%.4f,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,"
                    "\"%s\"\n",
                    elems[e], n, r, t, tot_steps, n_st, n_nt / d, n_jt / d, n_ft / d, n_ff / d,
                    cpu_tot, cpu_t, wall_t, tr, tj, tl, other, r < 0 ? msg : "");
        if (n_st > 0)
            fprintf(
                rep,
                "| %d | %d | %ld | %.2f | %.3f | %.3f (%.3f) | %.3g ms | %.3g ms | %.0f | %.0f | "
                "%.0f | %.0f | %.3g ms | %.3g s |\n",
                elems[e], n, n_st, n_nt / d, n_jt / d, n_ft / d, n_ff / d, 1e3 * cpu_t,
                1e3 * wall_t, 100 * tr / wall_t, 100 * tj / wall_t, 100 * tl / wall_t,
                100 * other / wall_t, n_ft > 0 ? 1e3 * cpu_t * (tl / wall_t) / (n_ft / d) : 0,
                cpu_tot);
        else
            fprintf(rep, "| %d | %d | failed: %s | | | | | | | | | | | |\n", elems[e], n, msg);
        dae_free(&sv);
        free(y);
        free(yp);
        bench_case_free(&bc);
    }
    *slope_n = np >= 2 ? bench_loglog_slope(xn, yt, np) : NAN;
    *slope_el = np >= 2 ? bench_loglog_slope(xe, yt, np) : NAN;
    fprintf(rep,
            "\nLog-log least-squares slope of the CPU time per step: %.3f against the unknowns, "
            "%.3f against the elements (target: <= 1.1, at most linear growth).\n\n",
            *slope_n, *slope_el);
    if (np >= 2)
        fprintf(rep,
                "Slopes of the parts against the unknowns (each part's CPU per step estimated as "
                "its share of the wall time times the CPU per step): residual %.2f, Jacobian "
                "%.2f, linear algebra %.2f, the integrator's own work %.2f.\n\n",
                bench_loglog_slope(xn, part[0], np), bench_loglog_slope(xn, part[1], np),
                bench_loglog_slope(xn, part[2], np), bench_loglog_slope(xn, part[3], np));
    if (np >= 2)
        fprintf(rep,
                "Against the elements, the slope of the time per step is that of the CPU time per "
                "Newton iteration, %.3f, plus that of the Newton iterations per step, %.3f (the "
                "log-log fits add up); Jacobians per step %.3f. A finer boom is stiffer: its "
                "predictor misses the joint reactions by more, and each step takes more "
                "iterations, while one iteration (residual, solve and the integrator's vector "
                "work) grows linearly.\n\n",
                bench_loglog_slope(xe, part[4], np), bench_loglog_slope(xe, part[5], np),
                bench_loglog_slope(xe, part[6], np));
    if (f) bench_file_close(&bf);
    for (int k = 0; k < NPART; k++)
        free(part[k]);
    free(xn);
    free(xe);
    free(yt);
    return fails;
}

/* ------------------------------------------------------------- full horizon ---- */

typedef struct full_row {
    const char *solver;
    int ida, guard;
    double rtol;
    run_out r;
    bp_score sc;
} full_row;

static void full_csv_row(bench_file *bf, const full_row *w, double atol)
{
    if (!bf->f) return;
    char k[16] = ""; /* the highest order ours took (IDA reports its last only: left empty) */
    if (!w->ida && w->r.max_order > 0) snprintf(k, sizeof k, "%d", w->r.max_order);
    fprintf(bf->f, "%s,%g,%g,%d,%.9g,%ld,%ld,%ld,%ld,%ld,%.6g,%.3f,%.3f,%.3f,%s,\"%s\"\n",
            w->solver, w->rtol, atol, w->r.status, w->r.t, w->r.steps, w->r.rejected, w->r.newton,
            w->r.jac, w->r.res, w->r.cpu, w->sc.scd, w->sc.mescd, w->sc.scd_i2, k,
            w->r.status < 0 ? w->r.msg : "");
    bench_file_flush(bf);
}

/* The CPU of solver name at accuracy scd: log CPU interpolated linearly in scd between its two
 * completed runs that bracket scd; *above = 1 (and its loosest run's CPU) when that run is
 * already more accurate. NAN when none brackets it. */
static double cpu_at(const full_row *rows, int nrow, const char *name, double scd, int *above)
{
    const full_row *lo = NULL, *hi = NULL, *loosest = NULL;
    *above = 0;
    for (int i = 0; i < nrow; i++) {
        const full_row *w = &rows[i];
        if (strcmp(w->solver, name) || w->r.status < 0 || !isfinite(w->sc.scd) || w->r.cpu <= 0)
            continue;
        if (!loosest || w->rtol > loosest->rtol) loosest = w;
        if (w->sc.scd <= scd && (!lo || w->sc.scd > lo->sc.scd)) lo = w;
        if (w->sc.scd >= scd && (!hi || w->sc.scd < hi->sc.scd)) hi = w;
    }
    if (lo && hi) {
        if (hi->sc.scd == lo->sc.scd) return lo->r.cpu;
        double f = (scd - lo->sc.scd) / (hi->sc.scd - lo->sc.scd);
        return exp(log(lo->r.cpu) + f * (log(hi->r.cpu) - log(lo->r.cpu)));
    }
    if (hi && loosest && loosest->sc.scd >= scd) {
        *above = 1;
        return loosest->r.cpu;
    }
    return NAN;
}

/* CPU ratios of ours (BDF, MEBDF) to IDA at the accuracy of each completed IDA run. */
static void equal_accuracy(FILE *rep, const full_row *rows, int nrow)
{
    static const char *const ours[] = {"bgdae-klu", "bgdae-mebdf", "bgdae-mebdf4"};
    int any = 0;
    for (int i = 0; i < nrow; i++) {
        const full_row *id = &rows[i];
        if (!id->ida || id->r.status < 0 || !isfinite(id->sc.scd) || id->r.cpu <= 0) continue;
        if (!any++)
            fprintf(rep, "CPU at equal accuracy, ours / IDA at the scd of each completed IDA run "
                         "(log CPU interpolated in scd between the two runs of ours around it; "
                         "\"<=\": ours' loosest run is already more accurate, its CPU used):\n\n");
        fprintf(rep, "- IDA at rtol %g, scd %.2f, %.2f s:", id->rtol, id->sc.scd, id->r.cpu);
        for (int k = 0; k < 3; k++) {
            int above = 0;
            double c = cpu_at(rows, nrow, ours[k], id->sc.scd, &above);
            if (isfinite(c))
                fprintf(rep, " %s %s%.2f", ours[k], above ? "<= " : "", c / id->r.cpu);
            else
                fprintf(rep, " %s not reached", ours[k]);
            fprintf(rep, k < 2 ? ";" : "\n");
        }
    }
    if (any) fprintf(rep, "\n");
}

int bench_crane_full(const char *dir, const char *csv, FILE *rep, const crane_scene *s,
                     const char *scene_name, const bench_full_opts *fo)
{
    const double *rtols = fo->rtols, rtol_ref = fo->rtol_ref;
    int nr = fo->nr, reps = fo->reps > 0 ? fo->reps : 1;
    char msg[BG_MESSAGE_SIZE] = "";
    bench_file bf;
    FILE *f = bench_file_open(&bf, dir, csv) == 0 ? bf.f : NULL;
    if (f)
        fprintf(f, "solver,rtol,atol,status,t_reached,steps,rejected,newton,jacobians,res_evals,"
                   "cpu_s,scd,mescd,scd_index2,max_order,message\n");
    fprintf(rep, "## Crane over its full %g s against IDA: %s\n\n", s->t_end, scene_name);
    bench_case bc;
    int fails = 0;
    int r = bench_crane_case(&bc, s, s->static_start, s->t_end, "crane_full", msg, sizeof msg);
    if (r == 0 && bench_case_start(&bc, 1e-10, msg, sizeof msg) != 0)
        fprintf(stderr, "crane full: no consistent start (the given values are used): %s\n", msg);
    if (r != 0) {
        fprintf(stderr, "crane full: %s\n", msg);
        fprintf(rep, "Not run: %s.\n\n", msg);
        if (f) bench_file_close(&bf);
        return 1;
    }
    const solver_def *ours = bench_solver_find("bgdae-klu");
#ifdef BENCH_HAVE_IDA
    const solver_def *ida = bench_solver_find("ida-klu");
#else
    const solver_def *ida = NULL;
#endif
    /* the reference */
    full_row ref;
    memset(&ref, 0, sizeof ref);
    ref.solver = "bgdae-klu (reference)";
    ref.rtol = rtol_ref;
    double c0 = bench_cpu_now();
    fprintf(stderr, "crane full: %s, reference: bgdae-klu at rtol %g over %g s\n", scene_name,
            rtol_ref, s->t_end);
    if (bench_run_alloc(&ref.r, bc.n) != 0) {
        bench_case_free(&bc);
        if (f) bench_file_close(&bf);
        return 1;
    }
    run_opts ro = {0};
    ro.rtol = rtol_ref;
    ro.max_steps = 100000000;
    bench_run(&bc, ours, &ro, &ref.r);
    ref.sc.scd = ref.sc.mescd = ref.sc.scd_i2 = NAN;
    full_csv_row(&bf, &ref, bc.atol_factor * rtol_ref);
    fprintf(stderr, "crane full: reference %s, %ld steps, %.1f s CPU\n",
            ref.r.status < 0 ? ref.r.msg : "ok", ref.r.steps, ref.r.cpu);
    if (ref.r.status < 0) {
        fails++;
    } else {
        bc.yref = malloc((size_t)bc.n * sizeof *bc.yref);
        bc.ypref = malloc((size_t)bc.n * sizeof *bc.ypref);
        if (bc.yref && bc.ypref) {
            memcpy(bc.yref, ref.r.y, (size_t)bc.n * sizeof *bc.yref);
            memcpy(bc.ypref, ref.r.yp, (size_t)bc.n * sizeof *bc.ypref);
        }
    }
    /* ours without the stability guard (the hard case: every mode resolved), ours with it when
     * the scene asks for it (as the crane program runs it), IDA */
    const solver_def *mebdf = bench_solver_find("bgdae-mebdf"),
                     *mebdf4 = bench_solver_find("bgdae-mebdf4");
    full_row *rows = calloc((size_t)(5 * nr + 1), sizeof *rows);
    int nrow = 0;
    for (int k = 0; k < nr && rows; k++)
        for (int q = 0; q < 5; q++) {
            const solver_def *sd = q < 2 ? ours : q == 2 ? ida : q == 3 ? mebdf : mebdf4;
            if (!sd || (q == 1 && !s->stability_guard)) continue;
            full_row *w = &rows[nrow];
            w->solver = q == 0 ? "bgdae-klu" : q == 1 ? "bgdae-klu+guard" : sd->name;
            w->ida = q == 2;
            w->guard = q == 1;
            w->rtol = rtols[k];
            if (bench_run_alloc(&w->r, bc.n) != 0) continue;
            nrow++;
            run_opts o = {0};
            o.rtol = rtols[k];
            o.max_steps = 100000000;
            /* IDA: in each segment between breakpoints at most as many steps as ours took over
             * the whole run at this tolerance (at least 10 000): with KLU's default pivot
             * tolerance (--ida-klu-pivot-tol 0.001) it was held on the damped scene from rtol
             * 1e-5 on at h = 3.5e-6 s (millions of steps over the 20 s, 2.3 ms of CPU each) */
            for (int j = 0; q == 2 && j < nrow - 1; j++)
                if (!strcmp(rows[j].solver, "bgdae-klu") && rows[j].rtol == rtols[k] &&
                    rows[j].r.status >= 0)
                    o.max_steps = rows[j].r.steps > 10000 ? rows[j].r.steps : 10000;
            o.ida_consistent_restart = 1;
            o.ida_max_newton = BENCH_IDA_MAX_NEWTON;
            o.ida_klu_tol = fo->ida_klu_tol;
            o.ida_scalar_atol = fo->ida_scalar_atol;
            o.ida_newton_diag = fo->ida_newton_diag;
            o.ida_index2_h = fo->ida_index2_h;
            if (q < 2) o.max_order = fo->max_order;
            bench_case bg = bc;
            bg.stability_guard = w->guard;
            double cpus[99];
            int m = 0;
            for (int k2 = 0; k2 < reps && (k2 == 0 || w->r.status >= 0); k2++) {
                bench_run(&bg, sd, &o, &w->r);
                cpus[m++] = w->r.cpu;
            }
            w->r.cpu = bench_median(cpus, m);
            double atol = bc.atol_factor * rtols[k];
            if (w->r.status >= 0 && bc.yref)
                bc.score(&bc, w->r.y, w->r.yp, rtols[k], atol, &w->sc);
            else
                w->sc.scd = w->sc.mescd = w->sc.scd_i2 = NAN;
            if (w->r.status < 0 && !sd->ida) fails++;
            full_csv_row(&bf, w, atol);
            fprintf(stderr,
                    "crane full: %-16s rtol %-6g %s t %.4g, %ld steps, %.1f s CPU, scd %.2f, "
                    "mescd %.2f%s%s\n",
                    w->solver, rtols[k], w->r.status < 0 ? "FAIL" : "ok", w->r.t, w->r.steps,
                    w->r.cpu, w->sc.scd, w->sc.mescd, w->r.status < 0 ? ": " : "",
                    w->r.status < 0 ? w->r.msg : "");
            bench_run_free(&w->r);
        }
    double total = bench_cpu_now() - c0;
    if (f) bench_file_close(&bf);
    /* the report */
    char order_note[96] = "";
    if (fo->max_order > 0)
        snprintf(order_note, sizeof order_note,
                 ", at orders up to %d (--crane-full-max-order; the reference's up to 5)",
                 fo->max_order);
    fprintf(rep,
            "Scene %s (%d boom elements, %d unknowns) over [0, %g] s from its %s start, %d "
            "breakpoints; atol = %g rtol at each tolerance below (times each unknown's nominal "
            "magnitude, for ours and, %s, for IDA); %d run%s each, CPU the median (%s): "
            "bgdae-klu without the stability guard (every mode resolved: the hard case)%s%s, "
            "IDA-KLU, bgdae-mebdf (Cash's modified extended BDF in our code, orders up to 8, no "
            "guard) and bgdae-mebdf4 (orders up to 4, where it is A-stable). IDA-KLU, its steps "
            "in each segment between breakpoints capped at those ours took over the run (at least "
            "10 000), has the "
            "Jacobian of ours, its algebraic unknowns out of the error test (IDASetId, "
            "IDASetSuppressAlg), at most %d Newton iterations per attempt (IDASetMaxNonlinIters; "
            "ours takes up to that many) and KLU with partial pivoting (pivot tolerance %g; "
            "with KLU's default 0.001 its Newton iteration diverged on the damped scene from "
            "rtol 1e-5 on and it stalled at h = 3.5e-6 s) and our fallback: a refactorization "
            "that meets a zero pivot is redone with fresh pivoting (without it, IDA stopped on "
            "the damped scene at 0.55 ms at every tolerance; bench_util.h, bench_ida_klu). "
            "Reference: bgdae-klu at rtol %g without the guard: %s (%ld steps, %.1f s "
            "CPU). IDA-KLU is restarted "
            "at every breakpoint from values made consistent by our dae_consistent_init (as our "
            "solver restarts there; IDA's own y' before a corner of the reference belongs to "
            "the input before it), its CPU time including that, with the last step before the "
            "breakpoint as its first step (from its own first step its corrector failed down to "
            "h = 1e-21 at t = 2 s from rtol 1e-8 on; from its own values it fails at 2 s, "
            "measured at rtol 1e-4, 1e-6 and 1e-8). scd over the crane's outputs "
            "(angle, rate, tip and load positions, rope force, line pressures), mescd over the "
            "differential unknowns, both against the reference at %g s. Total CPU of the "
            "series %.0f s.\n\n",
            scene_name, s->boom_elements, bc.n, s->t_end,
            s->static_start ? "static-equilibrium" : "geometric", bc.nbreakpoints,
            bc.atol_factor,
            fo->ida_scalar_atol ? "not (--ida-scalar-atol)"
            : fo->ida_index2_h  ? "its index-2 weights times |h| (--ida-index2-h)"
                                : "as IDASVtolerances",
            reps, reps > 1 ? "s" : "", csv, order_note,
            s->stability_guard ? ", bgdae-klu with the guard as the scene asks (stability_guard "
                                 "= true: order 2 where fast modes hold orders 3..5)"
                               : "",
            BENCH_IDA_MAX_NEWTON, fo->ida_klu_tol > 0 ? fo->ida_klu_tol : BENCH_IDA_KLU_TOL,
            rtol_ref, ref.r.status < 0 ? ref.r.msg : "completed", ref.r.steps,
            ref.r.cpu, s->t_end, total);
    fprintf(rep, "MORE STEPS: more than 5 %% more steps than the same solver took at a tighter "
                 "tolerance.\n\n");
    fprintf(rep, "| rtol | solver | status | t reached | steps | rejected | Newton | Jacobians | "
                 "CPU s | scd | mescd | steps ours / IDA | CPU ours / IDA | flag |\n"
                 "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    for (int i = 0; i < nrow; i++) {
        const full_row *w = &rows[i];
        char ratio[64] = " | ";
        const full_row *id = NULL;
        for (int j = 0; j < nrow; j++)
            if (rows[j].ida && rows[j].rtol == w->rtol) id = &rows[j];
        if (!w->ida && id && id->r.status >= 0 && w->r.status >= 0 && id->r.steps > 0 &&
            id->r.cpu > 0)
            snprintf(ratio, sizeof ratio, "%.2f | %.2f", (double)w->r.steps / id->r.steps,
                     w->r.cpu / id->r.cpu);
        char flag[96] = "";
        double worst = 1.05;
        for (int j = 0; j < nrow; j++) {
            const full_row *v = &rows[j];
            if (strcmp(v->solver, w->solver) || !(v->rtol < w->rtol) || v->r.status < 0 ||
                w->r.status < 0 || v->r.steps <= 0)
                continue;
            double q = (double)w->r.steps / (double)v->r.steps;
            if (q > worst) {
                worst = q;
                snprintf(flag, sizeof flag, "MORE STEPS than at %g (+%.0f %%)", v->rtol,
                         100 * (q - 1));
            }
        }
        fprintf(rep,
                "| %g | %s | %s | %.4g | %ld | %ld | %ld | %ld | %.1f | %.2f | %.2f | %s | %s |\n",
                w->rtol, w->solver, w->r.status < 0 ? "FAIL" : "ok", w->r.t, w->r.steps,
                w->r.rejected, w->r.newton, w->r.jac, w->r.cpu, w->sc.scd, w->sc.mescd, ratio,
                flag);
    }
    fprintf(rep, "\n");
    equal_accuracy(rep, rows, nrow);
    for (int i = 0; i < nrow; i++)
        if (rows[i].ida && rows[i].r.ls_fallback > 0)
            fprintf(rep, "- %s at rtol %g: %ld refactorizations redone with fresh pivots\n",
                    rows[i].solver, rows[i].rtol, rows[i].r.ls_fallback);
    for (int i = 0; i < nrow; i++)
        if (rows[i].r.status < 0)
            fprintf(rep, "- %s at rtol %g stopped at t = %.9g: %s\n", rows[i].solver,
                    rows[i].rtol, rows[i].r.t, rows[i].r.msg);
    for (int i = 0; i < nrow; i++) {
        const run_out *o = &rows[i].r;
        if (!rows[i].ida || o->nd_solves <= 0) continue;
        int a = o->nd_argmax >= 0 && o->nd_argmax < bc.n ? o->nd_argmax : 0;
        fprintf(rep,
                "- %s at rtol %g, its Newton corrections weighed as its test weighs them: %ld "
                "corrections, %ld convergence failures, %ld error-test failures; the index-2 "
                "unknowns hold more than half of the norm^2 in %ld, the test ||x|| < 0.33 fails "
                "only by them in %ld; largest WRMS norm of the differential, index-1 and index-2 "
                "parts %.3g, %.3g, %.3g, of the whole %.3g (its largest entry: %s); last step "
                "%.3g s at order %d\n",
                rows[i].solver, rows[i].rtol, o->nd_solves, o->conv_fail, o->rejected,
                o->nd_i2_dominant, o->nd_pass_without_i2, o->nd_max[0], o->nd_max[1],
                o->nd_max[2], o->nd_norm_max, bc.dp.names ? bc.dp.names[a] : "?", o->h_last,
                o->order_last);
    }
    fprintf(rep, "\n");
    free(rows);
    bench_run_free(&ref.r);
    bench_case_free(&bc);
    return fails;
}
