/* Hydraulic volume (hyd_volume) with sources (hyd_source), laminar leakage and the relief valve
 * (hyd_valve), and a motor (hyd_motor) driving an inertia (rot_inertia) read by sensors: the
 * exponential pressure transient, the hydraulic natural frequency, the pressure cap of the relief
 * valve, and the analytic Jacobian. The parameter checks of the volume, the leakage and the
 * relief valve: bad values refused with messages naming the element's path and the parameter,
 * and a model built through refusals works. */
#include "bondgraph/param_check.h"
#include "cmptest.h"
#include "hyd_motor.h"
#include "hyd_source.h"
#include "hyd_valve.h"
#include "hyd_volume.h"
#include "rot_inertia.h"
#include "sensors.h"

/* Constant flow Q into a volume V with a laminar leak G to the tank (p = 0):
 *   (V / beta) p' = Q - G p,  p(0) = 0  =>  p(t) = (Q / G) (1 - exp(-t / tau)), tau = V / (beta G).
 * The leak is drawn against the power direction (its bond starts at the leak), which must not
 * change anything. */
static void test_transient(void)
{
    const double Q = 1e-4, G = 1e-11, Vol = 1e-3, beta = 1.4e9;
    const double pss = Q / G, tau = Vol / (beta * G);
    bgr_model *m = bgr_model_create("rc");
    int src = hyd_flow_source(m, 0, "pump", Q);
    int vol = hyd_volume(m, 0, "line", 2, Vol, beta);
    int leak = hyd_leakage(m, 0, "leak", G);
    int tank = hyd_tank(m, 0, "tank", 0.0);
    B(m, "feed", src, 0, vol, 0);
    B(m, "out", vol, 1, leak, 0);
    B(m, "drain", tank, 0, leak, 1); /* reversed: power from the tank into the leak's port b */
    if (!compile_ok(m, "volume with leak")) {
        bgr_model_free(&m);
        return;
    }
    dae_solver *s = solver_new(m, 1e-10, 1e-12, NULL, NULL, 0, 0.0);
    int n = bgr_n(m), vp = V(m, "rc/line/p"), vq = V(m, "rc/out/f");
    double *y = calloc((size_t)n, sizeof *y), *yp = calloc((size_t)n, sizeof *yp);
    const double ts[4] = {0.1 * tau, tau, 3 * tau, 10 * tau};
    double worst = 0;
    int ok = s != NULL;
    for (int k = 0; ok && k < 4; k++) {
        ok = solve_to(s, ts[k], y, yp) >= 0;
        double want = pss * (1 - exp(-ts[k] / tau));
        worst = fmax(worst, fabs(at(y, vp) - want) / want);
        if (k == 1)
            tap_close(at(y, vp), pss * (1 - exp(-1.0)), 1e-7, 0,
                      "p(tau) = (Q/G)(1 - 1/e) = %.6g Pa (tau = V/(beta G) = %.6g s)",
                      pss * (1 - exp(-1.0)), tau);
    }
    tap_ok(ok && worst < 1e-7,
           "p(t) = (Q/G)(1 - exp(-t/tau)) at 0.1, 1, 3, 10 tau (max rel. error %.3g)", worst);
    tap_close(at(y, vq), G * at(y, vp), 1e-9, 0, "leak flow = G p at 10 tau");
    dae_free(&s);
    free(y);
    free(yp);
    bgr_model_free(&m);
}

/* Flow source Q -> volume V -> motor D (no leakage, no friction) -> inertia J, outlet to tank:
 *   (V / beta) p' = Q - D w / (2 pi),  J w' = D p / (2 pi),  p(0) = w(0) = 0
 * => w'' + wn^2 w = wn^2 w_ss with wn^2 = beta D^2 / (4 pi^2 V J), w_ss = 2 pi Q / D:
 *   w = w_ss (1 - cos wn t),  theta = w_ss (t - sin(wn t) / wn),
 *   p = (2 pi J / D) w_ss wn sin(wn t), zero at t = k pi / wn. */
