/* The stability guard (options.stability_guard, solver/dae_stab.c) against closed forms.
 *
 * Two undamped oscillators driven slowly, the second stiff (the fast mode of a flexible structure)
 * and excited from the start, as a first-order system y = (q1, v1, q2, v2):
 *     q_i'' = -omega_i^2 q_i + F_i sin(W t),
 *     q_i(t) = q_i(0) cos(omega_i t) + B_i sin(omega_i t) + F_i sin(W t) / (omega_i^2 - W^2),
 *     B_i = (v_i(0) - F_i W / (omega_i^2 - W^2)) / omega_i,
 * with omega_1 = 20, omega_2 = 700, W = 1 (rad/s), over 5 s, rtol = atol = 1e-5, 1e-6, 1e-7. The
 * slow oscillator asks order 5 for steps of 5 to 10 / omega_2, inside BDF5's unstable band
 * (0.72 < h omega < 9.4): without the guard the step sits at the band's edge, 0.72 / omega_2,
 * whatever the tolerance. With the guard the order is lowered to 2, BDF2 damps the fast mode,
 * and the steps follow the slow oscillator: fewer, and falling as the tolerance loosens. The
 * fast mode's amplitude is damped (numerical dissipation: the price, documented). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "bg_dae.h"
#include "bg_sparse.h"
#include "tap.h"

#define W1 20.0
#define W2 700.0
#define WF 1.0
#define F1 1.0
#define F2 1.0
#define TEND 5.0

static const double y0v[4] = {0.0, 0.5, 1e-7, 0.0};

static double wsq(int i)
{
    return i == 0 ? W1 * W1 : W2 * W2;
}

static void exact(double t, double *y)
{
    for (int i = 0; i < 2; i++) {
        double w = i == 0 ? W1 : W2, F = i == 0 ? F1 : F2, d = wsq(i) - WF * WF;
        double q0 = y0v[2 * i], v0 = y0v[2 * i + 1], B = (v0 - F * WF / d) / w;
        y[2 * i] = q0 * cos(w * t) + B * sin(w * t) + F * sin(WF * t) / d;
        y[2 * i + 1] = -q0 * w * sin(w * t) + B * w * cos(w * t) + F * WF * cos(WF * t) / d;
    }
}

static int res(void *user, double t, const double *y, const double *yp, double *F)
{
    (void)user;
    F[0] = yp[0] - y[1];
    F[1] = yp[1] + W1 * W1 * y[0] - F1 * sin(WF * t);
    F[2] = yp[2] - y[3];
    F[3] = yp[3] + W2 * W2 * y[2] - F2 * sin(WF * t);
    return 0;
}

typedef struct run {
    long steps, lowered, order2;
    double err_slow; /* max |q1 - exact| / (rtol |q1| + atol) at the output points */
    double fast_end; /* amplitude of the fast mode at the end over its exact amplitude */
    int status;
} run;

static run solve(double rtol, int guard)
{
    run out = {0};
    dae_problem p = {0};
    p.n = 4;
    p.res = res;
    dae_options o;
    dae_options_default(&o);
    o.rtol = rtol;
    o.atol = rtol;
    o.stability_guard = guard;
    o.max_steps = 2000000;

    bg_error e = {0};
    dae_solver *s = dae_create(&p, &o, &e);
    if (!s) {
        out.status = -1;
        return out;
    }
    double yp0[4], y[4], ye[4], t;
    res(NULL, 0, y0v, (double[4]){0, 0, 0, 0}, yp0); /* y' = f(0, y0): F(0, y0, 0) = -f */
    for (int i = 0; i < 4; i++)
        yp0[i] = -yp0[i];
    dae_init(s, 0.0, y0v, yp0);
    for (int k = 1; k <= 40; k++) {
        double tout = TEND * k / 40.0;
        out.status = dae_solve_to(s, tout, &t, y, NULL);
        if (out.status < 0) break;
        exact(t, ye);
        double e0 = fabs(y[0] - ye[0]) / (rtol * fabs(ye[0]) + rtol);
        if (e0 > out.err_slow) out.err_slow = e0;
    }
    exact(TEND, ye);
    /* fast mode: q2 minus its forced part, in amplitude units of its free oscillation */
    double d2 = wsq(1) - WF * WF, qf = F2 * sin(WF * TEND) / d2, vf = F2 * WF * cos(WF * TEND) / d2;
    double amp = hypot(y[2] - qf, (y[3] - vf) / W2), ampe = hypot(ye[2] - qf, (ye[3] - vf) / W2);
    out.fast_end = amp / ampe;
    const dae_stats *st = dae_get_stats(s);
    out.steps = st->steps;
    out.lowered = st->stab_lowered;
    out.order2 = st->steps_at_order[2];
    dae_free(&s);
    return out;
}

