/* Parameter checks of the element constructors and the component builders (internal,
 * header-only: not installed, not part of the API).
 *
 * Every constructor validates its parameters before it builds anything. A bad one is refused
 * with BG_ERR_ARGUMENT and a message that names the element by the path it would have had (the
 * component's path and the name as given), the constructor, the parameter and what was
 * expected, e.g.
 *     element rig/hydraulics/line_high (hyd_volume): V = -0.001, expected a finite number > 0
 * Nothing is added to the model: the name stays free and the model stays as it was.
 *
 * The rules: every number finite (no NaN, no Inf), and besides
 *   BGR_FINITE       any finite number
 *   BGR_POSITIVE     > 0
 *   BGR_NONNEGATIVE  >= 0
 *   BGR_NONZERO      != 0
 * and, for matrices, bgr_check_spd: finite, exactly symmetric and positive definite (a Cholesky
 * factorisation with positive pivots). */
#ifndef BGR_CHECK_H
#define BGR_CHECK_H

#include <math.h>
#include <stdarg.h>
#include <stdio.h>

#include "bgr_model.h"

typedef enum bgr_rule { BGR_FINITE, BGR_POSITIVE, BGR_NONNEGATIVE, BGR_NONZERO } bgr_rule;

static inline int bgr_rule_ok(double x, bgr_rule rule)
{
    if (!isfinite(x)) return 0;
    switch (rule) {
    case BGR_POSITIVE:
        return x > 0;
    case BGR_NONNEGATIVE:
        return x >= 0;
    case BGR_NONZERO:
        return x != 0;
    default:
        return 1;
    }
}

static inline const char *bgr_rule_text(bgr_rule rule)
{
    switch (rule) {
    case BGR_POSITIVE:
        return "a finite number > 0";
    case BGR_NONNEGATIVE:
        return "a finite number >= 0";
    case BGR_NONZERO:
        return "a finite number != 0";
    default:
        return "a finite number";
    }
}

/* BG_ERR_ARGUMENT with the message "element <path> (<where>): <text>", <path> the component's
 * path and the name ("(null)" for NULL; the name alone if the component does not exist). A NULL
 * model: the status only. */
BG_PRINTF(5, 6)
static inline int bgr_refuse(bgr_model *m, bgr_comp c, const char *name, const char *where,
                             const char *fmt, ...)
{
    if (!m) return BG_ERR_ARGUMENT;
    char path[BG_MESSAGE_SIZE], text[BG_MESSAGE_SIZE];
    const char *cp = bgr_component_path(m, c), *nm = name ? name : "(null)";
    if (cp)
        snprintf(path, sizeof path, "%s/%s", cp, nm);
    else
        snprintf(path, sizeof path, "%s", nm);
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(text, sizeof text, fmt, ap);
    va_end(ap);
    return bg_error_raise(bgr_model_error_mut(m), BG_ERR_ARGUMENT, where, "element %s (%s): %s",
                          path, where, text);
}

/* BG_OK if x obeys rule, else the refusal "<param> = <x>, expected <rule>". */
static inline int bgr_check_value(bgr_model *m, bgr_comp c, const char *name, const char *where,
                                  const char *param, double x, bgr_rule rule)
{
    if (bgr_rule_ok(x, rule)) return BG_OK;
    return bgr_refuse(m, c, name, where, "%s = %g, expected %s", param, x, bgr_rule_text(rule));
}

/* The same for the n values v[0 .. n-1], named <param>[i]; BG_OK for v NULL (nothing given). */
static inline int bgr_check_values(bgr_model *m, bgr_comp c, const char *name, const char *where,
                                   const char *param, const double *v, int n, bgr_rule rule)
{
    for (int i = 0; v && i < n; i++)
        if (!bgr_rule_ok(v[i], rule))
            return bgr_refuse(m, c, name, where, "%s[%d] = %g, expected %s", param, i, v[i],
                              bgr_rule_text(rule));
    return BG_OK;
}

/* BG_OK if the d x d column-major matrix A (1 <= d <= 16) is finite, exactly symmetric and
 * positive definite; else the refusal naming the entry <param>[i,j] or the failed pivot. */
static inline int bgr_check_spd(bgr_model *m, bgr_comp c, const char *name, const char *where,
                                const char *param, const double *A, int d)
{
    double L[16 * 16];
    if (d < 1 || d > 16)
        return bgr_refuse(m, c, name, where, "%s has dimension %d, expected 1 .. 16", param, d);
    for (int j = 0; j < d; j++)
        for (int i = 0; i < d; i++)
            if (!isfinite(A[i + j * d]))
                return bgr_refuse(m, c, name, where,
                                  "%s[%d,%d] = %g, expected a finite symmetric positive definite "
                                  "matrix",
                                  param, i, j, A[i + j * d]);
    for (int j = 0; j < d; j++)
        for (int i = j + 1; i < d; i++)
            if (A[i + j * d] != A[j + i * d])
                return bgr_refuse(m, c, name, where,
                                  "%s[%d,%d] = %g but %s[%d,%d] = %g, expected a symmetric "
                                  "positive definite matrix",
                                  param, i, j, A[i + j * d], param, j, i, A[j + i * d]);
    for (int j = 0; j < d; j++) { /* Cholesky A = L L^T, column by column */
        double s = A[j + j * d];
        for (int k = 0; k < j; k++)
            s -= L[j + k * d] * L[j + k * d];
        if (!(s > 0) || !isfinite(s))
            return bgr_refuse(m, c, name, where,
                              "%s is not positive definite (pivot %d of its Cholesky "
                              "factorisation is %g), expected a symmetric positive definite "
                              "matrix",
                              param, j, s);
        L[j + j * d] = sqrt(s);
        for (int i = j + 1; i < d; i++) {
            double t = A[i + j * d];
            for (int k = 0; k < j; k++)
                t -= L[i + k * d] * L[j + k * d];
            L[i + j * d] = t / L[j + j * d];
        }
    }
    return BG_OK;
}

#endif
