/* Signal sources (equations in sig_sources.h). A trapezoid and a constant are piecewise-linear
 * functions; every source evaluates its value, rate and integral in closed form. */
#include "sig_sources.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cmp_internal.h"

typedef enum shape { SHAPE_PWL, SHAPE_STEP, SHAPE_RAMP, SHAPE_SINE } shape;

typedef struct source {
    shape kind;
    sig_output out;
    const char *what; /* for listings */
    int n;
    double *t, *v, *cum; /* pwl: knots, values, integral from t[0] to t[k] */
    double a, b, c, d;   /* step: t_s, before, after; ramp: t_s, slope, offset;
                            sine: amplitude, omega, phase, offset */
    double A0;           /* antiderivative at t = 0 (the integral starts there) */
    int z;
} source;

static void source_free(void *p)
{
    source *q = p;
    if (!q) return;
    free(q->t);
    free(q->v);
    free(q->cum);
    free(q);
}

/* u(t), u'(t) and an antiderivative A(t) of u (A(0) is subtracted by the caller). */
static void shape_eval(const source *q, double t, double *u, double *du, double *A)
{
    switch (q->kind) {
    case SHAPE_PWL: {
        int n = q->n;
        const double *tk = q->t, *vk = q->v;
        if (n == 1 || t <= tk[0]) {
            *u = vk[0];
            *du = 0.0;
            *A = vk[0] * (t - tk[0]);
        } else if (t > tk[n - 1]) {
            *u = vk[n - 1];
            *du = 0.0;
            *A = q->cum[n - 1] + vk[n - 1] * (t - tk[n - 1]);
        } else {
            int lo = 0, hi = n - 1; /* tk[lo] < t <= tk[hi] */
            while (hi - lo > 1) {
                int mid = (lo + hi) / 2;
                if (t <= tk[mid])
                    hi = mid;
                else
                    lo = mid;
            }
            double s = (vk[hi] - vk[lo]) / (tk[hi] - tk[lo]), d = t - tk[lo];
            *u = vk[lo] + s * d;
            *du = s;
            *A = q->cum[lo] + vk[lo] * d + 0.5 * s * d * d;
        }
        return;
    }
    case SHAPE_STEP:
        *u = t <= q->a ? q->b : q->c;
        *du = 0.0;
        *A = q->b * t + (t > q->a ? (q->c - q->b) * (t - q->a) : 0.0);
        return;
    case SHAPE_RAMP: {
        double d = t > q->a ? t - q->a : 0.0;
        *u = q->c + q->b * d;
        *du = t > q->a ? q->b : 0.0;
        *A = q->c * t + 0.5 * q->b * d * d;
        return;
    }
    case SHAPE_SINE: {
        double arg = q->b * t + q->c; /* omega t + phase */
        *u = q->d + q->a * sin(arg);
        *du = q->a * q->b * cos(arg);
        *A = q->b != 0 ? q->d * t - q->a / q->b * cos(arg) : (q->d + q->a * sin(q->c)) * t;
        return;
    }
    }
}

static double source_value(const source *q, double t)
{
    double u = 0, du = 0, A = 0; /* set by every shape (the compiler cannot see it at -O3) */
    shape_eval(q, t, &u, &du, &A);
    return q->out == SIG_VALUE ? u : q->out == SIG_RATE ? du : A - q->A0;
}

/* The signal's scale: the largest |value| the output takes, from the source's parameters (0:
 * none, the output is unbounded or identically 0). */
static double source_scale(const source *q)
{
    double sc = 0;
    switch (q->kind) {
    case SHAPE_PWL:
        for (int k = 0; k < q->n; k++) {
            if (q->out == SIG_VALUE) sc = fmax(sc, fabs(q->v[k]));
            if (q->out == SIG_RATE && k > 0)
                sc = fmax(sc, fabs((q->v[k] - q->v[k - 1]) / (q->t[k] - q->t[k - 1])));
            /* the integral is bounded when the function ends (and, before 0, starts) at 0 */
            if (q->out == SIG_INTEGRAL && q->v[q->n - 1] == 0 && (q->v[0] == 0 || q->t[0] >= 0))
                sc = fmax(sc, fabs(q->cum[k] - q->A0));
        }
        return sc;
    case SHAPE_STEP:
        return q->out == SIG_VALUE ? fmax(fabs(q->b), fabs(q->c)) : 0.0;
    case SHAPE_RAMP:
        return q->out == SIG_RATE ? fabs(q->b) : 0.0;
    case SHAPE_SINE:
        return q->out == SIG_VALUE  ? fabs(q->a) + fabs(q->d)
               : q->out == SIG_RATE ? fabs(q->a * q->b)
                                    : 0.0;
    }
    return 0.0;
}

