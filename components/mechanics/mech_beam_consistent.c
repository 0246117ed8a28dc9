/* The consistent co-rotational beam element's own parts (equations in mech_beam.h): its rotation
 * measure, the bowing term of its axial strain, and its inertia.
 * Inertia: the kinetic energy is that of "points" moving with vector fields of the configuration:
 * the displacement field r(xi) carries the mass rho A, the section's directors D2(xi), D3(xi)
 * carry rho I_z and rho I_y (a rigid section with directors e2, e3 and the "masses" I_z, I_y has
 * the inertia I_y + I_z, I_y, I_z about e1, e2, e3: sum_i m_i |e_i'|^2 = w^T sum_i m_i (1 - e_i
 * e_i^T) w), at the 4 Gauss points, less the same points at the nodes (r = x, D = the node
 * triad's t2, t3: the node bodies' lumped masses and rotary inertias, exactly), and the bending
 * mass template's three points over the rates of the chord e1 and the node axes t1 (mech_beam.h,
 * change 4). Every field is a combination sum_b c_b(xi) B_b of 24 basis vectors: 22 made here
 * on the AD numbers of the element's energy (mech_beam.c), so that their velocity gradients and
 * Hessians give the points' velocities and accelerations exactly, and the node positions x_a,
 * x_b. The inertia loads follow by d'Alembert's principle, f = sum_p mu_p G_p^T (r_p'' - g). */
#include <math.h>
#include <string.h>

#include "mech_beam_impl.h"

/* The rotation measure: the skew part s of E^T T is sin(phi) n for a
 * relative rotation phi about n; th = s asin(|s|) / |s| is the rotation vector phi n itself
 * (the logarithm of the relative rotation, phi < pi / 2), so that the local deformations are
 * the angles the element's cubic field is written in. f(x) = asin(sqrt x) / sqrt x of x = |s|^2,
 * by its series sum c_j x^j (c_j = (2j)! / (4^j j!^2 (2j + 1))) below x = 0.04 (truncation
 * 3e-12), else in closed form. */
void mech_beam_angles_(const ad_ctx *c, beam_work *k, ad *th)
{
    ad_const(c, 0.0, &k->t1);
    for (int i = 0; i < 3; i++) {
        ad_mul(c, &th[i], &th[i], &k->t2);
        ad_axpy(c, &k->t1, 1.0, &k->t2, &k->t1);
    }
    double x = k->t1.v, f, fp, fpp;
    if (x < 0.04) {
        static const double cj[7] = {1.0,         1.0 / 6,     3.0 / 40,     5.0 / 112,
                                     35.0 / 1152, 63.0 / 2816, 231.0 / 13312};
        f = fp = fpp = 0;
        for (int j = 6; j >= 0; j--) {
            f = f * x + cj[j];
            if (j >= 1) fp = fp * x + j * cj[j];
            if (j >= 2) fpp = fpp * x + j * (j - 1) * cj[j];
        }
    } else {
        double sg = sqrt(x), A = asin(fmin(sg, 1.0)), r = sqrt(fmax(1 - x, 1e-300));
        f = A / sg;
        fp = 1 / (2 * x * r) - A / (2 * x * sg);
        fpp = -3 / (4 * x * x * r) + 1 / (4 * x * r * r * r) + 3 * A / (4 * x * x * sg);
    }
    ad_apply(c, &k->t1, f, fp, fpp, &k->t2);
    for (int i = 0; i < 3; i++) {
        ad_mul(c, &th[i], &k->t2, &k->t1);
        th[i] = k->t1;
    }
}

/* The bowing term: W += EA L0 eps^2 / 2, eps = u / L0 + (L / L0) bow / 30 (k->L, k->u, k->th
 * set). */
