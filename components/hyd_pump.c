/* Variable-displacement pump (equations in hyd_pump.h). */
#include "hyd_pump.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "cmp_internal.h"

typedef struct pump {
    double Dp, Cl;
    double wc;           /* actuator corner frequency 2 pi fc (rad/s); 0: none */
    double p_nom, w_nom; /* stated nominal pressure and drive speed (0: none) */
    bgr_ref cmd;
    /* variable ids and orientations, fixed at declaration */
    int x, T, w, pa, qa, pb, qb;
    int s; /* swash plate position (state) with an actuator, else x */
    int sw, sa, sb;
} pump;

static int pump_declare(bgr_element *el, bgr_model *m)
{
    static const char *const lab[4] = {"torque", "flow", "continuity", "servo"};
    pump *q = el->params;
    q->T = bgr_ev(el, m, 0, 0);
    q->w = bgr_fv(el, m, 0, 0);
    q->pa = bgr_ev(el, m, 1, 0);
    q->qa = bgr_fv(el, m, 1, 0);
    q->pb = bgr_ev(el, m, 2, 0);
    q->qb = bgr_fv(el, m, 2, 0);
    q->sw = el->sign[0];
    q->sa = el->sign[1];
    q->sb = el->sign[2];
    q->x = bgr_ref_var(m, q->cmd);
    if (q->x < 0)
        return bg_error_raise(bgr_model_error_mut(m), BG_ERR_ARGUMENT, "bgr_compile",
                              "pump %s: its displacement command refers to no unknown", el->name);
    q->s = q->wc > 0 ? bgr_sv(el, 0) : q->x;
    int st = bgr_declare_equations(el, m, q->wc > 0 ? 4 : 3, lab);
    if (st) return st;
    CMP_DEP(el, m, 0, q->T, 0);
    CMP_DEP(el, m, 0, q->pa, 0);
    CMP_DEP(el, m, 0, q->pb, 0);
    CMP_DEP(el, m, 0, q->s, 0);
    CMP_DEP(el, m, 1, q->qb, 0);
    CMP_DEP(el, m, 1, q->w, 0);
    CMP_DEP(el, m, 1, q->pa, 0);
    CMP_DEP(el, m, 1, q->pb, 0);
    CMP_DEP(el, m, 1, q->s, 0);
    CMP_DEP(el, m, 2, q->qa, 0);
    CMP_DEP(el, m, 2, q->qb, 0);
    if (q->wc > 0) {
        CMP_DEP(el, m, 3, q->s, 1);
        CMP_DEP(el, m, 3, q->s, 0);
        CMP_DEP(el, m, 3, q->x, 0);
    }
    /* Stated scales: the pressure for both ports; the torque the full displacement draws at
     * that pressure difference, Dp p / (2 pi); the drive speed; the full displacement times the
     * drive speed, Dp w / (2 pi), for the flows (the most the pump delivers). The command x is a
     * fraction of the full displacement: 1 is its scale already. */
    double k = q->Dp / CMP_TWO_PI;
    CMP_NOM(el, m, q->pa, q->p_nom);
    CMP_NOM(el, m, q->pb, q->p_nom);
    CMP_NOM(el, m, q->T, k * q->p_nom);
    CMP_NOM(el, m, q->w, q->w_nom);
    CMP_NOM(el, m, q->qa, k * q->w_nom);
    CMP_NOM(el, m, q->qb, k * q->w_nom);
    return BG_OK;
}

static int pump_residual(const bgr_element *el, double t, const double *y, const double *yp,
                         double *F)
{
    (void)t;
    const pump *q = el->params;
    double k = q->Dp / CMP_TWO_PI, x = y[q->s], dp = y[q->pb] - y[q->pa];
    double w = q->sw * y[q->w], qin = q->sa * y[q->qa], qout = -q->sb * y[q->qb];
    F[0] = y[q->T] - x * k * dp;
    F[1] = qout - x * k * w + q->Cl * dp;
    F[2] = qin - qout;
    if (q->wc > 0) F[3] = yp[q->s] - q->wc * (y[q->x] - y[q->s]);
    return 0;
}

