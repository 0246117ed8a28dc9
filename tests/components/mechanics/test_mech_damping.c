/* Masses added to bodies and the power that structural damping dissipates:
 *   - mech_body_add_mass: a body of 3 kg with 2 kg added, on a spring of 800 N/m to the ground,
 *     oscillates as x0 cos(sqrt(k / 5 kg) t) (closed form); the checks of the function;
 *   - mech_axial_dissipation: c L'^2 for a truss at a state whose ends move apart (closed form);
 *     0 for a rigid translation; for a mass on a damped spring the energy lost equals the
 *     integral of the dissipated power (the energy balance, over a decaying oscillation);
 *   - mech_beam_dissipation: beta d'^T K d' of a co-rotational element at states of known
 *     deformation rates: an axial stretching rate L' gives beta (E A / L0) L'^2, a rotation rate
 *     w of one end about e3 gives beta (4 E I_z / L0) w^2 (the end-rotation stiffness of the
 *     Euler-Bernoulli element), a rigid motion 0, and an element without damping 0. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bgr_elements.h"
#include "mech_axial.h"
#include "mech_beam.h"
#include "mech_body.h"
#include "mech_parts.h"
#include "modeltest.h"
#include "tap.h"

static const double zero3[3] = {0, 0, 0};

/* y[v] of the unknown called path = value; 0 if it exists. */
static int put(bgr_model *m, double *y, const char *path, double value)
{
    int v = bgr_find_var(m, path);
    if (v < 0) {
        tap_diag("no variable %s", path);
        return -1;
    }
    y[v] = value;
    return 0;
}

/* ground - spring - body (mass 3 kg + dm) at x0 along x, no gravity, no damping */
static void test_add_mass(void)
{
    const double k = 800, m0 = 3, dm = 2, x0 = 0.05, L0 = 1.0;
    bgr_model *m = bgr_model_create("osc");
    const double J[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1}, r[3] = {0, 0, 0};
    const int dims[1] = {3};
    int body = mech_body(m, 0, "body", m0, J, NULL, 1, r, dims);
    int gnd = mech_support(m, 0, "ground", 3), spr = mech_spring(m, 0, "spring", k, 0, L0);
    tap_ok(mech_body_add_mass(m, body, dm) == BG_OK, "2 kg added to a 3 kg body");
    tap_ok(mech_body_add_mass(m, body, -1) == BG_ERR_ARGUMENT &&
               strstr(bgr_model_error(m)->message, "dm = -1"),
           "a negative mass refused: %s", bgr_model_error(m)->message);
    tap_ok(mech_body_add_mass(m, body, NAN) == BG_ERR_ARGUMENT, "a NaN mass refused");
    tap_ok(mech_body_add_mass(m, spr, 1) == BG_ERR_ARGUMENT &&
               strstr(bgr_model_error(m)->message, "is not a body"),
           "a spring refused: %s", bgr_model_error(m)->message);
    bgr_bond(m, 0, "b0", 3, bgr_port_of(m, gnd, 0), bgr_port_of(m, spr, 0), NULL, NULL);
    bgr_bond(m, 0, "b1", 3, bgr_port_of(m, spr, 1), bgr_port_of(m, body, 0), NULL, NULL);
    if (bgr_compile(m) != BG_OK) {
        tap_ok(0, "oscillator compiles: %s", bgr_model_error(m)->message);
        bgr_model_free(&m);
        return;
    }
    tap_ok(mech_body_add_mass(m, body, 1) == BG_ERR_STATE, "after compiling: BG_ERR_STATE");
    const double xb[3] = {L0 + x0, 0, 0};
    mech_body_set(m, body, xb, NULL, NULL, NULL);
    mech_axial_set(m, spr, zero3, xb);
    dae_options o;
    dae_options_default(&o);
    o.rtol = o.atol = 1e-10;
    dae_solver *s = model_solver(m, &o, NULL, 0.0);
    double w = sqrt(k / (m0 + dm)), worst = 0, tret;
    int n = bgr_n(m), vx = mech_body_var(m, body, 'x');
    double *y = malloc(2 * (size_t)n * sizeof *y);
    for (int i = 1; s && i <= 8; i++) {
        double t = i * 0.25 * 2 * 3.14159265358979323846 / w * 0.9;
        if (dae_solve_to(s, t, &tret, y, y + n) < 0) break;
        worst = fmax(worst, fabs(y[vx] - L0 - x0 * cos(w * t)) / x0);
    }
    tap_ok(s && worst < 1e-6, "x = x0 cos(sqrt(k / (3 + 2) kg) t) within %.2e of x0", worst);
    double T = NAN, V = NAN;
    int re = BG_ERR_ARGUMENT;
    if (s) {
        y[mech_body_var(m, body, 'v')] = 0.4;
        y[mech_body_var(m, body, 'w')] = y[mech_body_var(m, body, 'w') + 1] = 0;
        y[mech_body_var(m, body, 'w') + 2] = 0;
        re = mech_body_energy(m, body, y, &T, &V);
    }
    tap_ok(re == BG_OK && fabs(T - 0.5 * (m0 + dm) * 0.16) < 1e-12 * T,
           "the kinetic energy counts the added mass: %.6g J at 0.4 m/s", T);
    dae_free(&s);
    free(y);
    bgr_model_free(&m);
}

