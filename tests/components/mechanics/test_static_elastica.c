/* The static solver (bg_static.h) on the elastica: a cantilever of length L under a dead tip
 * load P (downwards, clamped horizontal) with P L^2 / (E I) = k up to 10, from the defaults
 * (no settings), against the closed form of the elastica, and the solver's counts.
 *
 * Reference (independent of the program): EI theta'' = -P cos theta (theta the slope below the
 * horizontal), theta(0) = 0, theta'(L) = 0; the first integral theta'^2 = 2 (P/EI) (sin theta_t
 * - sin theta) gives the tip slope theta_t from
 *     sqrt(k) = sqrt(2) int_0^sqrt(sin theta_t) du / cos theta,  sin theta = sin theta_t - u^2
 * (the elliptic integral of the elastica, its endpoint singularity removed by u), and the tip
 *     x_t / L = sqrt(2 sin theta_t / k),
 *     z_t / L = -sqrt(2 / k) int_0^sqrt(sin theta_t) sin theta / cos theta du
 * (Timoshenko and Gere, Theory of Elastic Stability, 1961, sec. 2.7; Frisch-Fay, Flexible Bars,
 * 1962). The integrals by composite Gauss-Legendre (5 points, 400 panels: smooth integrands),
 * theta_t by bisection. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "bgr_analysis.h"
#include "bgr_elements.h"
#include "mech_beam.h"
#include "mech_beam_chain.h"
#include "mech_body.h"
#include "mech_parts.h"
#include "tap.h"

static const mech_section steel = {
    .E = 2.1e11, .G = 8.1e10, .A = 1e-4, .Iy = 1.6e-9, .Iz = 8.33e-10, .J = 1.4e-9, .rho = 7850};

static double seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* int_0^U f(u) du for f = 1 / cos theta (which 0) or sin theta / cos theta (which 1). */
static double elastica_int(double st, int which)
{
    static const double gx[5] = {-0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831,
                                 0.9061798459386640},
                        gw[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889,
                                 0.4786286704993665, 0.2369268850561891};
    const int P = 400;
    double U = sqrt(st), h = U / P, sum = 0;
    for (int p = 0; p < P; p++)
        for (int g = 0; g < 5; g++) {
            double u = h * (p + 0.5 + 0.5 * gx[g]), s = st - u * u, c = sqrt(1.0 - s * s);
            sum += 0.5 * h * gw[g] * (which ? s / c : 1.0 / c);
        }
    return sum;
}

/* The tip (x, z) / L of the elastica under k = P L^2 / EI. */
static void elastica_tip(double k, double *xt, double *zt)
{
    double lo = 0, hi = 1.0; /* sin theta_t */
    for (int it = 0; it < 100; it++) {
        double st = 0.5 * (lo + hi);
        if (sqrt(2.0) * elastica_int(st, 0) < sqrt(k))
            lo = st;
        else
            hi = st;
    }
    double st = 0.5 * (lo + hi);
    *xt = sqrt(2 * st / k);
    *zt = -sqrt(2 / k) * elastica_int(st, 1);
}

