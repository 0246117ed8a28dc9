/* Tests of the co-rotational beam: its Jacobian against finite differences, no deformation
 * energy under large rigid motions, and cantilevers against Euler-Bernoulli closed forms (tip
 * load P L^3/(3 E I), own weight q L^4/(8 E I)), reached by a damped transient; the parameter
 * checks of mech_beam and mech_beam_chain (bad values refused with messages naming the element's
 * path and the parameter, nothing added). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bgr_elements.h"
#include "bondgraph/param_check.h"
#include "mech_beam.h"
#include "mech_body.h"
#include "mech_parts.h"
#include "mech_util.h"
#include "tap.h"

static const mech_section steel = {
    .E = 2.1e11, .G = 8.1e10, .A = 1e-4, .Iy = 1.6e-9, .Iz = 8.33e-10, .J = 1.4e-9, .rho = 7850};

/* quaternion product r = a b */
static void qmul(const double *a, const double *b, double *r)
{
    double t[4] = {a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
                   a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
                   a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1],
                   a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0]};
    memcpy(r, t, sizeof t);
}

/* A free chain (no supports), for the checks that need no solver. */
static bgr_model *free_chain(int n, double L, int *nodes, int *elems)
{
    static const double p0[3] = {0, 0, 0}, up[3] = {0, 0.3, 1};
    double p1[3] = {L, 0.2 * L, -0.1 * L};
    bgr_model *m = bgr_model_create("free");
    int c = mech_beam_chain(m, 0, "beam", n, p0, p1, up, &steel, NULL, NULL, NULL, nodes, elems);
    if (c < 0 || bgr_compile(m) != BG_OK) {
        tap_diag("free chain: %s", bgr_model_error(m)->message);
        bgr_model_free(&m);
        return NULL;
    }
    mech_beam_chain_set(m, nodes, n, p0, p1);
    return m;
}

/* Largest difference between the port loads of the residual's plain path and of the AD path
 * over the elements, relative to the largest load of the element. */
static double loads_mismatch(const bgr_model *m, const int *elems, int ne, const double *y)
{
    double worst = 0;
    for (int e = 0; e < ne; e++) {
        double g0[12], g1[12], big = 0, diff = 0;
        if (mech_beam_loads(m, elems[e], y, 0, g0) != BG_OK ||
            mech_beam_loads(m, elems[e], y, 1, g1) != BG_OK)
            return INFINITY;
        for (int r = 0; r < 12; r++) {
            big = fmax(big, fabs(g1[r]));
            diff = fmax(diff, fabs(g0[r] - g1[r]));
        }
        worst = fmax(worst, big > 0 ? diff / big : diff);
    }
    return worst;
}

/* The residual's loads (plain arithmetic, reverse pass) against the AD loads at random states
 * of the chain: configuration offsets of size amp (quaternions left unnormalised: R(q) divides
 * by q.q), port flows of 0.1 (they enter through damping only). */
static void check_plain_loads(bgr_model *m, const int *elems, int ne, double amp, const char *what)
{
    int N = bgr_n(m);
    double *z = malloc((size_t)N * sizeof *z), worst = 0;
    tap_rng rng = tap_rng_seed(5);
    for (int trial = 0; z && trial < 4; trial++) {
        for (int i = 0; i < N; i++) {
            const char *nm = bgr_var_name(m, i);
            const char *sl = strrchr(nm, '/');
            int flow = sl && sl[1] == 'f' && sl[2] >= '0' && sl[2] <= '5' && !sl[3];
            z[i] = bgr_y0(m)[i] + (flow ? 0.1 : amp) * tap_rng_range(&rng, -1, 1);
        }
        worst = fmax(worst, loads_mismatch(m, elems, ne, z));
    }
    tap_ok(z && worst <= 1e-10,
           "%s: the residual's loads (plain arithmetic) equal the AD loads within %.2g of the "
           "largest (<= 1e-10) at configurations %g off the rest state",
           what, worst, amp);
    free(z);
}