void mech_beam_bow_(const ad_ctx *c, beam_work *k, double EA, double L0, int quartic)
{
    ad_const(c, 0.0, &k->bow);
    for (int a = 1; a <= 2; a++) { /* theta_y, theta_z */
        const ad *ta = &k->th[a], *tb = &k->th[3 + a];
        ad_mul(c, ta, ta, &k->t2);
        ad_axpy(c, &k->bow, 2.0, &k->t2, &k->bow);
        ad_mul(c, tb, tb, &k->t2);
        ad_axpy(c, &k->bow, 2.0, &k->t2, &k->bow);
        ad_mul(c, ta, tb, &k->t2);
        ad_axpy(c, &k->bow, -1.0, &k->t2, &k->bow);
        if (!quartic) continue;
        /* the bubble: 30 int (H1' ta + H2' tb + B' b)^2 / 2 adds (ta - tb) b + 2 b^2 / 7
         * (int H1' B' = 1/30, int H2' B' = -1/30, int B'^2 = 2/105) */
        const ad *bb = &k->bub[a - 1];
        ad_axpy(c, ta, -1.0, tb, &k->t1);
        ad_mul(c, &k->t1, bb, &k->t2);
        ad_axpy(c, &k->bow, 1.0, &k->t2, &k->bow);
        ad_mul(c, bb, bb, &k->t2);
        ad_axpy(c, &k->bow, 2.0 / 7, &k->t2, &k->bow);
    }
    /* the arc L (1 + bow / 30) of the field over the current chord L (mech_beam.h): eps = u / L0
     * + (L / L0) bow / 30 */
    ad_scale(c, 1.0 / L0, &k->L, &k->t1);
    ad_mul(c, &k->t1, &k->bow, &k->t2);
    ad_scale(c, 1.0 / L0, &k->u, &k->eps);
    ad_axpy(c, &k->eps, 1.0 / 30, &k->t2, &k->eps);
    ad_mul(c, &k->eps, &k->eps, &k->t2);
    ad_axpy(c, &k->W, 0.5 * EA * L0, &k->t2, &k->W);
}

void mech_beam_bow_loads_(const double *d, double EA, double L0, double *z)
{
    double bow = 0, s = 1 + d[0] / L0; /* s = L / L0 */
    for (int a = 2; a <= 3; a++)
        bow += 2 * d[a] * d[a] - d[a] * d[a + 3] + 2 * d[a + 3] * d[a + 3];
    double N = EA * (d[0] / L0 + s * bow / 30); /* the axial force EA eps */
    z[0] += (EA * s + N) * bow / 30;            /* dW/du = N (1 + bow / 30) */
    for (int a = 2; a <= 3; a++) {
        z[a] += N * L0 * s * (4 * d[a] - d[a + 3]) / 30;
        z[a + 3] += N * L0 * s * (4 * d[a + 3] - d[a]) / 30;
    }
}

/* 4-point Gauss-Legendre rule on [0, 1]: points and weights */
static const double GX[4] = {0.069431844202973712, 0.33000947820757187, 0.66999052179242813,
                             0.93056815579702629};
static const double GW[4] = {0.17392742256872693, 0.32607257743127307, 0.32607257743127307,
                             0.17392742256872693};

enum { NV = MECH_BEAM_NBASIS, NB = NV + 2, XA = NV, XB = NV + 1, NP = MECH_BEAM_NPOINTS };

/* The basis: 0 P = th_z,a e2 - th_y,a e3, 1 Q = th_z,b e2 - th_y,b e3, 2 e2, 3 e3,
 * 4 th_x,a e3, 5 th_x,b e3, 6 th_z,a e1, 7 th_z,b e1, 8 th_x,a e2, 9 th_x,b e2, 10 th_y,a e1,
 * 11 th_y,b e1, 12 t2 of node a, 13 t2 of node b, 14 t3 of node a, 15 t3 of node b, 16 the chord
 * e1, 17 t1 of node a, 18 t1 of node b, 19 (th_y,a^2 + th_z,a^2) e1, 20 (th_y,a th_y,b + th_z,a
 * th_z,b) e1, 21 (th_y,b^2 + th_z,b^2) e1; the quartic element's bubble: 22 V = b_z e2 - b_y e3,
 * 23 (th_y,a b_y + th_z,a b_z) e1, 24 (th_y,b b_y + th_z,b b_z) e1, 25 (b_y^2 + b_z^2) e1,
 * 26 b_z e1, 27 b_y e1 (then NV, NV + 1: the node positions x_a, x_b). The field's vectors (0, 1,
 * 16 to 25) are multiplied by L / L0 (the field over the current chord, mech_beam.h). */
static int nbasis(const beam *b)
{
    return mech_beam_quartic_(b) ? 28 : 22;
}

