/* The static solver (bg_static.h) and the modal analysis (bg_modes.h) on small DAEs written by
 * hand, against closed forms:
 *   - a mass on a spring and damper under gravity: the static stretch m g / k, the natural
 *     frequency sqrt(k/m) and the damping ratio c / (2 sqrt(k m)) (finite-difference Jacobians,
 *     with and without declared patterns);
 *   - the same spring with a stretch state of its own (d' = v, as the project's axial elements):
 *     the equations at rest leave the mass's position free; the solver keeps the invariant
 *     x - d of the start, and the modes list it as a constraint mode (zero, semisimple);
 *   - a free particle: rigid modes (zero and defective), no elastic one;
 *   - the index-2 pendulum in Cartesian coordinates with its constraint at velocity level
 *     (x u + y v = 0): started 40 degrees off, it comes to hang straight with the declared
 *     position constraint kept (r = L); the swing at sqrt(g/L), the index-2 pair at infinity
 *     and the drift of r at zero kept apart;
 *   - steady motion under a prescribed rate: a mass dragged through a spring and a damper at a
 *     constant speed V trails by c V / k;
 *   - a saturating spring (force atan x) under a load beyond its largest force: the
 *     continuation stops at the limit load factor and names the equation and the unknown;
 *     below it, the load factor of the model (options.load) and the Newton homotopy give the
 *     same root;
 *   - a chain of N masses between springs with stretch states (N + 1 zero modes besides the N
 *     oscillating ones): frequencies 2 sqrt(k/m) sin(j pi / (2 (N + 1))), the dense method for
 *     all, the sparse one (ARPACK) for the lowest ten and a window, without the zero modes. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bg_modes.h"
#include "bg_static.h"
#include "tap.h"

static const double PI = 3.14159265358979323846;
static const double G = 9.81;

/* ---- a mass on a spring and damper: y = (x, v, F) ---- */
typedef struct msd {
    double m, k, c, L0;
} msd;

static int msd_res(void *u, double t, const double *y, const double *yp, double *F)
{
    const msd *p = u;
    (void)t;
    F[0] = yp[0] - y[1];
    F[1] = p->m * yp[1] + y[2] + p->m * G;
    F[2] = y[2] - p->k * (y[0] - p->L0) - p->c * y[1];
    return 0;
}

static void test_mass_spring(int with_patterns)
{
    msd P = {.m = 2.0, .k = 800.0, .c = 8.0, .L0 = 1.0};
    /* patterns: dF/dy and dF/dy' */
    sp_csc *Jy = sp_csc_alloc(3, 3, 5), *Jyp = sp_csc_alloc(3, 3, 2);
    /* dF/dy: F0: v; F1: F; F2: x, v, F */
    int cy[4] = {0, 1, 3, 5}, ry[5] = {2, 0, 2, 1, 2};
    memcpy(Jy->colptr, cy, sizeof cy), memcpy(Jy->rowind, ry, sizeof ry), Jy->nnz = 5;
    int cyp[4] = {0, 1, 2, 2}, ryp[2] = {0, 1};
    memcpy(Jyp->colptr, cyp, sizeof cyp), memcpy(Jyp->rowind, ryp, sizeof ryp), Jyp->nnz = 2;
    dae_problem p = {.n = 3, .res = msd_res, .user = &P};
    if (with_patterns) p.jac_y_pattern = Jy, p.jac_yp_pattern = Jyp;
    const char *label = with_patterns ? "mass-spring (patterns)" : "mass-spring (dense)";
    double y[3] = {P.L0, 0, 0}, yp[3];
    dae_static_result r;
    bg_error err = {0};
    int st = dae_static_solve(&p, NULL, 0.0, y, yp, &r, &err);
    double want = P.L0 - P.m * G / P.k;
    tap_ok(st == BG_OK && fabs(y[0] - want) < 1e-9 && fabs(y[1]) < 1e-12 &&
               fabs(y[2] + P.m * G) < 1e-8 && r.residual <= 1,
           "%s: static x = %.12g (L0 - m g/k = %.12g), spring force %.9g = -m g, scaled "
           "residual %.2g (%s)",
           label, y[0], want, y[2], r.residual, st ? err.message : "ok");
    dae_modes *M = NULL;
    st = dae_modes_compute(&p, 0.0, y, NULL, NULL, &M, &err);
    int ne = -1, nr = -1, nc = -1;
    dae_modes_info(M, &ne, &nr, &nc, NULL, NULL, NULL);
    const dae_mode *md = dae_modes_get(M, 0);
    double wn = sqrt(P.k / P.m), zeta = P.c / (2 * sqrt(P.k * P.m));
    tap_ok(st == BG_OK && ne == 1 && nr == 0 && nc == 0 && md &&
               fabs(md->freq_hz - wn / (2 * PI)) < 1e-9 * wn && fabs(md->damping - zeta) < 1e-9,
           "%s: one elastic mode, %.9g Hz (sqrt(k/m)/2pi = %.9g), damping ratio %.9g (c/(2 "
           "sqrt(k m)) = %.9g)",
           label, md ? md->freq_hz : NAN, wn / (2 * PI), md ? md->damping : NAN, zeta);
    dae_modes_free(&M);
    sp_csc_free(&Jy);
    sp_csc_free(&Jyp);
}

