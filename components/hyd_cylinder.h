/* Double-acting hydraulic cylinder between two attachment points, with compressible chambers,
 * viscous friction and internal leakage across the piston.
 *
 * Ports (power counted into the cylinder at every port):
 *   0  A  3D  the barrel's attachment point (conventions of mech_body.h: flow v_A, effort the
 *             force on the cylinder at A from its partner, s_A = +1 at a bond's head, -1 at its
 *             tail)
 *   1  B  3D  the rod end's attachment point
 *   2  a  1D  cap side: effort p_a, flow q_a (volume flow into the cap chamber)
 *   3  b  1D  rod side: effort p_b, flow q_b (volume flow into the rod chamber)
 * It acts along the line A-B as the axial elements of mech_axial.h do. States: the vector
 * d = x_B - x_A (named d0 d1 d2; d' = v_B - v_A), the chamber pressures p_a and p_b (named "p_a",
 * "p_b"). With L = |d|, u = d / L, the extension x = L - L_min and its rate x' = L' = u.(v_B -
 * v_A):
 *   V_a = V_a0 + A_a x,   V_b = V_b0 + A_b (stroke - x)               chamber volumes
 *   q_l = G (p_a - p_b)                                                leakage a -> b
 *   p_a' = (beta / V_a) (q_a - A_a x' - q_l)                           ("pressure_a")
 *   p_b' = (beta / V_b) (q_b + A_b x' + q_l)                           ("pressure_b")
 *   T = -(p_a A_a - p_b A_b) + c x'                                    axial tension
 *   s_A F_A = -T u,   s_B F_B = T u       (the forces on the cylinder; "forceA0..2",
 *                                         "forceB0..2"; T > 0 pulls A and B together, so the
 *                                          cap pressure pushes them apart)
 *   e_a = p_a,   e_b = p_b                                                ("port_a", "port_b")
 *   d' = v_B - v_A                                                        ("stretch0..2")
 * The pressure equations are the continuity equation of a compressible chamber whose volume
 * changes with the piston, beta = -V dp/dV constant (the oil's density is rho0 exp(p / beta):
 * the equations conserve the oil's mass exactly); H. E. Merritt, Hydraulic Control Systems
 * (Wiley, 1967), the valve-controlled piston (load flow continuity and force balance), here with
 * both chambers kept separate and their volumes varying with the stroke. The piston, rod and
 * barrel are massless (put their mass into the bodies at A and B), and there are no seal
 * (Coulomb) friction and no end cushions.
 *
 * Ends of the stroke. The cylinder has no end stops: its equations hold for 0 <= x <= stroke.
 * A state outside (the piston through the cap or the head) makes the residual return 1, a
 * recoverable failure, with its rows pressure_a and pressure_b set to NaN: the integrator cuts
 * the step, and a motion that really drives the piston to an end stops the run (DAE_RES_FAIL once
 * the step has collapsed) with a message naming <path>/pressure_a, the cylinder's equation. Keep
 * the motion inside the stroke (a relief valve, a controller) or model an end stop. The chamber
 * volumes are then at least V_a0 and V_b0 > 0.
 *
 * Energy. For a liquid of constant bulk modulus the stored (free) energy of the compressed oil
 * per unit volume is g(p) = beta (exp(p / beta) - 1) - p = p^2 / (2 beta) (1 + p / (3 beta) + ..),
 * and the equations above give exactly
 *   d/dt [V_a g(p_a) + V_b g(p_b)] = P_hyd + P_conv + P_mech - P_fric - P_leak,
 *   P_hyd  = p_a q_a + p_b q_b                  power of the hydraulic bonds
 *   P_conv = g(p_a) q_a + g(p_b) q_b            compression energy the oil carries in (a share
 *                                               of about p / (2 beta) of P_hyd: 0.7 % at 20 MPa
 *                                               with beta = 1.4 GPa)
 *   P_mech = T x'                               power into the cylinder at A and B
 *   P_fric = c x'^2 >= 0,  P_leak = q_l beta (exp(p_a / beta) - exp(p_b / beta)) >= 0.
 * (d/dt (V g) = (p + g) (q_net) - p V' per chamber, from V p' = beta q_net and
 * beta g'(p) = p + g(p); the piston takes -p V' as work.) hyd_cylinder_evaluate returns every
 * term, so that an energy balance closes to the integration error.
 *
 * Nominal magnitudes (bgr_declare_nominal): the length L_min + stroke for d; with a stated
 * pressure p (hyd_cylinder_set_nominal) p for the pressures and the port efforts a and b and
 * p A_a for the forces at A and B; with a stated speed v, A_a v and A_b v for the flows q_a and
 * q_b. Not stated (0): those unknowns keep 1 (SI units). */
