/* Signal sources (sig_sources): value, rate and integral of every source against hand values,
 * the rate against central differences and the integral against Simpson's rule of the value,
 * the breakpoints they expose, a step driving a volume through the solver, and the Jacobian. The
 * parameter checks: bad times, values and outputs refused with messages naming the signal's path
 * and the parameter. */
#include "bondgraph/param_check.h"
#include "cmptest.h"
#include "hyd_source.h"
#include "hyd_volume.h"
#include "sig_sources.h"

enum { TRAP, PWL, STEP, RAMP, SINE, CONST, NSRC };

typedef struct sigs {
    bgr_model *m;
    int id[NSRC][3]; /* element of each source and output */
} sigs;

static sigs build_sources(void)
{
    sigs S;
    bgr_model *m = S.m = bgr_model_create("sig");
    static const double pt[3] = {1.0, 3.0, 4.0}, pv[3] = {2.0, -2.0, 0.0};
    static const char *const on[3] = {"v", "r", "i"};
    for (int o = 0; o < 3; o++) {
        char nm[32];
        snprintf(nm, sizeof nm, "trap_%s", on[o]);
        S.id[TRAP][o] = sig_trapezoid(m, 0, nm, 0.0, 2.0, 10.0, 12.0, 0.5, (sig_output)o);
        snprintf(nm, sizeof nm, "pwl_%s", on[o]);
        S.id[PWL][o] = sig_pwl(m, 0, nm, 3, pt, pv, (sig_output)o);
        snprintf(nm, sizeof nm, "step_%s", on[o]);
        S.id[STEP][o] = sig_step(m, 0, nm, 1.5, 1.0, 3.0, (sig_output)o);
        snprintf(nm, sizeof nm, "ramp_%s", on[o]);
        S.id[RAMP][o] = sig_ramp(m, 0, nm, 2.0, 0.5, 1.0, (sig_output)o);
        snprintf(nm, sizeof nm, "sine_%s", on[o]);
        S.id[SINE][o] = sig_sine(m, 0, nm, 2.0, 3.0, 0.4, 1.0, (sig_output)o);
        snprintf(nm, sizeof nm, "const_%s", on[o]);
        S.id[CONST][o] = sig_constant(m, 0, nm, 2.5, (sig_output)o);
    }
    return S;
}

/* The signal of element id at t, read from the model's residual at y = 0 (F = 0 - g(t)). */
static double sig_at(bgr_model *m, int id, double t, double *F, const double *zero)
{
    bgr_residual(m, t, zero, zero, F);
    return -F[bgr_element_get(m, id)->eq0];
}

/* Hand values: {t, value, rate, integral from 0}; at a corner the left limits. */
typedef struct hv {
    double t, v, r, i;
} hv;

static const hv trap_hv[] = {{-1, 0, 0, 0},       {1, 0.25, 0.25, 0.125}, {2, 0.5, 0.25, 0.5},
                             {5, 0.5, 0, 2.0},    {10, 0.5, 0, 4.5},      {11, 0.25, -0.25, 4.875},
                             {12, 0, -0.25, 5.0}, {15, 0, 0, 5.0}};
static const hv pwl_hv[] = {{0, 2, 0, 0},   {0.5, 2, 0, 1},     {2, 0, -2, 3},
                            {3, -2, -2, 2}, {3.5, -1, 2, 1.25}, {6, 0, 0, 1}};
static const hv step_hv[] = {{-1, 1, 0, -1}, {1.5, 1, 0, 1.5}, {2, 3, 0, 3}};
static const hv ramp_hv[] = {{1, 1, 0, 1}, {2, 1, 0, 2}, {4, 2, 0.5, 5}};
static const hv const_hv[] = {{-2, 2.5, 0, -5}, {3, 2.5, 0, 7.5}};

static void check_table(sigs *S, int k, const hv *tab, int n, const char *what, double *F,
                        const double *zero)
{
    double worst = 0;
    for (int j = 0; j < n; j++) {
        const double want[3] = {tab[j].v, tab[j].r, tab[j].i};
        for (int o = 0; o < 3; o++) {
            double got = sig_at(S->m, S->id[k][o], tab[j].t, F, zero);
            double e = fabs(got - want[o]);
            if (e > 1e-14 * (1 + fabs(want[o])))
                tap_diag("%s output %d at t = %g: %.17g, want %.17g", what, o, tab[j].t, got,
                         want[o]);
            worst = fmax(worst, e);
        }
    }
    tap_ok(worst <= 1e-13, "%s: value, rate, integral at %d times against hand values (max %.3g)",
           what, n, worst);
}

