/* The pump's displacement actuator (hyd_pump_servo): the swash plate follows the command as a
 * first-order lag of the stated bandwidth.
 *   - step: a pump driven at constant speed between two tanks (fixed pressures), the command
 *     jumping from 0 to x at t = 0 with the plate at 0: plate, delivered flow and drawn torque
 *     against the closed forms s = x (1 - exp(-2 pi fc t)), q = s Dp w / (2 pi) - Cl dp,
 *     T = s Dp dp / (2 pi) at five times;
 *   - fc = 0 is hyd_pump: the same unknowns, equations and residual;
 *   - the analytic Jacobian against finite differences;
 *   - bandwidths that are negative, NaN or infinite refused, naming the element and fc. */
#include "cmptest.h"
#include "hyd_pump.h"
#include "hyd_source.h"
#include "sig_sources.h"

static const double Dp = 1e-4, Cl = 2e-11, wp = 150.0, pa = 2e6, pb = 12e6, X = 0.6;

/* drive -> pump; tank a -> pump inlet; pump outlet -> tank b (power into the tank: a flow
 * source's port takes the bond's tail, so the outlet bond runs from the tank with -q). */
static bgr_model *pump_rig(double fc, int plain)
{
    bgr_model *m = bgr_model_create("rig");
    int drive = bgr_Sf(m, 0, "drive", 1, &wp);
    int cmd = sig_step(m, 0, "x", 0.0, 0.0, X, SIG_VALUE);
    int pump = plain ? hyd_pump(m, 0, "pump", Dp, Cl, (bgr_ref){BGR_OWN, cmd, 0})
                     : hyd_pump_servo(m, 0, "pump", Dp, Cl, (bgr_ref){BGR_OWN, cmd, 0}, fc);
    int ta = hyd_tank(m, 0, "tank_a", pa), tb = hyd_tank(m, 0, "tank_b", pb);
    B(m, "shaft", drive, 0, pump, 0);
    B(m, "in", ta, 0, pump, 1);
    B(m, "out", tb, 0, pump, 2);
    return m;
}

static void test_step(void)
{
    const double fc = 5.0, wc = 2 * PI * fc;
    bgr_model *m = pump_rig(fc, 0);
    if (!compile_ok(m, "pump with a 5 Hz actuator")) {
        bgr_model_free(&m);
        return;
    }
    int vs = V(m, "rig/pump/swash"), vq = V(m, "rig/out/f"), vT = V(m, "rig/shaft/e");
    tap_ok(vs >= 0 && bgr_kinds(m)[vs] == DAE_DIFF, "the swash plate is a state");
    dae_solver *s = solver_new(m, 1e-10, 1e-12, NULL, NULL, 0, 0.0);
    int n = bgr_n(m);
    double *y = calloc(2 * (size_t)n, sizeof *y), *yp = y + n;
    const double ts[5] = {0.01, 0.03, 0.1, 0.3, 1.0};
    double worst_s = 0, worst_q = 0, worst_T = 0;
    for (int k = 0; s && k < 5; k++) {
        if (solve_to(s, ts[k], y, yp) < 0) break;
        double se = X * (1 - exp(-wc * ts[k]));
        double qe = se * Dp * wp / (2 * PI) - Cl * (pb - pa), Te = se * Dp * (pb - pa) / (2 * PI);
        /* the outlet bond runs from tank b into the pump: its flow is minus the delivery */
        worst_s = fmax(worst_s, fabs(at(y, vs) - se) / X);
        worst_q = fmax(worst_q, fabs(-at(y, vq) - qe) / fabs(qe));
        worst_T = fmax(worst_T, fabs(at(y, vT) - Te) / fabs(Te));
        if (k == 0)
            tap_diag("t = %g: plate %.9g (closed form %.9g), flow %.9g m^3/s, torque %.9g N m",
                     ts[k], at(y, vs), se, -at(y, vq), at(y, vT));
    }
    tap_ok(s && worst_s < 1e-7, "plate s = x (1 - exp(-2 pi fc t)) within %.2e of x", worst_s);
    tap_ok(s && worst_q < 1e-7, "delivered flow s Dp w / (2 pi) - Cl dp within %.2e", worst_q);
    tap_ok(s && worst_T < 1e-7, "drawn torque s Dp dp / (2 pi) within %.2e", worst_T);
    /* 63 % of the step after one time constant */
    double t1 = 1.0 / wc;
    dae_free(&s);
    s = solver_new(m, 1e-10, 1e-12, NULL, NULL, 0, 0.0);
    if (s && solve_to(s, t1, y, yp) >= 0)
        tap_close(at(y, vs) / X, 1 - exp(-1.0), 1e-7, 0,
                  "after 1 / (2 pi fc) = %.4g s the plate is at %.4f of the step", t1,
                  at(y, vs) / X);
    /* the Jacobian at a random point, pressures of the size they have (the leakage term Cl dp
     * is lost in the differences' rounding at pressures of 1 Pa) */
    double *scale = malloc((size_t)n * sizeof *scale);
    for (int i = 0; i < n; i++) {
        const char *nm = bgr_var_name(m, i);
        scale[i] = strstr(nm, "/in/e") || strstr(nm, "/out/e") ? 1e7 : 1.0;
    }
    random_point(n, scale, 7, y, yp);
    free(scale);
    check_jac(m, 0.3, y, yp, 1e-6, "pump with actuator");
    dae_free(&s);
    free(y);
    bgr_model_free(&m);
}

static void test_zero_is_plain(void)
{
    bgr_model *a = pump_rig(0.0, 0), *b = pump_rig(0.0, 1);
    int ok = compile_ok(a, "hyd_pump_servo with fc = 0") && compile_ok(b, "hyd_pump");
    int n = ok ? bgr_n(a) : 0;
    tap_ok(ok && n == bgr_n(b) && bgr_find_var(a, "rig/pump/swash") < 0,
           "fc = 0: %d unknowns as the plain pump's %d, no actuator state", n, ok ? bgr_n(b) : 0);
    if (ok && n == bgr_n(b)) {
        double *y = calloc(4 * (size_t)n, sizeof *y), *yp = y + n, *Fa = yp + n, *Fb = Fa + n;
        random_point(n, NULL, 11, y, yp);
        int ra = bgr_residual(a, 0.2, y, yp, Fa), rb = bgr_residual(b, 0.2, y, yp, Fb);
        double d = 0;
        for (int i = 0; i < n; i++)
            d = fmax(d, fabs(Fa[i] - Fb[i]));
        tap_ok(ra == 0 && rb == 0 && d == 0, "and the same residual at a random point (%.2g)", d);
        free(y);
    }
    bgr_model_free(&a);
    bgr_model_free(&b);
}

static void test_refused(void)
{
    const double bad[3] = {-1.0, NAN, INFINITY};
    for (int k = 0; k < 3; k++) {
        bgr_model *m = bgr_model_create("args");
        int cmd = sig_constant(m, 0, "x", 0.5, SIG_VALUE);
        int id = hyd_pump_servo(m, 0, "p", Dp, Cl, (bgr_ref){BGR_OWN, cmd, 0}, bad[k]);
        const char *msg = bgr_model_error(m)->message;
        tap_ok(id == BG_ERR_ARGUMENT && strstr(msg, "args/p (hyd_pump_servo)") && strstr(msg, "fc"),
               "bandwidth %g refused: %s", bad[k], msg);
        bgr_model_free(&m);
    }
}

int main(void)
{
    test_step();
    test_zero_is_plain();
    test_refused();
    return tap_done();
}