int main(void)
{
    const double tols[3] = {1e-5, 1e-6, 1e-7};
    run on[3], off[3];
    for (int k = 0; k < 3; k++) {
        on[k] = solve(tols[k], 1);
        off[k] = solve(tols[k], 0);
        tap_ok(on[k].status >= 0 && off[k].status >= 0, "rtol %g: both runs reach t = %g (%d, %d)",
               tols[k], TEND, on[k].status, off[k].status);
        tap_diag("rtol %g: guard %ld steps (%ld at order 2, lowered %ld), slow error %.2f tol, "
                 "fast mode %.3g of its amplitude; without %ld steps, slow error %.2f tol",
                 tols[k], on[k].steps, on[k].order2, on[k].lowered, on[k].err_slow,
                 on[k].fast_end, off[k].steps, off[k].err_slow);
    }
    /* the trap exists without the guard: the steps sit at the fast mode's stability limit of
     * order 5 (0.72 / omega_2: 4900 steps over the run), a tolerance 100 times looser saves
     * almost nothing */
    tap_ok(off[0].steps > 0.8 * off[2].steps && off[0].steps > 0.6 * TEND * W2 / 0.72,
           "without the guard the steps are held by stability: %ld, %ld, %ld at rtol %g, %g, %g",
           off[0].steps, off[1].steps, off[2].steps, tols[0], tols[1], tols[2]);
    tap_ok(on[0].lowered >= 1 && on[0].order2 > on[0].steps / 3,
           "rtol %g: the guard lowers the order (%ld times; %ld of %ld steps at order 2)", tols[0],
           on[0].lowered, on[0].order2, on[0].steps);
    tap_ok(on[0].steps < 0.5 * off[0].steps,
           "rtol %g: with the guard at most half the steps (%ld against %ld)", tols[0],
           on[0].steps, off[0].steps);
    tap_ok(on[0].steps <= 1.05 * on[1].steps && on[1].steps <= 1.05 * on[2].steps,
           "with the guard the steps fall as the tolerance loosens: %ld, %ld, %ld at rtol %g, %g, "
           "%g",
           on[2].steps, on[1].steps, on[0].steps, tols[2], tols[1], tols[0]);
    /* the error test still holds each step: the slow oscillator converges with the tolerance
     * (its global error is the sum of the local ones, a phase error that BDF2's larger steps
     * accumulate: tens to hundreds of tolerances over 16 periods, against one without the
     * guard) */
    double e0 = on[0].err_slow * tols[0], e2 = on[2].err_slow * tols[2];
    tap_ok(e2 < 0.01 * e0 && on[2].err_slow < 100,
           "with the guard the slow oscillator converges: max error %.2g at rtol %g, %.2g at %g",
           e0, tols[0], e2, tols[2]);
    tap_ok(on[0].fast_end < 0.5 && off[0].fast_end > 0.5,
           "the price: the fast mode is damped to %.3g of its amplitude (%.3g without the guard)",
           on[0].fast_end, off[0].fast_end);
    return tap_done();
}
