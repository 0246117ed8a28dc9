/* examples/models/luffing-boom.yaml against independent references computed here by hand:
 *
 *   a. statics (mdl_static at the held reference angle, theta_0 = 10 and 35 deg): the angle
 *      equals the reference (the PI controller's integral); the thrust p_a A_a - p_b A_b equals
 *      the weights' moment about the hinge over the cylinder's lever arm, g cos(theta) (m_b L/2 +
 *      m_L L) / r with r = (x_A z_B - z_A x_B) / |B - A| (the distance of the line A-B from the
 *      hinge; equal to dL/dtheta by virtual work); the pressures and the spool command solve the
 *      valve's flow balance P->A = A->T + q_l, B->T = P->B + q_l with the orifice law of
 *      hyd_directional.h, solved here by Newton's method, and lie near Merritt's matched
 *      symmetric valve, p_a + p_b = p_s + p_t;
 *   b. the hydraulic mode (bgr_modes at rest, the controller slowed by replacements): against
 *      the closed form omega^2 = (k_theta + k_g) / J, k_theta = beta (A_a^2 / V_a + A_b^2 /
 *      V_b) r^2 (H. E. Merritt, Hydraulic Control Systems, 1967: the oil columns' spring),
 *      k_g = -F dr/dtheta - g sin(theta) (m_b L/2 + m_L L) (the geometric stiffness of the
 *      thrust's turning lever and of the weights), J = m_b L^2 / 3 + m_L L^2; and against the
 *      complete linearisation written here (the valve's flow-pressure coefficients, the leakage,
 *      the friction and the controller: five states), whose root near i omega is found by
 *      Newton's method on det(s I - A); its damping against the first-order energy argument
 *      (Merritt's flow-pressure coefficients with the bleed: Re s = -r^2 (K_ca c_a^2 A_a^2 +
 *      K_cb c_b^2 A_b^2 + G (c_a A_a + c_b A_b)^2 + c w^2) / (2 J w^2), c_x = beta / V_x);
 *   b2. the closed loop at 10 and 35 deg with the file's gains: every mode decays, the
 *      hydraulic one with zeta >= 0.1;
 *   c. the energy of a luffing run (10 -> 35 deg from 0.5 to 8.5 s, held to 12 s): the supply's
 *      energy = the valve's dissipation (its four port powers summed) + the change of the stored
 *      oil energy - the compression energy the oil carries in + the changes of kinetic and
 *      potential energy + the cylinder's friction and leakage with the bleed
 *      (hyd_cylinder_evaluate), each power integrated with 5-point Gauss-Legendre on every
 *      step's dense output (exact for the BDF interpolant's degree <= 5 times smooth powers; the
 *      balance then closes to the integration error, rtol 1e-9 here); the pressures stay within
 *      the supply; the run follows the reference within the error a proportional gain leaves
 *      for the feedforward's mismatch (tracking_estimate) and holds 35 deg within 0.05 deg. */
#include <complex.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bg_dae.h"
#include "bgr_analysis.h"
#include "hyd_cylinder.h"
#include "mdl_model.h"
#include "mech_body.h"
#include "mech_parts.h"
#include "tap.h"

#ifndef MODELS_DIR
#define MODELS_DIR "examples/models"
#endif

static const char *PATH = MODELS_DIR "/luffing-boom.yaml";
static const double PI = 3.14159265358979323846;

/* The machine's data, written again here (checked against the file's parameters). */
typedef struct data {
    double Lb, mb, mL, g, xA, zA, aB, eB, bore, rod, stroke, Lmin, Vline, beta, c, Gs, Gb;
    double ps, pt, qn, dpn, u0, kp, ki;
} data;
static const data D = {6.0,  500,   1500,    9.81, 0.5,       -1.4, 2.0,  0.25,
                       0.1,  0.07,  1.0,     1.80, 1.0e-3,    1e9,  5e3,  2e-13, 1e-11,
                       16e6, 0,     1e-3 / 0.6, 35e5, 0.01, 6, 6};
/* the cylinder's leakage conductance: the piston's seal and the bleed across the ports */
#define G_TOT (D.Gs + D.Gb)