static int pump_jacobian(const bgr_element *el, double t, const double *y, const double *yp,
                         double *v)
{
    (void)t, (void)yp;
    const pump *q = el->params;
    double k = q->Dp / CMP_TWO_PI, x = y[q->s], dp = y[q->pb] - y[q->pa];
    double w = q->sw * y[q->w];
    int n = 0;
    v[n++] = 1.0;            /* dF0/dT */
    v[n++] = x * k;          /* dF0/dp_a */
    v[n++] = -x * k;         /* dF0/dp_b */
    v[n++] = -k * dp;        /* dF0/dx */
    v[n++] = -q->sb;         /* dF1/dq_b */
    v[n++] = -x * k * q->sw; /* dF1/dw */
    v[n++] = -q->Cl;         /* dF1/dp_a */
    v[n++] = q->Cl;          /* dF1/dp_b */
    v[n++] = -k * w;         /* dF1/dx */
    v[n++] = q->sa;          /* dF2/dq_a */
    v[n++] = q->sb;          /* dF2/dq_b */
    if (q->wc > 0) {
        v[n++] = 1.0;    /* dF3/ds' */
        v[n++] = q->wc;  /* dF3/ds */
        v[n++] = -q->wc; /* dF3/dx */
    }
    return 0;
}

static const char *vn(const bgr_model *m, int v)
{
    const char *s = bgr_var_name(m, v);
    return s ? s : "?";
}

static void pump_describe(const bgr_element *el, const bgr_model *m, int k, char *buf, size_t n)
{
    const pump *q = el->params;
    const char *sa = q->sa > 0 ? "" : "-", *sb = q->sb > 0 ? "-" : "", *sw = q->sw > 0 ? "" : "-";
    if (k == 0)
        snprintf(buf, n, "%s = %s * %g/(2 pi) * (%s - %s)", vn(m, q->T), vn(m, q->s), q->Dp,
                 vn(m, q->pb), vn(m, q->pa));
    else if (k == 1)
        snprintf(buf, n, "%s%s = %s * %g/(2 pi) * %s%s - %g * (%s - %s)", sb, vn(m, q->qb),
                 vn(m, q->s), q->Dp, sw, vn(m, q->w), q->Cl, vn(m, q->pb), vn(m, q->pa));
    else if (k == 2)
        snprintf(buf, n, "%s%s = %s%s", sa, vn(m, q->qa), sb, vn(m, q->qb));
    else
        snprintf(buf, n, "%s' = %g * (%s - %s)", vn(m, q->s), q->wc, vn(m, q->x), vn(m, q->s));
}

const bgr_element_class hyd_class_pump = {.type = "pump",
                                          .declare = pump_declare,
                                          .residual = pump_residual,
                                          .jacobian = pump_jacobian,
                                          .describe = pump_describe,
                                          .destroy = free};

static int pump_add(bgr_model *m, bgr_comp c, const char *name, double Dp, double Cl,
                    bgr_ref command, double fc, const char *where)
{
    if (bgr_check_value(m, c, name, where, "Dp", Dp, BGR_POSITIVE) ||
        bgr_check_value(m, c, name, where, "Cl", Cl, BGR_NONNEGATIVE) ||
        bgr_check_value(m, c, name, where, "fc", fc, BGR_NONNEGATIVE))
        return BG_ERR_ARGUMENT;
    if (!isfinite(CMP_TWO_PI * fc))
        return bgr_refuse(m, c, name, where, "fc = %g, expected a finite 2 pi fc", fc);
    pump *q = calloc(1, sizeof *q);
    if (!q) return bg_error_raise(bgr_model_error_mut(m), BG_ERR_MEMORY, where, "out of memory");
    q->Dp = Dp;
    q->Cl = Cl;
    q->wc = CMP_TWO_PI * fc;
    q->cmd = command;
    static const int dims[3] = {1, 1, 1};
    static const char *const sn[1] = {"swash"};
    return bgr_element_add(m, c, name, &hyd_class_pump, q, 3, dims, fc > 0 ? 1 : 0, sn, 0, NULL);
}

int hyd_pump(bgr_model *m, bgr_comp c, const char *name, double Dp, double Cl, bgr_ref command)
{
    return pump_add(m, c, name, Dp, Cl, command, 0.0, "hyd_pump");
}

int hyd_pump_servo(bgr_model *m, bgr_comp c, const char *name, double Dp, double Cl,
                   bgr_ref command, double fc)
{
    return pump_add(m, c, name, Dp, Cl, command, fc, "hyd_pump_servo");
}

int hyd_pump_set_nominal(bgr_model *m, int id, double pressure, double speed)
{
    double v[2] = {pressure, speed};
    void *q = NULL;
    int st = cmp_check_scales(m, id, &hyd_class_pump, "a hydraulic pump", "hyd_pump_set_nominal",
                              v, 2, &q);
    if (st != BG_OK) return st;
    ((pump *)q)->p_nom = pressure;
    ((pump *)q)->w_nom = speed;
    return BG_OK;
}
