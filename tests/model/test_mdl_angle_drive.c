/* The prescribed-angle joint in model files (mech.revolute_angle, mech_parts.h):
 * examples/models/driven-pendulum.yaml (theta_ref = A sin(w t) from a sig.sine) against the
 * closed forms theta(t) = theta_ref(t) (the bob's geometric angle, from its quaternion) and
 * tau = I_h theta'' + m g l sin(theta); a point-to-point move whose rate is a trapezoid
 * (sig.trapezoid, output integral) against the trapezoid's area and the static torque at rest;
 * the projection the file's options switch on; and the refusal of a profile that is not a
 * signal source's value or integral. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bg_dae.h"
#include "mdl_model.h"
#include "tap.h"

#ifndef MODELS_DIR
#define MODELS_DIR "examples/models"
#endif

#define PI 3.14159265358979323846
static const double m = 2.0, l = 0.5, Jz = 0.05, g = 9.81;

static int col(const mdl_model *mm, const char *name)
{
    for (int i = 0; i < mdl_noutputs(mm); i++)
        if (!strcmp(mdl_output_name(mm, i), name)) return i;
    return -1;
}

/* Runs mm with the file's options to each multiple of dt up to T; calls check at each. */
typedef void (*check_fn)(void *ctx, double t, const double *out);
static int run(mdl_model *mm, double dt, double T, check_fn check, void *ctx, dae_options *used)
{
    bg_error e = {0};
    bgr_model *bm = mdl_bgr(mm);
    dae_problem p;
    dae_options o;
    double *bk = NULL;
    if (mdl_dae_problem(mm, &p) != BG_OK || mdl_dae_options(mm, &o, &bk) != BG_OK) return -1000;
    *used = o;
    dae_solver *s = dae_create(&p, &o, &e);
    int rc = s ? dae_init(s, 0, bgr_y0(bm), bgr_yp0(bm)) : -1000;
    if (rc == BG_OK || rc == DAE_WARNING) rc = dae_consistent_init(s);
    int n = bgr_n(bm);
    double *y = calloc((size_t)n, sizeof *y), out[8], tr;
    for (int k = 1; rc >= 0 && k * dt <= T + 1e-9; k++) {
        rc = dae_solve_to(s, k * dt, &tr, y, NULL);
        if (rc < 0) break;
        mdl_outputs(mm, tr, y, out, &e);
        check(ctx, tr, out);
    }
    if (rc < 0 && s) tap_diag("solver: %s", dae_get_error(s)->message);
    dae_free(&s);
    free(bk);
    free(y);
    return rc;
}

typedef struct sine_ctx {
    int iq0, iq3, itau;
    double A, w, angle_err, tau_err, tau_max;
} sine_ctx;

static void sine_check(void *c, double t, const double *out)
{
    sine_ctx *s = c;
    double ref = s->A * sin(s->w * t), th = 2 * atan2(out[s->iq3], out[s->iq0]);
    double tau = (Jz + m * l * l) * (-s->A * s->w * s->w * sin(s->w * t)) + m * g * l * sin(ref);
    s->angle_err = fmax(s->angle_err, fabs(remainder(th - ref, 2 * PI)));
    s->tau_err = fmax(s->tau_err, fabs(out[s->itau] - tau));
    s->tau_max = fmax(s->tau_max, fabs(tau));
}

typedef struct move_ctx {
    int iq0, iq3, itau;
    double end_angle, end_tau, ramp_err;
} move_ctx;

/* the trapezoid 0 -> 0.5 over [0, 1], 0.5 until 3, -> 0 at 4: its integral */
static double move_ref(double t)
{
    if (t <= 1) return 0.25 * t * t;
    if (t <= 3) return 0.25 + 0.5 * (t - 1);
    if (t <= 4) return 1.5 - 0.25 * (4 - t) * (4 - t);
    return 1.5;
}

static void move_check(void *c, double t, const double *out)
{
    move_ctx *s = c;
    double th = 2 * atan2(out[s->iq3], out[s->iq0]);
    s->ramp_err = fmax(s->ramp_err, fabs(th - move_ref(t)));
    s->end_angle = th;
    s->end_tau = out[s->itau];
}

