/* The cases of test_mdl_types.c: one tiny model per type (and a few variants), and parameters out
 * of range. Included once, by test_mdl_types.c.
 *
 * A build case names the type, the instance's parameters (flow-mapping text), the fixtures
 * ("name: {...}" items separated by ';'), the bonds ("a.p -> b.q" items separated by ';'), and
 * the number of equations the instance contributes, from its component's header: one per
 * port component plus one per state and per own algebraic unknown (bgr_model.h):
 *   mech.body 13 states + the points' dims; point mass 6 + 3; support dim; spherical 2 dim;
 *   revolute 12 (+ 1 with the drive port), revolute_angle 13; axial elements 3 (d) + 3 + 3; rotation sensor 2
 *   (theta, omega); free dim;
 *   hyd.pump 3 (torque, flow, continuity), with the servo + 1 (swash); motor 3; volume
 *   nports + 1 (p); sources 1; leakage and relief valve 2 (flow, continuity);
 *   rot.inertia 3 (momentum, velocity, angle); gear 2; damper 1; sensor 1;
 *   ctl.pid 2 (integral, output), with the filter 3; ctl.feedforward, ctl.shaper 1;
 *   ctl.state_feedback 1 (output), integral form 3 (+ integral, rate); ctl.sway_sensor 2;
 *   every sig.* and sig.gain 1;
 *   bg.I and bg.C 2 d; R, Se, Sf d; Se_signal, Sf_signal 1; TF, GY 2 d; TF_signal 2;
 *   junctions nports d.
 * Every signal the type lists is read by a sig.gain `g_<signal>` (skip: signals the variant does
 * not offer). The instance is `dut` in the model `t`: its equations are named t/dut/... */

typedef struct build_case {
    const char *type, *params, *fixtures, *bonds;
    int neq;
    const char *skip; /* signals of the type the case does not offer ("" none) */
} build_case;

#define BODY_INERTIA "inertia: [1, 0, 0, 0, 1, 0, 0, 0, 1]"
#define AXIAL_FIX                                                                                  \
    "s: {type: mech.support, dim: 3}; s2: {type: mech.support, dim: 3, position: [1, 0, 0]}"
#define HYD_AB "pa: {type: bg.Se, value: [2e6]}; pb: {type: bg.Se}"

