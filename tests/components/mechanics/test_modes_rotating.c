/* Modes of a structure in steady rotation, in the co-moving frame (bg_modes.h, "Co-moving
 * frames"; bgr_frame_rotation, bgr_analysis.h), against closed forms and an independent model:
 *   - a point mass on an axial spring (stiffness k, rest length L0) about a fixed centre, in a
 *     circular orbit at rate W: radius r = k L0 / (k - m W^2); in the frame that turns with it
 *     the small motions in the plane have the epicyclic frequency omega^2 = k/m + 3 W^2 (the
 *     frequency of small radial oscillations about a circular orbit: Goldstein, Classical
 *     Mechanics, on the stability of circular orbits; the radial stiffness k, the tangential one
 *     T/r = m W^2 cancelling the centrifugal term, Coriolis coupling the two), across the plane
 *     omega^2 = T / (m r) = W^2 (the tension over the radius; no centrifugal term along the
 *     axis);
 *   - Southwell's rotating cantilever: an Euler-Bernoulli beam clamped at its root to a hub
 *     driven at Omega about an axis normal to the beam. Flapwise (out of the rotation plane)
 *     EI w'''' - (T w')' + rho A w_tt = 0 with the centrifugal tension
 *     T(x) = rho A Omega^2 (L^2 - x^2) / 2; lead-lag (in the plane) the same operator less
 *     rho A Omega^2 w (the centrifugal force's component across the beam as it swings; the
 *     Coriolis coupling with the axial motion vanishes for an axially rigid beam), hence the same
 *     mode shapes and omega_lag^2 = omega_flap^2 - Omega^2 (the equations of the rotating beam as
 *     in Hodges and Rutkowski, "Free-vibration analysis of rotating beams by a variable-order
 *     finite-element method", AIAA J. 19 (1981), whose first flapwise frequencies 3.5160,
 *     4.7973, 7.3604, 13.1702 at gamma = 0, 3, 6, 12 the reference below reproduces). The
 *     reference is computed here another way: a fine Hermite cubic finite-element model of the
 *     flapwise equation (200 elements, consistent mass, geometric stiffness int T N_i' N_j' by
 *     4-point Gauss, LAPACK dsygv), at gamma = Omega sqrt(rho A L^4 / EI) = 0, 3, 6, 12; at
 *     gamma = 0 it is the clamped-free 1.8751^2 sqrt(EI / (rho A L^4)), checked here against the
 *     root of cos b cosh b = -1. The same Hermite model at 4 and 8 elements with the consistent
 *     element's mass (its template and the template's centrifugal terms) is the element's own
 *     discrete model: the element must give its frequencies, so that what is left against the
 *     fine reference is the cubic field's error, not the co-rotational element's.
 * The beam model: a chain of co-rotational elements (mech_beam_chain, consistent and lumped), its
 * root node on a revolute joint to the ground whose drive port a flow source turns at Omega. The
 * steady state comes from bgr_static in the frame (the centrifugal stretch and tension), the
 * modes from bgr_modes in the frame; without the frame both are refused ("not steady"). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bg_sparse.h"
#include "bgr_analysis.h"
#include "bgr_elements.h"
#include "mech_axial.h"
#include "mech_beam.h"
#include "mech_body.h"
#include "mech_parts.h"
#include "tap.h"

static const double PI = 3.14159265358979323846;

void dsygv_(const int *itype, const char *jobz, const char *uplo, const int *n, double *a,
            const int *lda, double *b, const int *ldb, double *w, double *work, const int *lwork,
            int *info, size_t l1, size_t l2);

/* ---- a point mass on an axial spring in orbit ---- */

