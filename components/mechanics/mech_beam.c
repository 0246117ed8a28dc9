/* The co-rotational beam element (equations in mech_beam.h; the chain builder that lumps the
 * mass into node bodies is mech_beam_chain.c, what it takes from here mech_beam_impl.h). The
 * energy W is written once on second-order automatic-differentiation numbers in the 14
 * configuration unknowns (x_a, x_b, q_a, q_b; 16 with the quartic element's bubbles b_y, b_z):
 * its gradient gives the port loads (and the bubbles' elastic forces), its Hessian their
 * Jacobian. The residual, evaluated a hundred times as often as the Jacobian, computes
 * the same loads in plain arithmetic with one reverse (adjoint) pass through the deformations
 * instead (mech_beam_plain.c); the tests hold the two to each other. The consistent element's
 * residual takes the AD path at order 3 (its inertia needs the second derivatives along the
 * motion; its own parts, and the quartic element's, are in mech_beam_consistent.c); the
 * argument checks are in mech_beam_check.c. */
#include "mech_beam.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mech_beam_impl.h"
#include "mech_body.h"

beam_work *mech_beam_work_new_(void)
{
    beam_work *w = calloc(1, sizeof *w);
    if (w) w->refs = 1;
    return w;
}

/* Drops one reference to a scratch; the last frees it. */
void mech_beam_work_release_(beam_work *w)
{
    if (w && --w->refs == 0) free(w);
}

static void beam_free(void *p)
{
    beam *b = p;
    if (b) {
        mech_beam_work_release_(b->work);
        free(b->pts);
    }
    free(b);
}

/* The nodal triad t[3*i + r] = (R(q) E0)_{r,i}, R(q) = N(q)/(q.q), of one node whose quaternion q
 * is the unknowns off..off+3 of the AD space. t depends on those four unknowns only: its value,
 * gradient and Hessian in q are computed in plain arithmetic and scattered, instead of carrying
 * 14-wide AD numbers (gradients of 14, Hessians of 14 x 14) through the products of what depends
 * on four unknowns.
 * N_k(q) = q^T A_k q with the symmetric A_k below (k column-major over the 3 x 3 matrix), s = q.q:
 *   dR = (dN - R ds) / s,  d2R_mn = (d2N_mn - dR_m ds_n - dR_n ds_m - R d2s_mn) / s. */
static const double QA[9][4][4] = {
    {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, -1, 0}, {0, 0, 0, -1}},  /* w2 + x2 - y2 - z2 */
    {{0, 0, 0, 1}, {0, 0, 1, 0}, {0, 1, 0, 0}, {1, 0, 0, 0}},    /* 2 (xy + wz) */
    {{0, 0, -1, 0}, {0, 0, 0, 1}, {-1, 0, 0, 0}, {0, 1, 0, 0}},  /* 2 (xz - wy) */
    {{0, 0, 0, -1}, {0, 0, 1, 0}, {0, 1, 0, 0}, {-1, 0, 0, 0}},  /* 2 (xy - wz) */
    {{1, 0, 0, 0}, {0, -1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, -1}},  /* w2 - x2 + y2 - z2 */
    {{0, 1, 0, 0}, {1, 0, 0, 0}, {0, 0, 0, 1}, {0, 0, 1, 0}},    /* 2 (yz + wx) */
    {{0, 0, 1, 0}, {0, 0, 0, 1}, {1, 0, 0, 0}, {0, 1, 0, 0}},    /* 2 (xz + wy) */
    {{0, -1, 0, 0}, {-1, 0, 0, 0}, {0, 0, 0, 1}, {0, 0, 1, 0}},  /* 2 (yz - wx) */
    {{1, 0, 0, 0}, {0, -1, 0, 0}, {0, 0, -1, 0}, {0, 0, 0, 1}}}; /* w2 - x2 - y2 + z2 */

