/* The damped settling start (crane_model.h: crane_settle_damped), the static start before the
 * static solver, kept for comparison; and the hooks the static start (crane_static.c) builds
 * on: the model moved in, the boom's ends, the deflections' reference tip. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "crane_model_impl.h"

/* Settling: the platform held (drive rate 0), extra damping in the boom, ties, rope and on the
 * load; integrated until the motion has died out. */
#define SETTLE_TIME 60.0

/* Settles the model sc; y receives its final state (bgr_n(sc->m) values). */
static int settle_run(crane *sc, double *y, bg_error *err)
{
    int n = bgr_n(sc->m), status;
    double *yp = malloc((size_t)(n > 0 ? n : 1) * sizeof *yp), tret;
    dae_problem p;
    dae_options o;
    dae_solver *sol = NULL;
    if (!yp || bgr_dae_problem(sc->m, &p) != BG_OK) {
        free(yp);
        return bg_error_raise(err, BG_ERR_MEMORY, "crane_settle", "out of memory");
    }
    dae_options_default(&o);
    o.rtol = 1e-6;
    o.atol = 1e-6;
    o.exclude_alg = 1;
    o.max_steps = 1000000;
    sol = dae_create(&p, &o, err);
    if (!sol) {
        free(yp);
        return err && err->status < 0 ? err->status : BG_ERR_ARGUMENT;
    }
    if ((status = dae_init(sol, 0.0, bgr_y0(sc->m), bgr_yp0(sc->m))) != BG_OK ||
        (status = dae_consistent_init(sol)) < 0 ||
        (status = dae_solve_to(sol, SETTLE_TIME, &tret, y, yp)) < 0) {
        status = status < 0 ? status : BG_ERR_ARGUMENT;
        bg_error_raise(err, status, "crane_settle", "static equilibrium: %s",
                       dae_get_error(sol)->message);
    } else {
        status = BG_OK;
    }
    dae_free(&sol);
    free(yp);
    return status;
}

/* The tip's distance from the slewing axis. */
static double tip_radius(const crane *c, const double *y, double *tip)
{
    double foot[3];
    boom_ends(c, y, tip, foot);
    return hypot(tip[0] - c->s.joint_A[0], tip[1] - c->s.joint_A[1]);
}

/* The damped settling run, the static start before the static solver (crane_static.c); kept for
 * comparison (crane_settle_damped in crane_model.h). */
int crane_settle_damped(crane *c, bg_error *err)
{
    crane *sc = NULL;
    double *y = NULL, L0 = c->tie_L0, R = c->s.boom_tip_radius;
    int status = BG_OK;
    /* The ties stretch under load and the boom bends: the unstretched tie length is corrected
     * until the settled tip is at the scene's radius (a rigid rotation about the hinge gives the
     * change of tie length per change of radius). */
    for (int it = 0; it < 8; it++) {
        crane_free(&sc);
        free(y);
        y = NULL;
        sc = crane_build_model(&c->s, 1, L0, err);
        if (!sc) return err && err->status < 0 ? err->status : BG_ERR_ARGUMENT;
        y = malloc((size_t)(bgr_n(sc->m) > 0 ? bgr_n(sc->m) : 1) * sizeof *y);
        if (!y) {
            status = bg_error_raise(err, BG_ERR_MEMORY, "crane_settle", "out of memory");
            goto done;
        }
        if ((status = settle_run(sc, y, err)) != BG_OK) goto done;
        if (!c->s.ties) break;
        double tip[3], r = tip_radius(sc, y, tip);
        if (fabs(r - R) <= 1e-5 * R) break;
        double dx = tip[0] - c->s.boom_foot[0], dz = tip[2] - c->s.boom_foot[2], u[3], L;
        gantry_point(&c->s, 0, c->nties, u);
        sub3(tip, u, u);
        L = sqrt(mech_dot(u, u));
        /* rotation dphi about the hinge's y axis: d tip = dphi (dz, 0, -dx) */
        double dLdr = (u[0] * dz - u[2] * dx) / (L * dz);
        L0 += dLdr * (R - r);
    }
    if (L0 != c->tie_L0) { /* rebuild with the corrected ties */
        crane *nc = crane_build_model(&c->s, 0, L0, err);
        if (!nc) {
            status = err && err->status < 0 ? err->status : BG_ERR_ARGUMENT;
            goto done;
        }
        bgr_model_free(&c->m);
        *c = *nc;
        free(nc);
    }
    /* copy the states by name (velocities and momenta are ~0 after the damping) */
    {
        const int *kinds = bgr_kinds(sc->m);
        double *y0 = bgr_y0(c->m);
        for (int i = 0; i < bgr_n(sc->m); i++) {
            if (kinds[i] != DAE_DIFF) continue;
            int j = bgr_find_var(c->m, bgr_var_name(sc->m, i));
            if (j >= 0) y0[j] = y[i];
        }
        tip_radius(c, y0, c->tip0);
    }
done:
    free(y);
    crane_free(&sc);
    return status;
}

void crane_replace(crane *c, crane **from)
{
    if (!c || !from || !*from) return;
    bgr_model_free(&c->m);
    *c = **from;
    free(*from);
    *from = NULL;
}

void crane_tip_foot(const crane *c, const double *y, double *tip, double *foot)
{
    boom_ends(c, y, tip, foot);
}

void crane_set_reference_tip(crane *c)
{
    tip_radius(c, bgr_y0(c->m), c->tip0);
}
