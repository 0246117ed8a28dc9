/* The crane's static start, its checks, and the crane's two analyses besides the dynamic run
 * (crane --static, crane --modes): the static equilibrium (solver/bg_static.h) and the modes
 * (solver/bg_modes.h) of the crane model.
 *
 * Static start (crane_static_start). The dynamic model itself is brought to rest at t = 0: the
 * static solver's continuation from the crane as assembled (boom straight at the scene's luffing
 * angle, ties and rope unstretched, lines and their ports at the charge pressure) ramps gravity
 * in (the Newton homotopy, bg_static.h); the hydraulic drive holds the platform (the motor at
 * rest, the PID's integral supplying the leakage flow), the velocity-level joints stay closed.
 * First the integral's holding value: solves with the ties at their geometric length, each
 * starting the integral from the last one's value, until the platform rests within 1e-12 rad of
 * theta = 0 (two solves; the value is reported, pid_integral0). Then, the integral held there,
 * the ties' unstretched length is trimmed until the tip is at the scene's radius to 1e-9 of it,
 * by the trim of the model files (solver/bg_trim.h: the secant from the geometric length, then
 * Illinois on a bracket 1 % below it: a steel tie breaks at about 1 % strain), each trial a
 * static solve of the crane built with that length (a few milliseconds with 16 boom elements,
 * 0.4 s with 512); the last one built is the start. crane/models/paper.yaml states the same procedure in the format (its trim, its
 * pid_integral0), and the two starts agree to the last bit (tests/crane/test_crane_model_file).

 * Checks, with their tolerances (crane_start_report; crane --static writes them to static.txt):
 *   - the static solve reached the full load (load factor 1) and a state at rest;
 *   - the tip at the scene's radius: |r - tip_radius| <= 1e-6 max(tip_radius, 1 m);
 *   - the boom above its foot (tip higher than the foot) and straight: no node farther than
 *     5 % of the boom's length from the line foot - tip (a buckled boom fails);
 *   - the load above the ground: its height above the slewing joint A's (the crane's base) > 0
 *     (the keys named: the rope's stiffness when it is strained beyond 5 %, else the geometry
 *     and the ground's height [platform] joint_A);
 *   - the ties in tension (a truss also carries compression: a tie anchored where it can only
 *     push would be a strut, which a tie or pendant is not), or slack within the rounding of
 *     their force, E A DBL_EPSILON (an unloaded crane);
 *   - every body at rest: the kinetic energy of platform, boom, load and counterweight at most
 *     1e-6 J.
 * A load whose weight is below the rounding of the rope's force at its rest length
 * (crane_load_weightless: DBL_EPSILON k eps ln 2, mech_axial.h; g = 0, a 1e-300 kg load) has no
 * equilibrium on the tension-only rope, smoothed at slack, that a solve can resolve, and
 * carries nothing: the procedure above runs on the crane without rope and load, which are then
 * hung at rest on it (the rope's force equal to the load's weight, or with g = 0 to the rounding
 * of its force at rest length: the rope slack).
 * A check that fails gives CRANE_ERR_START with a message naming the scene keys that cannot be
 * met together ("[ties] gantry_top, [boom] tip_radius, [load] mass") and what was found; the
 * state reached stays in the model (for equilibrium.csv). */
#ifndef CRANE_STATIC_H
#define CRANE_STATIC_H

#include <stdio.h>

#include "bg_modes.h"
#include "bg_static.h"
#include "crane_model.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The scene's keys cannot be met together (the program's exit status 2). */
#define CRANE_ERR_START (-100)

