/* The 3D rigid body (equations in mech_body.h). One function writes every partial derivative,
 * declaring them at compilation and filling their values at run time (mech_util.h). */
#include "mech_body.h"

#include <stdlib.h>
#include <string.h>

#include "mech_frame.h"
#include "mech_util.h"

#define MAXPORTS MECH_MAXPORTS

typedef struct body {
    double m, J[9], g[3];
    int np;
    double r[3 * MAXPORTS];
    int dim[MAXPORTS];
    /* variable ids (filled at declaration) */
    int fv[MAXPORTS], ev[MAXPORTS]; /* first flow / effort id of each port */
    int s[MAXPORTS];
    int x, v, w, q; /* first state ids */
    double *zero;   /* zeros, for the declaration pass */
    mech_scales sc; /* stated nominal scales */
} body;

static void body_free(void *p)
{
    body *b = p;
    if (b) free(b->zero);
    free(b);
}

/* Rows: ports (dim each), then x (3), v (3), w (3), q (4). */
static int body_rows(const body *b, int *row_x)
{
    int r = 0;
    for (int k = 0; k < b->np; k++)
        r += b->dim[k];
    *row_x = r;
    return r + 13;
}

/* All partial derivatives, in one fixed order. */
static void body_partials(const bgr_element *el, const double *y, mech_emit *E)
{
    const body *b = el->params;
    const double *q = y + b->q, *w = y + b->w;
    double R[9], dR[36];
    mech_quat_R(q, R, dR);
    int row = 0, rx;
    body_rows(b, &rx);
    /* port kinematics */
    for (int k = 0; k < b->np; k++) {
        const double *r = b->r + 3 * k;
        double a[3], da[4][3];
        mech_cross(w, r, a); /* w x r */
        for (int j = 0; j < 4; j++)
            mech_mv(dR + 9 * j, a, da[j]);
        /* d(R (w x r))/dw = -R [r]x: column c is R (e_c x r) */
        double Rrx[3][3];
        for (int c = 0; c < 3; c++) {
            double ec[3] = {0, 0, 0}, t[3];
            ec[c] = 1;
            mech_cross(ec, r, t);
            mech_mv(R, t, Rrx[c]);
        }
        for (int i = 0; i < 3; i++, row++) {
            mech_dep(E, row, b->fv[k] + i, 0, 1.0);
            mech_dep(E, row, b->v + i, 0, -1.0);
            for (int c = 0; c < 3; c++)
                mech_dep(E, row, b->w + c, 0, -Rrx[c][i]);
            for (int j = 0; j < 4; j++)
                mech_dep(E, row, b->q + j, 0, -da[j][i]);
        }
        if (b->dim[k] == 6) {
            for (int i = 0; i < 3; i++, row++) {
                mech_dep(E, row, b->fv[k] + 3 + i, 0, 1.0);
                for (int c = 0; c < 3; c++)
                    mech_dep(E, row, b->w + c, 0, -R[i + 3 * c]);
                for (int j = 0; j < 4; j++) {
                    double t[3];
                    mech_mv(dR + 9 * j, w, t);
                    mech_dep(E, row, b->q + j, 0, -t[i]);
                }
            }
        }
    }
    /* x' = v */
    for (int i = 0; i < 3; i++, row++) {
        mech_dep(E, row, b->x + i, 1, 1.0);
        mech_dep(E, row, b->v + i, 0, -1.0);
    }
    /* m v' - sum s F - m g */
    for (int i = 0; i < 3; i++, row++) {
        mech_dep(E, row, b->v + i, 1, b->m);
        for (int k = 0; k < b->np; k++)
            mech_dep(E, row, b->ev[k] + i, 0, -b->s[k]);
    }
    /* J w' + w x (J w) - sum [ r x (R^T s F) + R^T s M ] */
    {
        double h[3];
        mech_mv(b->J, w, h);
        /* d(w x h)/dw = [w]x J - [h]x ; column c */
        double dwh[3][3];
        for (int c = 0; c < 3; c++) {
            double ec[3] = {0, 0, 0}, Jc[3], t1[3], t2[3];
            ec[c] = 1;
            mech_mv(b->J, ec, Jc);
            mech_cross(w, Jc, t1);
            mech_cross(ec, h, t2);
            for (int i = 0; i < 3; i++)
                dwh[c][i] = t1[i] + t2[i];
        }
        /* body-frame loads for the q derivatives: sum_k s_k (r_k x dR^T F_k + dR^T M_k) */
        double dq[4][3] = {{0}};
        for (int j = 0; j < 4; j++)
            for (int k = 0; k < b->np; k++) {
                double t[3], u[3];
                mech_mtv(dR + 9 * j, y + b->ev[k], t);
                mech_cross(b->r + 3 * k, t, u);
                for (int i = 0; i < 3; i++)
                    dq[j][i] += b->s[k] * u[i];
                if (b->dim[k] == 6) {
                    mech_mtv(dR + 9 * j, y + b->ev[k] + 3, t);
                    for (int i = 0; i < 3; i++)
                        dq[j][i] += b->s[k] * t[i];
                }
            }
        for (int i = 0; i < 3; i++, row++) {
            for (int c = 0; c < 3; c++)
                mech_dep(E, row, b->w + c, 1, b->J[i + 3 * c]);
            for (int c = 0; c < 3; c++)
                mech_dep(E, row, b->w + c, 0, dwh[c][i]);
            for (int j = 0; j < 4; j++)
                mech_dep(E, row, b->q + j, 0, -dq[j][i]);
            for (int k = 0; k < b->np; k++) {
                const double *r = b->r + 3 * k;
                /* d/dF_c of r x (R^T F): r x (R^T e_c) = r x (row c of R as a vector) */
                for (int c = 0; c < 3; c++) {
                    /* R^T e_c = row c of R */
                    double Rc[3] = {R[c], R[c + 3], R[c + 6]}, t[3];
                    mech_cross(r, Rc, t);
                    mech_dep(E, row, b->ev[k] + c, 0, -b->s[k] * t[i]);
                }
                if (b->dim[k] == 6)
                    for (int c = 0; c < 3; c++)
                        mech_dep(E, row, b->ev[k] + 3 + c, 0, -b->s[k] * R[c + 3 * i]);
            }
        }
    }
    /* q' - G(q) w / 2 */
    {
        const double G[4][3] = {
            {-q[1], -q[2], -q[3]}, {q[0], -q[3], q[2]}, {q[3], q[0], -q[1]}, {-q[2], q[1], q[0]}};
        const double O[4][4] = {{0, -w[0], -w[1], -w[2]},
                                {w[0], 0, w[2], -w[1]},
                                {w[1], -w[2], 0, w[0]},
                                {w[2], w[1], -w[0], 0}};
        for (int i = 0; i < 4; i++, row++) {
            mech_dep(E, row, b->q + i, 1, 1.0);
            for (int c = 0; c < 3; c++)
                mech_dep(E, row, b->w + c, 0, -0.5 * G[i][c]);
            for (int j = 0; j < 4; j++)
                mech_dep(E, row, b->q + j, 0, -0.5 * O[i][j]);
        }
    }
}

