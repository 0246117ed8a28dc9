/* Rotation sensor of a rigid body (equations in mech_sensor.h). */
#include "mech_sensor.h"

#include <stdlib.h>
#include <string.h>

#include "mech_util.h"

typedef struct sensor {
    int body;
    double a[3];
    int th, wa, w, q; /* ids: angle, rate output, body angular velocity, body quaternion */
} sensor;

static void sensor_free(void *p)
{
    free(p);
}

/* s = (R w).a and its partial derivatives with respect to w (3) and q (4) */
static double rate_about(const sensor *p, const double *y, double *dw, double *dq)
{
    double R[9], dR[36], Rw[3];
    mech_quat_R(y + p->q, R, dR);
    mech_mv(R, y + p->w, Rw);
    for (int c = 0; c < 3; c++) /* d/dw_c = (R e_c).a = column c of R dotted with a */
        dw[c] = R[3 * c] * p->a[0] + R[3 * c + 1] * p->a[1] + R[3 * c + 2] * p->a[2];
    for (int j = 0; j < 4; j++) {
        double t[3];
        mech_mv(dR + 9 * j, y + p->w, t);
        dq[j] = mech_dot(t, p->a);
    }
    return mech_dot(Rw, p->a);
}

static void sensor_partials(const bgr_element *el, const double *y, mech_emit *E)
{
    const sensor *p = el->params;
    double dw[3], dq[4];
    rate_about(p, y, dw, dq);
    for (int r = 0; r < 2; r++) {
        if (r == 0)
            mech_dep(E, r, p->th, 1, 1.0);
        else
            mech_dep(E, r, p->wa, 0, 1.0);
        for (int c = 0; c < 3; c++)
            mech_dep(E, r, p->w + c, 0, -dw[c]);
        for (int j = 0; j < 4; j++)
            mech_dep(E, r, p->q + j, 0, -dq[j]);
    }
}

static int sensor_declare(bgr_element *el, bgr_model *m)
{
    sensor *p = el->params;
    bgr_ref rw = {BGR_STATE, p->body, 6}, rq = {BGR_STATE, p->body, 9};
    bgr_element *b = bgr_element_get(m, p->body);
    if (!b || b->nstates != 13 || strcmp(b->cls->type, "body"))
        return bg_error_raise(bgr_model_error_mut(m), BG_ERR_ARGUMENT, "bgr_compile",
                              "sensor %s/%s: element %d is not a rigid body",
                              bgr_component_path(m, el->comp), el->name, p->body);
    p->w = bgr_ref_var(m, rw);
    p->q = bgr_ref_var(m, rq);
    p->th = bgr_sv(el, 0);
    p->wa = bgr_av(el, 0);
    static const char *const lab[2] = {"angle", "rate"};
    int st = bgr_declare_equations(el, m, 2, lab);
    if (st != BG_OK) return st;
    double *zero = calloc((size_t)bgr_nvars(m) + 1, sizeof *zero);
    if (!zero)
        return bg_error_raise(bgr_model_error_mut(m), BG_ERR_MEMORY, "bgr_compile",
                              "out of memory");
    zero[p->q] = 1.0;
    mech_emit E = {1, el, m, NULL, 0, BG_OK};
    sensor_partials(el, zero, &E);
    free(zero);
    return E.status;
}

static int sensor_residual(const bgr_element *el, double t, const double *y, const double *yp,
                           double *F)
{
    (void)t;
    const sensor *p = el->params;
    double dw[3], dq[4], s = rate_about(p, y, dw, dq);
    F[0] = yp[p->th] - s;
    F[1] = y[p->wa] - s;
    return 0;
}

static int sensor_jacobian(const bgr_element *el, double t, const double *y, const double *yp,
                           double *v)
{
    (void)t, (void)yp;
    mech_emit E = {0, NULL, NULL, v, 0, BG_OK};
    sensor_partials(el, y, &E);
    return 0;
}

static const bgr_element_class sensor_class = {.type = "rotation sensor",
                                               .declare = sensor_declare,
                                               .residual = sensor_residual,
                                               .jacobian = sensor_jacobian,
                                               .destroy = sensor_free};

int mech_rotation_sensor(bgr_model *m, bgr_comp c, const char *name, int body, const double *axis)
{
    const char *w = "mech_rotation_sensor";
    if (!axis) return bgr_refuse(m, c, name, w, "the axis is NULL");
    if (bgr_check_values(m, c, name, w, "axis", axis, 3, BGR_FINITE)) return BG_ERR_ARGUMENT;
    double n = sqrt(mech_dot(axis, axis));
    if (!(n > 0) || !isfinite(n))
        return bgr_refuse(m, c, name, w,
                          "axis = (%g, %g, %g) has length %g, expected a nonzero finite axis",
                          axis[0], axis[1], axis[2], n);
    if (body < 0)
        return bgr_refuse(m, c, name, w, "body = %d, expected a body's element id", body);
    sensor *p = calloc(1, sizeof *p);
    if (!p)
        return bg_error_raise(bgr_model_error_mut(m), BG_ERR_MEMORY, "mech_rotation_sensor",
                              "out of memory");
    p->body = body;
    for (int i = 0; i < 3; i++)
        p->a[i] = axis[i] / n;
    static const char *const sn[1] = {"angle"}, *const an[1] = {"rate"};
    return bgr_element_add(m, c, name, &sensor_class, p, 0, NULL, 1, sn, 1, an);
}