static void test_orbit_components(void)
{
    const double mass = 2.0, k = 800.0, L0 = 1.0, W = 10.0;
    const double r = k * L0 / (k - mass * W * W);
    bgr_model *m = bgr_model_create("orbit");
    int pm = mech_point_mass(m, 0, "mass", mass, NULL);
    int sup = mech_support(m, 0, "centre", 3);
    int spr = mech_spring(m, 0, "spring", k, 0.0, L0);
    bgr_bond(m, 0, "b0", 3, bgr_port_of(m, sup, 0), bgr_port_of(m, spr, 0), NULL, NULL);
    bgr_bond(m, 0, "b1", 3, bgr_port_of(m, spr, 1), bgr_port_of(m, pm, 0), NULL, NULL);
    int st = bgr_compile(m);
    if (st != BG_OK) {
        tap_diag("%s", bgr_model_error(m)->message);
        tap_ok(0, "orbit model");
        bgr_model_free(&m);
        return;
    }
    /* the orbit, exactly: the mass at (r, 0, 0) moving at W r along y, the spring's d, its
     * tension T = k (r - L0) in the efforts of both bonds; y' = S y (the axis through the
     * origin: c = 0) */
    const double x0[3] = {r, 0, 0}, v0[3] = {0, W * r, 0}, o[3] = {0, 0, 0};
    mech_point_mass_set(m, pm, x0, v0);
    mech_axial_set(m, spr, o, x0);
    double *y = bgr_y0(m), *yp = bgr_yp0(m);
    y[bgr_find_var(m, "orbit/b0/e0")] = y[bgr_find_var(m, "orbit/b1/e0")] = -k * (r - L0);
    y[bgr_find_var(m, "orbit/b1/f1")] = W * r;
    const double axis[3] = {0, 0, 1};
    sp_csc *S = NULL;
    double *c = malloc((size_t)bgr_n(m) * sizeof *c), *F = malloc((size_t)bgr_n(m) * sizeof *F);
    st = bgr_frame_rotation(m, axis, W, NULL, &S, c);
    if (st != BG_OK) tap_diag("%s", bgr_model_error(m)->message);
    memcpy(yp, c, (size_t)bgr_n(m) * sizeof *yp);
    if (st == BG_OK) sp_matvec(S, 1.0, y, 1.0, yp);
    bgr_residual(m, 0.0, y, yp, F);
    double fmax_ = 0;
    for (int i = 0; i < bgr_n(m); i++)
        fmax_ = fmax(fmax_, fabs(F[i]));
    bg_error err = {0};
    dae_modes_options mo;
    dae_modes_options_default(&mo);
    mo.frame = S;
    dae_modes *M = NULL;
    if (st == BG_OK) st = bgr_modes(m, 0.0, NULL, bgr_yp0(m), &mo, &M, &err);
    if (st != BG_OK) tap_diag("%s", err.message);
    /* elastic: the epicyclic in-plane mode sqrt(k/m + 3 W^2) and the out-of-plane swing of the
     * mass on the stretched spring, sqrt(T / (m r)) = W (the tension m W^2 r over the radius) */
    double want[2] = {W, sqrt(k / mass + 3 * W * W)}, got[2] = {NAN, NAN};
    int ne = 0;
    for (int q = 0; M && q < dae_modes_count(M); q++) {
        const dae_mode *md = dae_modes_get(M, q);
        if (md->kind == DAE_MODE_ELASTIC && ne < 2) got[ne++] = 2 * PI * md->freq_hz;
    }
    tap_ok(st == BG_OK && fmax_ < 1e-9 && ne == 2 && fabs(got[0] - want[0]) < 1e-8 * want[0] &&
               fabs(got[1] - want[1]) < 1e-8 * want[1],
           "point mass on a spring in orbit (the state solves F = 0 to %.1e), modes in the "
           "frame from the components' declarations: %.10g, %.10g rad/s (W = %.10g across the "
           "plane, sqrt(k/m + 3 W^2) = %.10g in it)",
           fmax_, got[0], got[1], want[0], want[1]);
    dae_modes_free(&M);
    /* the inertial frame: refused as before */
    st = bgr_modes(m, 0.0, NULL, bgr_yp0(m), NULL, &M, &err);
    tap_ok(st == BG_ERR_ARGUMENT && strstr(err.message, "not steady"),
           "the same state without the frame: refused (%s)", err.message);
    dae_modes_free(&M);
    sp_csc_free(&S);
    free(c);
    free(F);
    bgr_model_free(&m);
}

/* ---- Southwell's rotating cantilever ---- */

/* The reference: lowest nm eigenvalues omega^2 (units EI = rho A = L = 1) of the flapwise
 * rotating Euler-Bernoulli cantilever at rate gamma, by ne Hermite cubic elements. tmpl = 0: the
 * consistent mass; tmpl = 1: the consistent element's discrete model (mech_beam.h, change 4):
 * the template mass rho A h / 17640 [6606 993 2214 -477; ...] and the centrifugal terms of the
 * template's points, which are unit vectors' combinations V = h sum_j a_j u_j (u_j: the chord's
 * and the end triads' axes, tilted by the slopes s_j), so that -mu W^2 |V_radial|^2 / 2 adds
 * W^2 h^3 / 420 (s_a^2 + s_b^2 - 2 s_E^2) / 2 per element (s_E = (w_b - w_a) / h; summed over
 * the three points, mu (sum a) a_j is 42, 42, -84 times rho A h / 17640) to the flapwise
 * energy, and the same less W^2 (the template part of the mass) to the lead-lag one, so that
 * omega_lag^2 = omega_flap^2 - W^2 holds for it too. xs: the ne + 1 node stations on [0, 1]
 * (NULL: uniform). 0 on success. */
