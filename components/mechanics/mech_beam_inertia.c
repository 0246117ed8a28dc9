/* Consistent inertia of the co-rotational beam element (equations in mech_beam.h): the mass of
 * the element at the 4 Gauss points of its co-rotational displacement field, its inertia loads
 * by d'Alembert's principle, less the point masses the node bodies already carry. The field's
 * transverse part is L0 (H1 P + H2 Q), P and Q the offset vectors made here on the AD numbers of
 * the element's energy (mech_beam.c), so that their velocity gradients and Hessians give the
 * Gauss points' velocities and accelerations exactly. */
#include <math.h>
#include <string.h>

#include "mech_beam_impl.h"

/* 4-point Gauss-Legendre rule on [0, 1]: points and weights */
static const double GX[4] = {0.069431844202973712, 0.33000947820757187, 0.66999052179242813,
                             0.93056815579702629};
static const double GW[4] = {0.17392742256872693, 0.32607257743127307, 0.32607257743127307,
                             0.17392742256872693};

void mech_beam_offsets_(const ad_ctx *c, beam_work *k)
{
    for (int n = 0; n < 2; n++)
        for (int i = 0; i < 3; i++) {
            ad *o = &k->PQ[3 * n + i];
            ad_mul(c, &k->th[3 * n + 2], &k->e2[i], &k->t1);
            ad_mul(c, &k->th[3 * n + 1], &k->e3[i], &k->t2);
            ad_axpy(c, &k->t1, -1.0, &k->t2, o);
            if (c->order > 1) ad_mirror(c, o);
        }
}

/* The node velocities u' in the port coordinates (v_a, omega_a, v_b, omega_b; omega = R w
 * global) from y (rates NULL) or their rates u'' = (v_a', R_a w_a', ...) from yp. */
static void port_rates(const beam *b, const double *y, const double *src, double *u)
{
    double R[9];
    const int q[2] = {b->qa, b->qb}, v[2] = {b->va, b->vb}, w[2] = {b->wa, b->wb};
    for (int n = 0; n < 2; n++) {
        mech_quat_R(y + q[n], R, NULL);
        memcpy(u + 6 * n, src + v[n], 3 * sizeof *u);
        mech_mv(R, src + w[n], u + 6 * n + 3);
    }
}

/* B: the rates of the 14 configuration unknowns from the port velocities, X' = B u' (x' = v,
 * q' = J(q) omega). */
static void config_rates(const beam *b, const double *y, double B[14][12])
{
    memset(B, 0, 14 * 12 * sizeof(double));
    double J[4][3];
    for (int n = 0; n < 2; n++) {
        for (int i = 0; i < 3; i++)
            B[3 * n + i][6 * n + i] = 1.0;
        mech_beam_quat_J_(y + (n ? b->qb : b->qa), J);
        for (int j = 0; j < 4; j++)
            for (int i = 0; i < 3; i++)
                B[6 + 4 * n + j][6 * n + 3 + i] = J[j][i];
    }
}

/* G_g[c]: the velocity gradient (12) of component c of Gauss point xi, from those of P, Q. */
static void point_gradient(double xi, double L0, const double (*gv)[12], int c, double *G)
{
    double h1 = xi * (1 - xi) * (1 - xi), h2 = -xi * xi * (1 - xi);
    for (int k = 0; k < 12; k++)
        G[k] = L0 * (h1 * gv[c][k] + h2 * gv[3 + c][k]);
    G[c] += 1 - xi;
    G[6 + c] += xi;
}

