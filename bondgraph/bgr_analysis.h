/* Static equilibrium and modes of a compiled bond-graph model: the solver's analyses
 * (bg_static.h, bg_modes.h) on the model's problem (bgr_dae_problem: residual, analytic
 * Jacobian, names of unknowns and equations, nominal magnitudes).
 *
 * bgr_static starts from the model's initial values bgr_y0 (the model as assembled: the load
 * factor of the Newton homotopy ramps the loads the assembled state does not carry, gravity and
 * sources, and the invariants of the velocity-level joints and members are kept at their
 * assembled values) and on success writes the equilibrium into bgr_y0 and y' = yp_s (zero by
 * default) into bgr_yp0, so that a dynamic run started from them starts at rest (when the
 * continuation fails, DAE_CONV_FAIL or DAE_TOO_MUCH_WORK, bgr_y0 receives the last state at rest,
 * the equilibrium under the load factor reached, for a look at what went wrong). Messages name
 * the model's equations and unknowns (rig/beam/el03/force_a2, rig/beam/node04/x2).
 *
 * bgr_modes linearises at (t, y, yp) (y NULL: bgr_y0; yp NULL: zero) and names the modes by the
 * model's unknowns grouped by component path (dae_modes_describe with depth 2: rig/beam,
 * rig/hydraulics); the result keeps pointers to the model's names, so the model must outlive
 * it.
 *
 * Both return BG_ERR_ARGUMENT for a NULL model, BG_ERR_STATE before bgr_compile, else the
 * statuses of dae_static_solve and dae_modes_compute.
 *
 * A structure in steady rotation (bg_modes.h, "Co-moving frames"): bgr_frame_rotation builds
 * the generator S of the frame that turns at rate (rad per time unit) about the axis through
 * point, from the kinds of unknowns the elements declare (bgr_declare_frame: the mechanical
 * components declare their global vectors, positions and quaternions), and the affine part c
 * of the frame's motion (x' = Omega x (x - point) for the positions: c = -Omega x point there,
 * zero elsewhere; a user adds the constant rates of ignorable unknowns, an angle that grows at
 * a driven rate). Then, with options.frame = S in both: bgr_static with options.yp_steady = c
 * finds the state at rest in the frame (the centrifugal stretch and the tension that stiffens
 * the structure) and writes y' = S y + c into bgr_yp0; bgr_modes at (bgr_y0, bgr_yp0) gives the
 * modes in the frame, with their Coriolis and centrifugal terms. S is the caller's (free it with
 * sp_csc_free); c may be NULL, point NULL is the origin. BG_OK, BG_ERR_ARGUMENT (a NULL model,
 * S or axis; an axis that is not finite and nonzero, a rate or point not finite), BG_ERR_STATE
 * (not compiled), BG_ERR_MEMORY; the message in bgr_model_error. */
#ifndef BGR_ANALYSIS_H
#define BGR_ANALYSIS_H

#include "bg_api.h"
#include "bg_modes.h"
#include "bg_static.h"
#include "bgr_model.h"

#ifdef __cplusplus
extern "C" {
#endif

BG_API int bgr_static(bgr_model *m, const dae_static_options *o, double t, dae_static_result *res,
                      bg_error *err);
BG_API int bgr_modes(bgr_model *m, double t, const double *y, const double *yp,
                     const dae_modes_options *o, dae_modes **out, bg_error *err);
BG_API int bgr_frame_rotation(const bgr_model *m, const double *axis, double rate,
                              const double *point, sp_csc **S, double *c);

#ifdef __cplusplus
}
#endif
#endif