static const build_case builds[] = {
    /* mechanics */
    {"mech.body",
     "mass: 1, " BODY_INERTIA ", points: {a: {r: [1, 0, 0], dim: 6}, b: {r: [-1, 0, 0], dim: 3}}",
     "fa: {type: mech.free, dim: 6}; fb: {type: mech.free, dim: 3}", "dut.a -> fa.p; dut.b -> fb.p",
     13 + 9, ""},
    {"mech.point_mass", "mass: 1, position: [0, 0, 1]", "f: {type: mech.free, dim: 3}",
     "dut.p -> f.p", 9, ""},
    {"mech.support", "dim: 6", "f: {type: mech.free, dim: 6}", "dut.p -> f.p", 6, ""},
    {"mech.spherical", "dim: 3", "s: {type: mech.support, dim: 3}; f: {type: mech.free, dim: 3}",
     "s.p -> dut.a; dut.b -> f.p", 6, ""},
    {"mech.revolute", "axis: [0, 0, 1], drive: true",
     "s: {type: mech.support}; f: {type: mech.free}; w: {type: bg.Sf, value: [1]}",
     "s.p -> dut.a; dut.b -> f.p; w.p -> dut.d", 13, ""},
    /* without a drive the b side needs inertia: a free end's rotation about the axis would be
     * undetermined (structurally singular) */
    {"mech.revolute", "axis: [0, 1, 0]",
     "s: {type: mech.support}; b: {type: mech.body, mass: 1, " BODY_INERTIA
     ", points: {a: {r: [0, 0, 0]}}}",
     "s.p -> dut.a; dut.b -> b.a", 12, ""},
    /* the prescribed angle: 12 joint equations + the rate, one own unknown (the torque) */
    {"mech.revolute_angle", "axis: [0, 0, 1], body: b, angle: p.y",
     "s: {type: mech.support}; b: {type: mech.body, mass: 1, " BODY_INERTIA
     ", points: {a: {r: [0, 0, 0]}}}; p: {type: sig.sine, amplitude: 0.5, omega: 2}",
     "s.p -> dut.a; dut.b -> b.a", 13, ""},
    {"mech.spring", "k: 100, L0: 0.9", AXIAL_FIX, "s.p -> dut.a; dut.b -> s2.p", 9, ""},
    {"mech.truss", "E: 2e11, A: 1e-4, L0: 1", AXIAL_FIX, "s.p -> dut.a; dut.b -> s2.p", 9, ""},
    {"mech.rope", "k: 1e5, L0: 1.1", AXIAL_FIX, "s.p -> dut.a; dut.b -> s2.p", 9, ""},
    {"mech.rotation_sensor", "body: b",
     "b: {type: mech.body, mass: 1, " BODY_INERTIA
     ", points: {a: {r: [0, 0, 0]}}}; f: {type: mech.free}",
     "b.a -> f.p", 2, ""},
    /* 4 elements: 5 node bodies of 13 states, each with one equation per port component: the 8
     * ports to the elements (6 each) and the foot (6) and the tip (3); 4 elements of 12 (6 at
     * each end): 65 + 48 + 9 + 48 = 170 */
    {"mech.beam_chain",
     "elements: 4, start: [0, 0, 0], end: [2, 0, 0], E: 2e11, G: 8e10, A: 1e-3, Iy: 1e-6, "
     "Iz: 2e-6, J: 1e-6, rho: 7850, ports: {foot: {node: 0}, tip: {node: 4, dim: 3}}",
     "s: {type: mech.support}; f: {type: mech.free, dim: 3}", "s.p -> dut.foot; dut.tip -> f.p",
     170, ""},
    {"mech.free", "dim: 3", "s: {type: mech.support, dim: 3}", "s.p -> dut.p", 3, ""},
    /* the linear drive */
    {"hyd.cylinder",
     "area_a: 0.01, area_b: 0.005, length_min: 0.8, stroke: 0.5, volume_a0: 1e-4, "
     "volume_b0: 1e-4, beta: 1.4e9, nominal_pressure: 1e7",
     AXIAL_FIX "; " HYD_AB, "s.p -> dut.A; dut.B -> s2.p; pa.p -> dut.a; pb.p -> dut.b", 13, ""},
    {"hyd.directional_valve", "command: x.y, flow_rated: 1e-3, dp_rated: 35e5, underlap: 0.01",
     "x: {type: sig.constant, value: 0.5}; sp: {type: bg.Se, value: [1e7]}; st: {type: bg.Se}; "
     "sa: {type: bg.Se, value: [3e6]}; sb: {type: bg.Se, value: [2e6]}",
     "sp.p -> dut.P; st.p -> dut.T; sa.p -> dut.A; sb.p -> dut.B", 4, ""},
    /* hydraulics */
    {"hyd.pump", "displacement: 1e-5, leakage: 1e-12, command: x.y, nominal_pressure: 1e7",
     "x: {type: sig.constant, value: 0.5}; w: {type: bg.Sf, value: [100]}; " HYD_AB,
     "w.p -> dut.shaft; pb.p -> dut.a; dut.b -> pa.p", 3, ""},
    {"hyd.pump_servo", "displacement: 1e-5, command: x.y, bandwidth: 10, nominal_speed: 100",
     "x: {type: sig.constant, value: 0.5}; w: {type: bg.Sf, value: [100]}; " HYD_AB,
     "w.p -> dut.shaft; pb.p -> dut.a; dut.b -> pa.p", 4, ""},
    {"hyd.motor", "displacement: 1e-5, friction: 0.01", "w: {type: bg.Sf}; " HYD_AB,
     "pa.p -> dut.a; dut.b -> pb.p; dut.shaft -> w.p", 3, ""},
    {"hyd.volume", "volume: 1e-3, bulk_modulus: 1.5e9, ports: [a, b, c], pressure: 1e5",
     "qa: {type: bg.Sf}; qb: {type: bg.Sf}; qc: {type: bg.Sf, value: [1e-4]}",
     "qa.p -> dut.a; qb.p -> dut.b; qc.p -> dut.c", 4, ""},
    {"hyd.volume", "volume: 1e-3, bulk_modulus: 1.5e9", "qa: {type: bg.Sf}; qb: {type: bg.Sf}",
     "qa.p -> dut.a; qb.p -> dut.b", 3, ""},
    {"hyd.tank", "pressure: 1e5", "q: {type: bg.Sf}", "dut.p -> q.p", 1, ""},
    {"hyd.pressure_source", "pressure: x.y", "x: {type: sig.ramp, slope: 1e5}; q: {type: bg.Sf}",
     "dut.p -> q.p", 1, ""},
    {"hyd.flow_source", "flow: 1e-4", "p: {type: bg.Se}", "dut.p -> p.p", 1, ""},
    {"hyd.flow_source_signal", "flow: x.y",
     "x: {type: sig.sine, amplitude: 1e-4, omega: 1}; p: {type: bg.Se}", "dut.p -> p.p", 1, ""},
    {"hyd.leakage", "conductance: 1e-11", HYD_AB, "pa.p -> dut.a; dut.b -> pb.p", 2, ""},
    {"hyd.relief_valve", "p_crack: 1e7, p_full: 1.1e7, q_rated: 1e-3, eps: 1e4", HYD_AB,
     "pa.p -> dut.a; dut.b -> pb.p", 2, ""},
    /* rotation */
    {"rot.inertia", "J: 2, speed: 1, angle: 0.5, nominal_speed: 10", "t: {type: bg.Se}",
     "t.p -> dut.p", 3, ""},
    {"rot.gear", "ratio: -3", "w: {type: bg.Sf}; t: {type: bg.Se}", "w.p -> dut.in; dut.out -> t.p",
     2, ""},
    {"rot.damper", "b: 0.1", "w: {type: bg.Sf}", "w.p -> dut.p", 1, ""},
    {"rot.sensor", "inertia: j, quantity: acceleration",
     "j: {type: rot.inertia, J: 1}; t: {type: bg.Se}", "t.p -> j.p", 1, ""},
    {"rot.sensor", "inertia: j, quantity: angle", "j: {type: rot.inertia, J: 1}; t: {type: bg.Se}",
     "t.p -> j.p", 1, ""},
    /* control and signals */
    {"ctl.pid", "kp: 1, ki: 0.5, reference: r.y, measurement: y.y",
     "r: {type: sig.step, t_step: 1, after: 1}; y: {type: sig.constant, value: 0}", "", 2,
     "filter"},
    {"ctl.pid",
     "kp: 1, kd: 0.1, reference: r.y, reference_rate: rr.y, measurement: y.y, measurement_rate: "
     "yr.y",
     "r: {type: sig.ramp, slope: 1}; rr: {type: sig.ramp, slope: 1, output: rate}; "
     "y: {type: sig.constant, value: 0}; yr: {type: sig.constant, value: 0}",
     "", 2, "filter"},
    {"ctl.pid",
     "kp: 1, kd: 0.1, derivative_filter: 0.01, out_min: -1, out_max: 1, reference: r.y, "
     "measurement: y.y",
     "r: {type: sig.trapezoid, t0: 0, t1: 2, t2: 10, t3: 12, height: 0.5}; y: {type: sig.constant, "
     "value: 0}",
     "", 3, ""},
    {"ctl.pid",
     "kp: 1, ki: 0.5, b: 0.5, c: 0, out_min: -1, out_max: 1, tracking_time: 2, feedforward: f.y, "
     "reference: r.y, measurement: y.y",
     "r: {type: sig.step, t_step: 1, after: 1}; y: {type: sig.constant, value: 0}; "
     "f: {type: sig.constant, value: 0.1}",
     "", 2, "filter"},
    {"ctl.feedforward",
     "reference_rate: r.y, ratio: 300, motor_displacement: 0.005, pump_displacement: 0.1, "
     "pump_speed: 150",
     "r: {type: sig.constant, value: 0.5}", "", 1, ""},
    {"ctl.shaper", "times: [0, 2, 10, 12], values: [0, 0.5, 0.5, 0], frequency: 0.057", "", "", 1,
     ""},
    {"ctl.shaper",
     "times: [0, 2], values: [0, 1], frequency: 0.5, damping: 0.1, shaper: zvd, output: integral",
     "", "", 1, ""},
    {"ctl.state_feedback",
     "x1: a.y, x2: b.y, r1: c.y, A: [0, 1, 0, 0], B: [0, 1], Q: [1, 2], R: 0.5, form: integral, "
     "bias: c.y, bias_rate: c.y",
     "a: {type: sig.constant, value: 1}; b: {type: sig.constant, value: 2}; "
     "c: {type: sig.constant, value: 3}",
     "", 3, ""},
    {"ctl.state_feedback", "x1: a.y, gains: [2]", "a: {type: sig.constant, value: 1}", "", 1,
     "rate integral"},
    {"ctl.sway_sensor", "load: p, angle: th.y, rate: om.y, center: [1, 0]",
     "p: {type: mech.point_mass, mass: 1, position: [3, 1, 0]}; f: {type: mech.free, dim: 3}; "
     "th: {type: sig.constant, value: 0.1}; om: {type: sig.constant, value: 0.2}",
     "p.p -> f.p", 2, ""},
    {"sig.trapezoid", "t0: 0, t1: 2, t2: 10, t3: 12, height: 0.5, output: integral", "", "", 1, ""},
    {"sig.pwl", "times: [0, 1, 2], values: [0, 1, 0]", "", "", 1, ""},
    {"sig.step", "t_step: 1, after: 2, output: integral", "", "", 1, ""},
    {"sig.ramp", "slope: 2, output: rate", "", "", 1, ""},
    {"sig.sine", "amplitude: 1, omega: 2, phase: 0.1", "", "", 1, ""},
    {"sig.constant", "value: 3", "", "", 1, ""},
    {"sig.gain", "input: c.y, gain: -2", "c: {type: sig.constant, value: 1}", "", 1, ""},
    /* bond-graph elements */
    {"bg.I", "dim: 2, mass: 3", "e: {type: bg.Se, dim: 2}", "e.p -> dut.p", 4, ""},
    {"bg.C", "stiffness: 10", "f: {type: bg.Sf}", "f.p -> dut.p", 2, ""},
    {"bg.R", "dim: 3, resistance: 2", "f: {type: bg.Sf, dim: 3}", "f.p -> dut.p", 3, ""},
    {"bg.Se", "dim: 2, value: [1, 2]", "f: {type: bg.Sf, dim: 2}", "dut.p -> f.p", 2, ""},
    {"bg.Sf", "dim: 2", "e: {type: bg.Se, dim: 2}", "dut.p -> e.p", 2, ""},
    {"bg.Se_signal", "signal: c.y", "c: {type: sig.constant, value: 1}; f: {type: bg.Sf}",
     "dut.p -> f.p", 1, ""},
    {"bg.Sf_signal", "signal: c.y", "c: {type: sig.constant, value: 1}; e: {type: bg.Se}",
     "dut.p -> e.p", 1, ""},
    {"bg.TF", "dim: 2, modulus: 3", "f: {type: bg.Sf, dim: 2}; e: {type: bg.Se, dim: 2}",
     "f.p -> dut.a; dut.b -> e.p", 4, ""},
    {"bg.GY", "modulus: 2", "f: {type: bg.Sf}; g: {type: bg.Sf}", "f.p -> dut.a; dut.b -> g.p", 2,
     ""},
    {"bg.TF_signal", "modulus: c.y",
     "c: {type: sig.constant, value: 2}; f: {type: bg.Sf}; e: {type: bg.Se}",
     "f.p -> dut.a; dut.b -> e.p", 2, ""},
    {"bg.zero", "dim: 2, ports: [a, b, c]",
     "e: {type: bg.Se, dim: 2}; f1: {type: bg.Sf, dim: 2}; f2: {type: bg.Sf, dim: 2}",
     "e.p -> dut.a; dut.b -> f1.p; dut.c -> f2.p", 6, ""},
    {"bg.one", "ports: [a, b, c]", "f: {type: bg.Sf}; e1: {type: bg.Se}; e2: {type: bg.Se}",
     "f.p -> dut.a; dut.b -> e1.p; e2.p -> dut.c", 3, ""},
};