static double Aa(void) { return PI / 4 * D.bore * D.bore; }
static double Ab(void) { return PI / 4 * (D.bore * D.bore - D.rod * D.rod); }

/* The geometry at angle th: eye to eye L, lever arm r = dL/dth, d2L/dth2. */
static void geometry(double th, double *L, double *r, double *dr)
{
    double bx = D.aB * cos(th) + D.eB * sin(th), bz = D.aB * sin(th) - D.eB * cos(th);
    double dx = bx - D.xA, dz = bz - D.zA, l = hypot(dx, dz);
    double bx1 = -bz, bz1 = bx;   /* dB/dth */
    double bx2 = -bx, bz2 = -bz;  /* d2B/dth2 */
    double rr = (dx * bx1 + dz * bz1) / l;
    *L = l;
    *r = rr;
    *dr = (bx1 * bx1 + bz1 * bz1 + dx * bx2 + dz * bz2 - rr * rr) / l;
}
/* the weights' moment about the hinge, S cos th, S = g (m_b L/2 + m_L L) */
static double S(void) { return D.g * (D.mb * D.Lb / 2 + D.mL * D.Lb); }

/* The valve of hyd_directional.h: Q = K o f(dp), K = q_n / f(dp_n), f(dp) = dp (dp^2 +
 * dp_l^2)^(-1/4), dp_l = 0.01 dp_n, o(z) = sp(z + u0) / sp(1 + u0), sp(z) = eps ln(1 + e^(z /
 * eps)), eps = 1e-3 (no leakage across the edges in the model). */
static double sp(double z)
{
    return z > 0 ? z + 1e-3 * log1p(exp(-z / 1e-3)) : 1e-3 * log1p(exp(z / 1e-3));
}
static double orf(double dp) { double l = 0.01 * D.dpn; return dp / sqrt(sqrt(dp * dp + l * l)); }
static double edge(double z, double dp)
{
    return D.qn / orf(D.dpn) * sp(z + D.u0) / sp(1 + D.u0) * orf(dp);
}
/* flows into the cap and the rod chamber at (p_a, p_b, u) */
static double qa(double pa, double u) { return edge(u, D.ps - pa) - edge(-u, pa - D.pt); }
static double qb(double pb, double u) { return edge(-u, D.ps - pb) - edge(u, pb - D.pt); }

/* Newton on x = (p_a, p_b, u): qa = q_l, qb = -q_l, p_a A_a - p_b A_b = F; from Merritt's
 * matched-valve estimate. */
static int valve_balance(double F, double x[3])
{
    x[0] = (F + (D.ps + D.pt) * Ab()) / (Aa() + Ab());
    x[1] = D.ps + D.pt - x[0];
    double rho = sqrt((x[0] - D.pt) / (D.ps - x[0]));
    x[2] = D.u0 * (rho - 1) / (rho + 1);
    const double sc[3] = {D.ps, D.ps, 1};
    for (int it = 0; it < 50; it++) {
        double f[3] = {0, 0, 0}, J[3][3];
        for (int k = -1; k < 3; k++) {
            double y[3] = {x[0], x[1], x[2]}, h = k >= 0 ? 1e-7 * sc[k] : 0;
            if (k >= 0) y[k] += h;
            double ql = G_TOT * (y[0] - y[1]);
            double g[3] = {(qa(y[0], y[2]) - ql) / D.qn, (qb(y[1], y[2]) + ql) / D.qn,
                           (y[0] * Aa() - y[1] * Ab() - F) / F};
            for (int i = 0; i < 3; i++) {
                if (k < 0) f[i] = g[i];
                else J[i][k] = (g[i] - f[i]) / h;
            }
        }
        double det = J[0][0] * (J[1][1] * J[2][2] - J[1][2] * J[2][1]) -
                     J[0][1] * (J[1][0] * J[2][2] - J[1][2] * J[2][0]) +
                     J[0][2] * (J[1][0] * J[2][1] - J[1][1] * J[2][0]);
        double dx[3];
        for (int c = 0; c < 3; c++) { /* Cramer */
            double M[3][3];
            memcpy(M, J, sizeof M);
            for (int i = 0; i < 3; i++) M[i][c] = -f[i];
            dx[c] = (M[0][0] * (M[1][1] * M[2][2] - M[1][2] * M[2][1]) -
                     M[0][1] * (M[1][0] * M[2][2] - M[1][2] * M[2][0]) +
                     M[0][2] * (M[1][0] * M[2][1] - M[1][1] * M[2][0])) / det;
        }
        double big = 0;
        for (int i = 0; i < 3; i++) {
            x[i] += dx[i];
            big = fmax(big, fabs(dx[i]) / sc[i]);
        }
        if (big < 1e-14) return 0;
    }
    return -1;
}