static int southwell_reference(double gamma, int ne, const double *xs, int nm, double *w2, int tmpl)
{
    int n = 2 * ne; /* w, w' at nodes 1..ne (node 0 clamped) */
    double *K = calloc((size_t)n * n, sizeof *K), *M = calloc((size_t)n * n, sizeof *M);
    double *ev = malloc((size_t)n * sizeof *ev);
    if (!K || !M || !ev) return 1;
    const double gx[4] = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563,
                          0.8611363115940526},
                 gw[4] = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461,
                          0.3478548451374538};
    for (int e = 0; e < ne; e++) {
        const double h = xs ? xs[e + 1] - xs[e] : 1.0 / ne, x0 = xs ? xs[e] : e * h;
        double ke[4][4] = {{12, 6 * h, -12, 6 * h},
                           {6 * h, 4 * h * h, -6 * h, 2 * h * h},
                           {-12, -6 * h, 12, -6 * h},
                           {6 * h, 2 * h * h, -6 * h, 4 * h * h}};
        double me[4][4] = {{156, 22 * h, 54, -13 * h},
                           {22 * h, 4 * h * h, 13 * h, -3 * h * h},
                           {54, 13 * h, 156, -22 * h},
                           {-13 * h, -3 * h * h, -22 * h, 4 * h * h}};
        const double mt[4][4] = {{6606, 993 * h, 2214, -477 * h},
                                 {993 * h, 262 * h * h, 477 * h, -109 * h * h},
                                 {2214, 477 * h, 6606, -993 * h},
                                 {-477 * h, -109 * h * h, -993 * h, 262 * h * h}};
        double kg[4][4] = {{0}};
        if (tmpl) {
            double ct = gamma * gamma * h * h * h / 420, cE = 2 * ct / (h * h);
            kg[1][1] = kg[3][3] = ct;
            kg[0][0] = kg[2][2] = -cE;
            kg[0][2] = kg[2][0] = cE;
            for (int i = 0; i < 4; i++)
                for (int j = 0; j < 4; j++)
                    me[i][j] = mt[i][j] * 420.0 / 17640;
        }
        for (int g = 0; g < 4; g++) { /* int T N_i' N_j' dx, T = gamma^2 (1 - x^2) / 2 */
            double xi = 0.5 * (gx[g] + 1), x = x0 + xi * h;
            double T = 0.5 * gamma * gamma * (1 - x * x);
            double d[4] = {(-6 * xi + 6 * xi * xi) / h, 1 - 4 * xi + 3 * xi * xi,
                           (6 * xi - 6 * xi * xi) / h, -2 * xi + 3 * xi * xi};
            for (int i = 0; i < 4; i++)
                for (int j = 0; j < 4; j++)
                    kg[i][j] += 0.5 * h * gw[g] * T * d[i] * d[j];
        }
        for (int i = 0; i < 4; i++)
            for (int j = 0; j < 4; j++) {
                int I = 2 * e + i - 2, J = 2 * e + j - 2;
                if (I < 0 || J < 0) continue;
                K[(size_t)J * n + I] += ke[i][j] / (h * h * h) + kg[i][j];
                M[(size_t)J * n + I] += me[i][j] * h / 420;
            }
    }
    /* M x = (1 / omega^2) K x: the lowest frequencies are the largest eigenvalues, accurate
     * to rounding relative to the largest (K x = omega^2 M x directly loses the lowest to the
     * stiffness's condition number, 1e-5 at 200 elements) */
    int itype = 1, info = 0, lwork = -1;
    double wq;
    dsygv_(&itype, "N", "U", &n, M, &n, K, &n, ev, &wq, &lwork, &info, 1, 1);
    lwork = (int)wq;
    double *work = malloc((size_t)lwork * sizeof *work);
    if (work) dsygv_(&itype, "N", "U", &n, M, &n, K, &n, ev, work, &lwork, &info, 1, 1);
    for (int k = 0; k < nm && info == 0 && work; k++)
        w2[k] = 1.0 / ev[n - 1 - k];
    int bad = info != 0 || !work;
    free(work);
    free(K);
    free(M);
    free(ev);
    return bad;
}

/* slender, equal bending stiffness in both planes: r/L = 1e-4 (the rotary inertia moves the
 * frequencies by less than 1e-6; the axial frequency is 4 000 times the first bending one, so
 * the lead-lag's Coriolis coupling with it is below 1e-6 too) */
static const mech_section blade = {
    .E = 2.1e11, .G = 8.1e10, .A = 1e-4, .Iy = 1e-12, .Iz = 1e-12, .J = 1.5e-12, .rho = 7850};

/* The spinning cantilever of n elements (element kind el) along x from the axis (z) at gamma:
 * the three lowest flapwise (z) and lead-lag (y) frequencies, in units of
 * sqrt(EI / (rho A L^4)), into f[0][..] and f[1][..]; the radial force at the root into *root
 * (the hub's reaction along x); jac, method: options.jacobian, options.method (the sparse one
 * with nev = 12). BG_OK or the status (message in err). */
