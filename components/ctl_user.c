/* User's controller (equations in ctl_user.h). */
#include "ctl_user.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "cmp_internal.h"

typedef struct usr {
    ctl_user_spec sp;
    int x[CTL_USER_MAX], u[CTL_USER_MAX];
} usr;

static int usr_declare(bgr_element *el, bgr_model *m)
{
    static const char *const lab[CTL_USER_MAX] = {
        "output 1", "output 2",  "output 3",  "output 4",  "output 5",  "output 6",
        "output 7", "output 8",  "output 9",  "output 10", "output 11", "output 12",
        "output 13", "output 14", "output 15", "output 16"};
    usr *q = el->params;
    const ctl_user_spec *s = &q->sp;
    for (int i = 0; i < s->n_in; i++)
        if ((q->x[i] = bgr_ref_var(m, s->in[i])) < 0)
            return bg_error_raise(bgr_model_error_mut(m), BG_ERR_ARGUMENT, "bgr_compile",
                                  "user controller %s: its input %d refers to no unknown",
                                  el->name, i + 1);
    for (int j = 0; j < s->n_out; j++) q->u[j] = bgr_av(el, j);
    int st = bgr_declare_equations(el, m, s->n_out, lab);
    if (st) return st;
    for (int j = 0; j < s->n_out; j++) {
        CMP_DEP(el, m, j, q->u[j], 0);
        for (int i = 0; i < s->n_in; i++) CMP_DEP(el, m, j, q->x[i], 0);
    }
    return BG_OK;
}

static int usr_eval(const usr *q, double t, const double *y, double *x, double *u, double *jac)
{
    const ctl_user_spec *s = &q->sp;
    for (int i = 0; i < s->n_in; i++) x[i] = y[q->x[i]];
    if (s->fn(s->user, t, x, u, s->has_jacobian ? jac : NULL)) return 1;
    if (!jac || s->has_jacobian) return 0;
    double up[CTL_USER_MAX], um[CTL_USER_MAX];
    for (int i = 0; i < s->n_in; i++) {
        double x0 = x[i], h = 1e-6 * (fabs(x0) + (s->scale[i] > 0 ? s->scale[i] : 1.0));
        x[i] = x0 + h;
        int r = s->fn(s->user, t, x, up, NULL);
        x[i] = x0 - h;
        r = r || s->fn(s->user, t, x, um, NULL);
        x[i] = x0;
        if (r) return 1;
        for (int j = 0; j < s->n_out; j++) jac[j + i * s->n_out] = (up[j] - um[j]) / (2 * h);
    }
    return 0;
}

static int usr_residual(const bgr_element *el, double t, const double *y, const double *yp,
                        double *F)
{
    (void)yp;
    const usr *q = el->params;
    double x[CTL_USER_MAX], u[CTL_USER_MAX];
    if (usr_eval(q, t, y, x, u, NULL)) return 1;
    for (int j = 0; j < q->sp.n_out; j++) {
        if (!isfinite(u[j])) return 1;
        F[j] = y[q->u[j]] - u[j];
    }
    return 0;
}

static int usr_jacobian(const bgr_element *el, double t, const double *y, const double *yp,
                        double *v)
{
    (void)yp;
    const usr *q = el->params;
    const ctl_user_spec *s = &q->sp;
    double x[CTL_USER_MAX], u[CTL_USER_MAX], jac[CTL_USER_MAX * CTL_USER_MAX];
    if (usr_eval(q, t, y, x, u, jac)) return 1;
    int n = 0;
    for (int j = 0; j < s->n_out; j++) {
        v[n++] = 1.0;
        for (int i = 0; i < s->n_in; i++) v[n++] = -jac[j + i * s->n_out];
    }
    return 0;
}

static void usr_describe(const bgr_element *el, const bgr_model *m, int k, char *buf, size_t n)
{
    (void)m;
    const usr *q = el->params;
    snprintf(buf, n, "u%d = f%d(t, x1..x%d) (user's callback)", k + 1, k + 1, q->sp.n_in);
}

const bgr_element_class ctl_class_user = {.type = "user controller",
                                          .declare = usr_declare,
                                          .residual = usr_residual,
                                          .jacobian = usr_jacobian,
                                          .describe = usr_describe,
                                          .destroy = free};

int ctl_user(bgr_model *m, bgr_comp c, const char *name, const ctl_user_spec *spec)
{
    const char *w = "ctl_user";
    if (!spec || !spec->fn)
        return bgr_refuse(m, c, name, w, "no specification or no callback (NULL)");
    if (spec->n_in < 1 || spec->n_in > CTL_USER_MAX || spec->n_out < 1 ||
        spec->n_out > CTL_USER_MAX)
        return bgr_refuse(m, c, name, w, "n_in = %d, n_out = %d, expected 1 .. %d each",
                          spec->n_in, spec->n_out, CTL_USER_MAX);
    for (int i = 0; i < spec->n_in; i++)
        if (!(spec->scale[i] >= 0) || !isfinite(spec->scale[i]))
            return bgr_refuse(m, c, name, w, "scale[%d] = %g, expected finite and >= 0", i,
                              spec->scale[i]);
    usr *q = calloc(1, sizeof *q);
    if (!q) return bg_error_raise(bgr_model_error_mut(m), BG_ERR_MEMORY, w, "out of memory");
    q->sp = *spec;
    static const char *const an[CTL_USER_MAX] = {"u1", "u2",  "u3",  "u4",  "u5",  "u6",
                                                 "u7", "u8",  "u9",  "u10", "u11", "u12",
                                                 "u13", "u14", "u15", "u16"};
    return bgr_element_add(m, c, name, &ctl_class_user, q, 0, NULL, 0, NULL, spec->n_out, an);
}
