/* The rotary crane of the crane paper (docs/crane.md) as a bond-graph model: scene parameters, the
 * builder, and the quantities the program writes.
 *
 * Parts (each built only if the scene asks for it): rotary platform (rigid body on a revolute
 * joint about Z0 at A, driven through the joint's drive port), boom (a chain of co-rotational
 * beam elements, or one rigid body when boom_elements = 0) hinged to the platform at B about the
 * platform's y axis, suspension ties (truss) from the boom tip to a gantry top on the platform,
 * rope (tension only) from the boom tip to the load, load and counterweight point masses, gravity,
 * and the drive: PID -> variable-displacement pump -> closed circuit (two line volumes, leakage)
 * -> hydraulic motor -> motor inertia -> gear -> platform, following the paper's trapezoidal
 * reference (Eq. 8); or, without hydraulics, the platform's rotation rate prescribed as the
 * reference itself.
 *
 * Units: SI (m, kg, s, N, Pa). Frames: global Z0 up; the platform frame coincides with the global
 * one at theta = 0. */
#ifndef CRANE_MODEL_H
#define CRANE_MODEL_H

#include <stdio.h>

#include "bg_dae.h"
#include "bgr_model.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct crane_scene {
    char name[64];
    /* gravity */
    double g;
    /* platform */
    double platform_mass, platform_inertia[3]; /* principal, about its mass centre (kg m^2) */
    double platform_com[3];                    /* mass centre in the platform frame */
    double joint_A[3];                         /* slewing joint on the axis, global */
    /* boom */
    int boom_elements;                   /* 0: one rigid body */
    int boom_consistent;                 /* 1: the consistent beam element (mech_beam.h) */
    int boom_quartic;                    /* 1: the quartic beam element (mech_beam.h) */
    double boom_foot[3];                 /* B in the platform frame */
    double boom_length, boom_tip_radius; /* luffing angle from the tip's distance to the axis */
    double boom_E, boom_G, boom_A, boom_I_luff, boom_I_side, boom_J, boom_rho, boom_beta;
    /* ties */
    int ties;             /* 0 / 1 */
    double gantry_top[3]; /* in the platform frame */
    double tie_spread;    /* m; > 0: a pair of ties to gantry_top -/+ (0, spread, 0); 0: one */
    double tie_E, tie_A;  /* each tie */
    double tie_rho;       /* kg/m^3; > 0: each tie's mass rho A L0 lumped half at its ends (the
                           * tip half into the boom's tip, the gantry half counted in the
                           * platform's mass); 0: massless */
    double tie_beta;      /* s; stiffness-proportional damping of each tie, c = beta E A / L0 */
    /* rope and load */
    int rope;
    double rope_length, rope_E, rope_A, rope_damping;
    double load_mass;
    /* counterweight */
    int counterweight;
    double cw_mass, cw_pos[3]; /* in the platform frame */
    /* drive */
    int hydraulics;                          /* 0: the platform's rate is prescribed (reference) */
    double pump_speed, pump_disp, pump_leak; /* rad/s, m^3/rev at x = 1, m^3/(s Pa) */
    double motor_disp, motor_leak, motor_inertia, gear_ratio;
    double line_volume, bulk_modulus, charge_pressure;
    double relief_pressure; /* Pa, cross-port relief valves crack at this pressure
                             * difference (full flow 5 MPa above); with them, check valves
                             * from the charge pressure keep both lines above it. 0: none */
    double pump_servo_bw;   /* Hz; > 0: the pump's swash plate follows the PID's command as a
                             * first-order lag of this bandwidth (hyd_pump_servo); 0: at once */
    double kp, kd, ki;      /* the paper's PID (x = fraction of the pump's displacement) */
    double kd_filter;       /* s; > 0: the derivative term acts on a filtered rate
                             * (ctl_pid derivative_filter); 0: on the measured acceleration
                             * (the paper's law, an index-2 quantity) */
    double x_limit;         /* |x| <= x_limit (smooth); 0: none */
    /* reference (Eq. 8): ramp time, plateau end, stop time, plateau rate */
    double ref_t1, ref_t2, ref_t3, ref_rate;
    /* equilibrium */
    int static_start; /* 1: start from the static equilibrium under gravity */
    /* solver and output */
    double t_end, rtol, atol, output_step;
    int nominal_scales; /* 1: the unknowns' nominal magnitudes from the components' scales (the
                         * absolute tolerance of unknown i is atol * nominal_i: a millionth of a
                         * pressure's 35 MPa, of a beam force's 0.85 MN, ... with atol = 1e-6);
                         * 0: all 1, atol in SI units for every unknown (the old behaviour) */
    /* nominal magnitudes of the unknowns that no parameter gives a size (with nominal_scales;
     * 0: 1 in SI units): positions and the members' stretch vectors (m; a member keeps its
     * length if that is larger), velocities (m/s), angular velocities (rad/s) */
    double nominal_length, nominal_velocity, nominal_angular_velocity;
    int stability_guard; /* 1: dae_options.stability_guard, the order lowered to 2 where the
                          * boom's and the lines' undamped fast modes hold BDF orders 3..5 at
                          * their stability limit (numerical dissipation of those modes); 0: the
                          * order follows the error estimates alone */
    int max_order;       /* dae_options.max_order: the highest BDF order, 1..5 (orders 3..5 are
                          * not A-stable: lightly damped modes can hold them at their stability
                          * limits at tight tolerances) */
    double newton_dgmax; /* dae_options.newton_dgmax: the Newton matrix refactored from the
                          * saved Jacobian when 1/cj moved by more than this (0: off) */
    int newton_jac_age;  /* dae_options.newton_jac_age: the Jacobian evaluated again after this
                          * many steps or a Newton failure (0, or newton_dgmax = 0: IDA's
                          * rule on cj) */
    int newton_index2_scale_h; /* dae_options.newton_index2_scale_h: index-2 unknowns weigh h
                                * times less in the Newton convergence test */
} crane_scene;