typedef struct crane_start_report {
    dae_static_result solve; /* the last static solve */
    int solves;              /* static solves (the integral's, then one per tie length) */
    double seconds;          /* wall time of the static start */
    double tie_L0_geometric, tie_L0; /* the ties' unstretched length, geometric and corrected */
    double pid_integral0;            /* the PID's integral that holds the platform at rest */
    /* the checks */
    double radius, radius_want, radius_tol; /* tip's distance to the slewing axis (m) */
    double tip_z, foot_z;                   /* heights of tip and foot (m) */
    double straightness, straightness_tol;  /* largest node distance from the line foot-tip */
    double load_z, ground_z;                /* load's height, the base's (joint A) */
    double kinetic, kinetic_tol;            /* J */
    double hinge_gap;                       /* the hinge's position mismatch (m) */
    double tie_tension_min;                 /* N, the smaller tie tension (NaN: no ties) */
    int ok_solve, ok_radius, ok_boom, ok_load, ok_rest, ok_ties, ok;
    char keys[512];     /* the scene keys that cannot be met together, "" when the checks pass */
    char message[1024]; /* what failed, "" when the checks pass */
} crane_start_report;

/* The static start above. rep may be NULL. BG_OK, CRANE_ERR_START (a check failed: err names
 * the keys, rep has the figures) or another status with err. */
int crane_static_start(crane *c, crane_start_report *rep, bg_error *err);
/* The checks as text (static.txt). BG_OK or BG_ERR_IO. */
int crane_start_print(const crane_start_report *rep, FILE *f);
/* equilibrium.csv at the model's initial values (the static state): name, x, y, z, value, unit
 * rows: the nodes of the boom, tip and foot, load, counterweight, platform, gantry points; the
 * tensions of rope and ties; the reactions of the base (on the slewing joint) and of the boom
 * hinge (on the boom's foot), force and moment; the line pressures, the pump's setting, the
 * platform's angle; the checks' figures. BG_OK or BG_ERR_IO. */
int crane_equilibrium_write(const crane *c, const crane_start_report *rep, FILE *f);

/* Modes of the crane at time T: at the static start (T = 0: the model's initial values), else
 * after a dynamic run from it to T with the scene's tolerances (landing on T). Dense for up to
 * 1200 differential unknowns (every mode, all kinds), else the lowest 20 elastic modes by ARPACK.
 * *out as dae_modes_compute (free it with dae_modes_free); y receives the state (bgr_n values, may
 * be NULL). BG_OK or a status with err. */
int crane_modes(crane *c, double T, dae_modes **out, double *y, bg_error *err);
/* Drift modes. The static start is an equilibrium: there the invariants the velocity-level
 * constraints leave (the quaternions' norms, the nodes' positions against their bodies) give
 * exact zero eigenvalues, constraint modes (bg_modes.h). At a state of the run (T > 0) the
 * model is linearised at a state in motion, and those eigenvalues move off zero by the
 * motion's rates: real or complex, some with negative damping, 1e-7 to 5e-4 Hz for the paper
 * scene, where its slowest physical mode (the drive's PID) is at 0.032 Hz at every T. They are
 * no motion of the crane: an elastic mode at T slower than CRANE_DRIFT_RATIO times the slowest
 * elastic mode of the static start is classed as drift (reported apart: modes.csv's kind
 * "drift", the summary's count, not plotted). *hz receives that bound (0 for T = 0: none); it
 * costs the modes at the static start once more. BG_OK or the failure of those modes. */
#define CRANE_DRIFT_RATIO 0.1
int crane_modes_drift(crane *c, double T, double *hz, bg_error *err);
/* The part a mode belongs to: the component under crane/ with the largest share ("boom",
 * "hydraulics", "load", "ties", "rope", "platform", ...; the left and right ties together).
 * Writes into buf, returns buf. */
const char *crane_mode_part(const dae_modes *M, int k, char *buf, size_t size);
/* modes.csv is the programs' writer (runner/rn_run.h: rn_modes_write with crane_mode_part). */
/* modes.gp: the elastic modes' damping ratio against frequency (log scale), one colour per part,
 * the lowest labelled, into modes.png, from modes.csv (the drift modes below drift_hz left
 * out). BG_OK or BG_ERR_IO. */
int crane_modes_plot_script(const dae_modes *M, const char *scene, double T, double drift_hz,
                            FILE *f);

#ifdef __cplusplus
}
#endif
#endif
