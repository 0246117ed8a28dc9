/* PID controller (equations in ctl_pid.h). */
#include "ctl_pid.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "cmp_internal.h"

typedef struct pid {
    ctl_pid_spec sp;
    int I, u, r, y, rd, yd; /* variable ids (rd, yd: -1 when absent) */
    int z;                  /* filter state, -1 without a derivative filter */
    int f;                  /* feedforward, -1 without */
    double b, c;            /* setpoint weights (1, 1 unweighted) */
} pid;

/* The unknowns v depends on, in the order of the Jacobian's entries after the first one of
 * each equation: r, y, I, then r', y', z, f where present (r', y' only with kd != 0). */
static int pid_inputs(const pid *q, int *var)
{
    int n = 0;
    var[n++] = q->r;
    var[n++] = q->y;
    var[n++] = q->I;
    if (q->rd >= 0 && q->sp.kd != 0) var[n++] = q->rd;
    if (q->yd >= 0 && q->sp.kd != 0) var[n++] = q->yd;
    if (q->z >= 0) var[n++] = q->z;
    if (q->f >= 0) var[n++] = q->f;
    return n;
}

static int pid_declare(bgr_element *el, bgr_model *m)
{
    static const char *const lab[3] = {"integral", "output", "filter"};
    pid *q = el->params;
    q->I = bgr_sv(el, 0);
    q->z = q->sp.derivative_filter > 0 ? bgr_sv(el, 1) : -1;
    q->u = bgr_av(el, 0);
    q->r = bgr_ref_var(m, q->sp.reference);
    q->y = bgr_ref_var(m, q->sp.measurement);
    q->rd = q->sp.use_reference_rate ? bgr_ref_var(m, q->sp.reference_rate) : -1;
    q->yd = q->sp.use_measurement_rate ? bgr_ref_var(m, q->sp.measurement_rate) : -1;
    q->f = q->sp.use_feedforward ? bgr_ref_var(m, q->sp.feedforward) : -1;
    q->b = q->sp.weighted ? q->sp.b : 1.0;
    q->c = q->sp.weighted ? q->sp.c : 1.0;
    if (q->r < 0 || q->y < 0 || (q->sp.use_reference_rate && q->rd < 0) ||
        (q->sp.use_measurement_rate && q->yd < 0) || (q->sp.use_feedforward && q->f < 0))
        return bg_error_raise(bgr_model_error_mut(m), BG_ERR_ARGUMENT, "bgr_compile",
                              "controller %s: its %s refers to no unknown", el->name,
                              q->r < 0                                ? "reference"
                              : q->y < 0                              ? "measurement"
                              : q->sp.use_reference_rate && q->rd < 0 ? "reference rate"
                              : q->sp.use_measurement_rate && q->yd < 0 ? "measurement rate"
                                                                        : "feedforward");
    int st = bgr_declare_equations(el, m, q->z >= 0 ? 3 : 2, lab);
    if (st) return st;
    int var[8], n = pid_inputs(q, var);
    CMP_DEP(el, m, 0, q->I, 1);
    if (q->sp.tracking_time > 0) {
        CMP_DEP(el, m, 0, q->u, 0);
        for (int k = 0; k < n; k++) CMP_DEP(el, m, 0, var[k], 0);
    } else {
        CMP_DEP(el, m, 0, q->r, 0);
        CMP_DEP(el, m, 0, q->y, 0);
    }
    CMP_DEP(el, m, 1, q->u, 0);
    for (int k = 0; k < n; k++) CMP_DEP(el, m, 1, var[k], 0);
    if (q->z >= 0) {
        CMP_DEP(el, m, 2, q->z, 1);
        CMP_DEP(el, m, 2, q->y, 0);
        CMP_DEP(el, m, 2, q->z, 0);
    }
    /* With limits, the output range max(|u_min|, |u_max|) is the output's scale, and that range
     * over Ki the integral's (the integral that alone drives the output to its limit). Without
     * limits the gains give no scale of the output (nor does anything give one of the filter
     * state, which follows the measurement): nothing declared. */
    if (q->sp.limit) {
        double un = fmax(fabs(q->sp.out_min), fabs(q->sp.out_max));
        CMP_NOM(el, m, q->u, un);
        if (q->sp.ki != 0) CMP_NOM(el, m, q->I, un / fabs(q->sp.ki));
    }
    return BG_OK;
}

/* The unlimited law v, its gradient dv (in pid_inputs' order, may be NULL) and the slope
 * g = dsat/dv of the limit at v. */
