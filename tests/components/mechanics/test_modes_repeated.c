/* Repeated eigenvalues in the sparse modal analysis (bg_modes.h, DAE_MODES_SPARSE): every mode
 * of a multiple eigenvalue is returned, once.
 *   - a cantilever of a section with equal bending stiffness in both planes (I_y = I_z): each
 *     bending frequency is double; the lowest modes against the Euler-Bernoulli clamped-free
 *     coefficients beta_n L = 1.875104, 4.694091, 7.854757 (lumped masses: within the
 *     discretisation error of 32 elements, checked against the dense method on the same model);
 *   - two identical cantilevers in one model (I_y != I_z): every frequency of one is double,
 *     and the sparse method's nev lowest are the dense method's nev lowest, pairs included. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bgr_analysis.h"
#include "bgr_elements.h"
#include "mech_beam.h"
#include "mech_beam_chain.h"
#include "mech_body.h"
#include "mech_parts.h"
#include "tap.h"

static const double PI = 3.14159265358979323846;

/* ncant cantilevers of n elements along x, side by side in y, clamped at node 0. */
static bgr_model *cantilevers(int ncant, int n, double L, const mech_section *sec)
{
    const double up[3] = {0, 0, 1};
    bgr_model *m = bgr_model_create("cant");
    int nodes[2][65], elems[64], extra[65];
    for (int k = 0; k <= n; k++)
        extra[k] = k == 0;
    for (int b = 0; b < ncant; b++) {
        const double p0[3] = {0, 0.5 * b, 0}, p1[3] = {L, 0.5 * b, 0};
        char name[16], cl[16], bn[16];
        snprintf(name, sizeof name, "beam%d", b);
        snprintf(cl, sizeof cl, "clamp%d", b);
        snprintf(bn, sizeof bn, "b_clamp%d", b);
        mech_beam_chain(m, 0, name, n, p0, p1, up, sec, NULL, extra, NULL, nodes[b], elems);
        int clamp = mech_support(m, 0, cl, 6);
        bgr_bond(m, 0, bn, 6, bgr_port_of(m, clamp, 0),
                 mech_beam_chain_port(m, nodes[b], n, extra, 0, 0), NULL, NULL);
    }
    if (bgr_compile(m) != BG_OK) {
        tap_diag("cantilevers: %s", bgr_model_error(m)->message);
        bgr_model_free(&m);
        return NULL;
    }
    for (int b = 0; b < ncant; b++) {
        const double p0[3] = {0, 0.5 * b, 0}, p1[3] = {L, 0.5 * b, 0};
        mech_beam_chain_set(m, nodes[b], n, p0, p1);
    }
    return m;
}

/* The elastic frequencies (rad/s, increasing) of m by method; their count, -1 on failure. */
static int freqs(bgr_model *m, int method, int nev, double *w, int cap)
{
    dae_modes_options o;
    dae_modes_options_default(&o);
    o.method = method;
    o.nev = nev;
    dae_modes *M = NULL;
    bg_error e = {0};
    int st = bgr_modes(m, 0.0, NULL, NULL, &o, &M, &e);
    if (st != BG_OK) {
        tap_diag("modes (method %d): %s", method, e.message);
        dae_modes_free(&M);
        return -1;
    }
    int k = 0;
    for (int i = 0; i < dae_modes_count(M) && k < cap; i++) {
        const dae_mode *md = dae_modes_get(M, i);
        if (md->kind == DAE_MODE_ELASTIC) w[k++] = 2 * PI * md->freq_hz;
    }
    dae_modes_free(&M);
    return k;
}

/* The sparse method's nev lowest against the dense method's: count and largest relative
 * difference. */
