/* The closed hydraulic circuit of the crane's drive (docs/crane.md, the paper's Fig. 4): a
 * variable-displacement pump (hyd_pump) driven at constant speed feeds a motor (hyd_motor)
 * through a high-pressure line (hyd_volume) with a cross-line leak (hyd_leakage); the low side is
 * held at the charge pressure by a tank (hyd_tank); the motor drives an inertia (rot_inertia)
 * with viscous load friction (rot_damper) through a gear (rot_gear). Steady state against
 * hand-computed values, power conservation of the gear, the power balance of the whole circuit,
 * and the analytic Jacobian. The nominal magnitudes the components declare (stated pressures and
 * speeds, the relief valve's full-flow pressure and rated flow, a tank's pressure) against the
 * rules of their headers applied by hand. The parameter checks of the pump, motor, sources and
 * gear: bad values refused with messages naming the element's path and the parameter. */
#include "bondgraph/param_check.h"
#include "cmptest.h"
#include "hyd_motor.h"
#include "hyd_pump.h"
#include "hyd_source.h"
#include "hyd_valve.h"
#include "hyd_volume.h"
#include "rot_damper.h"
#include "rot_gear.h"
#include "rot_inertia.h"
#include "sig_sources.h"

typedef struct circ_par {
    double wp, Dp, x, Cp, Dm, Cm, bm, Gl, V, beta, ratio, J, bL, pL;
    int rev; /* 1: some bonds drawn against the power direction (the physics must not change) */
} circ_par;

typedef struct circ {
    bgr_model *m;
    int sgn_pump_out, sgn_motor_in, sgn_leak, sgn_shaft, sgn_drive; /* +1 along the power */
    int vol, in;
} circ;

static int bond_dir(bgr_model *m, const char *name, int a, int pa, int b, int pb, int rev)
{
    return rev ? B(m, name, b, pb, a, pa) : B(m, name, a, pa, b, pb);
}

static circ build_circuit(const circ_par *P)
{
    circ C;
    bgr_model *m = C.m = bgr_model_create("circuit");
    int rv = P->rev;
    int drive = bgr_Sf(m, 0, "drive", 1, &P->wp);
    int cmd = sig_constant(m, 0, "x", P->x, SIG_VALUE);
    int pump = hyd_pump(m, 0, "pump", P->Dp, P->Cp, (bgr_ref){BGR_OWN, cmd, 0});
    int high = C.vol = hyd_volume(m, 0, "high", 3, P->V, P->beta);
    int motor = hyd_motor(m, 0, "motor", P->Dm, P->Cm, P->bm);
    int leak = hyd_leakage(m, 0, "leak", P->Gl);
    int low = bgr_zero(m, 0, "low", 4, 1);
    int tank = hyd_tank(m, 0, "tank", P->pL);
    int gear = rot_gear(m, 0, "gear", P->ratio);
    int load = bgr_one(m, 0, "load", 3, 1);
    int in = C.in = rot_inertia(m, 0, "inertia", P->J);
    int damp = rot_damper(m, 0, "damper", P->bL);
    bond_dir(m, "shaft_p", drive, 0, pump, 0, rv);
    bond_dir(m, "pump_out", pump, 2, high, 0, rv);
    bond_dir(m, "motor_in", high, 1, motor, 0, rv);
    bond_dir(m, "leak_in", high, 2, leak, 0, 0);
    bond_dir(m, "motor_out", motor, 1, low, 0, 0);
    bond_dir(m, "leak_out", leak, 1, low, 1, rv);
    bond_dir(m, "charge", tank, 0, low, 2, 0);
    bond_dir(m, "pump_in", low, 3, pump, 1, 0);
    bond_dir(m, "shaft_m", motor, 2, gear, 0, rv);
    bond_dir(m, "shaft_l", gear, 1, load, 0, 0);
    bond_dir(m, "to_inertia", load, 1, in, 0, 0);
    bond_dir(m, "to_damper", load, 2, damp, 0, rv);
    C.sgn_drive = C.sgn_pump_out = C.sgn_motor_in = C.sgn_shaft = rv ? -1 : 1;
    C.sgn_leak = rv ? -1 : 1;
    return C;
}