static const char *move_text =
    "format: bgsim 1\n"
    "name: move\n"
    "components:\n"
    "  ground: {type: mech.support, dim: 6}\n"
    "  profile: {type: sig.trapezoid, t0: 0, t1: 1, t2: 3, t3: 4, height: 0.5, output: %s}\n"
    "  hinge: {type: mech.revolute_angle, axis: [0, 0, 1], body: bob, angle: profile.y}\n"
    "  bob:\n"
    "    type: mech.body\n"
    "    mass: 2\n"
    "    inertia: [0.1, 0, 0,  0, 0.08, 0,  0, 0, 0.05]\n"
    "    gravity: [0, -9.81, 0]\n"
    "    points: {hinge: {r: [0, 0.5, 0], dim: 6}}\n"
    "    position: [0, -0.5, 0]\n"
    "bonds:\n"
    "  - ground.p -> hinge.a\n"
    "  - hinge.b -> bob.hinge\n"
    "outputs: {q0: bob.q0, q3: bob.q3, torque: hinge.torque}\n"
    "solver: {t_end: 6, output_step: 0.05, rtol: 1e-6, atol: 1e-8}\n";

int main(void)
{
    bg_error e = {0};
    mdl_model *mm = mdl_load(MODELS_DIR "/driven-pendulum.yaml", NULL, 0, &e);
    tap_ok(mm != NULL, "driven-pendulum.yaml loads (%s)", mm ? "ok" : e.message);
    if (mm) {
        sine_ctx s = {col(mm, "q0"), col(mm, "q3"), col(mm, "torque"), 0.8, PI, 0, 0, 0};
        dae_options o;
        int rc = run(mm, 0.05, 20, sine_check, &s, &o);
        tap_diag("driven pendulum, 20 s: angle err %.2e rad, torque err %.2e of %.3g N m",
                 s.angle_err, s.tau_err / s.tau_max, s.tau_max);
        tap_ok(o.projection == 1, "the file's options project onto the position invariants");
        tap_ok(rc >= 0 && s.angle_err < 1e-9,
               "the bob's geometric angle follows 0.8 sin(pi t) (err %.2e rad)", s.angle_err);
        tap_ok(rc >= 0 && s.tau_err < 1e-4 * s.tau_max,
               "the hinge's torque signal is I_h theta'' + m g l sin(theta) (err %.2e)",
               s.tau_err / s.tau_max);
        mdl_free(&mm);
    }

    char text[2048];
    snprintf(text, sizeof text, move_text, "integral");
    mm = mdl_load_string(text, "move.yaml", NULL, 0, &e);
    tap_ok(mm != NULL, "a point-to-point move (trapezoid rate, output integral) loads (%s)",
           mm ? "ok" : e.message);
    if (mm) {
        move_ctx s = {col(mm, "q0"), col(mm, "q3"), col(mm, "torque"), 0, 0, 0};
        dae_options o;
        int rc = run(mm, 0.05, 6, move_check, &s, &o);
        tap_diag("move: end angle %.15f, torque at rest %.9f, largest error on the way %.2e",
                 s.end_angle, s.end_tau, s.ramp_err);
        tap_ok(rc >= 0 && fabs(s.end_angle - 1.5) < 1e-9 && s.ramp_err < 1e-9,
               "the angle is the trapezoid's integral on the way and its area 1.5 rad at the end "
               "(err %.2e)",
               s.ramp_err);
        tap_close(s.end_tau, m * g * l * sin(1.5), 1e-6, 0,
                  "at rest the torque holds the weight: m g l sin(1.5)");
        mdl_free(&mm);
    }

    snprintf(text, sizeof text, move_text, "rate");
    mm = mdl_load_string(text, "move.yaml", NULL, 0, &e);
    tap_ok(!mm && strstr(e.message, "hinge") && strstr(e.message, "value or integral"),
           "a profile with the output rate is refused: %s", mm ? "(loaded)" : e.message);
    mdl_free(&mm);
    return tap_done();
}
