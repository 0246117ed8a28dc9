/* Hydraulic cylinder (hyd_cylinder) between a fixed support and a point mass (mech_parts),
 * against closed forms:
 *   - statics: a vertical cylinder holding a mass m on its rod end with the cap chamber closed
 *     and the rod chamber vented to the tank (bgr_static): p_a = m g / A_a, p_b = 0;
 *   - modes: both chambers closed, the mass on the two oil columns (bgr_modes): the hydraulic
 *     natural frequency omega^2 = (beta / m) (A_a^2 / V_a + A_b^2 / V_b) (H. E. Merritt,
 *     Hydraulic Control Systems, 1967) and, with viscous friction c, the damping ratio
 *     c / (2 sqrt(k m)) of m s^2 + c s + k = 0; the two lateral modes of the mass balanced on
 *     the strut, s = +-sqrt(g / L) (an inverted pendulum: real, one unstable);
 *   - energy: the cylinder driven through a 4/3 valve (hyd_directional) by a sine command, with
 *     friction and internal leakage: hydraulic energy in = change of stored oil energy + kinetic
 *     + potential + friction and leakage dissipation, integrated with Gauss quadrature on the
 *     dense output; and the mechanical power into the cylinder against the mass's energy;
 *   - the end of the stroke: a flow source driving the piston into the head stops the run with
 *     a message naming the cylinder's equation;
 *   - the analytic Jacobian against finite differences in an oblique pose, bonds of both
 *     orientations;
 *   - misuse: every parameter out of its range refused with BG_ERR_ARGUMENT and a message
 *     naming the path and the parameter (param_check.h), the helpers on wrong elements. */
#include "bgr_analysis.h"
#include "bondgraph/param_check.h"
#include "cmptest.h"
#include "hyd_cylinder.h"
#include "hyd_directional.h"
#include "hyd_source.h"
#include "hyd_valve.h"
#include "mech_parts.h"
#include "sig_sources.h"

static const double GRAV = 9.81;

/* A 3D bond from port pa of element a to port pb of element b. */
static int B3(bgr_model *m, const char *name, int a, int pa, int b, int pb)
{
    int id = bgr_bond(m, 0, name, 3, bgr_port_of(m, a, pa), bgr_port_of(m, b, pb), NULL, NULL);
    if (id < 0) {
        ct_bond_fail++;
        tap_diag("bond %s: %s", name, bgr_model_error(m)->message);
    }
    return id;
}

/* 80 mm bore, 56 mm rod (A_b about half of A_a), 0.5 m stroke. */
static hyd_cylinder_spec spec_default(void)
{
    hyd_cylinder_spec s = {.area_a = 5e-3,
                           .area_b = 2.5e-3,
                           .length_min = 1.0,
                           .stroke = 0.5,
                           .volume_a0 = 2e-4,
                           .volume_b0 = 1.5e-4,
                           .beta = 1.4e9,
                           .friction = 0,
                           .leakage = 0};
    return s;
}

/* Vertical cylinder, barrel on a support at the origin, rod end up at z = L_min + x0 carrying
 * the point mass. Cap port: closed (flow source 0). Rod port: closed, or vented to a tank at
 * 0 Pa through a laminar restriction (vent = 1). Compiled, set at x0 with zero pressures. */
static bgr_model *vertical(const hyd_cylinder_spec *s, double mass, double x0, int vent, int *cyl,
                           int *pm)
{
    const double g[3] = {0, 0, -GRAV};
    bgr_model *m = bgr_model_create("vc");
    int sup = mech_support(m, 0, "ground", 3);
    *cyl = hyd_cylinder(m, 0, "cyl", s);
    *pm = mech_point_mass(m, 0, "load", mass, g);
    int capq = hyd_flow_source(m, 0, "cap_closed", 0.0);
    B3(m, "b_ground", sup, 0, *cyl, 0);
    B3(m, "b_load", *cyl, 1, *pm, 0);
    B(m, "b_cap", capq, 0, *cyl, 2);
    if (vent) {
        int leak = hyd_leakage(m, 0, "vent", 1e-9), tank = hyd_tank(m, 0, "tank", 0.0);
        B(m, "b_rod", *cyl, 3, leak, 0);
        B(m, "b_tank", leak, 1, tank, 0);
    } else {
        int rodq = hyd_flow_source(m, 0, "rod_closed", 0.0);
        B(m, "b_rod", rodq, 0, *cyl, 3);
    }
    if (!compile_ok(m, vent ? "vertical cylinder, rod side vented" : "vertical cylinder, closed")) {
        bgr_model_free(&m);
        return NULL;
    }
    const double xa[3] = {0, 0, 0}, xb[3] = {0, 0, s->length_min + x0};
    hyd_cylinder_set(m, *cyl, xa, xb, 0.0, 0.0);
    mech_point_mass_set(m, *pm, xb, NULL);
    return m;
}