static int spinning_at(int n, const double *xi, int el, double gamma, double f[2][3], double *root,
                       int jac, int method, bg_error *err)
{
    const double L = 1.0, w0 = sqrt(blade.E * blade.Iz / (blade.rho * blade.A)) / (L * L);
    const double W = gamma * w0;
    const double p0[3] = {0, 0, 0}, p1[3] = {L, 0, 0}, up[3] = {0, 0, 1}, axis[3] = {0, 0, 1};
    int nodes[65], elems[64], extra[65];
    for (int k = 0; k <= n; k++)
        extra[k] = k == 0;
    mech_section sec = blade;
    sec.element = el;
    bgr_model *m = bgr_model_create("rotor");
    if (xi)
        mech_beam_chain_at(m, 0, "blade", n, xi, p0, p1, up, &sec, NULL, extra, NULL, nodes, elems);
    else
        mech_beam_chain(m, 0, "blade", n, p0, p1, up, &sec, NULL, extra, NULL, nodes, elems);
    int ground = mech_support(m, 0, "ground", 6);
    int hub = mech_revolute(m, 0, "hub", -1, axis, 1);
    int drive = bgr_Sf(m, 0, "drive", 1, &W);
    bgr_bond(m, 0, "b_ground", 6, bgr_port_of(m, ground, 0), bgr_port_of(m, hub, 0), NULL, NULL);
    bgr_bond(m, 0, "b_root", 6, bgr_port_of(m, hub, 1),
             mech_beam_chain_port(m, nodes, n, extra, 0, 0), NULL, NULL);
    bgr_bond(m, 0, "b_drive", 1, bgr_port_of(m, drive, 0), bgr_port_of(m, hub, 2), NULL, NULL);
    int st = bgr_compile(m);
    if (st != BG_OK) {
        bg_error_raise(err, st, "spinning", "%s", bgr_model_error(m)->message);
        bgr_model_free(&m);
        return st;
    }
    if (xi)
        mech_beam_chain_set_at(m, nodes, n, xi, p0, p1);
    else
        mech_beam_chain_set(m, nodes, n, p0, p1);
    sp_csc *S = NULL;
    double *c = malloc((size_t)bgr_n(m) * sizeof *c);
    st = bgr_frame_rotation(m, axis, W, NULL, &S, c);
    if (st != BG_OK) bg_error_raise(err, st, "spinning", "%s", bgr_model_error(m)->message);
    dae_static_options so;
    dae_static_options_default(&so);
    so.frame = S;
    so.yp_steady = c;
    dae_static_result res;
    if (st == BG_OK) st = bgr_static(m, &so, 0.0, &res, err);
    int ri = bgr_find_var(m, "rotor/b_ground/e0");
    *root = ri >= 0 ? fabs(bgr_y0(m)[ri]) : NAN;
    dae_modes_options mo;
    dae_modes_options_default(&mo);
    mo.frame = S;
    mo.jacobian = jac;
    mo.method = method;
    mo.nev = 12;
    dae_modes *M = NULL;
    if (st == BG_OK) st = bgr_modes(m, 0.0, NULL, bgr_yp0(m), &mo, &M, err);
    int N = bgr_n(m), nf[2] = {0, 0}, nb = 0;
    double *re = malloc((size_t)N * sizeof *re), *im = malloc((size_t)N * sizeof *im);
    for (int k = 0; st == BG_OK && k < dae_modes_count(M); k++) { /* ascending */
        const dae_mode *md = dae_modes_get(M, k);
        if (md->kind != DAE_MODE_ELASTIC) continue;
        dae_modes_vector(M, k, re, im);
        double s[3] = {0, 0, 0};
        for (int j = 1; j <= n; j++) {
            int v = mech_body_var(m, nodes[j], 'x');
            for (int q = 0; q < 3; q++)
                s[q] += re[v + q] * re[v + q] + im[v + q] * im[v + q];
        }
        int cls = s[2] > s[0] && s[2] > s[1] ? 0 : s[1] > s[0] && s[1] > s[2] ? 1 : -1;
        if (cls < 0) continue; /* axial, torsional */
        if (gamma == 0) {      /* equal in both planes: the pairs in order, whatever their mix */
            if (nb < 6) f[nb % 2][nb / 2] = md->freq_hz * 2 * PI / w0, nb++;
            nf[0] = nf[1] = nb / 2;
        } else if (nf[cls] < 3) {
            f[cls][nf[cls]++] = md->freq_hz * 2 * PI / w0;
        }
    }
    if (st == BG_OK && (nf[0] < 3 || nf[1] < 3))
        st = bg_error_raise(err, BG_ERR_CALLBACK, "spinning",
                            "%d flapwise and %d lead-lag modes found, 3 of each expected", nf[0],
                            nf[1]);
    free(re);
    free(im);
    dae_modes_free(&M);
    sp_csc_free(&S);
    free(c);
    bgr_model_free(&m);
    return st;
}