static void test_natural_frequency(void)
{
    const double Q = 1e-4, Vol = 1e-3, beta = 1.4e9, D = 1e-4, J = 1.0;
    const double wn = sqrt(beta * D * D / (4 * PI * PI * Vol * J)), wss = 2 * PI * Q / D;
    const double amp = 2 * PI * J / D * wss * wn;
    bgr_model *m = bgr_model_create("osc");
    int src = hyd_flow_source(m, 0, "pump", Q);
    int vol = hyd_volume(m, 0, "line", 2, Vol, beta);
    int mot = hyd_motor(m, 0, "motor", D, 0.0, 0.0);
    int tank = hyd_tank(m, 0, "tank", 0.0);
    int in = rot_inertia(m, 0, "load", J);
    int sw = rot_sensor(m, 0, "w", in, ROT_VELOCITY);
    int sth = rot_sensor(m, 0, "theta", in, ROT_ANGLE);
    int sa = rot_sensor(m, 0, "alpha", in, ROT_ACCELERATION);
    B(m, "feed", src, 0, vol, 0);
    B(m, "in", vol, 1, mot, 0);
    B(m, "ret", mot, 1, tank, 0); /* reversed: the motor's outlet bond ends at the tank */
    B(m, "shaft", mot, 2, in, 0);
    tap_ok(sw >= 0 && sth >= 0 && sa >= 0, "sensors created");
    if (!compile_ok(m, "oscillator")) {
        bgr_model_free(&m);
        return;
    }
    dae_solver *s = solver_new(m, 1e-10, 1e-12, NULL, NULL, 0, 0.0);
    int n = bgr_n(m), vp = V(m, "osc/line/p"), vw = V(m, "osc/w/velocity");
    int vth = V(m, "osc/theta/angle"), va = V(m, "osc/alpha/acceleration");
    double *y = calloc((size_t)n, sizeof *y), *yp = calloc((size_t)n, sizeof *yp);
    double *yc = calloc((size_t)n, sizeof *yc);
    double cross[32], t = 0, pprev = 0, pmax = 0, senserr = 0;
    int nc = 0, r = s ? 0 : -1;
    const double tend = 10.5 * PI / wn * 2; /* ten and a half periods */
    while (r >= 0 && t < tend) {
        double tprev = t;
        r = dae_step(s, tend, &t, y, yp);
        if (r < 0) break;
        double p = at(y, vp);
        pmax = fmax(pmax, p);
        /* sensors against the closed form at every step */
        senserr = fmax(senserr, fabs(at(y, vw) - wss * (1 - cos(wn * t))) / wss);
        senserr = fmax(senserr, fabs(at(y, vth) - wss * (t - sin(wn * t) / wn)) / (wss * t));
        senserr = fmax(senserr, fabs(at(y, va) - wss * wn * sin(wn * t)) / (wss * wn));
        if (tprev > 0 && (pprev > 0) != (p > 0) && nc < 32) { /* bisection on the interpolant */
            double a = tprev, b = t, pa = pprev;
            for (int it = 0; it < 100 && b - a > 1e-14 * b; it++) {
                double c = 0.5 * (a + b);
                dae_dense(s, c, yc, NULL);
                if ((yc[vp] > 0) == (pa > 0))
                    a = c, pa = yc[vp];
                else
                    b = c;
            }
            cross[nc++] = 0.5 * (a + b);
        }
        pprev = p;
    }
    tap_ok(r >= 0 && nc == 21, "oscillator: integrated over 10.5 periods, %d zero crossings of p",
           nc);
    if (nc >= 2) {
        double period = 2 * (cross[nc - 1] - cross[0]) / (nc - 1);
        tap_close(period, 2 * PI / wn, 1e-6, 0,
                  "observed period %.9f s = 2 pi / sqrt(beta D^2 / (4 pi^2 V J)) = %.9f s "
                  "(wn = %.6f rad/s)",
                  period, 2 * PI / wn, wn);
        tap_close(cross[0], PI / wn, 1e-6, 0, "first zero crossing of p at pi / wn");
        tap_diag("period: relative error %.3g", fabs(period * wn / (2 * PI) - 1));
    }
    tap_close(pmax, amp, 1e-4, 0, "pressure amplitude (2 pi J / D) w_ss wn = %.6g Pa", amp);
    tap_ok(senserr < 1e-5, "sensors: w, theta, alpha against the closed form (max rel. error %.3g)",
           senserr);
    dae_free(&s);
    free(y);
    free(yp);
    free(yc);
    bgr_model_free(&m);
}

