/* The trim's root finder (bg_trim.h) against closed forms: the cube root of 2 as the root of
 * p^3 - 2 by the secant from a value near it; a root the secant would leave the bracket for
 * (atan, whose secant from the flat part overshoots) found by Illinois inside the bracket, to
 * the tolerance; f of one sign at the bracket's ends refused with both values; a callback's
 * status passed on; options out of range refused; the last value evaluated is the answer. */
#include <math.h>
#include <stdio.h>

#include "bg_trim.h"
#include "tap.h"

typedef struct ctx {
    int kind, calls;
    double last;
} ctx;

static int fn(void *c_, double p, double *f, bg_error *err)
{
    ctx *c = c_;
    c->calls++;
    c->last = p;
    switch (c->kind) {
    case 0: *f = p * p * p - 2; break;
    case 1: *f = atan(4 * (p - 1.3)); break;
    case 2: *f = p * p + 1; break;
    default: return bg_error_raise(err, BG_ERR_CALLBACK, "test", "the model failed at %g", p);
    }
    return BG_OK;
}

int main(void)
{
    bg_error e = {0};
    dae_trim_result r;
    ctx c = {0, 0, 0};
    dae_trim_options o = {1.2, 0, 2, 1e-12};
    int st = dae_trim_solve(fn, &c, &o, &r, &e);
    tap_ok(st == BG_OK && fabs(r.p - cbrt(2.0)) <= 1e-12 && fabs(r.f) <= 1e-12 && !r.bracketed,
           "p^3 = 2 by the secant: %.17g (cbrt 2 = %.17g), %d evaluations", r.p, cbrt(2.0),
           r.evals);
    tap_ok(r.evals == c.calls && c.last == r.p, "the last value evaluated is the answer's");

    /* atan(4 (p - 1.3)) from p0 = 9.5: the secant through its flat part jumps out of [0, 10] */
    c = (ctx){1, 0, 0};
    o = (dae_trim_options){9.5, 0, 10, 1e-10};
    st = dae_trim_solve(fn, &c, &o, &r, &e);
    tap_ok(st == BG_OK && r.bracketed && fabs(r.p - 1.3) <= 1e-10 / 4 * 1.0001,
           "atan: the bracket used, p = %.15g (1.3), %d evaluations", r.p, r.evals);
    tap_ok(r.evals < 60, "Illinois converges superlinearly: %d evaluations for 1e-10 of a width "
           "of 10", r.evals);

    /* p^2 + 1 > 0 everywhere */
    c = (ctx){2, 0, 0};
    o = (dae_trim_options){0.5, -1, 2, 1e-9};
    st = dae_trim_solve(fn, &c, &o, &r, &e);
    tap_ok(st == DAE_CONV_FAIL && r.f_lo == 2 && r.f_hi == 5,
           "f of one sign at both ends: refused (%s) with f(lo) = %g, f(hi) = %g",
           bg_status_name(st), r.f_lo, r.f_hi);

    c = (ctx){3, 0, 0};
    o = (dae_trim_options){0.5, 0, 1, 1e-9};
    bg_error_clear(&e);
    st = dae_trim_solve(fn, &c, &o, &r, &e);
    tap_ok(st == BG_ERR_CALLBACK && c.calls == 1, "a callback's status stops the trim: %s (%s)",
           bg_status_name(st), e.message);

    /* p0 outside the bracket: its middle; on a bound: used */
    c = (ctx){0, 0, 0};
    o = (dae_trim_options){NAN, 0, 2, 1e-12};
    st = dae_trim_solve(fn, &c, &o, &r, &e);
    tap_ok(st == BG_OK && fabs(r.p - cbrt(2.0)) <= 1e-12, "no p0: from the bracket's middle");
    c = (ctx){0, 0, 0};
    o = (dae_trim_options){2, 0, 2, 1e-12};
    st = dae_trim_solve(fn, &c, &o, &r, &e);
    tap_ok(st == BG_OK && fabs(r.p - cbrt(2.0)) <= 1e-12, "p0 on the bracket's end: taken");

    const dae_trim_options bad[] = {{1, 2, 2, 1e-9}, {1, 3, 2, 1e-9}, {1, NAN, 2, 1e-9},
                                    {1, 0, INFINITY, 1e-9}, {1, 0, 2, 0}, {1, 0, 2, -1},
                                    {1, 0, 2, NAN}};
    int refused = 0;
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        c = (ctx){0, 0, 0};
        refused += dae_trim_solve(fn, &c, &bad[i], &r, &e) == BG_ERR_ARGUMENT && c.calls == 0;
    }
    tap_ok(refused == 7, "options out of range refused before any evaluation (%d of 7)", refused);
    tap_ok(dae_trim_solve(NULL, &c, &o, &r, &e) == BG_ERR_ARGUMENT &&
               dae_trim_solve(fn, &c, NULL, &r, &e) == BG_ERR_ARGUMENT &&
               dae_trim_solve(fn, &c, &o, NULL, &e) == BG_ERR_ARGUMENT,
           "no function, options or result: refused");
    return tap_done();
}
