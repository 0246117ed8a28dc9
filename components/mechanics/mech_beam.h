/* Co-rotational 3D Euler-Bernoulli beam element. The builder of chains of them with lumped node
 * bodies is declared in mech_beam_chain.h, which this header includes at its end.
 *
 * Kinematics (co-rotational, after Crisfield, Non-linear Finite Element Analysis of Solids and
 * Structures vol. 2, ch. 17, and Battini and Pacoste, CMAME 191 (2002) 1755): the two nodes are
 * rigid bodies (mech_body) whose positions x_a, x_b and orientations R(q_a), R(q_b) the element
 * reads. The nodal triads are t_i = R(q) E0 e_i, E0 the beam's initial local frame (e1 along the
 * beam). The co-rotating element frame follows the rigid motion:
 *     e1 = (x_b - x_a)/L,   e2 = normalised part of (t2_a + t2_b)/2 normal to e1,   e3 = e1 x e2.
 * The local deformations left after removing the rigid motion are the elongation u = L - L0
 * and the small rotations of each nodal triad relative to the element frame, the skew part of
 * E^T T:  theta_x = (e3.t2 - e2.t3)/2,  theta_y = (e1.t3 - e3.t1)/2,  theta_z = (e2.t1 - e1.t2)/2.
 * Local elasticity (Euler-Bernoulli, small strain):
 *     W = EA/(2 L0) u^2 + GJ/(2 L0) (theta_x,b - theta_x,a)^2
 *         + 2 EI_z/L0 (theta_z,a^2 + theta_z,a theta_z,b + theta_z,b^2)
 *         + 2 EI_y/L0 (theta_y,a^2 + theta_y,a theta_y,b + theta_y,b^2).
 * Timoshenko as an option (kappa > 0): with the shear parameter P = 12 EI/(kappa G A L0^2) each
 * bending term becomes EI/(2 L0 (1 + P)) [(4 + P)(theta_a^2 + theta_b^2) + 2 (2 - P) theta_a
 * theta_b], the two-node shear-flexible element's end-rotation stiffness (Przemieniecki,
 * Theory of Matrix Structural Analysis, 1968, sec. 5.6); P = 0 gives back Euler-Bernoulli.
 * The element is conservative: the forces and moments it takes at its ports are the gradient of
 * W with respect to the nodal positions and (global) nodal rotations, obtained with their exact
 * Jacobian by second-order automatic differentiation (mech_ad.h). W is invariant under any rigid
 * motion, so a rigidly rotating element has no deformation energy, however large the rotation.
 * Ports 0 (node a) and 1 (node b) are 6D (conventions of mech_body.h).
 * Mass, lumped (section.mass = MECH_BEAM_LUMPED, the default): none in the element; the chain
 * builder (mech_beam_chain.h) lumps it into the node bodies, which converges at second order
 * (bending frequencies: relative error about 0.045 (beta_n L / n)^2).
 * Mass, consistent (MECH_BEAM_CONSISTENT): the node bodies keep the lumped masses, and the
 * element adds the inertia of its distributed mass m = rho A L0 over the co-rotational
 * displacement field minus those point masses m/2 at its nodes, so that the total is the
 * consistent mass (Crisfield, Galvanetto and Jelenic, Proc. R. Soc. A 453 (1997) 1125; Le,
 * Battini and Hjiaj, Comput. Struct. 134 (2014) 112: cubic local interpolation, inertia terms
 * derived from it). The field, xi = s/L0 in [0, 1]:
 *     r(xi) = x_a + xi (x_b - x_a) + L0 [H1(xi) P + H2(xi) Q],
 *     H1 = xi (1 - xi)^2,  H2 = -xi^2 (1 - xi),
 *     P = theta_z,a e2 - theta_y,a e3,  Q = theta_z,b e2 - theta_y,b e3,
 * linear along the chord and cubic (Hermite) across it in the co-rotated frame. Its mass is
 * put at the 4 Gauss points xi_g (weights w_g) of [0, 1], which integrate the cubic field's
 * kinetic energy exactly at small deformation: point masses m w_g at r_g = r(xi_g). Their
 * inertia loads follow by d'Alembert's principle, exactly, with r_g'' = G_g u'' + G_g' u' (u'
 * the nodes' velocities v, omega = R w; G_g = dr_g/du the velocity gradient, G_g' its rate
 * along the motion, which carries the centrifugal and Coriolis terms):
 *     f = sum_g m w_g G_g^T (r_g'' - g) - (m/2) [(v_a' - g), 0, (v_b' - g), 0],
 * g the gravity (the chain's: the distributed weight with its end moments m g L0 / 12, where the
 * lumped node weights carry none). Linearised at a straight rest state this is the classical
 * consistent mass (cubic Hermite across, linear along), and the bending frequencies converge at
 * fourth order (relative error about 0.015 (beta_n L / n)^4 for a clamped-free beam). The
 * kinetic energy T = sum_g m w_g |r_g'|^2 / 2 - (m/4)(|v_a|^2 + |v_b|^2) is conserved with the
 * rest of the model's energy. Torsional and rotary inertia of the section stay lumped at the
 * nodes. The Jacobian is exact at rest (modes, static starts); in motion it leaves out the
 * derivatives of G_g' u' with respect to the configuration and of omega = R w, w' with
 * respect to the nodes' orientations (terms of the size of the inertia loads times the
 * rotation rates, which the Newton iteration absorbs).
 * No damping in the element unless beta > 0: stiffness-proportional (Rayleigh) damping,
 * the gradient with respect to the port velocities of D = beta/2 d'^T K d', d' the rates of the
 * local deformations and K the local stiffness, so that it acts on deformation only (a rigid
 * motion is not damped) and mode i of the linearised structure gets the damping ratio
 * beta w_i / 2. */