/* Under a frame's motion (mech_frame.h): x a point, v a vector, q an orientation, the ports'
 * vectors; w (body frame) keeps its values. */
static int body_frame(bgr_element *el, bgr_model *m, const body *b)
{
    int st = mech_frame_group(el, m, BGR_FRAME_POSITION, b->x);
    if (st == BG_OK) st = mech_frame_group(el, m, BGR_FRAME_VECTOR, b->v);
    if (st == BG_OK) st = mech_frame_group(el, m, BGR_FRAME_QUATERNION, b->q);
    return st == BG_OK ? mech_frame_ports(el, m) : st;
}

static int body_declare(bgr_element *el, bgr_model *m)
{
    body *b = el->params;
    int rx;
    for (int k = 0; k < b->np; k++) {
        b->s[k] = el->sign[k];
        b->fv[k] = bgr_fv(el, m, k, 0);
        b->ev[k] = bgr_ev(el, m, k, 0);
    }
    b->x = bgr_sv(el, 0);
    b->v = bgr_sv(el, 3);
    b->w = bgr_sv(el, 6);
    b->q = bgr_sv(el, 9);
    int nrows = body_rows(b, &rx);
    const char **lab = calloc((size_t)nrows, sizeof *lab);
    char(*buf)[24] = calloc((size_t)nrows, sizeof *buf);
    if (!lab || !buf) {
        free(lab);
        free(buf);
        return bg_error_raise(bgr_model_error_mut(m), BG_ERR_MEMORY, "bgr_compile",
                              "out of memory");
    }
    int row = 0;
    for (int k = 0; k < b->np; k++)
        for (int i = 0; i < b->dim[k]; i++, row++) {
            snprintf(buf[row], sizeof buf[row], "port%d_%s%d", k, i < 3 ? "v" : "w", i % 3);
            lab[row] = buf[row];
        }
    static const char *const rest[13] = {
        "position0", "position1", "position2", "newton0", "newton1", "newton2", "euler0",
        "euler1",    "euler2",    "quat0",     "quat1",   "quat2",   "quat3"};
    for (int i = 0; i < 13; i++)
        lab[row + i] = rest[i];
    int st = bgr_declare_equations(el, m, nrows, lab);
    free(lab);
    free(buf);
    if (st != BG_OK) return st;
    b->zero = calloc((size_t)bgr_nvars(m) + 1, sizeof *b->zero);
    if (!b->zero)
        return bg_error_raise(bgr_model_error_mut(m), BG_ERR_MEMORY, "bgr_compile",
                              "out of memory");
    b->zero[b->q] = 1.0; /* any nonzero quaternion: values are not used in this pass */
    mech_emit E = {1, el, m, NULL, 0, BG_OK};
    body_partials(el, b->zero, &E);
    free(b->zero);
    b->zero = NULL;
    if (E.status != BG_OK) return E.status;
    /* Nominal magnitudes. Forces: the stated force, else the weight m |g| (what its ports carry
     * of the body at rest); moments: the stated moment, else that force times the longest arm
     * max |r_k| (the weight hung at the farthest port); positions: the stated length only (a
     * global position has no scale of the body's). Velocities and angular velocities keep 1
     * (the parameters hold no time scale), the quaternion too (its norm is 1). */
    double F = b->sc.force > 0 ? b->sc.force : b->m * sqrt(mech_dot(b->g, b->g)), rmax = 0;
    for (int k = 0; k < b->np; k++)
        rmax = fmax(rmax, sqrt(mech_dot(b->r + 3 * k, b->r + 3 * k)));
    double M = b->sc.moment > 0 ? b->sc.moment : F * rmax;
    int st2 = BG_OK;
    for (int k = 0; k < b->np && st2 == BG_OK; k++)
        st2 = mech_nominal_port(el, m, b->ev[k], b->dim[k], F, M);
    for (int i = 0; i < 3 && st2 == BG_OK; i++)
        st2 = mech_nominal(el, m, b->x + i, b->sc.length);
    if (st2 == BG_OK) st2 = body_frame(el, m, b);
    return st2;
}


