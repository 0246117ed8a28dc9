/* The problem collection of problems.h: residuals F(t, y, y') = 0 written from the published
 * equations, analytic Jacobians filled on patterns declared once with sp_builder, exact solutions
 * of the manufactured problems, reference end values with their sources, and the IVP Test Set's
 * accuracy measures (scd, mescd). Every residual is in the form F = y' - f for differential rows
 * (or eps*y' - f where the source scales the row) and F = g for algebraic rows, so that
 * dF/dy' is the identity on differential rows. */
#include "problems_impl.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bg_fdjac.h"

/* ---- helpers (problems_impl.h) ---- */

/* A pattern from a list of (row, column) pairs, values zero. */
int bpi_pattern_from_pairs(int nrow, int ncol, const int (*ij)[2], int npairs, sp_csc **out)
{
    sp_builder *b = sp_builder_create(nrow, ncol, npairs);
    *out = NULL;
    if (!b) return BG_ERR_MEMORY;
    for (int k = 0; k < npairs; k++)
        if (sp_builder_add(b, ij[k][0], ij[k][1], 0.0) < 0) {
            sp_builder_free(&b);
            return BG_ERR_MEMORY;
        }
    *out = sp_builder_finish(b, NULL);
    sp_builder_free(&b);
    return *out ? 0 : BG_ERR_MEMORY;
}

/* The identity on the first m diagonal entries of an n x n pattern (dF/dy' of y' - f). */
int bpi_pattern_diag(int n, int m, sp_csc **out)
{
    int(*ij)[2] = malloc(((size_t)m + 1) * sizeof *ij);
    if (!ij) return BG_ERR_MEMORY;
    for (int k = 0; k < m; k++)
        ij[k][0] = ij[k][1] = k;
    int st = bpi_pattern_from_pairs(n, n, (const int(*)[2])ij, m, out);
    free(ij);
    return st;
}

/* Two patterns, or none (on failure both are freed). */
int bpi_patterns_pair(int n, const int (*iy)[2], int ny, const int (*iyp)[2], int nyp, sp_csc **jy,
                      sp_csc **jyp)
{
    int st = bpi_pattern_from_pairs(n, n, iy, ny, jy);
    if (st == 0) st = bpi_pattern_from_pairs(n, n, iyp, nyp, jyp);
    if (st != 0) {
        sp_csc_free(jy);
        sp_csc_free(jyp);
    }
    return st;
}

/* dF/dy from (row, column) pairs and dF/dy' the identity on the first m diagonal entries (y' - f
 * with m differential rows); on failure jy is freed. */
int bpi_patterns_diag(int n, const int (*iy)[2], int ny, int m, sp_csc **jy, sp_csc **jyp)
{
    int st = bpi_pattern_from_pairs(n, n, iy, ny, jy);
    if (st == 0 && (st = bpi_pattern_diag(n, m, jyp)) != 0) sp_csc_free(jy);
    return st;
}

/* J(i,j) = v; entries outside the pattern are a programming error and are ignored. */
void bpi_set(sp_csc *J, int i, int j, double v)
{
    int p = sp_csc_find(J, i, j);
    if (p >= 0) J->val[p] = v;
}

/* Dense row-major n x n values D copied onto J's pattern. */
void bpi_fill_from_dense(sp_csc *J, const double *D, int n)
{
    for (int j = 0; j < J->ncol; j++)
        for (int p = J->colptr[j]; p < J->colptr[j + 1]; p++)
            J->val[p] = D[(size_t)J->rowind[p] * (size_t)n + (size_t)j];
}
/* ==== ap102: Ascher and Petzold, Computer Methods for Ordinary Differential Equations and
 * Differential-Algebraic Equations (SIAM 1998), Example 10.2; the same system as SUNDIALS'
 * idaAnalytic_mels example (LLNL/sundials, examples/ida/serial; docs/testset.md):
 *   x1' = (1-a)/(t-2) x1 - x1 + (a-1) x2 + 2 e^t,   0 = (t+2) (x1 - e^t),   a = 10,
 * exact x1 = e^t, x2 = e^t/(t-2). The constraint fixes x1; its derivative x1' = e^t fixes x2
 * through the first row: x2 is index 2. */
#define AP_ALPHA 10.0

static int ap102_res(void *user, double t, const double *y, const double *yp, double *F)
{
    (void)user;
    double et = exp(t);
    F[0] =
        yp[0] - ((1.0 - AP_ALPHA) / (t - 2.0) * y[0] - y[0] + (AP_ALPHA - 1.0) * y[1] + 2.0 * et);
    F[1] = (t + 2.0) * (y[0] - et);
    return 0;
}

