/* The quartic co-rotational beam element (mech_beam.h, MECH_BEAM_QUARTIC: the consistent
 * element's cubic local field plus a bubble B(xi) = xi^2 (1 - xi)^2 per bending plane, its
 * amplitudes and rates states of the element) against independent references:
 *   - clamped-free bending frequencies in both planes, 2 .. 16 elements, against the
 *     Euler-Bernoulli closed form (the roots of cos b cosh b = -1, by Newton here) with the
 *     first-order correction for the section's rotary inertia; the measured orders;
 *   - the same under an axial tension N L^2 / (E I) = 50 (a dead tip load), against the closed
 *     form of the tensioned Rayleigh beam: the tension's work on the bubbles;
 *   - one element's kinetic energy against closed forms: a rigid motion, a bubble rate alone,
 *     and arbitrary node velocities with bubble rates against the quadrature of the quartic
 *     field's kinetic energy density (Simpson, 2 000 panels);
 *   - energy: a free chain spinning end over end while it bends (the bubbles moving);
 *   - a cantilever released in its second mode: the period against the closed form, energy;
 *   - the sag under the distributed weight: tip deflection q L^4 / (8 E I), tip slope
 *     q L^3 / (6 E I), and the strain energy q^2 L^5 / (40 E I), which the quartic field holds
 *     exactly (the cubic one does not);
 *   - the elastica, k = P L^2 / (E I) = 1, 3, 5, 10, against the extensible elastica by
 *     shooting, 4 .. 16 elements;
 *   - refusals: kappa > 0 and rho = 0 with the quartic element.
 * Its analytic Jacobian is held to central differences in test_beam_quartic_jac.c. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bg_sparse.h"
#include "bgr_analysis.h"
#include "beam_testlib.h"
#include "bgr_elements.h"
#include "mech_beam.h"
#include "mech_body.h"
#include "mech_parts.h"
#include "tap.h"

static const double PI = 3.14159265358979323846;
/* Sections in the order of mech_section: E, G, A, Iy, Iz, J, rho, kappa, beta, element.
 * slender: r^2 / L^2 = 1e-8, 2e-8 (steel, L = 1 m) */
static const mech_section slender = {2.1e11,  8.1e10, 1e-4, 2e-12, 1e-12,
                                     1.5e-12, 7850,   0,    0,     MECH_BEAM_QUARTIC};
/* a polymer rod, r^2 / L^2 = 1e-5, 2e-5: first bending frequency 8 rad/s, axial 3 100 */
static const mech_section rod = {2.1e9,  8.1e8, 1e-4, 2e-9, 1e-9,
                                 1.5e-9, 1000,  0,    0,    MECH_BEAM_QUARTIC};

/* The unknown of state i of element el (quartic: 0 b_y, 1 b_z, 2 c_y, 3 c_z). */
static int state_var(const bgr_model *m, int el, int i)
{
    return bgr_ref_var(m, (bgr_ref){.type = BGR_STATE, .id = el, .i = i});
}

/* The closed-form clamped-free bending frequency k (rad/s) with second moment I, L = 1. */
static double cantilever_frequency(const mech_section *s, double I, int k)
{
    double b = bt_clamped_free_root(k);
    return b * b * sqrt(s->E * I / (s->rho * s->A)) * (1 - 0.5 * I / s->A * bt_slope_ratio(b));
}

/* Plane of a mode from its node velocities (local e1 = x, e2 = z, e3 = -y): 0 along z (I_z),
 * 1 along y (I_y), -1 other (axial, torsion). */
static int mode_plane(const bgr_model *m, const int *nodes, int n, const double *re,
                      const double *im)
{
    double s[3] = {0, 0, 0};
    for (int j = 1; j <= n; j++)
        for (int c = 0; c < 3; c++) {
            int v = mech_body_var(m, nodes[j], 'v') + c;
            s[c] += re[v] * re[v] + im[v] * im[v];
        }
    return s[2] > s[0] && s[2] > s[1] ? 0 : s[1] > s[0] && s[1] > s[2] ? 1 : -1;
}

/* The first three bending frequencies (rad/s) of each plane (0: I_z, 1: I_y), under an axial
 * tip load Px (the modes about the static state). */
