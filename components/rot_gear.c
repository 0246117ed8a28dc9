/* Gear unit (see rot_gear.h): the standard TF element with modulus 1 / ratio. */
#include "rot_gear.h"

#include <math.h>

#include "bgr_check.h"
#include "bgr_elements.h"

int rot_gear(bgr_model *m, bgr_comp c, const char *name, double ratio)
{
    if (bgr_check_value(m, c, name, "rot_gear", "ratio", ratio, BGR_NONZERO))
        return BG_ERR_ARGUMENT;
    if (!isfinite(1.0 / ratio))
        return bgr_refuse(m, c, name, "rot_gear",
                          "ratio = %g, expected a finite number != 0 with a finite 1 / ratio",
                          ratio);
    return bgr_TF(m, c, name, 1, 1.0 / ratio);
}
