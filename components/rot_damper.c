/* Viscous rotational friction (see rot_damper.h): the standard R element with a checked b. */
#include "rot_damper.h"

#include <math.h>

#include "bgr_elements.h"

int rot_damper(bgr_model *m, bgr_comp c, const char *name, double b)
{
    if (!(b >= 0) || !isfinite(b))
        return bg_error_raise(bgr_model_error_mut(m), BG_ERR_ARGUMENT, "rot_damper",
                              "damper %s: b = %g must be >= 0, finite", name ? name : "(null)", b);
    return bgr_R(m, c, name, 1, b);
}
