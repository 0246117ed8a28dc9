/* Sensors on a rotating inertia: its angle, angular velocity or angular acceleration as a
 * signal.
 *
 * A sensor has no ports and one algebraic unknown of its own, the measured signal z (named
 * "angle", "velocity" or "acceleration"; other elements read it as bgr_ref {BGR_OWN, id, 0}).
 * It reads the rot_inertia element it is given (created before it), with J its moment of
 * inertia, p its momentum, theta its angle and T the net torque on its bond:
 *   ROT_ANGLE          z = theta
 *   ROT_VELOCITY       z = p / J                       (= w, the flow of its bond)
 *   ROT_ACCELERATION   z = T / J                       (= w' by Euler's law p' = T)
 * The acceleration is an algebraic function of the torque, not a derivative of y: the equation
 * stays algebraic, as the semi-explicit form the solver needs requires, and a controller can use
 * it for its derivative term (ctl_pid) without differencing samples. An ideal sensor: no lag, no
 * noise, no power drawn.
 * Source: Euler's law for rotation about a fixed axis, J w' = T (the I element of D. C. Karnopp,
 * D. L. Margolis and R. C. Rosenberg, System Dynamics, Wiley). */
#ifndef SENSORS_H
#define SENSORS_H

#include "bg_api.h"
#include "bgr_model.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum rot_quantity { ROT_ANGLE = 0, ROT_VELOCITY = 1, ROT_ACCELERATION = 2 } rot_quantity;

/* A sensor of quantity q on the rot_inertia element inertia. Returns the element id (its signal
 * is bgr_ref {BGR_OWN, id, 0}) or < 0 (message in the model's error record). Accepted: q one of
 * the three quantities, inertia the id of a rot_inertia element made before; anything else gives
 * BG_ERR_ARGUMENT before anything is built, with a message naming the sensor's path and the
 * parameter. */
BG_API int rot_sensor(bgr_model *m, bgr_comp c, const char *name, int inertia, rot_quantity q);

BG_API extern const bgr_element_class rot_class_sensor;

#ifdef __cplusplus
}
#endif
#endif