static int bending_frequencies(const mech_section *sec, int n, int element, double Px,
                               double f[2][3])
{
    int nodes[65], elems[64];
    bgr_model *m = bt_cantilever(sec, element, n, 1.0, NULL, Px, 0, nodes, elems);
    dae_modes *M = NULL;
    bg_error e = {0};
    dae_static_result sr;
    if (!m || (Px != 0 && bgr_static(m, NULL, 0.0, &sr, &e) != BG_OK) ||
        bgr_modes(m, 0.0, NULL, NULL, NULL, &M, &e) != BG_OK) {
        tap_diag("modes, n = %d: %s", n, m ? e.message : "model");
        bgr_model_free(&m);
        return 0;
    }
    int N = bgr_n(m), nf[2] = {0, 0};
    double *re = malloc((size_t)N * sizeof *re), *im = malloc((size_t)N * sizeof *im);
    for (int k = 0; k < dae_modes_count(M); k++) {
        if (dae_modes_get(M, k)->kind != DAE_MODE_ELASTIC) continue;
        dae_modes_vector(M, k, re, im);
        int cls = mode_plane(m, nodes, n, re, im);
        if (cls >= 0 && nf[cls] < 3) f[cls][nf[cls]++] = dae_modes_get(M, k)->freq_hz * 2 * PI;
    }
    free(re);
    free(im);
    dae_modes_free(&M);
    bgr_model_free(&m);
    return nf[0] == 3 && nf[1] == 3;
}

static void test_frequencies(void)
{
    enum { NN = 4 };
    const int ns[NN] = {2, 4, 8, 16};
    const double I2[2] = {slender.Iz, slender.Iy};
    tap_ok(fabs(bt_clamped_free_root(0) - 1.8751) < 1e-4 &&
               fabs(bt_clamped_free_root(1) - 4.6941) < 1e-4 &&
               fabs(bt_clamped_free_root(2) - 7.8548) < 1e-4,
           "clamped-free roots %.10f %.10f %.10f (1.8751, 4.6941, 7.8548)", bt_clamped_free_root(0),
           bt_clamped_free_root(1), bt_clamped_free_root(2));
    double err[NN][6]; /* [n][plane * 3 + mode] */
    int ok = 1;
    for (int i = 0; i < NN; i++) {
        double f[2][3];
        int got = bending_frequencies(&slender, ns[i], MECH_BEAM_QUARTIC, 0, f);
        ok &= got;
        for (int j = 0; j < 6; j++) {
            double want = cantilever_frequency(&slender, I2[j / 3], j % 3);
            err[i][j] = got ? fabs(f[j / 3][j % 3] - want) / want : INFINITY;
        }
        tap_diag("quartic %2d elements: bending z %.2e %.2e %.2e, bending y %.2e %.2e %.2e", ns[i],
                 err[i][0], err[i][1], err[i][2], err[i][3], err[i][4], err[i][5]);
    }
    /* orders log2(e(n) / e(2 n)); the asymptotic ones from 4 elements on (2 -> 4: the third
     * mode, half a wavelength per element, 3.9), where the finer error is above the
     * eigensolver's rounding (1e-12 relative: mode 1 at 16 elements is 1.7e-11) */
    double omin = INFINITY;
    for (int i = 0; i + 1 < NN; i++) {
        double o[6];
        for (int j = 0; j < 6; j++) {
            o[j] = log2(err[i][j] / err[i + 1][j]);
            if (i > 0 && err[i + 1][j] > 1e-11) omin = fmin(omin, o[j]);
        }
        tap_diag("orders %2d -> %2d elements: z %.2f %.2f %.2f, y %.2f %.2f %.2f", ns[i], ns[i + 1],
                 o[0], o[1], o[2], o[3], o[4], o[5]);
    }
    double w8 = 0;
    for (int j = 0; j < 6; j++)
        w8 = fmax(w8, err[2][j]);
    tap_ok(ok && w8 < 1e-4,
           "quartic element: the first three bending frequencies of both planes within %.2e of "
           "the closed form at 8 elements (target 1e-4)",
           w8);
    /* a conforming field of degree p with its consistent mass: eigenvalues of order 2 (p - 1),
     * 6 here (the cubic field's 4); measured 5.98 .. 6.01 from 4 elements on */
    tap_ok(ok && omin > 5.8,
           "quartic element: sixth order on the cantilever, 4 -> 8 -> 16 elements (smallest "
           "measured order %.2f)",
           omin);
}

/* ---- the cantilever under axial tension N (a dead tip load along the axis) ----
 * EI w'''' - N w'' = rho A omega^2 w, w(0) = w'(0) = 0, w''(L) = 0, EI w'''(L) - N w'(L) = 0
 * (the dead load keeps its direction: no transverse force at the tip). With r1^2, -r2^2 the
 * roots of EI r^4 - N r^2 - rho A omega^2 = 0, w = A (cosh r1 x - cos r2 x) + B (sinh r1 x -
 * (r1 / r2) sin r2 x) and the two end conditions give det(omega) = 0, whose roots are found by
 * a scan and bisection. The section's rotary inertia rho I (the Rayleigh beam: - rho I w''
 * omega^2 in the equation and in the shear at the tip) enters as the tension N - rho I omega^2,
 * exactly. The tension's work on a bubble is the bowing term's 2 b^2 / 7 (N int w'^2 / 2,
 * int B'^2 = 2 / 105); nothing else checks it: 2.5 / 7 there raises the errors at 2, 4, 8
 * elements from 8.1e-3, 3.0e-4, 4.4e-6 to 1.6e-2, 4.3e-4, 7.3e-6. */