static int spinning(int n, int el, double gamma, double f[2][3], double *root, int jac, int method,
                    bg_error *err)
{
    return spinning_at(n, NULL, el, gamma, f, root, jac, method, err);
}

static void test_southwell(void)
{
    const double gammas[4] = {0, 3, 6, 12};
    double ref[4][2][3];
    int ok = 1;
    for (int g = 0; g < 4; g++) {
        double w2[3];
        ok &= southwell_reference(gammas[g], 200, NULL, 3, w2, 0) == 0;
        for (int k = 0; k < 3; k++) {
            ref[g][0][k] = sqrt(w2[k]);
            ref[g][1][k] = sqrt(w2[k] - gammas[g] * gammas[g]);
        }
        tap_diag("reference gamma = %2g: flapwise %.7f %.7f %.7f, lead-lag %.7f %.7f %.7f",
                 gammas[g], ref[g][0][0], ref[g][0][1], ref[g][0][2], ref[g][1][0], ref[g][1][1],
                 ref[g][1][2]);
    }
    /* the reference at rest against the closed form (1.8751..)^2 */
    double lo = 1.0, hi = 2.5;
    for (int it = 0; it < 200; it++) {
        double mid = 0.5 * (lo + hi);
        if ((cos(mid) * cosh(mid) + 1 > 0) == (cos(lo) * cosh(lo) + 1 > 0))
            lo = mid;
        else
            hi = mid;
    }
    double b1 = 0.5 * (lo + hi);
    tap_ok(ok && fabs(ref[0][0][0] - b1 * b1) < 1e-7 * b1 * b1,
           "reference at gamma = 0: %.10f, (beta_1 L)^2 = %.10f (beta_1 L = %.6f)", ref[0][0][0],
           b1 * b1, b1);
    const int ns[2] = {8, 16};
    const int els[3] = {MECH_BEAM_CONSISTENT, MECH_BEAM_LUMPED, MECH_BEAM_QUARTIC};
    const char *elname[3] = {"consistent", "lumped", "quartic"};
    /* [element][n]: the largest errors, at gamma = 12: the consistent element's first lead-lag
     * mode, 4.4e-4 and 2.8e-5 (the cubic field's, below), the lumped one's third modes, 5.6e-2
     * and 1.5e-2 */
    const double tol[3][2] = {{5e-4, 3e-5}, {7e-2, 2e-2}, {1e-4, 1e-5}};
    for (int e = 0; e < 3; e++)
        for (int i = 0; i < 2; i++)
            for (int g = 0; g < 4; g++) {
                double f[2][3], root = NAN;
                bg_error err = {0};
                int st = spinning(ns[i], els[e], gammas[g], f, &root, DAE_MODES_JAC_AUTO,
                                  DAE_MODES_AUTO, &err);
                double worst = 0, er[2][3];
                for (int p = 0; p < 2; p++)
                    for (int k = 0; k < 3; k++) {
                        er[p][k] = st == BG_OK ? f[p][k] / ref[g][p][k] - 1 : NAN;
                        worst = fmax(worst, fabs(er[p][k]));
                    }
                if (st != BG_OK) tap_diag("%s", err.message);
                tap_ok(st == BG_OK && worst < tol[e][i],
                       "%s, %2d elements, gamma = %2g: relative errors flapwise %+.1e %+.1e "
                       "%+.1e, lead-lag %+.1e %+.1e %+.1e (below %g)",
                       elname[e], ns[i], gammas[g], er[0][0], er[0][1], er[0][2], er[1][0],
                       er[1][1], er[1][2], tol[e][i]);
                if (gammas[g] == 12 && ns[i] == 8) {
                    /* the steady state: the root carries the blade's centripetal force
                     * m Omega^2 L / 2 (to the stretch, 1e-7) */
                    double w0 = sqrt(blade.E * blade.Iz / (blade.rho * blade.A));
                    double Wr = 12 * w0, want = blade.rho * blade.A * Wr * Wr / 2;
                    tap_ok(fabs(root - want) < 1e-5 * want,
                           "%s, steady in the frame at gamma = 12: root force %.8g N, rho A "
                           "Omega^2 L^2 / 2 = %.8g N",
                           elname[e], root, want);
                }
            }
    /* The element against its own discrete model at gamma = 12 (southwell_reference, tmpl = 1:
     * the cubic field with the exact centrifugal tension T(x), the template mass and its
     * centrifugal terms), both planes: the same frequencies up to the effects the model leaves
     * out (the axial stretch and the rotary inertia, r / L = 1e-4). The element's points carry
     * the field's foreshortening (mech_beam.h, change 3), so that the centrifugal loads do their
     * work on the arc's shortening inside each element, the tension's variation along it
     * (without it: 3.3e-4 apart at 4 elements, 9e-6 at 8). What is left at 8 elements against
     * the continuum is the discrete model's own error. */
    for (int i = 0; i < 2; i++) {
        const int nd = 4 << i;
        double w2d[3], fd[2][3], f[2][3], root = NAN, dmax = 0, dis[2][3];
        int okd = southwell_reference(12, nd, NULL, 3, w2d, 1) == 0;
        for (int k = 0; k < 3; k++) {
            fd[0][k] = sqrt(w2d[k]);
            fd[1][k] = sqrt(w2d[k] - 144);
        }
        bg_error err = {0};
        int st = spinning(nd, MECH_BEAM_CONSISTENT, 12, f, &root, DAE_MODES_JAC_AUTO,
                          DAE_MODES_AUTO, &err);
        for (int p = 0; p < 2; p++)
            for (int k = 0; k < 3; k++) {
                dis[p][k] = fd[p][k] / ref[3][p][k] - 1;
                dmax = fmax(dmax, fabs(f[p][k] / fd[p][k] - 1));
            }
        if (st != BG_OK) tap_diag("%s", err.message);
        tap_ok(okd && st == BG_OK && dmax < 5e-6,
               "consistent, %d elements, gamma = 12: the six frequencies equal those of the "
               "cubic Hermite model with the exact centrifugal tension and the same mass to "
               "%.1e (below 5e-6); that model's errors: flapwise %+.1e %+.1e %+.1e, lead-lag "
               "%+.1e %+.1e %+.1e",
               nd, dmax, dis[0][0], dis[0][1], dis[0][2], dis[1][0], dis[1][1], dis[1][2]);
    }
    /* the problem's own Jacobian in the frame: the lumped element's is exact in motion (the
     * same modes as by differences), the consistent element's leaves out terms of the inertia
     * loads in motion (mech_beam.h), which the frame's linearisation needs */
    for (int e = 0; e < 2; e++) {
        double fa[2][3], fd[2][3], root;
        bg_error err = {0};
        int st = spinning(8, els[e], 12, fa, &root, DAE_MODES_JAC_PROBLEM, DAE_MODES_AUTO, &err);
        if (st == BG_OK)
            st =
                spinning(8, els[e], 12, fd, &root, DAE_MODES_JAC_DIFFERENCES, DAE_MODES_AUTO, &err);
        double dmax = 0;
        for (int p = 0; p < 2; p++)
            for (int k = 0; k < 3; k++)
                dmax = fmax(dmax, fabs(fa[p][k] / fd[p][k] - 1));
        if (st != BG_OK) tap_diag("%s", err.message);
        if (e == 1)
            tap_ok(st == BG_OK && dmax < 1e-6,
                   "lumped, 8 elements, gamma = 12: the problem's Jacobian and differences agree "
                   "to %.1e",
                   dmax);
        else
            tap_diag("consistent, 8 elements, gamma = 12: the problem's Jacobian against "
                     "differences: %.1e (terms left out in motion)",
                     dmax);
    }
}

