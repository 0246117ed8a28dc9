/* Hydraulic sources: the tank (reservoir at constant pressure), pressure and flow sources.
 *
 * One port of dimension 1, power counted out of the source (the bgr_Se / bgr_Sf convention):
 *   tank, pressure source     p = P        (constant, or a signal: any unknown through bgr_ref)
 *   flow source               q_out = Q    (constant, or a signal)
 * These are the standard effort and flow sources of the bond-graph layer (bgr_elements.h) under
 * hydraulic names, with their arguments checked: a tank is an ideal reservoir whose pressure does
 * not depend on the flow it takes or gives (the boost or charge pressure of a closed circuit, or
 * 0 for atmospheric); a flow source is an ideal fixed-displacement pump at constant speed.
 * Source: the effort and flow sources of D. C. Karnopp, D. L. Margolis and R. C. Rosenberg,
 * System Dynamics: Modeling, Simulation, and Control of Mechatronic Systems (Wiley). */
#ifndef HYD_SOURCE_H
#define HYD_SOURCE_H

#include "bg_api.h"
#include "bgr_model.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Each returns the element id or < 0 (message in the model's error record). Accepted: pressure
 * (Pa) and flow (m^3/s) finite, of any sign; a NaN or an infinity gives BG_ERR_ARGUMENT before
 * anything is built, with a message naming the element's path and the parameter. The signal
 * forms check nothing at construction (bgr_compile reports a signal that names no unknown). */
BG_API int hyd_tank(bgr_model *m, bgr_comp c, const char *name, double pressure);
BG_API int hyd_pressure_source_signal(bgr_model *m, bgr_comp c, const char *name, bgr_ref pressure);
BG_API int hyd_flow_source(bgr_model *m, bgr_comp c, const char *name, double flow);
BG_API int hyd_flow_source_signal(bgr_model *m, bgr_comp c, const char *name, bgr_ref flow);

#ifdef __cplusplus
}
#endif
#endif
