/* Scene files of the rotary crane: INI text (parsed with inih, behind pu_ini) -> crane_scene.
 *
 * A scene file starts from crane_scene_default() (the paper scene) and changes what it states;
 * every key is optional and may appear at most once. Lines are "key = value", "[section]",
 * blank, or comments starting with ';' or '#'; an inline comment starts with " ;" (a ';' after
 * white space). Lines end with LF, CR LF or CR. Keys and section names are matched without
 * regard to case.
 *
 * The keys, their sections, value types and ranges, defaults, units and meanings are listed in
 * docs/scene-keys.md, generated from the key table in crane_scene_keys.c (crane --list-keys
 * prints it; tests/crane/test_crane_scene_keys.c fails when the two disagree). The sections and
 * keys mirror the fields of crane_scene (crane_model.h). Units are SI: m, kg, s, N, Pa, rad.
 *
 * [solver] stability_guard, max_order, newton_dgmax, newton_jac_age and newton_index2_scale_h
 * set the solver's options of the same names (bg_dae.h). newton_dgmax and newton_jac_age are on in the
 * shipped scenes since the Jacobian follows the switching elements' regimes
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
 * Besides its keys' ranges, a scene must be consistent (crane_scene_check; docs/scene-keys.md):
 * the boom must reach its tip radius, a flexible boom must lean, the reference's times must be
 * ordered and output_step <= t_end.
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

/* The key list, generated from the key table: every key with its section, value type and range,
 * default, unit and meaning, as Markdown (docs/scene-keys.md is this text; crane --list-keys
 * prints it). BG_OK or BG_ERR_IO. */
int crane_scene_keys_markdown(FILE *f);

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

#ifdef __cplusplus
}
#endif
#endif
