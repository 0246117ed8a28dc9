/* Tests of the mechanical components against closed forms and conservation laws: torque-free
 * rigid body (angular momentum and energy, stability of the principal axes), a body on a driven
 * revolute joint (theta = T t^2/(2 I)), the physical pendulum (period and joint reaction),
 * a truss under an end force (F L/(E A)), a rope going slack, every element's analytic
 * Jacobian against finite differences, and the nominal magnitudes the elements declare (their
 * weights, lengths, stated forces and moments, a beam chain's weight) against the documented
 * rules applied by hand, and the parameter checks of every constructor (bad values refused with
 * messages naming the element's path and the parameter; a model built through refusals
 * works). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bgr_elements.h"
#include "bondgraph/param_check.h"
#include "mech_axial.h"
#include "mech_beam.h"
#include "mech_body.h"
#include "mech_parts.h"
#include "mech_sensor.h"
#include "tap.h"

static tap_rng rng;
#define PI 3.14159265358979323846

/* Random point of the model's unknowns with normalised-ish quaternions, for the checks. */
static void random_point(int n, double *y, double *yp)
{
    for (int i = 0; i < n; i++) {
        y[i] = tap_rng_range(&rng, -1, 1);
        yp[i] = tap_rng_range(&rng, -1, 1);
    }
}

/* At random points near the model's initial values (stiff elements far from their rest state
 * make residuals so large that finite differences lose the digits to compare). */
static int check_tol(bgr_model *m, const char *what, double tol);
static int check(bgr_model *m, const char *what)
{
    return check_tol(m, what, 1e-6);
}
static int check_tol(bgr_model *m, const char *what, double tol)
{
    int n = bgr_n(m);
    double *y = malloc((size_t)n * sizeof *y), *yp = malloc((size_t)n * sizeof *yp);
    const double *y0 = bgr_y0(m);
    char rep[512];
    int bad = 0;
    for (int trial = 0; trial < 3; trial++) {
        random_point(n, y, yp);
        for (int i = 0; i < n; i++)
            y[i] = y0[i] + (y0[i] != 0 ? 0.01 : 1.0) * y[i];
        int r = bgr_check_jacobian(m, 0.3, y, yp, tol, rep, sizeof rep);
        if (r != 0) {
            tap_diag("%s: %s", what, rep);
            bad = 1;
        }
    }
    free(y);
    free(yp);
    return !bad;
}

/* Integrates the compiled model to each time of tout (ascending) after consistent
 * initialisation, calling probe at every output. Returns the solver status. */
typedef void (*probe_fn)(void *ctx, double t, const double *y);
static int integrate(bgr_model *m, double rtol, const double *tout, int nout, probe_fn probe,
                     void *ctx, dae_stats *st)
{
    dae_problem p;
    bgr_dae_problem(m, &p);
    dae_options o;
    dae_options_default(&o);
    o.rtol = rtol;
    o.atol = rtol * 1e-2;
    bg_error err = {0};
    dae_solver *s = dae_create(&p, &o, &err);
    if (!s) {
        tap_diag("dae_create: %s", err.message);
        return -1000;
    }
    int n = bgr_n(m), r = dae_init(s, 0.0, bgr_y0(m), bgr_yp0(m));
    if (r == 0) r = dae_consistent_init(s);
    double *y = malloc((size_t)n * sizeof *y), *yp = malloc((size_t)n * sizeof *yp), t;
    for (int k = 0; r == 0 && k < nout; k++) {
        r = dae_solve_to(s, tout[k], &t, y, yp);
        if (r == 0 && probe) probe(ctx, t, y);
    }
    if (r < 0) tap_diag("solver: %s: %s", dae_return_name(r), dae_get_error(s)->message);
    if (st) *st = *dae_get_stats(s);
    free(y);
    free(yp);
    dae_free(&s);
    return r;
}

/* ---- torque-free rigid body ---- */
typedef struct free_ctx {
    bgr_model *m;
    int body;
    double J[9], H0[3], E0, maxdH, maxdE, w0min, w0max, w1min, w1max;
} free_ctx;

static void free_probe(void *c, double t, const double *y)
{
    (void)t;
    free_ctx *f = c;
    const double *w = y + mech_body_var(f->m, f->body, 'w'),
                 *q = y + mech_body_var(f->m, f->body, 'q');
    double s = q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3];
    double R[9] = {(q[0] * q[0] + q[1] * q[1] - q[2] * q[2] - q[3] * q[3]) / s,
                   2 * (q[1] * q[2] + q[0] * q[3]) / s,
                   2 * (q[1] * q[3] - q[0] * q[2]) / s,
                   2 * (q[1] * q[2] - q[0] * q[3]) / s,
                   (q[0] * q[0] - q[1] * q[1] + q[2] * q[2] - q[3] * q[3]) / s,
                   2 * (q[2] * q[3] + q[0] * q[1]) / s,
                   2 * (q[1] * q[3] + q[0] * q[2]) / s,
                   2 * (q[2] * q[3] - q[0] * q[1]) / s,
                   (q[0] * q[0] - q[1] * q[1] - q[2] * q[2] + q[3] * q[3]) / s};
    double Jw[3], H[3];
    for (int i = 0; i < 3; i++)
        Jw[i] = f->J[i] * w[0] + f->J[i + 3] * w[1] + f->J[i + 6] * w[2];
    for (int i = 0; i < 3; i++)
        H[i] = R[i] * Jw[0] + R[i + 3] * Jw[1] + R[i + 6] * Jw[2];
    double E = 0.5 * (w[0] * Jw[0] + w[1] * Jw[1] + w[2] * Jw[2]);
    double nH0 = sqrt(f->H0[0] * f->H0[0] + f->H0[1] * f->H0[1] + f->H0[2] * f->H0[2]);
    double dH = sqrt((H[0] - f->H0[0]) * (H[0] - f->H0[0]) + (H[1] - f->H0[1]) * (H[1] - f->H0[1]) +
                     (H[2] - f->H0[2]) * (H[2] - f->H0[2])) /
                nH0;
    f->maxdH = fmax(f->maxdH, dH);
    f->maxdE = fmax(f->maxdE, fabs(E - f->E0) / f->E0);
    f->w0min = fmin(f->w0min, w[0]);
    f->w0max = fmax(f->w0max, w[0]);
    f->w1min = fmin(f->w1min, w[1]);
    f->w1max = fmax(f->w1max, w[1]);
}