static double tension_det(double EI, double rA, double rI, double N0, double w)
{
    double N = N0 - rI * w * w, q = sqrt(N * N + 4 * EI * rA * w * w),
           r1 = sqrt((N + q) / (2 * EI)), r2 = sqrt((q - N) / (2 * EI));
    double ch = cosh(r1), sh = sinh(r1), c2 = cos(r2), s2 = sin(r2);
    double a3 = r1 * r1 * ch + r2 * r2 * c2, b3 = r1 * r1 * sh + r1 * r2 * s2;
    double a4 = EI * (r1 * r1 * r1 * sh - r2 * r2 * r2 * s2) - N * (r1 * sh + r2 * s2);
    double b4 = EI * (r1 * r1 * r1 * ch + r1 * r2 * r2 * c2) - N * (r1 * ch - r1 * c2);
    return (a3 * b4 - b3 * a4) / (ch * r1 * r1 * r1 * EI); /* scaled: no overflow of cosh */
}

static double tension_frequency(double EI, double rA, double rI, double N, int k)
{
    double w0 = sqrt(EI / rA), lo = 0.5 * w0, flo = tension_det(EI, rA, rI, N, lo);
    for (int found = -1;; lo += 0.05 * w0) { /* L = 1: the roots are (beta L)^2 w0 apart */
        double hi = lo + 0.05 * w0, fhi = tension_det(EI, rA, rI, N, hi);
        if ((flo > 0) != (fhi > 0) && ++found == k) {
            for (int it = 0; it < 100; it++) {
                double mid = 0.5 * (lo + hi), fm = tension_det(EI, rA, rI, N, mid);
                if ((fm > 0) == (flo > 0))
                    lo = mid, flo = fm;
                else
                    hi = mid;
            }
            return 0.5 * (lo + hi);
        }
        flo = fhi;
    }
}

static void test_tension(void)
{
    /* the closed form leaves out the stretch N / (E A) = 5e-7, which moves the frequencies by
     * about as much (the first modes' errors at 8 elements, 1e-7 .. 2e-7, are of that size) */
    const double rA = slender.rho * slender.A,
                 EI[2] = {slender.E * slender.Iz, slender.E * slender.Iy},
                 rI[2] = {slender.rho * slender.Iz, slender.rho * slender.Iy};
    const double N = 50 * EI[0]; /* N L^2 / (E I) = 50 and 25 in the two planes */
    double b0 = bt_clamped_free_root(2);
    double chk = tension_frequency(EI[0], rA, 0, 0, 2) / (b0 * b0 * sqrt(EI[0] / rA)) - 1;
    double chr =
        tension_frequency(EI[0], rA, rI[0], 0, 2) / cantilever_frequency(&slender, slender.Iz, 2) -
        1;
    double err[3][6], worst[3] = {0, 0, 0};
    const int ns[3] = {2, 4, 8};
    int ok = 1;
    for (int i = 0; i < 3; i++) {
        double f[2][3];
        ok &= bending_frequencies(&slender, ns[i], MECH_BEAM_QUARTIC, N, f);
        for (int j = 0; j < 6; j++) {
            double want = tension_frequency(EI[j / 3], rA, rI[j / 3], N, j % 3);
            err[i][j] = fabs(f[j / 3][j % 3] - want) / want;
            worst[i] = fmax(worst[i], err[i][j]);
        }
        tap_diag("tension N L^2/(E I_z) = 50, %d elements: errors z %.2e %.2e %.2e, y %.2e %.2e "
                 "%.2e",
                 ns[i], err[i][0], err[i][1], err[i][2], err[i][3], err[i][4], err[i][5]);
    }
    tap_ok(fabs(chk) < 1e-12 && fabs(chr) < 1e-9,
           "tensioned cantilever's closed form at N = 0: "
           "third frequency %.1e from cos b cosh b = -1's, %.1e from the Rayleigh quotient's "
           "with the rotary inertia",
           chk, chr);
    tap_ok(ok && worst[0] < 1e-2 && worst[1] < 3.5e-4 && worst[2] < 6e-6,
           "cantilever under axial tension (N L^2 / (E I) = 50, 25): the first three "
           "frequencies of both planes within %.1e, %.1e, %.1e at 2, 4, 8 elements (bounds "
           "1e-2, 3.5e-4, 6e-6)",
           worst[0], worst[1], worst[2]);
}

