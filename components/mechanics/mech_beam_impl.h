/* Internal to the beam (not installed, nothing here is exported): the element's data, shared by
 * the element (mech_beam.c), the consistent element's parts (mech_beam_consistent.c) and the
 * chain builder (mech_beam_chain.c). The checks are the element's own, so that a chain refuses a
 * section, or a length that makes its stiffness overflow, with the same messages as a single
 * element, and before it builds anything. */
#ifndef MECH_BEAM_IMPL_H
#define MECH_BEAM_IMPL_H

#include "mech_ad.h"
#include "mech_beam.h"
#include "mech_util.h"

/* The consistent inertia's basis vectors made on AD numbers (mech_beam_consistent.c): 22 for
 * the consistent element, 28 with the quartic element's bubble. */
#define MECH_BEAM_NBASIS 28
/* The configuration unknowns (the AD variables), at most: x_a, x_b, q_a, q_b (14) and the
 * quartic element's bubble amplitudes b_y, b_z; and the velocity coordinates, at most: v_a,
 * omega_a, v_b, omega_b (12, the ports' flows) and the bubbles' rates. */
#define MB_NC 16
#define MB_NV 14

/* AD scratch of one energy evaluation (about 130 kB with Hessians), allocated with the element
 * so that residual and Jacobian evaluations allocate nothing. The elements of a chain share one
 * (reference counted): they are evaluated one after another, and one scratch stays in cache
 * where one per element (60 MB for 512 elements) made the residual's cost per element grow
 * with their number. */
typedef struct beam_work {
    ad X[6], ta[9], tb[9], d[3], e1[3], e2[3], e3[3], th[6]; /* X: the nodes' positions */
    ad L, iL, s, p[3], w[3], nw, inw, u, t1, t2, W;
    ad bow, eps;               /* consistent element: the bowing term and the axial strain */
    ad sq[6];                  /* consistent inertia: the foreshortening's quadratic forms */
    ad bub[2];                 /* quartic element: the bubble amplitudes b_y, b_z */
    ad B[MECH_BEAM_NBASIS][3]; /* consistent inertia: the basis vectors of the fields (see
                                  mech_beam_consistent.c) */
    double gv[MECH_BEAM_NBASIS][3][MB_NV], dgv[MECH_BEAM_NBASIS][3][MB_NV][MB_NC]; /* their
                                  velocity gradients and derivatives */
    double dJ[7][MB_NV][MB_NC]; /* damping: derivatives of the deformation gradients */
    int refs;                   /* elements sharing it */
} beam_work;

/* An inertia point of the consistent and quartic elements (mech_beam_consistent.c): its field
 * as coefficients over the basis vectors and the two node positions, its mass mu, and whether
 * gravity acts on it. They depend on the element's length and section only: made once. */
#define MECH_BEAM_NPOINTS 21
typedef struct mech_beam_point {
    double c[MECH_BEAM_NBASIS + 2], mu;
    int weight;
} mech_beam_point;

typedef struct beam {
    mech_section sec;
    double E0[9], L0;
    double K[7][7]; /* local stiffness of (u, theta_a, theta_b): W = d^T K d / 2 */
    int node_a, node_b;
    int xa, qa, xb, qb; /* configuration variable ids */
    int va, wa, vb, wb; /* velocity ids of the nodes (consistent inertia) */
    int bs;             /* quartic: the element's states b_y, b_z, c_y, c_z (c = b') from bs */
    int nc, nv;         /* configuration unknowns (14, 16 quartic), velocity coordinates (12,
                           14 quartic) */
    int e[2], s[2];     /* first effort id and orientation of each port */
    int f[2];           /* first flow id of each port (damping) */
    double grav[3];     /* gravity (consistent inertia: the distributed weight) */
    beam_work *work;
    mech_beam_point *pts; /* the inertia points (consistent, quartic; NULL: lumped) */
    int npts;
    mech_scales sc; /* stated nominal scales (the chain builder states its weight) */
} beam;

/* A scratch holding one reference (the caller's); NULL when out of memory. */
beam_work *mech_beam_work_new_(void);
/* Drops one reference to a scratch (NULL: nothing); the last frees it. */
void mech_beam_work_release_(beam_work *w);

/* mech_beam with the scratch shared (shared gets one more reference; NULL: the element's own)
 * and the gravity of its distributed weight (consistent inertia; NULL: none). */
int mech_beam_add_(bgr_model *m, bgr_comp c, const char *name, int node_a, int node_b,
                   const mech_section *sec, const double *E0, double L0, beam_work *shared,
                   const double *gravity);

/* BG_OK if sec obeys the rules of mech_beam.h, else the refusal naming the field (w: the
 * constructor, for the message). */
int mech_beam_bad_section_(bgr_model *m, bgr_comp c, const char *name, const char *w,
                           const mech_section *sec);
/* BG_OK if E0 is a finite right-handed orthonormal frame (to 1e-9), else the refusal. */
int mech_beam_bad_frame_(bgr_model *m, bgr_comp c, const char *name, const char *w,
                         const double *E0);
/* BG_OK if node is a rigid body (mech_body) of m, else the refusal naming param. */
int mech_beam_bad_node_(bgr_model *m, bgr_comp c, const char *name, const char *w,
                        const char *param, int node);
