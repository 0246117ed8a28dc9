/* The static solver and the modal analysis (bgr_analysis.h) on mechanical and hydraulic
 * component models, against closed forms, with convergence in the number of beam elements:
 *   - cantilever, tip load: P L^3 / (3 E I) (exact at the nodes for cubic elements, any n);
 *     own weight: q L^4 / (8 E I) (lumped loads: second order in 1/n); a large deflection under
 *     P L^2 / (E I) = 3 against the elastica (EI phi'' = -P cos phi, shooting), second order;
 *   - Euler-Bernoulli clamped-free bending frequencies beta_n L = 1.8751, 4.6941, 7.8548 in
 *     both planes (I_z and I_y), the first axial (pi/2) sqrt(E/rho)/L and torsional (pi/2)
 *     sqrt(G J/(rho I_p))/L frequencies, for 4 .. 32 elements (lumped masses: second order);
 *   - a pendulum (body on a revolute joint, velocity-level constraints): one elastic mode at
 *     sqrt(m g l / (J + m l^2)), the joint's drift modes kept apart as constraint modes;
 *   - a mass on a spring (point mass, axial spring with its own stretch state): the static
 *     stretch m g / k, the vertical sqrt(k/m) and the two lateral sqrt(g / L) modes of the
 *     spring pendulum;
 *   - a hydraulic volume closed by a motor holding a torque: the static pressure 2 pi T / D and
 *     the hydraulic natural frequency sqrt(beta D^2 / (4 pi^2 V J)), the volume's stiffness
 *     beta / V against the inertia. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "bgr_analysis.h"
#include "bgr_elements.h"
#include "hyd_motor.h"
#include "hyd_source.h"
#include "hyd_volume.h"
#include "mech_axial.h"
#include "mech_beam.h"
#include "mech_body.h"
#include "mech_parts.h"
#include "rot_inertia.h"
#include "tap.h"

static const double PI = 3.14159265358979323846;
static const mech_section steel = {
    .E = 2.1e11, .G = 8.1e10, .A = 1e-4, .Iy = 1.6e-9, .Iz = 8.33e-10, .J = 1.4e-9, .rho = 7850};

static double seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* A cantilever of n elements along x from the origin, clamped at node 0, with a 6D tip load
 * (0, 0, -P) and gravity g (NULL: none); compiled and set straight. */
static bgr_model *cantilever(int n, double L, double P, const double *g, int *nodes)
{
    const double p0[3] = {0, 0, 0}, p1[3] = {L, 0, 0}, up[3] = {0, 0, 1};
    int elems[64], extra[65];
    for (int k = 0; k <= n; k++)
        extra[k] = k == 0 || k == n;
    bgr_model *m = bgr_model_create("cant");
    mech_beam_chain(m, 0, "beam", n, p0, p1, up, &steel, g, extra, NULL, nodes, elems);
    int clamp = mech_support(m, 0, "clamp", 6);
    bgr_bond(m, 0, "b_clamp", 6, bgr_port_of(m, clamp, 0),
             mech_beam_chain_port(m, nodes, n, extra, 0, 0), NULL, NULL);
    double load[6] = {0, 0, -P, 0, 0, 0};
    int src = bgr_Se(m, 0, "tip_load", 6, load);
    bgr_bond(m, 0, "b_load", 6, bgr_port_of(m, src, 0),
             mech_beam_chain_port(m, nodes, n, extra, n, 0), NULL, NULL);
    if (bgr_compile(m) != BG_OK) {
        tap_diag("cantilever: %s", bgr_model_error(m)->message);
        bgr_model_free(&m);
        return NULL;
    }
    mech_beam_chain_set(m, nodes, n, p0, p1);
    return m;
}

