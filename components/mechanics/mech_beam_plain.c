/* The beam element's residual loads in plain arithmetic (see mech_beam_impl.h): the local
 * stiffness of the deformations, and the forward, tangent and reverse passes through them. The
 * AD path in mech_beam.c computes the same loads with their Jacobian; the tests hold the two to
 * each other. */
#include <math.h>
#include <string.h>

#include "mech_beam_impl.h"

/* Local stiffness K (7 x 7) of the deformations (u, theta_a, theta_b): W = d^T K d / 2, with
 * EI/(2 L0 (1 + P)) [(4 + P)(ta^2 + tb^2) + 2 (2 - P) ta tb] in bending, P the shear parameter
 * 12 EI/(kappa G A L0^2) (0: Euler-Bernoulli, W = 2 EI/L0 (ta^2 + ta tb + tb^2)). Computed once,
 * with the element. */
void mech_beam_stiffness_(const beam *b, double K[7][7])
{
    const mech_section *S = &b->sec;
    double L0 = b->L0;
    memset(K, 0, 49 * sizeof(double));
    K[0][0] = S->E * S->A / L0;
    double kt = S->G * S->J / L0;
    K[1][1] = K[4][4] = kt;
    K[1][4] = K[4][1] = -kt;
    const double EI[2] = {S->Iy * S->E, S->Iz * S->E};
    for (int a = 0; a < 2; a++) {
        double P = S->kappa > 0 ? 12 * EI[a] / (S->kappa * S->G * S->A * L0 * L0) : 0.0;
        double f = EI[a] / (2 * L0 * (1 + P));
        int ia = 2 + a, ib = 5 + a;
        K[ia][ia] = K[ib][ib] = 2 * f * (4 + P);
        K[ia][ib] = K[ib][ia] = 2 * f * (2 - P);
    }
}

/* The residual's loads in plain arithmetic (order 1 only; the Jacobian keeps the AD path of
 * mech_beam.c, which the tests hold this one to). The loads are the velocity gradient of
 * sum_r z_r d_r over the seven deformations d = (u, theta_a, theta_b) with z = K (d + beta d'),
 * d' = Jd w: the elastic part is grad W = Jd^T K d, the damping part beta Jd^T K Jd w. So one
 * forward pass for d, one tangent pass for d' (damped elements only), and one reverse pass for
 * the gradient: about a third of the work of carrying 14-wide gradients through every
 * operation. */
typedef struct beam_fwd {
    double R[2][9], dR[2][9][4]; /* rotation of each node and its gradient in q */
    double t[2][3][3];           /* triads: t[n][i] = R(q_n) E0_i */
    double d[3], L, e1[3], p[3], s2, w[3], nw, e2[3], e3[3];
    double def[7]; /* u, theta_a (x, y, z), theta_b */
} beam_fwd;

static double dot3(const double *a, const double *b)
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void cross3(const double *a, const double *b, double *r)
{
    r[0] = a[1] * b[2] - a[2] * b[1];
    r[1] = a[2] * b[0] - a[0] * b[2];
    r[2] = a[0] * b[1] - a[1] * b[0];
}

/* t = R E0_i for the three columns i of E0 (R column-major) */
static void rotate_frame(const double *R, const double *E0, double t[3][3])
{
    for (int i = 0; i < 3; i++)
        for (int r = 0; r < 3; r++)
            t[i][r] = E0[3 * i] * R[r] + E0[3 * i + 1] * R[r + 3] + E0[3 * i + 2] * R[r + 6];
}

/* theta of a node with triad t against the element frame (e1, e2, e3), as in beam_energy */
static void node_angles(const double *e1, const double *e2, const double *e3, double t[3][3],
                        double *th)
{
    th[0] = 0.5 * (dot3(e3, t[1]) - dot3(e2, t[2]));
    th[1] = 0.5 * (dot3(e1, t[2]) - dot3(e3, t[0]));
    th[2] = 0.5 * (dot3(e2, t[0]) - dot3(e1, t[1]));
}