static int col(const mdl_model *mm, const char *name)
{
    for (int i = 0; i < mdl_noutputs(mm); i++)
        if (!strcmp(mdl_output_name(mm, i), name)) return i;
    return -1;
}

static int element(bgr_model *m, const char *name)
{
    bgr_element *el;
    for (int i = 0; (el = bgr_element_get(m, i)) != NULL; i++)
        if (el->name && !strcmp(el->name, name)) return i;
    return -1;
}

/* The static start at the file's angle (with the replacements sets), the default options: the
 * sources' place() start the supply, the tank and the reference at their values at t = 0. */
static mdl_model *at_rest(const mdl_set *sets, int nsets, const char *what)
{
    bg_error e = {0};
    bg_error_clear(&e);
    mdl_model *mm = mdl_load(PATH, sets, nsets, &e);
    tap_ok(mm != NULL, "%s: loads (%s)", what, mm ? "ok" : e.message);
    if (!mm) return NULL;
    tap_ok(mdl_start_kind(mm) == MDL_START_STATIC, "%s: the file asks for the static start", what);
    mdl_trim_report rep;
    int r = mdl_static(&mm, NULL, &rep, &e);
    tap_ok(r == BG_OK, "%s: static equilibrium (%s; %ld steps)", what, r ? e.message : "ok",
           rep.last.steps);
    if (r != BG_OK) mdl_free(&mm);
    return mm;
}

static void check_statics(const char *angle, double th)
{
    char what[64];
    snprintf(what, sizeof what, "statics at %s", angle);
    mdl_set set = {"theta_0", angle};
    mdl_model *mm = at_rest(&set, 1, what);
    if (!mm) return;
    double out[32];
    bg_error e = {0};
    mdl_outputs(mm, 0, bgr_y0(mdl_bgr(mm)), out, &e);
    double L, r, dr;
    geometry(th, &L, &r, &dr);
    double F = S() * cos(th) / r, x[3];
    tap_close(out[col(mm, "theta")], th, 0, 1e-10, "%s: the angle is the reference %.10f rad",
              what, th);
    tap_close(out[col(mm, "force")], F, 1e-8, 0,
              "%s: thrust = g cos(th) (m_b L/2 + m_L L) / r = %.6f N (r = %.6f m; model %.6f)",
              what, F, r, out[col(mm, "force")]);
    tap_close(out[col(mm, "stroke_used")], L - D.Lmin, 0, 1e-8,
              "%s: extension |B - A| - L_min = %.9f m", what, L - D.Lmin);
    int ok = valve_balance(F, x) == 0;
    tap_ok(ok, "%s: the valve's balance solved by hand", what);
    tap_close(out[col(mm, "p_a")], x[0], 1e-8, 0, "%s: p_a %.3f Pa from the orifice law (%.3f)",
              what, x[0], out[col(mm, "p_a")]);
    tap_close(out[col(mm, "p_b")], x[1], 1e-8, 0, "%s: p_b %.3f Pa from the orifice law (%.3f)",
              what, x[1], out[col(mm, "p_b")]);
    tap_close(out[col(mm, "command")], x[2], 1e-7, 1e-12, "%s: spool command %.9e (%.9e)", what,
              x[2], out[col(mm, "command")]);
    double sum = out[col(mm, "p_a")] + out[col(mm, "p_b")];
    tap_close(sum, D.ps + D.pt, 1e-3, 0,
              "%s: p_a + p_b = %.1f Pa near p_s + p_t (Merritt's matched valve; %.2e off by the "
              "piston's leakage flow)",
              what, sum, (sum - D.ps - D.pt) / D.ps);
    double qs = edge(x[2], D.ps - x[0]) + edge(-x[2], D.ps - x[1]);
    tap_close(out[col(mm, "q_supply")], qs, 1e-8, 0,
              "%s: supply flow P->A + P->B = %.6e m^3/s (the centre flow, %.3f l/min)", what, qs,
              qs * 6e4);
    mdl_free(&mm);
}