/* A graded chain (mech_beam_chain_at), shorter elements at the clamped root where a spinning
 * blade's boundary layer is (width sqrt(2) L / gamma: 0.12 L at gamma = 12, one element of
 * eight): node stations xi_k = (k / n)^p with p = 1.1 (root element 0.62 of the uniform length,
 * tip element 1.12), one grading for every gamma. The rule and p were chosen on the element's
 * discrete model (southwell_reference, tmpl = 1, with these stations), scanning p = 1 .. 2 by
 * 0.05 and geometric ratios 1 .. 1.5: the largest error over the six frequencies at gamma = 0,
 * 3, 6, 12 falls from 4.4e-4 (uniform) to 2.2e-4 at p = 1.1 .. 1.15 (geometric: 2.3e-4 at
 * ratio 1.05; the root element alone shortened to 0.6 of the others: 1.9e-4, but 1.3e-4 at
 * rest); no station set reaches 1e-4 at eight elements (a free minimax search over the seven
 * inner stations from 12 starts: 1.29e-4 at best), the third modes at gamma = 12 (-1.4e-4
 * uniform, the tension term the template does not cancel, docs/beam.md) getting worse as the
 * tip coarsens. Checked here: the graded chain gives the frequencies of its own discrete model
 * (node masses and element lengths from the stations), and at rest the continuum's within
 * 1e-4; the errors against the continuum at gamma = 3 and 12 are printed. */
