/* 4/3 proportional directional valve: four metering edges P->A, B->T, P->B, A->T opened by a
 * spool command, critically centred or with a small underlap, with laminar leakage.
 *
 * Ports (dimension 1, power counted into the valve at every port; effort: pressure, flow:
 * volume flow into the valve): 0 = P (supply), 1 = T (tank), 2 = A, 3 = B. The spool command u
 * is a signal (any unknown of the model, bgr_ref: a controller's output, a signal source), in
 * [-1, 1] in normal use: u > 0 opens P->A and B->T, u < 0 opens P->B and A->T, |u| = 1 is the
 * rated opening. No states, no power stored: the valve dissipates everything it passes.
 *
 * Edge flows, X->Y one of the four edges, dp = p_X - p_Y:
 *   Q_XY = K a_XY(u) f(dp) + G_l dp
 *   a_PA = a_BT = o(u),  a_PB = a_AT = o(-u),   o(z) = sp(z + u0) / sp(1 + u0)
 *   f(dp) = dp (dp^2 + dp_l^2)^(-1/4),          K = q_n / f(dp_n)
 * with sp(z) = eps ln(1 + exp(z / eps)) the softplus of cmp_internal.h (a smooth max(z, 0)).
 * Equations (q_X the flow into the valve at port X):
 *   q_P = Q_PA + Q_PB                                                     ("flow_P")
 *   q_A = Q_AT - Q_PA                                                     ("flow_A")
 *   q_B = Q_BT - Q_PB                                                     ("flow_B")
 *   q_P + q_T + q_A + q_B = 0                                             ("continuity")
 *
 * The metering edge: the turbulent orifice q = Cd w x sqrt(2 |dp| / rho) sign(dp) (H. E.
 * Merritt, Hydraulic Control Systems, Wiley 1967, the spool valve's orifice equation) with the
 * opening area w x linear in the spool's travel, written with the data a manufacturer states:
 * the rated flow q_n of one metering edge at the rated pressure drop dp_n across that edge
 * (e.g. 100 l/min at 35 bar per edge, i.e. 70 bar across the valve for P->A->B->T in series:
 * the convention of the catalogues' "rated flow at 35 bar per control edge"). Cd w sqrt(2/rho) x
 * is then K a(u), and at u = 1, dp = dp_n an edge passes exactly q_n + G_l dp_n.
 *
 * Underlap u0 (a fraction of the rated travel, >= 0; 0: critically centred): each edge's land
 * is u0 short, so an edge is open by u + u0 (P->A) or -u + u0 (P->B) of the travel, normalised
 * to 1 at u = 1: a_PA(u) = (u + u0) / (1 + u0) where positive. At u = 0 every edge is open by
 * u0 / (1 + u0), which gives an underlapped valve its centre flow P->A->T and P->B->T. u beyond
 * +-1 opens further in proportion (the valve does not saturate the command: limit it upstream,
 * ctl_pid's limits).
 *
 * Regularisations, and how far they move the ideal characteristic:
 *   - the opening o(z) replaces max(z + u0, 0) / (1 + u0) by the softplus of width eps (a
 *     fraction of the travel): 0 < sp(z) - max(z, 0) <= eps ln 2, so an edge's opening exceeds
 *     the ideal one by at most eps ln 2 / sp(1 + u0) < eps ln 2 / (1 + u0), at the edge's
 *     closing point (z = -u0), and by eps exp(-|z + u0| / eps) (times 1/sp(1 + u0)) away from
 *     it: a critically centred valve at u = 0 passes K eps ln 2 / sp(1) f(dp) per edge besides
 *     its leakage (6.9e-4 q_n sqrt(dp / dp_n) per edge for eps = 1e-3), a closed edge |z + u0|
 *     = 0.02 beyond its closing point is open by 2e-12 of its rated opening (eps = 1e-3). o(1) = 1
 *     exactly.
 *   - the orifice f(dp) = dp (dp^2 + dp_l^2)^(-1/4) is laminar near dp = 0 (f = dp / sqrt(dp_l)
 *     + O(dp^3): a conductance K a / sqrt(dp_l), finite, so the residual stays smooth where
 *     sqrt(|dp|) has an infinite slope) and turbulent beyond: f / (sign(dp) sqrt(|dp|)) =
 *     (1 + (dp_l / dp)^2)^(-1/4) lies in [1 - (dp_l / dp)^2 / 4, 1], so the flow is below the
 *     turbulent one by at most a fraction (dp_l / dp)^2 / 4 (0.25 % at |dp| = 10 dp_l,
 *     0.0025 % at 100 dp_l). f is odd, analytic and strictly increasing (f' = (dp^2 / 2 +
 *     dp_l^2) (dp^2 + dp_l^2)^(-5/4) > 0). K is calibrated on f itself, so the rated point holds
 *     exactly.
 * Every edge dissipates dp Q_XY >= 0 (f and the leakage have the sign of dp, a >= 0).
 *
 * Regime (bgr_element_class.regime, for the Jacobian refresh): the spool's two switches, the
 * slopes d1 = sp'(u + u0) (P->A, B->T) and d2 = sp'(-u + u0) (P->B, A->T) in the bands of
 * cmp_regime, combined as 4 cmp_regime(d1) + cmp_regime(d2) (0 .. 15): a fresh Jacobian when
 * either pair of edges crosses its closing point.
 *
 * Nominal magnitudes (bgr_declare_nominal): 2 dp_n (the supply pressure that drives the rated
 * flow through two edges in series) for the four pressures, q_n for the four flows, 1 for the
 * command. */
#ifndef HYD_DIRECTIONAL_H
#define HYD_DIRECTIONAL_H

#include "bg_api.h"
#include "bgr_model.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct hyd_directional_spec {
    double flow_rated;      /* q_n, rated flow of one metering edge (m^3/s), > 0 */
    double dp_rated;        /* dp_n, the pressure drop across one edge at q_n (Pa), > 0 */
    double underlap;        /* u0, fraction of the rated travel, 0 (critically centred) .. 0.5 */
    double leakage;         /* G_l, laminar leakage conductance per edge (m^3/(s Pa)), >= 0 */
    double dp_laminar;      /* dp_l, the orifice's laminar width (Pa), > 0 and <= dp_n; 0: the
                               default 0.01 dp_n */
    double spool_smoothing; /* eps, the opening's width (fraction of travel), > 0 and <= 0.1;
                               0: the default 1e-3 */
} hyd_directional_spec;

/* The valve with spool command u (a signal, resolved by bgr_compile, which reports one that
 * names no unknown). Returns the element id or < 0 (message in the model's error record).
 * Accepted: spec not NULL, every field finite and in the range stated beside it. Anything else
 * gives BG_ERR_ARGUMENT before anything is built, with a message naming the element's path and
 * the parameter (nothing is added to the model). */
BG_API int hyd_directional_valve(bgr_model *m, bgr_comp c, const char *name, bgr_ref command,
                                 const hyd_directional_spec *spec);

BG_API extern const bgr_element_class hyd_class_directional;

#ifdef __cplusplus
}
#endif
#endif