static void test_static(void)
{
    hyd_cylinder_spec s = spec_default();
    const double mass = 5000, x0 = 0.25;
    int cyl, pm;
    bgr_model *m = vertical(&s, mass, x0, 1, &cyl, &pm);
    if (!m) return;
    bg_error err = {0};
    dae_static_result res;
    int st = bgr_static(m, NULL, 0.0, &res, &err);
    const double *y = bgr_y0(m);
    double pa = at(y, V(m, "vc/cyl/p_a")), pb = at(y, V(m, "vc/cyl/p_b")),
           want = mass * GRAV / s.area_a;
    tap_ok(st == BG_OK, "static: equilibrium found (%s)", st ? err.message : "ok");
    tap_close(pa, want, 1e-9, 0, "static: cap pressure m g / A_a = %.9g Pa (%.9g)", want, pa);
    tap_ok(fabs(pb) < 1e-6 * want, "static: vented rod side at the tank's 0 Pa (%.3g Pa)", pb);
    /* the closed cap chamber keeps its oil, V_a exp(p_a / beta) as assembled; the static
     * solver keeps such a nonlinear invariant to second order (bg_static.h): within (p/beta)^2 */
    hyd_cylinder_values v;
    hyd_cylinder_evaluate(m, cyl, y, &v);
    double Va0 = s.volume_a0 + s.area_a * x0, Va = Va0 * exp(-want / s.beta);
    tap_close(v.volume_a, Va, pow(want / s.beta, 2), 0,
              "static: the piston sank until V_a = V_a(x0) exp(-p_a / beta) = %.9g m^3 (%.9g)", Va,
              v.volume_a);
    tap_close(v.tension, -mass * GRAV, 1e-9, 0, "static: the cylinder pushes with m g = %g N",
              mass * GRAV);
    bgr_model_free(&m);
}

/* Both chambers closed: the mode of the mass on the oil columns. */
static void test_modes(double c)
{
    hyd_cylinder_spec s = spec_default();
    s.friction = c;
    const double mass = 5000, x0 = 0.2;
    int cyl, pm;
    bgr_model *m = vertical(&s, mass, x0, 0, &cyl, &pm);
    if (!m) return;
    bg_error err = {0};
    int st = bgr_static(m, NULL, 0.0, NULL, &err);
    tap_ok(st == BG_OK, "modes, c = %g: equilibrium (%s)", c, st ? err.message : "ok");
    const double *y = bgr_y0(m);
    double pa = at(y, V(m, "vc/cyl/p_a")), pb = at(y, V(m, "vc/cyl/p_b"));
    tap_close(pa * s.area_a - pb * s.area_b, mass * GRAV, 1e-9, 0,
              "modes, c = %g: p_a A_a - p_b A_b = m g at rest", c);
    /* V_a, V_b from the length the equilibrium has */
    int vd = V(m, "vc/cyl/d0");
    double L = vd >= 0 ? sqrt(y[vd] * y[vd] + y[vd + 1] * y[vd + 1] + y[vd + 2] * y[vd + 2]) : NAN;
    double x = L - s.length_min, Va = s.volume_a0 + s.area_a * x;
    double Vb = s.volume_b0 + s.area_b * (s.stroke - x);
    double k = s.beta * (s.area_a * s.area_a / Va + s.area_b * s.area_b / Vb);
    double wn = sqrt(k / mass), zeta = c / (2 * sqrt(k * mass)), wl = sqrt(GRAV / L);
    dae_modes *M = NULL;
    st = bgr_modes(m, 0.0, NULL, NULL, NULL, &M, &err);
    int ne = -1;
    dae_modes_info(M, &ne, NULL, NULL, NULL, NULL, NULL);
    const dae_mode *hyd = NULL;
    int lateral = 0;
    for (int i = 0; i < dae_modes_count(M); i++) {
        const dae_mode *md = dae_modes_get(M, i);
        if (md->kind != DAE_MODE_ELASTIC) continue;
        double w = md->freq_hz * 2 * PI;
        if (fabs(w - wl) < 1e-8 * wl && fabs(fabs(md->damping) - 1) < 1e-8) lateral++;
        if (!hyd || md->freq_hz > hyd->freq_hz) hyd = md;
    }
    char desc[256] = "";
    for (int i = 0; hyd && i < dae_modes_count(M); i++)
        if (dae_modes_get(M, i) == hyd) dae_modes_describe(M, i, 2, 3, 2, desc, sizeof desc);
    double w = hyd ? hyd->freq_hz * 2 * PI : NAN;
    tap_ok(st == BG_OK && hyd && fabs(w - wn) < 1e-8 * wn,
           "modes, c = %g: hydraulic mode at sqrt((beta/m)(A_a^2/V_a + A_b^2/V_b)) = %.9g rad/s "
           "(%.9g; %s)",
           c, wn, w, st ? err.message : desc);
    tap_ok(hyd && fabs(hyd->damping - zeta) < 1e-8 + 1e-7 * zeta,
           "modes, c = %g: damping ratio c / (2 sqrt(k m)) = %.9g (%.9g)", c, zeta,
           hyd ? hyd->damping : NAN);
    tap_ok(lateral == 4,
           "modes, c = %g: the four real lateral eigenvalues s = +-sqrt(g/L) = +-%.6g rad/s of the "
           "mass balanced on the strut (%d found)",
           c, wl, lateral);
    dae_modes_free(&M);
    bgr_model_free(&m);
}