static void run_free_body(const double *w0, const char *what, free_ctx *f)
{
    static const double J[9] = {1, 0, 0, 0, 2, 0, 0, 0, 3};
    bgr_model *m = bgr_model_create("free");
    f->m = m;
    f->body = mech_body(m, 0, "body", 5.0, J, NULL, 0, NULL, NULL);
    int st = bgr_compile(m);
    tap_ok(st == BG_OK, "%s: compile (%s)", what, bgr_model_error(m)->message);
    mech_body_set(m, f->body, NULL, NULL, w0, NULL);
    memcpy(f->J, J, sizeof J);
    for (int i = 0; i < 3; i++)
        f->H0[i] = J[4 * i] * w0[i]; /* R = I at t = 0 */
    f->E0 = 0.5 * (J[0] * w0[0] * w0[0] + J[4] * w0[1] * w0[1] + J[8] * w0[2] * w0[2]);
    f->maxdH = f->maxdE = 0;
    f->w0min = f->w1min = INFINITY;
    f->w0max = f->w1max = -INFINITY;
    double tout[400];
    for (int k = 0; k < 400; k++)
        tout[k] = 0.25 * (k + 1); /* 100 s, ~30 revolutions */
    dae_stats sts;
    int r = integrate(m, 1e-9, tout, 400, free_probe, f, &sts);
    tap_ok(r == 0, "%s: integrated to t = 100 (%ld steps)", what, sts.steps);
    if (st == BG_OK) tap_ok(check(m, what), "%s: Jacobian matches finite differences", what);
    bgr_model_free(&m);
}

static void test_free_body(void)
{
    free_ctx f;
    const double wmin[3] = {2.0, 0.01, 0.01}, wmid[3] = {0.01, 2.0, 0.01},
                 wmax[3] = {0.01, 0.01, 2.0};
    run_free_body(wmin, "free body, spin about the axis of least inertia", &f);
    tap_ok(f.maxdH < 1e-6 && f.maxdE < 1e-6,
           "free body: angular momentum (%.2g) and energy (%.2g) conserved over 100 s", f.maxdH,
           f.maxdE);
    tap_ok(f.w0min > 1.9, "free body: spin about the least axis is stable (w0 >= %.4f)", f.w0min);
    run_free_body(wmid, "free body, spin about the intermediate axis", &f);
    tap_ok(f.maxdH < 1e-6 && f.maxdE < 1e-6,
           "free body (intermediate): momentum (%.2g) and energy (%.2g) conserved", f.maxdH,
           f.maxdE);
    tap_ok(f.w1min < -1.5 && f.w1max > 1.9,
           "free body: spin about the intermediate axis flips (w1 from %.3f to %.3f)", f.w1max,
           f.w1min);
    run_free_body(wmax, "free body, spin about the axis of greatest inertia", &f);
    tap_ok(f.maxdH < 1e-6 && f.maxdE < 1e-6, "free body (greatest): momentum %.2g, energy %.2g",
           f.maxdH, f.maxdE);
}

/* ---- body on a driven revolute joint: theta = T t^2 / (2 I) ---- */
typedef struct axis_ctx {
    bgr_model *m;
    int body;
    double maxerr_w, maxerr_th, I, T;
    double theta_prev, turns;
    int s_th, s_w; /* sensor outputs */
    double maxerr_s;
} axis_ctx;

static void axis_probe(void *c, double t, const double *y)
{
    axis_ctx *a = c;
    const double *w = y + mech_body_var(a->m, a->body, 'w'),
                 *q = y + mech_body_var(a->m, a->body, 'q');
    double th = 2 * atan2(q[3], q[0]); /* rotation about z, in (-2pi, 2pi] */
    while (th < a->theta_prev - PI)
        th += 2 * PI, a->turns += 1;
    a->theta_prev = th;
    double thx = a->T * t * t / (2 * a->I);
    a->maxerr_w = fmax(a->maxerr_w, fabs(w[2] - a->T * t / a->I) / (a->T * t / a->I));
    a->maxerr_th = fmax(a->maxerr_th, fabs(th - thx) / thx);
    /* the sensor's angle keeps counting past pi */
    a->maxerr_s = fmax(a->maxerr_s, fabs(y[a->s_th] - thx) / thx);
    a->maxerr_s = fmax(a->maxerr_s, fabs(y[a->s_w] - a->T * t / a->I) / (a->T * t / a->I));
}

static void test_driven_axis(void)
{
    static const double J[9] = {1, 0, 0, 0, 1.5, 0, 0, 0, 2};
    static const double z[3] = {0, 0, 1}, r0[3] = {0, 0, 0};
    bgr_model *m = bgr_model_create("axis");
    int body = mech_body(m, 0, "rotor", 4.0, J, NULL, 1, r0, NULL);
    int gnd = mech_support(m, 0, "ground", 6);
    int jnt = mech_revolute(m, 0, "hinge", -1, z, 1);
    double tau = 3.0;
    int src = bgr_Se(m, 0, "motor", 1, &tau);
    bgr_bond(m, 0, "b_ground", 6, bgr_port_of(m, gnd, 0), bgr_port_of(m, jnt, 0), NULL, NULL);
    bgr_bond(m, 0, "b_rotor", 6, bgr_port_of(m, jnt, 1), bgr_port_of(m, body, 0), NULL, NULL);
    bgr_bond(m, 0, "b_drive", 1, bgr_port_of(m, src, 0), bgr_port_of(m, jnt, 2), NULL, NULL);
    int sens = mech_rotation_sensor(m, 0, "encoder", body, z);
    int st = bgr_compile(m);
    tap_ok(st == BG_OK, "driven axis: compile (%s)", bgr_model_error(m)->message);
    if (st != BG_OK) {
        bgr_model_free(&m);
        return;
    }
    bgr_stats bs;
    bgr_get_stats(m, &bs);
    tap_diag("driven axis: %d equations, %d index-2 unknowns", bs.equations, bs.index2);
    mech_body_set(m, body, NULL, NULL, NULL, NULL);
    axis_ctx a = {m, body, 0, 0, 2.0, tau, 0, 0, 0, 0, 0};
    a.s_th = bgr_ref_var(m, (bgr_ref){BGR_STATE, sens, 0});
    a.s_w = bgr_ref_var(m, (bgr_ref){BGR_OWN, sens, 0});
    double tout[50];
    for (int k = 0; k < 50; k++)
        tout[k] = 0.05 * (k + 1);
    int r = integrate(m, 1e-9, tout, 50, axis_probe, &a, NULL);
    tap_ok(r == 0 && a.maxerr_w < 1e-7 && a.maxerr_th < 1e-6,
           "driven axis: w = T t/I (rel err %.2g) and theta = T t^2/(2 I) (rel err %.2g) to t = "
           "2.5",
           a.maxerr_w, a.maxerr_th);
    tap_ok(r == 0 && a.maxerr_s < 1e-6,
           "rotation sensor: angle (past pi: 4.69 rad at t = 2.5) and rate against the closed "
           "form (rel err %.2g)",
           a.maxerr_s);
    tap_ok(bs.index2 >= 5, "driven axis: the joint reactions are index 2 (%d)", bs.index2);
    tap_ok(check(m, "driven axis"), "driven axis: Jacobian matches finite differences");
    bgr_model_free(&m);
}

