/* The standard bond-graph elements, in d dimensions (the d components of a bond are independent
 * unless a matrix couples them). Sign convention: power is positive into one-port elements
 * (I, C, R) and out of sources (Se, Sf); an element whose bond points the other way sees the
 * flow with the opposite sign. TF and GY take power in at port 0 and give it out at port 1.
 * Junctions accept any orientation: s_k = +1 for a bond ending at the junction, -1 otherwise.
 *
 *   I   states p:  p' = e,            M f_in = p    (M = m I or a d x d matrix; or f = phi(p))
 *   C   states q:  q' = f_in,         e = k q       (or e = psi(q))
 *   R               e = r f_in                      (or e = phi(f_in))
 *   Se              e = E             (constant vector, function of t, or a signal)
 *   Sf              f_out = F         (idem; F = 0 makes the effort a constraint effort)
 *   TF              e0 = m e1,        f1_out = m f0_in     (m constant or a signal)
 *   GY              e0 = r f1_out,    e1 = r f0_in
 *   0-junction      e_k = e_0 (k > 0),  sum_k s_k f_k = 0
 *   1-junction      f_k = f_0 (k > 0),  sum_k s_k e_k = 0
 *   gain (signal)   z = g x             (x any unknown: a sensor, or a signal path)
 * TF, GY and the junctions conserve power exactly: sum of e.f over their ports is zero.
 * Nominal magnitudes (bgr_declare_nominal): a constant Se or Sf declares |E_i| (|F_i|) for the
 * effort (flow) it imposes, where nonzero; the other elements have no scale of their own (a
 * stiffness, mass or resistance relates two scales but sets neither) and declare nothing.
 *
 * Every constructor returns the element id (>= 0) or a negative status with the message in the
 * model's error record; ports are numbered 0, 1, ... as listed. Statuses: those of
 * bgr_element_add (BG_ERR_ARGUMENT for a NULL model or name, BG_ERR_STATE once the model is
 * compiled), and BG_ERR_ARGUMENT for a parameter out of the range stated next to it below: a
 * dimension d < 1 (I, C: above 16 as well), a NULL mass matrix or function, a junction with
 * fewer than 2 ports, and every number that is NaN or infinite or breaks its rule. The
 * parameters are checked before anything is built: a refused element is not added (its name
 * stays free), and the message names the element by its path (component path / name as given),
 * the constructor, the parameter and what was expected, e.g.
 *     element model/drive/m (bgr_I): mass = -1, expected a finite number > 0
 * A signal that refers to no unknown is reported by bgr_compile. */
#ifndef BGR_ELEMENTS_H
#define BGR_ELEMENTS_H

#include "bg_api.h"
#include "bgr_model.h"

#ifdef __cplusplus
extern "C" {
#endif

/* y = f(x) with dy/dx into *dfdx. */
typedef double (*bgr_fn)(void *user, double x, double *dfdx);
/* A function of time. */
typedef double (*bgr_time_fn)(void *user, double t);

/* d: 1 .. 16; mass: finite, > 0 (0 would make M f = p singular). */
BG_API int bgr_I(bgr_model *m, bgr_comp c, const char *name, int d, double mass);
/* d: 1 .. 16; M: d x d, column-major, finite, exactly symmetric (M[i + j d] == M[j + i d]) and
 * positive definite (its Cholesky factorisation has positive pivots). */
BG_API int bgr_I_matrix(bgr_model *m, bgr_comp c, const char *name, int d, const double *M);
/* phi: not NULL (it is the user's to keep finite). */
BG_API int bgr_I_fn(bgr_model *m, bgr_comp c, const char *name, bgr_fn phi, void *user);
/* d: 1 .. 16; stiffness: finite, >= 0 (0: no restoring effort; < 0 would store negative
 * energy). */
BG_API int bgr_C(bgr_model *m, bgr_comp c, const char *name, int d, double stiffness);
/* psi: not NULL. */
BG_API int bgr_C_fn(bgr_model *m, bgr_comp c, const char *name, bgr_fn psi, void *user);
/* d >= 1; resistance: finite, >= 0 (0: no loss; < 0 would generate power). */
BG_API int bgr_R(bgr_model *m, bgr_comp c, const char *name, int d, double resistance);
/* phi: not NULL. */
BG_API int bgr_R_fn(bgr_model *m, bgr_comp c, const char *name, bgr_fn phi, void *user);
/* d >= 1; value: d finite constants (NULL: zeros). fn (the _fn forms): not NULL. */
BG_API int bgr_Se(bgr_model *m, bgr_comp c, const char *name, int d, const double *value);
BG_API int bgr_Se_fn(bgr_model *m, bgr_comp c, const char *name, bgr_time_fn fn, void *user);
BG_API int bgr_Se_signal(bgr_model *m, bgr_comp c, const char *name, bgr_ref signal);
BG_API int bgr_Sf(bgr_model *m, bgr_comp c, const char *name, int d, const double *value);
BG_API int bgr_Sf_fn(bgr_model *m, bgr_comp c, const char *name, bgr_time_fn fn, void *user);
BG_API int bgr_Sf_signal(bgr_model *m, bgr_comp c, const char *name, bgr_ref signal);
/* d >= 1; modulus: finite, != 0 (any sign; 0 would cut the ports apart and leave the system
 * singular). A signal modulus is not checked: it is an unknown. */
BG_API int bgr_TF(bgr_model *m, bgr_comp c, const char *name, int d, double modulus);
BG_API int bgr_TF_signal(bgr_model *m, bgr_comp c, const char *name, bgr_ref modulus);
/* d >= 1; modulus: finite, != 0 (as for TF). */
BG_API int bgr_GY(bgr_model *m, bgr_comp c, const char *name, int d, double modulus);
/* nports >= 2, d >= 1. */
BG_API int bgr_zero(bgr_model *m, bgr_comp c, const char *name, int nports, int d);
BG_API int bgr_one(bgr_model *m, bgr_comp c, const char *name, int nports, int d);
/* Signal z = gain * x; its output is bgr_ref {BGR_OWN, id, 0}. gain: finite (any sign, 0
 * too). */
BG_API int bgr_gain(bgr_model *m, bgr_comp c, const char *name, bgr_ref x, double gain);

/* The classes themselves, for bgr_element_add by hand. */
BG_API extern const bgr_element_class bgr_class_I, bgr_class_C, bgr_class_R, bgr_class_Se,
    bgr_class_Sf, bgr_class_TF, bgr_class_GY, bgr_class_zero, bgr_class_one, bgr_class_gain;

#ifdef __cplusplus
}
#endif
#endif
