/* States in motion (bg_modes.h "States in motion", bg_static.h "Steady motion"): the modal
 * analysis linearises a moving state only if it is steady (stays a solution along its own
 * motion), and the static solver's constant rates must give such a state.
 *   - a mass on a central spring in a circular orbit (m Omega^2 r = k (r - L0)): the state
 *     solves the equations at one instant, but its position and velocity turn; the frozen
 *     pencil's modes are not those of small motions about the orbit, so dae_modes_compute
 *     refuses it (and gives the frozen modes on request), and dae_static_solve refuses the rates
 *     of the orbit as a steady motion;
 *   - a rotor on a torsion spring and a damper whose far end turns at a constant rate Omega: the
 *     angles grow, the twist stays (an ignorable coordinate); accepted, with the damped
 *     torsional mode of J s^2 + c s + k = 0 (omega_n = sqrt(k/J), zeta = c / (2 sqrt(k J))). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bg_modes.h"
#include "bg_sparse.h"
#include "bg_static.h"
#include "tap.h"

/* ---- orbit: y = (x, z, vx, vz) ---- */
typedef struct orbit {
    double m, k, L0;
} orbit;

static int orbit_res(void *u, double t, const double *y, const double *yp, double *F)
{
    (void)t;
    const orbit *o = u;
    double r = hypot(y[0], y[1]), f = o->k * (r - o->L0) / r;
    F[0] = yp[0] - y[2];
    F[1] = yp[1] - y[3];
    F[2] = o->m * yp[2] + f * y[0];
    F[3] = o->m * yp[3] + f * y[1];
    return 0;
}

static void test_orbit(void)
{
    orbit O = {.m = 2.0, .k = 800.0, .L0 = 1.0};
    const double W = 10.0, r = O.k * O.L0 / (O.k - O.m * W * W); /* m W^2 r = k (r - L0) */
    double y[4] = {r, 0, 0, W * r}, yp[4] = {0, W * r, -W * W * r, 0}, F[4];
    dae_problem p = {.n = 4, .res = orbit_res, .user = &O};
    orbit_res(&O, 0, y, yp, F);
    double fmax_ = fmax(fmax(fabs(F[0]), fabs(F[1])), fmax(fabs(F[2]), fabs(F[3])));
    dae_modes *M = NULL;
    bg_error err = {0};
    int st = dae_modes_compute(&p, 0.0, y, yp, NULL, &M, &err);
    tap_ok(fmax_ < 1e-9 && st == BG_ERR_ARGUMENT && !M && strstr(err.message, "not steady"),
           "orbit (the state solves F = 0 to %.1e): modes refused, status %d: \"%s\"", fmax_, st,
           err.message);
    dae_modes_options mo;
    dae_modes_options_default(&mo);
    mo.frozen = 1;
    st = dae_modes_compute(&p, 0.0, y, yp, &mo, &M, &err);
    tap_ok(st == BG_OK && dae_modes_count(M) > 0,
           "orbit, options.frozen = 1: the frozen pencil's %d modes on request",
           dae_modes_count(M));
    dae_modes_free(&M);
    /* the rates of the orbit as "steady" rates: refused */
    dae_static_options so;
    dae_static_options_default(&so);
    so.yp_steady = yp;
    double ys[4];
    memcpy(ys, y, sizeof ys);
    dae_static_result res;
    st = dae_static_solve(&p, &so, 0.0, ys, NULL, &res, &err);
    tap_ok(st == BG_ERR_ARGUMENT && strstr(err.message, "no steady motion"),
           "orbit: the static solver refuses the orbit's rates as a steady motion, status %d: "
           "\"%s\"",
           st, err.message);
}

/* The orbit in the frame that turns with it (options.frame): the state is at rest there, and
 * the small motions about the circular orbit of a mass on a central spring, in the rotating
 * frame's radial and tangential coordinates (xi, eta),
 *     m (xi'' - 2 W eta' - W^2 xi) + k xi = 0,   m (eta'' + 2 W xi' - W^2 eta) + (f / r) eta = 0,
 * with the spring's tension f = k (r - L0) = m W^2 r, have m s^2 (m s^2 + k + 3 m W^2) = 0: the
 * epicyclic frequency omega^2 = k/m + 3 W^2 (the frequency of small radial oscillations about a
 * circular orbit: Goldstein, Classical Mechanics, on the stability of circular orbits) and a
 * double zero (the orbit's phase drifting in the frame). */
static sp_csc *plane_rotation(double W)
{
    /* (x, z)' = W (-z, x), (vx, vz)' = W (-vz, vx) */
    double D[16] = {0};
    D[0 + 4 * 1] = -W, D[1 + 4 * 0] = W;
    D[2 + 4 * 3] = -W, D[3 + 4 * 2] = W;
    return sp_csc_from_dense(4, 4, D, 0.0);
}