/* ---- a spring with a stretch state of its own: y = (x, v, d) ---- */
static int sd_res(void *u, double t, const double *y, const double *yp, double *F)
{
    const msd *p = u;
    (void)t;
    F[0] = yp[0] - y[1];
    F[1] = yp[2] - y[1];
    F[2] = p->m * yp[1] + p->k * (y[2] - p->L0) + p->m * G;
    return 0;
}

static void test_stretch_state(void)
{
    msd P = {.m = 3.0, .k = 1200.0, .L0 = 1.0};
    dae_problem p = {.n = 3, .res = sd_res, .user = &P};
    static const char *const names[3] = {"mass/x", "mass/v", "spring/d"};
    p.names = names;
    double y[3] = {3.0, 0, P.L0};
    dae_static_result r;
    bg_error err = {0};
    int st = dae_static_solve(&p, NULL, 0.0, y, NULL, &r, &err);
    double d = P.L0 - P.m * G / P.k;
    tap_ok(st == BG_OK && fabs(y[2] - d) < 1e-10 && fabs(y[0] - y[2] - (3.0 - P.L0)) < 1e-12,
           "stretch state: d = %.12g (L0 - m g/k), the invariant x - d kept at %.12g (start 2): "
           "x follows d although no equation at rest contains it",
           y[2], y[0] - y[2]);
    dae_modes *M = NULL;
    st = dae_modes_compute(&p, 0.0, y, NULL, NULL, &M, &err);
    int ne = -1, nr = -1, nc = -1;
    dae_modes_info(M, &ne, &nr, &nc, NULL, NULL, NULL);
    const dae_mode *m0 = dae_modes_get(M, 0), *m1 = dae_modes_get(M, 1);
    double wn = sqrt(P.k / P.m);
    char desc[256] = "";
    if (m1) dae_modes_describe(M, 1, 1, 3, 2, desc, sizeof desc);
    tap_ok(st == BG_OK && ne == 1 && nr == 0 && nc == 1 && m0 &&
               fabs(m0->freq_hz * 2 * PI - wn) < 1e-9 * wn && m1 &&
               m1->kind == DAE_MODE_CONSTRAINT && m1->freq_hz < 1e-9,
           "stretch state: one elastic mode at sqrt(k/m) (%.9g rad/s) and the drift of x - d as "
           "a constraint mode at zero (rcond %.2g: %s)",
           m0 ? m0->freq_hz * 2 * PI : NAN, m1 ? m1->rcond : NAN, desc);
    dae_modes_free(&M);
}

/* ---- a free particle in the plane: y = (x, y, u, v) ---- */
static int free_res(void *u, double t, const double *y, const double *yp, double *F)
{
    (void)u, (void)t;
    F[0] = yp[0] - y[2];
    F[1] = yp[1] - y[3];
    F[2] = 5.0 * yp[2];
    F[3] = 5.0 * yp[3];
    return 0;
}

