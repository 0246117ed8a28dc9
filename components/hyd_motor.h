/* Fixed-displacement hydraulic motor with laminar cross-port leakage and optional viscous
 * friction.
 *
 * Ports (each of dimension 1; "in"/"out" is the direction of positive power):
 *   0  inlet a (in)   effort p_a: pressure; flow q_a: volume flow into the motor
 *   1  outlet b (out) effort p_b: pressure; flow q_b: volume flow out of the motor
 *   2  shaft   (out)  effort T: torque delivered to the load; flow w: shaft speed
 * Parameters: D, displacement per revolution (m^3/rev), > 0; Cl, cross-port leakage conductance
 * (m^3/(s Pa)), >= 0; b, viscous friction coefficient of the shaft (N m s/rad), >= 0.
 *
 * Equations, with dp = p_a - p_b and the flows counted in the port's power direction:
 *   q_ain  = D w / (2 pi) + Cl dp                      flow drawn          ("flow")
 *   q_bout = q_ain                                     the leak leaves at b ("continuity")
 *   T      = D dp / (2 pi) - b w                       shaft torque        ("torque")
 * Power: p_a q_ain - p_b q_bout - T w = Cl dp^2 + b w^2 >= 0 (leakage and friction losses); with
 * Cl = b = 0 the motor is a transformer (pressure difference to torque, speed to flow, modulus
 * D / (2 pi)) and conserves power exactly.
 *
 * Source: the ideal motor with laminar cross-port leakage and viscous friction of H. E. Merritt,
 * Hydraulic Control Systems (Wiley, 1967) (pump-controlled motor: flow continuity and torque
 * balance), displacement per radian written D / (2 pi). */
#ifndef HYD_MOTOR_H
#define HYD_MOTOR_H

#include "bg_api.h"
#include "bgr_model.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Returns the element id or < 0 (message in the model's error record). Accepted: D finite and
 * > 0; Cl and b finite and >= 0. Anything else: BG_ERR_ARGUMENT before anything is built, with a
 * message naming the element's path and the parameter (nothing is added to the model). */
BG_API int hyd_motor(bgr_model *m, bgr_comp c, const char *name, double D, double Cl, double b);

/* Optional nominal scales (bgr_declare_nominal), stated before bgr_compile: pressure (Pa) for
 * p_a and p_b, D pressure / (2 pi) for the torque T; speed (rad/s) for the shaft speed w and
 * D speed / (2 pi) for the flows q_a, q_b (the displacement times the speed). The motor's
 * parameters give no pressure or speed of their own (the load and the pump set them): not
 * stated (0), the unknowns keep 1 (SI units). BG_OK, BG_ERR_ARGUMENT (id not a motor, a scale
 * < 0 or not finite), BG_ERR_STATE (model compiled). */
BG_API int hyd_motor_set_nominal(bgr_model *m, int id, double pressure, double speed);

BG_API extern const bgr_element_class hyd_class_motor;

#ifdef __cplusplus
}
#endif
#endif