/* ---- physical pendulum on a revolute joint ---- */
typedef struct pend_ctx {
    bgr_model *m;
    int body, bond_var; /* effort z of the ground bond */
} pend_ctx;

static int pend_root_w; /* variable id of the body's w1 */
static int pend_roots(void *user, double t, const double *y, const double *yp, double *g)
{
    (void)user, (void)t, (void)yp;
    g[0] = y[pend_root_w];
    return 0;
}

static int pend_root_q; /* q2: sin(theta/2), zero at the lowest point */
static int pend_roots_low(void *user, double t, const double *y, const double *yp, double *g)
{
    (void)user, (void)t, (void)yp;
    g[0] = y[pend_root_q];
    return 0;
}

static bgr_model *build_pendulum(double mass, double d, const double *J, double theta0, int *body,
                                 int *fz)
{
    static const double yax[3] = {0, 1, 0}, g[3] = {0, 0, -9.81};
    double rp[3] = {0, 0, d}; /* pivot above the mass centre in the body frame */
    bgr_model *m = bgr_model_create("pendulum");
    *body = mech_body(m, 0, "bob", mass, J, g, 1, rp, NULL);
    int gnd = mech_support(m, 0, "ground", 6);
    int jnt = mech_revolute(m, 0, "pivot", -1, yax, 0);
    bgr_bond(m, 0, "b_ground", 6, bgr_port_of(m, gnd, 0), bgr_port_of(m, jnt, 0), NULL, NULL);
    bgr_bond(m, 0, "b_bob", 6, bgr_port_of(m, jnt, 1), bgr_port_of(m, *body, 0), NULL, NULL);
    if (bgr_compile(m) != BG_OK) {
        tap_diag("pendulum: %s", bgr_model_error(m)->message);
        bgr_model_free(&m);
        return NULL;
    }
    /* rotated by theta0 about y; pivot at the origin: x = -R r_p */
    double q[4] = {cos(theta0 / 2), 0, sin(theta0 / 2), 0};
    double x[3] = {-d * sin(theta0), 0, -d * cos(theta0)};
    mech_body_set(m, *body, x, NULL, NULL, q);
    *fz = bgr_find_var(m, "pendulum/b_ground/e2");
    return m;
}

static void test_pendulum(void)
{
    const double mass = 2.0, d = 0.5, J[9] = {0.1, 0, 0, 0, 0.08, 0, 0, 0, 0.05}, g = 9.81;
    double Ip = J[4] + mass * d * d;
    /* small amplitude: period against 2 pi sqrt(Ip/(m g d)) (1 + theta0^2/16) */
    int body, fz;
    double th0 = 0.02;
    bgr_model *m = build_pendulum(mass, d, J, th0, &body, &fz);
    tap_ok(m != NULL, "pendulum: compiles");
    if (!m) return;
    dae_problem p;
    bgr_dae_problem(m, &p);
    pend_root_w = mech_body_var(m, body, 'w') + 1;
    p.nroots = 1;
    p.roots = pend_roots;
    dae_options o;
    dae_options_default(&o);
    o.rtol = 1e-10;
    o.atol = 1e-12;
    bg_error err = {0};
    dae_solver *s = dae_create(&p, &o, &err);
    int n = bgr_n(m), r = s ? dae_init(s, 0, bgr_y0(m), bgr_yp0(m)) : -1;
    if (r == 0) r = dae_consistent_init(s);
    double *y = malloc((size_t)n * sizeof *y), *yp = malloc((size_t)n * sizeof *yp), t = 0;
    double troots[8];
    int nr = 0;
    while (r >= 0 && nr < 5) { /* w1 vanishes at the turning points: half periods */
        r = dae_solve_to(s, 10.0, &t, y, yp);
        if (r == DAE_ROOT_RETURN)
            troots[nr++] = t;
        else
            break;
    }
    double T0 = 2 * PI * sqrt(Ip / (mass * g * d)) * (1 + th0 * th0 / 16);
    double Tm = nr >= 5 ? (troots[4] - troots[0]) / 2 : NAN;
    tap_ok(nr >= 5 && fabs(Tm - T0) / T0 < 1e-6,
           "pendulum: small-amplitude period %.9f against %.9f (rel %.2g)", Tm, T0,
           fabs(Tm - T0) / T0);
    dae_free(&s);
    bgr_model_free(&m);

    /* amplitude 0.6 rad: at the lowest point the joint pushes up with m g + m d w^2,
     * w^2 = 2 m g d (1 - cos theta0)/Ip */
    th0 = 0.6;
    m = build_pendulum(mass, d, J, th0, &body, &fz);
    if (!m) {
        free(y);
        free(yp);
        return;
    }
    bgr_dae_problem(m, &p);
    pend_root_q = mech_body_var(m, body, 'q') + 2;
    p.nroots = 1;
    p.roots = pend_roots_low;
    s = dae_create(&p, &o, &err);
    r = s ? dae_init(s, 0, bgr_y0(m), bgr_yp0(m)) : -1;
    if (r == 0) r = dae_consistent_init(s);
    if (r == 0) r = dae_solve_to(s, 10.0, &t, y, yp);
    double w2 = 2 * mass * g * d * (1 - cos(th0)) / Ip, Fx = mass * g + mass * d * w2;
    tap_ok(r == DAE_ROOT_RETURN && fabs(y[fz] - Fx) / Fx < 1e-6,
           "pendulum: joint reaction at the lowest point %.9f against m g + m d w^2 = %.9f", y[fz],
           Fx);
    double wl = y[mech_body_var(m, body, 'w') + 1];
    tap_ok(r == DAE_ROOT_RETURN && fabs(wl * wl - w2) / w2 < 1e-7,
           "pendulum: angular velocity at the lowest point from energy (%.9f, %.9f)", wl * wl, w2);
    tap_ok(check(m, "pendulum"), "pendulum: Jacobian matches finite differences");
    dae_free(&s);
    bgr_model_free(&m);
    free(y);
    free(yp);
}

/* ---- truss under an end force, rope going slack ---- */
typedef struct last_ctx {
    double y[256];
    int n;
} last_ctx;

static void last_probe(void *c, double t, const double *y)
{
    (void)t;
    last_ctx *l = c;
    memcpy(l->y, y, (size_t)l->n * sizeof *y);
}

