/* The consistent co-rotational beam element (mech_beam.h, section.element) against independent
 * references, with the lumped element alongside:
 *   - clamped-free bending frequencies in both planes against the Euler-Bernoulli closed form
 *     (beta_n L the roots of cos b cosh b = -1, found here by bisection), corrected to first
 *     order for the section's rotary inertia (Rayleigh quotient of the closed-form mode shape),
 *     for 2 .. 32 elements: the errors, and the convergence order from the halvings;
 *   - one element's kinetic energy at arbitrary node velocities against its mass matrix (the
 *     bending mass template of mech_beam.h);
 *   - energy: a free chain spinning end over end while it bends, total energy (node bodies,
 *     elements' strain and kinetic energy) conserved over the motion: the centrifugal and
 *     Coriolis terms of the inertia loads, which the linearised frequencies do not see;
 *   - a cantilever vibrating freely in its second mode: the period of the integrated motion
 *     against the closed form, and its energy;
 *   - the element's Jacobian against central differences at a state at rest under gravity;
 *   - the distributed weight: a cantilever's sag under its own weight q L^4 / (8 E I) (the lumped
 *     node weights: second order; the consistent loads are exact at the nodes);
 *   - the elastica, tip loads P L^2 / (E I) = 1, 3, 5, 10, against the extensible elastica by
 *     shooting, 4 .. 32 elements;
 *   - the model file's key element: lumped | consistent. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "beam_testlib.h"
#include "bgr_analysis.h"
#include "bgr_elements.h"
#include "mech_beam.h"
#include "mech_body.h"
#include "mdl_model.h"
#include "mech_parts.h"
#include "tap.h"

static const double PI = 3.14159265358979323846;
/* slender: r^2 = I/A = 1e-8, 2e-8 m^2 on L = 1 m (the rotary inertia moves the third frequency
 * by about 1e-6, which the reference includes) */
static const mech_section slender = {
    .E = 2.1e11, .G = 8.1e10, .A = 1e-4, .Iy = 2e-12, .Iz = 1e-12, .J = 1.5e-12, .rho = 7850};

/* The first three bending frequencies (rad/s) in each plane (0: I_z, 1: I_y; a mode's plane is
 * that of its largest nodal motion) of an n-element cantilever; 0 on failure. */
static int bending_frequencies(int n, int mass, double f[2][3])
{
    int nodes[65], elems[64];
    bgr_model *m = bt_cantilever(&slender, mass, n, 1.0, NULL, 0, 0, nodes, elems);
    if (!m) return 0;
    dae_modes *M = NULL;
    bg_error e = {0};
    int st = bgr_modes(m, 0.0, NULL, NULL, NULL, &M, &e);
    if (st != BG_OK) {
        tap_diag("modes, n = %d: %s", n, e.message);
        bgr_model_free(&m);
        return 0;
    }
    int N = bgr_n(m), nf[2] = {0, 0};
    double *re = malloc((size_t)N * sizeof *re), *im = malloc((size_t)N * sizeof *im);
    for (int k = 0; k < dae_modes_count(M); k++) { /* ascending frequencies */
        const dae_mode *md = dae_modes_get(M, k);
        if (md->kind != DAE_MODE_ELASTIC) continue;
        dae_modes_vector(M, k, re, im);
        double s[3] = {0, 0, 0};
        for (int j = 1; j <= n; j++) {
            int v = mech_body_var(m, nodes[j], 'v');
            for (int c = 0; c < 3; c++)
                s[c] += re[v + c] * re[v + c] + im[v + c] * im[v + c];
        }
        /* local frame e1 = x, e2 = up = z, e3 = -y: bending with I_z (about e3) moves the
         * nodes along z, with I_y along y; axial modes along x are left out */
        int cls = s[2] > s[0] && s[2] > s[1] ? 0 : s[1] > s[0] && s[1] > s[2] ? 1 : -1;
        if (cls >= 0 && nf[cls] < 3) f[cls][nf[cls]++] = md->freq_hz * 2 * PI;
    }
    free(re);
    free(im);
    dae_modes_free(&M);
    bgr_model_free(&m);
    return nf[0] == 3 && nf[1] == 3;
}