static int source_declare(bgr_element *el, bgr_model *m)
{
    static const char *const lab[1] = {"signal"};
    source *q = el->params;
    q->z = bgr_av(el, 0);
    int st = bgr_declare_equations(el, m, 1, lab);
    if (st) return st;
    CMP_DEP(el, m, 0, q->z, 0);
    /* the largest magnitude of the output, where the parameters bound it */
    CMP_NOM(el, m, q->z, source_scale(q));
    return BG_OK;
}

static int source_residual(const bgr_element *el, double t, const double *y, const double *yp,
                           double *F)
{
    (void)yp;
    const source *q = el->params;
    F[0] = y[q->z] - source_value(q, t);
    return 0;
}

static int source_jacobian(const bgr_element *el, double t, const double *y, const double *yp,
                           double *v)
{
    (void)el, (void)t, (void)y, (void)yp;
    v[0] = 1.0;
    return 0;
}

static void source_describe(const bgr_element *el, const bgr_model *m, int k, char *buf, size_t n)
{
    (void)k;
    const source *q = el->params;
    const char *z = bgr_var_name(m, q->z);
    static const char *const op[3] = {"", "d/dt ", "integral_0^t "};
    snprintf(buf, n, "%s = %s%s(t)", z ? z : "z", op[q->out], q->what);
}

static int source_breakpoints(const bgr_element *el, double t0, double t1, double *t, int max)
{
    const source *q = el->params;
    int cnt = 0;
    if (q->kind == SHAPE_PWL) {
        for (int k = 0; k < q->n; k++)
            if (q->n > 1 && q->t[k] > t0 && q->t[k] <= t1) {
                if (t && cnt < max) t[cnt] = q->t[k];
                cnt++;
            }
    } else if (q->kind == SHAPE_STEP || q->kind == SHAPE_RAMP) {
        if (q->a > t0 && q->a <= t1) {
            if (t && cnt < max) t[cnt] = q->a;
            cnt++;
        }
    }
    return cnt;
}

const bgr_element_class sig_class_source = {.type = "signal",
                                            .declare = source_declare,
                                            .residual = source_residual,
                                            .jacobian = source_jacobian,
                                            .describe = source_describe,
                                            .destroy = source_free,
                                            .breakpoints = source_breakpoints};

static int add_source(bgr_model *m, bgr_comp c, const char *name, source *q, const char *where)
{
    if (!q) return bg_error_raise(bgr_model_error_mut(m), BG_ERR_MEMORY, where, "out of memory");
    double u, du;
    shape_eval(q, 0.0, &u, &du, &q->A0);
    static const char *const names[3] = {"value", "rate", "integral"};
    const char *an[1] = {names[q->out]};
    return bgr_element_add(m, c, name, &sig_class_source, q, 0, NULL, 0, NULL, 1, an);
}

static int bad_out(bgr_model *m, bgr_comp c, const char *name, sig_output out, const char *where)
{
    if (out == SIG_VALUE || out == SIG_RATE || out == SIG_INTEGRAL) return 0;
    return bgr_refuse(m, c, name, where,
                      "unknown output out = %d, expected SIG_VALUE, SIG_RATE or SIG_INTEGRAL",
                      (int)out);
}

/* BG_OK if the n points (t_k, v_k), finite with strictly increasing times, make a
 * piecewise-linear function whose slopes and segment areas are finite (knots not so close, or
 * values not so large, that they overflow); else the refusal naming the points. */