static void test_free_particle(void)
{
    dae_problem p = {.n = 4, .res = free_res};
    double y[4] = {1.0, -2.0, 0, 0};
    bg_error err = {0};
    dae_static_result r;
    int st = dae_static_solve(&p, NULL, 0.0, y, NULL, &r, &err);
    tap_ok(st == BG_OK && y[0] == 1.0 && y[1] == -2.0,
           "free particle: at rest where it starts (no force, the pseudo-time term holds it)");
    dae_modes *M = NULL;
    st = dae_modes_compute(&p, 0.0, y, NULL, NULL, &M, &err);
    int ne = -1, nr = -1, nc = -1;
    dae_modes_info(M, &ne, &nr, &nc, NULL, NULL, NULL);
    double rc = dae_modes_get(M, 0) ? dae_modes_get(M, 0)->rcond : NAN;
    tap_ok(st == BG_OK && ne == 0 && nr >= 2 && nc == 0,
           "free particle: %d rigid modes (zero and defective: rcond %.2g), no elastic or "
           "constraint mode",
           nr, rc);
    dae_modes_free(&M);
}

/* ---- the index-2 pendulum: y = (x, y, u, v, lambda) ---- */
typedef struct pend {
    double m, L;
} pend;

static int pend_res(void *u, double t, const double *y, const double *yp, double *F)
{
    const pend *p = u;
    (void)t;
    F[0] = yp[0] - y[2];
    F[1] = yp[1] - y[3];
    F[2] = p->m * yp[2] + y[4] * y[0];
    F[3] = p->m * yp[3] + y[4] * y[1] + p->m * G;
    F[4] = y[0] * y[2] + y[1] * y[3];
    return 0;
}

static int pend_cons(void *u, double t, const double *y, double *g, sp_csc *Gm)
{
    (void)u, (void)t;
    g[0] = y[0] * y[0] + y[1] * y[1];
    if (Gm) Gm->val[0] = 2 * y[0], Gm->val[1] = 2 * y[1];
    return 0;
}

static void test_pendulum(void)
{
    pend P = {.m = 2.0, .L = 1.5};
    sp_csc *Gp = sp_csc_alloc(1, 5, 2);
    int cp[6] = {0, 1, 2, 2, 2, 2}, rp[2] = {0, 0};
    memcpy(Gp->colptr, cp, sizeof cp), memcpy(Gp->rowind, rp, sizeof rp), Gp->nnz = 2;
    static const char *const names[5] = {"bob/x", "bob/y", "bob/u", "bob/v", "rod/lambda"};
    static const char *const eqs[5] = {"bob/dx", "bob/dy", "bob/mu", "bob/mv", "rod/constraint"};
    for (int with_cons = 0; with_cons < 2; with_cons++) {
        dae_problem p = {.n = 5, .res = pend_res, .user = &P, .names = names, .eq_names = eqs};
        if (with_cons) p.ncons = 1, p.cons = pend_cons, p.cons_pattern = Gp;
        double a = 40 * PI / 180, y[5] = {P.L * sin(a), -P.L * cos(a), 0, 0, 0};
        bg_error err = {0};
        dae_static_result r;
        int st = dae_static_solve(&p, NULL, 0.0, y, NULL, &r, &err);
        double rad = hypot(y[0], y[1]);
        if (with_cons)
            tap_ok(st == BG_OK && fabs(y[0]) < 1e-9 && fabs(rad - P.L) < 1e-12 &&
                       fabs(y[4] - P.m * G / P.L) < 1e-6,
                   "pendulum from 40 deg, position constraint declared: hangs at x = %.2g, r = "
                   "%.15g (L = %g), lambda = m g / L = %.9g (%ld steps)",
                   y[0], rad, P.L, y[4], r.steps);
        else /* the limitation, measured */
            tap_ok(st == BG_OK && fabs(y[0]) < 1e-9,
                   "pendulum from 40 deg, no constraint declared: hangs straight (x = %.2g); r = "
                   "%.6g against L = %g: a constraint held at velocity level keeps r only to "
                   "second order in each step's rotation (%ld steps)",
                   y[0], rad, P.L, r.steps);
    }
    /* modes at the hanging state */
    dae_problem p = {.n = 5, .res = pend_res, .user = &P, .names = names, .eq_names = eqs};
    double y[5] = {0, -P.L, 0, 0, P.m * G / P.L};
    dae_modes *M = NULL;
    bg_error err = {0};
    int st = dae_modes_compute(&p, 0.0, y, NULL, NULL, &M, &err);
    int ne = -1, nr = -1, nc = -1, inf = 0, zero = 0;
    dae_modes_info(M, &ne, &nr, &nc, NULL, NULL, NULL);
    for (int k = 0; k < dae_modes_count(M); k++) {
        const dae_mode *md = dae_modes_get(M, k);
        if (md->kind == DAE_MODE_CONSTRAINT) *(isinf(md->freq_hz) ? &inf : &zero) += 1;
    }
    const dae_mode *m0 = dae_modes_get(M, 0);
    double w = sqrt(G / P.L);
    tap_ok(st == BG_OK && ne == 1 && m0 && fabs(m0->freq_hz * 2 * PI - w) < 1e-9 * w &&
               fabs(m0->damping) < 1e-9 && nr == 0 && inf >= 1 && zero == 1,
           "pendulum modes: the swing at sqrt(g/L) = %.9g rad/s (%.9g), %d constraint modes at "
           "infinity (index 2) and %d at zero (the drift of r), no rigid mode",
           w, m0 ? m0->freq_hz * 2 * PI : NAN, inf, zero);
    dae_modes_free(&M);
    sp_csc_free(&Gp);
}

