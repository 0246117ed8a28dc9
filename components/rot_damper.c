/* Viscous rotational friction (see rot_damper.h): the standard R element with a checked b. */
#include "rot_damper.h"

#include <math.h>

#include "bgr_check.h"
#include "bgr_elements.h"

int rot_damper(bgr_model *m, bgr_comp c, const char *name, double b)
{
    if (bgr_check_value(m, c, name, "rot_damper", "b", b, BGR_NONNEGATIVE)) return BG_ERR_ARGUMENT;
    return bgr_R(m, c, name, 1, b);
}