/* Two relief valves (cracking p_c = 100 bar, full flow p_f = 120 bar at q_r = 2 l/s, width
 * eps = 0.2 bar) on volumes fed with Q1 = 1 l/s and Q2 = 0.02 l/s (= G eps). The steady pressure
 * solves Q = G eps ln(1 + exp((p - p_c)/eps)):
 *   p = p_c + eps ln(exp(Q / (G eps)) - 1),
 * inside the stated band [p_c + Q/G - eps ln(1/(1 - exp(-Q/(G eps)))), p_c + Q/G], below p_f. */
static void test_relief(void)
{
    const double pc = 1e7, pf = 1.2e7, qr = 2e-3, eps = 2e4, Vol = 1e-3, beta = 1.4e9;
    const double G = qr / (pf - pc), Qs[2] = {1e-3, 2e-5};
    bgr_model *m = bgr_model_create("relief");
    for (int k = 0; k < 2; k++) {
        char nm[4][16];
        snprintf(nm[0], 16, "pump%d", k);
        snprintf(nm[1], 16, "line%d", k);
        snprintf(nm[2], 16, "valve%d", k);
        snprintf(nm[3], 16, "tank%d", k);
        int src = hyd_flow_source(m, 0, nm[0], Qs[k]);
        int vol = hyd_volume(m, 0, nm[1], 2, Vol, beta);
        int rv = hyd_relief_valve(m, 0, nm[2], pc, pf, qr, eps);
        int tank = hyd_tank(m, 0, nm[3], 0.0);
        snprintf(nm[0], 16, "feed%d", k);
        snprintf(nm[1], 16, "vin%d", k);
        snprintf(nm[2], 16, "vout%d", k);
        B(m, nm[0], src, 0, vol, 0);
        B(m, nm[1], vol, 1, rv, 0);
        B(m, nm[2], rv, 1, tank, 0);
    }
    if (!compile_ok(m, "relief valves")) {
        bgr_model_free(&m);
        return;
    }
    dae_solver *s = solver_new(m, 1e-10, 1e-12, NULL, NULL, 0, 0.0);
    int n = bgr_n(m), vp[2] = {V(m, "relief/line0/p"), V(m, "relief/line1/p")};
    int vq[2] = {V(m, "relief/vin0/f"), V(m, "relief/vin1/f")};
    double *y = calloc((size_t)n, sizeof *y), *yp = calloc((size_t)n, sizeof *yp);
    double t = 0, pmax[2] = {0, 0};
    int r = s ? 0 : -1;
    while (r >= 0 && t < 1.0) {
        r = dae_step(s, 1.0, &t, y, yp);
        for (int k = 0; k < 2; k++)
            pmax[k] = fmax(pmax[k], at(y, vp[k]));
    }
    if (r >= 0) r = solve_to(s, 1.0, y, yp);
    tap_ok(r >= 0, "relief valves: integrated to t = 1 s");
    for (int k = 0; k < 2; k++) {
        double Q = Qs[k], x = Q / (G * eps);
        double pss = pc + eps * log(exp(x) - 1), ideal = pc + Q / G;
        double below = eps * log(1 / (1 - exp(-x)));
        tap_close(at(y, vp[k]), pss, 1e-9, 0,
                  "Q = %g m^3/s: steady pressure p_c + eps ln(exp(Q/(G eps)) - 1) = %.9g Pa", Q,
                  pss);
        tap_close(at(y, vq[k]), Q, 1e-8, 0, "Q = %g: the valve passes the whole flow", Q);
        tap_ok(pmax[k] <= ideal * (1 + 1e-9) && pmax[k] <= pf,
               "Q = %g: pressure never above p_c + Q/G = %.6g <= p_f (max %.9g)", Q, ideal,
               pmax[k]);
        tap_ok(at(y, vp[k]) >= ideal - below * (1 + 1e-6) && at(y, vp[k]) >= pc,
               "Q = %g: inside the band [p_c + Q/G - %.4g, p_c + Q/G] (deficit %.4g Pa)", Q, below,
               ideal - at(y, vp[k]));
    }
    tap_ok(fabs(eps * log(1 / (1 - exp(-1.0))) / eps - 0.4587) < 1e-4,
           "band width at Q = G eps: 0.46 eps, as stated in hyd_valve.h");
    dae_free(&s);
    free(y);
    free(yp);
    bgr_model_free(&m);
}

