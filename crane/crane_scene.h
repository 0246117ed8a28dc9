/* Scene files of the rotary crane: INI text (parsed with inih) -> crane_scene.
 *
 * A scene file starts from crane_scene_default() (the paper scene) and changes what it states;
 * every key is optional and may appear at most once. Lines are "key = value", "[section]",
 * blank, or comments starting with ';' or '#'; an inline comment starts with " ;" (a ';' after
 * white space). Lines end with LF, CR LF or CR. Keys and section names are matched without
 * regard to case. Values:
 *   number   a finite decimal number, e.g. 76, 0.0443, 1.08e11 (not hexadecimal: "0x4c" is
 *            refused, as are "inf" and "nan")
 *   integer  decimal digits with an optional sign
 *   boolean  true/false, yes/no, on/off, 1/0
 *   vector   three numbers "x, y, z"
 *   name     1 to 63 characters of [A-Za-z0-9_.-] (it names the output folder)
 * The sections and keys mirror the fields of crane_scene (crane_model.h); the key is the field's
 * name without the section's prefix. Units are SI: m, kg, s, N, Pa, rad.
 *
 *   [scene]          name             name           results go to results/<name>/
 *   [environment]    g                number >= 0    m/s^2, gravity along -Z0
 *   [platform]       mass             number > 0     kg
 *                    inertia          vector > 0     kg m^2, principal, about the mass centre
 *                    com              vector         m, mass centre (platform frame)
 *                    joint_A          vector         m, slewing joint A on the axis (global)
 *   [boom]           elements         0..512         beam elements; 0: one rigid body
 *                    foot             vector         m, hinge B (platform frame)
 *                    length           number > 0     m
 *                    tip_radius       number >= 0    m, tip's distance to the slewing axis
 *                    E, G             number > 0     Pa, Young's and shear moduli
 *                    A                number > 0     m^2, cross-section area
 *                    I_luff, I_side   number > 0     m^4, second moments (bending in / out of
 *                                                    the luffing plane)
 *                    J                number > 0     m^4, torsion constant
 *                    rho              number > 0     kg/m^3, density
 *                    beta             number >= 0    s, stiffness-proportional damping: mode i
 *                                                    gets the damping ratio beta omega_i / 2
 *   [ties]           enabled          boolean        build the suspension ties
 *                    gantry_top       vector         m, upper end on the platform (platform frame)
 *                    spread           number >= 0    m; > 0: a pair of ties ending at gantry_top
 *                                                    -/+ (0, spread, 0); 0: one tie
 *                    E                number > 0     Pa
 *                    A                number > 0     m^2
 *                    rho              number >= 0    kg/m^3; each tie's mass rho A L0 lumped half
 *                                                    at each end (the tip's half into the boom's
 *                                                    tip; the gantry's counts in the platform's
 *                                                    mass); 0: massless
 *                    beta             number >= 0    s, stiffness-proportional damping of each tie
 *                                                    (damping coefficient beta E A / L0)
 *   [rope]           enabled          boolean        build the rope and the load
 *                    length           number > 0     m, unstretched
 *                    E                number > 0     Pa (stiffness E A / length)
 *                    A                number > 0     m^2
 *                    damping          number >= 0    N s/m
 *   [load]           mass             number > 0     kg (load with hook; built with the rope)
 *   [counterweight]  enabled          boolean
 *                    mass             number > 0     kg
 *                    pos              vector         m (platform frame)
 *   [hydraulics]     enabled          boolean        false: the platform's rate is prescribed
 *                    pump_speed       number > 0     rad/s, drive speed of the pump
 *                    pump_disp        number > 0     m^3/rev at x = 1
 *                    pump_leak        number >= 0    m^3/(s Pa)
 *                    motor_disp       number > 0     m^3/rev
 *                    motor_leak       number >= 0    m^3/(s Pa)
 *                    motor_inertia    number > 0     kg m^2
 *                    gear_ratio       number > 0     motor turns per platform turn
 *                    line_volume      number > 0     m^3, each line
 *                    bulk_modulus     number > 0     Pa
 *                    charge_pressure  number >= 0    Pa
 *                    relief_pressure  number >= 0    Pa, cross-port relief cracking (0: none;
 *                                                    with it, anti-cavitation check valves)
 *                    pump_servo_bandwidth number >= 0 Hz, the pump's displacement actuator: its
 *                                                    swash plate follows the PID's command as a
 *                                                    first-order lag (hyd_pump_servo); 0: at once.
 *                                                    With kd_filter > 0 the drive's loop is
 *                                                    unstable with any lag (docs/crane.md)
 *   [controller]     kp, kd, ki       number >= 0    PID gains (x = fraction of the pump's
 *                                                    displacement; kp 1/(rad/s), kd 1/(rad/s^2),
 *                                                    ki 1/rad)
 *                    kd_filter        number >= 0    s, time constant of the rate filter of the
 *                                                    derivative term; 0: the measured acceleration
 *                    x_limit          number >= 0    |x| <= x_limit (smooth); 0: no limit
 *   [reference]      t1, t2, t3       number >= 0    s, end of the ramp up, end of the plateau,
 *                                                    stop time (0 < t1 <= t2 < t3)
 *                    rate             number         rad/s, plateau rate
 *   [initial]        static_start     boolean        start from the static equilibrium
 *   [solver]         t_end            number > 0     s, end time
 *                    rtol             number in (0, 1)  relative tolerance
 *                    atol             number > 0     absolute tolerance
 *                    output_step      number > 0     s, output interval (<= t_end)
 *                    nominal_scales   boolean        absolute tolerances scaled by the unknowns'
 *                                                    nominal magnitudes (default true; see below)
 *                    nominal_length   number >= 0    m, the nominal magnitude of positions (a
 *                                                    member's stretch vector keeps its length if
 *                                                    larger); 0: 1 m (SI)
 *                    nominal_velocity number >= 0    m/s, of velocities; 0: 1 m/s
 *                    nominal_angular_velocity number >= 0  rad/s, of angular velocities; 0: 1
 *                    stability_guard  boolean        the solver's stability guard (default
 *                                                    false, as the paper scene; see below)
 *                    newton_dgmax     number in [0, 1)  the Newton matrix is formed again from
 *                                                    the saved Jacobian and refactored when
 *                                                    1/cj moved by more than this since it was
 *                                                    factored (default 0.3, CVODE's value;
 *                                                    0: only with a new Jacobian; bg_dae.h)
 *                    newton_jac_age   integer 0..1000000  the Jacobian is evaluated again once
 *                                                    this many steps old or after a Newton
 *                                                    failure, and the Newton rate carries from
 *                                                    step to step (applies with newton_dgmax >
 *                                                    0; default 51, CVODE's value; 0: when 1/cj
 *                                                    leaves [0.6, 1.67] of its value then, IDA's
 *                                                    rule; bg_dae.h)
 *                    newton_index2_scale_h boolean   index-2 unknowns (the hinge and joint
 *                                                    reactions, the PID's output on the
 *                                                    measured acceleration, the motor's torque)
 *                                                    weigh h times less in the Newton
 *                                                    convergence test (default true; bg_dae.h)
 * Both on in the shipped scenes since the Jacobian follows the switching elements' regimes
 * (bg_dae.h, dae_problem.regimes): before, at rtol 1e-4, a Jacobian from an open check valve
 * used after it closed left phantom flows in the lines, and these settings, which keep a
 * Jacobian longer, made it worse (the line pressures off by 10 to 135 MPa over the 20 s). With
 * the regimes the paper scene at rtol 1e-4 .. 1e-3 stays within 2 MPa of its run at 1e-8
 * (tests/crane/test_crane_physics.c), and the settings save a fifth of its time at 1e-6
 * (docs/crane.md, "Solver settings").
 *
 * Tolerances. The solver weighs the error of unknown i with rtol |y_i| + atol nominal_i. With
 * nominal_scales = true (the default) nominal_i is the magnitude the components give that
 * unknown from the scene's parameters (crane_build.c states them): the relief valves' full-flow
 * pressure (relief_pressure + 5 MPa; the charge pressure without valves) for the line pressures,
 * the pump's full flow pump_disp pump_speed / (2 pi) for its flows, the plateau speed
 * rate * gear_ratio for the motor's, the weight of boom and load for the forces in boom, ties
 * and hinge (that weight times the element length for the beam moments), the load's weight for
 * the rope, the total weight and the larger overturning moment for the slewing joint, the
 * members' lengths for their stretch vectors, the pump's full displacement (x_limit) for the
 * PID output; the scene's nominal_length, nominal_velocity and nominal_angular_velocity for
 * positions, velocities and angular velocities (no parameter gives them a size: the paper
 * scene states 1 m, 1 m/s, 1 rad/s); 1 (SI) for angles. "rtol = atol = 1e-6" then asks every
 * unknown for about a millionth of its own size, |y| or its nominal, whichever is larger: 35 Pa
 * on a line pressure, 0.85 N on a boom force, 1 um on a position. With nominal_scales = false
 * every unknown has the absolute tolerance atol in SI units (1e-6 Pa on a 2..28 MPa pressure,
 * 1e-6 N on a force of 1e5 N: far below what the rounding of the residual resolves), the
 * behaviour before the scales existed. model_stats.txt lists the scales used by domain.
 *
 * Stability guard. Without structural damping (paper-undamped.ini) the boom's node rotations
 * (250 to 450 Hz with 16 elements, higher with more) and the loop of PID, pump and line
 * compressibility (about 820 Hz) are undamped or about 1 % damped, and stay excited: BDF of
 * order 3 to 5 then holds the step at its stability limit on them (0.72 / omega at order 5)
 * whatever the tolerance (144 000 steps). With stability_guard = true (paper-undamped.ini) the
 * solver lowers the order to 2 there (dae_stab.c), which damps those modes: about 46 000 steps.
 * The paper scene's structural damping overdamps the node rotations itself (beta = 2.33e-3 s:
 * above 170 Hz) and its leakage damps its loop mode (184 Hz) to 7.3 %; no lightly damped fast
 * mode is left for the guard, which there only lowers the order where orders 3 to 5 would do
 * (medians over rtol x {1, 1.01, 1.02, 1.03, 1.05} at 1e-6: 3 795 steps and 0.55 s without it,
 * 3 989 and 0.65 s with it; fewer steps at 1e-8 and 1e-7 too). So it is off there (false, the
 * default) and in the scenes derived from it.
 *
 * Besides the ranges above, a scene must be consistent: the boom must reach its tip radius
 * (|tip_radius - foot.x| < length), a flexible boom (elements > 0) must lean (tip_radius !=
 * foot.x: a vertical beam has no luffing plane) and the reference's times must be ordered.
 *
 * Errors (the library never prints): every function returns BG_OK or a status (BG_ERR_IO: the
 * file cannot be read; BG_ERR_ARGUMENT: the text is wrong; BG_ERR_MEMORY) and writes the
 * message into err, in the form
 *   FILE:LINE: key 'x' in [section]: expected a number > 0 (m), got '-3'
 *   FILE:LINE: unknown key 'lenght' in [boom]; did you mean 'length'?
 *   FILE:LINE: unknown section [bom]; did you mean [boom]?
 * so that an editor can jump to it. The scene is left partly changed on error. */