static int body_residual(const bgr_element *el, double t, const double *y, const double *yp,
                         double *F)
{
    (void)t;
    const body *b = el->params;
    const double *q = y + b->q, *w = y + b->w, *v = y + b->v;
    double R[9];
    mech_quat_R(q, R, NULL);
    int row = 0;
    for (int k = 0; k < b->np; k++) {
        double a[3], Ra[3];
        mech_cross(w, b->r + 3 * k, a);
        mech_mv(R, a, Ra);
        for (int i = 0; i < 3; i++)
            F[row++] = y[b->fv[k] + i] - v[i] - Ra[i];
        if (b->dim[k] == 6) {
            double Rw[3];
            mech_mv(R, w, Rw);
            for (int i = 0; i < 3; i++)
                F[row++] = y[b->fv[k] + 3 + i] - Rw[i];
        }
    }
    for (int i = 0; i < 3; i++)
        F[row++] = yp[b->x + i] - v[i];
    for (int i = 0; i < 3; i++) {
        double f = b->m * yp[b->v + i] - b->m * b->g[i];
        for (int k = 0; k < b->np; k++)
            f -= b->s[k] * y[b->ev[k] + i];
        F[row++] = f;
    }
    double h[3], wh[3], Jwp[3], load[3] = {0, 0, 0};
    mech_mv(b->J, w, h);
    mech_cross(w, h, wh);
    mech_mv(b->J, yp + b->w, Jwp);
    for (int k = 0; k < b->np; k++) {
        double Fb[3], u[3];
        mech_mtv(R, y + b->ev[k], Fb);
        mech_cross(b->r + 3 * k, Fb, u);
        for (int i = 0; i < 3; i++)
            load[i] += b->s[k] * u[i];
        if (b->dim[k] == 6) {
            mech_mtv(R, y + b->ev[k] + 3, Fb);
            for (int i = 0; i < 3; i++)
                load[i] += b->s[k] * Fb[i];
        }
    }
    for (int i = 0; i < 3; i++)
        F[row++] = Jwp[i] + wh[i] - load[i];
    const double *qp = yp + b->q;
    F[row++] = qp[0] - 0.5 * (-q[1] * w[0] - q[2] * w[1] - q[3] * w[2]);
    F[row++] = qp[1] - 0.5 * (q[0] * w[0] - q[3] * w[1] + q[2] * w[2]);
    F[row++] = qp[2] - 0.5 * (q[3] * w[0] + q[0] * w[1] - q[1] * w[2]);
    F[row++] = qp[3] - 0.5 * (-q[2] * w[0] + q[1] * w[1] + q[0] * w[2]);
    return 0;
}