static void test_frequencies(void)
{
    const int ns[5] = {2, 4, 8, 16, 32};
    const double I2[2] = {slender.Iz, slender.Iy};
    double want[2][3];
    for (int a = 0; a < 2; a++)
        for (int k = 0; k < 3; k++) {
            double b = bt_clamped_free_root(k);
            double w = b * b * sqrt(slender.E * I2[a] / (slender.rho * slender.A));
            /* Rayleigh quotient with the rotary inertia rho I phi'^2: first order in I/A */
            want[a][k] = w * (1 - 0.5 * I2[a] / slender.A * bt_slope_ratio(b));
        }
    tap_ok(fabs(bt_clamped_free_root(0) - 1.8751) < 1e-4 &&
               fabs(bt_clamped_free_root(1) - 4.6941) < 1e-4 &&
               fabs(bt_clamped_free_root(2) - 7.8548) < 1e-4,
           "clamped-free roots %.10f %.10f %.10f (1.8751, 4.6941, 7.8548)", bt_clamped_free_root(0),
           bt_clamped_free_root(1), bt_clamped_free_root(2));
    double err[2][5][6]; /* [mass][n][plane * 3 + mode] */
    int ok[2] = {1, 1};
    for (int mass = 0; mass < 2; mass++)
        for (int i = 0; i < 5; i++) {
            double f[2][3];
            if (!bending_frequencies(ns[i], mass, f)) {
                ok[mass] = 0;
                for (int j = 0; j < 6; j++)
                    err[mass][i][j] = INFINITY;
                continue;
            }
            for (int a = 0; a < 2; a++)
                for (int k = 0; k < 3; k++)
                    err[mass][i][3 * a + k] = fabs(f[a][k] - want[a][k]) / want[a][k];
        }
    const char *name[2] = {"lumped", "consistent"};
    for (int mass = 0; mass < 2; mass++)
        for (int i = 0; i < 5; i++)
            tap_diag("%-10s %2d elements: bending z %.2e %.2e %.2e, bending y %.2e %.2e %.2e",
                     name[mass], ns[i], err[mass][i][0], err[mass][i][1], err[mass][i][2],
                     err[mass][i][3], err[mass][i][4], err[mass][i][5]);
    /* orders: modes 2 and 3 from 8 to 16 elements, mode 1 from 4 to 8 (the consistent element's
     * errors reach the eigensolver's rounding, about 1e-12, beyond) */
    double order[2][6];
    for (int mass = 0; mass < 2; mass++)
        for (int j = 0; j < 6; j++)
            order[mass][j] = j % 3 ? log2(err[mass][2][j] / err[mass][3][j])
                                   : log2(err[mass][1][j] / err[mass][2][j]);
    tap_diag("orders (mode 1: 4 -> 8 elements, modes 2, 3: 8 -> 16): lumped %.2f %.2f %.2f / %.2f "
             "%.2f %.2f, consistent %.2f %.2f %.2f / %.2f %.2f %.2f",
             order[0][0], order[0][1], order[0][2], order[0][3], order[0][4], order[0][5],
             order[1][0], order[1][1], order[1][2], order[1][3], order[1][4], order[1][5]);
    double w8 = 0, w16 = 0, omin = INFINITY;
    for (int j = 0; j < 6; j++) {
        w8 = fmax(w8, err[1][2][j]);
        w16 = fmax(w16, err[1][3][j]);
        omin = fmin(omin, order[1][j]);
    }
    /* the cubic element with its consistent mass alone: 2.1e-6, 8.0e-5, 6.1e-4 at 8 elements,
     * fourth order ((beta L / n)^4 / 1440); with the bending correction of mech_beam.h the
     * dispersion error is of eighth order and the cantilever's end term cancels */
    tap_ok(ok[1] && w8 < 1e-4 && w16 < 1e-7,
           "consistent element: the first three bending frequencies of both planes within %.2e of "
           "the closed form at 8 elements (target 1e-4), within %.2e at 16",
           w8, w16);
    tap_ok(ok[1] && omin > 7.5,
           "consistent element: eighth order on the cantilever (smallest measured order %.2f)",
           omin);
    tap_ok(ok[0] && err[0][2][0] > 10 * err[1][2][0] && err[0][2][2] > 10 * err[1][2][2],
           "lumped element, 8 elements: errors %.2e and %.2e on modes 1 and 3, ten times the "
           "consistent ones at least",
           err[0][2][0], err[0][2][2]);
}

