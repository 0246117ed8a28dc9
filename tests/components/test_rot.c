/* Rotational components: inertia with angle (rot_inertia), viscous friction (rot_damper), gear
 * (rot_gear) and the sensors (sensors.h): spin-down and constant-torque runs against their closed
 * forms, power through the gear, and the analytic Jacobian; the parameter checks of the inertia,
 * the damper and the sensor (bad values refused with messages naming the element's path and the
 * parameter). */
#include "bondgraph/param_check.h"
#include "cmptest.h"
#include "rot_damper.h"
#include "rot_gear.h"
#include "rot_inertia.h"
#include "sensors.h"

/* An inertia J spinning at w0 on a damper b (1-junction): w = w0 exp(-b t / J),
 * theta = (J w0 / b)(1 - exp(-b t / J)), torque on the inertia -b w. */
static void test_spin_down(void)
{
    const double J = 2.0, b = 0.5, w0 = 3.0;
    bgr_model *m = bgr_model_create("spin");
    int in = rot_inertia(m, 0, "disk", J);
    int d = rot_damper(m, 0, "bearing", b);
    int j = bgr_one(m, 0, "shaft", 2, 1);
    int sw = rot_sensor(m, 0, "w", in, ROT_VELOCITY),
        sa = rot_sensor(m, 0, "a", in, ROT_ACCELERATION);
    (void)sw, (void)sa;
    B(m, "b1", j, 0, in, 0);
    B(m, "b2", j, 1, d, 0);
    if (!compile_ok(m, "spin-down")) {
        bgr_model_free(&m);
        return;
    }
    bgr_y0(m)[bgr_ref_var(m, (bgr_ref){BGR_STATE, in, 0})] = J * w0; /* momentum */
    dae_solver *s = solver_new(m, 1e-10, 1e-12, NULL, NULL, 0, 0.0);
    int n = bgr_n(m), vth = V(m, "spin/disk/angle"), vw = V(m, "spin/w/velocity");
    int va = V(m, "spin/a/acceleration"), vf = V(m, "spin/b1/f");
    double *y = calloc((size_t)n, sizeof *y), *yp = calloc((size_t)n, sizeof *yp);
    double worst = 0;
    int ok = s != NULL;
    for (int k = 1; ok && k <= 5; k++) {
        double t = 2.0 * k, e = exp(-b * t / J);
        ok = solve_to(s, t, y, yp) >= 0;
        worst = fmax(worst, fabs(at(y, vw) - w0 * e) / w0);
        worst = fmax(worst, fabs(at(y, vf) - w0 * e) / w0);
        worst = fmax(worst, fabs(at(y, va) + b / J * w0 * e) / w0);
        worst = fmax(worst, fabs(at(y, vth) - J * w0 / b * (1 - e)) / (J * w0 / b));
    }
    tap_ok(ok && worst < 1e-7,
           "spin-down: w, bond flow, acceleration, angle against w0 exp(-bt/J) and its integral "
           "(max rel. error %.3g)",
           worst);
    dae_free(&s);
    free(y);
    free(yp);
    bgr_model_free(&m);
}

/* A constant torque T on the input shaft of a gear of ratio i driving an inertia J at the
 * output: J_eff = J / i^2 at the input, w_in = i w_out, w_out = (i T / J) t,
 * theta_out = (i T / J) t^2 / 2; power T w_in = T_out w_out. The gear's input bond is drawn
 * backwards (from the gear to the source). */
static void test_gear(void)
{
    const double T = 1.5, i = 4.0, J = 8.0;
    bgr_model *m = bgr_model_create("gear");
    int src = bgr_Se(m, 0, "motor", 1, &T);
    int g = rot_gear(m, 0, "box", i);
    int in = rot_inertia(m, 0, "drum", J);
    B(m, "in", g, 0, src, 0);
    B(m, "out", g, 1, in, 0);
    if (!compile_ok(m, "gear")) {
        bgr_model_free(&m);
        return;
    }
    dae_solver *s = solver_new(m, 1e-10, 1e-12, NULL, NULL, 0, 0.0);
    int n = bgr_n(m), vth = V(m, "gear/drum/angle");
    int ei = V(m, "gear/in/e"), fi = V(m, "gear/in/f"), eo = V(m, "gear/out/e"),
        fo = V(m, "gear/out/f");
    double *y = calloc((size_t)n, sizeof *y), *yp = calloc((size_t)n, sizeof *yp);
    double t = 0, worst = 0, pw = 0;
    int r = s ? 0 : -1;
    while (r >= 0 && t < 3.0) {
        r = dae_step(s, 3.0, &t, y, yp);
        double a = i * T / J;
        worst = fmax(worst, fabs(at(y, fo) - a * t) / (a * 3));
        worst = fmax(worst, fabs(-at(y, fi) - i * a * t) / (i * a * 3)); /* reversed bond */
        worst = fmax(worst, fabs(at(y, vth) - a * t * t / 2) / (a * 4.5));
        worst = fmax(worst, fabs(at(y, eo) - i * T) / (i * T));
        double pin = at(y, ei) * -at(y, fi), pout = at(y, eo) * at(y, fo);
        if (t > 0) pw = fmax(pw, fabs(pin - pout) / fabs(pin));
    }
    tap_ok(r >= 0 && worst < 1e-7,
           "gear: output speed (iT/J) t, input speed i times it, output torque i T, drum angle "
           "(max rel. error %.3g)",
           worst);
    tap_ok(pw < 1e-9, "gear: power in = power out at every step (max rel. diff %.3g)", pw);
    dae_free(&s);
    free(y);
    free(yp);
    bgr_model_free(&m);
}