/* det(s I - A) of a 5x5 complex matrix, by elimination with partial pivoting */
static double complex det5(double complex s, const double A[5][5])
{
    double complex M[5][5], d = 1;
    for (int i = 0; i < 5; i++)
        for (int j = 0; j < 5; j++) M[i][j] = (i == j ? s : 0) - A[i][j];
    for (int k = 0; k < 5; k++) {
        int p = k;
        for (int i = k + 1; i < 5; i++)
            if (cabs(M[i][k]) > cabs(M[p][k])) p = i;
        if (p != k) {
            for (int j = 0; j < 5; j++) {
                double complex t = M[k][j];
                M[k][j] = M[p][j];
                M[p][j] = t;
            }
            d = -d;
        }
        d *= M[k][k];
        for (int i = k + 1; i < 5; i++) {
            double complex f = M[i][k] / M[k][k];
            for (int j = k; j < 5; j++) M[i][j] -= f * M[k][j];
        }
    }
    return d;
}

static void check_mode(void)
{
    const double kp = 0.02, ki = 0.01; /* the controller slowed 600 and 50 times */
    mdl_set sets[2] = {{"kp", "0.02"}, {"ki", "0.01"}};
    mdl_model *mm = at_rest(sets, 2, "modes (kp 0.02, ki 0.01)");
    if (!mm) return;
    bgr_model *m = mdl_bgr(mm);
    bg_error e = {0};
    double out[32], th = 10 * PI / 180, L, r, dr, x[3];
    mdl_outputs(mm, 0, bgr_y0(m), out, &e);
    geometry(th, &L, &r, &dr);
    double F = S() * cos(th) / r;
    valve_balance(F, x);
    double ext = L - D.Lmin, Va = D.Vline + Aa() * ext, Vb = D.Vline + Ab() * (D.stroke - ext);
    double J = D.mb * D.Lb * D.Lb / 3 + D.mL * D.Lb * D.Lb;
    double kth = D.beta * (Aa() * Aa() / Va + Ab() * Ab() / Vb) * r * r;
    double kg = -F * dr - S() * sin(th);
    double w_closed = sqrt((kth + kg) / J), w_oil = sqrt(kth / J);
    /* the complete linearisation: states th, w, p_a, p_b, I */
    double h = 1e-3, hu = 1e-9;
    double Kca = -(qa(x[0] + h, x[2]) - qa(x[0] - h, x[2])) / (2 * h);
    double Kcb = -(qb(x[1] + h, x[2]) - qb(x[1] - h, x[2])) / (2 * h);
    double Kqa = (qa(x[0], x[2] + hu) - qa(x[0], x[2] - hu)) / (2 * hu);
    double Kqb = (qb(x[1], x[2] + hu) - qb(x[1], x[2] - hu)) / (2 * hu);
    double ca = D.beta / Va, cb = D.beta / Vb;
    double complex s = I * w_closed, s0 = I * w_oil;
    for (int with_kg = 1; with_kg >= 0; with_kg--) {
        double k = with_kg ? kg : 0;
        const double A[5][5] = {
            {0, 1, 0, 0, 0},
            {-k / J, -D.c * r * r / J, r * Aa() / J, -r * Ab() / J, 0},
            {-ca * Kqa * kp, -ca * Aa() * r, -ca * (Kca + G_TOT), ca * G_TOT, ca * Kqa * ki},
            {-cb * Kqb * kp, cb * Ab() * r, cb * G_TOT, -cb * (Kcb + G_TOT), cb * Kqb * ki},
            {-1, 0, 0, 0, 0}};
        double complex *z = with_kg ? &s : &s0;
        for (int it = 0; it < 60; it++) {
            double complex ds = 1e-6 * w_closed, f = det5(*z, A);
            double complex step = f * ds / (det5(*z + ds, A) - f);
            *z -= step;
            if (cabs(step) < 1e-14 * w_closed) break;
        }
    }
    /* the damping to first order in it (Merritt's energy argument): the mode's pressures are
     * p_a = -c_a A_a r theta, p_b = c_b A_b r theta; the valve's edges, the leakage and the
     * friction dissipate K_ca p_a^2 + K_cb p_b^2 + G (p_a - p_b)^2 + c (r theta')^2 of the
     * energy J w^2 Theta^2 / 2, so Re s = -r^2 (K_ca c_a^2 A_a^2 + K_cb c_b^2 A_b^2 + G (c_a A_a
     * + c_b A_b)^2 + c w^2) / (2 J w^2); the next order is zeta^2 smaller */
    double w2 = w_closed * w_closed, cA = ca * Aa(), cB = cb * Ab();
    double sigma = r * r *
                   (Kca * cA * cA + Kcb * cB * cB + G_TOT * (cA + cB) * (cA + cB) + D.c * w2) /
                   (2 * J * w2);
    dae_modes *M = NULL;
    int st = bgr_modes(m, 0.0, NULL, NULL, NULL, &M, &e);
    tap_ok(st == BG_OK, "modes computed (%s)", st ? e.message : "ok");
    const dae_mode *best = NULL;
    for (int i = 0; st == BG_OK && i < dae_modes_count(M); i++) {
        const dae_mode *md = dae_modes_get(M, i);
        if (md->kind != DAE_MODE_ELASTIC || md->im <= 0) continue;
        if (!best || fabs(md->im - w_closed) < fabs(best->im - w_closed)) best = md;
    }
    tap_ok(best != NULL, "an oscillating mode near the closed form's %.4f rad/s", w_closed);
    if (best) {
        double wm = hypot(best->re, best->im), wf = cabs(s);
        double left = fabs(wf - w_closed) / w_closed;
        tap_diag("oil columns alone sqrt(k_theta/J) = %.6f rad/s; with k_g %.6f rad/s (k_theta "
                 "%.6e, k_g %.6e N m/rad, J %.1f kg m^2)", w_oil, w_closed, kth, kg, J);
        tap_diag("complete linearisation: s = %.9f + %.9f i; model: %.9f + %.9f i", creal(s),
                 cimag(s), best->re, best->im);
        tap_close(best->re, creal(s), 1e-6 * wf, 0,
                  "hydraulic mode: Re s %.6f from the linearisation by hand (%.6f)", creal(s),
                  best->re);
        tap_close(best->im, cimag(s), 1e-7 * wf, 0,
                  "hydraulic mode: Im s %.6f rad/s from the linearisation by hand (%.6f)",
                  cimag(s), best->im);
        tap_ok(fabs(wm - w_closed) <= 2 * left * w_closed + 1e-9 * w_closed,
               "hydraulic mode |s| %.6f rad/s (%.4f Hz) = the closed form %.6f within what it "
               "leaves out: valve, leakage, friction, controller, %.2e",
               wm, wm / (2 * PI), w_closed, left);
        tap_ok(fabs(best->im - cimag(s0)) > 1e3 * fabs(best->im - cimag(s)),
               "the geometric stiffness matters: the linearisation without k_g has Im s %.6f",
               cimag(s0));
        double zeta = sigma / w_closed;
        tap_close(-best->re, sigma, zeta * zeta, 0,
                  "hydraulic mode: damping Re s = -%.6f 1/s (zeta %.4f) by the energy argument "
                  "within zeta^2 (model %.6f; seal and bleed G = %.2e m^3/(s Pa), valve K_ca "
                  "%.3e, K_cb %.3e)",
                  sigma, zeta, best->re, G_TOT, Kca, Kcb);
    }
    dae_modes_free(&M);
    mdl_free(&mm);
}