/* ---- the element's kinetic energy against its mass matrix ----
 * One free element along x (local e1 = x, e2 = z, e3 = -y) at rest in the straight state with
 * arbitrary node velocities: the kinetic energy it adds to its node bodies must be
 * u'^T (M - M_L) u' / 2 in each bending plane, u = (w_a, L s_a, w_b, L s_b) (w the transverse
 * displacement, s = dw/dx the slope), with the mass template of mech_beam.h,
 * M = rho A L / 17640 [6606 993 2214 -477; 993 262 477 -109; 2214 477 6606 -993;
 * -477 -109 -993 262], and M_L = rho A L diag(1/2, 0, 1/2, 0) the node bodies' share; along
 * the axis rho A L ([1/3 1/6; 1/6 1/3] - diag(1/2, 1/2)). The section's rotary inertia is
 * 1e-8 of the rest here (r^2 / L^2 = 1e-8) and left out. The cubic element's consistent mass
 * (rho A L / 420 [156 22 54 -13; ...]) gives another energy. */
static void test_kinetic(void)
{
    const double L = 1.0, up[3] = {0, 0, 1}, p0[3] = {0, 0, 0}, p1[3] = {L, 0, 0};
    mech_section sec = slender;
    sec.element = MECH_BEAM_CONSISTENT;
    int nodes[2], elems[1];
    bgr_model *m = bgr_model_create("one");
    mech_beam_chain(m, 0, "beam", 1, p0, p1, up, &sec, NULL, NULL, NULL, nodes, elems);
    if (bgr_compile(m) != BG_OK) {
        tap_ok(0, "one element: compile (%s)", bgr_model_error(m)->message);
        bgr_model_free(&m);
        return;
    }
    /* velocities (v, w) of the nodes: translations along x, y, z and rotations about y, z */
    const double va[3] = {0.3, -0.7, 1.1}, wa[3] = {0, 0.9, -1.3}, vb[3] = {-0.2, 0.4, -0.5},
                 wb[3] = {0, -0.6, 0.8};
    const double xa[3] = {0, 0, 0}, xb[3] = {L, 0, 0};
    mech_body_set(m, nodes[0], xa, va, wa, NULL);
    mech_body_set(m, nodes[1], xb, vb, wb, NULL);
    const double Mt[4][4] = {{6606, 993, 2214, -477},
                             {993, 262, 477, -109},
                             {2214, 477, 6606, -993},
                             {-477, -109, -993, 262}};
    double mA = sec.rho * sec.A * L, want = 0;
    /* plane z: w = z, slope rate s' = -omega_y; plane y: w = y, s' = omega_z */
    const double u[2][4] = {{va[2], -L * wa[1], vb[2], -L * wb[1]},
                            {va[1], L * wa[2], vb[1], L * wb[2]}};
    for (int pl = 0; pl < 2; pl++)
        for (int i = 0; i < 4; i++)
            for (int j = 0; j < 4; j++) {
                double Mij = mA * Mt[i][j] / 17640 - (i == j && i % 2 == 0 ? mA / 2 : 0);
                want += 0.5 * u[pl][i] * Mij * u[pl][j];
            }
    want += 0.5 * mA * ((1.0 / 3 - 0.5) * (va[0] * va[0] + vb[0] * vb[0]) + va[0] * vb[0] / 3);
    double got = mech_beam_kinetic(m, elems[0], bgr_y0(m));
    tap_ok(fabs(got - want) < 1e-7 * mA,
           "one element: the kinetic energy it adds, %.10e J, is that of its mass matrix %.10e J "
           "(difference %.1e of rho A L)",
           got, want, fabs(got - want) / mA);
    bgr_model_free(&m);
}