/* Steady state by hand. With B = bm + bL / i^2 the load seen at the motor shaft, the torque
 * balance Dm dp / (2 pi) = B wm and the flow balance of the high-pressure line
 *   x Dp wp / (2 pi) - Cp dp = Dm wm / (2 pi) + Cm dp + Gl dp
 * give wm = (x Dp wp / 2pi) / (Dm / 2pi + (Cp + Cm + Gl) 2 pi B / Dm), dp = 2 pi B wm / Dm. */
typedef struct circ_ss {
    double wm, dp, qp, qm, ql, Tm, Tp, wL, pH;
} circ_ss;

static circ_ss steady(const circ_par *P)
{
    circ_ss s;
    double B = P->bm + P->bL / (P->ratio * P->ratio), tp = 2 * PI;
    s.wm = (P->x * P->Dp * P->wp / tp) / (P->Dm / tp + (P->Cp + P->Cm + P->Gl) * tp * B / P->Dm);
    s.dp = tp * B * s.wm / P->Dm;
    s.qp = P->x * P->Dp * P->wp / tp - P->Cp * s.dp;
    s.qm = P->Dm * s.wm / tp + P->Cm * s.dp;
    s.ql = P->Gl * s.dp;
    s.Tm = P->Dm * s.dp / tp - P->bm * s.wm;
    s.Tp = P->x * P->Dp * s.dp / tp;
    s.wL = s.wm / P->ratio;
    s.pH = P->pL + s.dp;
    return s;
}

