/* Viscous rotational friction (a linear rotary damper).
 *
 * One port of dimension 1 (power in): effort T, the friction torque; flow w, the relative
 * angular velocity across it. Parameter: b >= 0 (N m s/rad).
 * Equation (the R element of bgr_elements.h):
 *   T = b w_in                                         ("resistance")
 * It dissipates b w^2. Put it on the 1-junction of a shaft (friction against the ground) or on a
 * 1-junction of the difference of two speeds.
 * Source: the resistance of D. C. Karnopp, D. L. Margolis and R. C. Rosenberg, System Dynamics:
 * Modeling, Simulation, and Control of Mechatronic Systems (Wiley); viscous (Newtonian) friction
 * of a lubricated bearing. */
#ifndef ROT_DAMPER_H
#define ROT_DAMPER_H

#include "bg_api.h"
#include "bgr_model.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Returns the element id or < 0 (message in the model's error record). Accepted: b finite and
 * >= 0; anything else gives BG_ERR_ARGUMENT before anything is built, with a message naming the
 * element's path and the parameter (nothing is added to the model). */
BG_API int rot_damper(bgr_model *m, bgr_comp c, const char *name, double b);

#ifdef __cplusplus
}
#endif
#endif