static void test_orbit_frame(void)
{
    orbit O = {.m = 2.0, .k = 800.0, .L0 = 1.0};
    const double W = 10.0, r = O.k * O.L0 / (O.k - O.m * W * W);
    double y[4] = {r, 0, 0, W * r}, yp[4] = {0, W * r, -W * W * r, 0};
    dae_problem p = {.n = 4, .res = orbit_res, .user = &O};
    sp_csc *S = plane_rotation(W);
    dae_modes_options mo;
    dae_modes_options_default(&mo);
    mo.frame = S;
    dae_modes *M = NULL;
    bg_error err = {0};
    int st = dae_modes_compute(&p, 0.0, y, yp, &mo, &M, &err);
    if (st != BG_OK) tap_diag("%s", err.message);
    double want = sqrt(O.k / O.m + 3 * W * W), got = NAN;
    int ne = -1, nr = -1, nc = -1;
    dae_modes_info(M, &ne, &nr, &nc, NULL, NULL, NULL);
    if (M && ne == 1) got = 2 * 3.14159265358979323846 * dae_modes_get(M, 0)->freq_hz;
    tap_ok(st == BG_OK && ne == 1 && fabs(got - want) < 1e-8 * want,
           "orbit in the co-moving frame: the epicyclic mode %.12g rad/s (sqrt(k/m + 3 W^2) = "
           "%.12g), %d elastic, %d rigid, %d constraint",
           got, want, ne, nr, nc);
    dae_modes_free(&M);
    /* a radius off the orbit: not at rest in the frame, refused */
    double y2[4] = {1.1 * r, 0, 0, 1.1 * W * r}, yp2[4] = {0, 1.1 * W * r, -1.1 * W * W * r, 0};
    st = dae_modes_compute(&p, 0.0, y2, yp2, &mo, &M, &err);
    tap_ok(st == BG_ERR_ARGUMENT && !M && strstr(err.message, "not steady in the co-moving frame"),
           "a radius 10 %% off the orbit: refused in the frame, status %d: \"%s\"", st,
           err.message);
    /* the static solver in the frame finds the orbit from the spring's rest, at rest */
    dae_static_options so;
    dae_static_options_default(&so);
    so.frame = S;
    double ys[4] = {O.L0, 0, 0, 0}, yps[4];
    dae_static_result res;
    st = dae_static_solve(&p, &so, 0.0, ys, yps, &res, &err);
    if (st != BG_OK) tap_diag("%s", err.message);
    double rr = hypot(ys[0], ys[1]), vv = hypot(ys[2], ys[3]);
    tap_ok(st == BG_OK && fabs(rr - r) < 1e-9 * r && fabs(vv - W * r) < 1e-9 * W * r &&
               fabs(yps[2] + W * W * ys[0]) < 1e-9 * W * W * r,
           "static in the frame: radius %.12g (k L0 / (k - m W^2) = %.12g), speed %.12g (W r = "
           "%.12g), y' = S y",
           rr, r, vv, W * r);
    sp_csc_free(&S);
}

/* ---- driven rotor: y = (phi_d, phi, w) ---- */
typedef struct rotor {
    double J, k, c, W;
} rotor;

static int rotor_res(void *u, double t, const double *y, const double *yp, double *F)
{
    (void)t;
    const rotor *q = u;
    F[0] = yp[0] - q->W;
    F[1] = yp[1] - y[2];
    F[2] = q->J * yp[2] + q->k * (y[1] - y[0]) + q->c * (y[2] - q->W);
    return 0;
}

static void test_rotor(void)
{
    rotor q = {.J = 0.5, .k = 200.0, .c = 1.0, .W = 30.0};
    dae_problem p = {.n = 3, .res = rotor_res, .user = &q};
    double y[3] = {0.3, 0.1, 0}, yp[3];
    dae_static_options so;
    dae_static_options_default(&so);
    double yps[3] = {q.W, q.W, 0};
    so.yp_steady = yps;
    dae_static_result res;
    bg_error err = {0};
    int st = dae_static_solve(&p, &so, 0.0, y, yp, &res, &err);
    tap_ok(st == BG_OK && fabs(y[1] - y[0]) < 1e-9 && fabs(y[2] - q.W) < 1e-9 * q.W,
           "driven rotor: the steady motion at %g rad/s is accepted, twist %.1e rad, rate %.12g",
           q.W, y[1] - y[0], y[2]);
    dae_modes *M = NULL;
    st = dae_modes_compute(&p, 0.0, y, yp, NULL, &M, &err);
    double wn = sqrt(q.k / q.J), zeta = q.c / (2 * sqrt(q.k * q.J)), got_w = NAN, got_z = NAN;
    for (int k = 0; M && k < dae_modes_count(M); k++) {
        const dae_mode *md = dae_modes_get(M, k);
        if (md->kind == DAE_MODE_ELASTIC)
            got_w = 2 * 3.14159265358979323846 * md->freq_hz, got_z = md->damping;
    }
    if (st != BG_OK) tap_diag("%s", err.message);
    tap_ok(st == BG_OK && fabs(got_w - wn) < 1e-9 * wn && fabs(got_z - zeta) < 1e-9,
           "driven rotor in steady motion: the torsional mode omega_n = %.10g (sqrt(k/J) = "
           "%.10g), zeta = %.10g (c/(2 sqrt(kJ)) = %.10g)",
           got_w, wn, got_z, zeta);
    dae_modes_free(&M);
}

int main(void)
{
    test_orbit();
    test_orbit_frame();
    test_rotor();
    return tap_done();
}