static int body_jacobian(const bgr_element *el, double t, const double *y, const double *yp,
                         double *v)
{
    (void)t, (void)yp;
    mech_emit E = {0, NULL, NULL, v, 0, BG_OK};
    body_partials(el, y, &E);
    return 0;
}

static const bgr_element_class body_class = {.type = "body",
                                             .declare = body_declare,
                                             .residual = body_residual,
                                             .jacobian = body_jacobian,
                                             .destroy = body_free};

mech_scales *mech_body_scales_(bgr_element *el)
{
    return el && el->cls == &body_class ? &((body *)el->params)->sc : NULL;
}

int mech_body(bgr_model *m, bgr_comp c, const char *name, double mass, const double *inertia,
              const double *gravity, int nports, const double *r, const int *dims)
{
    bg_error *err = bgr_model_error_mut(m);
    const char *w = "mech_body";
    if (bgr_check_value(m, c, name, w, "mass", mass, BGR_POSITIVE)) return BG_ERR_ARGUMENT;
    if (!inertia) return bgr_refuse(m, c, name, w, "the inertia tensor is NULL");
    if (nports < 0 || nports > MAXPORTS)
        return bgr_refuse(m, c, name, w, "nports = %d, expected 0 .. %d ports", nports, MAXPORTS);
    if (nports > 0 && !r)
        return bgr_refuse(m, c, name, w, "the port points r are NULL (%d ports)", nports);
    /* finite, exactly symmetric and positive definite */
    if (bgr_check_spd(m, c, name, w, "inertia", inertia, 3) ||
        bgr_check_values(m, c, name, w, "gravity", gravity, 3, BGR_FINITE) ||
        bgr_check_values(m, c, name, w, "r", r, 3 * nports, BGR_FINITE))
        return BG_ERR_ARGUMENT;
    for (int k = 0; dims && k < nports; k++)
        if (dims[k] != 3 && dims[k] != 6)
            return bgr_refuse(m, c, name, w, "dims[%d] = %d, expected 3 or 6", k, dims[k]);
    body *b = calloc(1, sizeof *b);
    if (!b) return bg_error_raise(err, BG_ERR_MEMORY, w, "out of memory");
    b->m = mass;
    memcpy(b->J, inertia, sizeof b->J);
    if (gravity) memcpy(b->g, gravity, sizeof b->g);
    b->np = nports;
    if (nports) memcpy(b->r, r, (size_t)nports * 3 * sizeof *r);
    for (int k = 0; k < nports; k++)
        b->dim[k] = dims ? dims[k] : 6;
    static const char *const sn[13] = {"x0", "x1", "x2", "v0", "v1", "v2", "w0",
                                       "w1", "w2", "q0", "q1", "q2", "q3"};
    return bgr_element_add(m, c, name, &body_class, b, nports, b->dim, 13, sn, 0, NULL);
}