/* R(q) (column-major), its gradient dR[k][m] = dR_k/dq_m and, if d2R != NULL, its Hessian. */
void mech_beam_quat_rot_(const double *q, double R[9], double dR[9][4], double (*d2R)[4][4])
{
    double s = q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3], is = 1.0 / s;
    for (int k = 0; k < 9; k++) {
        double Aq[4], N = 0;
        for (int m = 0; m < 4; m++) {
            Aq[m] = 0;
            for (int l = 0; l < 4; l++)
                Aq[m] += QA[k][m][l] * q[l];
            N += q[m] * Aq[m];
        }
        R[k] = N * is;
        for (int m = 0; m < 4; m++) /* dN = 2 A q, ds = 2 q */
            dR[k][m] = (2 * Aq[m] - R[k] * 2 * q[m]) * is;
        if (d2R)
            for (int m = 0; m < 4; m++)
                for (int l = 0; l < 4; l++) /* d2N = 2 A, d2s = 2 I */
                    d2R[k][m][l] = (2 * QA[k][m][l] - dR[k][m] * 2 * q[l] - dR[k][l] * 2 * q[m] -
                                    (m == l ? 2 * R[k] : 0.0)) *
                                   is;
    }
}

static void triad_q(const ad_ctx *c, const double *q, int off, const double *E0, ad *t)
{
    double R[9], dR[9][4], d2R[9][4][4];
    mech_beam_quat_rot_(q, R, dR, c->order > 1 ? d2R : NULL);
    for (int i = 0; i < 3; i++)
        for (int r = 0; r < 3; r++) {
            ad *o = &t[3 * i + r];
            const double e[3] = {E0[0 + 3 * i], E0[1 + 3 * i], E0[2 + 3 * i]};
            ad_const(c, e[0] * R[r] + e[1] * R[r + 3] + e[2] * R[r + 6], o);
            for (int m = 0; m < 4; m++)
                o->g[off + m] = e[0] * dR[r][m] + e[1] * dR[r + 3][m] + e[2] * dR[r + 6][m];
            if (c->order == 3) /* H dir */
                for (int m = 0; m < 4; m++)
                    for (int l = 0; l < 4; l++)
                        o->h[off + m] += (e[0] * d2R[r][m][l] + e[1] * d2R[r + 3][m][l] +
                                          e[2] * d2R[r + 6][m][l]) *
                                         c->dir[off + l];
            else if (c->order > 1)
                for (int m = 0; m < 4; m++)
                    for (int l = 0; l < 4; l++)
                        o->h[(off + m) * AD_N + off + l] =
                            e[0] * d2R[r][m][l] + e[1] * d2R[r + 3][m][l] + e[2] * d2R[r + 6][m][l];
        }
}

/* (a.b - c.d)/2 */
static void half_diff_dots(const ad_ctx *c, const ad *a, const ad *b, const ad *cc, const ad *d,
                           ad *r)
{
    ad_dot3s(c, 0.5, a, b, 0, r);
    ad_dot3s(c, -0.5, cc, d, 1, r);
}

