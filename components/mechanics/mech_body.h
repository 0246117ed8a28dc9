/* 3D rigid body with ports at material points.
 *
 * Conventions of the mechanical components: every port is expressed in the global frame; its flow
 * is the velocity of the connection point (and, for 6D ports, the angular velocity), its effort
 * the force (and moment about the point) that the bond's partner exerts on the element at the
 * bond's head; an element at the bond's tail feels the opposite (force on the element = s e with
 * s = +1 at the head, -1 at the tail), so the power into an element is s e.f and a bond conserves
 * power.
 *
 * Unknowns (states): mass-centre position x and velocity v (global), angular velocity w in the
 * body frame, orientation quaternion q = (q0, q1, q2, q3) (body to global: R(q), see
 * mech_util.h for the homogeneous form that makes the drift of |q| harmless). Under a co-moving
 * frame's motion (bgr_declare_frame, bgr_frame_rotation) x is a point, v and every port quantity
 * a global vector, q an orientation; w, in the body frame, does not change (mech_frame.h).
 * Equations, for ports k at body-frame points r_k (mass-centre origin):
 *     x' = v
 *     m v' = sum_k s_k F_k + m g                                       (translation, global)
 *     J w' + w x (J w) = sum_k [ r_k x (R^T s_k F_k) + R^T s_k M_k ]    (Euler, body frame)
 *     q' = q (x) (0, w) / 2
 *     v_k = v + R (w x r_k),    omega_k = R w   (6D ports only)
 * These are the Newton-Euler equations (dp/dt = F_C in the global frame, dH/dt + w x H = M in
 * the body frame, v_k = v_C + w x r_Ck), with the port quantities rotated to the global frame
 * here so that joints and springs need no orientation of their own.
 * J: inertia tensor about the mass centre in the body frame (symmetric positive definite). */
#ifndef MECH_BODY_H
#define MECH_BODY_H

#include "bg_api.h"
#include "bgr_model.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Ports 0..nports-1 at body-frame points r (3 per port); dims[k] = 6 (force and moment) or 3
 * (force only; NULL: all 6). gravity: 3 values (NULL: none). Returns the element id or < 0.
 * States are named x0 x1 x2 v0 v1 v2 w0 w1 w2 q0 q1 q2 q3 under the element's path.
 * Accepted: mass finite and > 0 (kg); inertia not NULL, 3x3 column-major (kg m^2), finite,
 * exactly symmetric and positive definite; gravity finite; nports 0 .. 64, r not NULL when
 * nports > 0 and finite; dims[k] 3 or 6. Anything else gives BG_ERR_ARGUMENT before anything is
 * built, with a message naming the body's path and the parameter (nothing is added). */
BG_API int mech_body(bgr_model *m, bgr_comp c, const char *name, double mass, const double *inertia,
                     const double *gravity, int nports, const double *r, const int *dims);

/* A point mass dm (kg) at the body's mass centre, added before bgr_compile: the body's mass
 * becomes mass + dm (its weight with it), the inertia tensor about the mass centre stays (a point
 * at the reference point adds none). For masses lumped into a node: a member's share at its end
 * (a truss's lumped mass matrix puts half of rho A L at each end). BG_OK, BG_ERR_ARGUMENT (body
 * is not a body, dm not finite and >= 0), BG_ERR_STATE (model compiled). */
BG_API int mech_body_add_mass(bgr_model *m, int body, double dm);

/* Initial state (after bgr_compile): position x and velocity v of the mass centre, body
 * angular velocity w (x, v, w NULL: zero), orientation q (NULL: identity); written into bgr_y0.
 * BG_OK, or BG_ERR_ARGUMENT if body is not a body of a compiled model. */
BG_API int mech_body_set(bgr_model *m, int body, const double *x, const double *v, const double *w,
                         const double *q);

/* Kinetic energy (1/2 m v.v + 1/2 w.J w) and the potential of gravity (-m g.x) at a state y;
 * BG_OK or BG_ERR_ARGUMENT if body is not a body of a compiled model or a pointer is NULL. */
BG_API int mech_body_energy(const bgr_model *m, int body, const double *y, double *kinetic,
                            double *potential);

/* Variable ids of the states (after bgr_compile): first of x, v, w, q; -1 if body is not a body
 * of a compiled model or which is not one of 'x', 'v', 'w', 'q'. */
BG_API int mech_body_var(const bgr_model *m, int body, char which);

/* Nominal magnitudes (bgr_declare_nominal: the solver's absolute tolerance of an unknown is atol
 * times its nominal) of the unknowns of a mechanical element: body, point mass, support,
 * spherical or revolute joint, spring, truss, rope or beam element. Stated before bgr_compile:
 * force (N) for its port forces (a support's or joint's reactions), moment (N m) for its port
 * moments (and a revolute joint's drive torque), length (m) for its positions (body and point
 * mass x, the vector d of an axial element); 0 keeps what the element has (a later call replaces
 * a stated value). What each element declares from its own parameters:
 *   body          forces m |g| (with gravity: its weight), moments that force times its longest
 *                 port arm max |r_k|; positions only when a length is stated
 *   point mass    forces m |g|; positions only when stated
 *   axial         d: L0 (|d| is the member's length); forces only when stated (the stiffness
 *                 times a deformation the parameters do not give, or the weight it carries)
 *   beam element  forces only when stated (mech_beam_chain states the chain's weight rho A L |g|
 *                 when it has gravity); moments that force times L0 (the element's
 *                 equilibrium ties its end moments to its shear forces over L0)
 *   support, joints   only what is stated (the reactions depend on what they carry)
 * Velocities, angular velocities and quaternions keep 1 (no time scale among the parameters;
 * |q| = 1); a bond shared by two elements gets the larger of their declarations. BG_OK,
 * BG_ERR_ARGUMENT (id not a mechanical element, a value < 0 or not finite), BG_ERR_STATE (model
 * compiled). */
BG_API int mech_set_nominal(bgr_model *m, int id, double force, double moment, double length);

#ifdef __cplusplus
}
#endif
#endif