static void test_energy(void)
{
    const int n = 4;
    const double L = 1.0, W = 20.0, up[3] = {0, 0, 1}, p0[3] = {0, 0, 0}, p1[3] = {L, 0, 0};
    int nodes[8], elems[8];
    /* a stocky polymer rod: first free-free bending frequency 37 rad/s, axial 3 100 */
    const mech_section sec = {.E = 2.1e9,
                              .G = 8.1e8,
                              .A = 1e-4,
                              .Iy = 1e-9,
                              .Iz = 1e-9,
                              .J = 1.5e-9,
                              .rho = 1000,
                              .element = MECH_BEAM_CONSISTENT};
    bgr_model *m = bgr_model_create("free");
    mech_beam_chain(m, 0, "beam", n, p0, p1, up, &sec, NULL, NULL, NULL, nodes, elems);
    if (bgr_compile(m) != BG_OK) {
        tap_ok(0, "free chain: compile (%s)", bgr_model_error(m)->message);
        bgr_model_free(&m);
        return;
    }
    for (int k = 0; k <= n; k++) {
        double x0 = L * k / n, s = x0 / L - 0.5;
        /* bending: z velocity 2 (6 s^2 - 1/2) m/s, zero mean over the uniform mass */
        double x[3] = {x0, 0, 0}, v[3] = {0, W * s * L, 2.0 * (6 * s * s - 0.5)},
               w[3] = {0, -0.6 * s, W};
        mech_body_set(m, nodes[k], x, v, w, NULL);
    }
    dae_problem p;
    bgr_dae_problem(m, &p);
    dae_options o;
    dae_options_default(&o);
    o.rtol = 1e-6;
    o.atol = 1e-9;
    o.exclude_alg = 1;
    bg_error err = {0};
    dae_solver *s = dae_create(&p, &o, &err);
    int N = bgr_n(m), r = s ? dae_init(s, 0, bgr_y0(m), bgr_yp0(m)) : -1;
    if (r == 0) r = dae_consistent_init(s);
    double *y = malloc((size_t)N * sizeof *y), *yp = malloc((size_t)N * sizeof *yp), t = 0;
    memcpy(y, bgr_y0(m), (size_t)N * sizeof *y);
    double E0 = bt_total_energy(m, nodes, elems, n, y), drift = 0, Tel = 0, Wmax = 0;
    double T = 2 * 2 * PI / W; /* two revolutions */
    for (int j = 1; j <= 40 && r == 0; j++) {
        r = dae_solve_to(s, T * j / 40, &t, y, yp);
        double E = bt_total_energy(m, nodes, elems, n, y);
        drift = fmax(drift, fabs(E - E0) / E0);
        for (int k = 0; k < n; k++) {
            Tel = fmax(Tel, fabs(mech_beam_kinetic(m, elems[k], y)));
            Wmax = fmax(Wmax, mech_beam_energy(m, elems[k], y));
        }
    }
    if (r < 0) tap_diag("free chain: %s", s ? dae_get_error(s)->message : err.message);
    const dae_stats *ds = s ? dae_get_stats(s) : NULL;
    if (ds)
        tap_diag("free chain: %ld steps, %ld Newton iterations, %ld Jacobians", ds->steps,
                 ds->newton_iters, ds->jac_evals);
    /* at rtol 1e-6: 7e-6 (1e-8: 4e-8); without the rate term G' u' of the accelerations the
     * energy drifts by 2.4e-4 */
    tap_ok(
        r == 0 && drift < 3e-5,
        "free chain (consistent element) spinning at %g rad/s while it bends: total energy %.6e J "
        "kept within %.1e over two revolutions (elements' kinetic share up to %.2e J, strain "
        "up to %.2e J)",
        W, E0, drift, Tel, Wmax);
    dae_free(&s);
    free(y);
    free(yp);
    bgr_model_free(&m);
}

/* ---- a cantilever vibrating freely in its second bending mode ----
 * 4 consistent elements of a polymer rod, started straight with the node velocities of the
 * model's own second mode in the plane of I_z (from bgr_modes, so that the motion is that mode
 * alone) at a tip amplitude of 1e-4 L (at 1e-3 L the nonlinear terms shift the period by 7e-6).
 * Integrated over six periods at rtol 1e-9: the period from the tip's upward zero crossings
 * against the closed form's (with the rotary inertia, as above), and the total energy (node
 * bodies, elements' strain and kinetic energy) kept. The linearised model is 5.3e-6 off with
 * the mass template; the cubic element's consistent mass alone put it 1.2e-3 off. */