/* The paper scene's defaults (docs/crane.md, with the choices stated there and in
 * crane/scenes/paper.ini). */
void crane_scene_default(crane_scene *s);

typedef struct crane crane;

/* Builds and compiles the model; NULL with the reason in err. */
crane *crane_build(const crane_scene *s, bg_error *err);
void crane_free(crane **c);
bgr_model *crane_model(crane *c);
/* bgr_dae_problem of the crane's model with the scene's tolerance convention: the unknowns'
 * nominal magnitudes when [solver] nominal_scales is on, none (p->nominal NULL: atol in SI
 * units) when it is off. The model keeps its magnitudes either way: the static solve scales
 * its own iteration by them. BG_OK or bgr_dae_problem's status. */
int crane_dae_problem(crane *c, dae_problem *p);
/* Breakpoints of the reference in (0, t_end] (at most max), count returned. */
int crane_breakpoints(const crane *c, double *t, int max);

/* Static equilibrium under gravity at t = 0 (the model itself at rest: the drive holds the
 * platform, everything else in equilibrium), found by the static solver with the ties'
 * unstretched length corrected until the tip is at boom_tip_radius from the axis, then verified
 * (crane_static.h: crane_static_start, of which this is the short form; the errors name the
 * scene keys that cannot be met together, status CRANE_ERR_START). The model is rebuilt with
 * the corrected ties (call crane_model again afterwards) and the equilibrium becomes its initial
 * values (bgr_y0); the deflection outputs are measured from this static tip. BG_OK or a status
 * with err. */
int crane_settle(crane *c, bg_error *err);
/* The same by a damped settling run (the start before the static solver, kept for comparison):
 * the platform held by a zero drive rate, extra damping in boom, ties, rope and on the load, 60
 * s of simulated settling, the ties corrected to 1e-5 of the radius; no verification. */
int crane_settle_damped(crane *c, bg_error *err);
/* Hooks of the static start (crane_static.c): the model built with the ties' unstretched length
 * tie_L0 (0: geometric); moving *from into c (c's model freed, *from NULL); boom tip and foot
 * (global) at the state y; the deflection outputs' reference tip taken from bgr_y0; the scene. */
crane *crane_build_ties(const crane_scene *s, double tie_L0, bg_error *err);
void crane_replace(crane *c, crane **from);
void crane_tip_foot(const crane *c, const double *y, double *tip, double *foot);
void crane_set_reference_tip(crane *c);
const crane_scene *crane_get_scene(const crane *c);
/* 1 if the scene's load hangs on the rope and weighs no more than the rounding of the rope's
 * force at its rest length, DBL_EPSILON k eps ln 2 (the tension-only rope is smoothed at slack,
 * mech_axial.h; eps = 1e-4 L0): g = 0, or a load of, say, 1e-300 kg. Such a load carries
 * nothing; crane_static_start hangs it at rest after the crane's static solve. */
int crane_load_weightless(const crane_scene *s);
/* Unstretched length of the ties (geometric until crane_settle corrects it); 0 without ties. */
double crane_tie_length(const crane *c);

/* The output quantities, in the order of crane_output_names. */
#define CRANE_NOUT 20
/* t, theta, theta_ref, omega, omega_ref, omega_err = omega_ref - omega, alpha_err = alpha_ref -
 * alpha, tip_x/y/z, tip_defl_1/2 (tip displacement from the static tip carried round by theta,
 * along the boom's transverse directions in and out of the luffing plane), load_x/y/z,
 * rope_force, pump_x (the pump's displacement, a fraction of its full: the swash plate's
 * position, which follows the PID's command through the actuator of [hydraulics]
 * pump_servo_bandwidth, or the command itself without one), p_high, p_low,
 * constraint_drift (distance between the hinge point on the platform and the boom's foot: the
 * joints hold at velocity level). NaN for parts a scene lacks. */
extern const char *const crane_output_names[CRANE_NOUT]; /* "t [s]", "theta [rad]", ... */
/* Index in crane_output_names of the output called key (the name without its unit: "tip_x"),
 * -1 if none or key is NULL. */
