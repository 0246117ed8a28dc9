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
 * Three elements (section.element).
 * MECH_BEAM_LUMPED (the default): the energy W above; no mass in the element: the chain builder
 * (mech_beam_chain.h) lumps it into the node bodies. Second order in 1/n: at 8 elements the
 * clamped-free bending frequencies are off by 7e-3, 2.4e-2, 3.9e-2, the tip of the elastica at
 * P L^2 / (E I) = 10 by 8e-3 L (2e-3 L at 16).
 * MECH_BEAM_CONSISTENT: at 8 elements the clamped-free bending frequencies off by 1.4e-11,
 * 2.1e-8, 1.3e-6 (eighth order in 1/n, pinned-pinned too; sixth with other supports), the
 * elastica's tip at k = 10 by 2.1e-5 L, 1.5e-6 L at 16 (fourth order: the cubic field); the
 * tables are in docs/beam.md and tests/components/mechanics/test_beam_consistent.c. Spinning
 * (Southwell's cantilever, gamma = 12; tests/components/mechanics/test_modes_rotating.c) its
 * frequencies are those of the cubic Hermite model with the exact centrifugal tension and the
 * same mass, to 1.4e-6: at 8 elements 7.4e-5, 4.0e-5, -1.4e-4 flapwise, 4.4e-4, 4.5e-5,
 * -1.4e-4 lead-lag (fourth order; 2.8e-5 at most at 16), the cubic field's own error: the
 * clamped root's boundary layer, of width sqrt(EI / T(0)) = 0.12 L about one element, in the
 * first modes (the lead-lag's, omega^2 - Omega^2 of the flapwise one, magnifies it), and the
 * mass template's correction, made for the bending operator and not for the tension's, in the
 * third (-1.4e-4 where it is -1.3e-6 at rest). From four
 * changes, the first three the local form of the cubic (Hermite) field across the chord that
 * the local bending stiffness comes from, the fourth a correction of its mass:
 *   1. Angles: theta of a node is the rotation vector of its triad relative to the element frame
 *      (the logarithm phi n of E^T T, from its skew part sin(phi) n: theta = s asin|s| / |s|)
 *      instead of the skew part itself, which is short by phi^3 / 6.
 *   2. Bowing: the axial strain is that of the cubic field's arc, L (1 + bow / 30) over the
 *      current chord L = |x_b - x_a| (change 3), eps = u / L0 + (L / L0) bow / 30, bow = 2
 *      theta_a^2 - theta_a theta_b + 2 theta_b^2 summed over both bending planes, in the energy
 *      EA L0 eps^2 / 2 (the shallow-arch local element of Crisfield, Non-linear Finite Element
 *      Analysis of Solids and Structures vol. 1, 1991; it gives the axial force its
 *      consistent geometric stiffness 6 N / (5 L0) across (times L / L0), where the chord alone
 *      gives N / L0).
 *   3. Inertia: the node bodies keep the lumped masses and rotary inertias, and the element adds
 *      the kinetic energy of its distributed mass over the co-rotational field, less those
 *      (Crisfield, Galvanetto and Jelenic, "Dynamics of 3-D co-rotational beams", Comput. Mech. 20
 *      (1997); Le, Battini and Hjiaj, "A consistent 3D corotational beam element for nonlinear
 *      dynamic analysis of flexible structures", CMAME 269 (2014): cubic local interpolation).
 *      The fields, xi = s/L0 in [0, 1], H1 = xi (1 - xi)^2, H2 = -xi^2 (1 - xi):
 *        r(xi)  = x_a + xi (x_b - x_a) + L [H1 P + H2 Q] - L [F(xi) - xi F(1)] e1,
 *                 P = theta_z,a e2 - theta_y,a e3,  Q = theta_z,b e2 - theta_y,b e3,
 *                 F(xi) = int_0^xi (psi_y^2 + psi_z^2) / 2 dxi (psi_y,z below; F(1) = the
 *                 bowing term / 30),
 *        D2(xi) = e2 + psi_x e3 - psi_z e1,  D3(xi) = e3 - psi_x e2 + psi_y e1,
 *        psi_x = (1 - xi) theta_x,a + xi theta_x,b,  psi_y,z = H1' theta_y,z,a + H2' theta_y,z,b
 *      (D2, D3: the section's directors turned by its small local rotation psi; the last term
 *      of r, second order, is the foreshortening of the arc inside the element, the part of the
 *      axial motion the chord does not carry, after Kane, Ryan and Banerjee, "Dynamics of a
 *      cantilever beam attached to a moving base", J. Guidance 10 (1987) 139: with it the axial
 *      loads on the points, centrifugal or weight, do their work on the arc's shortening, the
 *      geometric stiffness of their variation along the element, int (N(x) - N) w'^2 / 2 dx,
 *      which the element's constant axial force N misses; spinning at gamma = 12 it moves the
 *      frequencies by up to 3.3e-4 at 4 elements, 9e-6 at 8). The field across the chord is
 *      scaled by the current chord L, not L0, so that its slopes at the nodes are the node
 *      rotations theta however the element is stretched (with L0 they were short by the axial
 *      strain u / L0: the fields of neighbouring elements then disagreed with the nodes by that
 *      strain times their local rotations, and the frequencies of an axially loaded chain kept
 *      an error eps (k h)^2, second order in the element size: 5e-7 on the crane boom's second
 *      bending frequency at 16 quartic elements, against 2e-9 with L; docs/beam.md); the kinetic
 *      energy T = sum_g w_g L0 [rho A |r_g'|^2 + rho I_z |D2_g'|^2 + rho I_y |D3_g'|^2] / 2
 *      at the 4 Gauss points xi_g (exact for the cubic field at small deformation; a section
 *      with directors e2, e3 of "masses" I_z, I_y has the rotary inertia I_y + I_z, I_y, I_z
 *      about e1, e2, e3), less the same of the node bodies (r = x, D = the triad's t2, t3, half
 *      the element's mass and rotary inertia at each). Every point p of T moves with its field,
 *      so d'Alembert's principle gives its inertia loads exactly, with r_p'' = G_p u'' + G_p' u'
 *      (u' the nodes' velocities v, omega = R w; G_p = dr_p/du the velocity gradient, G_p' its
 *      rate along the motion, the centrifugal and Coriolis terms):
 *        f = sum_p mu_p G_p^T (r_p'' - g)   (g: the chain's gravity on the displacement points:
 *                                            the distributed weight, with its end moments)
 *      Linearised at a straight rest state this is the classical consistent mass (cubic across,
 *      linear along, with the consistent rotary inertia), plus change 4. T is conserved with
 *      the rest of the model's energy. The Jacobian is exact at rest (modes, static starts); in
 *      motion it leaves out the derivatives of G_p' u' with respect to the configuration and of
 *      omega = R w, R w' with respect to the nodes' orientations (terms of the size of the
 *      inertia loads times the rotation rates, which the Newton iteration absorbs). The
 *      residual of this element takes the automatic-differentiation path with the second
 *      derivatives along the motion only (mech_ad.h, order 3: the points' accelerations need
 *      the fields' Hessians times the configuration's rate), over 20 times the cost of the
 *      lumped element's plain residual (docs/beam.md: the crane's boom at 3 and 4 consistent
 *      elements against its 16 lumped ones).
 *   4. Bending mass: a mass template (Felippa, Guo and Park, "Mass matrix templates: general
 *      description and 1D examples", Arch. Comput. Methods Eng. 22 (2015) 1-65: a mass matrix
 *      with free entries fixed by the dispersion of waves on a uniform mesh). The cubic field's
 *      consistent mass gives the eigenvalues the error (k h)^4 / 720 (frequencies: / 1440;
 *      6.1e-4 on the cantilever's third mode at 8 elements). T gets the further term
 *        T_4 = rho A L0^3 / 35280 [54 |E|^2 - 138 E.(A + B) + 94 (|A|^2 + |B|^2) + 34 A.B],
 *      E = e1', A = t1_a', B = t1_b' (the rates of the chord's and the node triads' first axes,
 *      in each bending plane the rates of the chord's and the end slopes; A = B = E in any rigid
 *      motion of the straight element, where T_4 = 0; no axial or torsional part), so that the
 *      bending mass in each plane, u = (w_a, L0 s_a, w_b, L0 s_b) (w the transverse
 *      displacement, s = dw/dx), is
 *        M = rho A L0 / 17640 [6606 993 2214 -477; 993 262 477 -109; 2214 477 6606 -993;
 *                              -477 -109 -993 262]
 *      (consistent: rho A L0 / 420 [156 22 54 -13; 22 4 13 -3; 54 13 156 -22; -13 -3 -22 4];
 *      both positive definite, the smallest eigenvalue 5.2e-3 and 4.9e-4 of rho A L0, so that
 *      T stays a positive definite form in the velocities). T_4 is taken as three more points
 *      of the kind above, 54 |E - 23/18 (A + B)|^2 - 98/3 |A + B|^2 + 77/2 |A - B|^2 for the
 *      bracket (the vectors times L, the "masses" times rho A L0 / 17640), with their inertia
 *      loads by d'Alembert's principle as the others'.
 *      Derivation: a symmetric element mass [a b c d; b e -d f; c -d a -b; d f -b e] in units
 *      of rho A h, with a + c = 1/2 (the mass), has five free entries. On the uniform infinite
 *      mesh of elements h with K = EI/h^3 [12 6 -12 6; 6 4 -6 2; ...], the Bloch waves
 *      (w, h s)_j = (W, S) exp(i j phi), phi = k h, solve det(K(phi) - lambda M(phi)) = 0,
 *      lambda = omega^2 rho A h^4 / EI; its acoustic root is lambda = phi^4 (1 + C1 phi^2 +
 *      C2 phi^4 + C3 phi^6 + O(phi^8)) with C1 = -(2a - 8d + 4e + 4f - 1) / 2, then (C1 = 0)
 *      C2 = -(240 d + 120 e - 600 f + 1) / 720, then (C2 = 0) C3 = -(907200 (e - f)^2
 *      - 28560 e + 62160 f + 407) / 1209600 (b drops out: its terms cancel between the two
 *      elements at a node). C1 = C2 = C3 = 0 (the frequencies' error of eighth order away from
 *      the ends) and the exact kinetic energy of a rigid rotation (a + 2e - 2d + 2f - 2b = 1/3)
 *      leave one parameter, u = e - f; the ends of a mesh add an error of sixth order, which
 *      u = 53/2520 cancels on the clamped-free beam (found by measurement on the matrix
 *      eigenproblem at 16 to 48 elements; any u in 0.017 .. 0.025 keeps its third frequency
 *      within 4e-5 at 8 elements). The consistent mass has C2 = 1/720; its mean with the mass
 *      of the nodal rule with end derivatives, h (f_a + f_b) / 2 + h^2 (f_a' - f_b') / 12
 *      ("Block diagonal and higher order mass matrices for Hermite beam elements", Chinese J.
 *      Comput. Mech. 2024) is C1 = C2 = 0 too, but keeps a larger end term: 1.8e-4 on the
 *      cantilever's third frequency at 8 elements, and an indefinite element mass. Other
 *      supports (the matrix eigenproblem), third mode at 8 elements: pinned-pinned 5.4e-6,
 *      clamped-pinned 6.9e-5, clamped-clamped 2.1e-4, free-free 2.5e-4 (the consistent mass:
 *      1.3e-3 .. 2.4e-3); at 4 elements the free-free third mode is worse (1.5e-2 against
 *      7.9e-3).
 * MECH_BEAM_QUARTIC: the consistent element's changes 1 to 3 (angles, bowing, inertia) on a
 * field one degree higher: in each bending plane the cubic field gets a bubble, B(xi) =
 * xi^2 (1 - xi)^2 (zero, with its slope, at both nodes), whose amplitudes b_y, b_z are unknowns
 * of the element itself, the hierarchical enrichment of p-version finite elements (Szabo and
 * Babuska, Finite Element Analysis, 1991, ch. 6; for rotating beams, Hodges and Rutkowski,
 * AIAA J. 19 (1981) 1459: variable-order elements that reach Southwell's coefficients with a
 * few elements). The element's states are b_y, b_z and their rates c_y, c_z, its equations
 * b' = c and the bubbles' equations of motion (d'Alembert's principle over the same points as
 * the ports' loads, plus the bubble's elastic and damping forces). In the fields above, with
 * V = b_z e2 - b_y e3 (the bubble in the element frame, in the convention of P and Q):
 *   r(xi) += L B(xi) V,   psi_y += B'(xi) b_y,   psi_z += B'(xi) b_z,
 * and F(xi) the foreshortening of the whole quartic arc (its integrals of products of H1', H2',
 * B'); the energy gets, per bending plane with the bending stiffness EI of that plane,
 *   EI / (2 L0) int B''^2 b^2 = (2/5) EI b^2 / L0   (B'' is orthogonal to the linear
 *                                                     curvatures of the cubic part: no coupling)
 * and the bowing term of the axial strain ((ta - tb) b + 2 b^2 / 7) / 30 (int H1' B' = 1/30,
 * int H2' B' = -1/30, int B'^2 = 2/105), so that the bubble takes the axial force's geometric
 * stiffness too. The mass is the consistent mass of the quartic field (5 Gauss points, exact
 * at small deformation), without change 4's template (which was made for the cubic field).
 * Damping (beta > 0) adds beta (4/5) EI / L0 c per plane to the bubble's equation (its part of
 * beta d'^T K d'). Euler-Bernoulli only: kappa > 0 is refused. Accuracy (tests/components/
 * mechanics/test_modes_rotating.c, test_beam_quartic.c): spinning (Southwell's cantilever,
 * gamma = 0 .. 12) the first three bending frequencies in both planes within 4.7e-6 at 8
 * elements (the consistent element: 4.4e-4 at gamma = 12); the crane's boom at 2 elements
 * within 1e-3 (docs/beam.md). The residual costs about 1.4 times the consistent element's per
 * element (16 AD variables instead of 14, 28 basis vectors, 5 points), fewer elements do the
 * same work. The bubble's own mode, the element's first clamped-clamped one (omega = 22.4
 * sqrt(EI / (rho A L0^4))), is among the mesh's highest: an undamped run that excites it
 * resolves it (a free chain of 4 elements bending and spinning, rtol 1e-6: 3.7 times the
 * consistent element's steps); stiffness-proportional damping damps it the most.
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

/* The element (mech_section.element): see above. */
enum { MECH_BEAM_LUMPED = 0, MECH_BEAM_CONSISTENT = 1, MECH_BEAM_QUARTIC = 2 };

/* Accepted: every field finite; E, G, A, Iy, Iz, J > 0; rho, kappa, beta >= 0 (the chain
 * builder, and element = MECH_BEAM_CONSISTENT or MECH_BEAM_QUARTIC, need rho > 0; the quartic
 * element kappa = 0); the stiffnesses they give (EA/L0, GJ/L0, EI/L0, times beta) finite;
 * element one of the three values. */
typedef struct mech_section {
    double E, G;      /* Young's and shear modulus (Pa), > 0 */
    double A, Iy, Iz; /* area (m^2); second moments about the local y (e2) and z (e3) axes (m^4),
                         > 0 */
    double J;         /* torsion constant (m^4), > 0 */
    double rho;   /* density (kg/m^3; for the chain builder's lumped masses), >= 0 (chain: > 0) */
    double kappa; /* shear correction factor: 0 Euler-Bernoulli, > 0 Timoshenko */
    double beta;  /* stiffness-proportional damping (s), >= 0: modal damping ratio beta w/2 */
    int element;  /* MECH_BEAM_LUMPED (0, masses in the node bodies), MECH_BEAM_CONSISTENT or
                     MECH_BEAM_QUARTIC */
} mech_section;

/* One element between node bodies node_a and node_b (element ids of mech_body instances whose
 * states are set to their initial positions with identity orientation), E0: the initial local
 * frame (3x3, column-major: e1 along the beam from a to b, e2, e3), L0 the initial length.
 * Ports 0 and 1 must be bonded to ports of node_a and node_b at their mass centres.
 * Accepted: sec not NULL and as stated above; E0 not NULL, finite, orthonormal to 1e-9 and
 * right-handed (e3 = e1 x e2); L0 finite and > 0; node_a != node_b, both rigid bodies made
 * before. With element = MECH_BEAM_CONSISTENT or MECH_BEAM_QUARTIC the node bodies must carry
 * half of the element's mass rho A L0 and rotary inertia rho (I_y + I_z, I_y, I_z) L0 at their
 * centres, as the chain builder's do; a single element has no gravity of its own (the nodes'
 * weights are lumped). A quartic element has four states of its own (bubble_y, bubble_z and
 * their rates bubble_y_rate, bubble_z_rate; zero: straight and at rest) and four equations.
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
 * bgr_compile): the consistent (or quartic) element's T less the nodes' share (above); 0 for a
 * lumped element; NaN as for the energy. */
BG_API double mech_beam_kinetic(const bgr_model *m, int elem, const double *y);
/* The 12 port loads (F_a, M_a, F_b, M_b) of a beam element at a state vector y, for tests:
 * path 0 as the residual computes them (plain arithmetic, one reverse pass; the quartic
 * element has no such path and gives path 1's), path 1 by the automatic differentiation the
 * Jacobian uses. BG_OK, or BG_ERR_ARGUMENT (not a beam element of
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