/* Every partial derivative: a 4-port volume with bonds of both orientations, leak, relief valve
 * near its cracking pressure, motor with leakage and friction, sources, inertia with sensors. */
static void test_jacobian(void)
{
    bgr_model *m = bgr_model_create("jac");
    int src = hyd_flow_source(m, 0, "pump", 0.7);
    int vol = hyd_volume(m, 0, "line", 4, 0.8, 1.9);
    int leak = hyd_leakage(m, 0, "leak", 0.35);
    int rv = hyd_relief_valve(m, 0, "relief", 0.9, 1.6, 0.8, 0.4);
    int mot = hyd_motor(m, 0, "motor", 1.3, 0.2, 0.45);
    int tank = hyd_tank(m, 0, "tank", 0.1);
    int low = bgr_zero(m, 0, "low", 4, 1);
    int in = rot_inertia(m, 0, "load", 0.9);
    int sw = rot_sensor(m, 0, "w", in, ROT_VELOCITY);
    int sa = rot_sensor(m, 0, "a", in, ROT_ACCELERATION);
    (void)sw, (void)sa;
    B(m, "feed", src, 0, vol, 0);
    B(m, "to_leak", leak, 0, vol, 1); /* reversed */
    B(m, "to_relief", vol, 2, rv, 0);
    B(m, "to_motor", vol, 3, mot, 0);
    B(m, "leak_out", leak, 1, low, 0);
    B(m, "relief_out", low, 1, rv, 1); /* reversed */
    B(m, "motor_out", mot, 1, low, 2);
    B(m, "tank", tank, 0, low, 3);
    B(m, "shaft", in, 0, mot, 2); /* reversed */
    if (compile_ok(m, "jacobian model")) {
        int n = bgr_n(m);
        double *y = malloc((size_t)n * sizeof *y), *yp = malloc((size_t)n * sizeof *yp);
        random_point(n, NULL, 21, y, yp);
        /* the relief valve near cracking: p_a - p_b - p_c within a width or so */
        y[V(m, "jac/to_relief/e")] = 1.2;
        y[V(m, "jac/relief_out/e")] = 0.1;
        check_jac(m, 0.0, y, yp, 1e-6, "hydraulic elements");
        y[V(m, "jac/to_relief/e")] = 0.6;
        check_jac(m, 0.0, y, yp, 1e-6, "same, relief valve below cracking");
        free(y);
        free(yp);
    }
    bgr_model_free(&m);
}

static void test_arguments(void)
{
    bgr_model *m = bgr_model_create("args");
    tap_ok(hyd_relief_valve(m, 0, "r", 2.0, 1.0, 1.0, 0.1) < 0 &&
               strstr(bgr_model_error(m)->message, "args/r (hyd_relief_valve)"),
           "relief valve with p_full < p_crack refused: %s", bgr_model_error(m)->message);
    tap_ok(hyd_relief_valve(m, 0, "r", 1.0, 2.0, 1.0, 0.0) < 0,
           "relief valve without width refused");
    tap_ok(hyd_leakage(m, 0, "l", -1.0) < 0, "negative leakage refused: %s",
           bgr_model_error(m)->message);
    tap_ok(hyd_volume(m, 0, "v", 2, 0.0, 1e9) < 0, "zero volume refused: %s",
           bgr_model_error(m)->message);
    tap_ok(hyd_tank(m, 0, "t", NAN) < 0, "tank with NaN pressure refused: %s",
           bgr_model_error(m)->message);
    tap_ok(rot_inertia(m, 0, "i", 0.0) < 0, "inertia J = 0 refused: %s",
           bgr_model_error(m)->message);
    tap_ok(rot_sensor(m, 0, "s", 99, ROT_ANGLE) < 0, "sensor on a missing inertia refused: %s",
           bgr_model_error(m)->message);
    bgr_model_free(&m);
}

