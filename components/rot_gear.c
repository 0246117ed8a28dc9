/* Gear unit (see rot_gear.h): the standard TF element with modulus 1 / ratio. */
#include "rot_gear.h"

#include <math.h>

#include "bgr_elements.h"

int rot_gear(bgr_model *m, bgr_comp c, const char *name, double ratio)
{
    if (!(ratio != 0) || !isfinite(ratio))
        return bg_error_raise(bgr_model_error_mut(m), BG_ERR_ARGUMENT, "rot_gear",
                              "gear %s: ratio %g must be finite and non-zero",
                              name ? name : "(null)", ratio);
    return bgr_TF(m, c, name, 1, 1.0 / ratio);
}