/* The closed loop at rest with the file's gains: every mode with a finite nonzero eigenvalue (3:
 * the hydraulic, the pressure level's, the PI's) decays; the hydraulic one keeps zeta >= 0.1. */
static void check_closed_loop(const char *angle)
{
    char what[64];
    snprintf(what, sizeof what, "closed loop at %s (kp %g, ki %g)", angle, D.kp, D.ki);
    mdl_set set = {"theta_0", angle};
    mdl_model *mm = at_rest(&set, 1, what);
    if (!mm) return;
    bg_error e = {0};
    dae_modes *M = NULL;
    int st = bgr_modes(mdl_bgr(mm), 0.0, NULL, NULL, NULL, &M, &e);
    tap_ok(st == BG_OK, "%s: modes computed (%s)", what, st ? e.message : "ok");
    int n = 0, stable = 1;
    double zh = -1, slowest = -1e30;
    for (int i = 0; st == BG_OK && i < dae_modes_count(M); i++) {
        const dae_mode *md = dae_modes_get(M, i);
        if (md->kind != DAE_MODE_ELASTIC || !isfinite(md->re) || hypot(md->re, md->im) < 1e-6)
            continue;
        n++;
        tap_diag("%s: s = %.6f %+.6f i (zeta %.4f)", what, md->re, md->im, md->damping);
        if (!(md->re < 0)) stable = 0;
        if (md->im > 10) zh = md->damping;
        slowest = fmax(slowest, md->re);
    }
    tap_ok(n >= 3 && stable, "%s: all %d modes decay, the slowest at Re s = %.4f 1/s", what, n,
           slowest);
    tap_ok(zh >= 0.1, "%s: the hydraulic mode keeps zeta %.4f >= 0.1", what, zh);
    dae_modes_free(&M);
    mdl_free(&mm);
}