/* ---- steady motion: y = (xa, xm, vm) ---- */
typedef struct drag {
    double m, k, c, L0, V;
} drag;

static int drag_res(void *u, double t, const double *y, const double *yp, double *F)
{
    const drag *p = u;
    (void)t;
    F[0] = yp[0] - p->V;
    F[1] = yp[1] - y[2];
    F[2] = p->m * yp[2] - p->k * (y[0] - y[1] - p->L0) + p->c * y[2];
    return 0;
}

static void test_steady(void)
{
    drag P = {.m = 4, .k = 500, .c = 30, .L0 = 2, .V = 1.5};
    dae_problem p = {.n = 3, .res = drag_res, .user = &P};
    double y[3] = {10, 8, 0}, yps[3] = {P.V, P.V, 0}, yp[3];
    dae_static_options o;
    dae_static_options_default(&o);
    o.yp_steady = yps;
    bg_error err = {0};
    int st = dae_static_solve(&p, &o, 0.0, y, yp, NULL, &err);
    double trail = P.c * P.V / P.k;
    tap_ok(st == BG_OK && fabs(y[2] - P.V) < 1e-10 && fabs(y[0] - y[1] - P.L0 - trail) < 1e-10 &&
               y[0] == 10 && yp[0] == P.V,
           "steady motion at the prescribed rate %g: the mass moves at %.12g and trails by "
           "L0 + c V/k = %.12g (%s)",
           P.V, y[2], P.L0 + trail, st ? err.message : "ok");
}

/* ---- a saturating spring (force atan x, at most pi/2) under a load: y = (x, v, F) ---- */
typedef struct soft {
    double P, lam; /* load, the model's own load factor */
} soft;

static int soft_res(void *u, double t, const double *y, const double *yp, double *F)
{
    const soft *s = u;
    (void)t;
    F[0] = yp[0] - y[1];
    F[1] = yp[1] + y[2] - s->lam * s->P;
    F[2] = y[2] - atan(y[0]) - 0.1 * y[1];
    return 0;
}

static int soft_load(void *u, double lam)
{
    ((soft *)u)->lam = lam;
    return 0;
}