static void test_graded(void)
{
    const int n = 8;
    const double gammas[4] = {0, 3, 6, 12};
    double xi[9];
    for (int k = 0; k <= n; k++)
        xi[k] = pow((double)k / n, 1.1);
    for (int g = 0; g < 4; g++) {
        double w2[3] = {0}, w2d[3] = {0}, f[2][3], root, er[2][3], dmax = 0, worst = 0;
        int ok = southwell_reference(gammas[g], 200, NULL, 3, w2, 0) == 0 &&
                 southwell_reference(gammas[g], n, xi, 3, w2d, 1) == 0;
        bg_error err = {0};
        int st = spinning_at(n, xi, MECH_BEAM_CONSISTENT, gammas[g], f, &root, DAE_MODES_JAC_AUTO,
                             DAE_MODES_AUTO, &err);
        if (st != BG_OK) tap_diag("%s", err.message);
        for (int p = 0; p < 2; p++)
            for (int k = 0; k < 3; k++) {
                double g2 = p ? gammas[g] * gammas[g] : 0.0;
                er[p][k] = st == BG_OK ? f[p][k] / sqrt(w2[k] - g2) - 1 : NAN;
                worst = fmax(worst, fabs(er[p][k]));
                dmax = fmax(dmax, st == BG_OK ? fabs(f[p][k] / sqrt(w2d[k] - g2) - 1) : INFINITY);
            }
        tap_ok(ok && st == BG_OK && dmax < 5e-6,
               "graded (k/8)^1.1, gamma = %2g: the six frequencies equal those of the graded "
               "cubic Hermite model with the same mass to %.1e (below 5e-6)",
               gammas[g], dmax);
        if (gammas[g] == 0)
            tap_ok(st == BG_OK && worst < 1e-4,
                   "graded (k/8)^1.1 at rest: relative errors %+.1e %+.1e %+.1e in both planes "
                   "(below 1e-4; uniform: 1.7e-6)",
                   er[0][0], er[0][1], er[0][2]);
        else
            tap_diag("graded (k/8)^1.1, gamma = %2g: relative errors flapwise %+.1e %+.1e %+.1e, "
                     "lead-lag %+.1e %+.1e %+.1e",
                     gammas[g], er[0][0], er[0][1], er[0][2], er[1][0], er[1][1], er[1][2]);
    }
    /* the uniform stations k / n through mech_beam_chain_at: the uniform chain's frequencies */
    double uni[9], fa[2][3], fu[2][3], root, dmax = 0;
    for (int k = 0; k <= n; k++)
        uni[k] = (double)k / n;
    bg_error err = {0};
    int st = spinning_at(n, uni, MECH_BEAM_CONSISTENT, 12, fa, &root, DAE_MODES_JAC_AUTO,
                         DAE_MODES_AUTO, &err);
    if (st == BG_OK)
        st = spinning(n, MECH_BEAM_CONSISTENT, 12, fu, &root, DAE_MODES_JAC_AUTO, DAE_MODES_AUTO,
                      &err);
    for (int p = 0; p < 2; p++)
        for (int k = 0; k < 3; k++)
            dmax = fmax(dmax, fabs(fa[p][k] / fu[p][k] - 1));
    if (st != BG_OK) tap_diag("%s", err.message);
    tap_ok(st == BG_OK && dmax < 1e-10,
           "stations k/8 through mech_beam_chain_at: the uniform chain's six frequencies at "
           "gamma = 12 to %.1e",
           dmax);
    /* bad stations: refused, nothing made */
    const double p0[3] = {0, 0, 0}, p1[3] = {1, 0, 0}, up[3] = {0, 0, 1};
    const double bad[4][3] = {{0, 0.5, 0.9}, {0, 1, 1}, {0.1, 0.5, 1}, {0, NAN, 1}};
    const char *want[4] = {"xi[2] = 0.9", "strictly increasing", "xi[0] = 0.1", "xi"};
    for (int q = 0; q < 5; q++) {
        bgr_model *m = bgr_model_create("bad");
        int nodes[3], elems[2];
        st = mech_beam_chain_at(m, 0, "blade", 2, q < 4 ? bad[q] : NULL, p0, p1, up, &blade, NULL,
                                NULL, NULL, nodes, elems);
        const char *msg = bgr_model_error(m)->message;
        tap_ok(st == BG_ERR_ARGUMENT && strstr(msg, q < 4 ? want[q] : "NULL") &&
                   strstr(msg, "blade"),
               "mech_beam_chain_at with bad stations refused: %s", msg);
        bgr_model_free(&m);
    }
}

