/* Sway sensor (equations in ctl_sway.h). */
#include "ctl_sway.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "cmp_internal.h"

typedef struct sway {
    ctl_sway_spec sp;
    int s, sd, x, y, vx, vy, th, om;
} sway;

static int sway_declare(bgr_element *el, bgr_model *m)
{
    static const char *const lab[2] = {"sway", "sway_rate"};
    sway *q = el->params;
    q->s = bgr_av(el, 0);
    q->sd = bgr_av(el, 1);
    q->x = bgr_ref_var(m, q->sp.x);
    q->y = bgr_ref_var(m, q->sp.y);
    q->vx = bgr_ref_var(m, q->sp.vx);
    q->vy = bgr_ref_var(m, q->sp.vy);
    q->th = bgr_ref_var(m, q->sp.theta);
    q->om = bgr_ref_var(m, q->sp.omega);
    if (q->x < 0 || q->y < 0 || q->vx < 0 || q->vy < 0 || q->th < 0 || q->om < 0)
        return bg_error_raise(bgr_model_error_mut(m), BG_ERR_ARGUMENT, "bgr_compile",
                              "sway sensor %s: an input refers to no unknown", el->name);
    int st = bgr_declare_equations(el, m, 2, lab);
    if (st) return st;
    CMP_DEP(el, m, 0, q->s, 0);
    CMP_DEP(el, m, 0, q->x, 0);
    CMP_DEP(el, m, 0, q->y, 0);
    CMP_DEP(el, m, 0, q->th, 0);
    CMP_DEP(el, m, 1, q->sd, 0);
    CMP_DEP(el, m, 1, q->x, 0);
    CMP_DEP(el, m, 1, q->y, 0);
    CMP_DEP(el, m, 1, q->vx, 0);
    CMP_DEP(el, m, 1, q->vy, 0);
    CMP_DEP(el, m, 1, q->th, 0);
    CMP_DEP(el, m, 1, q->om, 0);
    return BG_OK;
}

static int sway_residual(const bgr_element *el, double t, const double *y, const double *yp,
                         double *F)
{
    (void)t, (void)yp;
    const sway *q = el->params;
    double c = cos(y[q->th]), sn = sin(y[q->th]);
    double dx = y[q->x] - q->sp.cx, dy = y[q->y] - q->sp.cy, rho = dx * c + dy * sn;
    F[0] = y[q->s] - (-dx * sn + dy * c);
    F[1] = y[q->sd] - (-y[q->vx] * sn + y[q->vy] * c - y[q->om] * rho);
    return 0;
}

static int sway_jacobian(const bgr_element *el, double t, const double *y, const double *yp,
                         double *v)
{
    (void)t, (void)yp;
    const sway *q = el->params;
    double c = cos(y[q->th]), sn = sin(y[q->th]), w = y[q->om];
    double dx = y[q->x] - q->sp.cx, dy = y[q->y] - q->sp.cy, rho = dx * c + dy * sn;
    double s = -dx * sn + dy * c;
    int n = 0;
    v[n++] = 1.0;
    v[n++] = sn;
    v[n++] = -c;
    v[n++] = rho;
    v[n++] = 1.0;
    v[n++] = w * c;
    v[n++] = w * sn;
    v[n++] = sn;
    v[n++] = -c;
    v[n++] = y[q->vx] * c + y[q->vy] * sn + w * s;
    v[n++] = rho;
    return 0;
}

static void sway_describe(const bgr_element *el, const bgr_model *m, int k, char *buf, size_t n)
{
    (void)el, (void)m;
    snprintf(buf, n, "%s", k == 0 ? "s = -(x - cx) sin(theta) + (y - cy) cos(theta)"
                                  : "s' = -vx sin(theta) + vy cos(theta) - omega rho");
}

const bgr_element_class ctl_class_sway = {.type = "sway sensor",
                                          .declare = sway_declare,
                                          .residual = sway_residual,
                                          .jacobian = sway_jacobian,
                                          .describe = sway_describe,
                                          .destroy = free};

int ctl_sway(bgr_model *m, bgr_comp c, const char *name, const ctl_sway_spec *spec)
{
    const char *w = "ctl_sway";
    if (!spec) return bgr_refuse(m, c, name, w, "no specification (spec is NULL)");
    if (bgr_check_value(m, c, name, w, "cx", spec->cx, BGR_FINITE) ||
        bgr_check_value(m, c, name, w, "cy", spec->cy, BGR_FINITE))
        return BG_ERR_ARGUMENT;
    sway *q = calloc(1, sizeof *q);
    if (!q) return bg_error_raise(bgr_model_error_mut(m), BG_ERR_MEMORY, w, "out of memory");
    q->sp = *spec;
    static const char *const an[2] = {"sway", "sway_rate"};
    return bgr_element_add(m, c, name, &ctl_class_sway, q, 0, NULL, 0, NULL, 2, an);
}
