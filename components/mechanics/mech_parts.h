/* Point mass, fixed support and the two joints of the mechanical library. Conventions as in
 * mech_body.h: global frame; flow = velocity (and angular velocity), effort = force (and moment)
 * on the element at the bond's head, s = +1 there and -1 at the tail.
 *
 * Point mass (3D port):   x' = v,   m v' = s F + m g,   v_port = v.
 * Fixed support (3D or 6D port): all flows zero; the efforts are the reactions (index 2).
 * Spherical joint between ports A and B (both 3D or both 6D):
 *     v_A = v_B,   s_A F_A + s_B F_B = 0,   and for 6D ports s_A M_A = 0, s_B M_B = 0.
 * Revolute joint between 6D ports A and B, axis a fixed in the frame of body A (a = R_A a_A, or
 * a constant global axis when A is the ground), optional 1D drive port d:
 *     v_A = v_B,  (w_B - w_A).e1 = 0,  (w_B - w_A).e2 = 0        (e1, e2 = R_A e1_A, R_A e2_A,
 *                                                                  an orthonormal pair _|_ a)
 *     s_A F_A + s_B F_B = 0,   s_A M_A + s_B M_B = 0,
 *     (s_B M_B).a + s_d e_d = 0   (no drive: (s_B M_B).a = 0),   f_d = (w_B - w_A).a.
 * (s_B M_B is the moment on the joint at B, so body B receives s_d e_d about a.) Power is
 * conserved: the bodies receive s_d e_d f_d, the drive's input. The reactions (forces
 * and the moments across the axis) are index-2 unknowns: the constraints are written on the
 * velocities (the flows of the bond graph), not on the positions.
 *
 * Revolute joint with a prescribed angle (mech_revolute_angle): the joint's rotation theta of
 * body B relative to body A about a follows a profile theta_ref(t). The joint's equations above
 * without a drive port, the drive torque tau an own unknown in its place:
 *     (s_B M_B).a + tau = 0,        theta_ref'(t) - (w_B - w_A).a = 0,
 * so that body B receives tau about a (A the opposite), and tau, fixed only through the
 * derivative of the rate constraint, is an index-2 unknown like the other reactions. The rate
 * constraint alone lets the angle drift (the integration error of the rate accumulates: at rtol
 * 1e-6, 3.4e-6 rad after 100 s of a driven pendulum, 2.2e-5 after 15 s of a hub slewing a
 * flexible beam); the angle itself is stated as a position invariant (bgr_model.h, "Position
 * invariants"):
 *     g(t, y) = remainder(theta(q_A, q_B) - theta_ref(t), 2 pi) = 0,
 *     theta = atan2((R_A e2).(R_B e1), (R_A e1).(R_B e1)),
 * e1, e2 the joint's orthonormal pair _|_ a in A's frame (a constant global pair when A is the
 * ground; R_B = I when B is the ground): the geometric angle of B's frame relative to A's,
 * measured about a, zero where the two frames coincide (R_A^T R_B = rotation about a_A by
 * theta gives theta, for any choice of e1), counted modulo 2 pi so that theta_ref may run past
 * pi (a motor turning on). Its gradient is taken with respect to the quaternions of the bodies,
 * which the projection (dae_options.projection = 1) then corrects after every step, by the
 * smallest change of the quaternions: the angle follows theta_ref to rounding, with no drift.
 * Cost (tests/components/mechanics/test_mech_angle_drive.c): none on rigid bodies (the pendulum:
 * 6 489 steps, the rate drive 6 653), 1.7 times the rate drive's steps on the flexible hub (the
 * correction of the hub's orientation at each step, up to 4e-7 rad, is not shared by the beam's
 * nodes and shows in their error estimates). Set the bodies' initial orientations and angular
 * velocities so that theta(0) = theta_ref(0) and the rate holds (dae_consistent_init does not
 * move the orientations for an invariant; the projection moves them at the first step). */
#ifndef MECH_PARTS_H
#define MECH_PARTS_H

#include "bg_api.h"
#include "bgr_model.h"

#ifdef __cplusplus
extern "C" {
#endif

/* States x0 x1 x2 v0 v1 v2; gravity may be NULL.
 * Accepted (every constructor of this file): mass finite and > 0; gravity finite; dim 3 or 6;
 * axis_a not NULL, finite and nonzero; body_a >= -1 (a rigid body's id, checked by
 * bgr_compile). Anything else gives BG_ERR_ARGUMENT before anything is built, with a message
 * naming the element's path and the parameter (nothing is added to the model). */
BG_API int mech_point_mass(bgr_model *m, bgr_comp c, const char *name, double mass,
                           const double *gravity);
BG_API int mech_point_mass_set(bgr_model *m, int id, const double *x, const double *v);
/* Kinetic energy and the potential of gravity (-m g.x) at a state y (BG_ERR_ARGUMENT if id is
 * not a point mass of a compiled model, or a pointer is NULL). */
BG_API int mech_point_mass_energy(const bgr_model *m, int id, const double *y, double *kinetic,
                                  double *potential);

BG_API int mech_support(bgr_model *m, bgr_comp c, const char *name, int dim);

/* dim 3 or 6: ports 0 (A) and 1 (B). */
BG_API int mech_spherical(bgr_model *m, bgr_comp c, const char *name, int dim);

/* Ports 0 (A, 6D), 1 (B, 6D) and, if drive, 2 (1D: relative rotation rate and drive torque).
 * body_a: the element id of the body whose frame carries the axis axis_a (-1: axis_a is a fixed
 * global axis). */
BG_API int mech_revolute(bgr_model *m, bgr_comp c, const char *name, int body_a,
                         const double *axis_a, int drive);

/* The angle profile of mech_revolute_angle: theta_ref(t) (rad), its rate (rad/s) into *rate.
 * Smooth between the breakpoints given to the solver (its second derivative, the acceleration,
 * sets the drive torque; a corner of the rate is a jump of the torque); a value that is not
 * finite makes the residual and the invariant NaN (the step fails, the message names the
 * joint's rate equation). */
typedef double (*mech_angle_fn)(void *user, double t, double *rate);

/* A revolute joint whose angle follows theta(user, t): ports 0 (A, 6D) and 1 (B, 6D), the drive
 * torque its own unknown (named "torque", bgr_ref {BGR_OWN, id, 0}), and one position invariant
 * ("angle"). body_a as for mech_revolute; body_b: the element id of the body at port B (-1: the
 * ground), a different one from body_a, not both -1. The joint cannot tell which bodies are
 * bonded to its ports: body_a and body_b must be those (bgr_compile checks that they are rigid
 * bodies). Accepted as mech_revolute, and theta not NULL; else BG_ERR_ARGUMENT with a message
 * naming the joint and the parameter. */
BG_API int mech_revolute_angle(bgr_model *m, bgr_comp c, const char *name, int body_a,
                               const double *axis_a, int body_b, mech_angle_fn theta, void *user);
/* The same with the profile of a signal source (sig_sources.h, element id source, evaluated in
 * closed form by sig_evaluate; its breakpoints are the model's already): with the output value,
 * theta_ref = u(t) and theta_ref' = u'(t); with the output integral, theta_ref = the integral of
 * u from 0 to t and theta_ref' = u(t) (a trapezoid of the rate gives a point-to-point move).
 * The output rate is refused by bgr_compile (its derivative u'' is not available), as is an
 * element that is not a signal source. */
BG_API int mech_revolute_angle_source(bgr_model *m, bgr_comp c, const char *name, int body_a,
                                      const double *axis_a, int body_b, int source);

#ifdef __cplusplus
}
#endif
#endif
