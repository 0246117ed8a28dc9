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
 * velocities (the flows of the bond graph), not on the positions. */
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

#ifdef __cplusplus
}
#endif
#endif