int crane_output_index(const char *key);
void crane_outputs(const crane *c, double t, const double *y, const double *yp, double *out);
/* The unknowns crane_outputs reads of y and yp (CRANE_MAX_OUTPUT_UNKNOWNS at most) into idx,
 * some more than once: the angles, rates and references, the boom's tip and foot, the
 * platform's position and orientation, the load, the rope's stretch vector and the velocities
 * of its ends (mech_axial.h: the tension is T(L, L')), the pump and the pressures. Their count,
 * 0 for c or idx NULL. A loop that writes only the outputs interpolates these alone
 * (dae_set_output_unknowns). */
#define CRANE_MAX_OUTPUT_UNKNOWNS 64
int crane_output_unknowns(const crane *c, int *idx);

/* Mechanical energies at a state y: kinetic (platform, boom nodes or rigid boom, load,
 * counterweight), potential of gravity, elastic (beam elements, ties, rope). The hydraulic
 * drive's energies (motor inertia, oil compression) are not included. BG_OK or a status. */
int crane_energy(const crane *c, const double *y, double *kinetic, double *potential,
                 double *elastic);
/* Power the structural damping dissipates at a state y (boom elements, ties, rope; >= 0): with
 * crane_energy, the drive's work equals the change of energy plus the time integral of this. */
double crane_dissipation(const crane *c, const double *y);
/* Power delivered into the slewing joint's drive port (torque times relative rate). */
double crane_drive_power(const crane *c, const double *y);

/* Model statistics beside the paper's Table 2, and the counts by component. */
int crane_stats_print(const crane *c, FILE *f);

/* Positions and forces at a state, for the 3-D output (crane_vtk.h) and the animation
 * (crane_anim.h). Global frame (Z0 up, the scene's origin), SI units (m, kg, N, N m, Pa). */
#define CRANE_MAX_NODES 513 /* boom nodes: at most 512 beam elements + 1 */
typedef struct crane_geom {
    double t, theta, omega; /* s, platform angle (rad) and rate (rad/s) */
    double platform_x[3];   /* the platform's mass centre */
    double platform_R[9];   /* its orientation, platform frame to global (column-major) */
    double joint_A[3];      /* slewing joint on the axis */
    /* outline of the platform's deck: a rectangle in the platform's plane through A spanning
     * the points fixed to the platform (A, hinge, gantry, counterweight) with 1 m margins,
     * corners counter-clockwise seen from above */
    double deck[4][3];
    double hinge[3];      /* boom hinge B on the platform */
    double gantry_top[3]; /* the scene's gantry top */
    int ngantry;          /* upper tie ends: 2 for a spread pair of ties, else 1 (the top) */
    double gantry[2][3], gantry_base[2][3]; /* and the points below them in the deck's plane */
    /* boom: nodes from the foot (0) to the tip (nodes - 1), boom_elements + 1 of them, or foot
     * and tip of a rigid boom (2) */
    int nodes, beam; /* beam: 1 with beam elements (section forces given), 0 rigid boom */
    double node[CRANE_MAX_NODES][3];
    /* displacement from the node's start position (the static equilibrium with static_start)
     * carried round by theta about the axis through A, and its components along the boom's
     * transverse directions as tip_defl_1 (in the luffing plane) and tip_defl_2 (sideways,
     * y at theta = 0): at the tip node these are crane_outputs' tip_defl_1/2 */
    double defl[CRANE_MAX_NODES][3], defl_luff[CRANE_MAX_NODES], defl_side[CRANE_MAX_NODES];
    /* section force and moment (about the node) that the boom's tip side exerts on its foot
     * side at the node, from the beam elements' port loads (mean of the two elements at an
     * inner node); global, and their components along the boom's local directions b1 (along
     * the boom, foot to tip: the axial force, tension > 0; torsion), b2 (normal to the boom in
     * the luffing plane, up and outwards) and b3 (sideways: y at theta = 0): a moment about b3
     * bends the boom in the luffing plane, one about b2 sideways. 0 for a rigid boom. */
    double force[CRANE_MAX_NODES][3], moment[CRANE_MAX_NODES][3];
    double force_local[CRANE_MAX_NODES][3], moment_local[CRANE_MAX_NODES][3];
    int nties; /* 0, 1 or 2; tie k runs from gantry[k] (or gantry_top for one) to the tip */
    double tie_tension[2];
    int rope; /* the rope runs from the tip to the load */
    double load[3], load_mass, rope_tension;
    int counterweight;
    double cw[3], cw_mass;
    double pump_x, p_high, p_low; /* NaN without hydraulics */
} crane_geom;
/* Fills g (about 120 kB: allocate it once) at the state y, yp at time t (yp is not used yet).
 * BG_OK, or BG_ERR_ARGUMENT for a NULL pointer. */
int crane_geometry(const crane *c, double t, const double *y, const double *yp, crane_geom *g);

#ifdef __cplusplus
}
#endif
#endif