static double pid_law(const pid *q, const double *y, double *dv, double *g)
{
    const ctl_pid_spec *s = &q->sp;
    double v = s->kp * (q->b * y[q->r] - y[q->y]) + s->ki * y[q->I];
    double dy = -s->kp;
    if (s->kd != 0) {
        double ydot = q->z >= 0    ? (y[q->y] - y[q->z]) / s->derivative_filter
                      : q->yd >= 0 ? y[q->yd]
                                   : 0.0;
        v += s->kd * ((q->rd >= 0 ? q->c * y[q->rd] : 0.0) - ydot);
        if (q->z >= 0) dy -= s->kd / s->derivative_filter;
    }
    if (q->f >= 0) v += y[q->f];
    if (dv) {
        int n = 0;
        dv[n++] = s->kp * q->b;
        dv[n++] = dy;
        dv[n++] = s->ki;
        if (q->rd >= 0 && s->kd != 0) dv[n++] = s->kd * q->c;
        if (q->yd >= 0 && s->kd != 0) dv[n++] = -s->kd;
        if (q->z >= 0) dv[n++] = s->kd / s->derivative_filter;
        if (q->f >= 0) dv[n++] = 1.0;
    }
    if (!s->limit) {
        *g = 1.0;
        return v;
    }
    return cmp_clamp(v, s->out_min, s->out_max, s->smoothing, g);
}

/* the unlimited v itself (pid_law returns sat(v)) */
static double pid_unlimited(const pid *q, const double *y)
{
    ctl_pid_spec s = q->sp;
    pid p = *q;
    double g;
    s.limit = 0;
    p.sp = s;
    return pid_law(&p, y, NULL, &g);
}

static int pid_residual(const bgr_element *el, double t, const double *y, const double *yp,
                        double *F)
{
    (void)t;
    const pid *q = el->params;
    double g;
    F[0] = yp[q->I] - (y[q->r] - y[q->y]);
    if (q->sp.tracking_time > 0)
        F[0] -= (y[q->u] - pid_unlimited(q, y)) / (q->sp.ki * q->sp.tracking_time);
    F[1] = y[q->u] - pid_law(q, y, NULL, &g);
    if (q->z >= 0) F[2] = yp[q->z] - (y[q->y] - y[q->z]) / q->sp.derivative_filter;
    return 0;
}

static int pid_jacobian(const bgr_element *el, double t, const double *y, const double *yp,
                        double *v)
{
    (void)t, (void)yp;
    const pid *q = el->params;
    const ctl_pid_spec *s = &q->sp;
    double g, dv[8];
    int var[8], nin = pid_inputs(q, var);
    pid_law(q, y, dv, &g);
    int n = 0;
    v[n++] = 1.0;
    if (s->tracking_time > 0) {
        double w = 1.0 / (s->ki * s->tracking_time);
        v[n++] = -w;
        for (int k = 0; k < nin; k++)
            v[n++] = w * dv[k] + (var[k] == q->r ? -1.0 : var[k] == q->y ? 1.0 : 0.0);
    } else {
        v[n++] = -1.0;
        v[n++] = 1.0;
    }
    v[n++] = 1.0;
    for (int k = 0; k < nin; k++) v[n++] = -g * dv[k];
    if (q->z >= 0) {
        double tau = s->derivative_filter;
        v[n++] = 1.0;
        v[n++] = -1.0 / tau;
        v[n++] = 1.0 / tau;
    }
    return 0;
}

static const char *vname(const bgr_model *m, int v, const char *none)
{
    const char *s = v >= 0 ? bgr_var_name(m, v) : NULL;
    return s ? s : none;
}

static void pid_describe(const bgr_element *el, const bgr_model *m, int k, char *buf, size_t n)
{
    const pid *q = el->params;
    const ctl_pid_spec *s = &q->sp;
    const char *r = vname(m, q->r, "r"), *y = vname(m, q->y, "y"), *I = vname(m, q->I, "I");
    if (k == 0 && s->tracking_time > 0)
        snprintf(buf, n, "%s' = %s - %s + (%s - v) / (%g * %g)", I, r, y, vname(m, q->u, "u"),
                 s->ki, s->tracking_time);
    else if (k == 0)
        snprintf(buf, n, "%s' = %s - %s", I, r, y);
    else if (k == 2)
        snprintf(buf, n, "%s' = (%s - %s) / %g", vname(m, q->z, "z"), y, vname(m, q->z, "z"),
                 s->derivative_filter);
    else if (q->z >= 0)
        snprintf(buf, n, "%s = %s(%g * (%s - %s) + %g * (%s - (%s - %s) / %g) + %g * %s)",
                 vname(m, q->u, "u"), s->limit ? "sat" : "", s->kp, r, y, s->kd,
                 vname(m, q->rd, "0"), y, vname(m, q->z, "z"), s->derivative_filter, s->ki, I);
    else
        snprintf(buf, n, "%s = %s(%g * (%s - %s) + %g * (%s - %s) + %g * %s)", vname(m, q->u, "u"),
                 s->limit ? "sat" : "", s->kp, r, y, s->kd, vname(m, q->rd, "0"),
                 vname(m, q->yd, "0"), s->ki, I);
}

