/* The crane as a model file (crane/models/paper.yaml, paper-undamped.yaml) against the C crane
 * of the same scene (crane_build of crane/scenes/paper.ini, paper-undamped.ini):
 *   - the same model: as many unknowns and equations, as many differential, index-1 and
 *     index-2 unknowns, the same nonzeros of dF/dy and dF/dy' (bgr_get_stats), every unknown
 *     of the C crane found by its name in the file's model at the same index (the file lists
 *     the parts and bonds in crane_build's order, and the reader numbers the bonds in the
 *     file's order) with the same nominal magnitude;
 *   - the static start: the ties' unstretched length found by the file's `trim:` against the
 *     C crane's (crane_static_start: the same trim, bg_trim.h), the tip's radius, the PID's
 *     holding integral the file states against the one the C crane finds, and the two start
 *     states to the last bit;
 *   - the outputs: the file's expressions evaluated at the C crane's state (mapped by name)
 *     against crane_outputs, column by column (tip_defl_1 and alpha_err aside, see
 *     docs/crane.md "The crane as a model file");
 *   - the file's model built with the C crane's tie length and run from the C crane's start:
 *     the C crane's run exactly (steps, Newton iterations, Jacobians, rejections): the same DAE
 *     to the last bit;
 *   - a run over the scene's 20 s with each model's own solver options (the file's by
 *     mdl_dae_options, the C crane's by crane_solver_setup): the same steps, Newton iterations
 *     and Jacobians (the target was within 1 %; see main), and for the
 *     file's run the acceptance figures of test_crane_paper.c (mean tip radius within
 *     0.5 %, theta(12 s) within 0.05 rad of 5 rad, |omega - omega_r| <= 0.05 rad/s throughout
 *     and |omega| <= 2 % of the plateau rate from 13 s on, the line pressures in 0 .. 35 MPa).
 * The figures of both runs are printed for the table of docs/crane.md. About 30 s of computing
 * (paper-undamped's runs: 6 s each in a debug build). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "crane_model.h"
#include "crane_scene.h"
#include "crane_setup.h"
#include "crane_static.h"
#include "mdl_model.h"
#include "tap.h"

#ifndef CRANE_SCENES_DIR
#define CRANE_SCENES_DIR "crane/scenes"
#endif
#ifndef CRANE_MODELS_DIR
#define CRANE_MODELS_DIR "crane/models"
#endif

/* What a run samples every 0.01 s, and the figures it gives. */
typedef struct sample {
    double theta, omega, omega_ref, radius, p_high, p_low;
} sample;

typedef struct figures {
    double mean_r, rmin, rmax, th12, werr, wrest, threst, pmin, pmax, seconds;
    dae_stats st;
    int ok;
} figures;

typedef int (*sampler)(void *ctx, double t, const double *y, const double *yp, sample *s);

/* the C crane's outputs (crane_outputs.c) */
static int sample_c(void *ctx, double t, const double *y, const double *yp, sample *s)
{
    const crane *c = ctx;
    const double *A = crane_get_scene(c)->joint_A;
    double o[CRANE_NOUT];
    crane_outputs(c, t, y, yp, o);
    *s = (sample){o[1], o[3], o[4], hypot(o[7] - A[0], o[8] - A[1]), o[17], o[18]};
    return 0;
}

/* the file's outputs by column name */
typedef struct file_ctx {
    const mdl_model *mm;
    int nout, col[6];
    double *out;
} file_ctx;

static int col_of(const mdl_model *mm, const char *name)
{
    for (int i = 0; i < mdl_noutputs(mm); i++)
        if (!strcmp(mdl_output_name(mm, i), name)) return i;
    return -1;
}

static int sample_file(void *ctx, double t, const double *y, const double *yp, sample *s)
{
    (void)yp;
    file_ctx *f = ctx;
    bg_error e = {0};
    if (mdl_outputs(f->mm, t, y, f->out, &e) != BG_OK) {
        tap_diag("outputs at t = %g: %s", t, e.message);
        return -1;
    }
    *s = (sample){f->out[f->col[0]], f->out[f->col[1]], f->out[f->col[2]],
                  f->out[f->col[3]], f->out[f->col[4]], f->out[f->col[5]]};
    return 0;
}

/* The run from the model's initial values over [0, t_end] with the options o, sampled every
 * 0.01 s (dae_solve_to interpolates: the steps are the solver's own), with the acceptance
 * figures of test_crane_paper.c. */
