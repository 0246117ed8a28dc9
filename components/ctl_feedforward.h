/* Feedforward of a reference rate to a pump's displacement command.
 *
 * A pump of displacement Dp per revolution at full stroke, driven at w_p, feeds a motor of
 * displacement Dm per revolution geared to the load with ratio i (motor turns per load turn).
 * Without leakage and with the line's volume at rest (steady flow), the motor's flow equals the
 * pump's:
 *   x Dp w_p / (2 pi) = Dm w_m / (2 pi),   w_m = i omega,
 * so the displacement command that turns the load at the reference rate omega_r is
 *   u = k omega_r,   k = i Dm / (Dp w_p)                                   ("output")
 * (hyd_pump.h, hyd_motor.h: the ideal machines of Merritt, Hydraulic Control Systems, 1967).
 * The leakage's flow (pump and motor, proportional to the pressure difference) is not in it: a
 * feedback controller beside it (ctl_pid's feedforward input) corrects that share. The element
 * is a signal gain (bgr_gain of bgr_elements.h) with k computed from the drive's data; its
 * output is {BGR_OWN, id, 0}. */
#ifndef CTL_FEEDFORWARD_H
#define CTL_FEEDFORWARD_H

#include "bg_api.h"
#include "bgr_model.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct ctl_ff_spec {
    double ratio;            /* i, motor turns per load turn, finite, != 0 */
    double motor_disp;       /* Dm, m^3/rev, finite, > 0 */
    double pump_disp;        /* Dp, m^3/rev at x = 1, finite, > 0 */
    double pump_speed;       /* w_p, rad/s, finite, != 0 */
    bgr_ref reference_rate;  /* omega_r */
} ctl_ff_spec;

/* k = i Dm / (Dp w_p); NaN when a value is out of the ranges above. */
BG_API double ctl_feedforward_gain(const ctl_ff_spec *spec);

/* Returns the element id or < 0 (message in the model's error record; BG_ERR_ARGUMENT naming
 * the parameter for a value out of range, nothing added). */
BG_API int ctl_feedforward(bgr_model *m, bgr_comp c, const char *name, const ctl_ff_spec *spec);

#ifdef __cplusplus
}
#endif
#endif