static int check_segments(bgr_model *m, bgr_comp c, const char *name, const char *where, int n,
                          const double *t, const double *v)
{
    for (int k = 1; k < n; k++) {
        double dt = t[k] - t[k - 1], s = (v[k] - v[k - 1]) / dt, a = 0.5 * (v[k - 1] + v[k]) * dt;
        if (!isfinite(s) || !isfinite(a))
            return bgr_refuse(m, c, name, where,
                              "the segment from (t = %g, v = %g) to (t = %g, v = %g) has slope %g "
                              "and area %g, expected finite numbers (times too close or values "
                              "too large)",
                              t[k - 1], v[k - 1], t[k], v[k], s, a);
    }
    return BG_OK;
}

static source *new_source(shape kind, sig_output out, const char *what)
{
    source *q = calloc(1, sizeof *q);
    if (q) {
        q->kind = kind;
        q->out = out;
        q->what = what;
    }
    return q;
}

/* A pwl source with copies of the knots, or NULL (out of memory). */
static source *new_pwl(int n, const double *t, const double *v, sig_output out, const char *what)
{
    source *q = new_source(SHAPE_PWL, out, what);
    if (!q) return NULL;
    q->n = n;
    q->t = malloc((size_t)n * sizeof *q->t);
    q->v = malloc((size_t)n * sizeof *q->v);
    q->cum = malloc((size_t)n * sizeof *q->cum);
    if (!q->t || !q->v || !q->cum) {
        source_free(q);
        return NULL;
    }
    memcpy(q->t, t, (size_t)n * sizeof *t);
    memcpy(q->v, v, (size_t)n * sizeof *v);
    q->cum[0] = 0.0;
    for (int k = 1; k < n; k++)
        q->cum[k] = q->cum[k - 1] + 0.5 * (v[k - 1] + v[k]) * (t[k] - t[k - 1]);
    return q;
}

int sig_pwl(bgr_model *m, bgr_comp c, const char *name, int n, const double *t, const double *v,
            sig_output out)
{
    const char *w = "sig_pwl";
    if (bad_out(m, c, name, out, w)) return BG_ERR_ARGUMENT;
    if (n < 1) return bgr_refuse(m, c, name, w, "n = %d, expected at least 1 point", n);
    if (!t || !v)
        return bgr_refuse(m, c, name, w, "the points' %s are NULL", !t ? "times t" : "values v");
    if (bgr_check_values(m, c, name, w, "t", t, n, BGR_FINITE) ||
        bgr_check_values(m, c, name, w, "v", v, n, BGR_FINITE))
        return BG_ERR_ARGUMENT;
    for (int k = 1; k < n; k++)
        if (!(t[k] > t[k - 1]))
            return bgr_refuse(m, c, name, w,
                              "t[%d] = %g, expected > t[%d] = %g (strictly increasing times)", k,
                              t[k], k - 1, t[k - 1]);
    if (check_segments(m, c, name, w, n, t, v)) return BG_ERR_ARGUMENT;
    return add_source(m, c, name, new_pwl(n, t, v, out, "pwl"), w);
}

int sig_trapezoid(bgr_model *m, bgr_comp c, const char *name, double t0, double t1, double t2,
                  double t3, double height, sig_output out)
{
    const char *w = "sig_trapezoid";
    if (bad_out(m, c, name, out, w)) return BG_ERR_ARGUMENT;
    if (bgr_check_value(m, c, name, w, "t0", t0, BGR_FINITE) ||
        bgr_check_value(m, c, name, w, "t1", t1, BGR_FINITE) ||
        bgr_check_value(m, c, name, w, "t2", t2, BGR_FINITE) ||
        bgr_check_value(m, c, name, w, "t3", t3, BGR_FINITE) ||
        bgr_check_value(m, c, name, w, "height", height, BGR_FINITE))
        return BG_ERR_ARGUMENT;
    if (!(t0 < t1))
        return bgr_refuse(m, c, name, w, "t1 = %g, expected > t0 = %g (t0 < t1 <= t2 < t3)", t1,
                          t0);
    if (!(t1 <= t2))
        return bgr_refuse(m, c, name, w, "t2 = %g, expected >= t1 = %g (t0 < t1 <= t2 < t3)", t2,
                          t1);
    if (!(t2 < t3))
        return bgr_refuse(m, c, name, w, "t3 = %g, expected > t2 = %g (t0 < t1 <= t2 < t3)", t3,
                          t2);
    double tk[4] = {t0, t1, t2, t3}, vk[4] = {0.0, height, height, 0.0};
    if (t1 == t2) {
        tk[2] = t3;
        vk[2] = 0.0;
    }
    if (check_segments(m, c, name, w, t1 == t2 ? 3 : 4, tk, vk)) return BG_ERR_ARGUMENT;
    return add_source(m, c, name, new_pwl(t1 == t2 ? 3 : 4, tk, vk, out, "trapezoid"), w);
}