/* items separated by ';', each written as prefix item "\n" */
static size_t put_items(char *buf, size_t size, size_t o, const char *items, const char *prefix)
{
    const char *s = items;
    while (s && *s && o < size) {
        size_t k = strcspn(s, ";");
        while (*s == ' ')
            s++, k--;
        if (k > 0) o += (size_t)snprintf(buf + o, size - o, "%s%.*s\n", prefix, (int)k, s);
        s += k + (s[k] ? 1 : 0);
    }
    return o < size ? o : size;
}

static int skipped(const char *skip, const char *name)
{
    size_t n = strlen(name);
    for (const char *s = skip; s && *s;) {
        size_t k = strcspn(s, " ");
        if (k == n && !strncmp(s, name, n)) return 1;
        s += k + (s[k] ? 1 : 0);
    }
    return 0;
}

static void model_text(const mdl_type *t, const char *params, const char *fixtures,
                       const char *bonds, const char *skip, char *buf, size_t size)
{
    size_t o = (size_t)snprintf(buf, size,
                                "format: bgsim 1\nname: t\ncomponents:\n  dut: {type: %s%s%s}\n",
                                t->name, *params ? ", " : "", params);
    o = put_items(buf, size, o, fixtures, "  ");
    for (int i = 0; t && i < t->nsignals && o < size; i++)
        if (!skipped(skip, t->signals[i].name))
            o += (size_t)snprintf(buf + o, size - o,
                                  "  g_%s: {type: sig.gain, input: dut.%s, gain: 1}\n",
                                  t->signals[i].name, t->signals[i].name);
    if (bonds && *bonds && o < size) {
        o += (size_t)snprintf(buf + o, size - o, "bonds:\n");
        put_items(buf, size, o, bonds, "  - ");
    }
}