/* ground - axial element - 1-junction (force source, point mass) */
static bgr_model *build_hanging(int rope, double *force, int *ax, int *pm, double xend)
{
    bgr_model *m = bgr_model_create("hang");
    const double E = 2.1e11, A = 1e-4, L = 2.0;
    int gnd = mech_support(m, 0, "ground", 3);
    *ax = rope ? mech_rope(m, 0, "rope", E * A / L, 2e5, L, 0)
               : mech_truss(m, 0, "bar", E, A, L, 2e5);
    *pm = mech_point_mass(m, 0, "mass", 10.0, NULL);
    int j = bgr_one(m, 0, "end", 3, 3);
    int src = bgr_Se(m, 0, "load", 3, force);
    bgr_bond(m, 0, "b0", 3, bgr_port_of(m, gnd, 0), bgr_port_of(m, *ax, 0), NULL, NULL);
    bgr_bond(m, 0, "b1", 3, bgr_port_of(m, j, 0), bgr_port_of(m, *ax, 1), NULL, NULL);
    bgr_bond(m, 0, "b2", 3, bgr_port_of(m, j, 1), bgr_port_of(m, *pm, 0), NULL, NULL);
    bgr_bond(m, 0, "b3", 3, bgr_port_of(m, src, 0), bgr_port_of(m, j, 2), NULL, NULL);
    if (bgr_compile(m) != BG_OK) {
        tap_diag("hanging: %s", bgr_model_error(m)->message);
        bgr_model_free(&m);
        return NULL;
    }
    const double xa[3] = {0, 0, 0}, xb[3] = {xend, 0, 0};
    mech_axial_set(m, *ax, xa, xb);
    mech_point_mass_set(m, *pm, xb, NULL);
    return m;
}

static void test_truss_rope(void)
{
    double F[3] = {5e4, 0, 0};
    int ax, pm;
    bgr_model *m = build_hanging(0, F, &ax, &pm, 2.0);
    tap_ok(m != NULL, "truss: compiles");
    if (!m) return;
    last_ctx l = {{0}, bgr_n(m)};
    double tout[1] = {0.5};
    int r = integrate(m, 1e-7, tout, 1, last_probe, &l, NULL);
    const double E = 2.1e11, A = 1e-4, L = 2.0;
    double dl = l.y[bgr_find_var(m, "hang/bar/d0")] - L;
    double want = F[0] * L / (E * A);
    tap_ok(r == 0 && fabs(dl - want) / want < 1e-4,
           "truss: elongation %.6e against F L/(E A) = %.6e (damped to rest)", dl, want);
    /* stiff (E A/L = 1e7 N/m): residuals of 1e5 leave finite differences 1e-6 relative */
    tap_ok(check_tol(m, "truss", 1e-5), "truss: Jacobian matches finite differences");
    bgr_model_free(&m);

    /* rope, started 1 cm slack and pushed towards the support: it stays slack and the mass
     * moves freely (the smoothing leaves k eps exp(-|L - L0|/eps) of tension: nothing) */
    double P[3] = {-200, 0, 0};
    m = build_hanging(1, P, &ax, &pm, 1.99);
    if (!m) return;
    int n = bgr_n(m);
    last_ctx l2 = {{0}, n};
    double tout2[3] = {0.1, 0.2, 0.3};
    dae_stats st;
    r = integrate(m, 1e-8, tout2, 3, last_probe, &l2, &st);
    int xv = bgr_find_var(m, "hang/mass/x0");
    /* slack: free motion x = L + P t^2/(2 m) while the rope carries (almost) nothing */
    double xe = 1.99 + P[0] * 0.09 / 20.0, T = mech_axial_tension(m, ax, l2.y);
    tap_ok(r == 0 && fabs(l2.y[xv] - xe) < 1e-6 && fabs(T) < 1e-6,
           "rope: goes slack without a solver failure (x %.6f against free flight %.6f, tension "
           "%.3g N, %ld steps)",
           l2.y[xv], xe, T, st.steps);
    tap_ok(check_tol(m, "rope", 1e-5), "rope: Jacobian matches finite differences");
    bgr_model_free(&m);
}

/* ---- Jacobians of the joints and of a body with mixed ports ---- */
static void test_jacobians(void)
{
    static const double J[9] = {1, 0.1, 0, 0.1, 2, 0.2, 0, 0.2, 3}, g[3] = {0, 0, -9.81};
    static const double r[6] = {0.5, 0.1, -0.2, -0.3, 0.4, 0.1};
    static const int dims[2] = {6, 3};
    static const double ax[3] = {0.3, 0.5, 0.8};
    bgr_model *m = bgr_model_create("jac");
    int b1 = mech_body(m, 0, "b1", 3.0, J, g, 2, r, dims);
    int b2 = mech_body(m, 0, "b2", 2.0, J, g, 2, r, dims);
    int rev = mech_revolute(m, 0, "rev", b1, ax, 1);
    int sph = mech_spherical(m, 0, "sph", 3);
    int spr = mech_spring(m, 0, "spr", 100, 3, 0.5);
    int pm = mech_point_mass(m, 0, "pm", 1.0, g);
    double tau = 1;
    int src = bgr_Se(m, 0, "tau", 1, &tau);
    bgr_bond(m, 0, "a", 6, bgr_port_of(m, rev, 0), bgr_port_of(m, b1, 0), NULL, NULL);
    bgr_bond(m, 0, "b", 6, bgr_port_of(m, b2, 0), bgr_port_of(m, rev, 1), NULL, NULL);
    bgr_bond(m, 0, "c", 1, bgr_port_of(m, src, 0), bgr_port_of(m, rev, 2), NULL, NULL);
    bgr_bond(m, 0, "d", 3, bgr_port_of(m, b1, 1), bgr_port_of(m, sph, 0), NULL, NULL);
    bgr_bond(m, 0, "e", 3, bgr_port_of(m, sph, 1), bgr_port_of(m, spr, 0), NULL, NULL);
    bgr_bond(m, 0, "f", 3, bgr_port_of(m, spr, 1), bgr_port_of(m, b2, 1), NULL, NULL);
    (void)pm;
    int st = bgr_compile(m);
    /* the point mass has a free port: the compiler must say so */
    tap_ok(st == BG_ERR_PATTERN && strstr(bgr_model_error(m)->message, "jac/pm port 0"),
           "unconnected port reported: %s", bgr_model_error(m)->message);
    bgr_model_free(&m);

    m = bgr_model_create("jac");
    b1 = mech_body(m, 0, "b1", 3.0, J, g, 2, r, dims);
    b2 = mech_body(m, 0, "b2", 2.0, J, g, 2, r, dims);
    rev = mech_revolute(m, 0, "rev", b1, ax, 1);
    sph = mech_spherical(m, 0, "sph", 3);
    spr = mech_rope(m, 0, "rope", 100, 3, 0.5, 0.01);
    src = bgr_Se(m, 0, "tau", 1, &tau);
    bgr_bond(m, 0, "a", 6, bgr_port_of(m, rev, 0), bgr_port_of(m, b1, 0), NULL, NULL);
    bgr_bond(m, 0, "b", 6, bgr_port_of(m, b2, 0), bgr_port_of(m, rev, 1), NULL, NULL);
    bgr_bond(m, 0, "c", 1, bgr_port_of(m, src, 0), bgr_port_of(m, rev, 2), NULL, NULL);
    bgr_bond(m, 0, "d", 3, bgr_port_of(m, b1, 1), bgr_port_of(m, sph, 0), NULL, NULL);
    bgr_bond(m, 0, "e", 3, bgr_port_of(m, sph, 1), bgr_port_of(m, spr, 0), NULL, NULL);
    bgr_bond(m, 0, "f", 3, bgr_port_of(m, spr, 1), bgr_port_of(m, b2, 1), NULL, NULL);
    st = bgr_compile(m);
    tap_ok(st == BG_OK, "two bodies, revolute with drive, spherical, rope: compile (%s)",
           bgr_model_error(m)->message);
    if (st == BG_OK)
        tap_ok(check(m, "mixed mechanism"),
               "body (6D and 3D ports, products of inertia), revolute (body axis, drive), "
               "spherical, rope: Jacobians match finite differences");
    bgr_model_free(&m);
}