/* ---- the kinetic energy of one element ----
 * One free element along x (L = 1; local e1 = x, e2 = z, e3 = -y), straight, a stocky section
 * (r^2 = 1e-3, 2e-3 L^2: the rotary inertia counts). At the straight state the velocity field of
 * the element is linear in the velocities: the cubic Hermite interpolation of the node
 * velocities and slope rates in each bending plane plus L B(xi) c (the bubble rate: b_z moves
 * along z = e2, b_y along y = -e3), linear along the axis; the sections turn at the slope rates
 * (about y: -dz'/dx, about z: dy'/dx) and the interpolated twist rate. T_field = int (rho A |v|^2
 * + rho I_z w_y^2 + rho I_y w_z^2 + rho (I_y + I_z) w_x^2) / 2 dx, less the node bodies' share
 * (half the mass and rotary inertia at each node), integrated by Simpson's rule here.
 * Closed forms: a rigid motion (bubble at rest) of the straight element adds -m L^2 |w_perp|^2
 * / 12 (the bar's m L^2 / 12 against the nodes' 2 (m / 2) (L / 2)^2), the rotary parts cancel;
 * a bubble rate c alone: rho A L^3 c^2 int B^2 / 2 + rho I L c^2 int B'^2 / 2
 * = rho A L^3 c^2 / 1260 + rho I L c^2 / 105 (int B^2 = 1/630, int B'^2 = 2/105), with I = I_z
 * for c_z, I_y for c_y. */
static const mech_section stocky_q = {2.1e9, 8.1e8, 1e-2, 2e-5, 1e-5,
                                      2e-5,  1000,  0,    0,    MECH_BEAM_QUARTIC};

static double field_kinetic(const mech_section *s, const double *va, const double *wa,
                            const double *vb, const double *wb, const double *c)
{
    const int N = 2000;
    double T = 0;
    /* plane z: (z_a, slope_a = -w_y,a, z_b, slope_b); plane y: (y_a, w_z,a, ...) */
    const double u[2][4] = {{va[2], -wa[1], vb[2], -wb[1]}, {va[1], wa[2], vb[1], wb[2]}};
    const double cc[2] = {c[1], c[0]}; /* c_z in plane z, c_y in plane y */
    for (int i = 0; i <= N; i++) {
        double x = (double)i / N, wgt = (i == 0 || i == N) ? 1 : (i % 2 ? 4 : 2);
        double x2 = x * x, x3 = x2 * x;
        double N1 = 1 - 3 * x2 + 2 * x3, N2 = x - 2 * x2 + x3, N3 = 3 * x2 - 2 * x3, N4 = -x2 + x3;
        double d1 = -6 * x + 6 * x2, d2 = 1 - 4 * x + 3 * x2, d3 = 6 * x - 6 * x2,
               d4 = -2 * x + 3 * x2;
        double B = x2 * (1 - x) * (1 - x), dB = 2 * x - 6 * x2 + 4 * x3;
        double w[2], sl[2];
        for (int p = 0; p < 2; p++) {
            w[p] = N1 * u[p][0] + N2 * u[p][1] + N3 * u[p][2] + N4 * u[p][3] + B * cc[p];
            sl[p] = d1 * u[p][0] + d2 * u[p][1] + d3 * u[p][2] + d4 * u[p][3] + dB * cc[p];
        }
        double vx = (1 - x) * va[0] + x * vb[0], wx = (1 - x) * wa[0] + x * wb[0];
        double e = s->rho * (s->A * (vx * vx + w[0] * w[0] + w[1] * w[1]) + s->Iz * sl[0] * sl[0] +
                             s->Iy * sl[1] * sl[1] + (s->Iy + s->Iz) * wx * wx);
        T += 0.5 * e * wgt / (3.0 * N);
    }
    double m = s->rho * s->A, Jn[3] = {s->rho * (s->Iy + s->Iz), s->rho * s->Iz, s->rho * s->Iy};
    for (int i = 0; i < 3; i++)
        T -= 0.25 * m * (va[i] * va[i] + vb[i] * vb[i]) +
             0.25 * Jn[i] * (wa[i] * wa[i] + wb[i] * wb[i]);
    return T;
}

/* The element's kinetic energy at node velocities and bubble rates c (c_y, c_z); the element
 * of kind element. */
