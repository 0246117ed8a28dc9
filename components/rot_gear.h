/* Gear unit: an ideal transformer between two rotating shafts.
 *
 * Ports (dimension 1): 0 = input shaft (power in: torque T_in, speed w_in), 1 = output shaft
 * (power out: torque T_out, speed w_out). Parameter: the ratio i = w_in / w_out (i > 1 reduces
 * the speed and multiplies the torque; i < 0 reverses the sense of rotation; i != 0).
 * Equations (the TF element of bgr_elements.h with modulus 1/i):
 *   T_in  = T_out / i                                  ("effort")
 *   w_out = w_in / i                                   ("flow")
 * Power: T_in w_in = T_out w_out exactly (the same modulus appears in both equations); friction
 * and backlash are left out (add rot_damper on either shaft for losses).
 * Source: the transformer of D. C. Karnopp, D. L. Margolis and R. C. Rosenberg, System Dynamics:
 * Modeling, Simulation, and Control of Mechatronic Systems (Wiley): a gear pair is a TF whose
 * modulus is the ratio of the pitch radii. */
#ifndef ROT_GEAR_H
#define ROT_GEAR_H

#include "bg_api.h"
#include "bgr_model.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Returns the element id or < 0 (message in the model's error record). Accepted: ratio finite
 * and != 0 (any sign), with 1 / ratio finite; anything else gives BG_ERR_ARGUMENT before
 * anything is built, with a message naming the element's path and the parameter. */
BG_API int rot_gear(bgr_model *m, bgr_comp c, const char *name, double ratio);

#ifdef __cplusplus
}
#endif
#endif