static void test_limit_point(void)
{
    static const char *const names[3] = {"spring/x", "spring/v", "spring/F"};
    static const char *const eqs[3] = {"spring/kinematics", "spring/balance", "spring/law"};
    soft S = {.P = 1.2, .lam = 1};
    dae_problem p = {.n = 3, .res = soft_res, .user = &S, .names = names, .eq_names = eqs};
    double x_want = tan(S.P);
    double y[3] = {0, 0, 0};
    bg_error err = {0};
    int st = dae_static_solve(&p, NULL, 0.0, y, NULL, NULL, &err);
    double y2[3] = {0, 0, 0};
    dae_static_options o;
    dae_static_options_default(&o);
    o.load = soft_load;
    o.load_user = &S;
    int st2 = dae_static_solve(&p, &o, 0.0, y2, NULL, NULL, &err);
    tap_ok(st == BG_OK && st2 == BG_OK && fabs(y[0] - x_want) < 1e-10 &&
               fabs(y2[0] - x_want) < 1e-10,
           "saturating spring under 1.2: x = %.12g (homotopy) and %.12g (the model's load "
           "factor), tan(1.2) = %.12g",
           y[0], y2[0], x_want);
    /* beyond the largest force pi/2: the path ends at lambda = (pi/2) / P */
    S.P = 2.0;
    S.lam = 1;
    double y3[3] = {0, 0, 0}, lim = 0.5 * PI / S.P;
    dae_static_result r;
    st = dae_static_solve(&p, NULL, 0.0, y3, NULL, &r, &err);
    tap_ok(st == DAE_CONV_FAIL && r.lambda <= lim && r.lambda > lim - 0.02 &&
               strstr(err.message, "spring/") != NULL,
           "saturating spring under 2 > pi/2: fails at load factor %.5g, the limit %.5g (%s)",
           r.lambda, lim, err.message);
}

/* ---- a chain of masses and springs with stretch states ---- */
typedef struct chain {
    int N;
    double m, k;
} chain;
/* y = (x_1..x_N, v_1..v_N, d_0..d_N) */
static int chain_res(void *u, double t, const double *y, const double *yp, double *F)
{
    const chain *c = u;
    (void)t;
    int N = c->N;
    const double *x = y, *v = y + N, *d = y + 2 * N;
    (void)x;
    for (int i = 0; i < N; i++) {
        F[i] = yp[i] - v[i];
        F[N + i] = c->m * yp[N + i] - c->k * d[i + 1] + c->k * d[i];
    }
    for (int j = 0; j <= N; j++) {
        double vr = j < N ? v[j] : 0, vl = j > 0 ? v[j - 1] : 0;
        F[2 * N + j] = yp[2 * N + j] - (vr - vl);
    }
    return 0;
}

static int chain_jac(void *u, double t, const double *y, const double *yp, sp_csc *Jy, sp_csc *Jyp)
{
    const chain *c = u;
    (void)t, (void)y, (void)yp;
    int N = c->N;
    for (int j = 0; j < Jy->ncol; j++)
        for (int p = Jy->colptr[j]; p < Jy->colptr[j + 1]; p++) {
            int i = Jy->rowind[p];
            double v = 0;
            if (j >= N && j < 2 * N) { /* v_{j-N} */
                int a = j - N;
                if (i == a) v = -1;
                if (i == 2 * N + a) v = -1;      /* d_a' - (v_a - v_{a-1}) */
                if (i == 2 * N + a + 1) v = 1;   /* d_{a+1}' - (v_{a+1} - v_a) */
            } else if (j >= 2 * N) {
                int b = j - 2 * N;
                if (i == N + b - 1) v = -c->k; /* mass b-1 (0-based) pulled by d_b */
                if (i == N + b) v = c->k;
            }
            Jy->val[p] = v;
        }
    for (int j = 0; j < Jyp->ncol; j++)
        for (int p = Jyp->colptr[j]; p < Jyp->colptr[j + 1]; p++)
            Jyp->val[p] = (j >= N && j < 2 * N) ? c->m : 1.0;
    return 0;
}