int mech_body_add_mass(bgr_model *m, int body_id, double dm)
{
    const char *w = "mech_body_add_mass";
    if (!m) return BG_ERR_ARGUMENT;
    bgr_element *el = bgr_element_get(m, body_id);
    if (!el || el->cls != &body_class)
        return bg_error_raise(bgr_model_error_mut(m), BG_ERR_ARGUMENT, w,
                              "element %d is not a body", body_id);
    if (bgr_nvars(m) > 0)
        return bg_error_raise(bgr_model_error_mut(m), BG_ERR_STATE, w,
                              "body %s/%s: the model is compiled: add masses before bgr_compile",
                              bgr_component_path(m, el->comp), el->name);
    if (!(dm >= 0) || !isfinite(dm))
        return bg_error_raise(bgr_model_error_mut(m), BG_ERR_ARGUMENT, w,
                              "body %s/%s: dm = %g, expected a finite number >= 0",
                              bgr_component_path(m, el->comp), el->name, dm);
    ((body *)el->params)->m += dm;
    return BG_OK;
}

int mech_body_var(const bgr_model *m, int body_id, char which)
{
    const bgr_element *el = bgr_element_get((bgr_model *)m, body_id);
    if (!el || el->cls != &body_class || !bgr_nvars(m)) return -1;
    switch (which) {
    case 'x':
        return el->state0;
    case 'v':
        return el->state0 + 3;
    case 'w':
        return el->state0 + 6;
    case 'q':
        return el->state0 + 9;
    default:
        return -1;
    }
}

int mech_body_set(bgr_model *m, int body_id, const double *x, const double *v, const double *w,
                  const double *q)
{
    double *y0 = bgr_y0(m);
    int i0 = mech_body_var(m, body_id, 'x');
    if (!y0 || i0 < 0)
        return bg_error_raise(bgr_model_error_mut(m), BG_ERR_ARGUMENT, "mech_body_set",
                              "element %d is not a body of a compiled model", body_id);
    static const double qi[4] = {1, 0, 0, 0};
    for (int i = 0; i < 3; i++) {
        y0[i0 + i] = x ? x[i] : 0.0;
        y0[i0 + 3 + i] = v ? v[i] : 0.0;
        y0[i0 + 6 + i] = w ? w[i] : 0.0;
    }
    for (int i = 0; i < 4; i++)
        y0[i0 + 9 + i] = q ? q[i] : qi[i];
    return BG_OK;
}

int mech_body_energy(const bgr_model *m, int body_id, const double *y, double *kinetic,
                     double *potential)
{
    const bgr_element *el = bgr_element_get((bgr_model *)m, body_id);
    if (!el || el->cls != &body_class || !bgr_nvars(m) || !y || !kinetic || !potential)
        return BG_ERR_ARGUMENT;
    const body *b = el->params;
    const double *x = y + el->state0, *v = x + 3, *w = x + 6;
    double Jw[3];
    mech_mv(b->J, w, Jw);
    *kinetic = 0.5 * b->m * mech_dot(v, v) + 0.5 * mech_dot(w, Jw);
    *potential = -b->m * mech_dot(b->g, x);
    return BG_OK;
}

int mech_set_nominal(bgr_model *m, int id, double force, double moment, double length)
{
    const char *w = "mech_set_nominal";
    bgr_element *el = bgr_element_get(m, id);
    mech_scales *sc = mech_body_scales_(el);
    if (!sc) sc = mech_parts_scales_(el);
    if (!sc) sc = mech_axial_scales_(el);
    if (!sc) sc = mech_beam_scales_(el);
    if (!m) return BG_ERR_ARGUMENT;
    if (!sc)
        return bg_error_raise(bgr_model_error_mut(m), BG_ERR_ARGUMENT, w,
                              "element %d is not a mechanical element (body, point mass, support, "
                              "joint, axial element or beam)",
                              id);
    if (bgr_nvars(m) > 0)
        return bg_error_raise(bgr_model_error_mut(m), BG_ERR_STATE, w,
                              "element %s/%s: the model is compiled: state nominal scales before "
                              "bgr_compile",
                              bgr_component_path(m, el->comp), el->name);
    const double v[3] = {force, moment, length};
    for (int i = 0; i < 3; i++)
        if (!(v[i] >= 0) || !isfinite(v[i]))
            return bg_error_raise(bgr_model_error_mut(m), BG_ERR_ARGUMENT, w,
                                  "element %s/%s: the nominal %s %g must be finite and >= 0 (0: "
                                  "not stated)",
                                  bgr_component_path(m, el->comp), el->name,
                                  i == 0 ? "force" : i == 1 ? "moment" : "length", v[i]);
    if (force > 0) sc->force = force;
    if (moment > 0) sc->moment = moment;
    if (length > 0) sc->length = length;
    return BG_OK;
}