/* The limiter's regime: saturated low or high (slope near 0), in between, in range (slope 1);
 * without a limit always in range. */
static int pid_regime(const bgr_element *el, const double *y)
{
    const pid *q = el->params;
    double g;
    pid_law(q, y, NULL, &g);
    return cmp_regime(g);
}

const bgr_element_class ctl_class_pid = {.type = "PID",
                                         .declare = pid_declare,
                                         .residual = pid_residual,
                                         .jacobian = pid_jacobian,
                                         .describe = pid_describe,
                                         .destroy = free,
                                         .regime = pid_regime};

int ctl_pid(bgr_model *m, bgr_comp c, const char *name, const ctl_pid_spec *spec)
{
    const char *w = "ctl_pid";
    if (!spec) return bgr_refuse(m, c, name, w, "no specification (spec is NULL)");
    if (bgr_check_value(m, c, name, w, "kp", spec->kp, BGR_FINITE) ||
        bgr_check_value(m, c, name, w, "ki", spec->ki, BGR_FINITE) ||
        bgr_check_value(m, c, name, w, "kd", spec->kd, BGR_FINITE) ||
        bgr_check_value(m, c, name, w, "derivative_filter", spec->derivative_filter,
                        BGR_NONNEGATIVE))
        return BG_ERR_ARGUMENT;
    double tau = spec->derivative_filter;
    if (tau > 0 && !isfinite(1.0 / tau))
        return bgr_refuse(m, c, name, w,
                          "derivative_filter = %g, expected 0 or a finite number > 0 with a "
                          "finite 1 / derivative_filter",
                          tau);
    if (tau > 0 && spec->use_measurement_rate)
        return bgr_refuse(m, c, name, w,
                          "use_measurement_rate = %d with derivative_filter = %g: give the "
                          "measured rate or a derivative filter, not both",
                          spec->use_measurement_rate, tau);
    if (spec->kd != 0 && !spec->use_measurement_rate && !(tau > 0))
        return bgr_refuse(m, c, name, w,
                          "kd = %g needs the measured rate (use_measurement_rate, e.g. a "
                          "rot_sensor of the acceleration) or a derivative filter",
                          spec->kd);
    if (spec->limit) {
        if (bgr_check_value(m, c, name, w, "out_min", spec->out_min, BGR_FINITE) ||
            bgr_check_value(m, c, name, w, "out_max", spec->out_max, BGR_FINITE) ||
            bgr_check_value(m, c, name, w, "smoothing", spec->smoothing, BGR_POSITIVE))
            return BG_ERR_ARGUMENT;
        if (!(spec->out_max > spec->out_min))
            return bgr_refuse(m, c, name, w, "out_max = %g, expected > out_min = %g",
                              spec->out_max, spec->out_min);
    }
    if (spec->weighted && (bgr_check_value(m, c, name, w, "b", spec->b, BGR_FINITE) ||
                           bgr_check_value(m, c, name, w, "c", spec->c, BGR_FINITE)))
        return BG_ERR_ARGUMENT;
    if (bgr_check_value(m, c, name, w, "tracking_time", spec->tracking_time, BGR_NONNEGATIVE))
        return BG_ERR_ARGUMENT;
    if (spec->tracking_time > 0 && (!spec->limit || spec->ki == 0))
        return bgr_refuse(m, c, name, w,
                          "tracking_time = %g (anti-windup) needs the output limits and ki != 0",
                          spec->tracking_time);
    pid *q = calloc(1, sizeof *q);
    if (!q)
        return bg_error_raise(bgr_model_error_mut(m), BG_ERR_MEMORY, "ctl_pid", "out of memory");
    q->sp = *spec;
    static const char *const sn[2] = {"integral", "filter"}, *const an[1] = {"out"};
    return bgr_element_add(m, c, name, &ctl_class_pid, q, 0, NULL,
                           spec->derivative_filter > 0 ? 2 : 1, sn, 1, an);
}
