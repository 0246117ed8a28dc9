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
    test_rotor();
    return tap_done();
}