/* W(x_a, x_b, q_a, q_b) on AD numbers, into k->W. */
static void beam_energy(const beam *b, const double *y, const ad_ctx *c, beam_work *k)
{
    for (int i = 0; i < 3; i++) {
        ad_var(c, y[b->xa + i], i, &k->X[i]);
        ad_var(c, y[b->xb + i], 3 + i, &k->X[3 + i]);
    }
    triad_q(c, y + b->qa, 6, b->E0, k->ta);
    triad_q(c, y + b->qb, 10, b->E0, k->tb);
    if (mech_beam_quartic_(b))
        for (int a = 0; a < 2; a++)
            ad_var(c, y[b->bs + a], 14 + a, &k->bub[a]);
    /* chord */
    for (int i = 0; i < 3; i++)
        ad_axpy(c, &k->X[3 + i], -1.0, &k->X[i], &k->d[i]);
    ad_dot3(c, k->d, k->d, &k->s);
    ad_sqrt(c, &k->s, &k->L);
    ad_inv(c, &k->L, &k->iL);
    for (int i = 0; i < 3; i++)
        ad_mul(c, &k->d[i], &k->iL, &k->e1[i]);
    /* e2 from the mean of the nodal t2, made normal to e1 */
    for (int i = 0; i < 3; i++) {
        ad_axpy(c, &k->ta[3 + i], 1.0, &k->tb[3 + i], &k->p[i]);
        ad_scale(c, 0.5, &k->p[i], &k->p[i]);
    }
    ad_dot3(c, k->p, k->e1, &k->s);
    for (int i = 0; i < 3; i++) {
        ad_mul(c, &k->s, &k->e1[i], &k->t1);
        ad_axpy(c, &k->p[i], -1.0, &k->t1, &k->w[i]);
    }
    ad_dot3(c, k->w, k->w, &k->s);
    ad_sqrt(c, &k->s, &k->nw);
    ad_inv(c, &k->nw, &k->inw);
    for (int i = 0; i < 3; i++)
        ad_mul(c, &k->w[i], &k->inw, &k->e2[i]);
    for (int i = 0; i < 3; i++) { /* e3 = e1 x e2 */
        int j = (i + 1) % 3, l = (i + 2) % 3;
        ad_mul(c, &k->e1[j], &k->e2[l], &k->t1);
        ad_mul(c, &k->e1[l], &k->e2[j], &k->t2);
        ad_axpy(c, &k->t1, -1.0, &k->t2, &k->e3[i]);
    }
    /* local rotations of both nodes: theta_x, theta_y, theta_z */
    const ad *tr[2] = {k->ta, k->tb};
    for (int n = 0; n < 2; n++) {
        const ad *t = tr[n];
        half_diff_dots(c, k->e3, t + 3, k->e2, t + 6, &k->th[3 * n + 0]);
        half_diff_dots(c, k->e1, t + 6, k->e3, t + 0, &k->th[3 * n + 1]);
        half_diff_dots(c, k->e2, t + 0, k->e1, t + 3, &k->th[3 * n + 2]);
        if (mech_beam_inertial_(b)) mech_beam_angles_(c, k, &k->th[3 * n]);
    }
    /* energy W = d^T K d / 2 over the nonzero entries of the local stiffness */
    ad_const(c, -b->L0, &k->t1);
    ad_axpy(c, &k->L, 1.0, &k->t1, &k->u); /* u = L - L0 */
    const ad *dl[7] = {&k->u, &k->th[0], &k->th[1], &k->th[2], &k->th[3], &k->th[4], &k->th[5]};
    ad_const(c, 0.0, &k->W);
    int cons = mech_beam_inertial_(b);
    if (cons) mech_beam_bow_(c, k, b->sec.E * b->sec.A, b->L0, mech_beam_quartic_(b));
    for (int r = 0; r < 7; r++)
        for (int q = r; q < 7; q++) {
            if (b->K[r][q] == 0 || (cons && r == 0 && q == 0)) continue;
            ad_mul(c, dl[r], dl[q], &k->t2);
            ad_axpy(c, &k->W, (q == r ? 0.5 : 1.0) * b->K[r][q], &k->t2, &k->W);
        }
    if (mech_beam_quartic_(b)) { /* the bubbles' bending: EI / (2 L0) int B''^2 b^2, = 4/5 */
        const double EI[2] = {b->sec.E * b->sec.Iy, b->sec.E * b->sec.Iz};
        for (int a = 0; a < 2; a++) {
            ad_mul(c, &k->bub[a], &k->bub[a], &k->t2);
            ad_axpy(c, &k->W, 0.4 * EI[a] / b->L0, &k->t2, &k->W);
        }
    }
    if (cons) mech_beam_offsets_(c, b, k);
    /* the Hessians read whole (velocity_gradient): W's, and the deformations' for the damping */
    ad_mirror(c, &k->W);
    for (int r = 0; r < 7; r++)
        ad_mirror(c, (ad *)dl[r]);
}

/* J(q): dq = J(q) dphi for a global rotation dphi, dq = (0, dphi) (x) q / 2; rows j, cols k. */
void mech_beam_quat_J_(const double *q, double J[4][3])
{
    double w = q[0], v0 = q[1], v1 = q[2], v2 = q[3];
    double T[4][3] = {{-v0, -v1, -v2}, {w, v2, -v1}, {-v2, w, v0}, {v1, -v0, w}};
    for (int j = 0; j < 4; j++)
        for (int k = 0; k < 3; k++)
            J[j][k] = 0.5 * T[j][k];
}

static int config_var(const beam *b, int c)
{
    return c < 3    ? b->xa + c
           : c < 6  ? b->xb + c - 3
           : c < 10 ? b->qa + c - 6
           : c < 14 ? b->qb + c - 10
                    : b->bs + c - 14;
}

void mech_beam_node_J_(const beam *b, const double *y, mech_beam_nodej *nj)
{
    mech_beam_quat_J_(y + b->qa, nj->J[0]);
    mech_beam_quat_J_(y + b->qb, nj->J[1]);
}

