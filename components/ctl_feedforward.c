/* Feedforward of a reference rate to a pump (equations in ctl_feedforward.h). */
#include "ctl_feedforward.h"

#include <math.h>

#include "bgr_check.h"
#include "bgr_elements.h"

double ctl_feedforward_gain(const ctl_ff_spec *s)
{
    if (!s || !isfinite(s->ratio) || s->ratio == 0 || !(s->motor_disp > 0) ||
        !isfinite(s->motor_disp) || !(s->pump_disp > 0) || !isfinite(s->pump_disp) ||
        !isfinite(s->pump_speed) || s->pump_speed == 0)
        return NAN;
    return s->ratio * s->motor_disp / (s->pump_disp * s->pump_speed);
}

int ctl_feedforward(bgr_model *m, bgr_comp c, const char *name, const ctl_ff_spec *s)
{
    const char *w = "ctl_feedforward";
    if (!s) return bgr_refuse(m, c, name, w, "no specification (spec is NULL)");
    if (bgr_check_value(m, c, name, w, "ratio", s->ratio, BGR_NONZERO) ||
        bgr_check_value(m, c, name, w, "motor_disp", s->motor_disp, BGR_POSITIVE) ||
        bgr_check_value(m, c, name, w, "pump_disp", s->pump_disp, BGR_POSITIVE) ||
        bgr_check_value(m, c, name, w, "pump_speed", s->pump_speed, BGR_NONZERO))
        return BG_ERR_ARGUMENT;
    return bgr_gain(m, c, name, s->reference_rate, ctl_feedforward_gain(s));
}