/* BG_OK if the local stiffness of the section over the length L0 (and its damping beta K) is
 * finite, else the refusal. */
int mech_beam_bad_stiffness_(bgr_model *m, bgr_comp c, const char *name, const char *w,
                             const mech_section *sec, double L0);

/* The element has distributed inertia (consistent or quartic), a bubble (quartic). */
static inline int mech_beam_inertial_(const beam *b)
{
    return b->sec.element != MECH_BEAM_LUMPED;
}
static inline int mech_beam_quartic_(const beam *b)
{
    return b->sec.element == MECH_BEAM_QUARTIC;
}

/* J(q): dq = J(q) dphi for a global rotation increment dphi (rows: q, columns: dphi). */
void mech_beam_quat_J_(const double *q, double J[4][3]);
/* R(q) = N(q) / (q.q) (column-major), its gradient dR[k][m] = dR_k / dq_m and, if d2R != NULL,
 * its Hessian. */
void mech_beam_quat_rot_(const double *q, double R[9], double dR[9][4], double (*d2R)[4][4]);
/* J(q) of the element's two nodes (J[0]: node a, J[1]: node b), made once per evaluation. */
typedef struct mech_beam_nodej {
    double J[2][4][3];
} mech_beam_nodej;
/* The nodes' J at y. */
void mech_beam_node_J_(const beam *b, const double *y, mech_beam_nodej *nj);
/* gv (12) = the gradient ag (14 configuration unknowns x_a, x_b, q_a, q_b) in the ports'
 * velocity coordinates (x_a, phi_a, x_b, phi_b), through dq = J(q) dphi. */
void mech_beam_velocity_gradient_g_(const double *ag, const mech_beam_nodej *nj, double *gv);
/* The gradient gv (b->nv) of an AD scalar a in the velocity coordinates (x_a, phi_a, x_b,
 * phi_b, and the bubbles' b) and, if dgv != NULL, its derivatives with respect to the b->nc
 * configuration unknowns; nj: the nodes' J (mech_beam_node_J_). */
void mech_beam_velocity_gradient_(const beam *b, const ad *a, const mech_beam_nodej *nj, double *gv,
                                  double (*dgv)[MB_NC]);

/* The plain path (mech_beam_plain.c). The local stiffness K (7 x 7) of the deformations
 * (u, theta_a, theta_b), W = d^T K d / 2 (made once, with the element). */
void mech_beam_stiffness_(const beam *b, double K[7][7]);
/* The port loads g (12) of the lumped and consistent elements' residual at y: elastic, bowing
 * (consistent) and damping, by one forward, one tangent (damped only) and one reverse pass. */
void mech_beam_loads_plain_(const beam *b, const double *y, double *g);
/* beta d'^T K d': the power the section's damping dissipates at y (the bubbles' apart). */
double mech_beam_strain_power_(const beam *b, const double *y);

/* The consistent element (mech_beam_consistent.c). The rotation measure: the node angles th
 * (3) of one node turned from the skew part into the rotation vector, in place. */
void mech_beam_angles_(const ad_ctx *c, beam_work *k, ad *th);
/* The bowing term: k->W += EA L0 eps^2 / 2, eps = u / L0 + (L / L0) bow / 30, bow = 2 ta^2 -
 * ta tb + 2 tb^2 over both bending planes (k->L, k->u, k->th set), and with a bubble (quartic,
 * k->bub set) + (ta - tb) b + 2 b^2 / 7. */
void mech_beam_bow_(const ad_ctx *c, beam_work *k, double EA, double L0, int quartic);
/* The same on plain numbers: to z = dW/dd (7: u, theta_a, theta_b) of the quadratic energy
 * without its EA u^2 / (2 L0), the rest of the axial energy's gradient at the deformations d. */
void mech_beam_bow_loads_(const double *d, double EA, double L0, double *z);
/* X' (b->nc) = B u': the configuration's rate from the nodes' (and bubbles') velocities in y. */
void mech_beam_config_rate_(const beam *b, const double *y, double *Xd);
/* Inertia. After the element frame (e1, e2, e3), the node
 * triads and the node angles th are in the scratch: the basis vectors of the displacement and
 * director fields into k->B (Hessians mirrored at order 2). */
void mech_beam_offsets_(const ad_ctx *c, const beam *b, beam_work *k);
/* The inertial loads g (b->nv: the ports', then the bubbles') of the element at (y, yp), after
 * beam_energy at order 3 along X' (mech_beam_config_rate_; dX NULL) or at order 2 (the whole
 * Hessians), and, if dX != NULL, their Jacobian: dX (nv x nc, configuration unknowns), dV
 * (nv x nv: the node velocities v, w, body-frame w, and the bubbles' rates c), dA (nv x nv:
 * their rates). */
void mech_beam_inertia_(const beam *b, const double *y, const double *yp, double g[MB_NV],
                        double (*dX)[MB_NC], double (*dV)[MB_NV], double (*dA)[MB_NV]);
/* The inertia points of an element with distributed inertia into p (MECH_BEAM_NPOINTS): their
 * number. */
int mech_beam_points_(const beam *b, mech_beam_point *p);
/* The kinetic energy the element adds to its node bodies' (consistent minus lumped). */
double mech_beam_kinetic_(const beam *b, const double *y);

#endif