/* the equations named t/dut/... */
static int dut_equations(const bgr_model *m)
{
    int n = 0;
    for (int i = 0; i < bgr_n(m); i++)
        n += !strncmp(bgr_eq_name(m, i), "t/dut/", 6);
    return n;
}

static void check_builds(void)
{
    int ncases = (int)(sizeof builds / sizeof builds[0]);
    for (int i = 0, n = mdl_type_count(); i < n; i++) {
        int found = 0;
        for (int k = 0; k < ncases; k++)
            found |= !strcmp(builds[k].type, mdl_type_at(i)->name);
        tap_ok(found, "%s has a build case", mdl_type_at(i)->name);
    }
    for (int k = 0; k < ncases; k++) {
        const build_case *c = &builds[k];
        const mdl_type *t = mdl_type_find(c->type);
        if (!tap_ok(t != NULL, "case %d: type %s exists", k, c->type)) continue;
        char text[4096];
        model_text(t, c->params, c->fixtures, c->bonds, c->skip, text, sizeof text);
        bg_error e = {0}; /* no handler: the message is only recorded */
        mdl_model *mm = mdl_load_string(text, "case.yaml", NULL, 0, &e);
        if (!tap_ok(mm != NULL, "%s {%s}: loads and compiles", c->type, c->params)) {
            tap_diag("%s", e.message);
            tap_diag("model:\n%s", text);
            continue;
        }
        int neq = dut_equations(mdl_bgr(mm));
        tap_ok(neq == c->neq, "%s {%s}: %d equations (expected %d)", c->type, c->params, neq,
               c->neq);
        mdl_free(&mm);
    }
}

