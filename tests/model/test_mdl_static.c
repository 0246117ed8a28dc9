/* The static start and the trim of model files (mdl_static) against closed forms: a mass hanging
 * on a linear spring from a fixed point rests at z = -(L0 + m g / k); trimmed to rest at z = -1
 * the spring's unstretched length must come out as 1 - m g / k. A bracket that cannot hold the
 * condition is refused with the names and values. The sources start at their values at t = 0
 * (every source type's place()): the assembled start satisfies their own equations, whatever
 * way their bonds are written, and a hydraulic node between them rests at the flow balance. */
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

/* Every kind of source, on one oil volume: supply 5 MPa and a pressure source following a ramp
 * (offset 2 MPa) through conductances G, bg.Se 1 MPa through G, a flow source of 1e-4 m^3/s into
 * it, one of -2e-5 with its bond written into the source (it draws 2e-5 from the volume: the
 * bond's flow is +2e-5), bg.Sf 3e-5 with its bond written into it (it feeds 3e-5: the bond's
 * flow is -3e-5); the signals start at ramp 2e6, pwl rate 2, sine 0.25 + sin 0.5. At rest
 * G (5e6 + 2e6 + 1e6 - 3 p) + 1e-4 - 2e-5 + 3e-5 = 0. */
static const char *sources_text =
    "format: bgsim 1\n"
    "name: sources\n"
    "parameters: {G: 1e-10}\n"
    "components:\n"
    "  supply: {type: hyd.tank, pressure: 5e6}\n"
    "  ramp: {type: sig.ramp, slope: 1e5, offset: 2e6}\n"
    "  prof: {type: sig.pwl, times: [-1, 1], values: [0, 4], output: rate}\n"
    "  wave: {type: sig.sine, amplitude: 1, omega: 2, phase: 0.5, offset: 0.25}\n"
    "  pump: {type: hyd.pressure_source, pressure: ramp.y}\n"
    "  fin: {type: hyd.flow_source, flow: 1e-4}\n"
    "  fback: {type: hyd.flow_source, flow: -2e-5}\n"
    "  se: {type: bg.Se, value: [1e6]}\n"
    "  sf: {type: bg.Sf, value: [3e-5]}\n"
    "  node: {type: hyd.volume, volume: 1e-3, bulk_modulus: 1e9, ports: [a, b, c, d, e, f]}\n"
    "  o1: {type: hyd.leakage, conductance: G}\n"
    "  o2: {type: hyd.leakage, conductance: G}\n"
    "  o3: {type: hyd.leakage, conductance: G}\n"
    "bonds:\n"
    "  - supply.p -> o1.a\n"
    "  - o1.b -> node.a\n"
    "  - pump.p -> o2.a\n"
    "  - o2.b -> node.b\n"
    "  - fin.p -> node.c\n"
    "  - node.d -> fback.p\n"
    "  - se.p -> o3.a\n"
    "  - o3.b -> node.e\n"
    "  - node.f -> sf.p\n"
    "outputs:\n"
    "  p_supply: supply.p.e\n"
    "  p_pump: pump.p.e\n"
    "  q_fin: fin.p.f\n"
    "  q_fback: fback.p.f\n"
    "  e_se: se.p.e\n"
    "  f_sf: sf.p.f\n"
    "  ramp: ramp.y\n"
    "  rate: prof.y\n"
    "  wave: wave.y\n"
    "  p: node.p\n";

static void check_sources(void)
{
    bg_error e = {0};
    bg_error_clear(&e);
    mdl_model *mm = mdl_load_string(sources_text, "sources.yaml", NULL, 0, &e);
    tap_ok(mm != NULL, "sources: loads (%s)", mm ? "ok" : e.message);
    if (!mm) return;
    double out[10];
    const char *what[10] = {"hyd.tank's pressure", "hyd.pressure_source's (the ramp's offset)",
                            "hyd.flow_source's flow", "a flow source's, its bond written into it",
                            "bg.Se's effort", "bg.Sf's flow, its bond written into it",
                            "sig.ramp", "sig.pwl's rate", "sig.sine"};
    const double want[9] = {5e6, 2e6, 1e-4, 2e-5, 1e6, -3e-5, 2e6, 2, 0.25 + sin(0.5)};
    mdl_outputs(mm, 0, bgr_y0(mdl_bgr(mm)), out, &e);
    for (int i = 0; i < 9; i++)
        tap_close(out[i], want[i], 1e-15, 0, "sources: the start has %s at t = 0, %g", what[i],
                  want[i]);
    int r = mdl_static(&mm, NULL, NULL, &e);
    tap_ok(r == BG_OK, "sources: static with the default options (%s)", r ? e.message : "ok");
    const double G = 1e-10, p = (G * 8e6 + 1e-4 - 2e-5 + 3e-5) / (3 * G);
    if (r == BG_OK) mdl_outputs(mm, 0, bgr_y0(mdl_bgr(mm)), out, &e);
    tap_close(out[9], p, 1e-7, 0, "sources: the node rests at the flow balance, %.1f Pa", p);
    mdl_free(&mm);
}

