/* Hydraulic sources (see hyd_source.h): the standard Se and Sf elements with checked values. */
#include "hyd_source.h"

#include <math.h>

#include "bgr_check.h"
#include "bgr_elements.h"

int hyd_tank(bgr_model *m, bgr_comp c, const char *name, double pressure)
{
    if (bgr_check_value(m, c, name, "hyd_tank", "pressure", pressure, BGR_FINITE))
        return BG_ERR_ARGUMENT;
    return bgr_Se(m, c, name, 1, &pressure);
}

int hyd_pressure_source_signal(bgr_model *m, bgr_comp c, const char *name, bgr_ref pressure)
{
    return bgr_Se_signal(m, c, name, pressure);
}

int hyd_flow_source(bgr_model *m, bgr_comp c, const char *name, double flow)
{
    if (bgr_check_value(m, c, name, "hyd_flow_source", "flow", flow, BGR_FINITE))
        return BG_ERR_ARGUMENT;
    return bgr_Sf(m, c, name, 1, &flow);
}

int hyd_flow_source_signal(bgr_model *m, bgr_comp c, const char *name, bgr_ref flow)
{
    return bgr_Sf_signal(m, c, name, flow);
}