/* The rate against central differences of the value and the integral against Simpson's rule of
 * the value on each piece between the corners kn[] (200 intervals each), at times away from the
 * corners. */
static double simpson(sigs *S, int k, double a, double b, double *F, const double *zero)
{
    int N = 200;
    double h = (b - a) / N, sum = 0;
    for (int q = 0; q <= N; q++) {
        double w = q == 0 || q == N ? 1 : q % 2 ? 4 : 2;
        sum += w * sig_at(S->m, S->id[k][0], a + q * h, F, zero);
    }
    return sum * h / 3;
}

static void check_consistency(sigs *S, int k, const double *ts, int n, const double *kn, int nkn,
                              const char *what, double *F, const double *zero)
{
    double er = 0, ei = 0;
    for (int j = 0; j < n; j++) {
        double t = ts[j], h = 1e-5;
        double fd = (sig_at(S->m, S->id[k][0], t + h, F, zero) -
                     sig_at(S->m, S->id[k][0], t - h, F, zero)) /
                    (2 * h);
        er = fmax(er, fabs(fd - sig_at(S->m, S->id[k][1], t, F, zero)));
        double a = 0, sum = 0;
        for (int c = 0; c < nkn && kn[c] < t; c++)
            if (kn[c] > a) {
                sum += simpson(S, k, a, kn[c], F, zero);
                a = kn[c];
            }
        sum += simpson(S, k, a, t, F, zero);
        ei = fmax(ei, fabs(sum - sig_at(S->m, S->id[k][2], t, F, zero)));
    }
    tap_ok(
        er < 1e-8 && ei < 1e-9,
        "%s: rate = d(value)/dt (max diff %.2g), integral = Simpson of the value (max diff %.2g)",
        what, er, ei);
}

static void test_values(void)
{
    sigs S = build_sources();
    if (!compile_ok(S.m, "sources")) {
        bgr_model_free(&S.m);
        return;
    }
    int n = bgr_n(S.m);
    double *F = calloc((size_t)n, sizeof *F), *zero = calloc((size_t)n, sizeof *zero);
    check_table(&S, TRAP, trap_hv, 8, "trapezoid of the paper (Eq. 8)", F, zero);
    check_table(&S, PWL, pwl_hv, 6, "piecewise linear", F, zero);
    check_table(&S, STEP, step_hv, 3, "step", F, zero);
    check_table(&S, RAMP, ramp_hv, 3, "ramp", F, zero);
    check_table(&S, CONST, const_hv, 2, "constant", F, zero);
    /* the paper's formula for omega_r and the reference angle 5 rad from t = 12 on */
    double worst = 0;
    for (int j = 0; j <= 300; j++) {
        double t = -1 + 0.05 * j;
        double w = t <= 0 ? 0 : t <= 2 ? 0.25 * t : t <= 10 ? 0.5 : t <= 12 ? 0.25 * (12 - t) : 0;
        worst = fmax(worst, fabs(sig_at(S.m, S.id[TRAP][0], t, F, zero) - w));
    }
    tap_ok(worst < 1e-15, "trapezoid = paper Eq. 8 on a grid of [-1, 14] (max %.2g)", worst);
    double sine_t[3] = {0.7, 1.9, 4.2};
    double a = 2, w = 3, ph = 0.4, off = 1, t = 0.7;
    tap_close(sig_at(S.m, S.id[SINE][0], t, F, zero), off + a * sin(w * t + ph), 1e-15, 1e-15,
              "sine value at 0.7");
    tap_close(sig_at(S.m, S.id[SINE][2], t, F, zero), off * t - a / w * (cos(w * t + ph) - cos(ph)),
              1e-14, 1e-15, "sine integral at 0.7");
    const double kn[7] = {1, 1.5, 2, 3, 4, 10, 12}; /* every corner of the sources */
    check_consistency(&S, SINE, sine_t, 3, kn, 7, "sine", F, zero);
    double trap_t[4] = {1.3, 4.0, 10.7, 13.0};
    check_consistency(&S, TRAP, trap_t, 4, kn, 7, "trapezoid", F, zero);
    double pwl_t[3] = {0.8, 2.5, 3.3};
    check_consistency(&S, PWL, pwl_t, 3, kn, 7, "pwl", F, zero);
    double ramp_t[2] = {1.0, 3.7};
    check_consistency(&S, RAMP, ramp_t, 2, kn, 7, "ramp", F, zero);
    /* sig_evaluate gives the same numbers as the residual */
    double v, r, i;
    tap_ok(sig_evaluate(S.m, S.id[TRAP][0], 11.0, &v, &r, &i) == BG_OK && v == 0.25 && r == -0.25 &&
               i == 4.875,
           "sig_evaluate: trapezoid at 11: 0.25, -0.25, 4.875");
    tap_ok(sig_evaluate(S.m, 0, 1.0, &v, &r, &i) == BG_OK, "sig_evaluate on a source element");
    free(F);
    free(zero);
    bgr_model_free(&S.m);
}