#ifndef HYD_CYLINDER_H
#define HYD_CYLINDER_H

#include "bg_api.h"
#include "bgr_model.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct hyd_cylinder_spec {
    double area_a;     /* piston area A_a (m^2), > 0 */
    double area_b;     /* rod-side annulus area A_b (m^2), > 0 and <= A_a (A_a - A_b: the rod) */
    double length_min; /* L_min, distance A-B at zero stroke (m), > 0 */
    double stroke;     /* (m), > 0 */
    double volume_a0;  /* dead volume of the cap side at x = 0 (m^3), > 0 */
    double volume_b0;  /* dead volume of the rod side at x = stroke (m^3), > 0 */
    double beta;       /* bulk modulus of the oil (Pa), > 0 */
    double friction;   /* viscous friction c (N s/m), >= 0 */
    double leakage;    /* internal leakage conductance G across the piston (m^3/(s Pa)), >= 0 */
} hyd_cylinder_spec;

/* Returns the element id or < 0 (message in the model's error record). Accepted: spec not NULL,
 * every field finite and in the range stated beside it, and beta / V_a0, beta / V_b0 finite.
 * Anything else gives BG_ERR_ARGUMENT before anything is built, with a message naming the
 * element's path and the parameter (nothing is added to the model). */
BG_API int hyd_cylinder(bgr_model *m, bgr_comp c, const char *name, const hyd_cylinder_spec *spec);

/* Initial state (after bgr_compile): d = x_B - x_A and the chamber pressures. BG_OK, or
 * BG_ERR_ARGUMENT (id not a cylinder of a compiled model, xa or xb NULL, a value not finite). */
BG_API int hyd_cylinder_set(bgr_model *m, int id, const double *xa, const double *xb, double p_a,
                            double p_b);

/* Optional nominal scales, stated before bgr_compile (see above): pressure (Pa) and piston
 * speed (m/s), finite and >= 0 (0: not stated). BG_OK, BG_ERR_ARGUMENT (id not a cylinder, a
 * scale < 0 or not finite), BG_ERR_STATE (model compiled). */
BG_API int hyd_cylinder_set_nominal(bgr_model *m, int id, double pressure, double speed);

/* The cylinder's quantities at a state vector y (SI units; the powers of the energy balance
 * above, W). */
typedef struct hyd_cylinder_values {
    double extension, rate;    /* x = L - L_min and x' */
    double volume_a, volume_b; /* V_a, V_b */
    double tension;            /* T (< 0: the cylinder pushes A and B apart) */
    double leak_flow;          /* q_l, from a to b */
    double energy;             /* V_a g(p_a) + V_b g(p_b) */
    double power_hydraulic;    /* P_hyd */
    double power_convected;    /* P_conv */
    double power_mechanical;   /* P_mech */
    double dissipation_friction, dissipation_leakage; /* P_fric, P_leak */
} hyd_cylinder_values;

/* BG_OK, or BG_ERR_ARGUMENT (id not a cylinder of a compiled model, y or out NULL). Values
 * outside the stroke are computed all the same (a volume may then be <= 0). */
BG_API int hyd_cylinder_evaluate(const bgr_model *m, int id, const double *y,
                                 hyd_cylinder_values *out);

BG_API extern const bgr_element_class hyd_class_cylinder;

#ifdef __cplusplus
}
#endif
#endif