static void test_rigid_motion_and_jacobian(void)
{
    int nodes[4], elems[3], n = 3;
    bgr_model *m = free_chain(n, 1.5, nodes, elems);
    tap_ok(m != NULL, "beam chain: builds and compiles");
    if (!m) return;
    int N = bgr_n(m);
    double *y = malloc((size_t)N * sizeof *y), *yp = calloc((size_t)N, sizeof *yp);
    memcpy(y, bgr_y0(m), (size_t)N * sizeof *y);
    double W0 = 0;
    for (int e = 0; e < n; e++)
        W0 += fabs(mech_beam_energy(m, elems[e], y));
    tap_ok(W0 < 1e-20, "beam: no energy in the initial configuration (%.3g)", W0);
    /* rigid motion: rotate by 7.3 rad (more than a turn) about an oblique axis, translate */
    static const double axis[3] = {0.3, -0.5, 0.8}, shift[3] = {5, -2, 1};
    double qr[4], R[9];
    mech_quat_axis_angle(axis, 7.3, qr);
    mech_quat_R(qr, R, NULL);
    for (int k = 0; k <= n; k++) {
        int x = mech_body_var(m, nodes[k], 'x'), q = mech_body_var(m, nodes[k], 'q');
        double xr[3];
        mech_mv(R, y + x, xr);
        for (int i = 0; i < 3; i++)
            y[x + i] = xr[i] + shift[i];
        qmul(qr, y + q, y + q);
        for (int i = 0; i < 4; i++)
            y[q + i] *= 1.7; /* |q| != 1: the rotation is homogeneous */
    }
    double Wr = 0;
    for (int e = 0; e < n; e++)
        Wr += fabs(mech_beam_energy(m, elems[e], y));
    tap_ok(Wr < 1e-18, "beam: no deformation energy after a rigid rotation of 7.3 rad (%.3g J)",
           Wr);
    /* a real deformation: twist node 1 by 0.01 rad about the beam axis */
    {
        int q = mech_body_var(m, nodes[1], 'q');
        double dq[4], d[3] = {1, 0.2, -0.1};
        for (int i = 0; i < 3; i++)
            d[i] /= sqrt(1.05);
        double dr[3];
        mech_mv(R, d, dr);
        mech_quat_axis_angle(dr, 0.01, dq);
        qmul(dq, y + q, y + q);
        double W = mech_beam_energy(m, elems[0], y) + mech_beam_energy(m, elems[1], y);
        /* twist 0.01 rad over each of two elements of length L0: 2 * GJ/(2 L0) * 0.01^2 */
        double L0 = 1.5 * sqrt(1.05) / n, want = steel.G * steel.J / L0 * 1e-4;
        tap_ok(fabs(W - want) / want < 1e-3,
               "beam: twisting a node by 0.01 rad stores 2 GJ/(2 L0) theta^2 = %.6g J (got %.6g)",
               want, W);
    }
    /* Jacobian at perturbed configurations (moderate deformations) */
    char rep[512];
    int bad = 0;
    tap_rng rng = tap_rng_seed(7);
    for (int trial = 0; trial < 3; trial++) {
        double *z = malloc((size_t)N * sizeof *z);
        for (int i = 0; i < N; i++)
            z[i] = y[i] + 0.02 * tap_rng_range(&rng, -1, 1);
        int r = bgr_check_jacobian(m, 0.0, z, yp, 1e-5, rep, sizeof rep);
        if (r != 0) {
            tap_diag("beam Jacobian: %s", rep);
            bad = 1;
        }
        free(z);
    }
    tap_ok(!bad, "beam: analytic (AD) Jacobian matches finite differences: %s", rep);
    check_plain_loads(m, elems, n, 0.02, "free chain");
    check_plain_loads(m, elems, n, 0.3, "free chain");
    free(y);
    free(yp);
    bgr_model_free(&m);
}

/* Cantilever along x, clamped at node 0, dampers at every node; tip load P (along -z) and/or
 * gravity. Returns the tip deflection along z after settling. */
static double cantilever_sec(const mech_section *sec, int n, double L, double P,
                             const double *gravity, int *status);
static double cantilever(int n, double L, double P, const double *gravity, int *status)
{
    return cantilever_sec(&steel, n, L, P, gravity, status);
}