/* The feedforward k_ff r' opens P->A and B->T alike to (u + u_0) / (1 + u_0) of the rated flow
 * per edge: A_a r theta' = q_n (u + u_0) / (1 + u_0) sqrt((p_s - p_a) / dp_n) with p_b - p_t =
 * (p_s - p_a) (A_b / A_a)^2 and p_a A_a - p_b A_b = F (the square-root law, laminar part
 * aside), so the boom's rate per unit command is K_v(theta) = q_n sqrt((p_s - p_a) / dp_n) /
 * ((1 + u_0) A_a r); k_ff = 1 / K_v at the mid angle. The rate left to the loop is (1 - K_v
 * k_ff) theta', which a proportional gain alone holds at the error (1 - K_v k_ff) theta' / (K_v
 * kp); the integral only lowers it. Returns the largest over the luff, and k_ff in *kff. */
static double kv(double th)
{
    double L, r, dr, k = Ab() / Aa();
    geometry(th, &L, &r, &dr);
    double F = S() * cos(th) / r;
    double pa = (F + (D.pt + D.ps * k * k) * Ab()) / (Aa() + k * k * Ab());
    return D.qn * sqrt((D.ps - pa) / D.dpn) / ((1 + D.u0) * Aa() * r);
}
static double tracking_estimate(double th0, double th1, double w, double *kff)
{
    *kff = 1 / kv(0.5 * (th0 + th1));
    double worst = 0;
    for (int i = 0; i <= 1000; i++) {
        double th = th0 + (th1 - th0) * i / 1000.0, K = kv(th);
        worst = fmax(worst, fabs(1 - K * *kff) * w / (K * D.kp));
    }
    return worst;
}

/* Gauss-Legendre, 5 points on [-1, 1]. */
static const double GX[5] = {-0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831,
                             0.9061798459386640};
static const double GW[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889,
                             0.4786286704993665, 0.2369268850561891};