void mech_beam_offsets_(const ad_ctx *c, const beam *b, beam_work *k)
{
    const ad *th = k->th;
    int quartic = mech_beam_quartic_(b);
    for (int j = 0; j < 6; j++)
        ad_const(c, 0.0, &k->sq[j]);
    for (int a = 1; a <= 2; a++) { /* theta_y, theta_z */
        ad_mul(c, &th[a], &th[a], &k->t1);
        ad_axpy(c, &k->sq[0], 1.0, &k->t1, &k->sq[0]);
        ad_mul(c, &th[a], &th[3 + a], &k->t1);
        ad_axpy(c, &k->sq[1], 1.0, &k->t1, &k->sq[1]);
        ad_mul(c, &th[3 + a], &th[3 + a], &k->t1);
        ad_axpy(c, &k->sq[2], 1.0, &k->t1, &k->sq[2]);
        if (!quartic) continue;
        const ad *bb = &k->bub[a - 1];
        ad_mul(c, &th[a], bb, &k->t1);
        ad_axpy(c, &k->sq[3], 1.0, &k->t1, &k->sq[3]);
        ad_mul(c, &th[3 + a], bb, &k->t1);
        ad_axpy(c, &k->sq[4], 1.0, &k->t1, &k->sq[4]);
        ad_mul(c, bb, bb, &k->t1);
        ad_axpy(c, &k->sq[5], 1.0, &k->t1, &k->sq[5]);
    }
    for (int i = 0; i < 3; i++) {
        for (int n = 0; n < 2; n++) {
            ad_mul(c, &th[3 * n + 2], &k->e2[i], &k->t1);
            ad_mul(c, &th[3 * n + 1], &k->e3[i], &k->t2);
            ad_axpy(c, &k->t1, -1.0, &k->t2, &k->B[n][i]);
            ad_mul(c, &th[3 * n + 0], &k->e3[i], &k->B[4 + n][i]);
            ad_mul(c, &th[3 * n + 2], &k->e1[i], &k->B[6 + n][i]);
            ad_mul(c, &th[3 * n + 0], &k->e2[i], &k->B[8 + n][i]);
            ad_mul(c, &th[3 * n + 1], &k->e1[i], &k->B[10 + n][i]);
        }
        k->B[2][i] = k->e2[i];
        k->B[3][i] = k->e3[i];
        k->B[12][i] = k->ta[3 + i];
        k->B[13][i] = k->tb[3 + i];
        k->B[14][i] = k->ta[6 + i];
        k->B[15][i] = k->tb[6 + i];
        k->B[16][i] = k->e1[i];
        k->B[17][i] = k->ta[i];
        k->B[18][i] = k->tb[i];
        for (int j = 0; j < 3; j++)
            ad_mul(c, &k->sq[j], &k->e1[i], &k->B[19 + j][i]);
        if (!quartic) continue;
        ad_mul(c, &k->bub[1], &k->e2[i], &k->t1);
        ad_mul(c, &k->bub[0], &k->e3[i], &k->t2);
        ad_axpy(c, &k->t1, -1.0, &k->t2, &k->B[22][i]);
        for (int j = 0; j < 3; j++)
            ad_mul(c, &k->sq[3 + j], &k->e1[i], &k->B[23 + j][i]);
        ad_mul(c, &k->bub[1], &k->e1[i], &k->B[26][i]);
        ad_mul(c, &k->bub[0], &k->e1[i], &k->B[27][i]);
    }
    /* the field relative to the chord is written over the current chord L = L0 s (its slopes
     * at the nodes the node rotations): its displacements (P, Q, the bubble's V), their
     * foreshortening and the template's vectors scaled by s */
    static const int field[] = {0, 1, 16, 17, 18, 19, 20, 21, 22, 23, 24, 25};
    ad_scale(c, 1.0 / b->L0, &k->L, &k->t1);
    for (int j = 0; j < (quartic ? 12 : 8); j++)
        for (int i = 0; i < 3; i++) {
            ad_mul(c, &k->t1, &k->B[field[j]][i], &k->t2);
            k->B[field[j]][i] = k->t2;
        }
    if (c->order > 1)
        for (int bb = 0; bb < nbasis(b); bb++)
            for (int i = 0; i < 3; i++)
                ad_mirror(c, &k->B[bb][i]);
}

typedef mech_beam_point point;