static void test_vibration(void)
{
    const int n = 4;
    int nodes[8], elems[8];
    /* a polymer rod, r^2 / L^2 = 1e-5: its axial frequency 23 times the bending one */
    const mech_section rod = {
        .E = 2.1e9, .G = 8.1e8, .A = 1e-4, .Iy = 2e-9, .Iz = 1e-9, .J = 1.5e-9, .rho = 1000};
    bgr_model *m = bt_cantilever(&rod, MECH_BEAM_CONSISTENT, n, 1.0, NULL, 0, 0, nodes, elems);
    double want = bt_clamped_free_root(1) * bt_clamped_free_root(1) *
                  sqrt(rod.E * rod.Iz / (rod.rho * rod.A));
    want *= 1 - 0.5 * rod.Iz / rod.A * bt_slope_ratio(bt_clamped_free_root(1));
    /* the second z-plane mode's velocities turned real (the phase of the tip's) */
    char why[256] = "model";
    double wmode =
        m ? bt_release_in_mode(m, nodes, n, 1.0, 2, 1e-4 * want, NULL, 0, why, sizeof why) : NAN;
    if (isnan(wmode)) {
        tap_ok(0, "vibrating cantilever: modes (%s)", why);
        bgr_model_free(&m);
        return;
    }
    double T = 2 * PI / want;
    bt_run_out o;
    int r = bt_run(m, nodes, elems, n, 1e-9, 6 * T, 6 * 200, mech_body_var(m, nodes[n], 'x') + 2,
                   NULL, 0, "vibrating cantilever", &o);
    double err = fabs(o.period - T) / T;
    tap_ok(r == 0 && o.crossings >= 5 && err < 1e-4 && o.drift < 1e-6,
           "cantilever of 4 consistent elements vibrating in its second mode: period %.9f s from "
           "%d crossings, the closed form's %.9f s (error %.1e; target 1e-4), energy kept within "
           "%.1e (the linearised model's: %.1e)",
           o.period, o.crossings, T, err, o.drift, fabs(wmode - want) / want);
    bgr_model_free(&m);
}

/* ---- at rest under gravity: the sag under the distributed weight, and the Jacobian ----
 * The cantilever's tip deflection under its own weight q L^4 / (8 E I): the consistent loads
 * (with the end moments q l^2 / 12 the lumped node weights lack) make the cubic elements exact
 * at the nodes; the lumped weights converge at second order. The element's analytic Jacobian
 * (exact at rest) against central differences at the sagged state of a stocky rod (whose
 * axial stiffness leaves the differences their accuracy). */
static int sag(int n, int mass, double *tip)
{
    int nodes[65], elems[64];
    const double g[3] = {0, 0, -9.81e-5}; /* small: sag 4.6e-5 L, linear to 1e-9 */
    bgr_model *m = bt_cantilever(&slender, mass, n, 1.0, g, 0, 0, nodes, elems);
    if (!m) return -1;
    dae_static_result r;
    bg_error err = {0};
    int st = bgr_static(m, NULL, 0.0, &r, &err);
    if (st != BG_OK) tap_diag("sag n = %d: %s", n, err.message);
    *tip = -bgr_y0(m)[mech_body_var(m, nodes[n], 'x') + 2];
    bgr_model_free(&m);
    return st;
}

static void test_sag(void)
{
    double EI = slender.E * slender.Iz, q = slender.rho * slender.A * 9.81e-5, want = q / (8 * EI);
    double e[2][3], tip = 0;
    int ok = 1;
    const int ns[3] = {2, 4, 8};
    for (int mass = 0; mass < 2; mass++)
        for (int i = 0; i < 3; i++) {
            ok &= sag(ns[i], mass, &tip) == BG_OK;
            e[mass][i] = fabs(tip - want) / want;
        }
    tap_ok(ok && e[1][0] < 1e-6 && e[1][1] < 1e-6 && e[1][2] < 1e-6,
           "own weight, consistent: tip q L^4/(8 E I) = %.6e m within %.1e, %.1e, %.1e at 2, 4, "
           "8 elements (lumped: %.1e, %.1e, %.1e)",
           want, e[1][0], e[1][1], e[1][2], e[0][0], e[0][1], e[0][2]);
    const mech_section stocky = {
        .E = 2.1e9, .G = 8.1e8, .A = 1e-4, .Iy = 1e-9, .Iz = 2e-9, .J = 1.5e-9, .rho = 1000};
    const double g[3] = {0, 3.0, -9.81};
    int nodes[4], elems[3];
    bgr_model *m = bt_cantilever(&stocky, MECH_BEAM_CONSISTENT, 3, 1.0, g, 0, 0, nodes, elems);
    dae_static_result r;
    bg_error err = {0};
    int st = m ? bgr_static(m, NULL, 0.0, &r, &err) : -1;
    char rep[512] = "";
    int bad =
        st == BG_OK ? bgr_check_jacobian(m, 0.0, bgr_y0(m), bgr_yp0(m), 1e-6, rep, sizeof rep) : -1;
    tap_ok(bad == 0,
           "consistent element's Jacobian at rest under gravity against central "
           "differences (%d mismatches%s%s)",
           bad, bad ? ": " : "", bad ? rep : "");
    bgr_model_free(&m);
}