static double element_kinetic(int element, const double *va, const double *wa, const double *vb,
                              const double *wb, const double *c)
{
    const double up[3] = {0, 0, 1}, p0[3] = {0, 0, 0}, p1[3] = {1, 0, 0};
    mech_section sec = stocky_q;
    sec.element = element;
    int nodes[2], elems[1];
    bgr_model *m = bgr_model_create("one");
    mech_beam_chain(m, 0, "beam", 1, p0, p1, up, &sec, NULL, NULL, NULL, nodes, elems);
    if (bgr_compile(m) != BG_OK) {
        tap_diag("one element: %s", bgr_model_error(m)->message);
        bgr_model_free(&m);
        return NAN;
    }
    mech_body_set(m, nodes[0], p0, va, wa, NULL);
    mech_body_set(m, nodes[1], p1, vb, wb, NULL);
    if (element == MECH_BEAM_QUARTIC)
        for (int a = 0; a < 2; a++)
            bgr_y0(m)[state_var(m, elems[0], 2 + a)] = c[a];
    double T = mech_beam_kinetic(m, elems[0], bgr_y0(m));
    bgr_model_free(&m);
    return T;
}

static void test_kinetic(void)
{
    const mech_section *s = &stocky_q;
    double m = s->rho * s->A;
    /* a rigid motion: v_c and w, node velocities v_c + w x (x_n - x_c) */
    const double vc[3] = {0.3, -0.7, 1.1}, w[3] = {0.4, 0.9, -1.3}, zero[2] = {0, 0};
    double va[3], vb[3];
    const double r[3] = {0.5, 0, 0}; /* x_b - x_c = -(x_a - x_c) */
    double wxr[3] = {w[1] * r[2] - w[2] * r[1], w[2] * r[0] - w[0] * r[2],
                     w[0] * r[1] - w[1] * r[0]};
    for (int i = 0; i < 3; i++)
        va[i] = vc[i] - wxr[i], vb[i] = vc[i] + wxr[i];
    double want = -m * (w[1] * w[1] + w[2] * w[2]) / 12;
    double tq = element_kinetic(MECH_BEAM_QUARTIC, va, w, vb, w, zero);
    double tc = element_kinetic(MECH_BEAM_CONSISTENT, va, w, vb, w, zero);
    double tf = field_kinetic(s, va, w, vb, w, zero);
    tap_ok(fabs(tq - want) < 1e-12 * m && fabs(tc - want) < 1e-12 * m &&
               fabs(tf - want) < 1e-10 * m,
           "rigid motion of one element: the quartic element adds %.12f J, -m L^2 |w_perp|^2 / 12 "
           "= %.12f J (the consistent element %.12f J, the field's quadrature %.12f J)",
           tq, want, tc, tf);
    /* a bubble rate alone */
    const double c[2] = {0.8, -1.7}, nil[3] = {0, 0, 0};
    double wb_ = 0;
    for (int a = 0; a < 2; a++)
        wb_ +=
            s->rho * s->A * c[a] * c[a] / 1260 + s->rho * (a ? s->Iz : s->Iy) * c[a] * c[a] / 105;
    double tb = element_kinetic(MECH_BEAM_QUARTIC, nil, nil, nil, nil, c);
    tap_ok(fabs(tb - wb_) < 1e-12 * m,
           "bubble rates (c_y, c_z) = (%g, %g) alone: %.14f J, rho A L^3 c^2 / 1260 + rho I L c^2 "
           "/ 105 summed over the planes = %.14f J",
           c[0], c[1], tb, wb_);
    /* arbitrary node velocities and bubble rates */
    const double ua[3] = {0.3, -0.7, 1.1}, oa[3] = {0.2, 0.9, -1.3}, ub[3] = {-0.2, 0.4, -0.5},
                 ob[3] = {-0.6, -0.6, 0.8}, cb[2] = {0.7, -0.45};
    double tg = element_kinetic(MECH_BEAM_QUARTIC, ua, oa, ub, ob, cb);
    double tfg = field_kinetic(s, ua, oa, ub, ob, cb);
    double tc0 = field_kinetic(s, ua, oa, ub, ob, zero);
    tap_ok(fabs(tg - tfg) < 1e-10 * m,
           "node velocities and bubble rates: the element adds %.12f J, the quartic field's "
           "quadrature %.12f J (difference %.1e of rho A L; with the bubbles at rest the field "
           "gives %.6f J)",
           tg, tfg, fabs(tg - tfg) / m, tc0);
}