/* ground - truss (E A / L0, damping c) - point mass, no gravity */
static void test_axial(void)
{
    const double E = 2e9, A = 1e-4, L0 = 2.0, c = 300, mass = 4.0, x0 = 1e-3;
    const double k = E * A / L0;
    bgr_model *m = bgr_model_create("ax");
    int gnd = mech_support(m, 0, "ground", 3), bar = mech_truss(m, 0, "bar", E, A, L0, c);
    int pm = mech_point_mass(m, 0, "mass", mass, NULL);
    bgr_bond(m, 0, "b0", 3, bgr_port_of(m, gnd, 0), bgr_port_of(m, bar, 0), NULL, NULL);
    bgr_bond(m, 0, "b1", 3, bgr_port_of(m, bar, 1), bgr_port_of(m, pm, 0), NULL, NULL);
    if (bgr_compile(m) != BG_OK) {
        tap_ok(0, "truss compiles: %s", bgr_model_error(m)->message);
        bgr_model_free(&m);
        return;
    }
    int n = bgr_n(m);
    double *y = calloc(2 * (size_t)n, sizeof *y);
    /* a state: the end 2.001 m out along (0.6, 0.8, 0) moving at (1.2, -0.5, 0.3) m/s */
    const double u[3] = {0.6, 0.8, 0}, vb[3] = {1.2, -0.5, 0.3};
    double Ld = u[0] * vb[0] + u[1] * vb[1] + u[2] * vb[2];
    int ok = 0;
    for (int i = 0; i < 3; i++) {
        char nm[64];
        snprintf(nm, sizeof nm, "ax/bar/d%d", i);
        ok += put(m, y, nm, (L0 + x0) * u[i]);
        snprintf(nm, sizeof nm, "ax/b1/f%d", i);
        ok += put(m, y, nm, vb[i]);
    }
    double P = mech_axial_dissipation(m, bar, y);
    tap_ok(ok == 0 && fabs(P - c * Ld * Ld) <= 1e-12 * c * Ld * Ld,
           "truss: dissipation %.9g W = c L'^2 = %.9g W", P, c * Ld * Ld);
    for (int i = 0; i < 3; i++) { /* both ends moving alike: no stretching */
        char nm[64];
        snprintf(nm, sizeof nm, "ax/b0/f%d", i);
        if (bgr_find_var(m, nm) >= 0) put(m, y, nm, vb[i]);
    }
    double P0 = mech_axial_dissipation(m, bar, y);
    tap_ok(bgr_find_var(m, "ax/b0/f0") >= 0 && fabs(P0) < 1e-12,
           "truss: a rigid translation dissipates nothing (%.2g W)", P0);
    tap_ok(isnan(mech_axial_dissipation(m, pm, y)) && isnan(mech_axial_dissipation(m, bar, NULL)),
           "not an axial element, or no state: NaN");

    /* the energy balance of the decaying oscillation: E(0) - E(t) = integral of P (Simpson) */
    const double xb[3] = {L0 + x0, 0, 0};
    mech_axial_set(m, bar, zero3, xb);
    mech_point_mass_set(m, pm, xb, NULL);
    dae_options o;
    dae_options_default(&o);
    o.rtol = o.atol = 1e-10;
    dae_solver *s = model_solver(m, &o, NULL, 0.0);
    double t = 0, tn, D = 0, Pa, T = NAN, V, E0 = 0.5 * k * x0 * x0;
    double *ym = malloc((size_t)n * 2 * sizeof *ym);
    double period = 2 * 3.14159265358979323846 * sqrt(mass / k);
    if (s) dae_dense(s, 0.0, y, y + n);
    Pa = s ? mech_axial_dissipation(m, bar, y) : NAN;
    while (s && t < 5 * period) {
        if (dae_step(s, 5 * period, &tn, y, y + n) < 0) break;
        double Pb = mech_axial_dissipation(m, bar, y);
        dae_dense(s, 0.5 * (t + tn), ym, ym + n);
        D += (Pa + 4 * mech_axial_dissipation(m, bar, ym) + Pb) * (tn - t) / 6;
        Pa = Pb;
        t = tn;
    }
    double Ex = s ? mech_axial_energy(m, bar, y) : NAN;
    int pe = s ? mech_point_mass_energy(m, pm, y, &T, &V) : -1;
    double Et = Ex + T;
    tap_ok(s && pe == BG_OK && D > 0.1 * E0 && fabs(E0 - Et - D) < 1e-6 * E0,
           "mass on a damped truss, 5 periods: energy lost %.9g J = dissipated %.9g J (of %.6g J)",
           E0 - Et, D, E0);
    dae_free(&s);
    free(ym);
    free(y);
    bgr_model_free(&m);
}