static void test_breakpoints(void)
{
    sigs S = build_sources();
    if (!compile_ok(S.m, "breakpoints")) {
        bgr_model_free(&S.m);
        return;
    }
    double bp[16];
    const double want[7] = {1, 1.5, 2, 3, 4, 10, 12};
    int nb = bgr_breakpoints(S.m, 0.0, 20.0, bp, 16), same = nb == 7;
    for (int k = 0; same && k < 7; k++)
        same = bp[k] == want[k];
    tap_ok(same,
           "breakpoints in (0, 20]: %d: 1, 1.5, 2, 3, 4, 10, 12 (corners of trapezoid and "
           "pwl, step and ramp times; none for sine and constant)",
           nb);
    nb = bgr_breakpoints(S.m, -5.0, 20.0, bp, 16);
    tap_ok(nb == 8 && bp[0] == 0.0, "breakpoints in (-5, 20]: the trapezoid's start 0 as well");
    nb = bgr_breakpoints(S.m, 2.0, 10.0, bp, 16);
    tap_ok(nb == 3 && bp[0] == 3 && bp[1] == 4 && bp[2] == 10, "breakpoints in (2, 10]: 3, 4, 10");
    bgr_element *el = bgr_element_get(S.m, S.id[TRAP][1]);
    double t2[2];
    int c = el->cls->breakpoints(el, 0.0, 20.0, t2, 2);
    tap_ok(c == 3 && t2[0] == 2 && t2[1] == 10, "hook: count 3 with room for 2, first two written");
    el = bgr_element_get(S.m, S.id[SINE][0]);
    tap_ok(el->cls->breakpoints(el, -100, 100, NULL, 0) == 0, "hook: a sine has no breakpoints");
    bgr_model_free(&S.m);
}

/* A step of flow (0 until t = 1, then Q) into a closed volume: p(t) = (beta / V) Q (t - 1) for
 * t > 1, and the step's integral output equals V p / beta. The step time is a breakpoint; at it
 * the test restarts at its right limit (see test_ctl_pid.c for why). */
static void test_step_in_solver(void)
{
    const double Q = 2e-4, Vol = 1e-3, beta = 1.5e9;
    bgr_model *m = bgr_model_create("stepq");
    int q = sig_step(m, 0, "q", 1.0, 0.0, Q, SIG_VALUE);
    int qi = sig_step(m, 0, "qint", 1.0, 0.0, Q, SIG_INTEGRAL);
    int src = hyd_flow_source_signal(m, 0, "pump", (bgr_ref){BGR_OWN, q, 0});
    int vol = hyd_volume(m, 0, "line", 1, Vol, beta);
    B(m, "feed", src, 0, vol, 0);
    (void)qi;
    if (!compile_ok(m, "step into a volume")) {
        bgr_model_free(&m);
        return;
    }
    double bp[4];
    int nb = bgr_breakpoints(m, 0.0, 3.0, bp, 4);
    /* no help from the test: the solver restarts at the step from its right-hand value */
    dae_solver *s = solver_new(m, 1e-10, 1e-12, NULL, bp, nb, 0.0);
    int n = bgr_n(m), vp = V(m, "stepq/line/p"), vi = V(m, "stepq/qint/integral");
    double *y = calloc((size_t)n, sizeof *y), *yp = calloc((size_t)n, sizeof *yp);
    double t = 0, worst = 0;
    int r = s ? 0 : -1, landed = 0;
    while (r >= 0 && t < 3.0) {
        r = dae_step(s, 4.0, &t, y, yp);
        if (r < 0) {
            tap_diag("dae_step: %s", dae_get_error(s)->message);
            break;
        }
        double want = t > 1 ? beta / Vol * Q * (t - 1) : 0.0;
        worst = fmax(worst, fabs(at(y, vp) - want));
        worst = fmax(worst, fabs(at(y, vi) * beta / Vol - want));
        if (t == 1.0) landed = 1;
    }
    tap_ok(r >= 0 && landed, "step: the solver lands on the step time 1 and goes on to t = 3");
    tap_ok(worst < 1e-9 * beta / Vol * Q * 2,
           "step: p = (beta/V) Q (t - 1) at every step (max error %.3g Pa of %.3g)", worst,
           beta / Vol * Q * 2);
    dae_free(&s);
    free(y);
    free(yp);
    bgr_model_free(&m);
}