static void test_energy(void)
{
    const int n = 2;
    const double W = 20.0, up[3] = {0, 0, 1}, p0[3] = {0, 0, 0}, p1[3] = {1, 0, 0};
    int nodes[8], elems[8];
    mech_section sec = rod;
    sec.Iy = sec.Iz = 1e-9;
    bgr_model *m = bgr_model_create("free");
    mech_beam_chain(m, 0, "beam", n, p0, p1, up, &sec, NULL, NULL, NULL, nodes, elems);
    if (bgr_compile(m) != BG_OK) {
        tap_ok(0, "free chain: compile (%s)", bgr_model_error(m)->message);
        bgr_model_free(&m);
        return;
    }
    for (int k = 0; k <= n; k++) {
        double s = (double)k / n - 0.5;
        double x[3] = {s + 0.5, 0, 0}, v[3] = {0, W * s, 2.0 * (6 * s * s - 0.5)},
               w[3] = {0, -24.0 * s, W};
        mech_body_set(m, nodes[k], x, v, w, NULL);
    }
    int bub[2 * 2];
    for (int k = 0; k < n; k++)
        for (int a = 0; a < 2; a++)
            bub[2 * k + a] = state_var(m, elems[k], a);
    bt_run_out o;
    int r = bt_run(m, nodes, elems, n, 1e-6, 2 * PI / W, 40, -1, bub, 2 * n, "free chain", &o);
    tap_ok(r == 0 && o.drift < 3e-5 && o.bmax > 0,
           "free chain of 2 quartic elements spinning at %g rad/s while it bends: total energy "
           "kept within %.1e over a revolution at rtol 1e-6 (elements' kinetic share up to "
           "%.2e J, bubble amplitudes up to %.1e)",
           W, o.drift, o.Tel, o.bmax);
    bgr_model_free(&m);
}

/* ---- a cantilever released in its second bending mode ----
 * 4 quartic elements of the polymer rod, started straight with the velocities (nodes and
 * bubble rates) of the model's own second mode in the plane of I_z at a tip amplitude of
 * 1e-4 L, integrated over six periods at rtol 1e-9: the period from the tip's upward zero
 * crossings against the closed form's (with the rotary inertia), and the total energy. */
static void test_vibration(void)
{
    const int n = 4;
    int nodes[8], elems[8], rates[2 * 4];
    bgr_model *m = bt_cantilever(&rod, MECH_BEAM_QUARTIC, n, 1.0, NULL, 0, 0, nodes, elems);
    for (int k = 0; m && k < n; k++)
        for (int a = 0; a < 2; a++)
            rates[2 * k + a] = state_var(m, elems[k], 2 + a);
    double want = cantilever_frequency(&rod, rod.Iz, 1);
    char why[256] = "model";
    double wmode =
        m ? bt_release_in_mode(m, nodes, n, 1.0, 2, 1e-4 * want, rates, 2 * n, why, sizeof why)
          : NAN;
    if (isnan(wmode)) {
        tap_ok(0, "vibrating cantilever: modes (%s)", why);
        bgr_model_free(&m);
        return;
    }
    double cmax = 0;
    for (int k = 0; k < 2 * n; k++)
        cmax = fmax(cmax, fabs(bgr_y0(m)[rates[k]]));
    bt_run_out o;
    int r = bt_run(m, nodes, elems, n, 1e-9, 6 * 2 * PI / want, 6 * 200,
                   mech_body_var(m, nodes[n], 'x') + 2, NULL, 0, "vibrating cantilever", &o);
    double T = 2 * PI / want, err = fabs(o.period - T) / T, lin = fabs(wmode - want) / want;
    tap_ok(r == 0 && o.crossings >= 5 && err < 1e-4 && o.drift < 1e-6 && cmax > 0,
           "cantilever of 4 quartic elements vibrating in its second mode (bubble rates up to "
           "%.1e): period %.9f s from %d crossings, the closed form's %.9f s (error %.1e; the "
           "linearised model's %.1e), energy kept within %.1e",
           cmax, o.period, o.crossings, T, err, lin, o.drift);
    bgr_model_free(&m);
}

/* ---- the sag under the distributed weight ----
 * A cantilever under its own weight q = rho A g (g small: the sag 4.6e-5 L, linear to 1e-9):
 * w(x) = q x^2 (6 L^2 - 4 L x + x^2) / (24 E I), w(L) = q L^4 / (8 E I), slope at the tip
 * q L^3 / (6 E I), strain energy int M^2 / (2 E I) = q^2 L^5 / (40 E I). The deflection is a
 * quartic on every element: the quartic element holds it exactly, its energy too; the cubic
 * (consistent) element is exact at the nodes but short of the energy (its field is not the
 * exact one inside the elements). */
static int sag(int n, int element, double *tip, double *slope, double *mid, double *energy)
{
    int nodes[65], elems[64];
    const double g[3] = {0, 0, -9.81e-5};
    bgr_model *m = bt_cantilever(&slender, element, n, 1.0, g, 0, 0, nodes, elems);
    if (!m) return -1;
    dae_static_result r;
    bg_error err = {0};
    int st = bgr_static(m, NULL, 0.0, &r, &err);
    if (st != BG_OK) tap_diag("sag n = %d: %s", n, err.message);
    const double *y = bgr_y0(m), *q = y + mech_body_var(m, nodes[n], 'q');
    *tip = -y[mech_body_var(m, nodes[n], 'x') + 2];
    *mid = n % 2 ? NAN : -y[mech_body_var(m, nodes[n / 2], 'x') + 2];
    /* the tip's axis t1 = R(q) e_x, slope -t1_z / t1_x */
    double t1x = q[0] * q[0] + q[1] * q[1] - q[2] * q[2] - q[3] * q[3];
    double t1z = 2 * (q[1] * q[3] - q[0] * q[2]);
    *slope = -t1z / t1x;
    *energy = 0;
    for (int k = 0; k < n; k++)
        *energy += mech_beam_energy(m, elems[k], y);
    bgr_model_free(&m);
    return st;
}