static void run_steady(const circ_par *P, const char *what)
{
    circ C = build_circuit(P);
    bgr_model *m = C.m;
    if (!compile_ok(m, what)) {
        bgr_model_free(&C.m);
        return;
    }
    bgr_y0(m)[bgr_ref_var(m, (bgr_ref){BGR_STATE, C.vol, 0})] = P->pL; /* line at charge pressure */
    dae_solver *s = solver_new(m, 1e-9, 1e-12, NULL, NULL, 0, 0.0);
    int n = bgr_n(m);
    double *y = calloc((size_t)n, sizeof *y), *yp = calloc((size_t)n, sizeof *yp);
    int e_tm = V(m, "circuit/shaft_m/e"), f_tm = V(m, "circuit/shaft_m/f");
    int e_tl = V(m, "circuit/shaft_l/e"), f_tl = V(m, "circuit/shaft_l/f");
    double pmax = 0, t = 0;
    char line[512];
    int r = s ? 0 : -1;
    /* the gear at every step: power in = power out to the Newton tolerance */
    while (r >= 0 && t < 12.0) {
        r = dae_step(s, 12.0, &t, y, yp);
        if (r < 0) tap_diag("dae_step: %s: %s", dae_return_name(r), dae_get_error(s)->message);
        double pin = C.sgn_shaft * at(y, e_tm) * at(y, f_tm), pout = at(y, e_tl) * at(y, f_tl);
        if (fabs(pin) > 1e-3) pmax = fmax(pmax, fabs(pin - pout) / fabs(pin));
    }
    if (r >= 0) r = solve_to(s, 12.0, y, yp);
    tap_ok(r >= 0, "%s: integrated to t = 12 s", what);
    tap_diag("%s: %s", what, s ? (dae_stats_line(dae_get_stats(s), line, sizeof line), line) : "");
    circ_ss h = steady(P);
    double qp = C.sgn_pump_out * at(y, V(m, "circuit/pump_out/f"));
    double qm = C.sgn_motor_in * at(y, V(m, "circuit/motor_in/f"));
    double ql = at(y, V(m, "circuit/leak_in/f"));
    double Tm = at(y, e_tm), wm = C.sgn_shaft * at(y, f_tm);
    double Tp = at(y, V(m, "circuit/shaft_p/e")),
           wp = C.sgn_drive * at(y, V(m, "circuit/shaft_p/f"));
    double pH = at(y, V(m, "circuit/high/p")), pL = at(y, V(m, "circuit/pump_in/e"));
    double wL = at(y, V(m, "circuit/to_inertia/f"));
    double pdot = at(yp, V(m, "circuit/high/p"));
    tap_diag("%s: q_pump %.9g, q_motor %.9g, q_leak %.9g m^3/s; dp %.9g Pa; T_motor %.9g, "
             "T_pump %.9g N m; w_motor %.9g rad/s",
             what, qp, qm, ql, pH - pL, Tm, Tp, wm);
    tap_ok(fabs(pdot) < 1e-3 * h.dp, "%s: steady state reached (dp/dt = %.3g Pa/s)", what, pdot);
    tap_close(qp, qm + ql, 1e-9, 0, "%s: pump flow = motor flow + leakage", what);
    tap_close(qp, h.qp, 1e-7, 0, "%s: pump flow = x Dp wp/(2 pi) - Cp dp = %.9g", what, h.qp);
    tap_close(qm, h.qm, 1e-7, 0, "%s: motor flow = Dm wm/(2 pi) + Cm dp = %.9g", what, h.qm);
    tap_close(ql, h.ql, 1e-7, 0, "%s: leak flow = Gl dp = %.9g", what, h.ql);
    tap_close(pH - pL, h.dp, 1e-7, 0, "%s: pressure difference = %.9g Pa", what, h.dp);
    tap_close(pH, h.pH, 1e-7, 0, "%s: high-line pressure = charge + dp = %.9g", what, h.pH);
    tap_close(wm, h.wm, 1e-7, 0, "%s: motor speed = %.9g rad/s", what, h.wm);
    tap_close(Tm, P->Dm * (pH - pL) / (2 * PI) - P->bm * wm, 1e-9, 0,
              "%s: motor torque = D dp/(2 pi) - b w from the simulated dp and w", what);
    tap_close(Tm, h.Tm, 1e-7, 0, "%s: motor torque = %.9g N m (hand)", what, h.Tm);
    tap_close(Tp, h.Tp, 1e-7, 0, "%s: pump torque = x Dp dp/(2 pi) = %.9g N m", what, h.Tp);
    tap_close(wp, P->wp, 1e-12, 0, "%s: pump driven at %g rad/s", what, P->wp);
    tap_close(wL, h.wL, 1e-7, 0, "%s: load speed = w_motor / i = %.9g", what, h.wL);
    /* power balance: what the drive puts in is dissipated in the leaks and the frictions (the tank
     * exchanges no flow at steady state) */
    double diss = (P->Cp + P->Cm + P->Gl) * h.dp * h.dp + P->bm * h.wm * h.wm + P->bL * h.wL * h.wL;
    tap_close(Tp * wp, diss, 1e-7, 0, "%s: drive power = losses (%.6g W)", what, diss);
    tap_ok(pmax < 1e-8, "%s: gear power in = power out at every step (max rel. diff %.3g)", what,
           pmax);
    /* exactly: once the gear's two (linear, unit-coefficient) equations are solved, power is
     * conserved to round-off, whatever the other unknowns */
    if (r >= 0) {
        int eqe = bgr_find_eq(m, "circuit/gear/effort"), eqf = bgr_find_eq(m, "circuit/gear/flow");
        double *F = calloc((size_t)n, sizeof *F);
        tap_rng g = tap_rng_seed(3);
        double worst = 0;
        for (int k = 0; k < 100; k++) {
            y[e_tl] = tap_rng_range(&g, -1e3, 1e3);
            y[f_tm] = tap_rng_range(&g, -1e2, 1e2);
            bgr_residual(m, 0.0, y, yp, F);
            y[e_tm] -= F[eqe]; /* dF_effort/dT_in = 1 */
            y[f_tl] -= F[eqf]; /* dF_flow/dw_out = -s_out = 1 */
            double pin = C.sgn_shaft * y[e_tm] * y[f_tm], pout = y[e_tl] * y[f_tl];
            worst = fmax(worst, fabs(pin - pout) / fmax(fabs(pin), 1e-300));
        }
        tap_ok(eqe >= 0 && eqf >= 0 && worst <= 1e-14,
               "%s: gear conserves power exactly (100 random states: max rel. diff %.3g)", what,
               worst);
        free(F);
    }
    dae_free(&s);
    free(y);
    free(yp);
    bgr_model_free(&C.m);
}