/* Energies: the rope's elastic energy differentiates to its tension (central differences in the
 * stretch, slack through taut), and tends to k x^2 / 2 + k eps^2 pi^2 / 6 when taut and to 0 when
 * slack; point mass and body energies against hand-computed values. */
static void test_energies(void)
{
    const double k = 100, L0 = 0.5, eps = 0.01, g[3] = {0, 0, -9.81}, pi = 3.14159265358979323846;
    bgr_model *m = bgr_model_create("en");
    int a = mech_point_mass(m, 0, "a", 2.0, g), b = mech_point_mass(m, 0, "b", 3.0, g);
    int rope = mech_rope(m, 0, "rope", k, 0, L0, eps);
    double J[9] = {1, 0, 0, 0, 2, 0, 0, 0, 3}, r[3] = {0, 0, 0};
    int dims[1] = {3}, body = mech_body(m, 0, "body", 4.0, J, g, 1, r, dims);
    int sup = mech_support(m, 0, "ground", 3);
    bgr_bond(m, 0, "ra", 3, bgr_port_of(m, a, 0), bgr_port_of(m, rope, 0), NULL, NULL);
    bgr_bond(m, 0, "rb", 3, bgr_port_of(m, rope, 1), bgr_port_of(m, b, 0), NULL, NULL);
    bgr_bond(m, 0, "bs", 3, bgr_port_of(m, body, 0), bgr_port_of(m, sup, 0), NULL, NULL);
    if (bgr_compile(m) != BG_OK) {
        tap_ok(0, "energy model compiles: %s", bgr_model_error(m)->message);
        bgr_model_free(&m);
        return;
    }
    int n = bgr_n(m), id = bgr_find_var(m, "en/rope/d2");
    double *y = calloc((size_t)n, sizeof *y), worst = 0;
    const double x[6] = {-0.05, -0.01, 0.0, 0.004, 0.02, 0.2};
    for (int i = 0; i < 6; i++) {
        double h = 1e-5;
        y[id] = L0 + x[i] + h;
        double up = mech_axial_energy(m, rope, y);
        y[id] = L0 + x[i] - h;
        double dn = mech_axial_energy(m, rope, y);
        y[id] = L0 + x[i];
        double T = mech_axial_tension(m, rope, y), fd = (up - dn) / (2 * h);
        worst = fmax(worst, fabs(fd - T) / (fabs(T) + 1e-6 * k * eps));
    }
    tap_ok(worst < 1e-6, "rope: dU/dL = tension from slack to taut (worst relative %.2e)", worst);
    y[id] = L0 + 0.5; /* z = x / eps = 50: the correction e^-z is below round-off */
    tap_close(mech_axial_energy(m, rope, y), 0.5 * k * 0.25 + k * eps * eps * pi * pi / 6, 1e-12, 0,
              "taut rope: U = k x^2/2 + k eps^2 pi^2/6");
    y[id] = L0 - 0.5;
    double Us = mech_axial_energy(m, rope, y);
    tap_ok(Us >= 0 && Us < 1e-15, "slack rope: U = %.3g ~ 0", Us);
    double T, V;
    int ia = bgr_find_var(m, "en/a/x0");
    const double xa[6] = {1, 2, 3, 1, 0, 2};
    memcpy(y + ia, xa, sizeof xa);
    int st = mech_point_mass_energy(m, a, y, &T, &V);
    tap_ok(st == BG_OK && fabs(T - 5.0) < 1e-14 && fabs(V - 2.0 * 9.81 * 3) < 1e-12,
           "point mass: T = m v.v/2 = 5, V = m g z = 58.86 (got %g, %g)", T, V);
    int ib = mech_body_var(m, body, 'x');
    const double xb[9] = {0, 0, -1, 0, 1, 0, 1, 1, 1};
    memcpy(y + ib, xb, sizeof xb);
    st = mech_body_energy(m, body, y, &T, &V);
    tap_ok(st == BG_OK && fabs(T - (2.0 + 3.0)) < 1e-14 && fabs(V + 4.0 * 9.81) < 1e-12,
           "body: T = m v.v/2 + w.Jw/2 = 2 + 3, V = -39.24 (got %g, %g)", T, V);
    tap_ok(mech_body_energy(m, a, y, &T, &V) == BG_ERR_ARGUMENT &&
               isnan(mech_axial_energy(m, body, y)),
           "energy of the wrong kind of element refused");
    free(y);
    bgr_model_free(&m);
}

/* Nominal magnitudes (mech_set_nominal in mech_body.h), by hand from the documented rules: a body
 * of 100 kg under gravity with ports at |r| = 1, 5 and 1 m on a driven revolute joint (stated
 * 3000 N, 7e4 N m) over a support (stated 5000 N, 2e4 N m), a wall support, a truss (stated
 * 1.5e4 N) to a 10 kg point mass (stated length 0.5 m); a bond seen from two elements gets the
 * larger declaration. Then a chain of 4 beam elements under gravity: the chain's weight, and a
 * stated force on one element. */