void mech_beam_inertia_(const beam *b, const double *y, const double *yp, double g[12],
                        double (*dX)[14], double (*dV)[12], double (*dA)[12])
{
    const beam_work *k = b->work;
    const double *qa = y + b->qa, *qb = y + b->qb, L0 = b->L0;
    const double m = b->sec.rho * b->sec.A * L0;
    double ud[12], ua[12], B[14][12], Xd[14];
    port_rates(b, y, y, ud);
    port_rates(b, y, yp, ua);
    config_rates(b, y, B);
    for (int c = 0; c < 14; c++) {
        Xd[c] = 0;
        for (int j = 0; j < 12; j++)
            Xd[c] += B[c][j] * ud[j];
    }
    /* the offsets: velocity gradients gv, their derivatives dgv, accelerations acc */
    double gv[6][12], dgv[6][12][14], Cd[6][12], acc[6];
    for (int s = 0; s < 6; s++) {
        mech_beam_velocity_gradient_(&k->PQ[s], qa, qb, gv[s], dgv[s]);
        acc[s] = 0;
        for (int j = 0; j < 12; j++) {
            Cd[s][j] = 0; /* (dG/dX X')_j: the rate of the gradient */
            for (int c = 0; c < 14; c++)
                Cd[s][j] += dgv[s][j][c] * Xd[c];
            acc[s] += gv[s][j] * ua[j] + ud[j] * Cd[s][j];
        }
    }
    /* Gauss sums of a_g = m w_g (r_g'' - g): f = sum_g G_g^T a_g */
    double SP[6] = {0}, a[4][3];
    memset(g, 0, 12 * sizeof *g);
    for (int p = 0; p < 4; p++) {
        double xi = GX[p], mg = m * GW[p];
        double h1 = xi * (1 - xi) * (1 - xi), h2 = -xi * xi * (1 - xi);
        for (int c = 0; c < 3; c++) {
            double rdd = (1 - xi) * ua[c] + xi * ua[6 + c] + L0 * (h1 * acc[c] + h2 * acc[3 + c]);
            a[p][c] = mg * (rdd - b->grav[c]);
            g[c] += (1 - xi) * a[p][c];
            g[6 + c] += xi * a[p][c];
            SP[c] += L0 * h1 * a[p][c];
            SP[3 + c] += L0 * h2 * a[p][c];
        }
    }
    for (int c = 0; c < 3; c++) { /* less the nodes' point masses */
        g[c] -= 0.5 * m * (ua[c] - b->grav[c]);
        g[6 + c] -= 0.5 * m * (ua[6 + c] - b->grav[c]);
    }
    for (int s = 0; s < 6; s++)
        for (int j = 0; j < 12; j++)
            g[j] += SP[s] * gv[s][j];
    if (!dX) return;
    /* d acc_s / d u' = Cd_s + (dgv_s B)^T u';  d acc_s / dX ~ u''^T dgv_s (the configuration
     * derivative of G_s' u' left out: see mech_beam.h) */
    double dacc_u[6][12], dacc_X[6][14];
    for (int s = 0; s < 6; s++) {
        for (int j = 0; j < 12; j++) {
            double sum = Cd[s][j];
            for (int i = 0; i < 12; i++) {
                double dB = 0;
                for (int c = 0; c < 14; c++)
                    dB += dgv[s][i][c] * B[c][j];
                sum += ud[i] * dB;
            }
            dacc_u[s][j] = sum;
        }
        for (int c = 0; c < 14; c++) {
            double sum = 0;
            for (int i = 0; i < 12; i++)
                sum += ua[i] * dgv[s][i][c];
            dacc_X[s][c] = sum;
        }
    }
    memset(dX, 0, 12 * 14 * sizeof(double));
    memset(dV, 0, 144 * sizeof(double));
    memset(dA, 0, 144 * sizeof(double));
    for (int s = 0; s < 6; s++) /* the rate of G_g^T along X */
        for (int j = 0; j < 12; j++)
            for (int c = 0; c < 14; c++)
                dX[j][c] += SP[s] * dgv[s][j][c];
    for (int p = 0; p < 4; p++) {
        double xi = GX[p], mg = m * GW[p];
        double h1 = xi * (1 - xi) * (1 - xi), h2 = -xi * xi * (1 - xi);
        for (int c = 0; c < 3; c++) {
            double G[12];
            point_gradient(xi, L0, (const double(*)[12])gv, c, G);
            for (int j = 0; j < 12; j++) {
                double mgj = mg * G[j];
                for (int i = 0; i < 12; i++) {
                    dA[j][i] += mgj * G[i];
                    dV[j][i] += mgj * L0 * (h1 * dacc_u[c][i] + h2 * dacc_u[3 + c][i]);
                }
                for (int cc = 0; cc < 14; cc++)
                    dX[j][cc] += mgj * L0 * (h1 * dacc_X[c][cc] + h2 * dacc_X[3 + c][cc]);
            }
        }
    }
    for (int c = 0; c < 3; c++) {
        dA[c][c] -= 0.5 * m;
        dA[6 + c][6 + c] -= 0.5 * m;
    }
    /* columns of omega = R w (and its rate R w'): to the body-frame unknowns w */
    for (int n = 0; n < 2; n++) {
        double R[9];
        mech_quat_R(y + (n ? b->qb : b->qa), R, NULL);
        for (int j = 0; j < 12; j++) {
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

double mech_beam_kinetic_(const beam *b, const double *y)
{
    const beam_work *k = b->work;
    double ud[12], gv[6][12], T = 0;
    const double m = b->sec.rho * b->sec.A * b->L0;
    port_rates(b, y, y, ud);
    for (int s = 0; s < 6; s++)
        mech_beam_velocity_gradient_(&k->PQ[s], y + b->qa, y + b->qb, gv[s], NULL);
    for (int p = 0; p < 4; p++)
        for (int c = 0; c < 3; c++) {
            double G[12], v = 0;
            point_gradient(GX[p], b->L0, (const double(*)[12])gv, c, G);
            for (int j = 0; j < 12; j++)
                v += G[j] * ud[j];
            T += 0.5 * m * GW[p] * v * v;
        }
    for (int c = 0; c < 3; c++)
        T -= 0.25 * m * (ud[c] * ud[c] + ud[6 + c] * ud[6 + c]);
    return T;
}