static void beam_forward(const beam *b, const double *y, beam_fwd *f)
{
    const int qo[2] = {b->qa, b->qb};
    for (int n = 0; n < 2; n++) {
        mech_beam_quat_rot_(y + qo[n], f->R[n], f->dR[n], NULL);
        rotate_frame(f->R[n], b->E0, f->t[n]);
    }
    for (int i = 0; i < 3; i++)
        f->d[i] = y[b->xb + i] - y[b->xa + i];
    f->L = sqrt(dot3(f->d, f->d));
    for (int i = 0; i < 3; i++) {
        f->e1[i] = f->d[i] / f->L;
        f->p[i] = 0.5 * (f->t[0][1][i] + f->t[1][1][i]);
    }
    f->s2 = dot3(f->p, f->e1);
    for (int i = 0; i < 3; i++)
        f->w[i] = f->p[i] - f->s2 * f->e1[i];
    f->nw = sqrt(dot3(f->w, f->w));
    for (int i = 0; i < 3; i++)
        f->e2[i] = f->w[i] / f->nw;
    cross3(f->e1, f->e2, f->e3);
    f->def[0] = f->L - b->L0;
    for (int n = 0; n < 2; n++)
        node_angles(f->e1, f->e2, f->e3, f->t[n], f->def + 1 + 3 * n);
}

/* d' = the derivative of the deformations along the port flows w (velocity coordinates). */
static void beam_tangent(const beam *b, const beam_fwd *f, const mech_beam_nodej *nj,
                         const double *w, double *dd)
{
    double tt[2][3][3];
    for (int n = 0; n < 2; n++) {
        const double(*J)[3] = nj->J[n];
        double qd[4], Rd[9];
        for (int m = 0; m < 4; m++)
            qd[m] = J[m][0] * w[6 * n + 3] + J[m][1] * w[6 * n + 4] + J[m][2] * w[6 * n + 5];
        for (int k = 0; k < 9; k++)
            Rd[k] = f->dR[n][k][0] * qd[0] + f->dR[n][k][1] * qd[1] + f->dR[n][k][2] * qd[2] +
                    f->dR[n][k][3] * qd[3];
        rotate_frame(Rd, b->E0, tt[n]);
    }
    double ddv[3], e1d[3], pd[3], wd[3], e2d[3], e3d[3], a[3], c[3];
    for (int i = 0; i < 3; i++)
        ddv[i] = w[6 + i] - w[i];
    double Ld = dot3(f->e1, ddv);
    for (int i = 0; i < 3; i++) {
        e1d[i] = (ddv[i] - f->e1[i] * Ld) / f->L;
        pd[i] = 0.5 * (tt[0][1][i] + tt[1][1][i]);
    }
    double s2d = dot3(pd, f->e1) + dot3(f->p, e1d);
    for (int i = 0; i < 3; i++)
        wd[i] = pd[i] - s2d * f->e1[i] - f->s2 * e1d[i];
    double nwd = dot3(f->e2, wd);
    for (int i = 0; i < 3; i++)
        e2d[i] = (wd[i] - f->e2[i] * nwd) / f->nw;
    cross3(e1d, f->e2, a);
    cross3(f->e1, e2d, c);
    for (int i = 0; i < 3; i++)
        e3d[i] = a[i] + c[i];
    dd[0] = Ld;
    for (int n = 0; n < 2; n++) {
        const double(*t)[3] = f->t[n];
        double(*td)[3] = tt[n];
        double *o = dd + 1 + 3 * n;
        o[0] = 0.5 * (dot3(e3d, t[1]) + dot3(f->e3, td[1]) - dot3(e2d, t[2]) - dot3(f->e2, td[2]));
        o[1] = 0.5 * (dot3(e1d, t[2]) + dot3(f->e1, td[2]) - dot3(e3d, t[0]) - dot3(f->e3, td[0]));
        o[2] = 0.5 * (dot3(e2d, t[0]) + dot3(f->e2, td[0]) - dot3(e1d, t[1]) - dot3(f->e1, td[1]));
    }
}