static int ap102_jac(void *user, double t, const double *y, const double *yp, sp_csc *Jy,
                     sp_csc *Jyp)
{
    (void)user, (void)y, (void)yp;
    sp_csc_zero(Jy);
    sp_csc_zero(Jyp);
    bpi_set(Jy, 0, 0, -((1.0 - AP_ALPHA) / (t - 2.0) - 1.0));
    bpi_set(Jy, 0, 1, -(AP_ALPHA - 1.0));
    bpi_set(Jy, 1, 0, t + 2.0);
    bpi_set(Jyp, 0, 0, 1.0);
    return 0;
}

static int ap102_patterns(sp_csc **jy, sp_csc **jyp)
{
    static const int iy[][2] = {{0, 0}, {0, 1}, {1, 0}};
    static const int iyp[][2] = {{0, 0}};
    return bpi_patterns_pair(2, iy, 3, iyp, 1, jy, jyp);
}

static void ap102_exact(double t, double *y, double *yp)
{
    double et = exp(t), d = t - 2.0;
    y[0] = et;
    y[1] = et / d;
    if (yp) {
        yp[0] = et;
        yp[1] = et / d - et / (d * d);
    }
}

static const double ap102_y0[] = {1.0, -0.5};
static const double ap102_yp0[] = {1.0, -0.75};
static const int ap102_kind[] = {DAE_DIFF, DAE_ALG2};
static const char *const ap102_names[] = {"x1", "x2"};

/* ==== pendulum2: the index-2 pendulum of J. Cash's MEBDFDAE driver (pendul2.f, docs/testset.md):
 *   x' = u, y' = v, u' = -x lam, v' = -y lam - 1, 0 = x u + y v,  y(0) = (1, 0, 0, 1, 1).
 * The constraint is the velocity form of x^2 + y^2 = 1; lam is index 2 (g_x f_lam = -(x^2+y^2)).
 * Hidden constraint: d/dt (x u + y v) = u^2 + v^2 - lam (x^2 + y^2) - y = 0, so
 * lam = (u^2 + v^2 - y) / (x^2 + y^2) = 1 at t = 0, and lam' = -3 v = -3 there. */
static int pend_res(void *user, double t, const double *y, const double *yp, double *F)
{
    (void)user, (void)t;
    F[0] = yp[0] - y[2];
    F[1] = yp[1] - y[3];
    F[2] = yp[2] + y[0] * y[4];
    F[3] = yp[3] + y[1] * y[4] + 1.0;
    F[4] = y[0] * y[2] + y[1] * y[3];
    return 0;
}

static int pend_jac(void *user, double t, const double *y, const double *yp, sp_csc *Jy,
                    sp_csc *Jyp)
{
    (void)user, (void)t, (void)yp;
    sp_csc_zero(Jy);
    sp_csc_zero(Jyp);
    bpi_set(Jy, 0, 2, -1.0);
    bpi_set(Jy, 1, 3, -1.0);
    bpi_set(Jy, 2, 0, y[4]);
    bpi_set(Jy, 2, 4, y[0]);
    bpi_set(Jy, 3, 1, y[4]);
    bpi_set(Jy, 3, 4, y[1]);
    bpi_set(Jy, 4, 0, y[2]);
    bpi_set(Jy, 4, 1, y[3]);
    bpi_set(Jy, 4, 2, y[0]);
    bpi_set(Jy, 4, 3, y[1]);
    for (int i = 0; i < 4; i++)
        bpi_set(Jyp, i, i, 1.0);
    return 0;
}

static int pend_patterns(sp_csc **jy, sp_csc **jyp)
{
    static const int iy[][2] = {{0, 2}, {1, 3}, {2, 0}, {2, 4}, {3, 1},
                                {3, 4}, {4, 0}, {4, 1}, {4, 2}, {4, 3}};
    static const int iyp[][2] = {{0, 0}, {1, 1}, {2, 2}, {3, 3}};
    return bpi_patterns_pair(5, iy, 10, iyp, 4, jy, jyp);
}

int bp_pendulum_cons(void *user, double t, const double *y, double *g, sp_csc *G)
{
    (void)user, (void)t;
    g[0] = y[0] * y[0] + y[1] * y[1] - 1.0;
    if (G) {
        sp_csc_zero(G);
        bpi_set(G, 0, 0, 2.0 * y[0]);
        bpi_set(G, 0, 1, 2.0 * y[1]);
    }
    return 0;
}

static int pend_cons_pattern(sp_csc **g)
{
    static const int ij[][2] = {{0, 0}, {0, 1}};
    return bpi_pattern_from_pairs(1, 5, ij, 2, g);
}

static const double pend_y0[] = {1.0, 0.0, 0.0, 1.0, 1.0};
static const double pend_yp0[] = {0.0, 1.0, -1.0, -1.0, -3.0};
static const int pend_kind[] = {DAE_DIFF, DAE_DIFF, DAE_DIFF, DAE_DIFF, DAE_ALG2};
static const char *const pend_names[] = {"x", "y", "u", "v", "lam"};
/* An independent 30-digit Taylor-series recomputation of phi'' = -cos(phi) (docs/testset.md); the
 * published 18-digit values of pendul2.f are good to about 10-11 digits only. */