static void test_nominals(void)
{
    const double g[3] = {0, 0, -9.81}, z[3] = {0, 0, 1}, J[9] = {10, 0, 0, 0, 20, 0, 0, 0, 30};
    const double r[9] = {0, 0, -1, 3, 4, 0, 1, 0, 0};
    const int dims[3] = {6, 6, 3};
    const double W = 100 * 9.81, zero = 0;
    bgr_model *m = bgr_model_create("nom");
    int body = mech_body(m, 0, "body", 100, J, g, 3, r, dims);
    int ground = mech_support(m, 0, "ground", 6), wall = mech_support(m, 0, "wall", 6);
    int joint = mech_revolute(m, 0, "joint", -1, z, 1);
    int drive = bgr_Sf(m, 0, "drive", 1, &zero);
    int tie = mech_truss(m, 0, "tie", 2e11, 1e-4, 2.0, 0);
    int bob = mech_point_mass(m, 0, "bob", 10, g);
    int ok = body >= 0 && ground >= 0 && wall >= 0 && joint >= 0 && drive >= 0 && tie >= 0 &&
             bob >= 0 &&
             bgr_bond(m, 0, "b_base", 6, bgr_port_of(m, ground, 0), bgr_port_of(m, joint, 0), NULL,
                      NULL) >= 0 &&
             bgr_bond(m, 0, "b_slew", 6, bgr_port_of(m, joint, 1), bgr_port_of(m, body, 0), NULL,
                      NULL) >= 0 &&
             bgr_bond(m, 0, "b_drive", 1, bgr_port_of(m, drive, 0), bgr_port_of(m, joint, 2), NULL,
                      NULL) >= 0 &&
             bgr_bond(m, 0, "b_wall", 6, bgr_port_of(m, wall, 0), bgr_port_of(m, body, 1), NULL,
                      NULL) >= 0 &&
             bgr_bond(m, 0, "b_tie_a", 3, bgr_port_of(m, body, 2), bgr_port_of(m, tie, 0), NULL,
                      NULL) >= 0 &&
             bgr_bond(m, 0, "b_tie_b", 3, bgr_port_of(m, tie, 1), bgr_port_of(m, bob, 0), NULL,
                      NULL) >= 0;
    tap_ok(ok, "nominal model built %s", ok ? "" : bgr_model_error(m)->message);
    int st = mech_set_nominal(m, drive, 1.0, 0, 0);
    tap_ok(st == BG_ERR_ARGUMENT && strstr(bgr_model_error(m)->message, "not a mechanical"),
           "mech_set_nominal on an Sf: BG_ERR_ARGUMENT (%s)", bgr_model_error(m)->message);
    st = mech_set_nominal(m, tie, -1.0, 0, 0);
    tap_ok(st == BG_ERR_ARGUMENT && strstr(bgr_model_error(m)->message, "nom/tie"),
           "a negative force is refused naming the element (%s)", bgr_model_error(m)->message);
    st = mech_set_nominal(m, bob, 0, NAN, 0);
    tap_ok(st == BG_ERR_ARGUMENT && strstr(bgr_model_error(m)->message, "nom/bob"),
           "a NaN moment is refused naming the element (%s)", bgr_model_error(m)->message);
    ok = mech_set_nominal(m, joint, 3000, 7e4, 0) == BG_OK &&
         mech_set_nominal(m, ground, 5000, 2e4, 0) == BG_OK &&
         mech_set_nominal(m, tie, 1.5e4, 0, 0) == BG_OK &&
         mech_set_nominal(m, bob, 0, 0, 0.5) == BG_OK;
    tap_ok(ok, "mech_set_nominal accepts joint, support, truss and point mass scales");
    if (!tap_ok(bgr_compile(m) == BG_OK, "nominal model compiles")) {
        tap_diag("%s", bgr_model_error(m)->message);
        bgr_model_free(&m);
        return;
    }
    tap_ok(mech_set_nominal(m, tie, 1.0, 0, 0) == BG_ERR_STATE,
           "mech_set_nominal after compilation: BG_ERR_STATE (%s)", bgr_model_error(m)->message);
    const double *nom = bgr_nominals(m);
    struct {
        const char *path;
        double want;
        const char *why;
    } t[] = {
        {"nom/b_slew/e0", 3000, "joint force 3000 > body weight 981"},
        {"nom/b_slew/e5", 7e4, "joint moment 7e4 > weight x arm 981 x 5"},
        {"nom/b_base/e2", 5000, "support force 5000 > joint 3000"},
        {"nom/b_base/e3", 7e4, "joint moment 7e4 > support 2e4"},
        {"nom/b_drive/e", 7e4, "drive torque: the joint's moment"},
        {"nom/b_drive/f", 1.0, "drive speed: no scale"},
        {"nom/b_wall/e1", W, "unstated wall: the body's weight m |g|"},
        {"nom/b_wall/e4", W * 5, "unstated wall: weight x longest arm |(3, 4, 0)| = 5"},
        {"nom/b_wall/f0", 1.0, "velocity: 1"},
        {"nom/b_tie_a/e0", 1.5e4, "truss force 1.5e4 > body weight"},
        {"nom/b_tie_b/e2", 1.5e4, "truss force 1.5e4 > point mass weight 98.1"},
        {"nom/tie/d1", 2.0, "truss vector d: L0 = 2"},
        {"nom/bob/x2", 0.5, "point mass position: the stated 0.5"},
        {"nom/bob/v2", 1.0, "point mass velocity: 1"},
        {"nom/body/x0", 1.0, "body position: nothing stated, 1"},
        {"nom/body/q0", 1.0, "quaternion: 1"},
    };
    for (size_t i = 0; i < sizeof t / sizeof t[0]; i++) {
        int v = bgr_find_var(m, t[i].path);
        tap_close(v >= 0 ? nom[v] : NAN, t[i].want, 1e-14, 0, "nominal of %s = %g (%s)",
                  t[i].path, t[i].want, t[i].why);
    }
    bgr_model_free(&m);

    /* chain of 4 elements of 2 m under gravity: W = rho A L |g| for every element's forces and
     * W L_e for its moments; a stated 1e5 N on el03 gives its bonds 1e5 N and 2e5 N m */
    m = bgr_model_create("ch");
    mech_section sec = {.E = 2e11, .G = 8e10, .A = 0.01, .Iy = 1e-5, .Iz = 2e-5, .J = 3e-5,
                        .rho = 7850};
    const double p0[3] = {0, 0, 0}, p1[3] = {8, 0, 0}, up[3] = {0, 0, 1};
    int extra[5] = {1, 0, 0, 0, 0}, nodes[5], elems[4];
    int c = mech_beam_chain(m, 0, "boom", 4, p0, p1, up, &sec, g, extra, NULL, nodes, elems);
    int sup = mech_support(m, 0, "clamp", 6);
    ok = c >= 0 && sup >= 0 &&
         bgr_bond(m, 0, "b_clamp", 6, bgr_port_of(m, sup, 0),
                  mech_beam_chain_port(m, nodes, 4, extra, 0, 0), NULL, NULL) >= 0 &&
         mech_set_nominal(m, elems[3], 1e5, 0, 0) == BG_OK && bgr_compile(m) == BG_OK;
    tap_ok(ok, "beam chain with nominals compiles %s", ok ? "" : bgr_model_error(m)->message);
    nom = ok ? bgr_nominals(m) : NULL;
    const double Wc = 7850 * 0.01 * 8 * 9.81;
    struct {
        const char *path;
        double want;
        const char *why;
    } u[] = {
        {"ch/boom/ba00/e2", Wc, "element force: the chain's weight"},
        {"ch/boom/ba00/e4", 2 * Wc, "element moment: the chain's weight x L_e = 2 m"},
        {"ch/boom/bb02/e0", Wc, "element force: the chain's weight"},
        {"ch/boom/bb03/e1", 1e5, "el03: the stated force"},
        {"ch/boom/bb03/e3", 2e5, "el03: the stated force x L_e"},
        {"ch/b_clamp/e2", 7850 * 0.01 * 1 * 9.81, "clamp: the end node's weight (half an element)"},
    };
    for (size_t i = 0; nom && i < sizeof u / sizeof u[0]; i++) {
        int v = bgr_find_var(m, u[i].path);
        tap_close(v >= 0 ? nom[v] : NAN, u[i].want, 1e-14, 0, "nominal of %s = %g (%s)",
                  u[i].path, u[i].want, u[i].why);
    }
    bgr_model_free(&m);
}

