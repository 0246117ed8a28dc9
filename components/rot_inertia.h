/* Rotational inertia about a fixed axis, with its angle as a state.
 *
 * One port of dimension 1 (power in): effort T, the net torque on the body; flow w, its angular
 * velocity. States: the angular momentum p (named "p", bgr_ref {BGR_STATE, id, 0}) and the angle
 * theta ("angle", {BGR_STATE, id, 1}). Parameter: J, the moment of inertia about the axis
 * (kg m^2), > 0.
 *
 * Equations (the standard I element of bgr_elements.h plus the angle):
 *   p'     = T                                         Euler's law        ("momentum")
 *   J w_in = p                                         constitutive law   ("velocity")
 *   theta' = p / J                                     kinematics         ("angle")
 * Stored energy p^2 / (2 J). Several torques act through a 1-junction. The angle never enters
 * the other equations, so it only records the motion (rot_sensor reads it; rigid bodies in space
 * come with the multibody components).
 *
 * Source: D. C. Karnopp, D. L. Margolis and R. C. Rosenberg, System Dynamics: Modeling,
 * Simulation, and Control of Mechatronic Systems (Wiley): the I element for a rotating body, with
 * the angle the time integral of the flow. */
#ifndef ROT_INERTIA_H
#define ROT_INERTIA_H

#include "bg_api.h"
#include "bgr_model.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Returns the element id or < 0 (message in the model's error record). Accepted: J finite and
 * > 0, with 1 / J finite; anything else gives BG_ERR_ARGUMENT before anything is built, with a
 * message naming the element's path and the parameter (nothing is added to the model). */
BG_API int rot_inertia(bgr_model *m, bgr_comp c, const char *name, double J);
/* Optional nominal speed (rad/s; bgr_declare_nominal), stated before bgr_compile: the scale of
 * the speed w and, times J, of the momentum p. J gives no speed of its own: not stated (0), both
 * keep 1 (SI units); the angle and the torque always do. BG_OK, BG_ERR_ARGUMENT (id not an
 * inertia, speed < 0 or not finite), BG_ERR_STATE (model compiled). */
BG_API int rot_inertia_set_nominal(bgr_model *m, int id, double speed);
/* The moment of inertia of an element of class rot_class_inertia (0 for any other element). */
BG_API double rot_inertia_moment(const bgr_element *el);

BG_API extern const bgr_element_class rot_class_inertia;

#ifdef __cplusplus
}
#endif
#endif