static void test_jacobian(void)
{
    bgr_model *m = bgr_model_create("jac");
    const double T = 0.7;
    int src = bgr_Se(m, 0, "motor", 1, &T);
    int g = rot_gear(m, 0, "box", -2.5);
    int j = bgr_one(m, 0, "shaft", 3, 1);
    int in = rot_inertia(m, 0, "drum", 1.7);
    int d = rot_damper(m, 0, "friction", 0.6);
    int s1 = rot_sensor(m, 0, "th", in, ROT_ANGLE), s2 = rot_sensor(m, 0, "w", in, ROT_VELOCITY);
    int s3 = rot_sensor(m, 0, "a", in, ROT_ACCELERATION);
    (void)s1, (void)s2, (void)s3;
    B(m, "in", src, 0, g, 0);
    B(m, "out", g, 1, j, 0);
    B(m, "to_drum", in, 0, j, 1); /* reversed */
    B(m, "to_friction", j, 2, d, 0);
    if (compile_ok(m, "jacobian")) {
        int n = bgr_n(m);
        double *y = malloc((size_t)n * sizeof *y), *yp = malloc((size_t)n * sizeof *yp);
        random_point(n, NULL, 31, y, yp);
        check_jac(m, 0.0, y, yp, 1e-6, "gear, inertia, damper, sensors");
        free(y);
        free(yp);
    }
    bgr_model_free(&m);
}

/* The parameters of the inertia, the damper and the sensor (headers: the accepted ranges): NaN,
 * infinities, 0 and negative numbers where refused, a J whose inverse overflows, an unknown
 * quantity and an element that is no inertia; one test point each (param_check.h). */
static int pc_inertia = -1, pc_damper = -1; /* a valid inertia and a damper for the sensor */
static double pk(int which, int k, double x, double good)
{
    return which == k ? x : good;
}
static int mk_inertia(bgr_model *m, bgr_comp c, const char *name, int which, double x)
{
    return rot_inertia(m, c, name, pk(which, 0, x, 2.0));
}
static int mk_damper(bgr_model *m, bgr_comp c, const char *name, int which, double x)
{
    return rot_damper(m, c, name, pk(which, 0, x, 0.5));
}
/* which 0: the quantity, 1: the inertia's id, 2: the damper's id */
static int mk_sensor(bgr_model *m, bgr_comp c, const char *name, int which, double x)
{
    int q = which == 0 ? (int)x : ROT_VELOCITY;
    int in = which == 1 ? (int)x : which == 2 ? pc_damper : pc_inertia;
    return rot_sensor(m, c, name, in, (rot_quantity)q);
}

static void test_param_checks(void)
{
    const double nan = NAN, inf = INFINITY;
    const char *POS = "expected a finite number > 0", *NNEG = "expected a finite number >= 0";
    const char *RI = "expected the id of a rot_inertia element";
    const pc_case cases[] = {
        {"rot_inertia", mk_inertia, 0, nan, "J = ", POS},
        {"rot_inertia", mk_inertia, 0, inf, "J = ", POS},
        {"rot_inertia", mk_inertia, 0, 0.0, "J = ", POS},
        {"rot_inertia", mk_inertia, 0, -2.0, "J = ", POS},
        {"rot_inertia", mk_inertia, 0, 1e-310, "J = ", "with a finite 1 / J"},
        {"rot_damper", mk_damper, 0, nan, "b = ", NNEG},
        {"rot_damper", mk_damper, 0, inf, "b = ", NNEG},
        {"rot_damper", mk_damper, 0, -0.5, "b = ", NNEG},
        {"rot_sensor", mk_sensor, 0, 3, "quantity q = 3", "expected ROT_ANGLE"},
        {"rot_sensor", mk_sensor, 0, -1, "quantity q = -1", "expected ROT_ANGLE"},
        {"rot_sensor", mk_sensor, 1, -1, "inertia = -1", RI},
        {"rot_sensor", mk_sensor, 1, 99, "inertia = 99", RI},
        {"rot_sensor", mk_sensor, 2, 0, "inertia = ", RI},
    };
    int n = (int)(sizeof cases / sizeof cases[0]);
    bgr_model *m = bgr_model_create("params");
    pc_inertia = rot_inertia(m, 0, "disk", 1.0);
    pc_damper = rot_damper(m, 0, "bearing", 1.0);
    bgr_comp c = bgr_component(m, bgr_component(m, 0, "shaft"), "bad");
    int passed = pc_run(m, c, "x", cases, n);
    tap_diag("%d of %d refusals as required", passed, n);
    bgr_model_free(&m);
}

int main(void)
{
    test_spin_down();
    test_gear();
    test_jacobian();
    test_param_checks();
    return tap_done();
}