/* ---- parameter checks of the constructors ---- */

/* The constructors of mech_body.h, mech_parts.h, mech_sensor.h and mech_axial.h with parameter
 * which replaced by x (which < 0: all valid; integer parameters take (int) x). */
static double pk(int which, int k, double x, double good)
{
    return which == k ? x : good;
}
/* which 0: mass; 1..9: inertia[which - 1]; 10: gravity[1]; 11: r[4]; 12: dims[1];
 * 13: nports; 14: no inertia */
static int mk_body(bgr_model *m, bgr_comp c, const char *name, int which, double x)
{
    double J[9] = {1.0, 0.1, 0.0, 0.1, 2.0, 0.0, 0.0, 0.0, 3.0}, g[3] = {0, 0, -9.81};
    double r[6] = {0.5, 0, 0, -0.5, 0, 0};
    int dims[2] = {6, 3}, np = which == 13 ? (int)x : 2;
    if (which >= 1 && which <= 9) J[which - 1] = x;
    if (which == 10) g[1] = x;
    if (which == 11) r[4] = x;
    if (which == 12) dims[1] = (int)x;
    return mech_body(m, c, name, pk(which, 0, x, 3.0), which == 14 ? NULL : J, g, np, r, dims);
}
static int mk_point_mass(bgr_model *m, bgr_comp c, const char *name, int which, double x)
{
    double g[3] = {0, 0, -9.81};
    if (which == 1) g[0] = x;
    return mech_point_mass(m, c, name, pk(which, 0, x, 10.0), g);
}
static int mk_support(bgr_model *m, bgr_comp c, const char *name, int which, double x)
{
    return mech_support(m, c, name, which == 0 ? (int)x : 6);
}
static int mk_spherical(bgr_model *m, bgr_comp c, const char *name, int which, double x)
{
    return mech_spherical(m, c, name, which == 0 ? (int)x : 3);
}
/* which 0..2: axis[which]; 3: a zero axis; 4: the body (int) x */
static void pc_axis(int which, double x, double *a)
{
    a[0] = 0.0, a[1] = 0.0, a[2] = 2.0;
    if (which >= 0 && which < 3) a[which] = x;
    if (which == 3) a[2] = 0.0;
}
static int mk_revolute(bgr_model *m, bgr_comp c, const char *name, int which, double x)
{
    double a[3];
    pc_axis(which, x, a);
    return mech_revolute(m, c, name, which == 4 ? (int)x : -1, a, 1);
}
static int mk_rot_sensor(bgr_model *m, bgr_comp c, const char *name, int which, double x)
{
    double a[3];
    pc_axis(which, x, a);
    return mech_rotation_sensor(m, c, name, which == 4 ? (int)x : 0, a);
}
static int mk_spring(bgr_model *m, bgr_comp c, const char *name, int which, double x)
{
    return mech_spring(m, c, name, pk(which, 0, x, 100.0), pk(which, 1, x, 3.0),
                       pk(which, 2, x, 0.5));
}
/* which 0: E, 1: A, 2: L0, 3: c_damp; 4: E = A = x (their product overflows) */
static int mk_truss(bgr_model *m, bgr_comp c, const char *name, int which, double x)
{
    double E = which == 4 ? x : pk(which, 0, x, 2.1e11), A = which == 4 ? x : pk(which, 1, x, 1e-4);
    return mech_truss(m, c, name, E, A, pk(which, 2, x, 2.0), pk(which, 3, x, 0.0));
}
/* which 0: k, 1: c_damp, 2: L0, 3: eps; 4: L0 = x with the default width */
static int mk_rope(bgr_model *m, bgr_comp c, const char *name, int which, double x)
{
    double L0 = which == 4 ? x : pk(which, 2, x, 2.0), eps = which == 4 ? 0.0 : pk(which, 3, x, 0.01);
    return mech_rope(m, c, name, pk(which, 0, x, 1e6), pk(which, 1, x, 10.0), L0, eps);
}

/* Every constructor with bad parameters (NaN, infinities, 0 and negative numbers where refused,
 * an inertia tensor that is not symmetric positive definite, bad dimensions, zero axes, products
 * that overflow); one test point each (param_check.h). Then the hanging truss of
 * test_truss_rope built with a refusal before each element, under the refused names: it
 * compiles and stretches by F L / (E A). */
