/* Helpers shared by the component sources (internal: not installed, not part of the API).
 *
 * CMP_DEP declares a partial derivative inside a declare() hook and returns on failure, as the
 * standard elements do. The smooth functions replace kinks in component laws (the residuals
 * must stay smooth for the Newton iteration and the error estimate of the BDF method):
 *
 *   softplus   sp(z) = eps ln(1 + exp(z / eps)), a smooth max(z, 0):
 *              0 < sp(z) - max(z, 0) = eps ln(1 + exp(-|z| / eps)) <= eps ln 2,
 *              the excess decays like eps exp(-|z| / eps) away from z = 0; sp'(z) is the
 *              logistic function 1 / (1 + exp(-z / eps)), in (0, 1).
 *   clamp      c(v) = lo + sp(v - lo) - sp(v - hi), a smooth min(max(v, lo), hi):
 *              |c(v) - min(max(v, lo), hi)| <= eps ln 2 for every v (each of the two softplus
 *              excesses lies in [0, eps ln 2] and they enter with opposite signs), the largest
 *              deviation at the corners v = lo and v = hi; lo < c(v) < hi always.
 * Both are evaluated without overflow: sp(z) = max(z, 0) + eps log1p(exp(-|z| / eps)) is the
 * same analytic function (the kinks of max and |.| cancel), and the clamp switches to the equal
 * form hi - sp(hi - v) + sp(lo - v) above the midpoint (sp(z) - sp(-z) = z) so that no large
 * terms cancel. */
#ifndef CMP_INTERNAL_H
#define CMP_INTERNAL_H

#include <math.h>

#include "bgr_check.h"
#include "bgr_model.h"

#define CMP_DEP(el, m, k, var, wrt_yp)                                                             \
    do {                                                                                           \
        int st_ = bgr_declare_dep((el), (m), (k), (var), (wrt_yp));                                \
        if (st_ != BG_OK) return st_;                                                              \
    } while (0)

/* CMP_NOM declares the nominal magnitude nom of unknown var (bgr_declare_nominal) inside a
 * declare() hook, returning on failure; nothing when nom is not a scale (0: not stated) or var
 * does not exist (< 0). */
#define CMP_NOM(el, m, var, nom)                                                                   \
    do {                                                                                           \
        double nom_ = (nom);                                                                       \
        int var_ = (var);                                                                          \
        if (var_ >= 0 && nom_ > 0 && isfinite(nom_)) {                                             \
            int st_ = bgr_declare_nominal((el), (m), var_, nom_);                                  \
            if (st_ != BG_OK) return st_;                                                          \
        }                                                                                          \
    } while (0)

/* The check of the nominal-scale setters of the components: element id must be of class cls
 * (kind names it in the message), the model still being built, and every one of the n values
 * finite and >= 0 (0: not stated). BG_OK with *params the element's parameters, else the status
 * with a message naming the element and the setter (what). */
static inline int cmp_check_scales(bgr_model *m, int id, const bgr_element_class *cls,
                                   const char *kind, const char *what, const double *v, int n,
                                   void **params)
{
    if (!m) return BG_ERR_ARGUMENT;
    bgr_element *el = bgr_element_get(m, id);
    if (!el || el->cls != cls)
        return bg_error_raise(bgr_model_error_mut(m), BG_ERR_ARGUMENT, what,
                              "element %d is not %s", id, kind);
    if (bgr_nvars(m) > 0)
        return bg_error_raise(bgr_model_error_mut(m), BG_ERR_STATE, what,
                              "element %s/%s: the model is compiled: state nominal scales "
                              "before bgr_compile",
                              bgr_component_path(m, el->comp), el->name);
    for (int i = 0; i < n; i++)
        if (!(v[i] >= 0) || !isfinite(v[i]))
            return bg_error_raise(bgr_model_error_mut(m), BG_ERR_ARGUMENT, what,
                                  "element %s/%s: nominal scale %g must be finite and >= 0 "
                                  "(0: not stated)",
                                  bgr_component_path(m, el->comp), el->name, v[i]);
    *params = el->params;
    return BG_OK;
}

#define CMP_TWO_PI 6.283185307179586476925286766559

/* Smooth max(z, 0) with width eps > 0; its derivative into *dz (may be NULL). */
static inline double cmp_softplus(double z, double eps, double *dz)
{
    double e = exp(-fabs(z) / eps); /* in (0, 1] */
    if (dz) *dz = z >= 0 ? 1.0 / (1.0 + e) : e / (1.0 + e);
    return (z > 0 ? z : 0.0) + eps * log1p(e);
}

/* The regime of a smooth switch from its slope d in [0, 1] (the softplus's logistic, a
 * clamp's slope, a rope's tautness): 3 on (d > 0.98), 2 between (d >= 0.02), 1 nearly off
 * (d >= 1e-3), 0 off; the bands of bgr_element_class.regime. A Jacobian from a band of larger
 * slope used in one of smaller slope is the stiffer one, which the Newton test cannot see
 * (bg_dae.h, dae_problem.regimes); within a band the slope it carries is at most 50 times the
 * true one, or below 1e-3 of the switch's full gain. The band at 1e-3 is needed: with three
 * bands, a Jacobian from d = 0.019 (between) used after the switch has closed (d ~ 1e-10) carries
 * 1e8 times the true slope, and the iteration on it leaves a closed valve passing flow. */
static inline int cmp_regime(double d)
{
    return d > 0.98 ? 3 : d >= 0.02 ? 2 : d >= 1e-3 ? 1 : 0;
}

/* Smooth clamp of v to [lo, hi] (lo < hi) with width eps > 0; derivative into *dv. */
static inline double cmp_clamp(double v, double lo, double hi, double eps, double *dv)
{
    double d1, d2, r;
    if (v <= 0.5 * (lo + hi)) {
        r = lo + cmp_softplus(v - lo, eps, &d1) - cmp_softplus(v - hi, eps, &d2);
        *dv = d1 - d2;
    } else {
        r = hi - cmp_softplus(hi - v, eps, &d1) + cmp_softplus(lo - v, eps, &d2);
        *dv = d1 - d2;
    }
    return r;
}

#endif