static void check_energy(void)
{
    mdl_model *mm = at_rest(NULL, 0, "luffing run");
    if (!mm) return;
    bgr_model *m = mdl_bgr(mm);
    int cyl = element(m, "cyl"), body = element(m, "boom"), pm = element(m, "load");
    int vP[2] = {bgr_find_var(m, "luffing-boom/supply.p->valve.P/e"),
                 bgr_find_var(m, "luffing-boom/supply.p->valve.P/f")};
    int vT[2] = {bgr_find_var(m, "luffing-boom/valve.T->tank.p/e"),
                 bgr_find_var(m, "luffing-boom/valve.T->tank.p/f")};
    int vA[2] = {bgr_find_var(m, "luffing-boom/valve.A->cyl.a/e"),
                 bgr_find_var(m, "luffing-boom/valve.A->cyl.a/f")};
    int vB[2] = {bgr_find_var(m, "luffing-boom/valve.B->cyl.b/e"),
                 bgr_find_var(m, "luffing-boom/valve.B->cyl.b/f")};
    tap_ok(cyl >= 0 && body >= 0 && pm >= 0 && vP[1] >= 0 && vT[1] >= 0 && vA[1] >= 0 && vB[1] >= 0,
           "run: the cylinder, the boom, the load and the valve's bonds found");
    dae_problem p;
    dae_options o;
    double *bk = NULL;
    mdl_dae_problem(mm, &p);
    mdl_dae_options(mm, &o, &bk);
    o.rtol = o.atol = 1e-9;
    bg_error e = {0};
    dae_solver *sol = dae_create(&p, &o, &e);
    int rc = sol ? dae_init(sol, 0, bgr_y0(m), bgr_yp0(m)) : -1;
    if (rc >= 0) rc = dae_consistent_init(sol);
    int n = bgr_n(m), ith = col(mm, "theta"), iref = col(mm, "theta_ref"), ipa = col(mm, "p_a"),
        ipb = col(mm, "p_b"), iP = col(mm, "P_supply"), iK = col(mm, "E_kin"),
        iV = col(mm, "E_pot"), iO = col(mm, "E_oil");
    double *y = calloc((size_t)n, sizeof *y), *yp = calloc((size_t)n, sizeof *yp);
    double *yq = calloc((size_t)n, sizeof *yq), out[32], out0[32];
    hyd_cylinder_values v0, v;
    double ke0, pe0, ke1, pe1, ke, pe;
    hyd_cylinder_evaluate(m, cyl, bgr_y0(m), &v0);
    mech_body_energy(m, body, bgr_y0(m), &ke0, &pe0);
    mech_point_mass_energy(m, pm, bgr_y0(m), &ke1, &pe1);
    mdl_outputs(mm, 0, bgr_y0(m), out0, &e);
    double Esup = 0, Dval = 0, Econv = 0, Dfric = 0, Dleak = 0, Etank = 0, t = 0;
    double tend = mdl_solver(mm)->t_end;
    double err_max = 0, pmin = 1e30, pmax = -1e30, dout = 0;
    while (rc >= 0 && t < tend) {
        double t0 = t;
        rc = dae_step(sol, tend, &t, y, yp);
        if (rc < 0) break;
        for (int k = 0; k < 5; k++) {
            double tq = 0.5 * (t0 + t) + 0.5 * (t - t0) * GX[k], wq = 0.5 * (t - t0) * GW[k];
            dae_dense(sol, tq, yq, NULL);
            hyd_cylinder_evaluate(m, cyl, yq, &v);
            mdl_outputs(mm, tq, yq, out, &e);
            double PP = yq[vP[0]] * yq[vP[1]], PT = yq[vT[0]] * yq[vT[1]];
            double PA = yq[vA[0]] * yq[vA[1]], PB = yq[vB[0]] * yq[vB[1]];
            Esup += wq * out[iP];
            dout = fmax(dout, fabs(out[iP] - PP));
            Dval += wq * (PP - PT - PA - PB); /* into the valve at P, out at T, A and B */
            Etank += wq * PT;
            Econv += wq * v.power_convected;
            Dfric += wq * v.dissipation_friction;
            Dleak += wq * v.dissipation_leakage;
            err_max = fmax(err_max, fabs(out[ith] - out[iref]));
            pmin = fmin(pmin, fmin(out[ipa], out[ipb]));
            pmax = fmax(pmax, fmax(out[ipa], out[ipb]));
        }
    }
    tap_ok(rc >= 0 && t >= tend, "run: reaches %g s (%s)", tend,
           rc < 0 && sol ? dae_get_error(sol)->message : "ok");
    mdl_outputs(mm, t, y, out, &e);
    hyd_cylinder_evaluate(m, cyl, y, &v);
    double kb, pb, kl, pl;
    mech_body_energy(m, body, y, &kb, &pb);
    mech_point_mass_energy(m, pm, y, &kl, &pl);
    ke = kb + kl - ke0 - ke1;
    pe = pb + pl - pe0 - pe1;
    double stored = v.energy - v0.energy;
    double rhs = Dval + stored - Econv + ke + pe + Dfric + Dleak + Etank;
    tap_diag("run: supplied %.6f J; valve %.6f, oil %.6f, convected %.6f, kinetic %.3e, "
             "potential %.6f, friction %.6f, leakage %.6f, tank %.3e J",
             Esup, Dval, stored, Econv, ke, pe, Dfric, Dleak, Etank);
    tap_close(rhs, Esup, 1e-6, 0,
              "run: supplied %.6f J = dissipated + stored + potential + kinetic %.6f J (%.2e)",
              Esup, rhs, fabs(rhs - Esup) / Esup);
    tap_close(out[iK] - out0[iK], ke, 0, 1e-9, "run: output E_kin = the bodies' kinetic energy");
    tap_close(out[iV] - out0[iV], pe, 1e-12, 1e-9, "run: output E_pot = the bodies' potential "
              "(+%.3f J)", pe);
    tap_close(out[iO], v.energy, 1e-12, 1e-9, "run: output E_oil = the cylinder's stored energy");
    tap_ok(dout < 1e-12 * D.ps * D.qn, "run: output P_supply = the supply bond's e f");
    tap_close(pe, S() * (sin(out[ith]) - sin(10 * PI / 180)), 1e-9, 0,
              "run: potential energy gained g (m_b L/2 + m_L L)(sin theta_end - sin 10 deg)");
    double kff, kff_file = 0, w = 25 * PI / 180 / 7.5;
    double bound = tracking_estimate(10 * PI / 180, 35 * PI / 180, w, &kff);
    mdl_parameter(mm, "k_ff", &kff_file);
    tap_close(kff_file, kff, 1e-12, 0, "run: the file's k_ff %.6f s is 1 / K_v at 22.5 deg", kff);
    tap_ok(err_max <= bound,
           "run: |theta - theta_ref| <= %.4f deg, within the feedforward's mismatch over kp "
           "%.4f deg", err_max * 180 / PI, bound * 180 / PI);
    tap_close(out[ith], 35 * PI / 180, 0, 0.05 * PI / 180,
              "run: at %g s the boom holds 35 deg within 0.05 deg (%.6f deg)", t,
              out[ith] * 180 / PI);
    tap_ok(pmin > D.pt && pmax < D.ps, "run: pressures within the tank and the supply (%.3f .. "
           "%.3f MPa)", pmin / 1e6, pmax / 1e6);
    dae_free(&sol);
    free(bk);
    free(y);
    free(yp);
    free(yq);
    mdl_free(&mm);
}