int sig_constant(bgr_model *m, bgr_comp c, const char *name, double value, sig_output out)
{
    const char *w = "sig_constant";
    if (bad_out(m, c, name, out, w)) return BG_ERR_ARGUMENT;
    if (bgr_check_value(m, c, name, w, "value", value, BGR_FINITE)) return BG_ERR_ARGUMENT;
    double t0 = 0.0;
    return add_source(m, c, name, new_pwl(1, &t0, &value, out, "constant"), w);
}

/* np parameters p named pn, all finite (the unused ones 0). */
static int add_param_source(bgr_model *m, bgr_comp c, const char *name, shape kind, sig_output out,
                            const char *what, const double p[4], const char *const pn[4], int np,
                            const char *w)
{
    if (bad_out(m, c, name, out, w)) return BG_ERR_ARGUMENT;
    for (int k = 0; k < np; k++)
        if (bgr_check_value(m, c, name, w, pn[k], p[k], BGR_FINITE)) return BG_ERR_ARGUMENT;
    source *q = new_source(kind, out, what);
    if (q) {
        q->a = p[0];
        q->b = p[1];
        q->c = p[2];
        q->d = p[3];
    }
    return add_source(m, c, name, q, w);
}

int sig_step(bgr_model *m, bgr_comp c, const char *name, double t_step, double before, double after,
             sig_output out)
{
    const double p[4] = {t_step, before, after, 0.0};
    static const char *const pn[4] = {"t_step", "before", "after", ""};
    return add_param_source(m, c, name, SHAPE_STEP, out, "step", p, pn, 3, "sig_step");
}

int sig_ramp(bgr_model *m, bgr_comp c, const char *name, double t_start, double slope,
             double offset, sig_output out)
{
    const double p[4] = {t_start, slope, offset, 0.0};
    static const char *const pn[4] = {"t_start", "slope", "offset", ""};
    return add_param_source(m, c, name, SHAPE_RAMP, out, "ramp", p, pn, 3, "sig_ramp");
}

int sig_sine(bgr_model *m, bgr_comp c, const char *name, double amplitude, double omega,
             double phase, double offset, sig_output out)
{
    const double p[4] = {amplitude, omega, phase, offset};
    static const char *const pn[4] = {"amplitude", "omega", "phase", "offset"};
    return add_param_source(m, c, name, SHAPE_SINE, out, "sine", p, pn, 4, "sig_sine");
}

int sig_source_output(bgr_model *m, int id)
{
    bgr_element *el = bgr_element_get(m, id);
    if (!el || el->cls != &sig_class_source)
        return bg_error_raise(bgr_model_error_mut(m), BG_ERR_ARGUMENT, "sig_source_output",
                              "element %d is not a signal source", id);
    return (int)((const source *)el->params)->out;
}

int sig_evaluate(bgr_model *m, int id, double t, double *value, double *rate, double *integral)
{
    bgr_element *el = bgr_element_get(m, id);
    if (!el || el->cls != &sig_class_source)
        return bg_error_raise(bgr_model_error_mut(m), BG_ERR_ARGUMENT, "sig_evaluate",
                              "element %d is not a signal source", id);
    const source *q = el->params;
    double u, du, A;
    shape_eval(q, t, &u, &du, &A);
    if (value) *value = u;
    if (rate) *rate = du;
    if (integral) *integral = A - q->A0;
    return BG_OK;
}