/* The parameters of the volume, the leakage and the relief valve (headers: the accepted
 * ranges): NaN, infinities, 0 and negative numbers where refused, misordered pressures and
 * combinations that overflow; one test point each (param_check.h). Then the leaking volume of
 * test_transient built with a refusal before each element, under the refused names: it
 * compiles and follows the same transient. */
static double pk(int which, int k, double x, double good)
{
    return which == k ? x : good;
}
/* which 0: nports, 1: V, 2: beta */
static int mk_volume(bgr_model *m, bgr_comp c, const char *name, int which, double x)
{
    return hyd_volume(m, c, name, which == 0 ? (int)x : 2, pk(which, 1, x, 1e-3),
                      pk(which, 2, x, 1.4e9));
}
static int mk_leak(bgr_model *m, bgr_comp c, const char *name, int which, double x)
{
    return hyd_leakage(m, c, name, pk(which, 0, x, 1e-11));
}
/* which 0: p_crack, 1: p_full, 2: q_rated, 3: eps; 4: the band overflows (p_crack = -x,
 * p_full = x); 5: the band is too narrow for the rated flow x */
static int mk_relief(bgr_model *m, bgr_comp c, const char *name, int which, double x)
{
    double pc = pk(which, 0, x, 2e7), pf = pk(which, 1, x, 2.5e7), q = pk(which, 2, x, 1e-3);
    if (which == 4) pc = -x, pf = x;
    if (which == 5) pc = 1.0, pf = nextafter(1.0, 2.0), q = x;
    return hyd_relief_valve(m, c, name, pc, pf, q, pk(which, 3, x, 5e4));
}