/* ---- the elastica: a cantilever under a dead tip load P, k = P L^2 / (E I) up to 10 ----
 * Reference: the extensible elastica by shooting, EI phi'' = -P (1 + eps) cos phi with the
 * stretch eps = P sin phi / (E A) of the axial force, phi(0) = 0, phi'(L) = 0; x' = (1 + eps)
 * cos phi, z' = -(1 + eps) sin phi (RK4, 20 000 steps, bisection on phi'(0)). */
static void elastica(double k, double c, double *xt, double *zt)
{
    const int N = 20000;
    double lo = 0, hi = 2 * k;
    for (int it = 0; it < 100; it++) {
        double k0 = 0.5 * (lo + hi), ph = 0, kp = k0, h = 1.0 / N, x = 0, z = 0;
        for (int i = 0; i < N; i++) { /* RK4 on (phi, phi', x, z); c = E I / (E A L^2) */
            double Y[4] = {ph, kp, x, z}, K[4][4];
            for (int st = 0; st < 4; st++) {
                double f = st == 0 ? 0 : st == 3 ? 1 : 0.5, yy[4];
                for (int j = 0; j < 4; j++)
                    yy[j] = Y[j] + (st ? f * h * K[st - 1][j] : 0);
                double e = c * k * sin(yy[0]);
                K[st][0] = yy[1];
                K[st][1] = -k * (1 + e) * cos(yy[0]);
                K[st][2] = (1 + e) * cos(yy[0]);
                K[st][3] = -(1 + e) * sin(yy[0]);
            }
            ph += h * (K[0][0] + 2 * K[1][0] + 2 * K[2][0] + K[3][0]) / 6;
            kp += h * (K[0][1] + 2 * K[1][1] + 2 * K[2][1] + K[3][1]) / 6;
            x += h * (K[0][2] + 2 * K[1][2] + 2 * K[2][2] + K[3][2]) / 6;
            z += h * (K[0][3] + 2 * K[1][3] + 2 * K[2][3] + K[3][3]) / 6;
        }
        *xt = x, *zt = z;
        if (kp > 0) /* curvature left at the tip: too much at the root */
            hi = k0;
        else
            lo = k0;
    }
}

static void test_elastica(void)
{
    /* steel, r / L = 2.9e-3 */
    const mech_section steel = {.E = 2.1e11,
                                .G = 8.1e10,
                                .A = 1e-4,
                                .Iy = 1.6e-9,
                                .Iz = 8.33e-10,
                                .J = 1.4e-9,
                                .rho = 7850};
    const double ks[4] = {1, 3, 5, 10}, EI = steel.E * steel.Iz;
    const int ns[4] = {4, 8, 16, 32};
    double err[2][4][4]; /* [element][k][n] */
    int ok = 1;
    for (int ik = 0; ik < 4; ik++) {
        double xt, zt;
        elastica(ks[ik], steel.Iz / (steel.A), &xt, &zt);
        for (int mass = 0; mass < 2; mass++)
            for (int in = 0; in < 4; in++) {
                int nodes[65], elems[64];
                bgr_model *m =
                    bt_cantilever(&steel, mass, ns[in], 1.0, NULL, 0, ks[ik] * EI, nodes, elems);
                dae_static_options o;
                dae_static_options_default(&o);
                o.max_steps = 5000;
                dae_static_result r;
                bg_error e = {0};
                int st = m ? bgr_static(m, &o, 0.0, &r, &e) : -1;
                if (st != BG_OK) tap_diag("elastica k = %g, n = %d: %s", ks[ik], ns[in], e.message);
                ok &= st == BG_OK;
                const double *tip = m ? bgr_y0(m) + mech_body_var(m, nodes[ns[in]], 'x') : NULL;
                err[mass][ik][in] = st == BG_OK ? hypot(tip[0] - xt, tip[2] - zt) : INFINITY;
                bgr_model_free(&m);
            }
        tap_diag("elastica k = %g: tip (%.6f, %.6f) L; tip errors / L at 4, 8, 16, 32 elements: "
                 "lumped %.2e %.2e %.2e %.2e, consistent %.2e %.2e %.2e %.2e",
                 ks[ik], xt, zt, err[0][ik][0], err[0][ik][1], err[0][ik][2], err[0][ik][3],
                 err[1][ik][0], err[1][ik][1], err[1][ik][2], err[1][ik][3]);
    }
    double w16 = 0, omin = INFINITY;
    for (int ik = 0; ik < 4; ik++) {
        w16 = fmax(w16, err[1][ik][2]);
        omin = fmin(omin, log2(err[1][ik][1] / err[1][ik][2]));
    }
    tap_ok(ok && w16 < 1e-4,
           "elastica, consistent element: tip within %.2e L at 16 elements for k = 1, 3, 5, 10 "
           "(target 1e-4; lumped: %.2e at k = 10)",
           w16, err[0][3][2]);
    tap_ok(ok && omin > 3.7,
           "elastica, consistent element: fourth order (smallest order 8 -> 16 "
           "elements %.2f)",
           omin);
}