static void test_sag(void)
{
    double EI = slender.E * slender.Iz, q = slender.rho * slender.A * 9.81e-5;
    double wt = q / (8 * EI), st = q / (6 * EI), wm = q * (6 - 2 + 0.25) / (4 * 24 * EI),
           Wt = q * q / (40 * EI);
    const int ns[3] = {1, 2, 4};
    double e[2][3][4]; /* [element][n][tip, slope, mid, energy] */
    int ok = 1;
    for (int el = 0; el < 2; el++)
        for (int i = 0; i < 3; i++) {
            double tip = NAN, slope = NAN, mid = NAN, W = NAN;
            ok &= sag(ns[i], el ? MECH_BEAM_CONSISTENT : MECH_BEAM_QUARTIC, &tip, &slope, &mid,
                      &W) == BG_OK;
            e[el][i][0] = fabs(tip - wt) / wt;
            e[el][i][1] = fabs(slope - st) / st;
            e[el][i][2] = ns[i] > 1 ? fabs(mid - wm) / wm : 0;
            e[el][i][3] = fabs(W - Wt) / Wt;
        }
    double wq = 0, wc = INFINITY;
    for (int i = 0; i < 3; i++) {
        tap_diag("own weight, %d element(s): errors tip, tip slope, mid-span, strain energy: "
                 "quartic %.1e %.1e %.1e %.1e, consistent %.1e %.1e %.1e %.1e",
                 ns[i], e[0][i][0], e[0][i][1], e[0][i][2], e[0][i][3], e[1][i][0], e[1][i][1],
                 e[1][i][2], e[1][i][3]);
        for (int j = 0; j < 4; j++)
            wq = fmax(wq, e[0][i][j]);
        wc = fmin(wc, e[1][i][3]);
    }
    tap_ok(ok && wq < 1e-6 && wc > 1e-4,
           "own weight, quartic at 1, 2, 4 elements: tip q L^4/(8 E I) = %.6e m, tip slope "
           "q L^3/(6 E I) = %.6e, mid-span deflection, strain energy q^2 L^5/(40 E I) = %.6e J, "
           "all within %.1e (the consistent element's energy at least %.1e off)",
           wt, st, Wt, wq, wc);
}

/* ---- the elastica: a cantilever under a dead tip load P, k = P L^2 / (E I) up to 10 ----
 * Reference as in test_beam_consistent.c: the extensible elastica EI phi'' = -P (1 + eps)
 * cos phi, eps = P sin phi / (E A), phi(0) = 0, phi'(L) = 0, x' = (1 + eps) cos phi,
 * z' = -(1 + eps) sin phi, by shooting on phi'(0) (RK4, 20 000 steps, bisection). */
static void elastica(double k, double c, double *xt, double *zt)
{
    const int N = 20000;
    const double h = 1.0 / N, f[4] = {0, 0.5, 0.5, 1}, w[4] = {1, 2, 2, 1};
    double lo = 0, hi = 2 * k;
    for (int it = 0; it < 100; it++) {
        double Y[4] = {0, 0.5 * (lo + hi), 0, 0};
        for (int i = 0; i < N; i++) {
            double K[4] = {0, 0, 0, 0}, D[4] = {0, 0, 0, 0}, T[4];
            for (int st = 0; st < 4; st++) { /* RK4 on (phi, phi', x, z) */
                for (int j = 0; j < 4; j++)
                    T[j] = Y[j] + f[st] * h * K[j];
                double e = c * k * sin(T[0]);
                K[0] = T[1], K[1] = -k * (1 + e) * cos(T[0]);
                K[2] = (1 + e) * cos(T[0]), K[3] = -(1 + e) * sin(T[0]);
                for (int j = 0; j < 4; j++)
                    D[j] += w[st] * K[j] / 6;
            }
            for (int j = 0; j < 4; j++)
                Y[j] += h * D[j];
        }
        *xt = Y[2], *zt = Y[3];
        if (Y[1] > 0) /* curvature left at the tip: too much at the root */
            hi = 0.5 * (lo + hi);
        else
            lo = 0.5 * (lo + hi);
    }
}

