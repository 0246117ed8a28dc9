/* The user's callback controller (ctl_user.h) in a closed loop against its closed form, with
 * the callback's derivatives and with the element's differences; its Jacobian against central
 * differences; bad specifications refused.
 *
 * Loop: an inertia J = 1 (rot_inertia) under the torque u = f(theta, omega) = -k1 theta - k2 omega
 * with k1 = 2, k2 = sqrt 5, from theta(0) = 1 at rest: theta'' + k2 theta' + k1 theta = 0, roots
 * s +- i b with s = -sqrt 5 / 2, b = sqrt 3 / 2, theta = e^(s t) (cos(b t) - (s / b) sin(b t)).
 * The same law through the header's example form (a tanh limit of a small argument would not
 * be linear, so the loop uses the linear law; the example's derivatives are checked at random
 * points). */
#include "cmptest.h"
#include "ctl_user.h"
#include "rot_inertia.h"
#include "sensors.h"
#include "sig_sources.h"

static int linear_law(void *user, double t, const double *x, double *u, double *jac)
{
    (void)t;
    const double *k = user;
    u[0] = -k[0] * x[0] - k[1] * x[1];
    if (jac) {
        jac[0] = -k[0];
        jac[1] = -k[1];
    }
    return 0;
}

/* the header's example: u = tanh(kp (x0 - x1) + kff x2), and a second output x0 x1 */
static int example_law(void *user, double t, const double *x, double *u, double *jac)
{
    (void)t;
    const double *k = user;
    double v = k[0] * (x[0] - x[1]) + k[1] * x[2], th = tanh(v);
    u[0] = th;
    u[1] = x[0] * x[1];
    if (jac) {
        double d = 1 - th * th;
        jac[0] = d * k[0];
        jac[2] = -d * k[0];
        jac[4] = d * k[1];
        jac[1] = x[1];
        jac[3] = x[0];
        jac[5] = 0;
    }
    return 0;
}

static void test_loop(int has_jacobian)
{
    static double k[2];
    k[0] = 2;
    k[1] = sqrt(5.0);
    bgr_model *m = bgr_model_create("loop");
    int in = rot_inertia(m, 0, "body", 1.0);
    int ang = rot_sensor(m, 0, "angle", in, ROT_ANGLE), vel = rot_sensor(m, 0, "omega", in, ROT_VELOCITY);
    ctl_user_spec s = {.n_in = 2,
                       .n_out = 1,
                       .in = {{BGR_OWN, ang, 0}, {BGR_OWN, vel, 0}},
                       .fn = linear_law,
                       .user = k,
                       .has_jacobian = has_jacobian};
    int id = ctl_user(m, 0, "law", &s);
    int se = bgr_Se_signal(m, 0, "torque", (bgr_ref){BGR_OWN, id, 0});
    B(m, "drive", se, 0, in, 0);
    if (!compile_ok(m, has_jacobian ? "loop, callback's derivatives" : "loop, differences")) {
        bgr_model_free(&m);
        return;
    }
    bgr_y0(m)[bgr_ref_var(m, (bgr_ref){BGR_STATE, in, 1})] = 1.0;
    dae_solver *sv = solver_new(m, 1e-9, 1e-11, NULL, NULL, 0, 0.0);
    int n = bgr_nvars(m), th = bgr_ref_var(m, (bgr_ref){BGR_STATE, in, 1});
    double *y = calloc((size_t)n, sizeof *y), *yp = calloc((size_t)n, sizeof *yp);
    double sr = -sqrt(5.0) / 2, b = sqrt(3.0) / 2, worst = 0;
    int ok = sv != NULL;
    for (int i = 1; i <= 10 && ok; i++) {
        double t = 0.5 * i;
        ok = solve_to(sv, t, y, yp) >= 0;
        worst = fmax(worst, fabs(y[th] - exp(sr * t) * (cos(b * t) - (sr / b) * sin(b * t))));
    }
    tap_ok(ok && worst < 1e-6,
           "%s: theta(t) against the closed form, largest error %.1e over 0.5 .. 5 s",
           has_jacobian ? "callback's derivatives" : "element's differences", worst);
    dae_free(&sv);
    free(y);
    free(yp);
    bgr_model_free(&m);
}

static void test_jacobian_and_checks(void)
{
    static double k[2] = {5, 0.05};
    bgr_model *m = bgr_model_create("ex");
    int a = sig_constant(m, 0, "a", 0.3, SIG_VALUE), b = sig_constant(m, 0, "b", 0.1, SIG_VALUE),
        c = sig_constant(m, 0, "c", 2.0, SIG_VALUE);
    ctl_user_spec s = {.n_in = 3,
                       .n_out = 2,
                       .in = {{BGR_OWN, a, 0}, {BGR_OWN, b, 0}, {BGR_OWN, c, 0}},
                       .fn = example_law,
                       .user = k,
                       .has_jacobian = 1};
    ctl_user(m, 0, "with", &s);
    s.has_jacobian = 0;
    ctl_user(m, 0, "without", &s);
    if (compile_ok(m, "the header's example")) {
        int n = bgr_nvars(m);
        double *y = calloc((size_t)n, sizeof *y), *yp = calloc((size_t)n, sizeof *yp);
        random_point(n, NULL, 7, y, yp);
        check_jac(m, 0.3, y, yp, 1e-6, "user controller (callback's and differenced)");
        free(y);
        free(yp);
    }
    bgr_model_free(&m);
    m = bgr_model_create("bad");
    s.fn = NULL;
    int r1 = ctl_user(m, 0, "nofn", &s);
    s.fn = example_law;
    s.n_out = 0;
    int r2 = ctl_user(m, 0, "noout", &s);
    tap_ok(r1 == BG_ERR_ARGUMENT && r2 == BG_ERR_ARGUMENT &&
               strstr(bgr_model_error(m)->message, "n_out = 0"),
           "no callback, no outputs: refused (%s)", bgr_model_error(m)->message);
    bgr_model_free(&m);
}

int main(void)
{
    test_loop(1);
    test_loop(0);
    test_jacobian_and_checks();
    return tap_done();
}
