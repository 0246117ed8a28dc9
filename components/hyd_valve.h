/* Hydraulic restrictions between two ports: laminar leakage and the pressure relief valve.
 *
 * Ports (dimension 1): 0 = a (power in), 1 = b (power out). Effort: pressure; flow: volume flow.
 * Both elements pass the same flow q from a to b, a function of dp = p_a - p_b:
 *   q_ain  = Q(dp)                                     characteristic     ("flow")
 *   q_bout = q_ain                                     no storage         ("continuity")
 * They dissipate dp Q(dp) >= 0. Join b to a tank (hyd_tank) for a leak or a relief to the
 * reservoir.
 *
 * Laminar leakage (hyd_leakage): Q(dp) = G dp, G >= 0 the leakage conductance (m^3/(s Pa)):
 * Hagen-Poiseuille flow through a narrow gap or a long capillary (e.g. the clearance flow of
 * H. E. Merritt, Hydraulic Control Systems, Wiley 1967).
 *
 * Relief valve (hyd_relief_valve): closed below the cracking pressure p_c, then opening
 * linearly with the pressure override: the ideal (kinked) static characteristic is
 *   Q_ideal(dp) = G max(dp - p_c, 0),   G = q_r / (p_f - p_c),
 * with p_f the full-flow pressure at which the valve passes its rated flow q_r. The element uses
 * the smooth characteristic (no kink, so the Newton iteration and the error estimate see a
 * smooth residual):
 *   Q(dp) = G sp(dp - p_c),   sp(z) = eps ln(1 + exp(z / eps)),
 * eps > 0 a pressure width. How far it deviates (from the softplus bounds in cmp_internal.h):
 *   - flow: 0 < Q(dp) - Q_ideal(dp) <= G eps ln 2, largest at dp = p_c and falling off like
 *     G eps exp(-|dp - p_c| / eps); below cracking the valve leaks G eps ln(1 + exp((dp-p_c)/eps))
 *     (for instance less than 0.7 % of G eps at 5 eps below p_c);
 *   - pressure (the tolerance band): a steady flow q > 0 through the valve holds
 *       dp = p_c + eps ln(exp(q / (G eps)) - 1) = p_c + q/G + eps ln(1 - exp(-q / (G eps))),
 *     always below the ideal p_c + q/G, hence below p_f for q <= q_r, and at most
 *     eps ln(1 / (1 - exp(-q / (G eps)))) below it (0.46 eps for q >= G eps, 0.0068 eps for
 *     q >= 5 G eps). So the valve caps the pressure in the band [p_c - (a few eps), p_f] for
 *     flows up to q_r.
 * Static characteristic only: the valve's own dynamics (poppet mass, damping) are left out.
 *
 * Nominal magnitudes (bgr_declare_nominal): the relief valve declares its full-flow pressure
 * max(|p_c|, |p_f|) for the pressures at both ports (the highest pressure difference it lets the
 * circuit reach at its rated flow) and q_r for the flows; the leakage declares nothing (a
 * conductance is no pressure or flow scale). */
#ifndef HYD_VALVE_H
#define HYD_VALVE_H

#include "bg_api.h"
#include "bgr_model.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Laminar leakage with conductance G, finite and >= 0. Returns the element id or < 0.
 * Parameters out of their ranges (here and below) give BG_ERR_ARGUMENT before anything is built,
 * with a message naming the element's path and the parameter (nothing is added to the model). */
BG_API int hyd_leakage(bgr_model *m, bgr_comp c, const char *name, double G);
/* Relief valve: cracking pressure p_crack (finite, any sign), full-flow pressure p_full > p_crack
 * (finite) at the rated flow q_rated > 0 (finite), smoothing width eps > 0 (finite; a small
 * fraction of p_full - p_crack, e.g. 1 %); the open valve's conductance q_rated / (p_full -
 * p_crack) must come out finite and > 0 (no overflow of the band). Returns the element id or
 * < 0. */
BG_API int hyd_relief_valve(bgr_model *m, bgr_comp c, const char *name, double p_crack,
                            double p_full, double q_rated, double eps);

BG_API extern const bgr_element_class hyd_class_leakage, hyd_class_relief;

#ifdef __cplusplus
}
#endif
#endif