static void test_elastica(void)
{
    const mech_section steel = {2.1e11, 8.1e10, 1e-4, 1.6e-9, 8.33e-10, 1.4e-9, 7850, 0, 0, 0};
    enum { NK = 4, NN = 3 };
    const double ks[NK] = {1, 3, 5, 10}, EI = steel.E * steel.Iz;
    const int ns[NN] = {4, 8, 16};
    double err[NK][NN];
    int ok = 1;
    for (int ik = 0; ik < NK; ik++) {
        double xt, zt;
        elastica(ks[ik], steel.Iz / steel.A, &xt, &zt);
        for (int in = 0; in < NN; in++) {
            int nodes[65], elems[64];
            bgr_model *m = bt_cantilever(&steel, MECH_BEAM_QUARTIC, ns[in], 1.0, NULL, 0,
                                         ks[ik] * EI, nodes, elems);
            dae_static_result r;
            bg_error e = {0};
            int st = m ? bgr_static(m, NULL, 0.0, &r, &e) : -1;
            if (st != BG_OK) tap_diag("elastica k = %g, n = %d: %s", ks[ik], ns[in], e.message);
            ok &= st == BG_OK;
            const double *tip = m ? bgr_y0(m) + mech_body_var(m, nodes[ns[in]], 'x') : NULL;
            err[ik][in] = st == BG_OK ? hypot(tip[0] - xt, tip[2] - zt) : INFINITY;
            bgr_model_free(&m);
        }
        tap_diag("elastica k = %2g: tip (%.6f, %.6f) L; quartic tip errors / L at 4, 8, 16 "
                 "elements %.2e %.2e %.2e, orders %.2f %.2f",
                 ks[ik], xt, zt, err[ik][0], err[ik][1], err[ik][2], log2(err[ik][0] / err[ik][1]),
                 log2(err[ik][1] / err[ik][2]));
    }
    double w16 = 0, omin = INFINITY;
    for (int ik = 0; ik < NK; ik++) {
        w16 = fmax(w16, err[ik][2]);
        omin = fmin(omin, log2(err[ik][1] / err[ik][2]));
    }
    tap_ok(ok && w16 < 1e-4,
           "elastica, quartic element: tip within %.2e L at 16 elements for k = 1, 3, 5, 10 "
           "(target 1e-4)",
           w16);
    /* fourth order, as the consistent element (2.6e-4, 2.1e-5, 1.5e-6 at k = 10): the bubble
     * does not raise it; the limit lies in the co-rotational local kinematics, not in the
     * field's degree (measured with the field over L0, 1.9e-6 at k = 10 and 16 elements: the
     * shallow-arch arc length of the bowing term, int (1 + psi^2 / 2) for int sqrt(1 + psi^2),
     * was a third of it, - int psi^4 / 8 added gave 1.3e-6, the order stayed 3.8 .. 3.9; the
     * field over the current chord gives 1.3e-6, orders 3.8 .. 3.9) */
    tap_ok(ok && omin > 3.7,
           "elastica, quartic element: fourth order (smallest order 8 -> 16 elements %.2f)", omin);
}

/* ---- refusals: the quartic element is Euler-Bernoulli and needs a mass ---- */
static int refused(double kappa, double rho, const char *field, char *msg, size_t size)
{
    bgr_model *m = bgr_model_create("r");
    const double J[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1}, E0[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    const double ra[3] = {0, 0, 0};
    const int dims[1] = {6};
    int na = mech_body(m, 0, "a", 1.0, J, NULL, 1, ra, dims);
    int nb = mech_body(m, 0, "b", 1.0, J, NULL, 1, ra, dims);
    mech_section s = slender;
    s.kappa = kappa, s.rho = rho;
    int st = mech_beam(m, 0, "el", na, nb, &s, E0, 1.0);
    snprintf(msg, size, "%s", bgr_model_error(m)->message);
    bgr_model_free(&m);
    return st == BG_ERR_ARGUMENT && strstr(msg, field) && strstr(msg, "MECH_BEAM_QUARTIC");
}

static void test_refusals(void)
{
    char msg[1100];
    int r = refused(0.85, slender.rho, "kappa", msg, sizeof msg);
    tap_ok(r, "kappa = 0.85 with MECH_BEAM_QUARTIC refused: %s", msg);
    r = refused(0, 0, "rho", msg, sizeof msg);
    tap_ok(r, "rho = 0 with MECH_BEAM_QUARTIC refused: %s", msg);
    r = refused(0, slender.rho, "", msg, sizeof msg);
    tap_ok(!r, "the same section with kappa = 0 and rho > 0 accepted");
}

int main(void)
{
    test_refusals();
    test_frequencies();
    test_tension();
    test_kinetic();
    test_sag();
    test_elastica();
    test_energy();
    test_vibration();
    return tap_done();
}