/* A cantilever of n elements along x, clamped at node 0, the dead load (0, 0, -P) at the tip. */
static bgr_model *cantilever(int n, double L, double P, const mech_section *sec, int *nodes)
{
    const double p0[3] = {0, 0, 0}, p1[3] = {L, 0, 0}, up[3] = {0, 0, 1};
    int elems[128], extra[129];
    for (int k = 0; k <= n; k++)
        extra[k] = k == 0 || k == n;
    bgr_model *m = bgr_model_create("cant");
    mech_beam_chain(m, 0, "beam", n, p0, p1, up, sec, NULL, extra, NULL, nodes, elems);
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

/* Static solve of the elastica k with n elements of section sec (NULL: steel; o NULL: the
 * defaults); the status, the tip error / L against the closed form into *e, the counts into *r,
 * the message into msg. */
static int solve_sec(int n, double k, const mech_section *sec, const dae_static_options *o,
                     double *e, dae_static_result *r, char *msg, size_t size)
{
    const double L = 1.0;
    int nodes[129];
    if (!sec) sec = &steel;
    bgr_model *m = cantilever(n, L, k * sec->E * sec->Iz / (L * L), sec, nodes);
    if (!m) return -1;
    bg_error err = {0};
    int st = bgr_static(m, o, 0.0, r, &err);
    if (msg) snprintf(msg, size, "%s", st == BG_OK ? "" : err.message);
    double xt, zt;
    elastica_tip(k, &xt, &zt);
    const double *tip = bgr_y0(m) + mech_body_var(m, nodes[n], 'x');
    *e = hypot(tip[0] - xt * L, tip[2] - zt * L) / L;
    bgr_model_free(&m);
    return st;
}

static int solve(int n, double k, const dae_static_options *o, double *e, dae_static_result *r,
                 char *msg, size_t size)
{
    return solve_sec(n, k, NULL, o, e, r, msg, size);
}

static void test_reference(void)
{
    /* small loads: the linear tip deflection k/3 and shortening k^2/15 (to the next order) */
    double xt, zt;
    elastica_tip(1e-3, &xt, &zt);
    tap_ok(fabs(-zt - 1e-3 / 3) < 1e-9 && fabs(1 - xt - 1e-6 / 15) < 1e-10,
           "elastica closed form at k = 1e-3: z = %.9f (k/3 = %.9f), 1 - x = %.3e (k^2/15 = "
           "%.3e)",
           zt, -1e-3 / 3, 1 - xt, 1e-6 / 15);
}

static void test_defaults(void)
{
    const double ks[2] = {5.0, 10.0};
    for (int i = 0; i < 2; i++) {
        double e = NAN, t0 = seconds();
        dae_static_result r;
        char msg[1024];
        int st = solve(64, ks[i], NULL, &e, &r, msg, sizeof msg);
        double dt = seconds() - t0;
        if (st != BG_OK) tap_diag("%s", msg);
        tap_ok(st == BG_OK && e < 1e-3 && r.factorizations < 200,
               "elastica k = %g, 64 elements, default options: tip within %.1e L of the closed "
               "form; %ld steps (%ld rejected), %ld Newton iterations, %ld factorizations "
               "(< 200), %.3f s",
               ks[i], e, r.steps, r.rejected, r.newton_iters, r.factorizations, dt);
    }
}

/* an axially stiff section (E A = 1e10 N, E A L^2 / E I = 5.7e7) at 8 elements: the step
 * budget of the defaults (400) ran out at a load factor of 0.19 before */
static void test_stiff_axial(void)
{
    mech_section sec = steel;
    sec.A = 1e10 / sec.E;
    double e;
    dae_static_result r;
    char msg[1024];
    int st = solve_sec(8, 10.0, &sec, NULL, &e, &r, msg, sizeof msg);
    if (st != BG_OK) tap_diag("%s", msg);
    tap_ok(st == BG_OK && e < 1.5e-2,
           "elastica k = 10, E A = 1e10 N, 8 elements, default options: tip within %.1e L "
           "(lumped, 8 elements); %ld steps (%ld rejected), %ld factorizations",
           e, r.steps, r.rejected, r.factorizations);
}

static void test_no_continuation(void)
{
    dae_static_options o;
    dae_static_options_default(&o);
    o.continuation = 0;
    const double ks[2] = {0.1, 1.0};
    for (int i = 0; i < 2; i++) {
        double e = NAN;
        dae_static_result r;
        char msg[1024];
        int st = solve(32, ks[i], &o, &e, &r, msg, sizeof msg);
        if (st != BG_OK) tap_diag("%s", msg);
        tap_ok(st == BG_OK && e < 2e-3,
               "elastica k = %g, 32 elements, continuation = 0: tip within %.1e L; %ld steps, "
               "%ld factorizations",
               ks[i], e, r.steps, r.factorizations);
    }
}

static void test_messages(void)
{
    /* the step budget ends the run: the message says so, and blames no limit point */
    dae_static_options o;
    dae_static_options_default(&o);
    o.max_steps = 2;
    o.dlambda = 0.05;
    double e;
    dae_static_result r;
    char msg[1024];
    int st = solve(16, 10.0, &o, &e, &r, msg, sizeof msg);
    tap_ok(st == DAE_TOO_MUCH_WORK && strstr(msg, "max_steps = 2") && !strstr(msg, "limit point") &&
               r.lambda > 0 && r.lambda < 1,
           "max_steps = 2 at k = 10: DAE_TOO_MUCH_WORK, the message names the budget and no "
           "limit point: \"%s\"",
           msg);
}

int main(void)
{
    test_reference();
    test_defaults();
    test_stiff_axial();
    test_no_continuation();
    test_messages();
    return tap_done();
}