static void test_jacobian(void)
{
    /* O(1) parameters so that every partial derivative is of a size the check resolves */
    circ_par P = {.wp = 1.3,
                  .Dp = 0.9,
                  .x = 0.6,
                  .Cp = 0.2,
                  .Dm = 1.1,
                  .Cm = 0.3,
                  .bm = 0.4,
                  .Gl = 0.25,
                  .V = 0.8,
                  .beta = 1.7,
                  .ratio = 2.5,
                  .J = 0.6,
                  .bL = 0.7,
                  .pL = 0.3,
                  .rev = 1};
    for (int rev = 0; rev < 2; rev++) {
        P.rev = rev;
        circ C = build_circuit(&P);
        if (compile_ok(C.m, rev ? "jacobian, reversed bonds" : "jacobian")) {
            int n = bgr_n(C.m);
            double *y = malloc((size_t)n * sizeof *y), *yp = malloc((size_t)n * sizeof *yp);
            random_point(n, NULL, 11 + (uint64_t)rev, y, yp);
            check_jac(C.m, 0.5, y, yp, 1e-6, rev ? "circuit, reversed bonds" : "circuit");
            free(y);
            free(yp);
        }
        bgr_model_free(&C.m);
    }
}

static void test_arguments(void)
{
    bgr_model *m = bgr_model_create("args");
    int c = sig_constant(m, 0, "x", 1.0, SIG_VALUE);
    tap_ok(hyd_pump(m, 0, "p", -1.0, 0.0, (bgr_ref){BGR_OWN, c, 0}) < 0 &&
               strstr(bgr_model_error(m)->message, "args/p (hyd_pump)"),
           "pump with negative displacement refused: %s", bgr_model_error(m)->message);
    tap_ok(hyd_motor(m, 0, "mo", 1.0, -1.0, 0.0) < 0, "motor with negative leakage refused: %s",
           bgr_model_error(m)->message);
    tap_ok(rot_gear(m, 0, "g", 0.0) < 0, "gear with ratio 0 refused: %s",
           bgr_model_error(m)->message);
    tap_ok(hyd_volume(m, 0, "v", 0, 1.0, 1.0) < 0, "volume without ports refused: %s",
           bgr_model_error(m)->message);
    bgr_model_free(&m);
}

/* Nominal magnitudes of the hydraulic and rotational components: a drive (Sf, 150 rad/s) turns a
 * pump (command x = 0.5) that feeds a line volume; a motor returns the flow to a 0-junction held
 * at 1 MPa by a tank; a relief valve (cracking 3e7, full flow 3.5e7 Pa at 0.02 m^3/s) from the
 * line to the junction; the motor drives an inertia. Stated: pump 3e7 Pa and 150 rad/s, motor
 * 2.5e7 Pa and 80 rad/s, line 2e7 Pa, inertia 80 rad/s. Every expected value below is the
 * documented rule applied by hand; a bond seen from two elements gets the larger. */