static void test_jacobian(void)
{
    sigs S = build_sources();
    if (compile_ok(S.m, "jacobian")) {
        int n = bgr_n(S.m);
        double *y = malloc((size_t)n * sizeof *y), *yp = malloc((size_t)n * sizeof *yp);
        random_point(n, NULL, 5, y, yp);
        check_jac(S.m, 3.3, y, yp, 1e-6, "all sources");
        free(y);
        free(yp);
    }
    bgr_model_free(&S.m);
}

static void test_arguments(void)
{
    bgr_model *m = bgr_model_create("args");
    const double t[3] = {0, 2, 1}, v[3] = {0, 1, 2};
    tap_ok(sig_pwl(m, 0, "p", 3, t, v, SIG_VALUE) < 0 &&
               strstr(bgr_model_error(m)->message, "increasing"),
           "pwl with decreasing times refused: %s", bgr_model_error(m)->message);
    tap_ok(sig_trapezoid(m, 0, "tr", 0, 3, 2, 4, 1, SIG_VALUE) < 0,
           "trapezoid with t1 > t2 refused: %s", bgr_model_error(m)->message);
    tap_ok(sig_step(m, 0, "s", 1, 0, 1, (sig_output)7) < 0, "unknown output refused: %s",
           bgr_model_error(m)->message);
    tap_ok(sig_evaluate(m, 5, 0.0, NULL, NULL, NULL) < 0,
           "sig_evaluate on a missing element refused");
    int tri = sig_trapezoid(m, 0, "tri", 0, 1, 1, 2, 1, SIG_INTEGRAL);
    double i;
    tap_ok(tri >= 0 && sig_evaluate(m, tri, 5.0, NULL, NULL, &i) == BG_OK && fabs(i - 1) < 1e-15,
           "triangle (t1 = t2): area 1");
    bgr_model_free(&m);
}