static sp_csc *chain_pattern(int N, int yp_part)
{
    int n = 3 * N + 1, nnz = 0;
    sp_csc *A = sp_csc_alloc(n, n, 4 * n);
    for (int j = 0; j < n; j++) {
        A->colptr[j] = nnz;
        if (yp_part) {
            A->rowind[nnz++] = j;
        } else if (j >= N && j < 2 * N) {
            int a = j - N;
            A->rowind[nnz++] = a;
            A->rowind[nnz++] = 2 * N + a;
            A->rowind[nnz++] = 2 * N + a + 1;
        } else if (j >= 2 * N) {
            int b = j - 2 * N;
            if (b >= 1) A->rowind[nnz++] = N + b - 1;
            if (b < N) A->rowind[nnz++] = N + b;
        }
    }
    A->colptr[n] = nnz;
    A->nnz = nnz;
    return A;
}

static void test_chain(void)
{
    chain C = {.N = 150, .m = 2.0, .k = 5e4};
    int N = C.N, n = 3 * N + 1;
    sp_csc *Jy = chain_pattern(N, 0), *Jyp = chain_pattern(N, 1);
    dae_problem p = {.n = n, .res = chain_res, .jac = chain_jac, .user = &C,
                     .jac_y_pattern = Jy, .jac_yp_pattern = Jyp};
    double *y = calloc((size_t)n, sizeof *y);
    for (int i = 0; i < N; i++)
        y[i] = i + 1;
    bg_error err = {0};
    /* dense: every mode */
    dae_modes *M = NULL;
    dae_modes_options o;
    dae_modes_options_default(&o);
    o.method = DAE_MODES_DENSE;
    int st = dae_modes_compute(&p, 0.0, y, NULL, &o, &M, &err);
    int ne = -1, nr = -1, nc = -1;
    dae_modes_info(M, &ne, &nr, &nc, NULL, NULL, NULL);
    double worst = 0, w0 = sqrt(C.k / C.m);
    for (int j = 1; j <= ne && j <= N; j++) {
        double want = 2 * w0 * sin(j * PI / (2 * (N + 1)));
        worst = fmax(worst, fabs(dae_modes_get(M, j - 1)->freq_hz * 2 * PI - want) / want);
    }
    tap_ok(st == BG_OK && ne == N && nr == 0 && nc == N + 1 && worst < 1e-9,
           "chain of %d masses, dense: %d elastic modes within %.2g of 2 sqrt(k/m) sin(j pi / "
           "(2 (N+1))), %d constraint modes at zero (the N positions and the sum of the "
           "stretches: N + 1)",
           N, ne, worst, nc);
    dae_modes_free(&M);
    /* sparse: the lowest 10 */
    o.method = DAE_MODES_SPARSE;
    o.nev = 10;
    st = dae_modes_compute(&p, 0.0, y, NULL, &o, &M, &err);
    worst = 0;
    double sig = 0;
    dae_modes_info(M, &ne, &nr, &nc, &sig, NULL, NULL);
    for (int j = 1; j <= ne; j++) {
        double want = 2 * w0 * sin(j * PI / (2 * (N + 1)));
        const dae_mode *md = dae_modes_get(M, j - 1);
        worst = fmax(worst, fabs(md->freq_hz * 2 * PI - want) / want + fabs(md->damping));
    }
    tap_ok(st == BG_OK && ne == 10 && worst < 1e-9,
           "chain, sparse (ARPACK, sigma %.3g): the lowest 10 modes within %.2g (damping "
           "included), none of the %d zero modes among them (%s)",
           sig, worst, N + 1, st ? err.message : "ok");
    dae_modes_free(&M);
    /* a window around mode 60 */
    o.sigma = 2 * w0 * sin(60 * PI / (2 * (N + 1)));
    o.nev = 8;
    st = dae_modes_compute(&p, 0.0, y, NULL, &o, &M, &err);
    int found60 = 0, all_close = 1;
    for (int k = 0; k < dae_modes_count(M); k++) {
        double w = dae_modes_get(M, k)->freq_hz * 2 * PI;
        double jj = asin(w / (2 * w0)) * 2 * (N + 1) / PI; /* which mode it is */
        if (fabs(jj - 60) < 1e-6) found60 = 1;
        if (fabs(jj - round(jj)) > 1e-6 || fabs(jj - 60) > 8) all_close = 0;
    }
    tap_ok(st == BG_OK && dae_modes_count(M) >= 8 && found60 && all_close,
           "chain, sparse window at mode 60's frequency: %d modes, all of the closed form and "
           "near mode 60",
           dae_modes_count(M));
    dae_modes_free(&M);
    free(y);
    sp_csc_free(&Jy);
    sp_csc_free(&Jyp);
}