#ifndef MECH_BEAM_H
#define MECH_BEAM_H

#include "bg_api.h"
#include "bgr_model.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The element's inertia (mech_section.mass). */
enum { MECH_BEAM_LUMPED = 0, MECH_BEAM_CONSISTENT = 1 };

/* Accepted: every field finite; E, G, A, Iy, Iz, J > 0; rho, kappa, beta >= 0 (the chain
 * builder, and mass = MECH_BEAM_CONSISTENT, need rho > 0); the stiffnesses they give (EA/L0,
 * GJ/L0, EI/L0, times beta) finite; mass one of the two values. */
typedef struct mech_section {
    double E, G;      /* Young's and shear modulus (Pa), > 0 */
    double A, Iy, Iz; /* area (m^2); second moments about the local y (e2) and z (e3) axes (m^4),
                         > 0 */
    double J;         /* torsion constant (m^4), > 0 */
    double rho;       /* density (kg/m^3; for the chain builder's lumped masses), >= 0 (chain: > 0) */
    double kappa;     /* shear correction factor: 0 Euler-Bernoulli, > 0 Timoshenko */
    double beta;      /* stiffness-proportional damping (s), >= 0: modal damping ratio beta w/2 */
    int mass;         /* MECH_BEAM_LUMPED (0, in the node bodies) or MECH_BEAM_CONSISTENT */
} mech_section;

/* One element between node bodies node_a and node_b (element ids of mech_body instances whose
 * states are set to their initial positions with identity orientation), E0: the initial local
 * frame (3x3, column-major: e1 along the beam from a to b, e2, e3), L0 the initial length.
 * Ports 0 and 1 must be bonded to ports of node_a and node_b at their mass centres.
 * Accepted: sec not NULL and as stated above; E0 not NULL, finite, orthonormal to 1e-9 and
 * right-handed (e3 = e1 x e2); L0 finite and > 0; node_a != node_b, both rigid bodies made
 * before. With mass = MECH_BEAM_CONSISTENT the node bodies must carry the point masses
 * rho A L0 / 2 of the element at their centres (mech_body_add_mass), as the chain builder's do;
 * a single element has no gravity of its own (the nodes' weights are lumped).
 * Anything else gives BG_ERR_ARGUMENT before anything is built, with a message naming
 * the element's path and the parameter (nothing is added to the model). */
BG_API int mech_beam(bgr_model *m, bgr_comp c, const char *name, int node_a, int node_b,
                     const mech_section *sec, const double *E0, double L0);

/* The deformation energy W of an element at a state vector y (after bgr_compile); NaN if elem
 * is not a beam element of a compiled model, or y is NULL. */
BG_API double mech_beam_energy(const bgr_model *m, int elem, const double *y);
/* The power the element's damping dissipates at a state vector y (after bgr_compile): twice the
 * dissipation function, beta d'^T K d' >= 0 (0 without damping), d' the rates of the local
 * deformations from the node velocities in y; NaN as for the energy. */
BG_API double mech_beam_dissipation(const bgr_model *m, int elem, const double *y);
/* The kinetic energy the element adds to its node bodies' at a state vector y (after
 * bgr_compile): consistent mass, sum_g m w_g |r_g'|^2 / 2 - (m/4)(|v_a|^2 + |v_b|^2); 0 for a
 * lumped element; NaN as for the energy. */
BG_API double mech_beam_kinetic(const bgr_model *m, int elem, const double *y);
/* The 12 port loads (F_a, M_a, F_b, M_b) of a beam element at a state vector y, for tests:
 * path 0 as the residual computes them (plain arithmetic, one reverse pass), path 1 by the
 * automatic differentiation the Jacobian uses. BG_OK, or BG_ERR_ARGUMENT (not a beam element of
 * a compiled model, NULL arrays, another path). */
BG_API int mech_beam_loads(const bgr_model *m, int elem, const double *y, int path, double g[12]);

#ifdef __cplusplus
}
#endif

/* The chain builder comes with the element, so that a program that includes this header alone
 * keeps its declarations (mech_beam_chain.h includes this one for mech_section; the include
 * guards end the cycle whichever of the two comes first). */
#include "mech_beam_chain.h"

#endif
