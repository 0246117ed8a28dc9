/* Variable-displacement hydraulic pump, driven at its shaft, displacement set by a signal.
 *
 * Ports (each of dimension 1; "in"/"out" is the direction of positive power):
 *   0  shaft   (in)   effort T: the torque the pump draws from its drive; flow w_p: drive speed
 *   1  inlet a (in)   effort p_a: pressure; flow q_a: volume flow into the pump
 *   2  outlet b (out) effort p_b: pressure; flow q_b: volume flow out of the pump
 * Signal x: the displacement command, a fraction of the maximum displacement Dp (usually in
 * [-1, 1]; negative x reverses the flow), read from any unknown (bgr_ref).
 * Parameters: Dp, displacement per revolution at x = 1 (m^3/rev); Cl, laminar cross-port leakage
 * conductance (m^3/(s Pa)), >= 0; both finite, Dp > 0.
 *
 * Equations, with dp = p_b - p_a and the flows counted in the port's power direction:
 *   T      = x Dp dp / (2 pi)                          torque drawn       ("torque")
 *   q_bout = x Dp w_p / (2 pi) - Cl dp                 delivered flow     ("flow")
 *   q_ain  = q_bout                                    the leak returns inside ("continuity")
 * Power: T w_p + p_a q_ain - p_b q_bout = Cl dp^2 >= 0 (the leakage loss); with Cl = 0 the pump
 * is a modulated transformer and conserves power exactly.
 *
 * Displacement actuator (hyd_pump_servo with a bandwidth fc > 0): the swash plate does not
 * follow the command at once. Its position s (a fraction of Dp, the element's state "swash",
 * {BGR_STATE, id, 0}) follows the command x as a first-order lag of corner frequency fc (Hz):
 *   s'     = 2 pi fc (x - s)                           actuator           ("servo")
 * and s replaces x in the torque and flow equations above. A step of the command reaches
 * 1 - exp(-2 pi fc t) of its size at time t (63 % after 1 / (2 pi fc)); a command within
 * [-1, 1] keeps s within it. The swash plate is positioned by a servo piston fed through a
 * control valve with feedback of the plate's angle; when the valve's dynamics and the servo
 * piston's hydraulic resonance lie well above the loop gain K_v, that position loop answers as
 * s / x = 1 / (1 + s_L / K_v), a first-order lag of bandwidth K_v / (2 pi) (Merritt, Hydraulic
 * Control Systems, 1967, the valve-controlled piston in a position loop). fc = 0 is the pump
 * above: s = x, no state.
 *
 * Source: the ideal positive-displacement machine with laminar cross-port leakage, as in the
 * pump-controlled motor of H. E. Merritt, Hydraulic Control Systems (Wiley, 1967), with the
 * displacement per radian written Dp / (2 pi); in a drive under PID control x is the
 * controller's output (ctl_pid). */
#ifndef HYD_PUMP_H
#define HYD_PUMP_H

#include "bg_api.h"
#include "bgr_model.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Returns the element id or < 0 (message in the model's error record). Accepted: Dp finite and
 * > 0, Cl finite and >= 0; anything else gives BG_ERR_ARGUMENT before anything is built, with a
 * message naming the element's path and the parameter (nothing is added to the model). The
 * command must name an unknown once the model is compiled (bgr_compile reports it). */
BG_API int hyd_pump(bgr_model *m, bgr_comp c, const char *name, double Dp, double Cl,
                    bgr_ref command);
/* The same pump with its displacement actuator of bandwidth fc (Hz): fc > 0 gives the state
 * "swash" (start it at the command's initial value, or let a static or consistent start find
 * it), fc = 0 is hyd_pump exactly. Accepted as hyd_pump, and fc finite and >= 0; otherwise
 * BG_ERR_ARGUMENT naming the element's path and the parameter, nothing added. */
BG_API int hyd_pump_servo(bgr_model *m, bgr_comp c, const char *name, double Dp, double Cl,
                          bgr_ref command, double fc);

/* Optional nominal scales (bgr_declare_nominal), stated before bgr_compile: pressure (Pa) for
 * p_a and p_b, Dp pressure / (2 pi) for the torque T; speed (rad/s, the drive speed) for w_p and
 * Dp speed / (2 pi) for the flows q_a, q_b (the displacement times the speed: the full flow).
 * The command x and the swash plate's position keep 1 (fractions of the full displacement).
 * Not stated (0): the pressures, torque, speed and flows keep 1 (SI units). BG_OK, BG_ERR_ARGUMENT (id not a pump, a scale < 0
 * or not finite), BG_ERR_STATE (model compiled). */
BG_API int hyd_pump_set_nominal(bgr_model *m, int id, double pressure, double speed);

BG_API extern const bgr_element_class hyd_class_pump;

#ifdef __cplusplus
}
#endif
#endif
