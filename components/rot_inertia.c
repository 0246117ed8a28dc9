/* Rotational inertia with angle (equations in rot_inertia.h). */
#include "rot_inertia.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "cmp_internal.h"

typedef struct inertia {
    double J;
    double w_nom; /* stated nominal speed (rot_inertia_set_nominal), 0: none */
    int T, w, s, p, th;
} inertia;

static int inertia_declare(bgr_element *el, bgr_model *m)
{
    static const char *const lab[3] = {"momentum", "velocity", "angle"};
    inertia *q = el->params;
    q->T = bgr_ev(el, m, 0, 0);
    q->w = bgr_fv(el, m, 0, 0);
    q->s = el->sign[0];
    q->p = bgr_sv(el, 0);
    q->th = bgr_sv(el, 1);
    int st = bgr_declare_equations(el, m, 3, lab);
    if (st) return st;
    CMP_DEP(el, m, 0, q->p, 1);
    CMP_DEP(el, m, 0, q->T, 0);
    CMP_DEP(el, m, 1, q->w, 0);
    CMP_DEP(el, m, 1, q->p, 0);
    CMP_DEP(el, m, 2, q->th, 1);
    CMP_DEP(el, m, 2, q->p, 0);
    /* J alone gives no speed; a stated speed scales the speed and the momentum J w. The angle
     * keeps 1 rad (it grows without bound, no scale of its own); the torque 1 N m (set by the
     * rest of the drive). */
    CMP_NOM(el, m, q->w, q->w_nom);
    CMP_NOM(el, m, q->p, q->J * q->w_nom);
    return BG_OK;
}

static int inertia_residual(const bgr_element *el, double t, const double *y, const double *yp,
                            double *F)
{
    (void)t;
    const inertia *q = el->params;
    F[0] = yp[q->p] - y[q->T];
    F[1] = q->J * q->s * y[q->w] - y[q->p];
    F[2] = yp[q->th] - y[q->p] / q->J;
    return 0;
}

static int inertia_jacobian(const bgr_element *el, double t, const double *y, const double *yp,
                            double *v)
{
    (void)t, (void)y, (void)yp;
    const inertia *q = el->params;
    v[0] = 1.0;
    v[1] = -1.0;
    v[2] = q->J * q->s;
    v[3] = -1.0;
    v[4] = 1.0;
    v[5] = -1.0 / q->J;
    return 0;
}

static void inertia_describe(const bgr_element *el, const bgr_model *m, int k, char *buf, size_t n)
{
    const inertia *q = el->params;
    const char *p = bgr_var_name(m, q->p), *th = bgr_var_name(m, q->th);
    const char *T = bgr_var_name(m, q->T), *w = bgr_var_name(m, q->w);
    if (k == 0)
        snprintf(buf, n, "%s' = %s", p ? p : "p", T ? T : "T");
    else if (k == 1)
        snprintf(buf, n, "%g * %s%s = %s", q->J, q->s > 0 ? "" : "-", w ? w : "w", p ? p : "p");
    else
        snprintf(buf, n, "%s' = %s / %g", th ? th : "theta", p ? p : "p", q->J);
}

const bgr_element_class rot_class_inertia = {.type = "inertia",
                                             .declare = inertia_declare,
                                             .residual = inertia_residual,
                                             .jacobian = inertia_jacobian,
                                             .describe = inertia_describe,
                                             .destroy = free};

double rot_inertia_moment(const bgr_element *el)
{
    if (!el || el->cls != &rot_class_inertia) return 0.0;
    return ((const inertia *)el->params)->J;
}

int rot_inertia(bgr_model *m, bgr_comp c, const char *name, double J)
{
    if (bgr_check_value(m, c, name, "rot_inertia", "J", J, BGR_POSITIVE)) return BG_ERR_ARGUMENT;
    if (!isfinite(1.0 / J))
        return bgr_refuse(m, c, name, "rot_inertia",
                          "J = %g, expected a finite number > 0 with a finite 1 / J", J);
    inertia *q = calloc(1, sizeof *q);
    if (!q)
        return bg_error_raise(bgr_model_error_mut(m), BG_ERR_MEMORY, "rot_inertia",
                              "out of memory");
    q->J = J;
    static const int dims[1] = {1};
    static const char *const sn[2] = {"p", "angle"};
    return bgr_element_add(m, c, name, &rot_class_inertia, q, 1, dims, 2, sn, 0, NULL);
}

int rot_inertia_set_nominal(bgr_model *m, int id, double speed)
{
    void *q = NULL;
    int st = cmp_check_scales(m, id, &rot_class_inertia, "a rotational inertia",
                              "rot_inertia_set_nominal", &speed, 1, &q);
    if (st != BG_OK) return st;
    ((inertia *)q)->w_nom = speed;
    return BG_OK;
}
