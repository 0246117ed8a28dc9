/* Axial elements between two points (3D ports A and B, conventions of mech_body.h): linear spring
 * with damper, rope (tension only) and truss bar.
 *
 * State: the vector d = x_B - x_A from A to B (global frame), d' = v_B - v_A; length L = |d|,
 * direction u = d/L, elongation rate L' = u.(v_B - v_A). With the tension T(L, L'):
 *     s_A F_A = T u      (A is pulled towards B when T > 0),     s_B F_B = -T u.
 * Laws:
 *   spring/damper   T = k (L - L0) + c L'
 *   truss           T = (E A / L0) (L - L0) + c L'      (large displacement, small strain: the
 *                                                        engineering strain (L - L0)/L0)
 *   rope            T = k s_eps(L - L0) + c L' h_eps(L - L0), tension only, smooth at slack:
 *                   s_eps(x) = eps log(1 + exp(x/eps)) (softplus: > 0, = x + eps e^(-x/eps)
 *                   when taut, eps e^(x/eps) when slack, s_eps(0) = eps ln 2), and
 *                   h_eps = s_eps' = 1/(1 + exp(-x/eps)) the matching smooth step for the
 *                   damping; both leave exponentially small forces once the rope is a few eps
 *                   slack. eps = 1e-4 L0 by default.
 * No kink anywhere, so the residual stays smooth for the solver (the rope's slack/taut
 * transition is spread over a few eps of elongation). */
#ifndef MECH_AXIAL_H
#define MECH_AXIAL_H

#include "bg_api.h"
#include "bgr_model.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Ports 0 (A) and 1 (B), 3D. The state is named d0 d1 d2; set its initial value to x_B - x_A.
 * Accepted (all finite): stiffness k >= 0 (N/m), damping c_damp >= 0 (N s/m), rest length
 * L0 > 0 (m); truss: Young's modulus E > 0 (Pa) and area A > 0 (m^2) with E A / L0 finite;
 * rope: eps finite (<= 0: the default 1e-4 L0, which must not underflow to 0). Anything else
 * gives BG_ERR_ARGUMENT before anything is built, with a message naming the element's path and
 * the parameter (nothing is added to the model). */
BG_API int mech_spring(bgr_model *m, bgr_comp c, const char *name, double k, double c_damp,
                       double L0);
BG_API int mech_truss(bgr_model *m, bgr_comp c, const char *name, double E, double A, double L0,
                      double c_damp);
/* eps <= 0: 1e-4 L0 */
BG_API int mech_rope(bgr_model *m, bgr_comp c, const char *name, double k, double c_damp, double L0,
                     double eps);
/* Initial d (after bgr_compile). BG_OK, or BG_ERR_ARGUMENT (id not an axial element of a
 * compiled model, xa or xb NULL). */
BG_API int mech_axial_set(bgr_model *m, int id, const double *xa, const double *xb);
/* Elastic energy at a state vector y (after bgr_compile): k (L - L0)^2 / 2; for the rope k times
 * the integral of its smoothed stretch (softplus) from full slack, which differs from
 * k max(L - L0, 0)^2 / 2 by at most k eps^2 pi^2 / 6. NaN if id is not an axial element of a
 * compiled model, or y is NULL. */
BG_API double mech_axial_energy(const bgr_model *m, int id, const double *y);
/* Tension at a state vector y (after bgr_compile); NaN as for the energy. */
BG_API double mech_axial_tension(const bgr_model *m, int id, const double *y);
/* Power the damper dissipates at a state vector y (after bgr_compile): the damping force times
 * the elongation rate, c L'^2 (rope: c h_eps(L - L0) L'^2), >= 0; NaN as for the energy. With
 * the elastic energy: d/dt (energy) = T L' - dissipation, the power the member takes at its
 * ends less what it turns into heat. */
BG_API double mech_axial_dissipation(const bgr_model *m, int id, const double *y);

#ifdef __cplusplus
}
#endif
#endif