/* A volume's own equations e_k = p hold at the start: the bonds at its ports carry its initial
 * pressure (before, they started at 0, and a valve between it and a tank at that pressure saw
 * the whole pressure across it: the static start's load homotopy then took 10 steps where 3 do). */
static void check_volume_start(void)
{
    static const char *text =
        "format: bgsim 1\nname: v\n"
        "components:\n"
        "  tank: {type: hyd.tank, pressure: 2e6}\n"
        "  check: {type: hyd.relief_valve, p_crack: 1e5, p_full: 5e5, q_rated: 1e-3, eps: 1e4}\n"
        "  line: {type: hyd.volume, ports: [a, b], volume: 1e-3, bulk_modulus: 1.4e9,\n"
        "         pressure: 2e6}\n"
        "  leak: {type: hyd.leakage, conductance: 1e-11}\n"
        "  drain: {type: hyd.tank, pressure: 0}\n"
        "bonds: [tank.p -> check.a, check.b -> line.a, line.b -> leak.a, leak.b -> drain.p]\n";
    bg_error e = {0};
    mdl_model *mm = mdl_load_string(text, "v.yaml", NULL, 0, &e);
    tap_ok(mm != NULL, "volume start: loads (%s)", mm ? "ok" : e.message);
    if (!mm) return;
    bgr_model *m = mdl_bgr(mm);
    int n = bgr_n(m);
    double F[64] = {0}, yp[64] = {0};
    if (n <= 64) bgr_residual(m, 0, bgr_y0(m), yp, F);
    int pa = bgr_find_eq(m, "v/line/port0"), pb = bgr_find_eq(m, "v/line/port1");
    tap_ok(n <= 64 && pa >= 0 && pb >= 0 && F[pa] == 0 && F[pb] == 0,
           "volume start: its ports carry its pressure (e_k = p holds: %g, %g)",
           pa >= 0 ? F[pa] : NAN, pb >= 0 ? F[pb] : NAN);
    mdl_free(&mm);
}

int main(void)
{
    check_sources();
    check_volume_start();
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

    /* a trim whose static solves fail (no stiffness: the mass has no equilibrium) says so with
     * the solve's reason, not the trim's condition (it gave "nan") */
    {
        char text[4096];
        snprintf(text, sizeof text, "%s",
                 model_text("trim: {adjust: L0, until: z, equals: -1, between: [0.5, 1]}\n"));
        char *kk = strstr(text, "k: 400");
        if (kk) memcpy(kk, "k: 0  ", 6);
        mm = mdl_load_string(text, "hanging.yaml", NULL, 0, &e);
        r = mm ? mdl_static(&mm, NULL, &rep, &e) : BG_ERR_ARGUMENT;
        tap_ok(mm && r != BG_OK &&
                   strstr(e.message, "the static solve with L0 = ") &&
                   strstr(e.message, "failed: ") && !strstr(e.message, "nan"),
               "a trim whose static solve fails gives the solve's reason (status %d: %s)", r,
               e.message);
        mdl_free(&mm);
    }

    mm = mdl_load_string(model_text("trim: {adjust: L1, until: z, equals: -1, between: [0.1, 0.5]}\n"),
                         "hanging.yaml", NULL, 0, &e);
    tap_ok(!mm && strstr(e.message, "hanging.yaml:14:") && strstr(e.message, "'L1'"),
           "trim of an unknown parameter: position and name (%s)", e.message);
    mdl_free(&mm);
    return tap_done();
}