static const double pend_yref[] = {0.8673486406004393217343081, 0.4977010504796729293537128,
                                   -0.03374801806095451960914128, 0.0588130114652500075408496,
                                   -0.4931031514390187880611383};

/* ==== robertson: H. H. Robertson's chemical kinetics, IVP Test Set "rober"
 * (deTestSet ex_rober.R, docs/testset.md):
 *   y1' = -k1 y1 + k3 y2 y3,  y2' = k1 y1 - k2 y2^2 - k3 y2 y3,  y3' = k2 y2^2,
 * k1 = 0.04, k2 = 3e7, k3 = 1e4, y(0) = (1, 0, 0), t in [0, 1e11]. y1 + y2 + y3 = 1 is kept by the
 * exact flow (the rows sum to zero), which any linear multistep method preserves too. */
#define RB_K1 0.04
#define RB_K2 3.0e7
#define RB_K3 1.0e4

static int rober_res(void *user, double t, const double *y, const double *yp, double *F)
{
    (void)user, (void)t;
    F[0] = yp[0] - (-RB_K1 * y[0] + RB_K3 * y[1] * y[2]);
    F[1] = yp[1] - (RB_K1 * y[0] - RB_K2 * y[1] * y[1] - RB_K3 * y[1] * y[2]);
    F[2] = yp[2] - RB_K2 * y[1] * y[1];
    return 0;
}

static int rober_jac(void *user, double t, const double *y, const double *yp, sp_csc *Jy,
                     sp_csc *Jyp)
{
    (void)user, (void)t, (void)yp;
    sp_csc_zero(Jy);
    sp_csc_zero(Jyp);
    bpi_set(Jy, 0, 0, RB_K1);
    bpi_set(Jy, 0, 1, -RB_K3 * y[2]);
    bpi_set(Jy, 0, 2, -RB_K3 * y[1]);
    bpi_set(Jy, 1, 0, -RB_K1);
    bpi_set(Jy, 1, 1, 2.0 * RB_K2 * y[1] + RB_K3 * y[2]);
    bpi_set(Jy, 1, 2, RB_K3 * y[1]);
    bpi_set(Jy, 2, 1, -2.0 * RB_K2 * y[1]);
    for (int i = 0; i < 3; i++)
        bpi_set(Jyp, i, i, 1.0);
    return 0;
}

static int rober_patterns(sp_csc **jy, sp_csc **jyp)
{
    static const int iy[][2] = {{0, 0}, {0, 1}, {0, 2}, {1, 0}, {1, 1}, {1, 2}, {2, 1}};
    return bpi_patterns_diag(3, iy, 7, 3, jy, jyp);
}

static const double rober_y0[] = {1.0, 0.0, 0.0};
static const double rober_yp0[] = {-RB_K1, RB_K1, 0.0};
static const int rober_kind[] = {DAE_DIFF, DAE_DIFF, DAE_DIFF};
static const char *const rober_names[] = {"y1", "y2", "y3"};
/* deTestSet R/ex_reference.R, rober (docs/testset.md). */
static const double rober_yref[] = {0.2083340149701255e-7, 0.8333360770334713e-13,
                                    0.9999999791665050};

/* ==== vdp_scaled: van der Pol in the scaled form of the IVP Test Set "vdpol" (Test Set for IVP
 * Solvers, Release 2.4, problem vdpol.f):
 *   y1' = y2,  eps y2' = (1 - y1^2) y2 - y1,  eps = 1e-6,  y(0) = (2, 0),  t in [0, 2].
 * Note: deTestSet's ex_vdpol.R is the unscaled variant (mu = 1000, t in [0, 2000]) and
 * deTestSet's reference collection has no van der Pol entry. The reference below is the
 * IVP Test Set's own (vdpol.f, subroutine solut: RADAU in extended precision, rtol = atol = h0 =
 * 1.1e-18), which belongs to y(0) = (2, 0); Hairer and Wanner's smooth start y2(0) = -2/3 +
 * 10/81 eps - ... would shift the solution by O(eps) and is therefore not used. */
#define VDP_EPS 1.0e-6

static int vdp_res(void *user, double t, const double *y, const double *yp, double *F)
{
    (void)user, (void)t;
    F[0] = yp[0] - y[1];
    F[1] = VDP_EPS * yp[1] - ((1.0 - y[0] * y[0]) * y[1] - y[0]);
    return 0;
}