/* The gradient of an AD scalar a in the velocity coordinates (x_a, phi_a, x_b, phi_b) of the
 * ports (phi: global rotation increments, through dq = J(q) dphi); mech_beam_velocity_gradient_
 * adds the bubbles' and the derivatives. */
void mech_beam_velocity_gradient_g_(const double *ag, const mech_beam_nodej *nj, double *gv)
{
    const double(*J)[4][3] = nj->J;
    const int qoff[2] = {6, 10}, xoff[2] = {0, 3};
    for (int n = 0; n < 2; n++) {
        for (int i = 0; i < 3; i++) {
            gv[6 * n + i] = ag[xoff[n] + i];
            double mk = 0;
            for (int j = 0; j < 4; j++)
                mk += ag[qoff[n] + j] * J[n][j][i];
            gv[6 * n + 3 + i] = mk;
        }
    }
}

void mech_beam_velocity_gradient_(const beam *b, const ad *a, const mech_beam_nodej *nj, double *gv,
                                  double (*dgv)[MB_NC])
{
    const int qoff[2] = {6, 10}, xoff[2] = {0, 3};
    const double(*J)[4][3] = nj->J;
    mech_beam_velocity_gradient_g_(a->g, nj, gv);
    for (int k = 12; k < b->nv; k++) { /* the bubbles: their rates are their velocities */
        gv[k] = a->g[k + 2];
        for (int cc = 0; dgv && cc < b->nc; cc++)
            dgv[k][cc] = a->h[(k + 2) * AD_N + cc];
    }
    double dJ[4][4][3]; /* dJ/dq_m: J is linear in q, J(e_m) */
    for (int m = 0; m < 4 && dgv; m++) {
        double e[4] = {0, 0, 0, 0};
        e[m] = 1.0;
        mech_beam_quat_J_(e, dJ[m]);
    }
    for (int n = 0; n < 2 && dgv; n++) {
        for (int cc = 0; cc < b->nc; cc++) {
            for (int i = 0; i < 3; i++) {
                dgv[6 * n + i][cc] = a->h[(xoff[n] + i) * AD_N + cc];
                double d = 0;
                for (int j = 0; j < 4; j++)
                    d += a->h[(qoff[n] + j) * AD_N + cc] * J[n][j][i];
                if (cc >= qoff[n] && cc < qoff[n] + 4)
                    for (int j = 0; j < 4; j++)
                        d += a->g[qoff[n] + j] * dJ[cc - qoff[n]][j][i];
                dgv[6 * n + 3 + i][cc] = d;
            }
        }
    }
}

/* Port loads g (12: F_a, M_a, F_b, M_b; then the quartic element's bubble forces dW/db) and, if
 * dg != NULL, dg[r][c] = d g_r / d X_c (b->nc configuration unknowns) and dgw[r][m] =
 * d g_r / d w_m (12 port flows, damping only).
 * Elastic loads: the gradient of W. Stiffness-proportional damping (beta > 0): the gradient of
 * the dissipation function D = beta/2 d'^T K d' with d' = Jd w (Jd: the gradients of the local
 * deformations in the velocity coordinates, w: the port flows), i.e. beta Jd^T K Jd w. */