/* Nominal magnitudes (sig_sources.h): the largest |output| the parameters bound, by hand. */
static void test_nominals(void)
{
    bgr_model *m = bgr_model_create("nom");
    const double pt[3] = {-1.0, 0.0, 2.0}, pv[3] = {1.0, 3.0, 3.0};
    struct {
        const char *name;
        int id;
        double want;
        const char *why;
    } t[] = {
        {"crane_value", sig_trapezoid(m, 0, "crane_value", 0, 2, 10, 12, 0.5, SIG_VALUE), 0.5,
         "trapezoid value: its height"},
        {"crane_rate", sig_trapezoid(m, 0, "crane_rate", 0, 2, 10, 12, 0.5, SIG_RATE), 0.25,
         "trapezoid rate: 0.5 / 2 s"},
        {"crane_integral", sig_trapezoid(m, 0, "crane_integral", 0, 2, 10, 12, 0.5, SIG_INTEGRAL),
         5.0, "trapezoid integral: the area 0.5 (12 + 10 - 2) / 2 = 5 rad"},
        {"late_rate", sig_trapezoid(m, 0, "late_rate", 1, 3, 5, 9, -2.0, SIG_RATE), 1.0,
         "trapezoid rate: the steeper ramp, 2 / 2 s"},
        {"late_integral", sig_trapezoid(m, 0, "late_integral", 1, 3, 5, 9, -2.0, SIG_INTEGRAL),
         10.0, "trapezoid integral: |area| 2 (9 + 5 - 3 - 1) / 2 = 10"},
        {"sine_value", sig_sine(m, 0, "sine_value", 3.0, 4.0, 0.3, -1.0, SIG_VALUE), 4.0,
         "sine value: |a| + |offset|"},
        {"sine_rate", sig_sine(m, 0, "sine_rate", 3.0, 4.0, 0.3, -1.0, SIG_RATE), 12.0,
         "sine rate: |a omega|"},
        {"sine_integral", sig_sine(m, 0, "sine_integral", 3.0, 4.0, 0.3, -1.0, SIG_INTEGRAL), 1.0,
         "sine integral: unbounded (offset), 1"},
        {"step_value", sig_step(m, 0, "step_value", 1.0, 2.0, -5.0, SIG_VALUE), 5.0,
         "step value: the larger |level|"},
        {"ramp_value", sig_ramp(m, 0, "ramp_value", 1.0, 0.3, 2.0, SIG_VALUE), 1.0,
         "ramp value: unbounded, 1"},
        {"ramp_rate", sig_ramp(m, 0, "ramp_rate", 1.0, 0.3, 2.0, SIG_RATE), 0.3,
         "ramp rate: |slope|"},
        {"zero", sig_constant(m, 0, "zero", 0.0, SIG_VALUE), 1.0, "constant 0: no scale, 1"},
        {"pwl_value", sig_pwl(m, 0, "pwl_value", 3, pt, pv, SIG_VALUE), 3.0, "pwl value: max |v|"},
        {"pwl_rate", sig_pwl(m, 0, "pwl_rate", 3, pt, pv, SIG_RATE), 2.0,
         "pwl rate: the steepest slope (3 - 1) / 1"},
        {"pwl_integral", sig_pwl(m, 0, "pwl_integral", 3, pt, pv, SIG_INTEGRAL), 1.0,
         "pwl integral: ends at 3, unbounded, 1"},
    };
    if (!compile_ok(m, "nominal sources")) {
        bgr_model_free(&m);
        return;
    }
    const double *nom = bgr_nominals(m);
    for (size_t i = 0; i < sizeof t / sizeof t[0]; i++) {
        int v = bgr_ref_var(m, (bgr_ref){BGR_OWN, t[i].id, 0});
        tap_close(v >= 0 ? nom[v] : NAN, t[i].want, 1e-14, 0, "nominal of %s = %g (%s)",
                  t[i].name, t[i].want, t[i].why);
    }
    bgr_model_free(&m);
}

/* The parameters of the sources (sig_sources.h: the accepted ranges): NaN and infinite times and
 * values, misordered trapezoid corners and pwl times, too few points, slopes that overflow, an
 * unknown output; one test point each (param_check.h). */
static double pk(int which, int k, double x, double good)
{
    return which == k ? x : good;
}
/* which 0..4: t0, t1, t2, t3, height; 5: the output (int) x */
static int mk_trapezoid(bgr_model *m, bgr_comp c, const char *name, int which, double x)
{
    return sig_trapezoid(m, c, name, pk(which, 0, x, 0.0), pk(which, 1, x, 2.0),
                         pk(which, 2, x, 10.0), pk(which, 3, x, 12.0), pk(which, 4, x, 0.5),
                         which == 5 ? (sig_output)(int)x : SIG_RATE);
}
/* which 0..2: t[which], 3..5: v[which - 3]; 6: n = (int) x */
static int mk_pwl(bgr_model *m, bgr_comp c, const char *name, int which, double x)
{
    double t[3] = {0.0, 1.0, 6.0}, v[3] = {1.0, -1.0, 2.0};
    if (which >= 0 && which < 3) t[which] = x;
    if (which >= 3 && which < 6) v[which - 3] = x;
    return sig_pwl(m, c, name, which == 6 ? (int)x : 3, t, v, SIG_INTEGRAL);
}
static int mk_step(bgr_model *m, bgr_comp c, const char *name, int which, double x)
{
    return sig_step(m, c, name, pk(which, 0, x, 1.0), pk(which, 1, x, 0.0), pk(which, 2, x, 2.0),
                    SIG_VALUE);
}
static int mk_ramp(bgr_model *m, bgr_comp c, const char *name, int which, double x)
{
    return sig_ramp(m, c, name, pk(which, 0, x, 1.0), pk(which, 1, x, 0.5), pk(which, 2, x, 1.0),
                    SIG_VALUE);
}
static int mk_sine(bgr_model *m, bgr_comp c, const char *name, int which, double x)
{
    return sig_sine(m, c, name, pk(which, 0, x, 2.0), pk(which, 1, x, 3.0), pk(which, 2, x, 0.1),
                    pk(which, 3, x, -1.0), SIG_RATE);
}
static int mk_constant(bgr_model *m, bgr_comp c, const char *name, int which, double x)
{
    return sig_constant(m, c, name, pk(which, 0, x, 4.0), SIG_VALUE);
}