/* ---- 3. parameters out of range ---- */

typedef struct error_case {
    const char *type, *params, *fixtures;
    const char *want[2]; /* what the message must contain: the path and the parameter */
} error_case;

static const error_case errors[] = {
    {"mech.spring", "k: -1, L0: 1", "", {"dut.k", "out of range"}},
    {"hyd.cylinder",
     "area_a: 0.01, area_b: 0.02, length_min: 0.8, stroke: 0.5, volume_a0: 1e-4, "
     "volume_b0: 1e-4, beta: 1.4e9",
     "",
     {"dut", "area_b"}},
    {"hyd.directional_valve",
     "command: x.y, flow_rated: 1e-3, dp_rated: 35e5, underlap: 0.7",
     "x: {type: sig.constant, value: 1}",
     {"dut.underlap", "out of range"}},
    {"mech.body",
     "mass: 0, " BODY_INERTIA ", points: {a: {r: [0, 0, 0]}}",
     "",
     {"dut.mass", "> 0"}},
    {"hyd.pump",
     "displacement: -1, command: x.y",
     "x: {type: sig.constant, value: 1}",
     {"dut.displacement", "out of range"}},
    {"hyd.pump",
     "displacement: 1e-5, command: x.z",
     "x: {type: sig.constant, value: 1}",
     {"dut.command", "'z'"}},
    {"hyd.volume", "volume: 1e-3, bulk_modulus: 0", "", {"dut.bulk_modulus", "> 0"}},
    {"hyd.volume", "volume: 1e-3, bulk_modulus: 1e9, ports: [a, a]", "", {"dut.ports", "twice"}},
    {"hyd.relief_valve",
     "p_crack: 1e7, p_full: 0.9e7, q_rated: 1e-3, eps: 1e4",
     "",
     {"dut", "p_full"}},
    {"hyd.leakage", "conductance: -1e-12", "", {"dut.conductance", "out of range"}},
    {"rot.inertia", "J: 0", "", {"dut.J", "out of range"}},
    {"rot.gear", "ratio: 0", "", {"dut", "ratio"}},
    {"rot.sensor",
     "inertia: j, quantity: speed",
     "j: {type: rot.inertia, J: 1}",
     {"dut.quantity", "velocity"}},
    {"rot.sensor",
     "inertia: j, quantity: angle",
     "j: {type: rot.damper, b: 1}",
     {"dut", "inertia"}},
    {"ctl.pid",
     "kp: 1, kd: 1, reference: c.y, measurement: c.y",
     "c: {type: sig.constant, value: 1}",
     {"dut", "kd"}},
    {"ctl.pid",
     "kp: 1, out_min: 0, reference: c.y, measurement: c.y",
     "c: {type: sig.constant, value: 1}",
     {"dut", "out_max"}},
    {"ctl.pid",
     "kp: 1, out_min: 1, out_max: 0, reference: c.y, measurement: c.y",
     "c: {type: sig.constant, value: 1}",
     {"dut", "out_max"}},
    {"ctl.pid",
     "kp: 1, derivative_filter: -1, reference: c.y, measurement: c.y",
     "c: {type: sig.constant, value: 1}",
     {"dut.derivative_filter", "out of range"}},
    {"ctl.pid",
     "kp: 1, ki: 1, tracking_time: 1, reference: c.y, measurement: c.y",
     "c: {type: sig.constant, value: 1}",
     {"dut", "tracking_time"}},
    {"ctl.feedforward",
     "reference_rate: c.y, ratio: 0, motor_displacement: 1, pump_displacement: 1, pump_speed: 1",
     "c: {type: sig.constant, value: 1}",
     {"dut", "ratio"}},
    {"ctl.shaper", "times: [0, 1], values: [0, 1], frequency: 1, damping: 1", "",
     {"dut.damping", "out of range"}},
    {"ctl.state_feedback", "x1: c.y, gains: [1, 2]", "c: {type: sig.constant, value: 1}",
     {"dut", "gains"}},
    {"ctl.state_feedback", "x1: c.y, A: [0], B: [0], Q: [1], R: 1",
     "c: {type: sig.constant, value: 1}", {"dut", "stabilisable"}},
    {"ctl.sway_sensor", "load: c, angle: c.y, rate: c.y", "c: {type: sig.constant, value: 1}",
     {"dut", "point mass"}},
    {"sig.trapezoid", "t0: 0, t1: -1, t2: 10, t3: 12, height: 1", "", {"dut", "t1"}},
    {"sig.pwl", "times: [0, 1], values: [0, 1, 2]", "", {"dut", "values"}},
    {"sig.pwl", "times: [0, 1, 1], values: [0, 1, 2]", "", {"dut", "times"}},
    {"sig.step",
     "t_step: 1, after: 1, output: velocity",
     "",
     {"dut.output", "value|rate|integral"}},
    {"sig.gain", "input: c.y, gain: 1/0", "c: {type: sig.constant, value: 1}", {"dut.gain", ""}},
    {"bg.I", "dim: 17, mass: 1", "", {"dut.dim", "out of range"}},
    {"bg.R", "resistance: -1", "", {"dut.resistance", "out of range"}},
    {"bg.Se", "dim: 2, value: [1]", "", {"dut", "value"}},
    {"bg.TF", "modulus: 0", "", {"dut", "modulus"}},
    {"bg.zero", "ports: [a]", "", {"dut", "ports"}},
    {"bg.one", "ports: [a, 2b]", "", {"dut.ports", "2b"}},
};

static void check_errors(void)
{
    for (size_t k = 0; k < sizeof errors / sizeof errors[0]; k++) {
        const error_case *c = &errors[k];
        const mdl_type *t = mdl_type_find(c->type);
        if (!tap_ok(t != NULL, "error case %zu: type %s exists", k, c->type)) continue;
        char text[4096];
        model_text(t, c->params, c->fixtures, "", "", text, sizeof text);
        /* the signal readers would fail on their own: leave them out */
        char *g = strstr(text, "  g_");
        if (g) *g = 0;
        bg_error e = {0}; /* no handler: the message is only recorded */
        mdl_model *mm = mdl_load_string(text, "bad.yaml", NULL, 0, &e);
        int ok = !mm && strstr(e.message, c->want[0]) && strstr(e.message, c->want[1]) &&
                 strstr(e.message, "bad.yaml:");
        tap_ok(ok, "%s {%s}: refused naming '%s' and '%s'", c->type, c->params, c->want[0],
               c->want[1]);
        if (!ok) tap_diag("message: %s", mm ? "(none: it loaded)" : e.message);
        mdl_free(&mm);
    }
}