static void run(dae_problem *p, const dae_options *o, const double *y0, const double *yp0,
                sampler fn, void *ctx, const crane_scene *sc, figures *F)
{
    const double dt = 0.01, t3 = sc->ref_t3;
    const double theta_end = 0.5 * sc->ref_rate * sc->ref_t1 + sc->ref_rate * (sc->ref_t2 - sc->ref_t1) +
                             0.5 * sc->ref_rate * (sc->ref_t3 - sc->ref_t2);
    memset(F, 0, sizeof *F);
    F->rmin = F->pmin = INFINITY;
    F->rmax = F->pmax = -INFINITY;
    F->th12 = NAN;
    bg_error e = {0};
    struct timespec a, b;
    clock_gettime(CLOCK_MONOTONIC, &a);
    dae_solver *s = dae_create(p, o, &e);
    double *y = malloc(2 * (size_t)p->n * sizeof *y), *yp = y ? y + p->n : NULL;
    if (!s || !y || dae_init(s, 0, y0, yp0) != BG_OK || dae_consistent_init(s) != BG_OK ||
        dae_dense(s, 0.0, y, yp) != BG_OK) {
        tap_diag("run: start: %s", s ? dae_get_error(s)->message : e.message);
        dae_free(&s);
        free(y);
        return;
    }
    double sum = 0;
    long nr = 0, last = lround(sc->t_end / dt);
    int ok = 1;
    for (long k = 0; k <= last && ok; k++) {
        double t = k * dt, tr = 0;
        sample sm;
        if (k > 0 && dae_solve_to(s, t, &tr, y, yp) < 0) {
            tap_diag("run: t = %g: %s", t, dae_get_error(s)->message);
            ok = 0;
            break;
        }
        if (fn(ctx, t, y, yp, &sm) != 0) {
            ok = 0;
            break;
        }
        sum += sm.radius, nr++;
        F->rmin = fmin(F->rmin, sm.radius), F->rmax = fmax(F->rmax, sm.radius);
        F->werr = fmax(F->werr, fabs(sm.omega - sm.omega_ref));
        if (fabs(t - t3) < 0.5 * dt) F->th12 = sm.theta;
        if (t >= t3 + 1) {
            F->wrest = fmax(F->wrest, fabs(sm.omega));
            F->threst = fmax(F->threst, fabs(sm.theta - theta_end));
        }
        F->pmin = fmin(F->pmin, fmin(sm.p_high, sm.p_low));
        F->pmax = fmax(F->pmax, fmax(sm.p_high, sm.p_low));
    }
    clock_gettime(CLOCK_MONOTONIC, &b);
    F->seconds = (double)(b.tv_sec - a.tv_sec) + 1e-9 * (double)(b.tv_nsec - a.tv_nsec);
    F->mean_r = nr ? sum / (double)nr : NAN;
    F->st = *dae_get_stats(s);
    F->ok = ok;
    dae_free(&s);
    free(y);
}

/* the file model's unknown of the C crane's unknown i (the C crane's drive lies in its
 * component "hydraulics", the file's at the top level), -1 if none */
static int file_var(const bgr_model *cm, const bgr_model *fm, int i)
{
    const char *nm = bgr_var_name(cm, i);
    int j = bgr_find_var(fm, nm);
    const char *h = strstr(nm, "/hydraulics/");
    if (j < 0 && h) {
        char t[256];
        snprintf(t, sizeof t, "%.*s/%s", (int)(h - nm), nm, h + strlen("/hydraulics/"));
        j = bgr_find_var(fm, t);
    }
    return j;
}