static void test_nominals(void)
{
    const double Dp = 5e-5, Dm = 1e-4, J = 50.0, wp = 150.0, pL = 1e6;
    bgr_model *m = bgr_model_create("nh");
    int drive = bgr_Sf(m, 0, "drive", 1, &wp);
    int cmd = sig_constant(m, 0, "x", 0.5, SIG_VALUE);
    int pump = hyd_pump(m, 0, "pump", Dp, 1e-12, (bgr_ref){BGR_OWN, cmd, 0});
    int line = hyd_volume(m, 0, "line", 3, 1e-3, 1.4e9);
    int motor = hyd_motor(m, 0, "motor", Dm, 1e-12, 0.0);
    int low = bgr_zero(m, 0, "low", 4, 1);
    int tank = hyd_tank(m, 0, "tank", pL);
    int relief = hyd_relief_valve(m, 0, "relief", 3e7, 3.5e7, 0.02, 1e5);
    int in = rot_inertia(m, 0, "inertia", J);
    B(m, "shaft_p", drive, 0, pump, 0);
    B(m, "pump_out", pump, 2, line, 0);
    B(m, "motor_in", line, 1, motor, 0);
    B(m, "relief_in", line, 2, relief, 0);
    B(m, "relief_out", relief, 1, low, 0);
    B(m, "motor_out", motor, 1, low, 1);
    B(m, "charge", tank, 0, low, 2);
    B(m, "pump_in", low, 3, pump, 1);
    B(m, "shaft_m", motor, 2, in, 0);
    /* bad statements first: nothing is changed by them */
    tap_ok(hyd_pump_set_nominal(m, motor, 1e7, 1.0) == BG_ERR_ARGUMENT &&
               hyd_motor_set_nominal(m, pump, 1e7, 1.0) == BG_ERR_ARGUMENT &&
               hyd_volume_set_nominal(m, pump, 1e7) == BG_ERR_ARGUMENT &&
               rot_inertia_set_nominal(m, line, 1.0) == BG_ERR_ARGUMENT,
           "the nominal setters refuse an element of another kind (%s)",
           bgr_model_error(m)->message);
    int bad = hyd_volume_set_nominal(m, line, -2e7);
    tap_ok(bad == BG_ERR_ARGUMENT && strstr(bgr_model_error(m)->message, "nh/line"),
           "a negative nominal pressure is refused naming the element (%s)",
           bgr_model_error(m)->message);
    bad = hyd_pump_set_nominal(m, pump, 3e7, NAN);
    tap_ok(bad == BG_ERR_ARGUMENT && strstr(bgr_model_error(m)->message, "nh/pump"),
           "a NaN nominal speed is refused naming the element (%s)", bgr_model_error(m)->message);
    tap_ok(hyd_pump_set_nominal(m, pump, 3e7, wp) == BG_OK &&
               hyd_motor_set_nominal(m, motor, 2.5e7, 80.0) == BG_OK &&
               hyd_volume_set_nominal(m, line, 2e7) == BG_OK &&
               rot_inertia_set_nominal(m, in, 80.0) == BG_OK,
           "the nominal setters accept pump, motor, volume and inertia scales");
    if (!compile_ok(m, "nominal circuit")) {
        bgr_model_free(&m);
        return;
    }
    tap_ok(hyd_volume_set_nominal(m, line, 1e7) == BG_ERR_STATE,
           "stating a scale after compilation: BG_ERR_STATE (%s)", bgr_model_error(m)->message);
    const double *nom = bgr_nominals(m);
    const double k_p = Dp / (2 * PI), k_m = Dm / (2 * PI);
    struct {
        const char *path;
        double want;
        const char *why;
    } t[] = {
        {"nh/line/p", 2e7, "line pressure: the stated 2e7"},
        {"nh/pump_out/e", 3e7, "pump outlet: pump 3e7 > line 2e7"},
        {"nh/motor_in/e", 2.5e7, "motor inlet: motor 2.5e7 > line 2e7"},
        {"nh/relief_in/e", 3.5e7, "relief inlet: its full-flow pressure 3.5e7 > line 2e7"},
        {"nh/relief_out/e", 3.5e7, "relief outlet: its full-flow pressure"},
        {"nh/relief_in/f", 0.02, "relief flow: its rated flow"},
        {"nh/pump_in/e", 3e7, "pump inlet: the stated pressure"},
        {"nh/motor_out/e", 2.5e7, "motor outlet: the stated pressure"},
        {"nh/charge/e", pL, "tank: its pressure (a constant Se)"},
        {"nh/shaft_p/e", k_p * 3e7, "pump torque Dp p / (2 pi)"},
        {"nh/shaft_p/f", wp, "pump speed: the stated one and the drive's 150"},
        {"nh/pump_out/f", k_p * wp, "pump flow Dp w / (2 pi)"},
        {"nh/motor_in/f", k_m * 80.0, "motor flow Dm w / (2 pi)"},
        {"nh/shaft_m/e", k_m * 2.5e7, "motor torque Dm p / (2 pi)"},
        {"nh/shaft_m/f", 80.0, "motor speed"},
        {"nh/inertia/p", J * 80.0, "inertia momentum J w"},
        {"nh/inertia/angle", 1.0, "angle: no scale"},
        {"nh/x/value", 0.5, "constant signal: its value"},
        {"nh/charge/f", 1.0, "the tank's flow: no scale"},
    };
    for (size_t i = 0; i < sizeof t / sizeof t[0]; i++) {
        int v = V(m, t[i].path);
        tap_close(v >= 0 ? nom[v] : NAN, t[i].want, 1e-15, 0, "nominal of %s = %g (%s)",
                  t[i].path, t[i].want, t[i].why);
    }
    bgr_model_free(&m);

    /* unstated: the same circuit keeps 1 (SI) where no parameter gives a scale */
    m = bgr_model_create("plain");
    line = hyd_volume(m, 0, "line", 1, 1e-3, 1.4e9);
    int src = hyd_flow_source(m, 0, "q", 0.0);
    B(m, "b", src, 0, line, 0);
    if (compile_ok(m, "volume without a stated pressure")) {
        nom = bgr_nominals(m);
        int vp = V(m, "plain/line/p"), ve = V(m, "plain/b/e");
        tap_ok(vp >= 0 && ve >= 0 && nom[vp] == 1.0 && nom[ve] == 1.0,
               "a volume without a stated pressure declares nothing: p and its port 1 Pa");
    }
    bgr_model_free(&m);
}