/* int_0^x a(t) b(t) dt of two polynomials (coefficients from t^0) */
static double poly_int_prod(const double *a, int na, const double *b, int nb, double x)
{
    double r = 0;
    for (int i = 0; i < na; i++)
        for (int j = 0; j < nb; j++)
            r += a[i] * b[j] * pow(x, i + j + 1) / (i + j + 1);
    return r;
}

/* 5-point Gauss-Legendre rule on [0, 1] (the quartic element: |r'|^2 of degree 8) */
static const double GX5[5] = {0.046910077030668004, 0.23076534494715845, 0.5, 0.76923465505284155,
                              0.95308992296933200};
static const double GW5[5] = {0.11846344252809454, 0.23931433524968324, 0.28444444444444444,
                              0.23931433524968324, 0.11846344252809454};

/* The section's directors at xi (weight w of the rule): D2 = e2 + psi_x e3 - psi_z e1 and
 * D3 = e3 - psi_x e2 + psi_y e1, psi_x = (1 - xi) th_x,a + xi th_x,b, psi_y,z = H1' th_y,z,a +
 * H2' th_y,z,b (+ B' b_y,z: bd = B'(xi), 0 without a bubble): the directors e2, e3 turned by
 * the section's small rotation. Returns the next free point. */
static int director_points(point *p, int n, double xi, double bd, double mz, double my, double w)
{
    double d1 = 1 - 4 * xi + 3 * xi * xi, d2 = -2 * xi + 3 * xi * xi; /* H1', H2' */
    p[n].c[2] = 1, p[n].c[4] = 1 - xi, p[n].c[5] = xi, p[n].c[6] = -d1, p[n].c[7] = -d2;
    if (bd != 0) p[n].c[26] = -bd;
    p[n++].mu = mz * w;
    p[n].c[3] = 1, p[n].c[8] = -(1 - xi), p[n].c[9] = -xi, p[n].c[10] = d1, p[n].c[11] = d2;
    if (bd != 0) p[n].c[27] = bd;
    p[n++].mu = my * w;
    return n;
}

/* Less the nodes' lumped masses and rotary inertias (half of the element's at each). Returns
 * the next free point. */
static int node_points(point *p, int n, double mA, double mz, double my)
{
    p[n].c[XA] = 1, p[n].mu = -0.5 * mA, p[n++].weight = 1;
    p[n].c[XB] = 1, p[n].mu = -0.5 * mA, p[n++].weight = 1;
    p[n].c[12] = 1, p[n++].mu = -0.5 * mz;
    p[n].c[13] = 1, p[n++].mu = -0.5 * mz;
    p[n].c[14] = 1, p[n++].mu = -0.5 * my;
    p[n].c[15] = 1, p[n++].mu = -0.5 * my;
    return n;
}

/* The quartic element's points (mech_beam.h): the cubic field plus the bubble B(xi) = xi^2
 * (1 - xi)^2 in each bending plane, with the foreshortening of the whole quartic arc; the
 * consistent mass of the field (no template: the bubble's own mass carries the accuracy). */
static int quartic_points(const beam *b, point *p)
{
    const mech_section *S = &b->sec;
    double L0 = b->L0, mA = S->rho * S->A * L0, mz = S->rho * S->Iz * L0, my = S->rho * S->Iy * L0;
    static const double H1d[3] = {1, -4, 3}, H2d[3] = {0, -2, 3}, Bd[4] = {0, 2, -6, 4};
    const double F11e = poly_int_prod(H1d, 3, H1d, 3, 1), F12e = poly_int_prod(H1d, 3, H2d, 3, 1),
                 F22e = poly_int_prod(H2d, 3, H2d, 3, 1), F1Be = poly_int_prod(H1d, 3, Bd, 4, 1),
                 F2Be = poly_int_prod(H2d, 3, Bd, 4, 1), FBBe = poly_int_prod(Bd, 4, Bd, 4, 1);
    int n = 0;
    memset(p, 0, NP * sizeof *p);
    for (int g = 0; g < 5; g++) {
        double xi = GX5[g], h1 = xi * (1 - xi) * (1 - xi), h2 = -xi * xi * (1 - xi);
        double bu = xi * xi * (1 - xi) * (1 - xi), bd = 2 * xi - 6 * xi * xi + 4 * xi * xi * xi;
        p[n].c[XA] = 1 - xi, p[n].c[XB] = xi, p[n].c[0] = L0 * h1, p[n].c[1] = L0 * h2;
        p[n].c[22] = L0 * bu;
        p[n].c[19] = -0.5 * L0 * (poly_int_prod(H1d, 3, H1d, 3, xi) - xi * F11e);
        p[n].c[20] = -L0 * (poly_int_prod(H1d, 3, H2d, 3, xi) - xi * F12e);
        p[n].c[21] = -0.5 * L0 * (poly_int_prod(H2d, 3, H2d, 3, xi) - xi * F22e);
        p[n].c[23] = -L0 * (poly_int_prod(H1d, 3, Bd, 4, xi) - xi * F1Be);
        p[n].c[24] = -L0 * (poly_int_prod(H2d, 3, Bd, 4, xi) - xi * F2Be);
        p[n].c[25] = -0.5 * L0 * (poly_int_prod(Bd, 4, Bd, 4, xi) - xi * FBBe);
        p[n].mu = mA * GW5[g], p[n++].weight = 1;
        n = director_points(p, n, xi, bd, mz, my, GW5[g]);
    }
    return node_points(p, n, mA, mz, my);
}