static void test_misuse(void)
{
    bg_error err = {0};
    double y[3] = {0};
    tap_ok(dae_static_solve(NULL, NULL, 0, y, NULL, NULL, &err) == BG_ERR_ARGUMENT,
           "static: NULL problem refused");
    msd P = {.m = 1, .k = 1, .L0 = 0};
    dae_problem p = {.n = 3, .res = msd_res, .user = &P};
    dae_static_options o;
    dae_static_options_default(&o);
    o.rtol = -1;
    tap_ok(dae_static_solve(&p, &o, 0, y, NULL, NULL, &err) == BG_ERR_ARGUMENT &&
               strstr(err.message, "rtol"),
           "static: bad tolerance refused (%s)", err.message);
    dae_modes *M = NULL;
    tap_ok(dae_modes_compute(&p, 0, NULL, NULL, NULL, &M, &err) == BG_ERR_ARGUMENT && !M,
           "modes: NULL state refused");
    tap_ok(dae_modes_count(NULL) == 0 && dae_modes_get(NULL, 0) == NULL &&
               dae_modes_describe(NULL, 0, 1, 1, 1, NULL, 0) == BG_ERR_ARGUMENT,
           "modes: queries of NULL are harmless");
    dae_modes_free(&M);
    dae_modes_free(NULL);
}

/* ---- a hardening spring: y = (x, v), m v' = 1 - x - x^2/2 - c v; at rest x = sqrt(3) - 1 ---- */
static int hard_res(void *u, double t, const double *y, const double *yp, double *F)
{
    (void)u, (void)t;
    F[0] = yp[0] - y[1];
    F[1] = yp[1] + 0.5 * y[1] + y[0] + 0.5 * y[0] * y[0] - 1.0;
    return 0;
}

static const char *const hard_names[2] = {"spring/x", "spring/v"};

/* The checks of the problem's data (bg_check_nominal, bg_check_state) and of the modes
 * options: refused with the name of the unknown or field and the value, where a nominal of -1
 * used to give a wrong rest (x = 0.7396 for 0.7321, BG_OK) and NaN states reached the
 * factorization ("matrix entry (1,0) is nan"). */
