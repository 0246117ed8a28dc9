/* Feedforward of the reference rate to the pump (ctl_feedforward.h), against the hand
 * calculation and a run of the drive it commands.
 *
 * The paper crane's drive (crane/models/crane-parts.yaml): pump Dp = 0.1 m^3/rev driven at
 * w_p = 150 rad/s, motor Dm = 0.005 m^3/rev, gear i = 300. At omega_r = 0.5 rad/s the motor must
 * turn at i omega_r = 150 rad/s, i.e. take Dm 150 / (2 pi) = 0.1194 m^3/s, which the pump
 * delivers at x Dp 150 / (2 pi): by hand x = 300 * 0.005 * 0.5 / (0.1 * 150) = 0.05. Run: the pump
 * under the feedforward alone feeds the motor through a line volume; the motor (with viscous
 * friction, so that the line carries pressure) drives an inertia. Without leakage the flows
 * balance at the steady state: the motor's speed is then i omega_r = 150 rad/s exactly, the
 * pressure the friction's torque over Dm / (2 pi). */
#include "bgr_model.h"
#include "ctl_feedforward.h"
#include "ctltest.h"

#define PI 3.14159265358979323846

static const char *model =
    "format: bgsim 1\n"
    "name: ff\n"
    "components:\n"
    "  omega_ref: {type: sig.constant, value: 0.5}\n"
    "  ff: {type: ctl.feedforward, reference_rate: omega_ref.y, ratio: 300, "
    "motor_displacement: 0.005, pump_displacement: 0.1, pump_speed: 150}\n"
    "  drive: {type: bg.Sf, value: [150]}\n"
    "  pump: {type: hyd.pump, displacement: 0.1, command: ff.u, nominal_pressure: 1e6, "
    "nominal_speed: 150}\n"
    "  tank_in: {type: hyd.tank}\n"
    "  tank_out: {type: hyd.tank}\n"
    "  line: {type: hyd.volume, volume: 1e-3, bulk_modulus: 1e9, ports: [pump, motor], "
    "nominal_pressure: 1e6}\n"
    "  motor: {type: hyd.motor, displacement: 0.005, friction: 10, nominal_pressure: 1e6, "
    "nominal_speed: 150}\n"
    "  shaft: {type: rot.inertia, J: 1, nominal_speed: 150}\n"
    "  speed: {type: rot.sensor, inertia: shaft, quantity: velocity}\n"
    "bonds:\n"
    "  - {from: drive.p, to: pump.shaft}\n"
    "  - {from: tank_in.p, to: pump.a}\n"
    "  - {from: pump.b, to: line.pump}\n"
    "  - {from: line.motor, to: motor.a}\n"
    "  - {from: motor.b, to: tank_out.p}\n"
    "  - {from: motor.shaft, to: shaft.p}\n"
    "outputs:\n"
    "  x: ff.u\n"
    "  w_motor: speed.value\n"
    "  p: line.p\n";

int main(void)
{
    ctl_ff_spec s = {.ratio = 300, .motor_disp = 0.005, .pump_disp = 0.1, .pump_speed = 150};
    double k = ctl_feedforward_gain(&s);
    tap_ok(fabs(k * 0.5 - 0.05) < 1e-16, "the crane's feedforward at 0.5 rad/s: x = %.17g, by hand "
                                         "0.05",
           k * 0.5);
    s.pump_disp = 0;
    tap_ok(isnan(ctl_feedforward_gain(&s)), "a pump displacement of 0 gives no gain (NaN)");
    bgr_model *m = bgr_model_create("bad");
    int id = ctl_feedforward(m, 0, "ff", &s);
    tap_ok(id == BG_ERR_ARGUMENT && strstr(bgr_model_error(m)->message, "pump_disp"),
           "and is refused with a message naming it: %s", bgr_model_error(m)->message);
    bgr_model_free(&m);

    ctl_run r;
    if (tap_ok(cr_open(&r, model, 1e-9, 1e-9), "pump and motor under the feedforward load") &&
        cr_to(&r, 40.0)) {
        double x = cr_out(&r, "x"), w = cr_out(&r, "w_motor"), p = cr_out(&r, "p");
        tap_ok(fabs(x - 0.05) < 1e-15, "the steady pump displacement: %.17g (hand: 0.05)", x);
        tap_ok(fabs(w - 150) < 1e-6 * 150,
               "the motor turns at i omega_r = 150 rad/s: %.9f (the flows balance)", w);
        double pf = 10 * 150 * 2 * PI / 0.005;
        tap_ok(fabs(p - pf) < 1e-5 * pf,
               "the line carries the friction's torque: p = %.1f Pa, b w 2 pi / Dm = %.1f Pa", p,
               pf);
    }
    cr_close(&r);
    return tap_done();
}