#ifndef CRANE_SCENE_H
#define CRANE_SCENE_H

#include <stddef.h>
#include <stdio.h>

#include "bg_status.h"
#include "crane_model.h"

#ifdef __cplusplus
extern "C" {
#endif

/* crane_scene_default(s), then the file at path (a regular file: a directory, FIFO or device
 * is refused with BG_ERR_IO naming what it is, without blocking on a FIFO). */
int crane_scene_load(crane_scene *s, const char *path, bg_error *err);
/* The same, and *nkeys (may be NULL) = the number of keys the file sets (0: the file is empty or
 * holds only comments and section headers). */
int crane_scene_load_counted(crane_scene *s, const char *path, int *nkeys, bg_error *err);
/* "a directory", "a FIFO (named pipe)", "a character device", ... for a stat st_mode. */
const char *crane_file_kind(unsigned mode);
/* Apply a scene file's text to s (not reset first); filename is used in messages. */
int crane_scene_parse_file(crane_scene *s, FILE *f, const char *filename, bg_error *err);
int crane_scene_parse_string(crane_scene *s, const char *text, const char *filename, bg_error *err);

/* Set one key from its text, with the same checks as in a file (not the consistency checks:
 * call crane_scene_check afterwards). origin starts the message (e.g. "--t-end"; NULL: none). */
int crane_scene_set(crane_scene *s, const char *section, const char *key, const char *value,
                    const char *origin, bg_error *err);

/* The ranges of every field and the consistency of the scene; origin starts the message. */
int crane_scene_check(const crane_scene *s, const char *origin, bg_error *err);

/* Write s as a complete scene file (every key, with its unit and meaning as a comment); parsing
 * it gives s back exactly. Returns BG_OK or BG_ERR_IO. */
int crane_scene_write(const crane_scene *s, FILE *f);

/* Number of keys whose values differ between a and b; the first is named in what
 * ("[boom] length"; what may be NULL). */
int crane_scene_compare(const crane_scene *a, const crane_scene *b, char *what, size_t size);

/* The keys, for listings and tests. */
typedef enum crane_key_type {
    CRANE_KEY_NUMBER,
    CRANE_KEY_INTEGER,
    CRANE_KEY_BOOLEAN,
    CRANE_KEY_VECTOR,
    CRANE_KEY_NAME
} crane_key_type;
typedef struct crane_scene_key {
    const char *section, *key;
    crane_key_type type;
    const char *unit;     /* "m", "Pa", ... ("" if none) */
    const char *expected; /* the range in words: "a number > 0", ... */
    const char *meaning;
} crane_scene_key;
int crane_scene_nkeys(void);
/* Key i (0 .. crane_scene_nkeys()-1), or NULL. */
const crane_scene_key *crane_scene_key_at(int i);

/* Edit distance (optimal string alignment: insertions, deletions, substitutions, transpositions
 * of neighbours), case-insensitive; used for the suggestions. */
int crane_scene_edit_distance(const char *a, const char *b);

#ifdef __cplusplus
}
#endif
#endif