/* The sparse method (ARPACK, nev = 12) in the frame: the same modes as the dense one. */
static void test_sparse(void)
{
    double fd[2][3], fs[2][3], root;
    bg_error err = {0};
    int st =
        spinning(16, MECH_BEAM_CONSISTENT, 6, fd, &root, DAE_MODES_JAC_AUTO, DAE_MODES_DENSE, &err);
    if (st == BG_OK)
        st = spinning(16, MECH_BEAM_CONSISTENT, 6, fs, &root, DAE_MODES_JAC_AUTO, DAE_MODES_SPARSE,
                      &err);
    double dmax = 0;
    for (int p = 0; p < 2; p++)
        for (int k = 0; k < 3; k++)
            dmax = fmax(dmax, fabs(fs[p][k] / fd[p][k] - 1));
    if (st != BG_OK) tap_diag("%s", err.message);
    tap_ok(st == BG_OK && dmax < 1e-8,
           "consistent, 16 elements, gamma = 6: the sparse method's six bending modes equal the "
           "dense ones to %.1e",
           dmax);
}

/* What the frame cannot make steady stays refused: the cantilever spinning about z under
 * gravity along -x (a load that does not turn with the frame), and bad arguments of
 * bgr_frame_rotation. */
static void test_refusals(void)
{
    const int n = 4;
    const double p0[3] = {0, 0, 0}, p1[3] = {1, 0, 0}, up[3] = {0, 0, 1}, axis[3] = {0, 0, 1};
    const double g[3] = {-9.81, 0, 0}, W = 3.0;
    int nodes[5], elems[4], extra[5] = {1, 0, 0, 0, 0};
    mech_section sec = blade;
    bgr_model *m = bgr_model_create("rotor");
    mech_beam_chain(m, 0, "blade", n, p0, p1, up, &sec, g, extra, NULL, nodes, elems);
    int ground = mech_support(m, 0, "ground", 6);
    int hub = mech_revolute(m, 0, "hub", -1, axis, 1);
    int drive = bgr_Sf(m, 0, "drive", 1, &W);
    bgr_bond(m, 0, "b_ground", 6, bgr_port_of(m, ground, 0), bgr_port_of(m, hub, 0), NULL, NULL);
    bgr_bond(m, 0, "b_root", 6, bgr_port_of(m, hub, 1),
             mech_beam_chain_port(m, nodes, n, extra, 0, 0), NULL, NULL);
    bgr_bond(m, 0, "b_drive", 1, bgr_port_of(m, drive, 0), bgr_port_of(m, hub, 2), NULL, NULL);
    int st = bgr_compile(m);
    mech_beam_chain_set(m, nodes, n, p0, p1);
    sp_csc *S = NULL;
    double *c = malloc((size_t)bgr_n(m) * sizeof *c);
    if (st == BG_OK) st = bgr_frame_rotation(m, axis, W, NULL, &S, c);
    dae_static_options so;
    dae_static_options_default(&so);
    so.frame = S;
    so.yp_steady = c;
    dae_static_result res;
    bg_error err = {0};
    if (st == BG_OK) st = bgr_static(m, &so, 0.0, &res, &err);
    tap_ok(st == BG_ERR_ARGUMENT && strstr(err.message, "no steady motion"),
           "gravity across the axis: no state at rest in the frame, refused (status %d: %s)", st,
           err.message);
    /* the modes at the assembled state with the frame's rates: not steady, refused */
    double *yp = bgr_yp0(m);
    memcpy(yp, c, (size_t)bgr_n(m) * sizeof *yp);
    sp_matvec(S, 1.0, bgr_y0(m), 1.0, yp);
    dae_modes_options mo;
    dae_modes_options_default(&mo);
    mo.frame = S;
    dae_modes *M = NULL;
    st = bgr_modes(m, 0.0, NULL, yp, &mo, &M, &err);
    tap_ok(st == BG_ERR_ARGUMENT && !M && strstr(err.message, "not steady in the co-moving frame"),
           "its modes in the frame: refused (status %d: %s)", st, err.message);
    const double zero[3] = {0, 0, 0};
    sp_csc *S2 = NULL;
    st = bgr_frame_rotation(m, zero, W, NULL, &S2, NULL);
    tap_ok(st == BG_ERR_ARGUMENT && !S2 && strstr(bgr_model_error(m)->message, "axis"),
           "bgr_frame_rotation with a zero axis: status %d: %s", st, bgr_model_error(m)->message);
    mo.jacobian = 7;
    st = bgr_modes(m, 0.0, NULL, yp, &mo, &M, &err);
    tap_ok(st == BG_ERR_ARGUMENT && strstr(err.message, "jacobian = 7"),
           "options.jacobian out of range: status %d: %s", st, err.message);
    sp_csc_free(&S);
    free(c);
    bgr_model_free(&m);
}

int main(void)
{
    test_orbit_components();
    test_southwell();
    test_graded();
    test_sparse();
    test_refusals();
    return tap_done();
}