/* Gauss-Legendre, 5 points on [-1, 1]. */
static const double GX[5] = {-0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831,
                             0.9061798459386640};
static const double GW[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889,
                             0.4786286704993665, 0.2369268850561891};

/* Supply p_s -> valve P, valve T -> tank, valve A -> cap, valve B -> rod side; the mass on the
 * rod end of the vertical cylinder; command u = 0.4 sin(2 pi t / 1.5 s). */
static void test_energy(void)
{
    hyd_cylinder_spec s = spec_default();
    s.friction = 2e4;
    s.leakage = 1e-12;
    const double mass = 2000, x0 = 0.25, ps = 1.6e7, tend = 1.5;
    hyd_directional_spec vs = {.flow_rated = 100.0 / 60000, .dp_rated = 35e5, .leakage = 1e-13};
    const double g[3] = {0, 0, -GRAV};
    bgr_model *m = bgr_model_create("en");
    int sup = mech_support(m, 0, "ground", 3), cyl = hyd_cylinder(m, 0, "cyl", &s);
    int pm = mech_point_mass(m, 0, "load", mass, g);
    int cmd = sig_sine(m, 0, "command", 0.4, 2 * PI / tend, 0.0, 0.0, SIG_VALUE);
    int valve = hyd_directional_valve(m, 0, "valve", (bgr_ref){BGR_OWN, cmd, 0}, &vs);
    int sp = hyd_tank(m, 0, "supply", ps), tank = hyd_tank(m, 0, "tank", 0.0);
    B3(m, "b_ground", sup, 0, cyl, 0);
    B3(m, "b_load", cyl, 1, pm, 0);
    B(m, "b_p", sp, 0, valve, 0);
    B(m, "b_t", valve, 1, tank, 0);
    B(m, "b_a", valve, 2, cyl, 2);
    B(m, "b_b", cyl, 3, valve, 3); /* reversed: power from the rod side into the valve's B */
    hyd_cylinder_set_nominal(m, cyl, ps, 0.1);
    if (!compile_ok(m, "energy: valve-driven cylinder")) {
        bgr_model_free(&m);
        return;
    }
    const double xa[3] = {0, 0, 0}, xb[3] = {0, 0, s.length_min + x0};
    double pa0 = (mass * GRAV + 0.3 * ps * s.area_b) / s.area_a;
    hyd_cylinder_set(m, cyl, xa, xb, pa0, 0.3 * ps);
    mech_point_mass_set(m, pm, xb, NULL);
    dae_solver *sol = solver_new(m, 1e-10, 1e-10, NULL, NULL, 0, 0.0);
    int n = bgr_n(m);
    double *y = calloc((size_t)n, sizeof *y), *yp = calloc((size_t)n, sizeof *yp);
    double *yq = calloc((size_t)n, sizeof *yq);
    hyd_cylinder_values v0, v;
    double ke0, pe0, ke, pe;
    hyd_cylinder_evaluate(m, cyl, bgr_y0(m), &v0);
    mech_point_mass_energy(m, pm, bgr_y0(m), &ke0, &pe0);
    double Ehyd = 0, Econv = 0, Emech = 0, Dfric = 0, Dleak = 0, t = 0, xmin = 1, xmax = 0;
    int r = sol ? 0 : -1;
    while (r >= 0 && t < tend) {
        double t0 = t;
        r = dae_step(sol, tend, &t, y, yp);
        if (r < 0) break;
        for (int k = 0; k < 5; k++) {
            double tq = 0.5 * (t0 + t) + 0.5 * (t - t0) * GX[k], wq = 0.5 * (t - t0) * GW[k];
            dae_dense(sol, tq, yq, NULL);
            hyd_cylinder_evaluate(m, cyl, yq, &v);
            Ehyd += wq * v.power_hydraulic;
            Econv += wq * v.power_convected;
            Emech += wq * v.power_mechanical;
            Dfric += wq * v.dissipation_friction;
            Dleak += wq * v.dissipation_leakage;
        }
        hyd_cylinder_evaluate(m, cyl, y, &v);
        xmin = fmin(xmin, v.extension);
        xmax = fmax(xmax, v.extension);
    }
    if (r < 0) tap_diag("energy run stopped at t = %g: %s", t, dae_get_error(sol)->message);
    tap_ok(r >= 0 && t >= tend, "energy: integrated to %g s (stroke used %.4f .. %.4f m)", tend,
           xmin, xmax);
    hyd_cylinder_evaluate(m, cyl, y, &v);
    mech_point_mass_energy(m, pm, y, &ke, &pe);
    double stored = v.energy - v0.energy, dkin = ke - ke0, dpot = pe - pe0;
    double in = Ehyd + Econv, out = stored + dkin + dpot + Dfric + Dleak;
    double scale = fabs(Ehyd) + fabs(Dfric) + fabs(dpot) + fabs(stored);
    tap_diag("energy: in %.9g J (bonds %.9g, convected %.6g), stored %.6g, kinetic %.6g, "
             "potential %.6g, friction %.6g, leakage %.6g",
             in, Ehyd, Econv, stored, dkin, dpot, Dfric, Dleak);
    tap_ok(fabs(in - out) < 1e-7 * scale,
           "energy: hydraulic in %.9g J = stored + kinetic + potential + dissipated %.9g J "
           "(|difference| %.3g, %.2g of the scale %.4g J)",
           in, out, fabs(in - out), fabs(in - out) / scale, scale);
    tap_ok(fabs(Econv) > 1e3 * fabs(in - out),
           "energy: the oil's convected compression energy (%.4g J) is resolved by the balance",
           Econv);
    tap_ok(fabs(Emech + dkin + dpot) < 1e-7 * scale,
           "energy: mechanical power into the cylinder %.9g J = -(kinetic + potential) %.9g J",
           Emech, -(dkin + dpot));
    tap_ok(Dfric > 0 && Dleak > 0 && xmax - xmin > 0.01,
           "energy: friction %.4g J and leakage %.4g J dissipated, piston moved %.4f m", Dfric,
           Dleak, xmax - xmin);
    dae_free(&sol);
    free(y);
    free(yp);
    free(yq);
    bgr_model_free(&m);
}