static void test_param_checks(void)
{
    const double nan = NAN, inf = INFINITY;
    const char *POS = "expected a finite number > 0", *NNEG = "expected a finite number >= 0";
    const char *FIN = "expected a finite number";
    const pc_case cases[] = {
        {"hyd_volume", mk_volume, 0, 0, "nports = 0", "expected 1 .. 1000"},
        {"hyd_volume", mk_volume, 0, 1001, "nports = 1001", "expected 1 .. 1000"},
        {"hyd_volume", mk_volume, 1, nan, "V = ", POS},
        {"hyd_volume", mk_volume, 1, inf, "V = ", POS},
        {"hyd_volume", mk_volume, 1, 0.0, "V = ", POS},
        {"hyd_volume", mk_volume, 1, -1e-3, "V = ", POS},
        {"hyd_volume", mk_volume, 1, 1e-300, "beta / V = inf", FIN},
        {"hyd_volume", mk_volume, 2, nan, "beta = ", POS},
        {"hyd_volume", mk_volume, 2, inf, "beta = ", POS},
        {"hyd_volume", mk_volume, 2, 0.0, "beta = ", POS},
        {"hyd_volume", mk_volume, 2, -1.4e9, "beta = ", POS},
        {"hyd_leakage", mk_leak, 0, nan, "G = ", NNEG},
        {"hyd_leakage", mk_leak, 0, inf, "G = ", NNEG},
        {"hyd_leakage", mk_leak, 0, -1e-12, "G = ", NNEG},
        {"hyd_relief_valve", mk_relief, 0, nan, "p_crack = ", FIN},
        {"hyd_relief_valve", mk_relief, 0, -inf, "p_crack = ", FIN},
        {"hyd_relief_valve", mk_relief, 0, 2.5e7, "p_full = 2.5e+07", "expected > p_crack"},
        {"hyd_relief_valve", mk_relief, 0, 3e7, "p_full = 2.5e+07", "expected > p_crack"},
        {"hyd_relief_valve", mk_relief, 1, nan, "p_full = ", FIN},
        {"hyd_relief_valve", mk_relief, 1, inf, "p_full = ", FIN},
        {"hyd_relief_valve", mk_relief, 2, nan, "q_rated = ", POS},
        {"hyd_relief_valve", mk_relief, 2, inf, "q_rated = ", POS},
        {"hyd_relief_valve", mk_relief, 2, 0.0, "q_rated = ", POS},
        {"hyd_relief_valve", mk_relief, 2, -1e-3, "q_rated = ", POS},
        {"hyd_relief_valve", mk_relief, 3, nan, "eps = ", POS},
        {"hyd_relief_valve", mk_relief, 3, inf, "eps = ", POS},
        {"hyd_relief_valve", mk_relief, 3, 0.0, "eps = ", POS},
        {"hyd_relief_valve", mk_relief, 3, -5e4, "eps = ", POS},
        {"hyd_relief_valve", mk_relief, 4, 1e308, "q_rated / (p_full - p_crack) = 0", POS},
        {"hyd_relief_valve", mk_relief, 5, 1e300, "q_rated / (p_full - p_crack) = inf", POS},
    };
    int n = (int)(sizeof cases / sizeof cases[0]);
    bgr_model *m = bgr_model_create("params");
    bgr_comp c = bgr_component(m, bgr_component(m, 0, "circuit"), "bad");
    int passed = pc_run(m, c, "x", cases, n);
    tap_diag("%d of %d refusals as required", passed, n);
    bgr_model_free(&m);

    const double Q = 1e-4, G = 1e-11, Vol = 1e-3, beta = 1.4e9, tau = Vol / (beta * G);
    m = bgr_model_create("rc");
    int refused = 0;
    refused += hyd_flow_source(m, 0, "pump", nan) == BG_ERR_ARGUMENT;
    int src = hyd_flow_source(m, 0, "pump", Q);
    refused += hyd_volume(m, 0, "line", 2, 1e-300, beta) == BG_ERR_ARGUMENT;
    int vol = hyd_volume(m, 0, "line", 2, Vol, beta);
    refused += hyd_leakage(m, 0, "leak", -G) == BG_ERR_ARGUMENT;
    int leak = hyd_leakage(m, 0, "leak", G);
    refused += hyd_tank(m, 0, "tank", inf) == BG_ERR_ARGUMENT;
    int tank = hyd_tank(m, 0, "tank", 0.0);
    B(m, "feed", src, 0, vol, 0);
    B(m, "out", vol, 1, leak, 0);
    B(m, "drain", tank, 0, leak, 1);
    int st = bgr_compile(m);
    double p = NAN, want = Q / G * (1 - exp(-3.0));
    if (st == BG_OK) {
        dae_solver *s = solver_new(m, 1e-10, 1e-12, NULL, NULL, 0, 0.0);
        int nv = bgr_n(m);
        double *y = calloc((size_t)nv, sizeof *y), *yp = calloc((size_t)nv, sizeof *yp);
        if (s && solve_to(s, 3 * tau, y, yp) >= 0) p = at(y, V(m, "rc/line/p"));
        dae_free(&s);
        free(y);
        free(yp);
    }
    tap_ok(refused == 4 && st == BG_OK && fabs(p - want) <= 1e-7 * want,
           "the leaking volume built with a refusal before each element (%d of 4 refused) "
           "compiles (%d) and reaches p(3 tau) = %.6g Pa (got %.6g): '%s'",
           refused, st, want, p, bgr_model_error(m)->message);
    bgr_model_free(&m);
}

int main(void)
{
    test_transient();
    test_natural_frequency();
    test_relief();
    test_jacobian();
    test_arguments();
    test_param_checks();
    return tap_done();
}