static int compare(bgr_model *m, int nev, double *worst, int *nsparse)
{
    double ws[64], wd[1024];
    *nsparse = freqs(m, DAE_MODES_SPARSE, nev, ws, 64);
    int nd = freqs(m, DAE_MODES_DENSE, 20, wd, 1024);
    *worst = INFINITY;
    if (*nsparse != nev || nd < nev) return 0;
    *worst = 0;
    for (int k = 0; k < nev; k++)
        *worst = fmax(*worst, fabs(ws[k] - wd[k]) / wd[k]);
    return 1;
}

static void test_symmetric_section(void)
{
    const mech_section sec = {.E = 2.1e11,
                              .G = 8.1e10,
                              .A = 1e-4,
                              .Iy = 8.33e-10,
                              .Iz = 8.33e-10,
                              .J = 1.4e-9,
                              .rho = 7850};
    const double L = 1.0, beta[3] = {1.875104, 4.694091, 7.854757};
    const int n = 32, nev = 20;
    bgr_model *m = cantilevers(1, n, L, &sec);
    if (!m) {
        tap_ok(0, "symmetric section: model");
        return;
    }
    double w[64];
    int k = freqs(m, DAE_MODES_SPARSE, nev, w, 64);
    double c = sqrt(sec.E * sec.Iz / (sec.rho * sec.A * L * L * L * L)), worst = 0;
    /* lumped masses at 32 elements: about 0.45 (beta_n L / n)^2 / 12 .. (test_statics_modes) */
    const double lim[3] = {1e-3, 3e-3, 5e-3};
    int within = k >= 6;
    for (int j = 0; j < 6 && k >= 6; j++) {
        double want = beta[j / 2] * beta[j / 2] * c, e = fabs(w[j] - want) / want;
        worst = fmax(worst, e);
        within &= e < lim[j / 2];
        if (j % 2) within &= fabs(w[j] - w[j - 1]) <= 1e-8 * w[j];
    }
    tap_ok(k == nev && within,
           "symmetric section, %d elements, sparse nev = %d: %d modes; the six lowest are the "
           "three Euler-Bernoulli bending frequencies %.2f %.2f %.2f rad/s twice (worst relative "
           "error %.1e; lumped masses; pairs equal within 1e-8)",
           n, nev, k, beta[0] * beta[0] * c, beta[1] * beta[1] * c, beta[2] * beta[2] * c, worst);
    double d;
    int ns;
    int ok = compare(m, nev, &d, &ns);
    tap_ok(ok && d < 1e-8,
           "symmetric section: the sparse method's %d lowest are the dense method's %d lowest "
           "(%d returned, largest relative difference %.1e)",
           nev, nev, ns, d);
    bgr_model_free(&m);
}

static void test_two_identical(void)
{
    const mech_section sec = {.E = 2.1e11,
                              .G = 8.1e10,
                              .A = 1e-4,
                              .Iy = 1.6e-9,
                              .Iz = 8.33e-10,
                              .J = 1.4e-9,
                              .rho = 7850};
    const int n = 16, nev = 16;
    bgr_model *m = cantilevers(2, n, 1.0, &sec);
    if (!m) {
        tap_ok(0, "two cantilevers: model");
        return;
    }
    double w[64];
    int k = freqs(m, DAE_MODES_SPARSE, nev, w, 64), pairs = 1;
    for (int j = 0; j + 1 < k; j += 2)
        pairs &= fabs(w[j + 1] - w[j]) <= 1e-8 * w[j];
    tap_ok(k == nev && pairs,
           "two identical cantilevers, sparse nev = %d: %d modes, in equal pairs (%s)", nev, k,
           pairs ? "yes" : "no");
    double d;
    int ns;
    int ok = compare(m, nev, &d, &ns);
    tap_ok(ok && d < 1e-8,
           "two identical cantilevers: the sparse method's %d lowest are the dense method's "
           "(%d returned, largest relative difference %.1e)",
           nev, ns, d);
    bgr_model_free(&m);
}

int main(void)
{
    test_symmetric_section();
    test_two_identical();
    return tap_done();
}
