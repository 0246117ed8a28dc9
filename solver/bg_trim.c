/* The trim's root finder (bg_trim.h): the secant from a caller's value, then Illinois on the
 * bracket. */
#include <math.h>
#include <stddef.h>

#include "bg_trim.h"

static int eval(dae_trim_fn fn, void *ctx, double p, double *f, dae_trim_result *res,
                bg_error *err)
{
    res->evals++;
    res->p = p;
    int r = fn(ctx, p, f, err);
    res->f = *f;
    if (r == BG_OK && !isfinite(*f))
        return bg_error_raise(err, BG_ERR_NONFINITE, "dae_trim_solve",
                              "the condition's value at %.17g is not finite", p);
    return r;
}

int dae_trim_solve(dae_trim_fn fn, void *ctx, const dae_trim_options *o, dae_trim_result *res,
                   bg_error *err)
{
    if (!res) return bg_error_raise(err, BG_ERR_ARGUMENT, "dae_trim_solve", "no result");
    *res = (dae_trim_result){NAN, NAN, NAN, NAN, 0, 0};
    if (!fn || !o)
        return bg_error_raise(err, BG_ERR_ARGUMENT, "dae_trim_solve", "no function or options");
    double a = o->lo, b = o->hi, tol = o->tol;
    if (!isfinite(a) || !isfinite(b) || !(a < b) || !isfinite(tol) || !(tol > 0))
        return bg_error_raise(err, BG_ERR_ARGUMENT, "dae_trim_solve",
                              "the bracket [%.17g, %.17g] and tolerance %.3g: expected finite "
                              "lo < hi and tol > 0", a, b, tol);
    /* the secant from p0 */
    double p0 = o->p0 >= a && o->p0 <= b ? o->p0 : 0.5 * (a + b);
    double h = 1e-4 * (b - a), p1 = p0 + h <= b ? p0 + h : p0 - h, f0, f1;
    int r = eval(fn, ctx, p0, &f0, res, err);
    if (r != BG_OK) return r;
    if (fabs(f0) <= tol) return BG_OK;
    for (int it = 0; it < 12; it++) {
        if ((r = eval(fn, ctx, p1, &f1, res, err)) != BG_OK) return r;
        if (fabs(f1) <= tol) return BG_OK;
        if (f1 == f0) break;
        double p2 = p1 - f1 * (p1 - p0) / (f1 - f0);
        if (!(p2 >= a && p2 <= b)) break; /* out of the bracket: use it */
        p0 = p1, f0 = f1, p1 = p2;
    }
    /* Illinois on [a, b] */
    double fa, fb;
    res->bracketed = 1;
    if ((r = eval(fn, ctx, a, &fa, res, err)) != BG_OK) return r;
    res->f_lo = fa;
    if (fabs(fa) <= tol) return BG_OK;
    if ((r = eval(fn, ctx, b, &fb, res, err)) != BG_OK) return r;
    res->f_hi = fb;
    if (fabs(fb) <= tol) return BG_OK;
    if (fa * fb > 0)
        return bg_error_raise(err, DAE_CONV_FAIL, "dae_trim_solve",
                              "the condition has the same sign at both ends of the bracket "
                              "[%.17g, %.17g] (%.9g and %.9g)", a, b, fa, fb);
    const double width = b - a;
    for (int it = 0; it < 200 && fabs(b - a) > 1e-12 * width; it++) {
        double p = b - fb * (b - a) / (fb - fa), fp;
        if ((r = eval(fn, ctx, p, &fp, res, err)) != BG_OK) return r;
        if (fabs(fp) <= tol) return BG_OK;
        if (fp * fb < 0) /* the root between p and b: the old b becomes the kept end */
            a = b, fa = fb;
        else /* the kept end a stays again: its value halved (Illinois) */
            fa /= 2;
        b = p, fb = fp;
    }
    return bg_error_raise(err, DAE_CONV_FAIL, "dae_trim_solve",
                          "the condition is not met within %.3g (last %.17g gives %.9g after %d "
                          "evaluations)", tol, res->p, res->f, res->evals);
}