int mech_beam_points_(const beam *b, point *p)
{
    if (mech_beam_quartic_(b)) return quartic_points(b, p);
    const mech_section *S = &b->sec;
    double L0 = b->L0, mA = S->rho * S->A * L0, mz = S->rho * S->Iz * L0, my = S->rho * S->Iy * L0;
    int n = 0;
    memset(p, 0, NP * sizeof *p);
    for (int g = 0; g < 4; g++) {
        double xi = GX[g], h1 = xi * (1 - xi) * (1 - xi), h2 = -xi * xi * (1 - xi);
        /* r = (1 - xi) x_a + xi x_b + L (H1 P + H2 Q) - L (F(xi) - xi F(1)) e1 (L0 here, the
         * basis vectors carry L / L0: mech_beam_offsets_), the
         * foreshortening F(xi) = int_0^xi (psi_y^2 + psi_z^2) / 2 of the cubic field's slopes
         * psi = H1' th_a + H2' th_b: with F_ij = int_0^xi Hi' Hj' (F_11(1) = F_22(1) = 2/15,
         * F_12(1) = -1/30) the coefficients of the basis' quadratic forms 19, 20, 21 */
        double x2 = xi * xi, x3 = x2 * xi, x4 = x3 * xi, x5 = x4 * xi;
        double F11 = xi - 4 * x2 + 22.0 / 3 * x3 - 6 * x4 + 9.0 / 5 * x5;
        double F12 = -x2 + 11.0 / 3 * x3 - 4.5 * x4 + 9.0 / 5 * x5;
        double F22 = 4.0 / 3 * x3 - 3 * x4 + 9.0 / 5 * x5;
        p[n].c[XA] = 1 - xi, p[n].c[XB] = xi, p[n].c[0] = L0 * h1, p[n].c[1] = L0 * h2;
        p[n].c[19] = -0.5 * L0 * (F11 - 2.0 / 15 * xi);
        p[n].c[20] = -L0 * (F12 + xi / 30);
        p[n].c[21] = -0.5 * L0 * (F22 - 2.0 / 15 * xi);
        p[n].mu = mA * GW[g], p[n++].weight = 1;
        n = director_points(p, n, xi, 0.0, mz, my, GW[g]);
    }
    n = node_points(p, n, mA, mz, my);
    /* the bending correction (mech_beam.h): mu0 L0^2 Q with E = e1', A = t1_a', B = t1_b',
     * Q = 54 |E - 23/18 (A + B)|^2 - 98/3 |A + B|^2 + 77/2 |A - B|^2 */
    double m0 = mA / 17640, l = L0;
    p[n].c[16] = l, p[n].c[17] = p[n].c[18] = -23.0 / 18 * l, p[n++].mu = 54 * m0;
    p[n].c[17] = p[n].c[18] = l, p[n++].mu = -98.0 / 3 * m0;
    p[n].c[17] = l, p[n].c[18] = -l, p[n++].mu = 77.0 / 2 * m0;
    return n;
}

/* The velocities u' in the velocity coordinates (v_a, omega_a, v_b, omega_b; omega = R w
 * global; the bubbles' rates c) from src = y, or their rates u'' = (v_a', R_a w_a', ..., c')
 * from src = yp. */