static void compare(const char *label, const char *scene, const char *file)
{
    bg_error e = {0};
    crane_scene sc;
    if (crane_scene_load(&sc, scene, &e) != BG_OK) {
        tap_ok(0, "%s: the scene loads: %s", label, e.message);
        return;
    }
    crane *c = crane_build(&sc, &e);
    mdl_model *mm = mdl_load(file, NULL, 0, &e);
    tap_ok(c && mm, "%s: the C crane and %s load (%s)", label, file, c && mm ? "ok" : e.message);
    if (!c || !mm) {
        crane_free(&c);
        mdl_free(&mm);
        return;
    }

    /* ---- the same model ---- */
    bgr_stats a, b;
    bgr_get_stats(crane_model(c), &a);
    bgr_get_stats(mdl_bgr(mm), &b);
    tap_ok(a.equations == b.equations && bgr_n(crane_model(c)) == bgr_n(mdl_bgr(mm)),
           "%s: %d unknowns and equations (C crane %d)", label, b.equations, a.equations);
    tap_ok(a.differential == b.differential && a.algebraic == b.algebraic && a.index2 == b.index2,
           "%s: differential / index-1 / index-2: %d / %d / %d (C crane %d / %d / %d)", label,
           b.differential, b.algebraic, b.index2, a.differential, a.algebraic, a.index2);
    tap_ok(a.nnz_dy == b.nnz_dy && a.nnz_dyp == b.nnz_dyp,
           "%s: nnz dF/dy %d, dF/dy' %d (C crane %d, %d)", label, b.nnz_dy, b.nnz_dyp, a.nnz_dy,
           a.nnz_dyp);
    tap_diag("%s: elements %d, bonds %d (C crane %d, %d)", label, b.elements, b.bonds, a.elements,
             a.bonds);

    /* ---- the static start: the C crane's (crane_static_start), the file's (mdl_static with
     * its trim), the static solver's options as crane_static_start sets them ---- */
    crane_start_report rep;
    int rc = crane_static_start(c, &rep, &e);
    tap_ok(rc == BG_OK, "%s: the C crane's static start (%s)", label, rc == BG_OK ? "ok" : e.message);
    dae_static_options so;
    dae_static_options_default(&so);
    so.max_steps = 150;
    mdl_trim_report tr;
    rc = mdl_static(&mm, &so, &tr, &e);
    tap_ok(rc == BG_OK && tr.trimmed,
           "%s: the file's static start with its trim (%s): %d static solves (C crane %d)", label,
           rc == BG_OK ? "ok" : e.message, tr.solves, rep.solves);
    if (rc != BG_OK) {
        crane_free(&c);
        mdl_free(&mm);
        return;
    }
    bgr_model *cm = crane_model(c), *fm = mdl_bgr(mm);
    const int n = bgr_n(cm);
    tap_close(tr.value, rep.tie_L0, 0, 1e-7,
              "%s: the ties' unstretched length %.12f m (C crane %.12f m, geometric %.6f m)", label,
              tr.value, rep.tie_L0, rep.tie_L0_geometric);
    tap_close(tr.achieved, sc.boom_tip_radius, 0, 1e-8,
              "%s: the tip's radius at the start %.10f m (C crane %.10f m)", label, tr.achieved,
              rep.radius);
    /* the start states by name, and the nominal magnitudes */
    int *map = malloc((size_t)n * sizeof *map), unmatched = 0, nominal_diff = 0, worst = -1,
        moved = 0;
    double dmax = 0;
    const double *yc = bgr_y0(cm), *yf = bgr_y0(fm), *nc = bgr_nominals(cm), *nf = bgr_nominals(fm);
    for (int i = 0; map && i < n; i++) {
        int j = map[i] = file_var(cm, fm, i);
        if (j < 0) {
            unmatched++;
            continue;
        }
        moved += j != i;
        /* the ties' stretch vectors: their trimmed length, equal to the trim's tolerance */
        nominal_diff += fabs(nc[i] - nf[j]) > 1e-9 * nc[i];
        double d = fabs(yc[i] - yf[j]) / nc[i];
        if (d > dmax) dmax = d, worst = i;
    }
    tap_ok(map && !unmatched, "%s: every unknown of the C crane is the file model's by name "
           "(%d not)", label, unmatched);
    tap_ok(map && !moved, "%s: and at the same index (%d elsewhere)", label, moved);
    tap_ok(!nominal_diff, "%s: with the same nominal magnitude (%d differ)", label, nominal_diff);
    double I0f = NAN;
    mdl_parameter(mm, "pid_integral0", &I0f);
    tap_ok(I0f == rep.pid_integral0, "%s: the PID's integral that holds the platform %.17g (the "
           "file's pid_integral0 %.17g)", label, rep.pid_integral0, I0f);
    tap_ok(dmax == 0, "%s: the start states agree to the last bit (largest difference %.3g "
           "nominal magnitudes, at %s)", label, dmax, worst >= 0 ? bgr_var_name(cm, worst) : "-");

    /* ---- the runs, each with its own options ---- */
    dae_problem pc, pf;
    dae_options oc, of;
    double *bc = NULL, *bf = NULL;
    crane_dae_problem(c, &pc);
    mdl_dae_problem(mm, &pf);
    rc = crane_solver_setup(&sc, c, &oc, &bc, &e);
    if (rc == BG_OK) rc = mdl_dae_options(mm, &of, &bf);
    /* max_order 0 is BDF's largest, 5 (dae_options) */
    int moc = oc.max_order ? oc.max_order : 5, mof = of.max_order ? of.max_order : 5;
    tap_ok(rc == BG_OK && oc.nbreakpoints == of.nbreakpoints && oc.rtol == of.rtol &&
               oc.atol == of.atol && oc.t_stop == of.t_stop &&
               oc.stability_guard == of.stability_guard && oc.newton_dgmax == of.newton_dgmax &&
               oc.newton_jac_age == of.newton_jac_age &&
               oc.newton_index2_scale_h == of.newton_index2_scale_h &&
               oc.exclude_alg == of.exclude_alg && moc == mof,
           "%s: the same solver options from the scene and the file (%d breakpoints)", label,
           of.nbreakpoints);
    oc.max_steps = of.max_steps = 10000000;
    file_ctx fc = {mm, mdl_noutputs(mm), {0}, malloc((size_t)mdl_noutputs(mm) * sizeof(double))};
    static const char *const cols[] = {"theta", "omega", "omega_ref", "tip_radius", "p_high",
                                       "p_low"};
    int cols_ok = fc.out != NULL;
    for (int k = 0; k < 6; k++)
        cols_ok &= (fc.col[k] = col_of(mm, cols[k])) >= 0;
    tap_ok(cols_ok, "%s: the file's outputs name theta, omega, omega_ref, tip_radius, p_high, "
           "p_low", label);
    figures Fc, Ff;
    run(&pc, &oc, bgr_y0(cm), bgr_yp0(cm), sample_c, c, &sc, &Fc);
    if (cols_ok) run(&pf, &of, bgr_y0(fm), bgr_yp0(fm), sample_file, &fc, &sc, &Ff);
    tap_ok(Fc.ok && cols_ok && Ff.ok, "%s: both runs reach %g s", label, sc.t_end);
    tap_ok(Ff.st.steps == Fc.st.steps && Ff.st.newton_iters == Fc.st.newton_iters &&
               Ff.st.jac_evals == Fc.st.jac_evals,
           "%s: the C crane's run: %ld steps, %ld Newton iterations, %ld Jacobians (C crane %ld, "
           "%ld, %ld)", label, Ff.st.steps, Ff.st.newton_iters, Ff.st.jac_evals, Fc.st.steps,
           Fc.st.newton_iters, Fc.st.jac_evals);
    /* the acceptance figures of test_crane_paper.c for the file's run */
    const double R = sc.boom_tip_radius, wr = sc.ref_rate;
    tap_ok(fabs(Ff.mean_r - R) <= 0.005 * R, "%s: mean tip radius %.4f m (C crane %.4f m)", label,
           Ff.mean_r, Fc.mean_r);
    tap_ok(fabs(Ff.th12 - 5) <= 0.05, "%s: theta(12 s) = %.4f rad (C crane %.4f rad)", label,
           Ff.th12, Fc.th12);
    tap_ok(Ff.werr <= 0.05, "%s: |omega - omega_r| <= %.4f rad/s throughout (C crane %.4f)",
           label, Ff.werr, Fc.werr);
    tap_ok(Ff.wrest <= 0.02 * wr && Ff.threst <= 0.05,
           "%s: from 13 s on |omega - omega_r| <= %.5f rad/s, theta within %.4f rad of 5 (C crane "
           "%.5f, %.4f)", label, Ff.wrest, Ff.threst, Fc.wrest, Fc.threst);
    tap_ok(Ff.pmin > 0 && Ff.pmax < 35e6,
           "%s: line pressures %.3f .. %.3f MPa (C crane %.3f .. %.3f)", label, Ff.pmin / 1e6,
           Ff.pmax / 1e6, Fc.pmin / 1e6, Fc.pmax / 1e6);
    /* the C crane again from its start with every start value moved by two units in the last
     * place: how much rounding alone moves its step count */
    {
        figures Fp;
        double *y = malloc((size_t)n * sizeof *y);
        for (int i = 0; y && i < n; i++)
            y[i] = yc[i] * (1 + 4.4e-16);
        if (y) run(&pc, &oc, y, bgr_yp0(cm), sample_c, c, &sc, &Fp);
        tap_diag("%s: the C crane from its start moved by 2 ulp: %ld steps, %ld Newton iterations",
                 label, Fp.st.steps, Fp.st.newton_iters);
        free(y);
    }
    /* a model of the file loaded again with the C crane's tie length, run from the C crane's
     * start (mapped by name): the same DAE gives the same run to the last bit */
    char L0[64];
    snprintf(L0, sizeof L0, "%.17g", rep.tie_L0);
    mdl_set trimmed = {"tie_L0", L0};
    mdl_model *m2 = map && !unmatched ? mdl_load(file, &trimmed, 1, &e) : NULL;
    if (m2) {
        figures Fm;
        dae_problem p2;
        dae_options o2;
        double *b2 = NULL, *y = bgr_y0(mdl_bgr(m2)), *yp = bgr_yp0(mdl_bgr(m2));
        for (int i = 0; i < n; i++)
            y[map[i]] = yc[i], yp[map[i]] = bgr_yp0(cm)[i];
        file_ctx f2 = fc;
        f2.mm = m2;
        mdl_dae_problem(m2, &p2);
        mdl_dae_options(m2, &o2, &b2);
        o2.max_steps = 10000000;
        run(&p2, &o2, y, yp, sample_file, &f2, &sc, &Fm);
        tap_ok(Fm.ok && Fm.st.steps == Fc.st.steps && Fm.st.newton_iters == Fc.st.newton_iters &&
                   Fm.st.jac_evals == Fc.st.jac_evals &&
                   Fm.st.rejected_error == Fc.st.rejected_error &&
                   Fm.st.newton_fails == Fc.st.newton_fails,
               "%s: the file's model with the C crane's tie length from the C crane's start: "
               "%ld steps, %ld Newton iterations, %ld Jacobians (C crane %ld, %ld, %ld)", label,
               Fm.st.steps, Fm.st.newton_iters, Fm.st.jac_evals, Fc.st.steps,
               Fc.st.newton_iters, Fc.st.jac_evals);
        free(b2);
        mdl_free(&m2);
    }
    tap_diag("%s | unknowns %d | %d | steps %ld | %ld | Newton %ld | %ld | Jacobians %ld | %ld | "
             "rejected %ld | %ld | seconds %.2f | %.2f", label, a.equations, b.equations,
             Fc.st.steps, Ff.st.steps, Fc.st.newton_iters, Ff.st.newton_iters, Fc.st.jac_evals,
             Ff.st.jac_evals, Fc.st.rejected_error + Fc.st.newton_fails,
             Ff.st.rejected_error + Ff.st.newton_fails, Fc.seconds, Ff.seconds);

    /* ---- the outputs at one state: the C crane's start mapped into the file's unknowns ---- */
    if (map && !unmatched && fc.out) {
        double *y = malloc((size_t)n * sizeof *y), *yp = calloc((size_t)n, sizeof *yp), o[CRANE_NOUT];
        for (int i = 0; y && i < n; i++)
            y[map[i]] = yc[i];
        if (y && yp && mdl_outputs(mm, 0.0, y, fc.out, &e) == BG_OK) {
            crane_outputs(c, 0.0, yc, yp, o);
            int bad = 0;
            for (int k = 1; k < CRANE_NOUT; k++) {
                char key[32];
                snprintf(key, sizeof key, "%.*s", (int)strcspn(crane_output_names[k], " "),
                         crane_output_names[k]);
                int j = col_of(mm, key);
                if (j < 0 || !strcmp(key, "tip_defl_1") || !strcmp(key, "alpha_err")) continue;
                double d = fabs(fc.out[j] - o[k]);
                if (d > 1e-9 * fmax(1, fabs(o[k]))) {
                    tap_diag("%s: output %s: file %.12g, C crane %.12g", label, key, fc.out[j], o[k]);
                    bad++;
                }
            }
            tap_ok(!bad, "%s: the file's outputs equal crane_outputs at the C crane's start",
                   label);
        }
        free(y);
        free(yp);
    }
    free(fc.out);
    free(map);
    free(bc);
    free(bf);
    crane_free(&c);
    mdl_free(&mm);
}

int main(void)
{
    /* The issue "Models as files" asked for the step counts within 1 % of the C crane's. They
     * depend on the rounding of the solves as well as on the model: the C crane from its own
     * start moved by 2 ulp takes 0.7 % fewer steps (paper) and 6 % fewer (paper-undamped, the
     * solver's hard case: no damping, a fast drive); this test prints that diagnostic run. So
     * the file and the C crane share their static start's procedure (bg_trim.h, the integral's
     * holding value) and build the same model in the same order: the runs are the same to the
     * last bit, and the test asks for that (docs/crane.md, "The crane as a model file"). */
    compare("paper", CRANE_SCENES_DIR "/paper.ini", CRANE_MODELS_DIR "/paper.yaml");
    compare("paper-undamped", CRANE_SCENES_DIR "/paper-undamped.ini",
            CRANE_MODELS_DIR "/paper-undamped.yaml");
    return tap_done();
}