/* The parameters of the pump, the motor, the sources and the gear (headers: the accepted
 * ranges): NaN, infinities, 0 and negative numbers where refused; one test point each
 * (param_check.h: refused with a message naming the element's path and the parameter, nothing
 * added, the name free afterwards). */
static double pk(int which, int k, double x, double good)
{
    return which == k ? x : good;
}
static int mk_pump(bgr_model *m, bgr_comp c, const char *name, int which, double x)
{
    bgr_ref cmd = {BGR_OWN, 0, 0};
    return hyd_pump(m, c, name, pk(which, 0, x, 5e-5), pk(which, 1, x, 1e-12), cmd);
}
static int mk_motor(bgr_model *m, bgr_comp c, const char *name, int which, double x)
{
    return hyd_motor(m, c, name, pk(which, 0, x, 1e-4), pk(which, 1, x, 1e-12),
                     pk(which, 2, x, 0.5));
}
static int mk_tank(bgr_model *m, bgr_comp c, const char *name, int which, double x)
{
    return hyd_tank(m, c, name, pk(which, 0, x, 1e6));
}
static int mk_flow(bgr_model *m, bgr_comp c, const char *name, int which, double x)
{
    return hyd_flow_source(m, c, name, pk(which, 0, x, -1e-3));
}
static int mk_gear(bgr_model *m, bgr_comp c, const char *name, int which, double x)
{
    return rot_gear(m, c, name, pk(which, 0, x, 10.0));
}