static double cantilever_sec(const mech_section *sec, int n, double L, double P,
                             const double *gravity, int *status)
{
    static const double p0[3] = {0, 0, 0}, up[3] = {0, 0, 1};
    double p1[3] = {L, 0, 0};
    int nodes[64], elems[64], extra[64];
    for (int k = 0; k <= n; k++)
        extra[k] = k == 0 ? 1 : k == n ? 2 : 1;
    bgr_model *m = bgr_model_create("cant");
    int c = mech_beam_chain(m, 0, "beam", n, p0, p1, up, sec, gravity, extra, NULL, nodes, elems);
    *status = -1;
    if (c < 0) {
        tap_diag("cantilever: %s", bgr_model_error(m)->message);
        bgr_model_free(&m);
        return NAN;
    }
    double mnode = sec->rho * sec->A * L / n;
    double w1 = 3.516 * sqrt(sec->E * sec->Iz / (sec->rho * sec->A * L * L * L * L));
    double cdamp = 2 * w1 * mnode; /* about critical for the first mode */
    int clamp = mech_support(m, 0, "clamp", 6);
    bgr_bond(m, 0, "b_clamp", 6, bgr_port_of(m, clamp, 0),
             mech_beam_chain_port(m, nodes, n, extra, 0, 0), NULL, NULL);
    for (int k = 1; k <= n; k++) {
        char nm[32];
        snprintf(nm, sizeof nm, "damper%02d", k);
        int r = bgr_R(m, 0, nm, 6, cdamp);
        snprintf(nm, sizeof nm, "b_damper%02d", k);
        bgr_bond(m, 0, nm, 6, mech_beam_chain_port(m, nodes, n, extra, k, 0), bgr_port_of(m, r, 0),
                 NULL, NULL);
    }
    double load[6] = {0, 0, -P, 0, 0, 0};
    int src = bgr_Se(m, 0, "tip_load", 6, load);
    bgr_bond(m, 0, "b_load", 6, bgr_port_of(m, src, 0),
             mech_beam_chain_port(m, nodes, n, extra, n, 1), NULL, NULL);
    if (bgr_compile(m) != BG_OK) {
        tap_diag("cantilever: %s", bgr_model_error(m)->message);
        bgr_model_free(&m);
        return NAN;
    }
    mech_beam_chain_set(m, nodes, n, p0, p1);
    dae_problem p;
    bgr_dae_problem(m, &p);
    dae_options o;
    dae_options_default(&o);
    o.rtol = 1e-6;
    o.atol = 1e-9;
    o.exclude_alg = 1; /* bond forces follow from the states; see dae_options */
    bg_error err = {0};
    dae_solver *s = dae_create(&p, &o, &err);
    int N = bgr_n(m), r = s ? dae_init(s, 0, bgr_y0(m), bgr_yp0(m)) : -1;
    if (r == 0) r = dae_consistent_init(s);
    double *y = malloc((size_t)N * sizeof *y), *yp = malloc((size_t)N * sizeof *yp), t;
    /* the dampers also resist the nodes' rotations, which leaves a slow creep (rate about 4/s):
     * at t = 5 the tip moves at below 1e-9 m/s */
    if (r == 0) r = dae_solve_to(s, 5.0, &t, y, yp);
    double dz = NAN;
    if (r == 0)
        dz = y[mech_body_var(m, nodes[n], 'x') + 2];
    else if (s)
        tap_diag("cantilever: %s", dae_get_error(s)->message);
    if (s) {
        char line[600];
        dae_stats_line(dae_get_stats(s), line, sizeof line);
        tap_diag("cantilever n = %d: %s", n, line);
    }
    *status = r;
    free(y);
    free(yp);
    dae_free(&s);
    bgr_model_free(&m);
    return dz;
}

static void test_cantilever(void)
{
    int st;
    double L = 1.0, P = 1.0;
    double dz = cantilever(8, L, P, NULL, &st);
    double want = -P * L * L * L / (3 * steel.E * steel.Iz);
    /* cubic (Euler-Bernoulli) elements are exact at the nodes for a tip load */
    tap_ok(st == 0 && fabs(dz - want) / fabs(want) < 1e-4,
           "cantilever, 8 elements, tip load: deflection %.6e against P L^3/(3 E I) = %.6e "
           "(rel %.2g)",
           dz, want, fabs(dz - want) / fabs(want));
    const double g[3] = {0, 0, -9.81};
    /* Timoshenko option: a short, thick cantilever, tip load: P L^3/(3 E I) + P L/(kappa G A) */
    mech_section thick = steel;
    thick.A = 4e-2; /* 0.2 m square */
    thick.Iy = thick.Iz = 0.2 * 0.2 * 0.2 * 0.2 / 12;
    thick.J = 0.1406 * 0.2 * 0.2 * 0.2 * 0.2;
    thick.kappa = 5.0 / 6.0;
    double Lt = 0.5, Pt = 1e5;
    dz = cantilever_sec(&thick, 4, Lt, Pt, NULL, &st);
    double wb = Pt * Lt * Lt * Lt / (3 * thick.E * thick.Iz),
           ws = Pt * Lt / (thick.kappa * thick.G * thick.A);
    tap_ok(st == 0 && fabs(-dz - (wb + ws)) / (wb + ws) < 1e-3,
           "Timoshenko cantilever (L/h = 2.5): deflection %.6e against bending %.4e + shear %.4e "
           "(rel %.2g)",
           -dz, wb, ws, fabs(-dz - (wb + ws)) / (wb + ws));
    dz = cantilever(16, L, 0.0, g, &st);
    double q = steel.rho * steel.A * 9.81;
    want = -q * L * L * L * L / (8 * steel.E * steel.Iz);
    /* lumped nodal weights instead of consistent loads: within 0.5 % (the bound) */
    tap_ok(st == 0 && fabs(dz - want) / fabs(want) < 5e-3,
           "cantilever, 16 elements, own weight: deflection %.6e against q L^4/(8 E I) = %.6e "
           "(rel %.2g)",
           dz, want, fabs(dz - want) / fabs(want));
}