int main(void)
{
    mdl_model *mm;
    bg_error e = {0};
    bg_error_clear(&e);
    mm = mdl_load(PATH, NULL, 0, &e);
    tap_ok(mm != NULL, "luffing-boom.yaml loads (%s)", mm ? "ok" : e.message);
    if (!mm) return tap_done();
    const char *names[] = {"L_boom", "m_boom", "m_load", "g", "x_A", "z_A", "a_B", "e_B", "bore",
                           "rod", "stroke", "L_min", "V_line", "beta", "c_cyl", "G_cyl", "G_bleed",
                           "p_s",
                           "p_t", "q_n", "dp_n", "u_0", "kp", "ki"};
    const double *want = &D.Lb;
    int same = 1;
    for (int i = 0; i < (int)(sizeof names / sizeof *names); i++) {
        double x;
        if (mdl_parameter(mm, names[i], &x) != BG_OK || fabs(x - want[i]) > 1e-12 * fabs(want[i])) {
            tap_diag("parameter %s: %.17g, the test has %.17g", names[i], x, want[i]);
            same = 0;
        }
    }
    tap_ok(same, "the file's parameters are the test's data");
    mdl_free(&mm);
    check_statics("10*deg", 10 * PI / 180);
    check_statics("35*deg", 35 * PI / 180);
    check_mode();
    check_closed_loop("10*deg");
    check_closed_loop("35*deg");
    check_energy();
    return tap_done();
}