static void test_param_checks(void)
{
    const double nan = NAN, inf = INFINITY;
    const char *FIN = "expected a finite number", *ORD = "(t0 < t1 <= t2 < t3)";
    const char *SEG = "expected finite numbers (times too close or values too large)";
    const pc_case cases[] = {
        {"sig_trapezoid", mk_trapezoid, 0, nan, "t0 = ", FIN},
        {"sig_trapezoid", mk_trapezoid, 1, inf, "t1 = ", FIN},
        {"sig_trapezoid", mk_trapezoid, 2, nan, "t2 = ", FIN},
        {"sig_trapezoid", mk_trapezoid, 3, -inf, "t3 = ", FIN},
        {"sig_trapezoid", mk_trapezoid, 4, nan, "height = ", FIN},
        {"sig_trapezoid", mk_trapezoid, 4, inf, "height = ", FIN},
        {"sig_trapezoid", mk_trapezoid, 1, 0.0, "t1 = 0, expected > t0 = 0", ORD},
        {"sig_trapezoid", mk_trapezoid, 2, 1.0, "t2 = 1, expected >= t1 = 2", ORD},
        {"sig_trapezoid", mk_trapezoid, 3, 10.0, "t3 = 10, expected > t2 = 10", ORD},
        {"sig_trapezoid", mk_trapezoid, 1, 1e-310, "slope", SEG},
        {"sig_trapezoid", mk_trapezoid, 5, 7, "unknown output out = 7", "expected SIG_VALUE"},
        {"sig_pwl", mk_pwl, 0, nan, "t[0] = ", FIN},
        {"sig_pwl", mk_pwl, 2, inf, "t[2] = ", FIN},
        {"sig_pwl", mk_pwl, 4, nan, "v[1] = ", FIN},
        {"sig_pwl", mk_pwl, 5, -inf, "v[2] = ", FIN},
        {"sig_pwl", mk_pwl, 1, 6.0, "t[2] = 6, expected > t[1] = 6", "strictly increasing"},
        {"sig_pwl", mk_pwl, 1, -1.0, "t[1] = -1, expected > t[0] = 0", "strictly increasing"},
        {"sig_pwl", mk_pwl, 6, 0, "n = 0", "expected at least 1 point"},
        {"sig_pwl", mk_pwl, 1, 1e-310, "slope", SEG},
        {"sig_pwl", mk_pwl, 5, 1.5e308, "area", SEG},
        {"sig_step", mk_step, 0, nan, "t_step = ", FIN},
        {"sig_step", mk_step, 1, inf, "before = ", FIN},
        {"sig_step", mk_step, 2, -inf, "after = ", FIN},
        {"sig_ramp", mk_ramp, 0, inf, "t_start = ", FIN},
        {"sig_ramp", mk_ramp, 1, nan, "slope = ", FIN},
        {"sig_ramp", mk_ramp, 2, -inf, "offset = ", FIN},
        {"sig_sine", mk_sine, 0, nan, "amplitude = ", FIN},
        {"sig_sine", mk_sine, 1, inf, "omega = ", FIN},
        {"sig_sine", mk_sine, 2, nan, "phase = ", FIN},
        {"sig_sine", mk_sine, 3, -inf, "offset = ", FIN},
        {"sig_constant", mk_constant, 0, nan, "value = ", FIN},
        {"sig_constant", mk_constant, 0, inf, "value = ", FIN},
    };
    int n = (int)(sizeof cases / sizeof cases[0]);
    bgr_model *m = bgr_model_create("params");
    bgr_comp c = bgr_component(m, bgr_component(m, 0, "reference"), "bad");
    int passed = pc_run(m, c, "x", cases, n);
    tap_diag("%d of %d refusals as required", passed, n);
    bgr_model_free(&m);
}

int main(void)
{
    test_values();
    test_breakpoints();
    test_step_in_solver();
    test_jacobian();
    test_arguments();
    test_nominals();
    test_param_checks();
    return tap_done();
}
