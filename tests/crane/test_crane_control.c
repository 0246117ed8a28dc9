/* The controlled crane (crane/models/crane-control.yaml) and its controllers on the full model:
 *   - all switches off it is the paper crane: a 4 s run of it and of paper.yaml from their
 *     static starts agree in the platform's angle, the load's position and the line pressure
 *     (to the solver's tolerance; the two differ in how the reference is built, a ctl.shaper
 *     with `none` against sig.trapezoid, and in the idle controllers' unknowns);
 *   - every controller's closed loop is stable on the linearised crane: the modes at the static
 *     start (bgr_modes of the model with the controller's switches, as crane --modes computes
 *     them) have every elastic mode damped (damping ratio > 0);
 *   - the LQR feedback damps the load's pendulum: its tangential mode's damping ratio on the
 *     full crane against the design model's (the closed loop A - B K of crane-control.yaml's
 *     design, theta'' = a, s'' = -(g / L) s - R a, whose pendulum pair has the damping computed
 *     here from K by LAPACK dgeev): the crane's within a factor 2 of it and at least 50 times the
 *     open loop's (0.0003).
 * About 20 s of computing. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bg_modes.h"
#include "bgr_analysis.h"
#include "ctl_lqr.h"
#include "mdl_model.h"
#include "tap.h"

#ifndef CRANE_MODELS_DIR
#define CRANE_MODELS_DIR "crane/models"
#endif

extern void dgeev_(const char *jobvl, const char *jobvr, const int *n, double *a, const int *lda,
                   double *wr, double *wi, double *vl, const int *ldvl, double *vr,
                   const int *ldvr, double *work, const int *lwork, int *info);

static mdl_model *load_static(const char *file, const mdl_set *sets, int nsets)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/%s", CRANE_MODELS_DIR, file);
    bg_error e = {0};
    mdl_model *mm = mdl_load(path, sets, nsets, &e);
    if (!mm) {
        tap_diag("%s: %s", file, e.message);
        return NULL;
    }
    dae_static_options so;
    dae_static_options_default(&so);
    so.max_steps = 150;
    mdl_trim_report tr;
    if (mdl_static(&mm, &so, &tr, &e) != BG_OK) {
        tap_diag("%s: static start: %s", file, e.message);
        mdl_free(&mm);
    }
    return mm;
}

/* runs mm to t and evaluates its outputs into out; 1 on success */
static int run_to(mdl_model *mm, double t, double *out)
{
    dae_options o;
    double *bk = NULL;
    dae_problem p;
    bg_error e = {0};
    int ok = 0;
    if (mdl_dae_options(mm, &o, &bk) != BG_OK || mdl_dae_problem(mm, &p) != BG_OK) return 0;
    dae_solver *s = dae_create(&p, &o, &e);
    bgr_model *m = mdl_bgr(mm);
    int n = bgr_nvars(m);
    double *y = calloc((size_t)n, sizeof *y), *yp = calloc((size_t)n, sizeof *yp), tret;
    if (s && y && yp && dae_init(s, 0, bgr_y0(m), bgr_yp0(m)) == BG_OK &&
        dae_consistent_init(s) == BG_OK && dae_solve_to(s, t, &tret, y, yp) >= 0 &&
        mdl_outputs(mm, t, y, out, &e) == BG_OK)
        ok = 1;
    else if (s)
        tap_diag("run: %s", dae_get_error(s)->message);
    dae_free(&s);
    free(y);
    free(yp);
    free(bk);
    return ok;
}

static int out_index(const mdl_model *mm, const char *name)
{
    for (int i = 0; i < mdl_noutputs(mm); i++)
        if (!strcmp(mdl_output_name(mm, i), name)) return i;
    return -1;
}

static void test_off_is_paper(void)
{
    mdl_model *a = load_static("paper.yaml", NULL, 0), *b = load_static("crane-control.yaml", NULL, 0);
    double oa[64], ob[64];
    int ok = a && b && run_to(a, 4.0, oa) && run_to(b, 4.0, ob);
    const char *names[4] = {"theta", "load_x", "load_y", "p_high"};
    const double tol[4] = {1e-5, 1e-3, 1e-3, 2e4};
    for (int k = 0; k < 4 && ok; k++) {
        int ia = out_index(a, names[k]), ib = out_index(b, names[k]);
        double va = ia >= 0 ? oa[ia] : NAN, vb = ib >= 0 ? ob[ib] : NAN;
        tap_ok(fabs(va - vb) <= tol[k], "switches off: %s(4 s) = %.9g, paper.yaml's %.9g", names[k],
               vb, va);
    }
    if (!ok) tap_ok(0, "paper.yaml and crane-control.yaml run 4 s from their static starts");
    mdl_free(&a);
    mdl_free(&b);
}