static void test_param_checks(void)
{
    const double nan = NAN, inf = INFINITY;
    const char *POS = "expected a finite number > 0", *NNEG = "expected a finite number >= 0";
    const char *FIN = "expected a finite number", *NZ = "expected a finite number != 0";
    const pc_case cases[] = {
        {"hyd_pump", mk_pump, 0, nan, "Dp = ", POS},
        {"hyd_pump", mk_pump, 0, inf, "Dp = ", POS},
        {"hyd_pump", mk_pump, 0, 0.0, "Dp = ", POS},
        {"hyd_pump", mk_pump, 0, -5e-5, "Dp = ", POS},
        {"hyd_pump", mk_pump, 1, nan, "Cl = ", NNEG},
        {"hyd_pump", mk_pump, 1, inf, "Cl = ", NNEG},
        {"hyd_pump", mk_pump, 1, -1e-12, "Cl = ", NNEG},
        {"hyd_motor", mk_motor, 0, nan, "D = ", POS},
        {"hyd_motor", mk_motor, 0, -inf, "D = ", POS},
        {"hyd_motor", mk_motor, 0, 0.0, "D = ", POS},
        {"hyd_motor", mk_motor, 0, -1e-4, "D = ", POS},
        {"hyd_motor", mk_motor, 1, inf, "Cl = ", NNEG},
        {"hyd_motor", mk_motor, 1, -1.0, "Cl = ", NNEG},
        {"hyd_motor", mk_motor, 2, nan, "b = ", NNEG},
        {"hyd_motor", mk_motor, 2, -0.5, "b = ", NNEG},
        {"hyd_tank", mk_tank, 0, nan, "pressure = ", FIN},
        {"hyd_tank", mk_tank, 0, inf, "pressure = ", FIN},
        {"hyd_tank", mk_tank, 0, -inf, "pressure = ", FIN},
        {"hyd_flow_source", mk_flow, 0, nan, "flow = ", FIN},
        {"hyd_flow_source", mk_flow, 0, inf, "flow = ", FIN},
        {"rot_gear", mk_gear, 0, nan, "ratio = ", NZ},
        {"rot_gear", mk_gear, 0, inf, "ratio = ", NZ},
        {"rot_gear", mk_gear, 0, 0.0, "ratio = ", NZ},
        {"rot_gear", mk_gear, 0, 1e-310, "ratio = ", "with a finite 1 / ratio"},
    };
    int n = (int)(sizeof cases / sizeof cases[0]);
    bgr_model *m = bgr_model_create("params");
    bgr_comp c = bgr_component(m, bgr_component(m, 0, "drive"), "bad");
    int passed = pc_run(m, c, "x", cases, n);
    tap_diag("%d of %d refusals as required", passed, n);
    bgr_model_free(&m);
}

int main(void)
{
    /* 50 cm^3/rev pump at 150 rad/s, 60 % displacement; 100 cm^3/rev motor; 1 l line; gear 10:1
     * onto 50 kg m^2 with 500 N m s load friction; 10 bar charge pressure */
    circ_par P = {.wp = 150.0,
                  .Dp = 5e-5,
                  .x = 0.6,
                  .Cp = 1e-12,
                  .Dm = 1e-4,
                  .Cm = 1e-12,
                  .bm = 0.0,
                  .Gl = 5e-13,
                  .V = 1e-3,
                  .beta = 1.4e9,
                  .ratio = 10.0,
                  .J = 50.0,
                  .bL = 500.0,
                  .pL = 1e6,
                  .rev = 0};
    run_steady(&P, "closed circuit");
    P.bm = 0.5;
    P.rev = 1;
    run_steady(&P, "with motor friction, reversed bonds");
    test_jacobian();
    test_arguments();
    test_param_checks();
    test_nominals();
    return tap_done();
}