/* One element from (0, 0, 0) to (L, 0, 0), e2 along z, e3 along -y; with or without damping. */
static bgr_model *one_element(double beta, int *elem)
{
    static const double p0[3] = {0, 0, 0}, up[3] = {0, 0, 1};
    const double p1[3] = {3.0, 0, 0};
    mech_section sec = {.E = 2.1e11, .G = 8.1e10, .A = 1e-3, .Iy = 2e-6, .Iz = 5e-6, .J = 3e-6,
                        .rho = 7850, .beta = beta};
    int nodes[2], elems[1];
    bgr_model *m = bgr_model_create("b");
    int c = mech_beam_chain(m, 0, "beam", 1, p0, p1, up, &sec, NULL, NULL, NULL, nodes, elems);
    if (c < 0 || bgr_compile(m) != BG_OK) {
        tap_diag("element: %s", bgr_model_error(m)->message);
        bgr_model_free(&m);
        return NULL;
    }
    mech_beam_chain_set(m, nodes, 1, p0, p1);
    *elem = elems[0];
    return m;
}

/* the port flows of the element (velocity, angular velocity of each end, global) into y */
static int set_flows(bgr_model *m, double *y, const double *w)
{
    int bad = 0, found = 0;
    for (int i = 0; i < bgr_n(m); i++) {
        const char *nm = bgr_var_name(m, i), *leaf = strrchr(nm, '/');
        int end = strstr(nm, "beam/ba00/") ? 0 : strstr(nm, "beam/bb00/") ? 1 : -1;
        if (end < 0 || !leaf || leaf[1] != 'f') continue;
        int j = atoi(leaf + 2);
        if (j < 0 || j > 5) bad++;
        y[i] = w[6 * end + j];
        found++;
    }
    return bad == 0 && found == 12 ? 0 : -1;
}

static void test_beam(void)
{
    const double beta = 2e-3, E = 2.1e11, A = 1e-3, Iz = 5e-6, L = 3.0;
    int el;
    bgr_model *m = one_element(beta, &el);
    if (!m) {
        tap_ok(0, "one beam element compiles");
        return;
    }
    int n = bgr_n(m);
    double *y = malloc((size_t)n * sizeof *y);
    memcpy(y, bgr_y0(m), (size_t)n * sizeof *y);
    double w[12] = {0};
    w[6] = 0.7; /* the far end moves along the element: L' = 0.7 m/s */
    int ok = set_flows(m, y, w);
    double P = mech_beam_dissipation(m, el, y), want = beta * E * A / L * 0.49;
    tap_ok(ok == 0 && fabs(P - want) <= 1e-9 * want,
           "beam: stretching at L' = 0.7 m/s dissipates %.9g W = beta (E A / L0) L'^2 = %.9g W",
           P, want);
    memset(w, 0, sizeof w);
    w[10] = -0.3; /* the far end turns about e3 = -y at 0.3 rad/s */
    set_flows(m, y, w);
    P = mech_beam_dissipation(m, el, y);
    want = beta * 4 * E * Iz / L * 0.09;
    tap_ok(fabs(P - want) <= 1e-9 * want,
           "beam: one end turning at 0.3 rad/s about e3 dissipates %.9g W = beta (4 E I_z / L0) "
           "w^2 = %.9g W",
           P, want);
    /* rigid: translation (0.2, -1, 0.5) m/s and rotation W = (0.1, 0.4, -0.3) rad/s about the
     * first end: the far end moves at v + W x (L, 0, 0) */
    const double v[3] = {0.2, -1, 0.5}, Wr[3] = {0.1, 0.4, -0.3};
    for (int i = 0; i < 3; i++) {
        w[i] = v[i];
        w[3 + i] = w[9 + i] = Wr[i];
    }
    w[6] = v[0];
    w[7] = v[1] + Wr[2] * L;
    w[8] = v[2] - Wr[1] * L;
    set_flows(m, y, w);
    P = mech_beam_dissipation(m, el, y);
    tap_ok(fabs(P) <= 1e-12 * beta * E * A / L, "beam: a rigid motion dissipates nothing (%.2g W)",
           P);
    tap_ok(isnan(mech_beam_dissipation(m, el, NULL)), "no state: NaN");
    free(y);
    bgr_model_free(&m);
    m = one_element(0.0, &el);
    if (m) {
        y = malloc((size_t)bgr_n(m) * sizeof *y);
        memcpy(y, bgr_y0(m), (size_t)bgr_n(m) * sizeof *y);
        memset(w, 0, sizeof w);
        w[6] = 0.7;
        set_flows(m, y, w);
        tap_ok(mech_beam_dissipation(m, el, y) == 0, "beam without damping: 0");
        free(y);
        bgr_model_free(&m);
    }
}

int main(void)
{
    test_add_mass();
    test_axial();
    test_beam();
    return tap_done();
}