/* ---- natural frequencies of a cantilever from the linearised model ----
 * At rest (straight, unloaded) the compiled model linearises to Jy dy + Jyp dy' = 0, whose
 * finite generalised eigenvalues s (Jy v = -s Jyp v; LAPACK dggev) are +-i omega of the modes.
 * Against Euler-Bernoulli: omega_k = beta_k^2 sqrt(E I/(rho A L^4)), beta = 1.8751, 4.6941,
 * 7.8548 (bending in both planes), axial (pi/2) sqrt(E/rho)/L, torsion (pi/2) sqrt(G J/(rho
 * Ip))/L with Ip = Iy + Iz. */
void dggev_(const char *jobvl, const char *jobvr, const int *n, double *a, const int *lda,
            double *b, const int *ldb, double *alphar, double *alphai, double *beta, double *vl,
            const int *ldvl, double *vr, const int *ldvr, double *work, const int *lwork, int *info,
            size_t l1, size_t l2);

static int cmp_dbl(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static int near(const double *w, int nw, double target, double *found)
{
    double best = INFINITY;
    for (int i = 0; i < nw; i++)
        if (fabs(w[i] - target) < fabs(best - target)) best = w[i];
    *found = best;
    return isfinite(best);
}

/* The model "name": a chain of n elements of section sec from (0,0,0) to (L,0,0), clamped at its
 * foot (6 dof support), compiled and set straight; NULL on failure (a failed test point "what:
 * compile"). */
static bgr_model *clamped_chain(const char *name, const char *what, int n, double L,
                                const mech_section *sec, int *nodes, int *elems, int *extra)
{
    const double p0[3] = {0, 0, 0}, p1[3] = {L, 0, 0}, up[3] = {0, 0, 1};
    bgr_model *m = bgr_model_create(name);
    mech_beam_chain(m, 0, "beam", n, p0, p1, up, sec, NULL, extra, NULL, nodes, elems);
    int clamp = mech_support(m, 0, "clamp", 6);
    bgr_bond(m, 0, "b_clamp", 6, bgr_port_of(m, clamp, 0),
             mech_beam_chain_port(m, nodes, n, extra, 0, 0), NULL, NULL);
    if (bgr_compile(m) != BG_OK) {
        tap_ok(0, "%s: compile (%s)", what, bgr_model_error(m)->message);
        bgr_model_free(&m);
        return NULL;
    }
    mech_beam_chain_set(m, nodes, n, p0, p1);
    return m;
}

/* The generalised eigenvalues s = (ar + i ai) / be of the linearisation of the compiled model m
 * at (bgr_y0, yp): dF/dy v = s (-dF/dy') v, by LAPACK dggev. ar, ai, be get N = bgr_n(m) values
 * each in arrays the caller frees; returns dggev's info. */
static int pencil_eigs(bgr_model *m, const double *yp, double **ar_out, double **ai_out,
                       double **be_out)
{
    dae_problem p;
    bgr_dae_problem(m, &p);
    int N = bgr_n(m);
    sp_csc *Jy = sp_csc_copy(p.jac_y_pattern), *Jyp = sp_csc_copy(p.jac_yp_pattern);
    bgr_jacobian(m, 0.0, bgr_y0(m), yp, Jy, Jyp);
    double *A = malloc((size_t)N * N * sizeof *A), *B = malloc((size_t)N * N * sizeof *B);
    double *ar = malloc((size_t)N * sizeof *ar), *ai = malloc((size_t)N * sizeof *ai),
           *be = malloc((size_t)N * sizeof *be);
    sp_csc_to_dense(Jy, A);
    sp_csc_to_dense(Jyp, B);
    for (long i = 0; i < (long)N * N; i++)
        B[i] = -B[i];
    int lwork = -1, info = 0, one = 1;
    double wq;
    dggev_("N", "N", &N, A, &N, B, &N, ar, ai, be, NULL, &one, NULL, &one, &wq, &lwork, &info, 1,
           1);
    lwork = (int)wq;
    double *work = malloc((size_t)lwork * sizeof *work);
    dggev_("N", "N", &N, A, &N, B, &N, ar, ai, be, NULL, &one, NULL, &one, work, &lwork, &info, 1,
           1);
    free(A);
    free(B);
    free(work);
    sp_csc_free(&Jy);
    sp_csc_free(&Jyp);
    *ar_out = ar;
    *ai_out = ai;
    *be_out = be;
    return info;
}

static void test_frequencies(void)
{
    const int n = 20;
    const double L = 1.0;
    int nodes[32], elems[32], extra[32] = {1};
    bgr_model *m = clamped_chain("modes", "modes", n, L, &steel, nodes, elems, extra);
    if (!m) return;
    int N = bgr_n(m);
    double *yp = calloc((size_t)N, sizeof *yp), *ar, *ai, *be;
    int info = pencil_eigs(m, yp, &ar, &ai, &be);
    double *om = malloc((size_t)N * sizeof *om);
    int nw = 0;
    for (int i = 0; i < N; i++)
        if (info == 0 && fabs(be[i]) > 1e-12 * (fabs(ar[i]) + fabs(ai[i])) && ai[i] / be[i] > 1.0)
            om[nw++] = ai[i] / be[i];
    qsort(om, (size_t)nw, sizeof *om, cmp_dbl);
    tap_diag("modes: %d unknowns, %d oscillatory modes, lowest %.4f %.4f %.4f %.4f rad/s", N, nw,
             nw > 0 ? om[0] : NAN, nw > 1 ? om[1] : NAN, nw > 2 ? om[2] : NAN,
             nw > 3 ? om[3] : NAN);
    const double beta[3] = {1.8751, 4.6941, 7.8548};
    const double I2[2] = {steel.Iz, steel.Iy};
    const char *plane[2] = {"in the e1-e2 plane (Iz)", "out of it (Iy)"};
    for (int a = 0; a < 2; a++)
        for (int k = 0; k < 3; k++) {
            double w = beta[k] * beta[k] *
                       sqrt(steel.E * I2[a] / (steel.rho * steel.A * L * L * L * L)),
                   got;
            near(om, nw, w, &got);
            tap_ok(fabs(got - w) / w < 1e-2,
                   "modes: bending %d %s: %.4f rad/s against %.4f (rel %.2g)", k + 1, plane[a], got,
                   w, fabs(got - w) / w);
        }
    double wa = 0.5 * 3.14159265358979 * sqrt(steel.E / steel.rho) / L, got;
    near(om, nw, wa, &got);
    tap_ok(fabs(got - wa) / wa < 1e-2, "modes: first axial %.2f rad/s against %.2f (rel %.2g)", got,
           wa, fabs(got - wa) / wa);
    double wt =
        0.5 * 3.14159265358979 * sqrt(steel.G * steel.J / (steel.rho * (steel.Iy + steel.Iz))) / L;
    near(om, nw, wt, &got);
    tap_ok(fabs(got - wt) / wt < 1e-2, "modes: first torsional %.2f rad/s against %.2f (rel %.2g)",
           got, wt, fabs(got - wt) / wt);
    free(ar);
    free(ai);
    free(be);
    free(om);
    free(yp);
    bgr_model_free(&m);
}

/* ---- a beam spun about a perpendicular axis through its foot ----
 * Revolute hub (axis z) driven at a constant rate W by a flow source, beam along the rotating
 * x axis, started from the closed-form stretched state with the velocities of the rigid
 * rotation. Rotating bar (small strain, EA u'' + rho A W^2 x = 0, u(0) = 0, u'(L) = 0):
 * u(x) = rho W^2/E (L^2 x/2 - x^3/6), tip u(L) = rho W^2 L^3/(3 E). Over one revolution the tip
 * stays on the radius at L + u(L) (up to the lumped discretisation) and nothing bends. */
static void test_spinning(void)
{
    const int n = 10;
    const double L = 1.0, W = 50.0, up[3] = {0, 0, 1};
    int nodes[32], elems[32], extra[32] = {1};
    bgr_model *m = bgr_model_create("spin");
    const double p0[3] = {0, 0, 0}, p1[3] = {L, 0, 0}, z[3] = {0, 0, 1};
    mech_beam_chain(m, 0, "beam", n, p0, p1, up, &steel, NULL, extra, NULL, nodes, elems);
    int gnd = mech_support(m, 0, "ground", 6), hub = mech_revolute(m, 0, "hub", -1, z, 1);
    double rate = W;
    int drive = bgr_Sf(m, 0, "drive", 1, &rate);
    bgr_bond(m, 0, "b_ground", 6, bgr_port_of(m, gnd, 0), bgr_port_of(m, hub, 0), NULL, NULL);
    bgr_bond(m, 0, "b_hub", 6, bgr_port_of(m, hub, 1),
             mech_beam_chain_port(m, nodes, n, extra, 0, 0), NULL, NULL);
    bgr_bond(m, 0, "b_drive", 1, bgr_port_of(m, drive, 0), bgr_port_of(m, hub, 2), NULL, NULL);
    if (bgr_compile(m) != BG_OK) {
        tap_ok(0, "spinning: compile (%s)", bgr_model_error(m)->message);
        bgr_model_free(&m);
        return;
    }
    double k2 = steel.rho * W * W / steel.E;
    for (int k = 0; k <= n; k++) {
        double x0 = L * k / n, u = k2 * (L * L * x0 / 2 - x0 * x0 * x0 / 6);
        double x[3] = {x0 + u, 0, 0}, v[3] = {0, W * (x0 + u), 0}, w[3] = {0, 0, W};
        mech_body_set(m, nodes[k], x, v, w, NULL);
    }
    dae_problem p;
    bgr_dae_problem(m, &p);
    dae_options o;
    dae_options_default(&o);
    o.rtol = 1e-7;
    o.atol = 1e-11;
    o.exclude_alg = 1;
    bg_error err = {0};
    dae_solver *s = dae_create(&p, &o, &err);
    int N = bgr_n(m), r = s ? dae_init(s, 0, bgr_y0(m), bgr_yp0(m)) : -1;
    if (r == 0) r = dae_consistent_init(s);
    double *y = malloc((size_t)N * sizeof *y), *yp = malloc((size_t)N * sizeof *yp), t;
    double T = 2 * 3.14159265358979 / W, want = k2 * L * L * L / 3, maxdev = 0, maxlat = 0;
    /* strain energy of the stretched bar: EA/2 int u'^2 = EA k2^2 L^5 / 15 */
    double Wax = steel.E * steel.A * k2 * k2 * L * L * L * L * L / 15, maxw = 0;
    int xt = mech_body_var(m, nodes[n], 'x');
    for (int j = 1; j <= 40 && r == 0; j++) {
        r = dae_solve_to(s, T * j / 40, &t, y, yp);
        double ang = W * t, c = cos(ang), sn = sin(ang);
        double radial = y[xt] * c + y[xt + 1] * sn, lateral = -y[xt] * sn + y[xt + 1] * c;
        maxdev = fmax(maxdev, fabs(radial - L - want) / want);
        maxlat = fmax(maxlat, fabs(lateral) + fabs(y[xt + 2]));
        double Wt = 0;
        for (int e = 0; e < n; e++)
            Wt += mech_beam_energy(m, elems[e], y);
        maxw = fmax(maxw, fabs(Wt - Wax) / Wax);
    }
    if (r < 0) tap_diag("spinning: %s", dae_get_error(s)->message);
    tap_ok(r == 0 && maxdev < 0.02,
           "spinning beam: tip stretch stays at rho W^2 L^3/(3E) = %.4e m over a revolution "
           "(largest deviation %.2g of it)",
           want, maxdev);
    /* no spurious strain: the deformation energy is the axial one of the closed form (the
     * residual axial vibration of the lumped model moves it by a few per cent) */
    tap_ok(r == 0 && maxw < 0.05,
           "spinning beam: deformation energy stays at the axial EA k^4 L^5/15 = %.4g J "
           "(largest deviation %.2g of it)",
           Wax, maxw);
    tap_diag("spinning beam: the tip stays within %.2g m of the rotating radius (integration "
             "error at rtol 1e-7 over 1 m)",
             maxlat);
    dae_free(&s);
    free(y);
    free(yp);
    bgr_model_free(&m);
}

/* ---- stiffness-proportional damping ----
 * With beta > 0 the linearised cantilever's eigenvalues become -beta w^2/2 +- i w sqrt(1 - zeta^2)
 * (damping proportional to the stiffness keeps the undamped modes): the real parts of the first
 * bending modes against -beta w^2/2, and the damped element's Jacobian (it now depends on the
 * port velocities too) against finite differences. */
static void test_damping(void)
{
    const int n = 10;
    const double L = 1.0;
    mech_section sec = steel;
    sec.beta = 2e-4;
    int nodes[16], elems[16], extra[16] = {1};
    bgr_model *m = clamped_chain("damped", "damping", n, L, &sec, nodes, elems, extra);
    if (!m) return;
    int N = bgr_n(m);
    /* Jacobian at perturbed states with velocities */
    double *z = malloc((size_t)N * sizeof *z), *zp = calloc((size_t)N, sizeof *zp);
    tap_rng rng = tap_rng_seed(11);
    char rep[512];
    int bad = 0;
    /* configurations 1e-6 off the rest state (stiff bars: larger offsets make elastic forces
     * that drown the damping terms in the finite differences), port velocities of order 0.1 */
    for (int trial = 0; trial < 2; trial++) {
        for (int i = 0; i < N; i++) {
            const char *nm = bgr_var_name(m, i);
            const char *sl = strrchr(nm, '/');
            int flow = sl && sl[1] == 'f' && sl[2] >= '0' && sl[2] <= '5' && !sl[3];
            z[i] = bgr_y0(m)[i] + (flow ? 0.1 : 1e-6) * tap_rng_range(&rng, -1, 1);
        }
        if (bgr_check_jacobian(m, 0.0, z, zp, 1e-5, rep, sizeof rep) != 0) {
            tap_diag("damped beam Jacobian: %s", rep);
            bad = 1;
        }
    }
    tap_ok(!bad, "damping: Jacobian with the velocity terms matches finite differences: %s", rep);
    check_plain_loads(m, elems, n, 1e-6, "damping");
    check_plain_loads(m, elems, n, 0.05, "damping");
    /* eigenvalues at rest */
    double *ar, *ai, *be;
    int info = pencil_eigs(m, zp, &ar, &ai, &be);
    const double beta_[2] = {1.8751, 4.6941};
    for (int k = 0; k < 2; k++) {
        double w = beta_[k] * beta_[k] * sqrt(sec.E * sec.Iz / (sec.rho * sec.A * L * L * L * L));
        /* the eigenvalue with the imaginary part closest to this mode's */
        int best = -1;
        for (int i = 0; i < N; i++) {
            if (!(info == 0 && fabs(be[i]) > 1e-12 * (fabs(ar[i]) + fabs(ai[i])))) continue;
            double im = ai[i] / be[i];
            if (im > 0 && (best < 0 || fabs(im - w) < fabs(ai[best] / be[best] - w))) best = i;
        }
        double re = best >= 0 ? ar[best] / be[best] : NAN,
               im = best >= 0 ? ai[best] / be[best] : NAN;
        double want = -sec.beta * im * im / 2 / (1 - sec.beta * sec.beta * im * im / 4);
        tap_ok(fabs(re - want) / fabs(want) < 1e-3,
               "damping: bending mode %d: Re(s) = %.6f against -beta w^2/2 = %.6f (w = %.3f)",
               k + 1, re, want, im);
    }
    free(ar);
    free(ai);
    free(be);
    free(z);
    free(zp);
    bgr_model_free(&m);
}

/* ---- parameter checks of mech_beam and mech_beam_chain ---- */

static int pc_na = -1, pc_nb = -1, pc_sup = -1; /* two bodies and a support for mech_beam */

/* which 0..8: the section's E, G, A, Iy, Iz, J, rho, kappa, beta; 9: no section */
static void pc_section(int which, double x, mech_section *s)
{
    *s = steel;
    s->beta = 1e-4;
    double *f[9] = {&s->E, &s->G, &s->A, &s->Iy, &s->Iz, &s->J, &s->rho, &s->kappa, &s->beta};
    if (which >= 0 && which < 9) *f[which] = x;
}

/* mech_beam: which 0..9 as pc_section; 10: no frame; 11: E0[4] = x; 12: E0[0] = x (not
 * orthonormal); 13: left-handed; 14: L0; 15: node_a, 16: node_b (int) x; 17: node_b = node_a;
 * 18: E = A = x (the stiffness overflows) */
static int mk_beam(bgr_model *m, bgr_comp c, const char *name, int which, double x)
{
    mech_section s;
    pc_section(which, x, &s);
    if (which == 18) s.E = s.A = x;
    double E0[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    if (which == 11) E0[4] = x;
    if (which == 12) E0[0] = x;
    if (which == 13) E0[8] = -1;
    int na = which == 15 ? (int)x : pc_na, nb = which == 16 ? (int)x : which == 17 ? na : pc_nb;
    return mech_beam(m, c, name, na, nb, which == 9 ? NULL : &s, which == 10 ? NULL : E0,
                     which == 14 ? x : 1.0);
}

/* mech_beam_chain: which 0..9 as pc_section; 10: n; 11: p0[0]; 12: p1 = p0; 13: up along the
 * beam; 14: up[2]; 15: gravity[1]; 16: extra[1] (int) x; 17: extra[0] (int) x; 18: no id
 * arrays */
static int mk_chain(bgr_model *m, bgr_comp c, const char *name, int which, double x)
{
    mech_section s;
    pc_section(which, x, &s);
    double p0[3] = {0, 0, 0}, p1[3] = {2, 0, 0}, up[3] = {0, 0, 1}, g[3] = {0, 0, -9.81};
    int extra[3] = {1, 0, 0}, nodes[3], elems[2];
    if (which == 11) p0[0] = x;
    if (which == 12) p1[0] = 0;
    if (which == 13) up[0] = 1, up[2] = 0;
    if (which == 14) up[2] = x;
    if (which == 15) g[1] = x;
    if (which == 16) extra[1] = (int)x;
    if (which == 17) extra[0] = (int)x;
    return mech_beam_chain(m, c, name, which == 10 ? (int)x : 2, p0, p1, up, which == 9 ? NULL : &s,
                           g, extra, NULL, which == 18 ? NULL : nodes, elems);
}

/* The section, frame, length and nodes of a beam element and the arguments of the chain
 * builder: NaN, infinities, 0 and negative numbers where refused, frames that are not
 * orthonormal or right-handed, nodes that are not bodies, stiffnesses and lumped inertias that
 * overflow or vanish; one test point each (tests/bondgraph/param_check.h; a refused chain leaves
 * no component, element or bond). */
static void test_param_checks(void)
{
    const double nan = NAN, inf = INFINITY;
    const char *POS = "expected a finite number > 0", *NNEG = "expected a finite number >= 0";
    const char *FIN = "expected a finite number", *BODY = "expected the element id of a rigid body";
    const char *ENDS = "expected two distinct end points";
    const pc_case cases[] = {
        {"mech_beam", mk_beam, 0, nan, "section.E = ", POS},
        {"mech_beam", mk_beam, 0, 0.0, "section.E = ", POS},
        {"mech_beam", mk_beam, 1, -8.1e10, "section.G = ", POS},
        {"mech_beam", mk_beam, 2, inf, "section.A = ", POS},
        {"mech_beam", mk_beam, 3, 0.0, "section.Iy = ", POS},
        {"mech_beam", mk_beam, 4, nan, "section.Iz = ", POS},
        {"mech_beam", mk_beam, 5, -1.0, "section.J = ", POS},
        {"mech_beam", mk_beam, 6, -1.0, "section.rho = ", NNEG},
        {"mech_beam", mk_beam, 6, inf, "section.rho = ", NNEG},
        {"mech_beam", mk_beam, 7, nan, "section.kappa = ", NNEG},
        {"mech_beam", mk_beam, 8, -1e-4, "section.beta = ", NNEG},
        {"mech_beam", mk_beam, 9, 0, "the section is NULL", "NULL"},
        {"mech_beam", mk_beam, 10, 0, "the initial frame E0 is NULL", "NULL"},
        {"mech_beam", mk_beam, 11, nan, "E0[4] = ", FIN},
        {"mech_beam", mk_beam, 12, 2.0, "E0's columns 0 and 0 have the product 4",
         "expected an orthonormal frame"},
        {"mech_beam", mk_beam, 13, 0, "E0 is left-handed", "expected e3 = e1 x e2"},
        {"mech_beam", mk_beam, 14, 0.0, "L0 = ", POS},
        {"mech_beam", mk_beam, 14, nan, "L0 = ", POS},
        {"mech_beam", mk_beam, 14, -1.0, "L0 = ", POS},
        {"mech_beam", mk_beam, 15, -1, "node_a = -1", BODY},
        {"mech_beam", mk_beam, 16, 99, "node_b = 99", BODY},
        {"mech_beam", mk_beam, 16, 2, "node_b = 2", BODY},
        {"mech_beam", mk_beam, 17, 0, "node_a = node_b = 0", "expected two different bodies"},
        {"mech_beam", mk_beam, 18, 1e200, "the local stiffness of the section over L0 = 1",
         "are finite"},
        {"mech_beam_chain", mk_chain, 0, nan, "section.E = ", POS},
        {"mech_beam_chain", mk_chain, 6, 0.0, "section.rho = 0", "the chain lumps the mass"},
        {"mech_beam_chain", mk_chain, 6, -7850, "section.rho = ", NNEG},
        {"mech_beam_chain", mk_chain, 6, 1e-320, "a node standing for l = ", "finite and > 0"},
        {"mech_beam_chain", mk_chain, 2, 1e300, "the local stiffness of the section", "finite"},
        {"mech_beam_chain", mk_chain, 9, 0, "the section is NULL", "NULL"},
        {"mech_beam_chain", mk_chain, 10, 0, "n = 0", "expected at least 1 element"},
        {"mech_beam_chain", mk_chain, 11, nan, "p0[0] = ", FIN},
        {"mech_beam_chain", mk_chain, 11, -inf, "p0[0] = ", FIN},
        {"mech_beam_chain", mk_chain, 12, 0, "p1 = (0, 0, 0)", ENDS},
        {"mech_beam_chain", mk_chain, 13, 0, "up = (1, 0, 0)", "not along the beam"},
        {"mech_beam_chain", mk_chain, 14, inf, "up[2] = ", FIN},
        {"mech_beam_chain", mk_chain, 15, nan, "gravity[1] = ", FIN},
        {"mech_beam_chain", mk_chain, 16, -1, "node 1 has a negative number of extra ports",
         "(-1)"},
        {"mech_beam_chain", mk_chain, 17, 64, "node 0 has 65 ports", "expected at most 64"},
        {"mech_beam_chain", mk_chain, 18, 0, "the arrays for the node and element ids", "NULL"},
    };
    int n = (int)(sizeof cases / sizeof cases[0]);
    bgr_model *m = bgr_model_create("params");
    double J[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1}, r[3] = {0, 0, 0};
    pc_na = mech_body(m, 0, "a", 1.0, J, NULL, 1, r, NULL);
    pc_nb = mech_body(m, 0, "b", 1.0, J, NULL, 1, r, NULL);
    pc_sup = mech_support(m, 0, "ground", 6);
    if (pc_na != 0 || pc_nb != 1 || pc_sup != 2) /* the cases name the support's id 2 */
        tap_diag("the nodes and the support got the ids %d, %d, %d (expected 0, 1, 2)", pc_na,
                 pc_nb, pc_sup);
    bgr_comp c = bgr_component(m, bgr_component(m, 0, "boom"), "bad");
    int passed = pc_run(m, c, "x", cases, n);
    tap_diag("%d of %d refusals as required", passed, n);
    bgr_model_free(&m);
}

int main(void)
{
    test_rigid_motion_and_jacobian();
    test_cantilever();
    test_frequencies();
    test_spinning();
    test_damping();
    test_param_checks();
    return tap_done();
}