static int vdp_jac(void *user, double t, const double *y, const double *yp, sp_csc *Jy, sp_csc *Jyp)
{
    (void)user, (void)t, (void)yp;
    sp_csc_zero(Jy);
    sp_csc_zero(Jyp);
    bpi_set(Jy, 0, 1, -1.0);
    bpi_set(Jy, 1, 0, 2.0 * y[0] * y[1] + 1.0);
    bpi_set(Jy, 1, 1, -(1.0 - y[0] * y[0]));
    bpi_set(Jyp, 0, 0, 1.0);
    bpi_set(Jyp, 1, 1, VDP_EPS);
    return 0;
}

static int vdp_patterns(sp_csc **jy, sp_csc **jyp)
{
    static const int iy[][2] = {{0, 1}, {1, 0}, {1, 1}};
    return bpi_patterns_diag(2, iy, 3, 2, jy, jyp);
}

static const double vdp_y0[] = {2.0, 0.0};
static const double vdp_yp0[] = {0.0, -2.0 / VDP_EPS};
static const int vdp_kind[] = {DAE_DIFF, DAE_DIFF};
static const char *const vdp_names[] = {"y1", "y2"};
static const double vdp_yref[] = {0.1706167732170483e+01, -0.8928097010247975e+00};

/* ==== hires: HIRES, plant physiology (Schaefer 1975), IVP Test Set "hires"
 * (deTestSet Ex_hires.f, ex_hires.R; docs/testset.md); t in [0, 321.8122]. */
#define HI_K1 1.71
#define HI_K2 0.43
#define HI_K3 8.32
#define HI_K4 0.69
#define HI_K5 0.035
#define HI_K6 8.32
#define HI_K7 280.0
#define HI_K8 0.69
#define HI_K9 0.69
#define HI_OKS 0.0007

static void hires_f(const double *y, double *f)
{
    f[0] = -HI_K1 * y[0] + HI_K2 * y[1] + HI_K6 * y[2] + HI_OKS;
    f[1] = HI_K1 * y[0] - (HI_K2 + HI_K3) * y[1];
    f[2] = -(HI_K6 + HI_K1) * y[2] + HI_K2 * y[3] + HI_K5 * y[4];
    f[3] = HI_K3 * y[1] + HI_K1 * y[2] - (HI_K4 + HI_K2) * y[3];
    f[4] = -(HI_K5 + HI_K1) * y[4] + HI_K2 * (y[5] + y[6]);
    f[5] = -HI_K7 * y[5] * y[7] + HI_K8 * y[3] + HI_K1 * y[4] - HI_K2 * y[5] + HI_K8 * y[6];
    f[6] = HI_K7 * y[5] * y[7] - (HI_K2 + HI_K8 + HI_K9) * y[6];
    f[7] = -f[6];
}

static int hires_res(void *user, double t, const double *y, const double *yp, double *F)
{
    (void)user, (void)t;
    double f[8];
    hires_f(y, f);
    for (int i = 0; i < 8; i++)
        F[i] = yp[i] - f[i];
    return 0;
}

/* Pattern of df/dy (Ex_hires.f, hiresjac); dF/dy = -df/dy. */
static const int hires_ij[][2] = {{0, 0}, {0, 1}, {0, 2}, {1, 0}, {1, 1}, {2, 2}, {2, 3},
                                  {2, 4}, {3, 1}, {3, 2}, {3, 3}, {4, 4}, {4, 5}, {4, 6},
                                  {5, 3}, {5, 4}, {5, 5}, {5, 6}, {5, 7}, {6, 5}, {6, 6},
                                  {6, 7}, {7, 5}, {7, 6}, {7, 7}};

static int hires_jac(void *user, double t, const double *y, const double *yp, sp_csc *Jy,
                     sp_csc *Jyp)
{
    (void)user, (void)t, (void)yp;
    sp_csc_zero(Jy);
    sp_csc_zero(Jyp);
    /* df/dy row by row, entered negated */
    bpi_set(Jy, 0, 0, HI_K1);
    bpi_set(Jy, 0, 1, -HI_K2);
    bpi_set(Jy, 0, 2, -HI_K6);
    bpi_set(Jy, 1, 0, -HI_K1);
    bpi_set(Jy, 1, 1, HI_K2 + HI_K3);
    bpi_set(Jy, 2, 2, HI_K6 + HI_K1);
    bpi_set(Jy, 2, 3, -HI_K2);
    bpi_set(Jy, 2, 4, -HI_K5);
    bpi_set(Jy, 3, 1, -HI_K3);
    bpi_set(Jy, 3, 2, -HI_K1);
    bpi_set(Jy, 3, 3, HI_K4 + HI_K2);
    bpi_set(Jy, 4, 4, HI_K5 + HI_K1);
    bpi_set(Jy, 4, 5, -HI_K2);
    bpi_set(Jy, 4, 6, -HI_K2);
    bpi_set(Jy, 5, 3, -HI_K8);
    bpi_set(Jy, 5, 4, -HI_K1);
    bpi_set(Jy, 5, 5, HI_K7 * y[7] + HI_K2);
    bpi_set(Jy, 5, 6, -HI_K8);
    bpi_set(Jy, 5, 7, HI_K7 * y[5]);
    bpi_set(Jy, 6, 5, -HI_K7 * y[7]);
    bpi_set(Jy, 6, 6, HI_K2 + HI_K8 + HI_K9);
    bpi_set(Jy, 6, 7, -HI_K7 * y[5]);
    bpi_set(Jy, 7, 5, HI_K7 * y[7]);
    bpi_set(Jy, 7, 6, -(HI_K2 + HI_K8 + HI_K9));
    bpi_set(Jy, 7, 7, HI_K7 * y[5]);
    for (int i = 0; i < 8; i++)
        bpi_set(Jyp, i, i, 1.0);
    return 0;
}