static void test_param_checks(void)
{
    const double nan = NAN, inf = INFINITY;
    const char *POS = "expected a finite number > 0", *NNEG = "expected a finite number >= 0";
    const char *FIN = "expected a finite number", *SPD = "symmetric positive definite matrix";
    const char *AX = "expected a nonzero finite axis";
    const pc_case cases[] = {
        {"mech_body", mk_body, 0, nan, "mass = ", POS},
        {"mech_body", mk_body, 0, inf, "mass = ", POS},
        {"mech_body", mk_body, 0, 0.0, "mass = ", POS},
        {"mech_body", mk_body, 0, -3.0, "mass = ", POS},
        {"mech_body", mk_body, 5, nan, "inertia[1,1] = nan", SPD},
        {"mech_body", mk_body, 9, inf, "inertia[2,2] = inf", SPD},
        {"mech_body", mk_body, 2, 0.3, "inertia[1,0] = 0.3 but inertia[0,1] = 0.1", SPD},
        {"mech_body", mk_body, 1, -1.0, "inertia is not positive definite (pivot 0", SPD},
        {"mech_body", mk_body, 9, 0.0, "inertia is not positive definite (pivot 2", SPD},
        {"mech_body", mk_body, 1, 0.005, "inertia is not positive definite (pivot 1", SPD},
        {"mech_body", mk_body, 14, 0, "the inertia tensor is NULL", "NULL"},
        {"mech_body", mk_body, 10, nan, "gravity[1] = ", FIN},
        {"mech_body", mk_body, 11, -inf, "r[4] = ", FIN},
        {"mech_body", mk_body, 12, 4, "dims[1] = 4", "expected 3 or 6"},
        {"mech_body", mk_body, 13, 65, "nports = 65", "expected 0 .. 64"},
        {"mech_body", mk_body, 13, -1, "nports = -1", "expected 0 .. 64"},
        {"mech_point_mass", mk_point_mass, 0, nan, "mass = ", POS},
        {"mech_point_mass", mk_point_mass, 0, inf, "mass = ", POS},
        {"mech_point_mass", mk_point_mass, 0, 0.0, "mass = ", POS},
        {"mech_point_mass", mk_point_mass, 0, -10.0, "mass = ", POS},
        {"mech_point_mass", mk_point_mass, 1, inf, "gravity[0] = ", FIN},
        {"mech_support", mk_support, 0, 4, "dim = 4", "expected 3 or 6"},
        {"mech_spherical", mk_spherical, 0, 0, "dim = 0", "expected 3 or 6"},
        {"mech_revolute", mk_revolute, 0, nan, "axis_a[0] = ", FIN},
        {"mech_revolute", mk_revolute, 2, inf, "axis_a[2] = ", FIN},
        {"mech_revolute", mk_revolute, 3, 0, "has length 0", AX},
        {"mech_revolute", mk_revolute, 4, -2, "body_a = -2", "expected -1"},
        {"mech_rotation_sensor", mk_rot_sensor, 1, -inf, "axis[1] = ", FIN},
        {"mech_rotation_sensor", mk_rot_sensor, 3, 0, "has length 0", AX},
        {"mech_rotation_sensor", mk_rot_sensor, 4, -1, "body = -1", "expected a body's"},
        {"mech_spring", mk_spring, 0, nan, "k = ", NNEG},
        {"mech_spring", mk_spring, 0, inf, "k = ", NNEG},
        {"mech_spring", mk_spring, 0, -100.0, "k = ", NNEG},
        {"mech_spring", mk_spring, 1, nan, "c_damp = ", NNEG},
        {"mech_spring", mk_spring, 1, -3.0, "c_damp = ", NNEG},
        {"mech_spring", mk_spring, 2, 0.0, "L0 = ", POS},
        {"mech_spring", mk_spring, 2, -0.5, "L0 = ", POS},
        {"mech_spring", mk_spring, 2, inf, "L0 = ", POS},
        {"mech_truss", mk_truss, 0, nan, "E = ", POS},
        {"mech_truss", mk_truss, 0, 0.0, "E = ", POS},
        {"mech_truss", mk_truss, 0, -2.1e11, "E = ", POS},
        {"mech_truss", mk_truss, 1, inf, "A = ", POS},
        {"mech_truss", mk_truss, 1, 0.0, "A = ", POS},
        {"mech_truss", mk_truss, 2, 0.0, "L0 = ", POS},
        {"mech_truss", mk_truss, 2, nan, "L0 = ", POS},
        {"mech_truss", mk_truss, 3, -1.0, "c_damp = ", NNEG},
        {"mech_truss", mk_truss, 4, 1e200, "E A / L0 = inf", "expected a finite stiffness"},
        {"mech_rope", mk_rope, 0, nan, "k = ", NNEG},
        {"mech_rope", mk_rope, 0, -1e6, "k = ", NNEG},
        {"mech_rope", mk_rope, 1, inf, "c_damp = ", NNEG},
        {"mech_rope", mk_rope, 2, 0.0, "L0 = ", POS},
        {"mech_rope", mk_rope, 2, nan, "L0 = ", POS},
        {"mech_rope", mk_rope, 3, nan, "eps = ", FIN},
        {"mech_rope", mk_rope, 3, inf, "eps = ", FIN},
        {"mech_rope", mk_rope, 4, 1e-321, "eps = 0 asks for the default width", "give eps > 0"},
    };
    int n = (int)(sizeof cases / sizeof cases[0]);
    bgr_model *m = bgr_model_create("params");
    bgr_comp c = bgr_component(m, bgr_component(m, 0, "frame"), "bad");
    int passed = pc_run(m, c, "x", cases, n);
    tap_diag("%d of %d refusals as required", passed, n);
    bgr_model_free(&m);

    /* the hanging truss, each element first refused under its name */
    const double E = 2.1e11, A = 1e-4, L = 2.0;
    double F[3] = {5e4, 0, 0}, Fbad[3] = {5e4, nan, 0};
    m = bgr_model_create("hang");
    int refused = 0;
    refused += mech_support(m, 0, "ground", 5) == BG_ERR_ARGUMENT;
    int gnd = mech_support(m, 0, "ground", 3);
    refused += mech_truss(m, 0, "bar", E, -A, L, 2e5) == BG_ERR_ARGUMENT;
    int ax = mech_truss(m, 0, "bar", E, A, L, 2e5);
    refused += mech_point_mass(m, 0, "mass", 0.0, NULL) == BG_ERR_ARGUMENT;
    int pm = mech_point_mass(m, 0, "mass", 10.0, NULL);
    int j = bgr_one(m, 0, "end", 3, 3);
    refused += bgr_Se(m, 0, "load", 3, Fbad) == BG_ERR_ARGUMENT;
    int src = bgr_Se(m, 0, "load", 3, F);
    bgr_bond(m, 0, "b0", 3, bgr_port_of(m, gnd, 0), bgr_port_of(m, ax, 0), NULL, NULL);
    bgr_bond(m, 0, "b1", 3, bgr_port_of(m, j, 0), bgr_port_of(m, ax, 1), NULL, NULL);
    bgr_bond(m, 0, "b2", 3, bgr_port_of(m, j, 1), bgr_port_of(m, pm, 0), NULL, NULL);
    bgr_bond(m, 0, "b3", 3, bgr_port_of(m, src, 0), bgr_port_of(m, j, 2), NULL, NULL);
    int st = bgr_compile(m), r = -1;
    double dl = NAN, want = F[0] * L / (E * A);
    if (st == BG_OK) {
        const double xa[3] = {0, 0, 0}, xb[3] = {L, 0, 0};
        mech_axial_set(m, ax, xa, xb);
        mech_point_mass_set(m, pm, xb, NULL);
        last_ctx l = {{0}, bgr_n(m)};
        double tout[1] = {0.5};
        r = integrate(m, 1e-7, tout, 1, last_probe, &l, NULL);
        dl = l.y[bgr_find_var(m, "hang/bar/d0")] - L;
    }
    tap_ok(refused == 4 && st == BG_OK && r == 0 && fabs(dl - want) / want < 1e-4,
           "the hanging truss built with a refusal before each element (%d of 4 refused) "
           "compiles (%d) and stretches by F L/(E A) = %.6e (got %.6e): '%s'",
           refused, st, want, dl, bgr_model_error(m)->message);
    bgr_model_free(&m);
}

int main(void)
{
    rng = tap_rng_seed(20261122);
    test_jacobians();
    test_free_body();
    test_driven_axis();
    test_pendulum();
    test_truss_rope();
    test_energies();
    test_nominals();
    test_param_checks();
    return tap_done();
}