/* g (14 configuration unknowns, ordered as the AD variables) = sum_r z_r grad d_r. */
static void beam_reverse(const beam *b, const beam_fwd *f, const double *z, double *g)
{
    double b1[3] = {0, 0, 0}, b2[3] = {0, 0, 0}, b3[3] = {0, 0, 0}, tb[2][3][3];
    memset(tb, 0, sizeof tb);
    for (int n = 0; n < 2; n++) { /* the node angles */
        const double(*t)[3] = f->t[n];
        double hx = 0.5 * z[1 + 3 * n], hy = 0.5 * z[2 + 3 * n], hz = 0.5 * z[3 + 3 * n];
        for (int i = 0; i < 3; i++) {
            b3[i] += hx * t[1][i] - hy * t[0][i];
            b2[i] += hz * t[0][i] - hx * t[2][i];
            b1[i] += hy * t[2][i] - hz * t[1][i];
            tb[n][0][i] += hz * f->e2[i] - hy * f->e3[i];
            tb[n][1][i] += hx * f->e3[i] - hz * f->e1[i];
            tb[n][2][i] += hy * f->e1[i] - hx * f->e2[i];
        }
    }
    double a[3], c[3]; /* e3 = e1 x e2 */
    cross3(f->e2, b3, a);
    cross3(b3, f->e1, c);
    for (int i = 0; i < 3; i++) {
        b1[i] += a[i];
        b2[i] += c[i];
    }
    double k2 = dot3(f->e2, b2), wb[3], pb[3]; /* e2 = w / |w| */
    for (int i = 0; i < 3; i++)
        wb[i] = (b2[i] - f->e2[i] * k2) / f->nw;
    double s2b = -dot3(wb, f->e1); /* w = p - s2 e1, s2 = p . e1 */
    for (int i = 0; i < 3; i++) {
        pb[i] = wb[i] + s2b * f->e1[i];
        b1[i] += s2b * f->p[i] - f->s2 * wb[i];
    }
    double k1 = dot3(f->e1, b1), db[3]; /* e1 = d / L, L = |d| (u = L - L0) */
    for (int i = 0; i < 3; i++) {
        db[i] = (b1[i] - f->e1[i] * k1) / f->L + z[0] * f->e1[i];
        g[i] = -db[i];
        g[3 + i] = db[i];
        tb[0][1][i] += 0.5 * pb[i]; /* p = (t_a1 + t_b1) / 2 */
        tb[1][1][i] += 0.5 * pb[i];
    }
    for (int n = 0; n < 2; n++) { /* t_i = R E0_i */
        double Rb[9];
        for (int r = 0; r < 3; r++)
            for (int cc = 0; cc < 3; cc++)
                Rb[r + 3 * cc] = tb[n][0][r] * b->E0[cc] + tb[n][1][r] * b->E0[3 + cc] +
                                 tb[n][2][r] * b->E0[6 + cc];
        for (int m = 0; m < 4; m++) {
            double sum = 0;
            for (int k = 0; k < 9; k++)
                sum += Rb[k] * f->dR[n][k][m];
            g[6 + 4 * n + m] = sum;
        }
    }
}

void mech_beam_loads_plain_(const beam *b, const double *y, double *g)
{
    beam_fwd f;
    beam_forward(b, y, &f);
    mech_beam_nodej nj;
    mech_beam_node_J_(b, y, &nj);
    const double(*K)[7] = b->K;
    double v[7], z[7], gc[14];
    for (int r = 0; r < 7; r++)
        v[r] = f.def[r];
    if (b->sec.beta > 0) {
        double w[12], dd[7];
        for (int m = 0; m < 6; m++) {
            w[m] = y[b->f[0] + m];
            w[6 + m] = y[b->f[1] + m];
        }
        beam_tangent(b, &f, &nj, w, dd);
        for (int r = 0; r < 7; r++)
            v[r] += b->sec.beta * dd[r];
    }
    for (int r = 0; r < 7; r++) {
        z[r] = 0;
        for (int s2 = 0; s2 < 7; s2++)
            z[r] += K[r][s2] * v[s2];
    }
    if (b->sec.element == MECH_BEAM_CONSISTENT)
        mech_beam_bow_loads_(f.def, b->sec.E * b->sec.A, b->L0, z);
    beam_reverse(b, &f, z, gc);
    mech_beam_velocity_gradient_g_(gc, &nj, g);
}

double mech_beam_strain_power_(const beam *b, const double *y)
{
    beam_fwd f;
    beam_forward(b, y, &f);
    mech_beam_nodej nj;
    mech_beam_node_J_(b, y, &nj);
    double w[12], dd[7], P = 0;
    for (int k = 0; k < 6; k++) {
        w[k] = y[b->f[0] + k];
        w[6 + k] = y[b->f[1] + k];
    }
    beam_tangent(b, &f, &nj, w, dd);
    for (int r = 0; r < 7; r++)
        for (int c = 0; c < 7; c++)
            P += dd[r] * b->K[r][c] * dd[c];
    return b->sec.beta * P;
}