static int hires_patterns(sp_csc **jy, sp_csc **jyp)
{
    return bpi_patterns_diag(8, hires_ij, 25, 8, jy, jyp);
}

static const double hires_y0[] = {1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0057};
static const double hires_yp0[] = {-HI_K1 + HI_OKS, HI_K1, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
static const int hires_kind[] = {DAE_DIFF, DAE_DIFF, DAE_DIFF, DAE_DIFF,
                                 DAE_DIFF, DAE_DIFF, DAE_DIFF, DAE_DIFF};
static const char *const hires_names[] = {"Pr",   "Pfr",   "PrX",    "PfrX",
                                          "PrX2", "PfrX2", "PfrX2E", "E"};
/* deTestSet R/ex_reference.R, hires (docs/testset.md); hiressol in
 * Ex_hires.f: RADAU5 in extended precision, rtol = atol = h0 = 1.1e-18). */
static const double hires_yref[] = {
    0.7371312573325668e-3, 0.1442485726316185e-3, 0.5888729740967575e-4, 0.1175651343283149e-2,
    0.2386356198831331e-2, 0.6238968252742796e-2, 0.2849998395185769e-2, 0.2850001604814231e-2};

/* ==== lin2: a linear semi-explicit index-2 system with a manufactured solution (ours):
 *   x1' = x2 + lam + f1(t),  x2' = -x1 + 2 lam + f2(t),  0 = x1 + x2 - s(t).
 * Index 2: g_x f_lam = (1, 1) . (1, 2)^T = 3 != 0, so one differentiation of the constraint,
 * x1' + x2' = s', gives 3 lam = s' - x2 + x1 - f1 - f2, i.e. lam after a second one. On the
 * constraint manifold (x2 = s - x1) the flow is x1' = (-x1 + s' + 2 s + 2 f1 - f2) / 3: a
 * stable mode with rate 1/3. The forcing is chosen so that the exact solution is
 *   x1 = sin t,  x2 = cos 2t,  lam = e^-t,
 * i.e. f1 = x1' - x2 - lam, f2 = x2' + x1 - 2 lam, s = x1 + x2 evaluated on it. */
static void lin2_exact(double t, double *y, double *yp)
{
    y[0] = sin(t);
    y[1] = cos(2.0 * t);
    y[2] = exp(-t);
    if (yp) {
        yp[0] = cos(t);
        yp[1] = -2.0 * sin(2.0 * t);
        yp[2] = -exp(-t);
    }
}

static int lin2_res(void *user, double t, const double *y, const double *yp, double *F)
{
    (void)user;
    double e[3], ep[3];
    lin2_exact(t, e, ep);
    F[0] = yp[0] - y[1] - y[2] - (ep[0] - e[1] - e[2]);
    F[1] = yp[1] + y[0] - 2.0 * y[2] - (ep[1] + e[0] - 2.0 * e[2]);
    F[2] = y[0] + y[1] - (e[0] + e[1]);
    return 0;
}

static int lin2_jac(void *user, double t, const double *y, const double *yp, sp_csc *Jy,
                    sp_csc *Jyp)
{
    (void)user, (void)t, (void)y, (void)yp;
    sp_csc_zero(Jy);
    sp_csc_zero(Jyp);
    bpi_set(Jy, 0, 1, -1.0);
    bpi_set(Jy, 0, 2, -1.0);
    bpi_set(Jy, 1, 0, 1.0);
    bpi_set(Jy, 1, 2, -2.0);
    bpi_set(Jy, 2, 0, 1.0);
    bpi_set(Jy, 2, 1, 1.0);
    bpi_set(Jyp, 0, 0, 1.0);
    bpi_set(Jyp, 1, 1, 1.0);
    return 0;
}

static int lin2_patterns(sp_csc **jy, sp_csc **jyp)
{
    static const int iy[][2] = {{0, 1}, {0, 2}, {1, 0}, {1, 2}, {2, 0}, {2, 1}};
    return bpi_patterns_diag(3, iy, 6, 2, jy, jyp);
}

static const double lin2_y0[] = {0.0, 1.0, 1.0};
static const double lin2_yp0[] = {1.0, 0.0, -1.0};
static const int lin2_kind[] = {DAE_DIFF, DAE_DIFF, DAE_ALG2};
static const char *const lin2_names[] = {"x1", "x2", "lam"};

/* ==== smooth_ode: y' = A y + r(t), A = [-1 1; -1 -3] (double eigenvalue -2), with r chosen so
 * that y1 = e^-t + sin t, y2 = cos 2t + e^-2t (ours). */
static void smooth_exact(double t, double *y, double *yp)
{
    y[0] = exp(-t) + sin(t);
    y[1] = cos(2.0 * t) + exp(-2.0 * t);
    if (yp) {
        yp[0] = -exp(-t) + cos(t);
        yp[1] = -2.0 * sin(2.0 * t) - 2.0 * exp(-2.0 * t);
    }
}

static int smooth_res(void *user, double t, const double *y, const double *yp, double *F)
{
    (void)user;
    double e[2], ep[2];
    smooth_exact(t, e, ep);
    F[0] = yp[0] - (-y[0] + y[1]) - (ep[0] - (-e[0] + e[1]));
    F[1] = yp[1] - (-y[0] - 3.0 * y[1]) - (ep[1] - (-e[0] - 3.0 * e[1]));
    return 0;
}

static int smooth_jac(void *user, double t, const double *y, const double *yp, sp_csc *Jy,
                      sp_csc *Jyp)
{
    (void)user, (void)t, (void)y, (void)yp;
    sp_csc_zero(Jy);
    sp_csc_zero(Jyp);
    bpi_set(Jy, 0, 0, 1.0);
    bpi_set(Jy, 0, 1, -1.0);
    bpi_set(Jy, 1, 0, 1.0);
    bpi_set(Jy, 1, 1, 3.0);
    bpi_set(Jyp, 0, 0, 1.0);
    bpi_set(Jyp, 1, 1, 1.0);
    return 0;
}

static int smooth_patterns(sp_csc **jy, sp_csc **jyp)
{
    static const int iy[][2] = {{0, 0}, {0, 1}, {1, 0}, {1, 1}};
    return bpi_patterns_diag(2, iy, 4, 2, jy, jyp);
}

static const double smooth_y0[] = {1.0, 2.0};
static const double smooth_yp0[] = {0.0, -2.0};
static const int smooth_kind[] = {DAE_DIFF, DAE_DIFF};
static const char *const smooth_names[] = {"y1", "y2"};

/* ==== kinks: y1' = u(t), y2' = y1, y(0) = 0, t in [0, 1], u piecewise linear through the nodes
 * (0, 1), (0.3, -1), (0.55, 2), (0.8, 0.5), (1, 1.5): kinks of u (jumps of y1'') at 0.3, 0.55
 * and 0.8, the problem's breakpoints. Exact y1 piecewise quadratic, y2 piecewise cubic (ours). */
#define KINK_NODES 5
static const double kink_t[KINK_NODES] = {0.0, 0.3, 0.55, 0.8, 1.0};
static const double kink_u[KINK_NODES] = {1.0, -1.0, 2.0, 0.5, 1.5};
static const double kink_bp[] = {0.3, 0.55, 0.8};

/* Segment of t (the first for t < 0.3, the last for t >= 0.8, extrapolating beyond). */
static int kink_segment(double t)
{
    int s = 0;
    while (s < KINK_NODES - 2 && t >= kink_t[s + 1])
        s++;
    return s;
}

static double kink_slope(int s)
{
    return (kink_u[s + 1] - kink_u[s]) / (kink_t[s + 1] - kink_t[s]);
}

static double kink_force(double t)
{
    int s = kink_segment(t);
    return kink_u[s] + kink_slope(s) * (t - kink_t[s]);
}

static void kinks_exact(double t, double *y, double *yp)
{
    double y1 = 0.0, y2 = 0.0;
    int s = 0;
    /* whole segments before t's */
    int last = kink_segment(t);
    for (s = 0; s < last; s++) {
        double d = kink_t[s + 1] - kink_t[s], u = kink_u[s], m = kink_slope(s);
        y2 += y1 * d + u * d * d / 2.0 + m * d * d * d / 6.0;
        y1 += u * d + m * d * d / 2.0;
    }
    double d = t - kink_t[last], u = kink_u[last], m = kink_slope(last);
    y[1] = y2 + y1 * d + u * d * d / 2.0 + m * d * d * d / 6.0;
    y[0] = y1 + u * d + m * d * d / 2.0;
    if (yp) {
        yp[0] = u + m * d;
        yp[1] = y[0];
    }
}

static int kinks_res(void *user, double t, const double *y, const double *yp, double *F)
{
    (void)user;
    F[0] = yp[0] - kink_force(t);
    F[1] = yp[1] - y[0];
    return 0;
}

static int kinks_jac(void *user, double t, const double *y, const double *yp, sp_csc *Jy,
                     sp_csc *Jyp)
{
    (void)user, (void)t, (void)y, (void)yp;
    sp_csc_zero(Jy);
    sp_csc_zero(Jyp);
    bpi_set(Jy, 1, 0, -1.0);
    bpi_set(Jyp, 0, 0, 1.0);
    bpi_set(Jyp, 1, 1, 1.0);
    return 0;
}

static int kinks_patterns(sp_csc **jy, sp_csc **jyp)
{
    static const int iy[][2] = {{1, 0}};
    return bpi_patterns_diag(2, iy, 1, 2, jy, jyp);
}

static const double kinks_y0[] = {0.0, 0.0};
static const double kinks_yp0[] = {1.0, 0.0};
static const int kinks_kind[] = {DAE_DIFF, DAE_DIFF};
static const char *const kinks_names[] = {"y1", "y2"};

/* ==== the table ==== */

static const bp_problem problems[] = {
    {.name = "ap102",
     .title = "Ascher-Petzold Ex. 10.2 (linear index 2, exact solution)",
     .n = 2,
     .t0 = 0.0,
     .tend = 1.0,
     BP_PARTS(ap102),
     .exact = ap102_exact,
     .ref_source = "exact solution x1 = e^t, x2 = e^t/(t-2)"},
    {.name = "pendulum2",
     .title = "pendulum, index-2 formulation (Cash, pendul2.f)",
     .n = 5,
     .t0 = 0.0,
     .tend = 1.0,
     BP_PARTS(pend),
     .yref = pend_yref,
     .ref_source = "30-digit Taylor-series recomputation (docs/testset.md)",
     .ncons = 1,
     .cons = bp_pendulum_cons,
     .cons_pattern = pend_cons_pattern},
    {.name = "robertson",
     .title = "Robertson chemical kinetics (IVP Test Set rober)",
     .n = 3,
     .t0 = 0.0,
     .tend = 1.0e11,
     BP_PARTS(rober),
     .yref = rober_yref,
     .ref_source = "deTestSet ex_reference.R rober (docs/testset.md)"},
    {.name = "vdp_scaled",
     .title = "van der Pol, scaled, eps = 1e-6 (IVP Test Set vdpol)",
     .n = 2,
     .t0 = 0.0,
     .tend = 2.0,
     BP_PARTS(vdp),
     .yref = vdp_yref,
     .ref_source = "IVP Test Set 2.4 vdpol.f solut (RADAU, rtol = atol = 1.1e-18; "
                   "docs/testset.md)"},
    {.name = "hires",
     .title = "HIRES plant physiology (IVP Test Set hires)",
     .n = 8,
     .t0 = 0.0,
     .tend = 321.8122,
     BP_PARTS(hires),
     .yref = hires_yref,
     .ref_source = "deTestSet ex_reference.R hires (docs/testset.md)"},
    {.name = "lin2",
     .title = "linear index 2, manufactured solution x1 = sin t, x2 = cos 2t, lam = e^-t",
     .n = 3,
     .t0 = 0.0,
     .tend = 2.0,
     BP_PARTS(lin2),
     .exact = lin2_exact,
     .ref_source = "exact solution"},
    {.name = "smooth_ode",
     .title = "linear 2x2 ODE, manufactured solution",
     .n = 2,
     .t0 = 0.0,
     .tend = 2.0,
     BP_PARTS(smooth),
     .exact = smooth_exact,
     .ref_source = "exact solution"},
    {.name = "kinks",
     .title = "y1' = u(t) piecewise linear with kinks, y2' = y1",
     .n = 2,
     .t0 = 0.0,
     .tend = 1.0,
     BP_PARTS(kinks),
     .exact = kinks_exact,
     .ref_source = "exact solution (piecewise polynomial)",
     .nbreakpoints = 3,
     .breakpoints = kink_bp},
};

#define NPROBLEMS ((int)(sizeof problems / sizeof problems[0]))

int bp_count(void)
{
    return NPROBLEMS;
}

const bp_problem *bp_get(int i)
{
    return (i >= 0 && i < NPROBLEMS) ? &problems[i] : NULL;
}

const bp_problem *bp_find(const char *name)
{
    if (!name) return NULL;
    for (int i = 0; i < bp_count(); i++)
        if (strcmp(bp_get(i)->name, name) == 0) return bp_get(i);
    for (int i = 0; i < bp_testset_count(); i++)
        if (strcmp(bp_testset_get(i)->name, name) == 0) return bp_testset_get(i);
    for (int i = 0; i < bp_osc_count(); i++)
        if (strcmp(bp_osc_get(i)->name, name) == 0) return bp_osc_get(i);
    return NULL;
}

/* ==== instances ==== */

void bp_instance_free(bp_instance *in)
{
    if (!in) return;
    sp_csc_free(&in->jy);
    sp_csc_free(&in->jyp);
    sp_csc_free(&in->g);
    memset(in, 0, sizeof *in);
}

int bp_instance_init(bp_instance *in, const bp_problem *p)
{
    memset(in, 0, sizeof *in);
    in->p = p;
    if (p->patterns(&in->jy, &in->jyp) != 0) goto fail;
    if (p->ncons > 0 && p->cons_pattern(&in->g) != 0) goto fail;
    in->dp.n = p->n;
    in->dp.res = p->res;
    in->dp.jac = p->jac;
    in->dp.jac_y_pattern = in->jy;
    in->dp.jac_yp_pattern = in->jyp;
    in->dp.kind = p->kind;
    in->dp.names = p->names;
    in->dp.user = NULL;
    in->dp.ncons = p->ncons;
    in->dp.cons = p->ncons > 0 ? p->cons : NULL;
    in->dp.cons_pattern = in->g;
    in->dp.nroots = 0;
    in->dp.roots = NULL;
    return 0;
fail:
    bp_instance_free(in);
    return BG_ERR_MEMORY;
}

int bp_reference(const bp_problem *p, double *yref)
{
    if (p->yref) {
        memcpy(yref, p->yref, (size_t)p->n * sizeof *yref);
        return 0;
    }
    if (p->exact) {
        p->exact(p->tend, yref, NULL);
        return 0;
    }
    return -1;
}

/* ==== accuracy ==== */

static double neglog10(double e, int any)
{
    if (!any) return NAN;
    if (isnan(e)) return -INFINITY;
    return e > 0 ? -log10(e) : INFINITY;
}

void bp_score_compute(const bp_problem *p, const double *y, const double *yref, double rtol,
                      double atol, bp_score *s)
{
    double e_scd = 0, e_mescd = 0, e_scd2 = 0, e_mescd2 = 0, worst_e = -1;
    int n_scd = 0, n_mescd = 0, n_scd2 = 0, n_mescd2 = 0;
    int nan_seen = 0, nan2_seen = 0;
    s->worst = -1;
    for (int i = 0; i < p->n; i++) {
        int i2 = p->kind[i] == DAE_ALG2;
        double d = fabs(y[i] - yref[i]);
        if (isnan(d)) {
            if (i2)
                nan2_seen = 1;
            else
                nan_seen = 1;
        }
        double em = d / (atol / rtol + fabs(yref[i]));
        if (i2) {
            n_mescd2++;
            if (em > e_mescd2) e_mescd2 = em;
        } else {
            n_mescd++;
            if (em > e_mescd) e_mescd = em;
        }
        if ((!p->scored || p->scored[i]) && yref[i] != 0.0) {
            double er = d / fabs(yref[i]);
            if (i2) {
                n_scd2++;
                if (er > e_scd2) e_scd2 = er;
            } else {
                n_scd++;
                if (er > e_scd) e_scd = er;
                if (er > worst_e || isnan(er)) {
                    worst_e = isnan(er) ? INFINITY : er;
                    s->worst = i;
                }
            }
        }
    }
    s->scd = nan_seen ? -INFINITY : neglog10(e_scd, n_scd);
    s->mescd = nan_seen ? -INFINITY : neglog10(e_mescd, n_mescd);
    s->scd_i2 = nan2_seen ? -INFINITY : neglog10(e_scd2, n_scd2);
    s->mescd_i2 = nan2_seen ? -INFINITY : neglog10(e_mescd2, n_mescd2);
}

/* ==== Jacobian check ==== */

typedef struct jc_ctx {
    const bp_problem *p;
    double t;
    const double *y, *yp;
} jc_ctx;

static int jc_f_y(void *user, const double *x, double *f)
{
    jc_ctx *c = user;
    return c->p->res(NULL, c->t, x, c->yp, f);
}

static int jc_f_yp(void *user, const double *x, double *f)
{
    jc_ctx *c = user;
    return c->p->res(NULL, c->t, c->y, x, f);
}

int bp_check_jacobian(const bp_problem *p, double t, const double *y, const double *yp,
                      double floor, double *max_err_y, double *max_err_yp)
{
    sp_csc *jy = NULL, *jyp = NULL;
    jc_ctx c = {p, t, y, yp};
    int st = p->patterns(&jy, &jyp);
    *max_err_y = *max_err_yp = INFINITY;
    if (st != 0) return st;
    st = p->jac(NULL, t, y, yp, jy, jyp);
    if (st == 0) {
        int r = sp_jac_check(jy, jc_f_y, &c, p->n, y, floor, INFINITY, NULL, 0, max_err_y);
        if (r < 0) st = r;
    }
    if (st == 0) {
        int r = sp_jac_check(jyp, jc_f_yp, &c, p->n, yp, floor, INFINITY, NULL, 0, max_err_yp);
        if (r < 0) st = r;
    }
    sp_csc_free(&jy);
    sp_csc_free(&jyp);
    return st;
}
