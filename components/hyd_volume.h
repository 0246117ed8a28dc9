/* Hydraulic line or chamber volume: the pressure built up by the compressibility of the oil.
 *
 * A node with nports >= 1 hydraulic ports (dimension 1), all with power counted into the volume
 * (an element whose bond leaves the volume sees the flow with the opposite sign, as for the
 * standard C element). State: the pressure p (named "p"; set its initial value through
 * bgr_ref {BGR_STATE, id, 0}). Parameters: V, the volume (m^3), > 0; beta, the effective bulk
 * modulus of the oil in it (Pa), > 0.
 *
 * Equations, q_k the flow into the volume at port k:
 *   p'  = (beta / V) sum_k q_k                         pressure build-up  ("pressure")
 *   e_k = p,  k = 0 .. nports-1                        common pressure    ("port<k>")
 * The element is a 0-junction and a capacitance C = V / beta in one; V and beta are constant
 * (the linearised continuity equation, valid while the volume change is small against V).
 * Stored energy V p^2 / (2 beta).
 *
 * Source: the continuity equation of a compressible volume, q_in - q_out = (V / beta) dp/dt,
 * H. E. Merritt, Hydraulic Control Systems (Wiley, 1967), with the bulk modulus beta
 * = -V dp/dV. */
#ifndef HYD_VOLUME_H
#define HYD_VOLUME_H

#include "bg_api.h"
#include "bgr_model.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Returns the element id or < 0 (message in the model's error record). Accepted: nports 1 ..
 * 1000; V and beta finite and > 0, with beta / V finite. Anything else gives BG_ERR_ARGUMENT
 * before anything is built, with a message naming the element's path and the parameter (nothing
 * is added to the model). */
BG_API int hyd_volume(bgr_model *m, bgr_comp c, const char *name, int nports, double V,
                      double beta);

/* Optional: the nominal pressure of the volume (Pa; bgr_declare_nominal), stated before
 * bgr_compile: the scale of its pressure p and of its ports' efforts, so that the solver's
 * absolute tolerance of them is atol * pressure. A system pressure (the circuit's relief or
 * working pressure) is the right value: V and beta give none (the pressure is set by the rest of
 * the circuit). Not stated (or 0): nothing declared, 1 Pa (SI units). BG_OK, BG_ERR_ARGUMENT (id
 * not a volume, pressure < 0 or not finite), BG_ERR_STATE (model compiled). */
BG_API int hyd_volume_set_nominal(bgr_model *m, int id, double pressure);

BG_API extern const bgr_element_class hyd_class_volume;

#ifdef __cplusplus
}
#endif
#endif