static void beam_loads(const beam *b, const double *y, int order, const double *dir, double *g,
                       double (*dg)[MB_NC], double (*dgw)[12])
{
    beam_work *k = b->work;
    ad_ctx c = {.order = order, .dir = dir, .n = b->nc};
    beam_energy(b, y, &c, k);
    mech_beam_nodej nj;
    mech_beam_node_J_(b, y, &nj);
    mech_beam_velocity_gradient_(b, &k->W, &nj, g, dg);
    if (dgw) memset(dgw, 0, 144 * sizeof(double));
    double beta = b->sec.beta;
    if (!(beta > 0)) return;
    const ad *dl[7] = {&k->u, &k->th[0], &k->th[1], &k->th[2], &k->th[3], &k->th[4], &k->th[5]};
    double Jd[7][MB_NV], (*dJ)[MB_NV][MB_NC] = k->dJ, w[12], dd[7] = {0}, z[7] = {0};
    const double(*K)[7] = b->K;
    for (int r = 0; r < 7; r++)
        mech_beam_velocity_gradient_(b, dl[r], &nj, Jd[r], dg ? dJ[r] : NULL);
    for (int m = 0; m < 6; m++) {
        w[m] = y[b->f[0] + m];
        w[6 + m] = y[b->f[1] + m];
    }
    for (int r = 0; r < 7; r++)
        for (int m = 0; m < 12; m++)
            dd[r] += Jd[r][m] * w[m];
    for (int r = 0; r < 7; r++)
        for (int s2 = 0; s2 < 7; s2++)
            z[r] += K[r][s2] * dd[s2];
    for (int kk = 0; kk < 12; kk++) {
        double sum = 0;
        for (int r = 0; r < 7; r++)
            sum += Jd[r][kk] * z[r];
        g[kk] += beta * sum;
    }
    if (!dg) return;
    double KJ[7][12]; /* K Jd */
    for (int r = 0; r < 7; r++)
        for (int m = 0; m < 12; m++) {
            double sum = 0;
            for (int s2 = 0; s2 < 7; s2++)
                sum += K[r][s2] * Jd[s2][m];
            KJ[r][m] = sum;
        }
    for (int kk = 0; kk < 12; kk++)
        for (int m = 0; m < 12; m++) {
            double sum = 0;
            for (int r = 0; r < 7; r++)
                sum += Jd[r][kk] * KJ[r][m];
            dgw[kk][m] = beta * sum;
        }
    /* d dd_s / dc = sum_m dJ[s][m][c] w_m */
    double ddc[7][MB_NC];
    for (int s2 = 0; s2 < 7; s2++)
        for (int cc = 0; cc < b->nc; cc++) {
            double sum = 0;
            for (int m = 0; m < 12; m++)
                sum += dJ[s2][m][cc] * w[m];
            ddc[s2][cc] = sum;
        }
    for (int kk = 0; kk < 12; kk++)
        for (int cc = 0; cc < b->nc; cc++) {
            double sum = 0;
            for (int r = 0; r < 7; r++) {
                double kz = 0;
                for (int s2 = 0; s2 < 7; s2++)
                    kz += K[r][s2] * ddc[s2][cc];
                sum += dJ[r][kk][cc] * z[r] + Jd[r][kk] * kz;
            }
            dg[kk][cc] += beta * sum;
        }
}

/* The velocity unknowns of the nodes, in the port order (v_a, w_a, v_b, w_b), then the
 * bubbles' rates c_y, c_z (quartic): p = 0 .. nv - 1. */
static int node_rate_var(const beam *b, int p)
{
    if (p >= 12) return b->bs + 2 + p - 12;
    const int base[4] = {b->va, b->wa, b->vb, b->wb};
    return base[p / 3] + p % 3;
}

/* The bubbles' damping (quartic, beta > 0): the dissipation function beta/2 (4/5) EI / L0 c^2
 * of each, the part of beta/2 d'^T K d' the bubble adds (its bending is uncoupled). */
static double bubble_damping(const beam *b, int a)
{
    const double EI = b->sec.E * (a ? b->sec.Iz : b->sec.Iy);
    return b->sec.beta * 0.8 * EI / b->L0;
}