static void test_checks(void)
{
    dae_problem p = {.n = 2, .res = hard_res, .names = hard_names};
    const double want = sqrt(3.0) - 1.0;
    double y[2] = {0, 0};
    bg_error err = {0};
    const double good[2] = {1, 1};
    p.nominal = good;
    int st = dae_static_solve(&p, NULL, 0, y, NULL, NULL, &err);
    tap_ok(st == BG_OK && fabs(y[0] - want) < 1e-9,
           "static: the hardening spring rests at x = %.10g (exact sqrt(3) - 1 = %.10g), status %d",
           y[0], want, st);
    /* nominal magnitudes that are not finite and > 0: named, by name or by index */
    const double badnom[3][2] = {{-1, 1}, {1, 0}, {NAN, 1}};
    const char *who[3] = {"spring/x", "spring/v", "spring/x"}, *val[3] = {"is -1", "is 0", "is nan"};
    for (int k = 0; k < 3; k++) {
        p.nominal = badnom[k];
        y[0] = y[1] = 0;
        st = dae_static_solve(&p, NULL, 0, y, NULL, NULL, &err);
        tap_ok(st == BG_ERR_ARGUMENT && strstr(err.message, who[k]) &&
                   strstr(err.message, val[k]) && strstr(err.message, "nominal") && y[0] == 0,
               "static: nominal (%g, %g) refused: %s", badnom[k][0], badnom[k][1], err.message);
        dae_modes *M = NULL;
        st = dae_modes_compute(&p, 0, y, NULL, NULL, &M, &err);
        tap_ok(st == BG_ERR_ARGUMENT && !M && strstr(err.message, who[k]) &&
                   strstr(err.message, val[k]) && strstr(err.message, "nominal"),
               "modes: nominal (%g, %g) refused: %s", badnom[k][0], badnom[k][1], err.message);
        dae_modes_free(&M);
    }
    p.names = NULL;
    p.nominal = badnom[0];
    st = dae_static_solve(&p, NULL, 0, y, NULL, NULL, &err);
    tap_ok(st == BG_ERR_ARGUMENT && strstr(err.message, "y[0]") && strstr(err.message, "is -1"),
           "static: without names the unknown is named by its index: %s", err.message);
    p.names = hard_names;
    p.nominal = good;
    /* a state that is not finite, named */
    double ybad[2] = {0, NAN}, ypbad[2] = {INFINITY, 0};
    st = dae_static_solve(&p, NULL, 0, ybad, NULL, NULL, &err);
    tap_ok(st == BG_ERR_NONFINITE && strstr(err.message, "starting value of spring/v") &&
               strstr(err.message, "nan"),
           "static: a NaN start named by the problem's name: %s", err.message);
    dae_modes *M = NULL;
    st = dae_modes_compute(&p, 0, ybad, NULL, NULL, &M, &err);
    tap_ok(st == BG_ERR_NONFINITE && !M && strstr(err.message, "value of spring/v") &&
               strstr(err.message, "nan"),
           "modes: a NaN state named: %s", err.message);
    st = dae_modes_compute(&p, 0, y, ypbad, NULL, &M, &err);
    tap_ok(st == BG_ERR_NONFINITE && !M && strstr(err.message, "derivative of spring/x") &&
               strstr(err.message, "inf"),
           "modes: an infinite derivative named: %s", err.message);
    /* every modes option out of range: the field, its value and the range */
    struct {
        const char *field, *text;
    } cases[10] = {{"method", "method = 3, it must be a dae_modes_method"},
                   {"dense_max", "dense_max = 0, it must be >= 1"},
                   {"sigma", "sigma = nan, it must be finite"},
                   {"nev", "nev = 0, it must be >= 1"},
                   {"ncv", "ncv = -1, it must be >= 0"},
                   {"tol", "tol = -1, it must be >= 0"},
                   {"maxiter", "maxiter = 0, it must be >= 1"},
                   {"zero_tol", "zero_tol = nan, it must be in [0, 1)"},
                   {"inf_tol", "inf_tol = -1, it must be in [0, 1)"},
                   {"linsol", "linsol = 7, it must be a linear solver"}};
    for (int k = 0; k < 10; k++) {
        dae_modes_options o;
        dae_modes_options_default(&o);
        switch (k) {
        case 0: o.method = 3; break;
        case 1: o.dense_max = 0; break;
        case 2: o.sigma = NAN; break;
        case 3: o.nev = 0; break;
        case 4: o.ncv = -1; break;
        case 5: o.tol = -1; break;
        case 6: o.maxiter = 0; break;
        case 7: o.zero_tol = NAN; break;
        case 8: o.inf_tol = -1; break;
        default: o.linsol = (ls_kind)7; break;
        }
        st = dae_modes_compute(&p, 0, y, NULL, &o, &M, &err);
        tap_ok(st == BG_ERR_ARGUMENT && !M && strstr(err.message, cases[k].text),
               "modes: options.%s out of range named with its value and range: %s",
               cases[k].field, err.message);
        dae_modes_free(&M);
    }
    /* the default of dense_max is the one the header states */
    dae_modes_options od;
    dae_modes_options_default(&od);
    tap_ok(od.dense_max == 1200 && od.method == DAE_MODES_AUTO,
           "modes: dense_max defaults to 1200 (bg_modes.h), got %d", od.dense_max);
}

int main(void)
{
    test_mass_spring(1);
    test_mass_spring(0);
    test_stretch_state();
    test_free_particle();
    test_pendulum();
    test_steady();
    test_limit_point();
    test_chain();
    test_misuse();
    test_checks();
    return tap_done();
}