/* the elastic modes at the static start: the smallest damping ratio, and the damping of the
 * load's tangential pendulum: the lowest mode between 0.04 and 0.08 Hz (sqrt(g / L) / (2 pi) =
 * 0.059 Hz) with the load's sideways position x1 among its three leading unknowns (the
 * description weights the unknowns by their nominal magnitudes: with the LQR the motor's angle,
 * 300 times the platform's, leads) */
static int modes_of(mdl_model *mm, double *zmin, double *zload, double *fload)
{
    dae_modes *md = NULL;
    bg_error e = {0};
    int st = bgr_modes(mdl_bgr(mm), 0.0, NULL, NULL, NULL, &md, &e);
    if (st != BG_OK) {
        tap_diag("modes: %s", e.message);
        dae_modes_free(&md);
        return 0;
    }
    *zmin = INFINITY;
    *zload = NAN;
    *fload = NAN;
    char buf[512];
    for (int k = 0; k < dae_modes_count(md); k++) {
        const dae_mode *d = dae_modes_get(md, k);
        if (d->kind != DAE_MODE_ELASTIC) continue;
        *zmin = fmin(*zmin, d->damping);
        dae_modes_describe(md, k, 2, 3, 3, buf, sizeof buf);
        if (isnan(*zload) && strstr(buf, "load/x1") && d->freq_hz > 0.04 && d->freq_hz < 0.08) {
            *zload = d->damping;
            *fload = d->freq_hz;
        }
    }
    dae_modes_free(&md);
    return 1;
}

/* the design model's pendulum pair: the damping ratio of the complex pair of A - B K with the
 * lower frequency */
static double design_damping(void)
{
    const double g = 9.81, L = 71.51, R = 12, q[4] = {1, 10, 0.001, 0.01}, r = 1;
    double A[16] = {0}, B[4] = {0, 1, 0, -R}, Q[16] = {0}, K[4];
    A[0 + 1 * 4] = 1;
    A[2 + 3 * 4] = 1;
    A[3 + 2 * 4] = -g / L;
    for (int i = 0; i < 4; i++) Q[i + 4 * i] = q[i];
    if (ctl_lqr(4, 1, A, B, Q, &r, K, NULL, NULL) != BG_OK) return NAN;
    double C[16], wr[4], wi[4], work[64];
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++) C[i + 4 * j] = A[i + 4 * j] - B[i] * K[j];
    int n = 4, lw = 64, info;
    dgeev_("N", "N", &n, C, &n, wr, wi, NULL, &n, NULL, &n, work, &lw, &info);
    double best = NAN, wbest = INFINITY;
    for (int i = 0; i < 4; i++)
        if (wi[i] > 0) {
            double w = hypot(wr[i], wi[i]);
            if (fabs(w - sqrt(g / L)) < wbest) {
                wbest = fabs(w - sqrt(g / L));
                best = -wr[i] / w;
            }
        }
    return best;
}

static void test_stability(void)
{
    static const struct {
        const char *name;
        mdl_set sets[6];
        int n;
    } ctl[] = {
        {"pid", {{0}}, 0},
        {"pid_2dof", {{"pid_b", "0.5"}, {"pid_tt", "5"}}, 2},
        {"feedforward", {{"ff_on", "1"}}, 1},
        {"zvd", {{"omega_ref.shaper", "zvd"}, {"alpha_ref.shaper", "zvd"}, {"theta_ref.shaper", "zvd"}}, 3},
        {"lqr", {{"lqr_on", "1"}}, 1},
    };
    double zpend[8];
    for (size_t k = 0; k < sizeof ctl / sizeof *ctl; k++) {
        mdl_model *mm = load_static("crane-control.yaml", ctl[k].sets, ctl[k].n);
        double zmin = NAN, zl = NAN, fl = NAN;
        int ok = mm && modes_of(mm, &zmin, &zl, &fl);
        zpend[k] = zl;
        tap_ok(ok && zmin > 0, "%s: every elastic mode at the static start damped (smallest "
                               "damping ratio %.3g; the load's pendulum %.5f Hz, %.4g)",
               ctl[k].name, zmin, fl, zl);
        mdl_free(&mm);
    }
    double zd = design_damping();
    double zl = zpend[4];
    tap_ok(zl > 50 * zpend[0] && zl > 0.5 * zd && zl < 2 * zd,
           "LQR: the pendulum's damping ratio %.4f on the crane, %.4f on the design model, %.2g "
           "under the PID alone",
           zl, zd, zpend[0]);
}

int main(void)
{
    test_off_is_paper();
    test_stability();
    return tap_done();
}