static int beam_declare(bgr_element *el, bgr_model *m)
{
    beam *b = el->params;
    bgr_ref ra = {BGR_STATE, b->node_a, 0}, rb = {BGR_STATE, b->node_b, 0};
    bgr_element *na = bgr_element_get(m, b->node_a), *nb = bgr_element_get(m, b->node_b);
    if (!na || !nb || na->nstates != 13 || nb->nstates != 13 || strcmp(na->cls->type, "body") ||
        strcmp(nb->cls->type, "body"))
        return bg_error_raise(bgr_model_error_mut(m), BG_ERR_ARGUMENT, "bgr_compile",
                              "beam %s/%s: its nodes must be rigid bodies (mech_body)",
                              bgr_component_path(m, el->comp), el->name);
    b->xa = bgr_ref_var(m, ra);
    b->xb = bgr_ref_var(m, rb);
    b->va = b->xa + 3; /* mech_body's states: x, v, w, q */
    b->vb = b->xb + 3;
    b->wa = b->xa + 6;
    b->wb = b->xb + 6;
    b->qa = b->xa + 9;
    b->qb = b->xb + 9;
    b->bs = el->state0;
    for (int k = 0; k < 2; k++) {
        b->e[k] = bgr_ev(el, m, k, 0);
        b->f[k] = bgr_fv(el, m, k, 0);
        b->s[k] = el->sign[k];
    }
    static const char *const lab[16] = {
        "force_a0",      "force_a1",      "force_a2",        "moment_a0",
        "moment_a1",     "moment_a2",     "force_b0",        "force_b1",
        "force_b2",      "moment_b0",     "moment_b1",       "moment_b2",
        "bubble_y_rate", "bubble_z_rate", "bubble_y_motion", "bubble_z_motion"};
    int quartic = mech_beam_quartic_(b), inertial = mech_beam_inertial_(b);
    int st = bgr_declare_equations(el, m, quartic ? 16 : 12, lab);
    for (int r = 0; st == BG_OK && r < 12; r++) {
        st = bgr_declare_dep(el, m, r, b->e[r / 6] + r % 6, 0);
        for (int cc = 0; st == BG_OK && cc < b->nc; cc++)
            st = bgr_declare_dep(el, m, r, config_var(b, cc), 0);
        for (int mm = 0; st == BG_OK && b->sec.beta > 0 && mm < 12; mm++)
            st = bgr_declare_dep(el, m, r, b->f[mm / 6] + mm % 6, 0);
        for (int p = 0; st == BG_OK && inertial && p < 2 * b->nv; p++)
            st = bgr_declare_dep(el, m, r, node_rate_var(b, p % b->nv), p / b->nv);
    }
    for (int a = 0; st == BG_OK && quartic && a < 2; a++) { /* b' = c */
        st = bgr_declare_dep(el, m, 12 + a, b->bs + a, 1);
        if (st == BG_OK) st = bgr_declare_dep(el, m, 12 + a, b->bs + 2 + a, 0);
    }
    for (int a = 0; st == BG_OK && quartic && a < 2; a++) { /* the bubble's motion */
        for (int cc = 0; st == BG_OK && cc < b->nc; cc++)
            st = bgr_declare_dep(el, m, 14 + a, config_var(b, cc), 0);
        for (int p = 0; st == BG_OK && p < 2 * b->nv; p++)
            st = bgr_declare_dep(el, m, 14 + a, node_rate_var(b, p % b->nv), p / b->nv);
    }
    /* Nominal magnitudes of the port loads: the stated force (the chain builder states the
     * chain's weight; a section alone carries no load); moments: the stated moment, else that
     * force times L0 (the element's equilibrium M_a + M_b + L0 e1 x F_b = 0 ties its end moments
     * to its shear forces over its length). */
    double M = b->sc.moment > 0 ? b->sc.moment : b->sc.force * b->L0;
    for (int k = 0; k < 2 && st == BG_OK; k++)
        st = mech_nominal_port(el, m, b->e[k], 6, b->sc.force, M);
    return st;
}

static int beam_residual(const bgr_element *el, double t, const double *y, const double *yp,
                         double *F)
{
    (void)t;
    const beam *b = el->params;
    double g[MB_NV], gi[MB_NV];
    if (mech_beam_inertial_(b)) { /* the inertia: Hessians along the motion */
        double Xd[MB_NC];         /* the configuration's rate: the accelerations' direction */
        mech_beam_config_rate_(b, y, Xd);
        beam_loads(b, y, 3, Xd, g, NULL, NULL);
        mech_beam_inertia_(b, y, yp, gi, NULL, NULL, NULL);
        for (int r = 0; r < b->nv; r++)
            g[r] += gi[r];
    } else {
        mech_beam_loads_plain_(b, y, g);
    }
    for (int r = 0; r < 12; r++)
        F[r] = b->s[r / 6] * y[b->e[r / 6] + r % 6] - g[r];
    int neq = 12;
    if (mech_beam_quartic_(b)) {
        for (int a = 0; a < 2; a++) {
            F[12 + a] = yp[b->bs + a] - y[b->bs + 2 + a];
            F[14 + a] = g[12 + a] + bubble_damping(b, a) * y[b->bs + 2 + a];
        }
        neq = 16;
    }
    for (int r = 0; r < neq; r++)
        if (!isfinite(F[r])) return 1; /* degenerate configuration: cut the step */
    return 0;
}