/* A flow source of 1 l/s into the cap side, the rod side vented: the piston reaches the head
 * at x = stroke after (stroke - x0) A_a / Q s, where the run must stop and name the cylinder. */
static void test_end_of_stroke(void)
{
    hyd_cylinder_spec s = spec_default();
    s.friction = 1e3;
    const double Q = 1e-3, x0 = 0.3, tend = 5.0;
    const double g[3] = {0, 0, 0};
    bgr_model *m = bgr_model_create("eos");
    int sup = mech_support(m, 0, "ground", 3), cyl = hyd_cylinder(m, 0, "cyl", &s);
    int pm = mech_point_mass(m, 0, "load", 100.0, g);
    int pump = hyd_flow_source(m, 0, "pump", Q), leak = hyd_leakage(m, 0, "vent", 1e-8);
    int tank = hyd_tank(m, 0, "tank", 0.0);
    B3(m, "b_ground", sup, 0, cyl, 0);
    B3(m, "b_load", cyl, 1, pm, 0);
    B(m, "b_cap", pump, 0, cyl, 2);
    B(m, "b_rod", cyl, 3, leak, 0);
    B(m, "b_tank", leak, 1, tank, 0);
    if (!compile_ok(m, "end of stroke")) {
        bgr_model_free(&m);
        return;
    }
    const double xa[3] = {0, 0, 0}, xb[3] = {s.length_min + x0, 0, 0};
    hyd_cylinder_set(m, cyl, xa, xb, 0.0, 0.0);
    mech_point_mass_set(m, pm, xb, NULL);
    dae_solver *sol = solver_new(m, 1e-8, 1e-8, NULL, NULL, 0, 0.0);
    int n = bgr_n(m);
    double *y = calloc((size_t)n, sizeof *y), *yp = calloc((size_t)n, sizeof *yp);
    double tret = 0;
    int r = sol ? dae_solve_to(sol, tend, &tret, y, yp) : 0;
    const char *msg = sol ? dae_get_error(sol)->message : "";
    double tend_stroke = (s.stroke - x0) * s.area_a / Q;
    tap_ok(r == DAE_RES_FAIL && strstr(msg, "eos/cyl/pressure_a") &&
               fabs(tret - tend_stroke) < 0.02,
           "end of stroke: the run stops at t = %.6g s (the head is reached at %.6g s), status "
           "%s: %s",
           tret, tend_stroke, dae_return_name(r), msg);
    dae_free(&sol);
    free(y);
    free(yp);
    bgr_model_free(&m);
}

