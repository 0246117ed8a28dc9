/* The static start and the trim of model files (mdl_static) against closed forms: a mass hanging
 * on a linear spring from a fixed point rests at z = -(L0 + m g / k); trimmed to rest at z = -1
 * the spring's unstretched length must come out as 1 - m g / k. A bracket that cannot hold the
 * condition is refused with the names and values. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "bgr_model.h"
#include "mdl_model.h"
#include "tap.h"

static const char *model_text(const char *trim)
{
    static char buf[4096];
    snprintf(buf, sizeof buf,
             "format: bgsim 1\n"
             "name: hanging\n"
             "parameters: {m: 2, k: 400, L0: 0.8, g: 9.81}\n"
             "components:\n"
             "  top: {type: mech.support, dim: 3}\n"
             "  spring: {type: mech.spring, k: k, L0: L0, c: 5}\n"
             "  load: {type: mech.point_mass, mass: m, gravity: [0, 0, -g], position: [0, 0, -1.2]}\n"
             "bonds:\n"
             "  - top.p -> spring.a\n"
             "  - spring.b -> load.p\n"
             "outputs:\n"
             "  z: load.x2\n"
             "  tension: k*(-load.x2 - L0)\n"
             "%s",
             trim);
    return buf;
}

int main(void)
{
    const double m = 2, k = 400, g = 9.81;
    bg_error e = {0};
    bg_error_clear(&e);
    mdl_model *mm = mdl_load_string(model_text(""), "hanging.yaml", NULL, 0, &e);
    tap_ok(mm != NULL, "the hanging mass loads (%s)", mm ? "ok" : e.message);
    if (!mm) return tap_done();
    mdl_trim_report rep;
    int r = mdl_static(&mm, NULL, &rep, &e);
    tap_ok(r == BG_OK, "static start (%s)", r == BG_OK ? "ok" : e.message);
    double out[2];
    mdl_outputs(mm, 0, bgr_y0(mdl_bgr(mm)), out, &e);
    tap_close(out[0], -(0.8 + m * g / k), 1e-7, 0, "rests at z = -(L0 + m g / k)");
    tap_close(out[1], m * g, 1e-6, 0, "the spring carries the weight m g");
    tap_ok(!rep.trimmed && rep.solves == 1, "no trim: one static solve");
    mdl_free(&mm);

    mm = mdl_load_string(model_text("trim: {adjust: L0, until: z, equals: -1, between: [0.5, 1]}\n"),
                         "hanging.yaml", NULL, 0, &e);
    tap_ok(mm != NULL, "with trim: loads (%s)", mm ? "ok" : e.message);
    if (!mm) return tap_done();
    r = mdl_static(&mm, NULL, &rep, &e);
    tap_ok(r == BG_OK, "trimmed static start (%s)", r == BG_OK ? "ok" : e.message);
    tap_close(rep.value, 1 - m * g / k, 1e-6, 0, "L0 found: 1 - m g / k = %.6f", 1 - m * g / k);
    mdl_outputs(mm, 0, bgr_y0(mdl_bgr(mm)), out, &e);
    tap_close(out[0], -1, 0, 1e-6, "the model handed back rests at z = -1");
    double L0;
    tap_ok(mdl_parameter(mm, "L0", &L0) == BG_OK && L0 == rep.value, "its L0 is the value found");
    tap_ok(rep.solves >= 3 && rep.solves <= 12, "%d static solves", rep.solves);
    mdl_free(&mm);

    mm = mdl_load_string(model_text("trim: {adjust: L0, until: z, equals: -1, between: [0.1, 0.5]}\n"),
                         "hanging.yaml", NULL, 0, &e);
    r = mm ? mdl_static(&mm, NULL, &rep, &e) : BG_ERR_ARGUMENT;
    tap_ok(r == DAE_CONV_FAIL && strstr(e.message, "cannot be met") && strstr(e.message, "L0") &&
               strstr(e.message, "z"),
           "a bracket without the condition is refused, naming L0 and z (%s)", e.message);
    mdl_free(&mm);

    mm = mdl_load_string(model_text("trim: {adjust: L1, until: z, equals: -1, between: [0.1, 0.5]}\n"),
                         "hanging.yaml", NULL, 0, &e);
    tap_ok(!mm && strstr(e.message, "hanging.yaml:14:") && strstr(e.message, "'L1'"),
           "trim of an unknown parameter: position and name (%s)", e.message);
    mdl_free(&mm);
    return tap_done();
}