static int beam_jacobian(const bgr_element *el, double t, const double *y, const double *yp,
                         double *v)
{
    (void)t;
    const beam *b = el->params;
    double g[MB_NV], dg[MB_NV][MB_NC], dgw[12][12], gi[MB_NV], dX[MB_NV][MB_NC], dV[MB_NV][MB_NV],
        dA[MB_NV][MB_NV];
    int cons = mech_beam_inertial_(b), nv = b->nv, nc = b->nc;
    beam_loads(b, y, 2, NULL, g, dg, dgw);
    if (cons) mech_beam_inertia_(b, y, yp, gi, dX, dV, dA);
    int n = 0;
    for (int r = 0; r < 12; r++) {
        v[n++] = b->s[r / 6];
        for (int cc = 0; cc < nc; cc++)
            v[n++] = -dg[r][cc] - (cons ? dX[r][cc] : 0.0);
        for (int mm = 0; b->sec.beta > 0 && mm < 12; mm++)
            v[n++] = -dgw[r][mm];
        for (int p = 0; cons && p < 2 * nv; p++)
            v[n++] = -(p < nv ? dV[r][p] : dA[r][p - nv]);
    }
    if (!mech_beam_quartic_(b)) return 0;
    for (int a = 0; a < 2; a++) {
        v[n++] = 1.0;
        v[n++] = -1.0;
    }
    for (int a = 0; a < 2; a++) {
        int r = 12 + a;
        for (int cc = 0; cc < nc; cc++)
            v[n++] = dg[r][cc] + dX[r][cc];
        for (int p = 0; p < 2 * nv; p++)
            v[n++] = (p < nv ? dV[r][p] : dA[r][p - nv]) + (p == r ? bubble_damping(b, a) : 0.0);
    }
    return 0;
}

static const bgr_element_class beam_class = {.type = "beam",
                                             .declare = beam_declare,
                                             .residual = beam_residual,
                                             .jacobian = beam_jacobian,
                                             .destroy = beam_free};

mech_scales *mech_beam_scales_(bgr_element *el)
{
    return el && el->cls == &beam_class ? &((beam *)el->params)->sc : NULL;
}

/* BG_OK if the local stiffness of the section over the length L0 (and its damping beta K) is
 * finite, else the refusal (products of the section's numbers that overflow). */
int mech_beam_bad_stiffness_(bgr_model *m, bgr_comp c, const char *name, const char *w,
                             const mech_section *s, double L0)
{
    beam b;
    memset(&b, 0, sizeof b);
    b.sec = *s;
    b.L0 = L0;
    mech_beam_stiffness_(&b, b.K);
    for (int i = 0; i < 7; i++)
        for (int j = 0; j < 7; j++)
            if (!isfinite(b.K[i][j]) || !isfinite(s->beta * b.K[i][j]))
                return bgr_refuse(m, c, name, w,
                                  "the local stiffness of the section over L0 = %g is not finite "
                                  "(K[%d][%d] = %g), expected section properties whose "
                                  "stiffnesses EA/L0, GJ/L0, EI/L0 (times beta) are finite",
                                  L0, i, j, b.K[i][j]);
    return BG_OK;
}