/* Every partial derivative: the cylinder between two point masses in an oblique pose, with
 * friction and leakage, its bonds of both orientations. */
static void test_jacobian(void)
{
    hyd_cylinder_spec s = {.area_a = 0.8,
                           .area_b = 0.5,
                           .length_min = 1.0,
                           .stroke = 1.2,
                           .volume_a0 = 0.3,
                           .volume_b0 = 0.4,
                           .beta = 2.0,
                           .friction = 0.7,
                           .leakage = 0.3};
    const double g[3] = {0.1, -0.2, -1.0};
    bgr_model *m = bgr_model_create("jac");
    int ma = mech_point_mass(m, 0, "ma", 1.3, g), mb = mech_point_mass(m, 0, "mb", 0.8, g);
    int cyl = hyd_cylinder(m, 0, "cyl", &s);
    int qa = hyd_flow_source(m, 0, "qa", 0.2), tank = hyd_tank(m, 0, "tank", 0.1);
    B3(m, "b_a", cyl, 0, ma, 0); /* reversed: the bond starts at the cylinder */
    B3(m, "b_b", mb, 0, cyl, 1);
    B(m, "b_qa", qa, 0, cyl, 2);
    B(m, "b_tank", cyl, 3, tank, 0); /* reversed */
    if (!compile_ok(m, "jacobian")) {
        bgr_model_free(&m);
        return;
    }
    int n = bgr_n(m);
    double *y = calloc((size_t)n, sizeof *y), *yp = calloc((size_t)n, sizeof *yp);
    random_point(n, NULL, 17, y, yp);
    int vd = V(m, "jac/cyl/d0");
    const double d[3] = {0.9, -0.8, 1.1}; /* |d| = 1.677: x = 0.677 inside the stroke */
    for (int i = 0; i < 3 && vd >= 0; i++)
        y[vd + i] = d[i];
    check_jac(m, 0.0, y, yp, 1e-6, "cylinder");
    bgr_model_free(&m);
    free(y);
    free(yp);
}

/* The cylinder with spec field which (0 .. 8 in the order of hyd_cylinder_spec; 9: area_b
 * against area_a) replaced by x; which < 0: valid. */
static int mk_cylinder(bgr_model *m, bgr_comp c, const char *name, int which, double x)
{
    hyd_cylinder_spec s = spec_default();
    double *f[9] = {&s.area_a,    &s.area_b, &s.length_min, &s.stroke, &s.volume_a0,
                    &s.volume_b0, &s.beta,   &s.friction,   &s.leakage};
    if (which >= 0 && which < 9) *f[which] = x;
    if (which == 9) s.area_b = s.area_a * x;
    return hyd_cylinder(m, c, name, &s);
}

