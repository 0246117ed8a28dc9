/* Rotation sensor of a rigid body: angle and angular velocity about a fixed global axis a.
 *
 * Signals (own unknowns): the angular velocity w_a = (R(q) w_body).a and the angle theta, a state
 * with theta' = w_a, so that it keeps counting past +-pi (no wrap-around, no kink):
 *     theta' - (R w).a = 0,     w_a - (R w).a = 0.
 * theta starts at its initial value (bgr_y0; 0 by default). The outputs, e.g. the measurement of
 * a controller (ctl_pid), are bgr_ref {BGR_STATE, id, 0} (theta) and {BGR_OWN, id, 0} (w_a). */
#ifndef MECH_SENSOR_H
#define MECH_SENSOR_H

#include "bg_api.h"
#include "bgr_model.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Accepted: axis not NULL, finite and nonzero (normalised here); body >= 0 (a rigid body's id,
 * checked by bgr_compile). Anything else gives BG_ERR_ARGUMENT before anything is built, with a
 * message naming the sensor's path and the parameter. */
BG_API int mech_rotation_sensor(bgr_model *m, bgr_comp c, const char *name, int body,
                                const double *axis);

#ifdef __cplusplus
}
#endif
#endif