/* mech_beam with the scratch shared (NULL: its own). */
int mech_beam_add_(bgr_model *m, bgr_comp c, const char *name, int node_a, int node_b,
                   const mech_section *sec, const double *E0, double L0, beam_work *shared,
                   const double *gravity)
{
    const char *w = "mech_beam";
    if (mech_beam_bad_section_(m, c, name, w, sec) || mech_beam_bad_frame_(m, c, name, w, E0) ||
        bgr_check_value(m, c, name, w, "L0", L0, BGR_POSITIVE) ||
        mech_beam_bad_node_(m, c, name, w, "node_a", node_a) ||
        mech_beam_bad_node_(m, c, name, w, "node_b", node_b) ||
        mech_beam_bad_stiffness_(m, c, name, w, sec, L0) ||
        bgr_check_values(m, c, name, w, "gravity", gravity, 3, BGR_FINITE))
        return BG_ERR_ARGUMENT;
    if (sec->element != MECH_BEAM_LUMPED && !(sec->rho > 0 && isfinite(sec->rho * sec->A * L0)))
        return bgr_refuse(m, c, name, w,
                          "section.rho = %g with element = %s, expected rho > 0 and a finite "
                          "element mass rho A L0",
                          sec->rho,
                          sec->element == MECH_BEAM_QUARTIC ? "MECH_BEAM_QUARTIC"
                                                            : "MECH_BEAM_CONSISTENT");
    if (sec->element == MECH_BEAM_QUARTIC && sec->kappa > 0)
        return bgr_refuse(m, c, name, w,
                          "section.kappa = %g with element = MECH_BEAM_QUARTIC, expected 0 (the "
                          "quartic element is Euler-Bernoulli)",
                          sec->kappa);
    if (node_a == node_b)
        return bgr_refuse(m, c, name, w, "node_a = node_b = %d, expected two different bodies",
                          node_a);
    beam *b = calloc(1, sizeof *b);
    if (b && shared) {
        b->work = shared;
        shared->refs++;
    } else if (b && !(b->work = calloc(1, sizeof *b->work))) {
        free(b);
        b = NULL;
    } else if (b) {
        b->work->refs = 1;
    }
    if (!b)
        return bg_error_raise(bgr_model_error_mut(m), BG_ERR_MEMORY, "mech_beam", "out of memory");
    b->sec = *sec;
    memcpy(b->E0, E0, sizeof b->E0);
    b->L0 = L0;
    if (gravity) memcpy(b->grav, gravity, sizeof b->grav);
    mech_beam_stiffness_(b, b->K);
    b->node_a = node_a;
    b->node_b = node_b;
    int quartic = sec->element == MECH_BEAM_QUARTIC;
    b->nc = quartic ? 16 : 14;
    b->nv = quartic ? 14 : 12;
    if (mech_beam_inertial_(b)) {
        if (!(b->pts = calloc(MECH_BEAM_NPOINTS, sizeof *b->pts))) {
            beam_free(b);
            return bg_error_raise(bgr_model_error_mut(m), BG_ERR_MEMORY, "mech_beam",
                                  "out of memory");
        }
        b->npts = mech_beam_points_(b, b->pts);
    }
    const int dims[2] = {6, 6};
    static const char *const states[4] = {"bubble_y", "bubble_z", "bubble_y_rate", "bubble_z_rate"};
    return bgr_element_add(m, c, name, &beam_class, b, 2, dims, quartic ? 4 : 0,
                           quartic ? states : NULL, 0, NULL);
}

int mech_beam(bgr_model *m, bgr_comp c, const char *name, int node_a, int node_b,
              const mech_section *sec, const double *E0, double L0)
{
    return mech_beam_add_(m, c, name, node_a, node_b, sec, E0, L0, NULL, NULL);
}

double mech_beam_energy(const bgr_model *m, int elem, const double *y)
{
    bgr_element *el = bgr_element_get((bgr_model *)m, elem);
    if (!el || el->cls != &beam_class || !bgr_n(m) || !y) return NAN;
    const beam *b = el->params;
    ad_ctx c = {.order = 1, .n = b->nc};
    beam_energy(b, y, &c, b->work);
    return b->work->W.v;
}

double mech_beam_dissipation(const bgr_model *m, int elem, const double *y)
{
    bgr_element *el = bgr_element_get((bgr_model *)m, elem);
    if (!el || el->cls != &beam_class || !bgr_n(m) || !y) return NAN;
    const beam *b = el->params;
    if (!(b->sec.beta > 0)) return 0.0;
    double P = mech_beam_strain_power_(b, y);
    for (int a = 0; mech_beam_quartic_(b) && a < 2; a++)
        P += bubble_damping(b, a) * y[b->bs + 2 + a] * y[b->bs + 2 + a];
    return P;
}

double mech_beam_kinetic(const bgr_model *m, int elem, const double *y)
{
    bgr_element *el = bgr_element_get((bgr_model *)m, elem);
    if (!el || el->cls != &beam_class || !bgr_n(m) || !y) return NAN;
    const beam *b = el->params;
    if (!mech_beam_inertial_(b)) return 0.0;
    ad_ctx c = {.order = 1, .n = b->nc};
    beam_energy(b, y, &c, b->work);
    return mech_beam_kinetic_(b, y);
}

int mech_beam_loads(const bgr_model *m, int elem, const double *y, int path, double g[12])
{
    bgr_element *el = bgr_element_get((bgr_model *)m, elem);
    if (!el || el->cls != &beam_class || !bgr_n(m) || !y || !g || path < 0 || path > 1)
        return BG_ERR_ARGUMENT;
    const beam *b = el->params;
    double gl[MB_NV];
    if (path == 0 && !mech_beam_quartic_(b))
        mech_beam_loads_plain_(b, y, gl);
    else
        beam_loads(b, y, 1, NULL, gl, NULL, NULL);
    memcpy(g, gl, 12 * sizeof *g);
    return BG_OK;
}