/* Static tip position of a cantilever; NaN on failure. */
static int cantilever_tip(int n, double L, double P, const double *g, double *tip,
                          dae_static_result *r)
{
    int nodes[65];
    bgr_model *m = cantilever(n, L, P, g, nodes);
    if (!m) return -1;
    bg_error err = {0};
    int st = bgr_static(m, NULL, 0.0, r, &err);
    if (st != BG_OK) tap_diag("cantilever n = %d: %s", n, err.message);
    memcpy(tip, bgr_y0(m) + mech_body_var(m, nodes[n], 'x'), 3 * sizeof *tip);
    bgr_model_free(&m);
    return st;
}

/* The elastica of a cantilever under a dead tip load: phi'' = -a cos phi, phi(0) = 0,
 * phi'(1) = 0 (s in units of L, a = P L^2 / E I); the tip (x, z) / L by shooting on phi'(0). */
static void elastica(double a, double *xt, double *zt)
{
    const int N = 20000;
    double lo = 0, hi = a, k0 = 0;
    for (int it = 0; it < 80; it++) {
        k0 = 0.5 * (lo + hi);
        double ph = 0, k = k0, h = 1.0 / N, x = 0, z = 0;
        for (int i = 0; i < N; i++) { /* RK4 on (phi, phi', x, z) */
            double p1 = k, k1 = -a * cos(ph), x1 = cos(ph), z1 = -sin(ph);
            double p2 = k + 0.5 * h * k1, k2 = -a * cos(ph + 0.5 * h * p1), x2 = cos(ph + 0.5 * h * p1),
                   z2 = -sin(ph + 0.5 * h * p1);
            double p3 = k + 0.5 * h * k2, k3 = -a * cos(ph + 0.5 * h * p2), x3 = cos(ph + 0.5 * h * p2),
                   z3 = -sin(ph + 0.5 * h * p2);
            double p4 = k + h * k3, k4 = -a * cos(ph + h * p3), x4 = cos(ph + h * p3),
                   z4 = -sin(ph + h * p3);
            ph += h * (p1 + 2 * p2 + 2 * p3 + p4) / 6;
            k += h * (k1 + 2 * k2 + 2 * k3 + k4) / 6;
            x += h * (x1 + 2 * x2 + 2 * x3 + x4) / 6;
            z += h * (z1 + 2 * z2 + 2 * z3 + z4) / 6;
        }
        *xt = x, *zt = z;
        if (k > 0) /* curvature left at the tip: too much at the root */
            hi = k0;
        else
            lo = k0;
    }
}

static void test_cantilever_statics(void)
{
    const double L = 1.0, EI = steel.E * steel.Iz;
    /* a small tip load: exact at the nodes for any n */
    double P = 3 * EI * 1e-4 / (L * L * L), want = P * L * L * L / (3 * EI), worst = 0, tip[3];
    int ok = 1;
    dae_static_result r;
    for (int n = 1; n <= 8; n *= 2) {
        ok &= cantilever_tip(n, L, P, NULL, tip, &r) == BG_OK;
        worst = fmax(worst, fabs(-tip[2] - want) / want);
    }
    tap_ok(ok && worst < 1e-6,
           "cantilever, tip load (deflection 1e-4 L): P L^3/(3 E I) = %.6e m within %.2g for 1, "
           "2, 4, 8 elements",
           want, worst);
    /* own weight: q L^4 / (8 E I), lumped nodal loads */
    const double g[3] = {0, 0, -9.81};
    double q = steel.rho * steel.A * 9.81, wq = q * L * L * L * L / (8 * EI), e[6];
    char line[256];
    int len = 0;
    ok = 1;
    for (int i = 0, n = 2; n <= 32; n *= 2, i++) {
        ok &= cantilever_tip(n, L, 0, g, tip, &r) == BG_OK;
        e[i] = fabs(-tip[2] - wq) / wq;
        len += snprintf(line + len, sizeof line - (size_t)len, " n=%d: %.2e", n, e[i]);
    }
    tap_ok(ok && e[4] < 2e-3 && e[3] / e[4] > 3.0 && e[2] / e[3] > 3.0,
           "cantilever, own weight: q L^4/(8 E I) = %.6e m, relative errors%s (second order: "
           "ratios %.2f, %.2f)",
           wq, line, e[2] / e[3], e[3] / e[4]);
    /* a large deflection: P L^2 / (E I) = 3 against the elastica */
    double a = 3.0, xt, zt;
    elastica(a, &xt, &zt);
    P = a * EI / (L * L);
    len = 0;
    ok = 1;
    double ee[4], t0 = seconds();
    long steps = 0;
    for (int i = 0, n = 4; n <= 32; n *= 2, i++) {
        ok &= cantilever_tip(n, L, P, NULL, tip, &r) == BG_OK;
        steps += r.steps;
        ee[i] = hypot(tip[0] - xt * L, tip[2] - zt * L) / L;
        len += snprintf(line + len, sizeof line - (size_t)len, " n=%d: %.2e", n, ee[i]);
    }
    tap_ok(ok && ee[3] < 3e-4 && ee[2] / ee[3] > 3.0,
           "cantilever, large deflection P L^2/(E I) = 3: elastica tip (%.5f, %.5f) L; tip "
           "errors / L%s (ratio %.2f; %ld continuation steps, %.2f s for the four)",
           xt, zt, line, ee[2] / ee[3], steps, seconds() - t0);
}

