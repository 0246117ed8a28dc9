/* The states the integrator returns for a part of the unknowns (dae_set_output_unknowns), on
 * six decoupled decays with a closed form,
 *
 *   y_i' = -k_i y_i,   y_i(0) = 1,   y_i(t) = exp(-k_i t),   k = 1, 2, 5, 10, 0.5, 3:
 *
 *   - the selected unknowns' values and derivatives at 200 output times are bitwise those of
 *     the same run returning the whole state, the others are left as they were, and the steps
 *     are the same;
 *   - they agree with the closed form within the tolerances;
 *   - dae_step returns them at the end of each step bitwise as dae_dense gives them there;
 *   - m = 0 returns to the whole state; an index outside 0 .. n-1 or m < 0 is refused with a
 *     message naming it. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "bg_dae.h"
#include "bg_sparse.h"
#include "tap.h"

#define N 6
#define NOUT 200
#define DT 0.01
#define SENTINEL 12345.0

static const double K[N] = {1, 2, 5, 10, 0.5, 3};

static int res(void *user, double t, const double *y, const double *yp, double *F)
{
    (void)user, (void)t;
    for (int i = 0; i < N; i++)
        F[i] = yp[i] + K[i] * y[i];
    return 0;
}

static int jac(void *user, double t, const double *y, const double *yp, sp_csc *Jy, sp_csc *Jyp)
{
    (void)user, (void)t, (void)y, (void)yp;
    for (int i = 0; i < N; i++) {
        Jy->val[i] = K[i];
        Jyp->val[i] = 1.0;
    }
    return 0;
}

static sp_csc *diagonal(void)
{
    sp_builder *b = sp_builder_create(N, N, N);
    for (int i = 0; i < N; i++)
        sp_builder_add(b, i, i, 1.0);
    sp_csc *P = sp_builder_finish(b, NULL);
    sp_builder_free(&b);
    return P;
}

static dae_solver *start(sp_csc *P, sp_csc *Pp)
{
    dae_problem dp = {0};
    dp.n = N;
    dp.res = res;
    dp.jac = jac;
    dp.jac_y_pattern = P;
    dp.jac_yp_pattern = Pp;
    dae_options opt;
    dae_options_default(&opt);
    opt.rtol = 1e-8;
    opt.atol = 1e-10;
    bg_error err = {0};
    dae_solver *s = dae_create(&dp, &opt, &err);
    double y0[N], yp0[N];
    for (int i = 0; i < N; i++)
        y0[i] = 1.0, yp0[i] = -K[i];
    if (s && dae_init(s, 0.0, y0, yp0) != BG_OK) dae_free(&s);
    return s;
}

static int same_bits(double a, double b)
{
    return memcmp(&a, &b, sizeof a) == 0;
}

int main(void)
{
    sp_csc *P = diagonal(), *Pp = diagonal();
    dae_solver *full = start(P, Pp), *part = start(P, Pp);
    if (!full || !part) {
        tap_ok(0, "the solvers start");
        return tap_done();
    }
    const int sel[2] = {1, 4};
    tap_ok(dae_set_output_unknowns(part, sel, 2) == BG_OK, "unknowns 1 and 4 selected");

    /* dae_solve_to at the output times, the whole state against the selection */
    int same = 1, kept = 1, st = 0;
    double worst = 0;
    for (int k = 1; k <= NOUT && st >= 0; k++) {
        double t = k * DT, ta = 0, tb = 0, ya[N], ypa[N], yb[N], ypb[N];
        for (int i = 0; i < N; i++)
            yb[i] = ypb[i] = SENTINEL;
        st = dae_solve_to(full, t, &ta, ya, ypa);
        if (st >= 0) st = dae_solve_to(part, t, &tb, yb, ypb);
        if (st < 0 || ta != tb) break;
        for (int i = 0; i < N; i++) {
            int in = i == sel[0] || i == sel[1];
            if (in) {
                same &= same_bits(ya[i], yb[i]) && same_bits(ypa[i], ypb[i]);
                double e = exp(-K[i] * ta);
                worst = fmax(worst, fabs(yb[i] - e) / (1e-10 + 1e-8 * e));
            } else {
                kept &= yb[i] == SENTINEL && ypb[i] == SENTINEL;
            }
        }
    }
    tap_ok(st >= 0, "both runs reach t = %g", NOUT * DT);
    tap_ok(same, "the selected unknowns' values and derivatives are bitwise the whole state's");
    tap_ok(kept, "the unknowns not selected are left as they were");
    tap_ok(dae_get_stats(full)->steps == dae_get_stats(part)->steps &&
               dae_get_stats(full)->newton_iters == dae_get_stats(part)->newton_iters,
           "the same steps (%ld) and Newton iterations (%ld)", dae_get_stats(part)->steps,
           dae_get_stats(part)->newton_iters);
    tap_ok(worst < 10, "y_1 and y_4 within 10 tolerances of exp(-k t) (%.3g)", worst);

    /* dae_step: the end of each step, against dae_dense there */
    same = 1, kept = 1;
    for (int k = 0; k < 20 && st >= 0; k++) {
        double t = 0, yb[N], ypb[N], yd[N], ypd[N];
        for (int i = 0; i < N; i++)
            yb[i] = ypb[i] = SENTINEL;
        st = dae_step(part, 10.0, &t, yb, ypb);
        if (st < 0 || dae_dense(part, t, yd, ypd) != BG_OK) {
            st = -1;
            break;
        }
        for (int i = 0; i < N; i++) {
            if (i == sel[0] || i == sel[1])
                same &= same_bits(yd[i], yb[i]) && same_bits(ypd[i], ypb[i]);
            else
                kept &= yb[i] == SENTINEL && ypb[i] == SENTINEL;
        }
    }
    tap_ok(st >= 0 && same && kept,
           "dae_step returns the selected unknowns as dae_dense gives them, the rest untouched");

    /* back to the whole state */
    double y[N], yp[N], t = 0;
    for (int i = 0; i < N; i++)
        y[i] = yp[i] = SENTINEL;
    tap_ok(dae_set_output_unknowns(part, NULL, 0) == BG_OK &&
               dae_solve_to(part, dae_current_time(part), &t, y, yp) >= 0 && y[0] != SENTINEL &&
               yp[5] != SENTINEL,
           "m = 0: the whole state again");

    /* refused */
    const int bad[2] = {2, N};
    int rc = dae_set_output_unknowns(part, bad, 2);
    tap_ok(rc == BG_ERR_ARGUMENT && strstr(dae_get_error(part)->message, "unknown 6 (entry 1)"),
           "an index outside 0 .. n-1 refused, named: %s", dae_get_error(part)->message);
    rc = dae_set_output_unknowns(part, sel, -1);
    tap_ok(rc == BG_ERR_ARGUMENT && dae_set_output_unknowns(NULL, sel, 2) == BG_ERR_ARGUMENT,
           "m < 0 and a NULL solver refused");

    dae_free(&full);
    dae_free(&part);
    sp_csc_free(&P);
    sp_csc_free(&Pp);
    return tap_done();
}
