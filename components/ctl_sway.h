/* Sway sensor: a point's offset from a rotating vertical plane, and its rate in that plane's
 * frame, the measured quantities of a slewing crane's load-sway feedback.
 *
 * The plane contains the vertical axis through (cx, cy) and turns with the angle theta about it
 * (the boom's luffing plane, at theta = 0 the plane y = cy). A point at (x, y) with velocity
 * (vx, vy) has the tangential offset and radial distance
 *   s   = -(x - cx) sin(theta) + (y - cy) cos(theta)                       ("sway")
 *   rho =  (x - cx) cos(theta) + (y - cy) sin(theta)
 * and the rate of s in the turning frame (d/dt of s with theta' = omega)
 *   s'  = -vx sin(theta) + vy cos(theta) - omega rho                       ("sway_rate")
 * For a load hanging on a rope of length L from the tip of a boom at radius R, s is the load's
 * swing out of the boom's plane; linearised about the hanging rest it obeys
 *   s'' = -(g / L) s - R theta''
 * (the pendulum whose suspension point moves sideways at R theta''), the design model of
 * ctl_lqr.h's crane example (docs/control.md). Inputs are signals (bgr_ref): the point's x, y,
 * vx, vy (a mech_point_mass's states 0, 1, 3, 4) and the plane's theta, omega (a rotation
 * sensor's). Outputs: s {BGR_OWN, id, 0} and s' {BGR_OWN, id, 1}. */
#ifndef CTL_SWAY_H
#define CTL_SWAY_H

#include "bg_api.h"
#include "bgr_model.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct ctl_sway_spec {
    bgr_ref x, y, vx, vy, theta, omega;
    double cx, cy; /* the axis, finite */
} ctl_sway_spec;

/* Returns the element id or < 0 (message in the model's error record). */
BG_API int ctl_sway(bgr_model *m, bgr_comp c, const char *name, const ctl_sway_spec *spec);

BG_API extern const bgr_element_class ctl_class_sway;

#ifdef __cplusplus
}
#endif
#endif
