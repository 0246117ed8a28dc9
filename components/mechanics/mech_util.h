/* Shared helpers of the mechanical components (internal, header-only).
 *
 * 1. The dependency emitter. An element's partial derivatives are written once, in one function
 *    that runs in two modes: at compilation it declares each (equation, variable, y or y')
 *    triple, at run time it stores the values in the same order. Declaration and values can
 *    therefore not drift apart.
 * 2. Small 3-vector and 3x3 helpers (column-major 3x3 arrays).
 * 3. Quaternions q = (w, x, y, z) and the rotation matrix of the homogeneous form
 *        R(q) = N(q) / (q.q),  N = [[w2+x2-y2-z2, 2(xy-wz), 2(xz+wy)],
 *                                   [2(xy+wz), w2-x2+y2-z2, 2(yz-wx)],
 *                                   [2(xz-wy), 2(yz+wx), w2-x2-y2+z2]],
 *    which is a rotation for any q != 0, so the drift of |q| under integration has no physical
 *    effect (the kinematics q' = q (x) (0, w)/2 preserves |q| exactly; BDF changes it by about
 *    the tolerance per step); dR/dq_k = (dN/dq_k - 2 q_k R)/(q.q).
 *    Reference: J. Diebel, "Representing attitude: Euler angles, unit quaternions, and rotation
 *    vectors" (Stanford, 2006), sec. 6.
 * 4. Nominal magnitudes (bgr_declare_nominal): the scales stated for an element through
 *    mech_set_nominal (mech_body.h), kept in its parameters, and the declaration helpers. */
#ifndef MECH_UTIL_H
#define MECH_UTIL_H

#include <math.h>
#include <string.h>

#include "bgr_check.h"
#include "bgr_model.h"

/* The most ports a body (mech_body) takes. */
#define MECH_MAXPORTS 64

typedef struct mech_emit {
    int declare; /* 1: declare dependencies; 0: store values */
    bgr_element *el;
    bgr_model *m;
    double *v;
    int n, status;
} mech_emit;

static inline void mech_dep(mech_emit *e, int row, int var, int wrt_yp, double value)
{
    if (e->declare) {
        if (e->status == BG_OK) e->status = bgr_declare_dep(e->el, e->m, row, var, wrt_yp);
    } else {
        e->v[e->n++] = value;
    }
}

/* Scales stated through mech_set_nominal (0: not stated: the element's own, or none): force (N)
 * for forces, moment (N m) for moments, length (m) for positions and displacements. */
typedef struct mech_scales {
    double force, moment, length;
} mech_scales;

/* The stated scales of element el if it is one of the file's classes, else NULL (one per source
 * file, for mech_set_nominal). */
mech_scales *mech_body_scales_(bgr_element *el);
mech_scales *mech_parts_scales_(bgr_element *el);
mech_scales *mech_axial_scales_(bgr_element *el);
mech_scales *mech_beam_scales_(bgr_element *el);

/* Declares the nominal magnitude nom of unknown var (nothing if nom is no scale, i.e. not > 0,
 * or var < 0); BG_OK or the status. */
static inline int mech_nominal(bgr_element *el, bgr_model *m, int var, double nom)
{
    if (var < 0 || !(nom > 0) || !isfinite(nom)) return BG_OK;
    return bgr_declare_nominal(el, m, var, nom);
}

/* The same for the effort of a port of dimension dim (3 or 6) whose first effort id is e0: force
 * for its forces (components 0..2), moment for its moments (3..5). */
static inline int mech_nominal_port(bgr_element *el, bgr_model *m, int e0, int dim, double force,
                                    double moment)
{
    int st = BG_OK;
    for (int i = 0; i < dim && st == BG_OK && e0 >= 0; i++)
        st = mech_nominal(el, m, e0 + i, i < 3 ? force : moment);
    return st;
}

/* c = a x b */
static inline void mech_cross(const double *a, const double *b, double *c)
{
    double t0 = a[1] * b[2] - a[2] * b[1], t1 = a[2] * b[0] - a[0] * b[2],
           t2 = a[0] * b[1] - a[1] * b[0];
    c[0] = t0;
    c[1] = t1;
    c[2] = t2;
}

/* y = A x, y = A^T x (A column-major 3x3) */
static inline void mech_mv(const double *A, const double *x, double *y)
{
    for (int i = 0; i < 3; i++)
        y[i] = A[i] * x[0] + A[i + 3] * x[1] + A[i + 6] * x[2];
}

static inline void mech_mtv(const double *A, const double *x, double *y)
{
    for (int i = 0; i < 3; i++)
        y[i] = A[3 * i] * x[0] + A[3 * i + 1] * x[1] + A[3 * i + 2] * x[2];
}

static inline double mech_dot(const double *a, const double *b)
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* N(q), column-major, and its derivatives dN/dq_k */
static inline void mech_quat_N(const double *q, double *N)
{
    double w = q[0], x = q[1], y = q[2], z = q[3];
    N[0] = w * w + x * x - y * y - z * z;
    N[1] = 2 * (x * y + w * z);
    N[2] = 2 * (x * z - w * y);
    N[3] = 2 * (x * y - w * z);
    N[4] = w * w - x * x + y * y - z * z;
    N[5] = 2 * (y * z + w * x);
    N[6] = 2 * (x * z + w * y);
    N[7] = 2 * (y * z - w * x);
    N[8] = w * w - x * x - y * y + z * z;
}

static inline void mech_quat_dN(const double *q, int k, double *D)
{
    double w = q[0], x = q[1], y = q[2], z = q[3];
    /* column-major entries of dN/dq_k */
    switch (k) {
    case 0: {
        double d[9] = {2 * w, 2 * z, -2 * y, -2 * z, 2 * w, 2 * x, 2 * y, -2 * x, 2 * w};
        memcpy(D, d, sizeof d);
        break;
    }
    case 1: {
        double d[9] = {2 * x, 2 * y, 2 * z, 2 * y, -2 * x, 2 * w, 2 * z, -2 * w, -2 * x};
        memcpy(D, d, sizeof d);
        break;
    }
    case 2: {
        double d[9] = {-2 * y, 2 * x, -2 * w, 2 * x, 2 * y, 2 * z, 2 * w, 2 * z, -2 * y};
        memcpy(D, d, sizeof d);
        break;
    }
    default: {
        double d[9] = {-2 * z, 2 * w, 2 * x, -2 * w, -2 * z, 2 * y, 2 * x, 2 * y, 2 * z};
        memcpy(D, d, sizeof d);
        break;
    }
    }
}

/* R(q) and, if dR != NULL, dR[k] = dR/dq_k (4 blocks of 9). */
static inline void mech_quat_R(const double *q, double *R, double *dR)
{
    double s = q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3];
    mech_quat_N(q, R);
    for (int i = 0; i < 9; i++)
        R[i] /= s;
    if (!dR) return;
    for (int k = 0; k < 4; k++) {
        mech_quat_dN(q, k, dR + 9 * k);
        for (int i = 0; i < 9; i++)
            dR[9 * k + i] = (dR[9 * k + i] - 2 * q[k] * R[i]) / s;
    }
}

/* Quaternion from a unit rotation axis and an angle. */
static inline void mech_quat_axis_angle(const double *axis, double angle, double *q)
{
    double n = sqrt(mech_dot(axis, axis)), s = sin(0.5 * angle) / (n > 0 ? n : 1);
    q[0] = cos(0.5 * angle);
    q[1] = axis[0] * s;
    q[2] = axis[1] * s;
    q[3] = axis[2] * s;
}

#endif
