/* Private to libcrane's model files (crane_build.c, crane_settle.c, crane_outputs.c; the
 * static start, crane_static.c, uses crane_model.h's hooks only): the crane's record, the
 * builder's entry and the small geometric helpers they share. Not installed, not for programs.
 *
 * Invariants of struct crane: m is compiled; the variable ids (v_*) are those of m, -1 where the
 * scene lacks the part; tip0 is the undeformed tip until a static start puts the static one
 * there; tie_L0 is the ties' unstretched length (geometric unless corrected). */
#ifndef CRANE_MODEL_IMPL_H
#define CRANE_MODEL_IMPL_H

#include <string.h>

#include "crane_model.h"
#include "mech_util.h"

#define MAXEL 512

struct crane {
    crane_scene s;
    bgr_model *m;
    int settle; /* built for the equilibrium: drive held, extra damping */
    int platform, slew, hinge, sensor;
    int n, nodes[MAXEL + 1], elems[MAXEL], boom; /* beam chain, or rigid boom body */
    int tie[2], nties, rope, load, cw;           /* nties: 0, 1 or 2 (a laterally spread pair) */
    int drive_bond;                              /* into the slewing joint's drive port */
    double tie_L0;                               /* unstretched tie length */
    int ref_value, ref_rate, ref_int, pid, pump, vol_h, vol_l, motor_acc;
    int prime, tanks[3], ntanks; /* the drive's sources: the prime mover, the charge tanks */
    double tip0[3], e2[3], e3[3]; /* undeformed tip, boom's transverse directions (theta = 0) */
    double tip_r[3];              /* rigid boom: tip in its body frame */
    double boom_cs[3];            /* rigid boom: its mass centre from the boom's middle */
    double foot_r[3];             /* rigid boom: foot in its body frame */
    /* variable ids of the outputs */
    int v_theta, v_omega, v_theta_ref, v_omega_ref, v_alpha_ref, v_alpha, v_x, v_ph, v_pl;
    int v_tip, v_tipq, v_load, v_plat_x, v_plat_q, v_node0;
};

/* The model of scene sc (crane_build.c): settle = 1 builds the damped settling model (drive
 * held, extra damping: crane_settle.c); tie_L0 is the ties' unstretched length (0: geometric).
 * NULL with the reason in err. */
crane *crane_build_model(const crane_scene *sc, int settle, double tie_L0, bg_error *err);

/* The physical quantity of an unknown from its path (crane_build.c), for the nominal scales and
 * their table in crane_stats_print. */
const char *crane_domain_of(const char *nm);

static inline void sub3(const double *a, const double *b, double *r)
{
    for (int i = 0; i < 3; i++)
        r[i] = a[i] - b[i];
}

/* Upper end of tie k (of nties) on the platform, platform frame: the gantry top, or with a
 * lateral spread w the points gantry_top -/+ (0, w, 0). */
static inline void gantry_point(const crane_scene *s, int k, int nties, double *p)
{
    memcpy(p, s->gantry_top, 3 * sizeof *p);
    if (nties == 2) p[1] += k == 0 ? -s->tie_spread : s->tie_spread;
}

/* A point of a body (mass centre x, orientation q) given in its body frame, in the global frame. */
static inline void body_point(const double *y, int ix, int iq, const double *r, double *p)
{
    double R[9], Rr[3];
    mech_quat_R(y + iq, R, NULL);
    mech_mv(R, r, Rr);
    for (int i = 0; i < 3; i++)
        p[i] = y[ix + i] + Rr[i];
}

/* Boom tip and boom foot (global) at the state y. */
static inline void boom_ends(const crane *c, const double *y, double *tip, double *foot)
{
    if (c->n > 0) {
        memcpy(tip, y + c->v_tip, 3 * sizeof(double));
        memcpy(foot, y + c->v_node0, 3 * sizeof(double));
    } else {
        body_point(y, c->v_tip, c->v_tipq, c->tip_r, tip);
        body_point(y, c->v_tip, c->v_tipq, c->foot_r, foot);
    }
}

#endif
