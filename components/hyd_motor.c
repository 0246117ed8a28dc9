/* Hydraulic motor (equations in hyd_motor.h). */
#include "hyd_motor.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "cmp_internal.h"

typedef struct motor {
    double D, Cl, b;
    double p_nom, w_nom; /* stated nominal pressure and shaft speed (0: none) */
    int pa, qa, pb, qb, T, w;
    int sa, sb, sw;
} motor;

static int motor_declare(bgr_element *el, bgr_model *m)
{
    static const char *const lab[3] = {"flow", "continuity", "torque"};
    motor *q = el->params;
    q->pa = bgr_ev(el, m, 0, 0);
    q->qa = bgr_fv(el, m, 0, 0);
    q->pb = bgr_ev(el, m, 1, 0);
    q->qb = bgr_fv(el, m, 1, 0);
    q->T = bgr_ev(el, m, 2, 0);
    q->w = bgr_fv(el, m, 2, 0);
    q->sa = el->sign[0];
    q->sb = el->sign[1];
    q->sw = el->sign[2];
    int st = bgr_declare_equations(el, m, 3, lab);
    if (st) return st;
    CMP_DEP(el, m, 0, q->qa, 0);
    CMP_DEP(el, m, 0, q->w, 0);
    CMP_DEP(el, m, 0, q->pa, 0);
    CMP_DEP(el, m, 0, q->pb, 0);
    CMP_DEP(el, m, 1, q->qb, 0);
    CMP_DEP(el, m, 1, q->qa, 0);
    CMP_DEP(el, m, 2, q->T, 0);
    CMP_DEP(el, m, 2, q->pa, 0);
    CMP_DEP(el, m, 2, q->pb, 0);
    CMP_DEP(el, m, 2, q->w, 0);
    /* Stated scales: the pressure for both ports; the torque the displacement gives at that
     * pressure difference, D p / (2 pi); the shaft speed; the flow the displacement swallows at
     * that speed, D w / (2 pi) (the leakage is a small part of it). */
    double k = q->D / CMP_TWO_PI;
    CMP_NOM(el, m, q->pa, q->p_nom);
    CMP_NOM(el, m, q->pb, q->p_nom);
    CMP_NOM(el, m, q->T, k * q->p_nom);
    CMP_NOM(el, m, q->w, q->w_nom);
    CMP_NOM(el, m, q->qa, k * q->w_nom);
    CMP_NOM(el, m, q->qb, k * q->w_nom);
    return BG_OK;
}

static int motor_residual(const bgr_element *el, double t, const double *y, const double *yp,
                          double *F)
{
    (void)t, (void)yp;
    const motor *q = el->params;
    double k = q->D / CMP_TWO_PI, dp = y[q->pa] - y[q->pb];
    double qin = q->sa * y[q->qa], qout = -q->sb * y[q->qb], w = -q->sw * y[q->w];
    F[0] = qin - k * w - q->Cl * dp;
    F[1] = qout - qin;
    F[2] = y[q->T] - k * dp + q->b * w;
    return 0;
}

static int motor_jacobian(const bgr_element *el, double t, const double *y, const double *yp,
                          double *v)
{
    (void)t, (void)y, (void)yp;
    const motor *q = el->params;
    double k = q->D / CMP_TWO_PI;
    int n = 0;
    v[n++] = q->sa;         /* dF0/dq_a */
    v[n++] = k * q->sw;     /* dF0/dw (w_out = -s_w f) */
    v[n++] = -q->Cl;        /* dF0/dp_a */
    v[n++] = q->Cl;         /* dF0/dp_b */
    v[n++] = -q->sb;        /* dF1/dq_b */
    v[n++] = -q->sa;        /* dF1/dq_a */
    v[n++] = 1.0;           /* dF2/dT */
    v[n++] = -k;            /* dF2/dp_a */
    v[n++] = k;             /* dF2/dp_b */
    v[n++] = -q->b * q->sw; /* dF2/dw */
    return 0;
}

static const char *vn(const bgr_model *m, int v)
{
    const char *s = bgr_var_name(m, v);
    return s ? s : "?";
}

static void motor_describe(const bgr_element *el, const bgr_model *m, int k, char *buf, size_t n)
{
    const motor *q = el->params;
    const char *sa = q->sa > 0 ? "" : "-", *sb = q->sb > 0 ? "-" : "", *sw = q->sw > 0 ? "-" : "";
    if (k == 0)
        snprintf(buf, n, "%s%s = %g/(2 pi) * %s%s + %g * (%s - %s)", sa, vn(m, q->qa), q->D, sw,
                 vn(m, q->w), q->Cl, vn(m, q->pa), vn(m, q->pb));
    else if (k == 1)
        snprintf(buf, n, "%s%s = %s%s", sb, vn(m, q->qb), sa, vn(m, q->qa));
    else
        snprintf(buf, n, "%s = %g/(2 pi) * (%s - %s) - %g * %s%s", vn(m, q->T), q->D, vn(m, q->pa),
                 vn(m, q->pb), q->b, sw, vn(m, q->w));
}

const bgr_element_class hyd_class_motor = {.type = "motor",
                                           .declare = motor_declare,
                                           .residual = motor_residual,
                                           .jacobian = motor_jacobian,
                                           .describe = motor_describe,
                                           .destroy = free};

int hyd_motor(bgr_model *m, bgr_comp c, const char *name, double D, double Cl, double b)
{
    const char *w = "hyd_motor";
    if (bgr_check_value(m, c, name, w, "D", D, BGR_POSITIVE) ||
        bgr_check_value(m, c, name, w, "Cl", Cl, BGR_NONNEGATIVE) ||
        bgr_check_value(m, c, name, w, "b", b, BGR_NONNEGATIVE))
        return BG_ERR_ARGUMENT;
    motor *q = calloc(1, sizeof *q);
    if (!q)
        return bg_error_raise(bgr_model_error_mut(m), BG_ERR_MEMORY, "hyd_motor", "out of memory");
    q->D = D;
    q->Cl = Cl;
    q->b = b;
    static const int dims[3] = {1, 1, 1};
    return bgr_element_add(m, c, name, &hyd_class_motor, q, 3, dims, 0, NULL, 0, NULL);
}

int hyd_motor_set_nominal(bgr_model *m, int id, double pressure, double speed)
{
    double v[2] = {pressure, speed};
    void *q = NULL;
    int st = cmp_check_scales(m, id, &hyd_class_motor, "a hydraulic motor",
                              "hyd_motor_set_nominal", v, 2, &q);
    if (st != BG_OK) return st;
    ((motor *)q)->p_nom = pressure;
    ((motor *)q)->w_nom = speed;
    return BG_OK;
}