static void port_rates(const beam *b, const double *y, const double *src, double *u)
{
    double R[9];
    const int q[2] = {b->qa, b->qb}, v[2] = {b->va, b->vb}, w[2] = {b->wa, b->wb};
    for (int n = 0; n < 2; n++) {
        mech_quat_R(y + q[n], R, NULL);
        memcpy(u + 6 * n, src + v[n], 3 * sizeof *u);
        mech_mv(R, src + w[n], u + 6 * n + 3);
    }
    for (int k = 12; k < b->nv; k++)
        u[k] = src[b->bs + 2 + k - 12];
}

/* B: the rates of the configuration unknowns from the velocities, X' = B u' (x' = v,
 * q' = J(q) omega, b' = c). */
static void config_rates(const beam *b, const mech_beam_nodej *nj, double B[MB_NC][MB_NV])
{
    memset(B, 0, MB_NC * MB_NV * sizeof(double));
    for (int n = 0; n < 2; n++) {
        for (int i = 0; i < 3; i++)
            B[3 * n + i][6 * n + i] = 1.0;
        for (int j = 0; j < 4; j++)
            for (int i = 0; i < 3; i++)
                B[6 + 4 * n + j][6 * n + 3 + i] = nj->J[n][j][i];
    }
    for (int k = 14; k < b->nc; k++)
        B[k][k - 2] = 1.0;
}

void mech_beam_config_rate_(const beam *b, const double *y, double *Xd)
{
    double ud[MB_NV], B[MB_NC][MB_NV];
    mech_beam_nodej nj;
    mech_beam_node_J_(b, y, &nj);
    port_rates(b, y, y, ud);
    config_rates(b, &nj, B);
    for (int c = 0; c < b->nc; c++) {
        Xd[c] = 0;
        for (int j = 0; j < b->nv; j++)
            Xd[c] += B[c][j] * ud[j];
    }
}

/* Cd = (dgv X') of an AD scalar a of order 3 along X' (h = H X'): the rate of its velocity
 * gradient, from the positions' (and bubbles') rows of H X' and, for the rotations,
 * sum_m (H X')_q,m J(q)_m + g_q,m J(q')_m (J is linear in q). */
static void gradient_rate(const ad *a, const beam *b, const mech_beam_nodej *nj,
                          const mech_beam_nodej *njd, double *Cd)
{
    const double(*J)[4][3] = nj->J, (*Jd)[4][3] = njd->J;
    const int qoff[2] = {6, 10}, xoff[2] = {0, 3};
    for (int n = 0; n < 2; n++) {
        for (int i = 0; i < 3; i++) {
            Cd[6 * n + i] = a->h[xoff[n] + i];
            double r = 0;
            for (int m = 0; m < 4; m++)
                r += a->h[qoff[n] + m] * J[n][m][i] + a->g[qoff[n] + m] * Jd[n][m][i];
            Cd[6 * n + 3 + i] = r;
        }
    }
    for (int k = 12; k < b->nv; k++)
        Cd[k] = a->h[k + 2];
}

/* The basis' velocity gradients (and their derivatives if dgv is wanted) into the scratch. */
static void basis_gradients(const beam *b, const mech_beam_nodej *nj, beam_work *k, int with_dgv)
{
    for (int bb = 0; bb < nbasis(b); bb++)
        for (int i = 0; i < 3; i++)
            mech_beam_velocity_gradient_(b, &k->B[bb][i], nj, k->gv[bb][i],
                                         with_dgv ? k->dgv[bb][i] : NULL);
}

/* G (nv) of component i of a point: sum_b c_b gv_b,i (nbs basis vectors), the node positions'
 * unit gradients. */
static inline void point_gradient(const beam_work *k, const point *p, int i, double *G,
                                  const int nv, const int nbs)
{
    memset(G, 0, MB_NV * sizeof *G);
    for (int bb = 0; bb < nbs; bb++)
        if (p->c[bb] != 0)
            for (int j = 0; j < nv; j++)
                G[j] += p->c[bb] * k->gv[bb][i][j];
    G[i] += p->c[XA];
    G[6 + i] += p->c[XB];
}

/* mech_beam_inertia_ for nv velocity coordinates and nc configuration unknowns (compiled for
 * the two kinds, so that the loops' bounds are constants) */