/* ---- the model file's key: element: consistent | quartic ----
 * A clamped-free chain of 4 elements read from a model file with each value of the key: the
 * first bending frequency (I_z = I_y: the lowest elastic mode) against the closed form, whose
 * error is 3.6e-9 with the consistent element, 6.9e-8 with the quartic one and 2.8e-2 with the
 * lumped one; the quartic chain has the bubbles' four unknowns per element more (*n: the
 * model's unknowns). */
static double model_file_first(const char *element, int *n)
{
    char text[1024];
    snprintf(text, sizeof text,
             "format: bgsim 1\nname: cant\n"
             "components:\n"
             "  clamp: {type: mech.support}\n"
             "  beam: {type: mech.beam_chain, elements: 4, start: [0, 0, 0], end: [1, 0, 0],\n"
             "         E: 2.1e11, G: 8.1e10, A: 1e-4, Iy: 1e-12, Iz: 1e-12, J: 1.5e-12,\n"
             "         rho: 7850, element: %s, ports: {foot: {node: 0}}}\n"
             "bonds: [clamp.p -> beam.foot]\n",
             element);
    bg_error e = {0};
    mdl_model *mm = mdl_load_string(text, "cant.yaml", NULL, 0, &e);
    if (!mm) {
        tap_diag("model file (element: %s): %s", element, e.message);
        return NAN;
    }
    dae_modes *M = NULL;
    double f = NAN;
    *n = bgr_n(mdl_bgr(mm));
    if (bgr_modes(mdl_bgr(mm), 0.0, NULL, NULL, NULL, &M, &e) == BG_OK)
        for (int k = 0; k < dae_modes_count(M); k++)
            if (dae_modes_get(M, k)->kind == DAE_MODE_ELASTIC) {
                f = dae_modes_get(M, k)->freq_hz * 2 * PI;
                break;
            }
    dae_modes_free(&M);
    mdl_free(&mm);
    return f;
}

static void test_model_file(void)
{
    double b = bt_clamped_free_root(0), EI = slender.E * 1e-12;
    double w = b * b * sqrt(EI / (slender.rho * slender.A));
    w *= 1 - 0.5 * 1e-12 / slender.A * bt_slope_ratio(b);
    int nc = 0, nl = 0, nq = 0;
    double fc = model_file_first("consistent", &nc), fl = model_file_first("lumped", &nl);
    double fq = model_file_first("quartic", &nq);
    tap_ok(fabs(fc - w) / w < 1e-6 && fabs(fl - w) / w > 1e-2,
           "model file, 4 elements: first bending frequency %.6f rad/s with element: consistent "
           "(closed form %.6f, error %.1e), %.6f with element: lumped (error %.1e)",
           fc, w, fabs(fc - w) / w, fl, fabs(fl - w) / w);
    tap_ok(fabs(fq - w) / w < 1e-6 && nq == nc + 16 && nc == nl,
           "model file, 4 elements, element: quartic: first bending frequency %.6f rad/s (error "
           "%.1e), %d unknowns against the consistent chain's %d (4 bubble states per element)",
           fq, fabs(fq - w) / w, nq, nc);
}

int main(void)
{
    test_frequencies();
    test_kinetic();
    test_model_file();
    test_sag();
    test_elastica();
    test_energy();
    test_vibration();
    return tap_done();
}
