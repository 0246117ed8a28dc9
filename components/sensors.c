/* Sensors on a rotating inertia (equations in sensors.h). */
#include "sensors.h"

#include <stdio.h>
#include <stdlib.h>

#include "cmp_internal.h"
#include "rot_inertia.h"

typedef struct sensor {
    int inertia;
    rot_quantity q;
    double J;
    int z, src; /* the signal, the variable it reads */
} sensor;

static const char *const qname[3] = {"angle", "velocity", "acceleration"};

static int sensor_declare(bgr_element *el, bgr_model *m)
{
    static const char *const lab[1] = {"signal"};
    sensor *q = el->params;
    bgr_element *in = bgr_element_get(m, q->inertia);
    q->J = rot_inertia_moment(in);
    if (!(q->J > 0))
        return bg_error_raise(bgr_model_error_mut(m), BG_ERR_ARGUMENT, "bgr_compile",
                              "sensor %s: element %d is not a rot_inertia", el->name, q->inertia);
    q->z = bgr_av(el, 0);
    if (q->q == ROT_ANGLE)
        q->src = bgr_sv(in, 1);
    else if (q->q == ROT_VELOCITY)
        q->src = bgr_sv(in, 0);
    else
        q->src = bgr_ev(in, m, 0, 0);
    int st = bgr_declare_equations(el, m, 1, lab);
    if (st) return st;
    CMP_DEP(el, m, 0, q->z, 0);
    CMP_DEP(el, m, 0, q->src, 0);
    return BG_OK;
}

static int sensor_residual(const bgr_element *el, double t, const double *y, const double *yp,
                           double *F)
{
    (void)t, (void)yp;
    const sensor *q = el->params;
    double g = q->q == ROT_ANGLE ? 1.0 : 1.0 / q->J;
    F[0] = y[q->z] - g * y[q->src];
    return 0;
}

static int sensor_jacobian(const bgr_element *el, double t, const double *y, const double *yp,
                           double *v)
{
    (void)t, (void)y, (void)yp;
    const sensor *q = el->params;
    v[0] = 1.0;
    v[1] = q->q == ROT_ANGLE ? -1.0 : -1.0 / q->J;
    return 0;
}

static void sensor_describe(const bgr_element *el, const bgr_model *m, int k, char *buf, size_t n)
{
    (void)k;
    const sensor *q = el->params;
    const char *z = bgr_var_name(m, q->z), *s = bgr_var_name(m, q->src);
    if (q->q == ROT_ANGLE)
        snprintf(buf, n, "%s = %s", z ? z : "z", s ? s : "theta");
    else
        snprintf(buf, n, "%s = %s / %g", z ? z : "z", s ? s : "?", q->J);
}

const bgr_element_class rot_class_sensor = {.type = "sensor",
                                            .declare = sensor_declare,
                                            .residual = sensor_residual,
                                            .jacobian = sensor_jacobian,
                                            .describe = sensor_describe,
                                            .destroy = free};

int rot_sensor(bgr_model *m, bgr_comp c, const char *name, int inertia, rot_quantity q)
{
    if (q != ROT_ANGLE && q != ROT_VELOCITY && q != ROT_ACCELERATION)
        return bgr_refuse(m, c, name, "rot_sensor",
                          "quantity q = %d, expected ROT_ANGLE, ROT_VELOCITY or ROT_ACCELERATION",
                          (int)q);
    if (!(rot_inertia_moment(bgr_element_get(m, inertia)) > 0))
        return bgr_refuse(m, c, name, "rot_sensor",
                          "inertia = %d, expected the id of a rot_inertia element", inertia);
    sensor *p = calloc(1, sizeof *p);
    if (!p)
        return bg_error_raise(bgr_model_error_mut(m), BG_ERR_MEMORY, "rot_sensor", "out of memory");
    p->inertia = inertia;
    p->q = q;
    const char *an[1] = {qname[q]};
    return bgr_element_add(m, c, name, &rot_class_sensor, p, 0, NULL, 0, NULL, 1, an);
}