#if defined(__GNUC__)
__attribute__((always_inline))
#endif
static inline void
inertia_k(const beam *b, const double *y, const double *yp, double g[MB_NV], double (*dX)[MB_NC],
          double (*dV)[MB_NV], double (*dA)[MB_NV], const int nv, const int nc)
{
    beam_work *k = b->work;
    const int nbs = nc == MB_NC ? 28 : 22;
    double ud[MB_NV], ua[MB_NV], B[MB_NC][MB_NV], Xd[MB_NC];
    mech_beam_nodej nj, njd; /* the nodes' J(q), and J(q') (J is linear in q) */
    mech_beam_node_J_(b, y, &nj);
    port_rates(b, y, y, ud);
    port_rates(b, y, yp, ua);
    config_rates(b, &nj, B);
    for (int c = 0; c < nc; c++) {
        Xd[c] = 0;
        for (int j = 0; j < nv; j++)
            Xd[c] += B[c][j] * ud[j];
    }
    /* the basis vectors' accelerations acc = gv . u'' + u' . (dgv X') (the second term: the
     * rate of the gradient along the motion, centrifugal and Coriolis): with the Jacobian from
     * the whole Hessians (order 2), for the residual from the Hessians along X' (order 3) */
    mech_beam_quat_J_(Xd + 6, njd.J[0]);
    mech_beam_quat_J_(Xd + 10, njd.J[1]);
    basis_gradients(b, &nj, k, dX != NULL);
    double Cd[NV][3][MB_NV], acc[NB][3];
    for (int bb = 0; bb < nbs; bb++)
        for (int i = 0; i < 3; i++) {
            if (dX)
                for (int j = 0; j < nv; j++) {
                    double cd = 0;
                    for (int c = 0; c < nc; c++)
                        cd += k->dgv[bb][i][j][c] * Xd[c];
                    Cd[bb][i][j] = cd;
                }
            else
                gradient_rate(&k->B[bb][i], b, &nj, &njd, Cd[bb][i]);
            double s = 0;
            for (int j = 0; j < nv; j++)
                s += k->gv[bb][i][j] * ua[j] + ud[j] * Cd[bb][i][j];
            acc[bb][i] = s;
        }
    for (int i = 0; i < 3; i++) {
        acc[XA][i] = ua[i];
        acc[XB][i] = ua[6 + i];
    }
    const point *P = b->pts;
    int np = b->npts;
    /* a_p = mu_p (r_p'' - g); f = sum_p G_p^T a_p = sum_b sum_i S_b,i gv_b,i (+ the x's) */
    double S[NB][3];
    memset(S, 0, sizeof S);
    double a[NP][3];
    for (int p = 0; p < np; p++)
        for (int i = 0; i < 3; i++) {
            double rdd = 0;
            for (int bb = 0; bb < nbs; bb++)
                rdd += P[p].c[bb] * acc[bb][i];
            rdd += P[p].c[XA] * acc[XA][i];
            rdd += P[p].c[XB] * acc[XB][i];
            a[p][i] = P[p].mu * (rdd - (P[p].weight ? b->grav[i] : 0.0));
            for (int bb = 0; bb < nbs; bb++)
                S[bb][i] += P[p].c[bb] * a[p][i];
            S[XA][i] += P[p].c[XA] * a[p][i];
            S[XB][i] += P[p].c[XB] * a[p][i];
        }
    memset(g, 0, MB_NV * sizeof *g);
    for (int i = 0; i < 3; i++) {
        g[i] += S[XA][i];
        g[6 + i] += S[XB][i];
    }
    for (int bb = 0; bb < nbs; bb++)
        for (int i = 0; i < 3; i++)
            if (S[bb][i] != 0)
                for (int j = 0; j < nv; j++)
                    g[j] += S[bb][i] * k->gv[bb][i][j];
    if (!dX) return;
    /* d acc / d u' = Cd + (dgv B)^T u';  d acc / dX ~ u''^T dgv (the configuration derivative
     * of the rate term left out: see mech_beam.h) */
    double dacc_u[NV][3][MB_NV], dacc_X[NV][3][MB_NC];
    for (int bb = 0; bb < nbs; bb++)
        for (int i = 0; i < 3; i++) {
            const double(*D)[MB_NC] = (const double(*)[MB_NC])k->dgv[bb][i];
            double uD[MB_NC] = {0}; /* u'^T dgv, then (u'^T dgv) B: one product each */
            for (int l = 0; l < nv; l++)
                if (ud[l] != 0)
                    for (int c = 0; c < nc; c++)
                        uD[c] += ud[l] * D[l][c];
            for (int j = 0; j < nv; j++) {
                double dB = 0;
                for (int c = 0; c < nc; c++)
                    dB += uD[c] * B[c][j];
                dacc_u[bb][i][j] = Cd[bb][i][j] + dB;
            }
            for (int c = 0; c < nc; c++) {
                double sum = 0;
                for (int l = 0; l < nv; l++)
                    sum += ua[l] * D[l][c];
                dacc_X[bb][i][c] = sum;
            }
        }
    memset(dX, 0, MB_NV * MB_NC * sizeof(double));
    memset(dV, 0, MB_NV * MB_NV * sizeof(double));
    memset(dA, 0, MB_NV * MB_NV * sizeof(double));
    for (int bb = 0; bb < nbs; bb++) /* the rate of G^T along X */
        for (int i = 0; i < 3; i++)
            if (S[bb][i] != 0)
                for (int j = 0; j < nv; j++)
                    for (int c = 0; c < nc; c++)
                        dX[j][c] += S[bb][i] * k->dgv[bb][i][j][c];
    for (int p = 0; p < np; p++)
        for (int i = 0; i < 3; i++) {
            double G[MB_NV], du[MB_NV] = {0}, dx[MB_NC] = {0};
            point_gradient(k, &P[p], i, G, nv, nbs);
            for (int bb = 0; bb < nbs; bb++) {
                double cb = P[p].c[bb];
                if (cb == 0) continue;
                for (int j = 0; j < nv; j++)
                    du[j] += cb * dacc_u[bb][i][j];
                for (int c = 0; c < nc; c++)
                    dx[c] += cb * dacc_X[bb][i][c];
            }
            for (int j = 0; j < nv; j++) {
                double mg = P[p].mu * G[j];
                for (int l = 0; l < nv; l++) {
                    dA[j][l] += mg * G[l];
                    dV[j][l] += mg * du[l];
                }
                for (int c = 0; c < nc; c++)
                    dX[j][c] += mg * dx[c];
            }
        }
    /* columns of omega = R w (and of its rate R w'): to the body-frame unknowns w */
    for (int n = 0; n < 2; n++) {
        double R[9];
        mech_quat_R(y + (n ? b->qb : b->qa), R, NULL);
        for (int j = 0; j < nv; j++) {
            double tv[3], ta[3];
            for (int i = 0; i < 3; i++) {
                tv[i] = ta[i] = 0;
                for (int l = 0; l < 3; l++) {
                    tv[i] += dV[j][6 * n + 3 + l] * R[l + 3 * i];
                    ta[i] += dA[j][6 * n + 3 + l] * R[l + 3 * i];
                }
            }
            memcpy(&dV[j][6 * n + 3], tv, sizeof tv);
            memcpy(&dA[j][6 * n + 3], ta, sizeof ta);
        }
    }
}

void mech_beam_inertia_(const beam *b, const double *y, const double *yp, double g[MB_NV],
                        double (*dX)[MB_NC], double (*dV)[MB_NV], double (*dA)[MB_NV])
{
    if (mech_beam_quartic_(b))
        inertia_k(b, y, yp, g, dX, dV, dA, 14, 16);
    else
        inertia_k(b, y, yp, g, dX, dV, dA, 12, 14);
}

double mech_beam_kinetic_(const beam *b, const double *y)
{
    beam_work *k = b->work;
    double ud[MB_NV], T = 0;
    port_rates(b, y, y, ud);
    mech_beam_nodej nj;
    mech_beam_node_J_(b, y, &nj);
    basis_gradients(b, &nj, k, 0);
    const point *P = b->pts;
    int np = b->npts;
    for (int p = 0; p < np; p++)
        for (int i = 0; i < 3; i++) {
            double G[MB_NV], v = 0;
            point_gradient(k, &P[p], i, G, b->nv, nbasis(b));
            for (int j = 0; j < b->nv; j++)
                v += G[j] * ud[j];
            T += 0.5 * P[p].mu * v * v;
        }
    return T;
}
