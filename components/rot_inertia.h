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

#include "bgr_model.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Returns the element id or < 0 (message in the model's error record). */
int rot_inertia(bgr_model *m, bgr_comp c, const char *name, double J);
/* The moment of inertia of an element of class rot_class_inertia (0 for any other element). */
double rot_inertia_moment(const bgr_element *el);

extern const bgr_element_class rot_class_inertia;

#ifdef __cplusplus
}
#endif
#endif