static void test_param_checks(void)
{
    const double inf = INFINITY, nan = NAN;
    const char *POS = "expected a finite number > 0", *NNEG = "expected a finite number >= 0";
    const pc_case cases[] = {
        {"hyd_cylinder", mk_cylinder, 0, 0.0, "area_a = 0", POS},
        {"hyd_cylinder", mk_cylinder, 0, nan, "area_a = nan", POS},
        {"hyd_cylinder", mk_cylinder, 1, -1e-3, "area_b = -0.001", POS},
        {"hyd_cylinder", mk_cylinder, 1, inf, "area_b = inf", POS},
        {"hyd_cylinder", mk_cylinder, 2, 0.0, "length_min = 0", POS},
        {"hyd_cylinder", mk_cylinder, 3, -0.5, "stroke = -0.5", POS},
        {"hyd_cylinder", mk_cylinder, 3, nan, "stroke = nan", POS},
        {"hyd_cylinder", mk_cylinder, 4, 0.0, "volume_a0 = 0", POS},
        {"hyd_cylinder", mk_cylinder, 5, -inf, "volume_b0 = -inf", POS},
        {"hyd_cylinder", mk_cylinder, 6, 0.0, "beta = 0", POS},
        {"hyd_cylinder", mk_cylinder, 7, -1.0, "friction = -1", NNEG},
        {"hyd_cylinder", mk_cylinder, 8, nan, "leakage = nan", NNEG},
        {"hyd_cylinder", mk_cylinder, 9, 1.5, "area_b = 0.0075", "expected <= area_a = 0.005"},
        {"hyd_cylinder", mk_cylinder, 4, 1e-310, "beta / volume_a0 = inf", "finite numbers"},
    };
    const int n = (int)(sizeof cases / sizeof cases[0]);
    bgr_model *m = bgr_model_create("params");
    bgr_comp c = bgr_component(m, 0, "drive");
    int passed = pc_run(m, c, "cyl", cases, n);
    tap_diag("%d of %d refusals as required", passed, n);

    int st = hyd_cylinder(m, c, "nospec", NULL);
    tap_ok(st == BG_ERR_ARGUMENT && strstr(bgr_model_error(m)->message, "params/drive/nospec") &&
               strstr(bgr_model_error(m)->message, "spec = NULL"),
           "spec NULL refused: %s", bgr_model_error(m)->message);
    int cyl = mk_cylinder(m, c, "ok", -1, 0), leak = hyd_leakage(m, 0, "leak", 1e-12);
    st = hyd_cylinder_set_nominal(m, cyl, -1.0, 0.0);
    tap_ok(st == BG_ERR_ARGUMENT && strstr(bgr_model_error(m)->message, "params/drive/ok") &&
               strstr(bgr_model_error(m)->message, "nominal scale -1"),
           "a negative nominal pressure refused: %s", bgr_model_error(m)->message);
    st = hyd_cylinder_set_nominal(m, leak, 1e7, 0.1);
    tap_ok(st == BG_ERR_ARGUMENT && strstr(bgr_model_error(m)->message, "not a hydraulic cylinder"),
           "nominal scales on a leakage refused: %s", bgr_model_error(m)->message);
    const double xa[3] = {0, 0, 0}, xb[3] = {0, 0, 1.2};
    st = hyd_cylinder_set(m, cyl, xa, xb, 0, 0);
    tap_ok(st == BG_ERR_ARGUMENT, "hyd_cylinder_set before compilation refused: %s",
           bgr_model_error(m)->message);
    hyd_cylinder_values v;
    tap_ok(hyd_cylinder_evaluate(m, cyl, xa, &v) == BG_ERR_ARGUMENT &&
               hyd_cylinder_evaluate(NULL, cyl, xa, &v) == BG_ERR_ARGUMENT,
           "hyd_cylinder_evaluate before compilation and on a NULL model refused");
    bgr_model_free(&m);
}

int main(void)
{
    test_static();
    test_modes(0.0);
    test_modes(5e4);
    test_energy();
    test_end_of_stroke();
    test_jacobian();
    test_param_checks();
    return tap_done();
}