/* ---- frequencies of a clamped-free beam ---- */
static int cmp_dbl(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static void test_beam_frequencies(void)
{
    const double L = 1.0;
    const double beta[3] = {1.8751, 4.6941, 7.8548};
    const double I2[2] = {steel.Iz, steel.Iy};
    double err[4][8]; /* per n: bending z 1..3, bending y 1..3, axial, torsion */
    int ok = 1, ns[4] = {4, 8, 16, 32};
    double t_modes = 0;
    for (int in = 0; in < 4; in++) {
        int n = ns[in], nodes[65];
        bgr_model *m = cantilever(n, L, 0, NULL, nodes);
        if (!m) {
            ok = 0;
            continue;
        }
        dae_modes *M = NULL;
        bg_error e = {0};
        double t0 = seconds();
        int st = bgr_modes(m, 0.0, NULL, NULL, NULL, &M, &e);
        t_modes += seconds() - t0;
        if (st != BG_OK) {
            tap_diag("modes, n = %d: %s", n, e.message);
            ok = 0;
            bgr_model_free(&m);
            continue;
        }
        /* classify each elastic mode by its largest motion: v0 axial, v1 bending y (I_y), v2
         * bending z (I_z), w0 torsion */
        double f[4][64];
        int nf[4] = {0}, N = bgr_n(m);
        double *re = malloc((size_t)N * sizeof *re), *im = malloc((size_t)N * sizeof *im);
        for (int k = 0; k < dae_modes_count(M); k++) {
            const dae_mode *md = dae_modes_get(M, k);
            if (md->kind != DAE_MODE_ELASTIC) continue;
            dae_modes_vector(M, k, re, im);
            double s[4] = {0};
            for (int j = 1; j <= n; j++) {
                int v = mech_body_var(m, nodes[j], 'v'), w = mech_body_var(m, nodes[j], 'w');
                for (int c = 0; c < 3; c++)
                    s[c] += re[v + c] * re[v + c] + im[v + c] * im[v + c];
                s[3] += (re[w] * re[w] + im[w] * im[w]) * (L / n) * (L / n);
            }
            int b = 0;
            for (int c = 1; c < 4; c++)
                if (s[c] > s[b]) b = c;
            int cls = b == 2 ? 0 : b == 1 ? 1 : b == 0 ? 2 : 3;
            if (nf[cls] < 64) f[cls][nf[cls]++] = md->freq_hz * 2 * PI;
        }
        for (int c = 0; c < 4; c++)
            qsort(f[c], (size_t)nf[c], sizeof(double), cmp_dbl);
        for (int a = 0; a < 2; a++)
            for (int k = 0; k < 3; k++) {
                double w = beta[k] * beta[k] *
                           sqrt(steel.E * I2[a] / (steel.rho * steel.A * L * L * L * L));
                err[in][3 * a + k] = nf[a] > k ? fabs(f[a][k] - w) / w : INFINITY;
            }
        double wa = 0.5 * PI * sqrt(steel.E / steel.rho) / L;
        double wt = 0.5 * PI * sqrt(steel.G * steel.J / (steel.rho * (steel.Iy + steel.Iz))) / L;
        err[in][6] = nf[2] ? fabs(f[2][0] - wa) / wa : INFINITY;
        err[in][7] = nf[3] ? fabs(f[3][0] - wt) / wt : INFINITY;
        int ne, nr, nc;
        dae_modes_info(M, &ne, &nr, &nc, NULL, NULL, NULL);
        tap_diag("beam modes, %2d elements: %d elastic (6 per node: %d), %d rigid, %d constraint; "
                 "errors: bending z %.1e %.1e %.1e, bending y %.1e %.1e %.1e, axial %.1e, "
                 "torsion %.1e",
                 n, ne, 6 * n, nr, nc, err[in][0], err[in][1], err[in][2], err[in][3], err[in][4],
                 err[in][5], err[in][6], err[in][7]);
        ok &= ne == 6 * n && nr == 0;
        free(re);
        free(im);
        dae_modes_free(&M);
        bgr_model_free(&m);
    }
    const char *what[8] = {"bending 1 (I_z)", "bending 2 (I_z)", "bending 3 (I_z)",
                           "bending 1 (I_y)", "bending 2 (I_y)", "bending 3 (I_y)",
                           "axial 1",          "torsion 1"};
    for (int j = 0; j < 8; j++) {
        /* lumped masses: about 0.45 (beta_n L / n)^2 / 12 .. for bending */
        double lim = j < 6 ? (j % 3 == 0 ? 1e-3 : j % 3 == 1 ? 3e-3 : 5e-3) : 2e-4;
        tap_ok(ok && err[3][j] < lim && err[2][j] / err[3][j] > 3.0,
               "clamped-free %s: relative error %.1e, %.1e, %.1e, %.1e for 4, 8, 16, 32 "
               "elements (ratio %.2f: second order)",
               what[j], err[0][j], err[1][j], err[2][j], err[3][j], err[2][j] / err[3][j]);
    }
    tap_diag("beam modes: %.3f s for the four dense analyses", t_modes);
}

/* ---- a pendulum: a body on a revolute joint ---- */
static void test_pendulum(void)
{
    const double mass = 5.0, l = 0.8, J[9] = {0.2, 0, 0, 0, 0.3, 0, 0, 0, 0.1};
    const double g[3] = {0, 0, -9.81}, axis[3] = {0, 1, 0}, r[3] = {0, 0, l};
    bgr_model *m = bgr_model_create("pend");
    int gnd = mech_support(m, 0, "ground", 6), hinge = mech_revolute(m, 0, "hinge", -1, axis, 0);
    int dims[1] = {6}, bob = mech_body(m, 0, "bob", mass, J, g, 1, r, dims);
    bgr_bond(m, 0, "b_ground", 6, bgr_port_of(m, gnd, 0), bgr_port_of(m, hinge, 0), NULL, NULL);
    bgr_bond(m, 0, "b_bob", 6, bgr_port_of(m, hinge, 1), bgr_port_of(m, bob, 0), NULL, NULL);
    if (bgr_compile(m) != BG_OK) {
        tap_ok(0, "pendulum: compile (%s)", bgr_model_error(m)->message);
        bgr_model_free(&m);
        return;
    }
    double x0[3] = {0, 0, -l};
    mech_body_set(m, bob, x0, NULL, NULL, NULL);
    bg_error err = {0};
    dae_static_result res;
    int st = bgr_static(m, NULL, 0.0, &res, &err);
    int vf = bgr_find_var(m, "pend/b_bob/e2");
    tap_ok(st == BG_OK && vf >= 0 && fabs(fabs(bgr_y0(m)[vf]) - mass * 9.81) < 1e-6,
           "pendulum: at rest hanging, the joint carries the weight %.6g N (%s)",
           vf >= 0 ? fabs(bgr_y0(m)[vf]) : NAN, st ? err.message : "ok");
    dae_modes *M = NULL;
    st = bgr_modes(m, 0.0, NULL, NULL, NULL, &M, &err);
    int ne = -1, nr = -1, nc = -1;
    dae_modes_info(M, &ne, &nr, &nc, NULL, NULL, NULL);
    const dae_mode *m0 = dae_modes_get(M, 0);
    double w = sqrt(mass * 9.81 * l / (J[4] + mass * l * l));
    char desc[256] = "";
    if (m0) dae_modes_describe(M, 0, 2, 3, 3, desc, sizeof desc);
    tap_ok(st == BG_OK && ne == 1 && nr == 0 && m0 && fabs(m0->freq_hz * 2 * PI - w) < 1e-9 * w,
           "pendulum: one elastic mode at sqrt(m g l/(J + m l^2)) = %.9g rad/s (%.9g; %s); %d "
           "constraint modes (the joint: index-2 pairs at infinity, the velocity-level drift at "
           "zero), no rigid mode",
           w, m0 ? m0->freq_hz * 2 * PI : NAN, desc, nc);
    dae_modes_free(&M);
    bgr_model_free(&m);
}

/* ---- a mass on a spring ---- */
static void test_spring_mass(void)
{
    const double k = 2000, mass = 3, L0 = 1.2, gz = 9.81, g[3] = {0, 0, -gz};
    bgr_model *m = bgr_model_create("sm");
    int sup = mech_support(m, 0, "anchor", 3), spr = mech_spring(m, 0, "spring", k, 0, L0);
    int pm = mech_point_mass(m, 0, "mass", mass, g);
    bgr_bond(m, 0, "b_anchor", 3, bgr_port_of(m, sup, 0), bgr_port_of(m, spr, 0), NULL, NULL);
    bgr_bond(m, 0, "b_mass", 3, bgr_port_of(m, spr, 1), bgr_port_of(m, pm, 0), NULL, NULL);
    if (bgr_compile(m) != BG_OK) {
        tap_ok(0, "spring-mass: compile (%s)", bgr_model_error(m)->message);
        bgr_model_free(&m);
        return;
    }
    const double a[3] = {0, 0, 0}, b[3] = {0, 0, -L0};
    mech_axial_set(m, spr, a, b);
    mech_point_mass_set(m, pm, b, NULL);
    bg_error err = {0};
    int st = bgr_static(m, NULL, 0.0, NULL, &err);
    int vx = bgr_ref_var(m, (bgr_ref){BGR_STATE, pm, 0});
    double Ls = L0 + mass * gz / k, z = bgr_y0(m)[vx + 2];
    tap_ok(st == BG_OK && fabs(z + Ls) < 1e-10,
           "mass on a spring: hangs at z = %.12g (-(L0 + m g/k) = %.12g)", z, -Ls);
    dae_modes *M = NULL;
    st = bgr_modes(m, 0.0, NULL, NULL, NULL, &M, &err);
    int ne = -1, nr = -1, nc = -1;
    dae_modes_info(M, &ne, &nr, &nc, NULL, NULL, NULL);
    double wl = sqrt(gz / Ls), wv = sqrt(k / mass), f[3] = {NAN, NAN, NAN};
    for (int i = 0; i < 3 && i < dae_modes_count(M); i++)
        f[i] = dae_modes_get(M, i)->freq_hz * 2 * PI;
    tap_ok(st == BG_OK && ne == 3 && fabs(f[0] - wl) < 1e-9 * wl && fabs(f[1] - wl) < 1e-9 * wl &&
               fabs(f[2] - wv) < 1e-9 * wv && nc >= 3,
           "mass on a spring: lateral %.9g, %.9g rad/s (sqrt(g/L) = %.9g), vertical %.9g "
           "(sqrt(k/m) = %.9g); %d constraint modes (the stretch state against the mass)",
           f[0], f[1], wl, f[2], wv, nc);
    dae_modes_free(&M);
    bgr_model_free(&m);
}

/* ---- a hydraulic volume closed by a motor holding a torque ---- */
static void test_hydraulic(void)
{
    const double Vol = 1e-3, beta = 1.4e9, D = 1e-4, J = 1.0, T = 50.0;
    bgr_model *m = bgr_model_create("hyd");
    int vol = hyd_volume(m, 0, "line", 1, Vol, beta), mot = hyd_motor(m, 0, "motor", D, 0, 0);
    int tank = hyd_tank(m, 0, "tank", 0.0), in = rot_inertia(m, 0, "load", J);
    int shaft = bgr_one(m, 0, "shaft", 3, 1);
    double load = -T;
    int src = bgr_Se(m, 0, "torque", 1, &load);
    bgr_bond(m, 0, "b_in", 1, bgr_port_of(m, vol, 0), bgr_port_of(m, mot, 0), NULL, NULL);
    bgr_bond(m, 0, "b_ret", 1, bgr_port_of(m, mot, 1), bgr_port_of(m, tank, 0), NULL, NULL);
    bgr_bond(m, 0, "b_shaft", 1, bgr_port_of(m, mot, 2), bgr_port_of(m, shaft, 0), NULL, NULL);
    bgr_bond(m, 0, "b_inertia", 1, bgr_port_of(m, shaft, 1), bgr_port_of(m, in, 0), NULL, NULL);
    bgr_bond(m, 0, "b_torque", 1, bgr_port_of(m, src, 0), bgr_port_of(m, shaft, 2), NULL, NULL);
    if (bgr_compile(m) != BG_OK) {
        tap_ok(0, "hydraulic: compile (%s)", bgr_model_error(m)->message);
        bgr_model_free(&m);
        return;
    }
    bg_error err = {0};
    int st = bgr_static(m, NULL, 0.0, NULL, &err);
    int vp = bgr_find_var(m, "hyd/line/p");
    double p = vp >= 0 ? bgr_y0(m)[vp] : NAN, want = 2 * PI * T / D;
    tap_ok(st == BG_OK && fabs(p - want) < 1e-9 * want,
           "hydraulic volume: the static pressure holding %g N m is 2 pi T / D = %.9g Pa (%.9g; "
           "%s)",
           T, want, p, st ? err.message : "ok");
    dae_modes *M = NULL;
    st = bgr_modes(m, 0.0, NULL, NULL, NULL, &M, &err);
    int ne = -1;
    dae_modes_info(M, &ne, NULL, NULL, NULL, NULL, NULL);
    double w = sqrt(beta / Vol * (D / (2 * PI)) * (D / (2 * PI)) / J);
    const dae_mode *m0 = dae_modes_get(M, 0);
    char desc[256] = "";
    if (m0) dae_modes_describe(M, 0, 2, 3, 2, desc, sizeof desc);
    tap_ok(st == BG_OK && ne == 1 && m0 && fabs(m0->freq_hz * 2 * PI - w) < 1e-9 * w,
           "hydraulic volume: one elastic mode at sqrt((beta/V) (D/2pi)^2 / J) = %.9g rad/s "
           "(%.9g; %s)",
           w, m0 ? m0->freq_hz * 2 * PI : NAN, desc);
    dae_modes_free(&M);
    bgr_model_free(&m);
}

int main(void)
{
    test_cantilever_statics();
    test_beam_frequencies();
    test_pendulum();
    test_spring_mass();
    test_hydraulic();
    return tap_done();
}
