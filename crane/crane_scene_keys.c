/* The scene keys (crane_scene.h): one table holds each key's section, name, type, field
 * (offset), range, default, unit and meaning. From it come the defaults (crane_scene_default),
 * the range checks and the parser's look-ups (crane_scene.c), writing and comparing scenes, and
 * the key list (crane_scene_keys_markdown: crane --list-keys, docs/scene-keys.md). Independent of
 * the INI reader. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "crane_scene_impl.h"
#include "pu_cli.h"

/* The table's entries by type: section, key, field, range (the text "expected" follows from it),
 * the default, unit, meaning (written beside the key by crane_scene_write) and a note for the
 * key list only (NULL: none). The defaults are the paper scene's (docs/crane.md,
 * crane/scenes/paper.ini); a comment above an entry gives the reason of its default. */
#define OFF(field) offsetof(crane_scene, field)
#define KNUM(sec, key, field, rng, dflt, unit, meaning, note)                                      \
    {                                                                                              \
        {sec, key, CRANE_KEY_NUMBER, unit, EXPN_##rng, meaning}, OFF(field), rng, 0, 0, {dflt},    \
            NULL, note                                                                             \
    }
#define KVEC(sec, key, field, rng, x, y, z, unit, meaning, note)                                   \
    {                                                                                              \
        {sec, key, CRANE_KEY_VECTOR, unit, EXPV_##rng, meaning}, OFF(field), rng, 0, 0, {x, y, z}, \
            NULL, note                                                                             \
    }
#define KBOOL(sec, key, field, dflt, meaning, note)                                                \
    {                                                                                              \
        {sec, key, CRANE_KEY_BOOLEAN, "", "a boolean (true/false, yes/no, on/off, 1/0)", meaning}, \
            OFF(field), R_INT, 0, 1, {dflt}, NULL, note                                            \
    }
#define KINT(sec, key, field, lo, hi, dflt, unit, meaning, note)                                   \
    {                                                                                              \
        {sec, key, CRANE_KEY_INTEGER, unit, "an integer in " #lo ".." #hi, meaning}, OFF(field),   \
            R_INT, lo, hi, {dflt}, NULL, note                                                      \
    }

/* "expected" of a number (EXPN_) or a vector (EXPV_) by range kind */
#define EXPN_R_ANY "a finite number"
#define EXPN_R_POS "a number > 0"
#define EXPN_R_NONNEG "a number >= 0"
#define EXPN_R_OPEN01 "a number in (0, 1)"
#define EXPN_R_UNIT0 "a number in [0, 1)"
#define EXPV_R_ANY "three finite numbers 'x, y, z'"
#define EXPV_R_POS "three numbers > 0 'x, y, z'"

const key_def crane_scene_keys[] = {
    {{"scene", "name", CRANE_KEY_NAME, "", "a name of 1 to 63 characters from [A-Za-z0-9_.-]",
      "results go to results/<name>/"},
     OFF(name),
     R_ANY,
     0,
     0,
     {0},
     "paper",
     NULL},
    KNUM("environment", "g", g, R_NONNEG, 9.81, "m/s^2", "gravity, along -Z0", NULL),
    /* Table 1: 53, read in tonnes */
    KNUM("platform", "mass", platform_mass, R_POS, 53e3, "kg", "platform mass", NULL),
    KVEC("platform", "inertia", platform_inertia, R_POS, 3e5, 3e5, 4e5, "kg m^2",
         "principal moments of inertia about the mass centre", NULL),
    KVEC("platform", "com", platform_com, R_ANY, 0, 0, 1.0, "m", "mass centre, platform frame",
         NULL),
    KVEC("platform", "joint_A", joint_A, R_ANY, 0, 0, 0, "m",
         "slewing joint A on the axis, global frame", NULL),
    KINT("boom", "elements", boom_elements, 0, 512, 16, "",
         "beam elements; 0: the boom is one rigid body", NULL),
    /* false: the paper scene's results as they were computed (docs/beam.md: the mesh study) */
    KBOOL("boom", "consistent", boom_consistent, 0,
          "the consistent beam element instead of the lumped one (mech_beam.h)",
          "3 elements give the boom's first four frequencies within 1e-3 (docs/beam.md)"),
    KBOOL("boom", "quartic", boom_quartic, 0,
          "the quartic beam element (a bubble per bending plane) instead of the lumped one "
          "(mech_beam.h); not with consistent = true",
          "2 elements give the boom's first four frequencies and peak deflections within 1e-3 "
          "(docs/beam.md)"),
    KVEC("boom", "foot", boom_foot, R_ANY, 1.5, 0, 2.5, "m", "boom foot (hinge) B, platform frame",
         NULL),
    KNUM("boom", "length", boom_length, R_POS, 76.0, "m", "boom length", NULL),
    KNUM("boom", "tip_radius", boom_tip_radius, R_NONNEG, 12.0, "m",
         "distance of the tip from the slewing axis (sets the luffing angle)", NULL),
    KNUM("boom", "E", boom_E, R_POS, 1.08e11, "Pa", "Young's modulus", NULL),
    KNUM("boom", "G", boom_G, R_POS, 4.15e10, "Pa", "shear modulus", NULL),
    KNUM("boom", "A", boom_A, R_POS, 0.0443, "m^2", "cross-section area", NULL),
    KNUM("boom", "I_luff", boom_I_luff, R_POS, 0.0836, "m^4",
         "second moment of area, bending in the luffing plane", NULL),
    KNUM("boom", "I_side", boom_I_side, R_POS, 0.0665, "m^4",
         "second moment of area, bending out of the luffing plane", NULL),
    /* equivalent lattice boom: polar of the two */
    KNUM("boom", "J", boom_J, R_POS, 0.0836 + 0.0665, "m^4", "torsion constant", NULL),
    KNUM("boom", "rho", boom_rho, R_POS, 7850, "kg/m^3", "density", NULL),
    /* s: 0.48 % of critical at the first bending mode (docs/crane.md) */
    KNUM("boom", "beta", boom_beta, R_NONNEG, 2.33e-3, "s",
         "stiffness-proportional damping; 0: none",
         "mode i gets the damping ratio beta omega_i / 2"),
    KBOOL("ties", "enabled", ties, 1, "build the suspension ties", NULL),
    KVEC("ties", "gantry_top", gantry_top, R_ANY, -10.0, 0, 20.0, "m",
         "upper end of the ties on the platform, platform frame", NULL),
    KNUM("ties", "spread", tie_spread, R_NONNEG, 3.0, "m",
         "half the lateral distance of a pair of ties at the gantry (0: one tie)", NULL),
    KNUM("ties", "E", tie_E, R_POS, 2.1e11, "Pa", "Young's modulus", NULL),
    KNUM("ties", "A", tie_A, R_POS, 0.0084, "m^2", "cross-section area", NULL),
    /* steel: each tie's mass lumped half at its ends */
    KNUM("ties", "rho", tie_rho, R_NONNEG, 7850, "kg/m^3",
         "density: each tie's mass lumped half at each end; 0: massless",
         "the tip's half goes into the boom's tip, the gantry's counts in the platform's mass"),
    /* s: the boom's, one structure */
    KNUM("ties", "beta", tie_beta, R_NONNEG, 2.33e-3, "s",
         "stiffness-proportional damping (c = beta E A / length); 0: none", NULL),
    KBOOL("rope", "enabled", rope, 1, "build the rope and the load", NULL),
    KNUM("rope", "length", rope_length, R_POS, 71.51, "m", "unstretched length", NULL),
    KNUM("rope", "E", rope_E, R_POS, 1.0e11, "Pa", "Young's modulus (stiffness E A / length)",
         NULL),
    KNUM("rope", "A", rope_A, R_POS, 0.0004, "m^2", "cross-section area", NULL),
    /* N s/m: 0.32 % of critical at the load's bounce mode */
    KNUM("rope", "damping", rope_damping, R_NONNEG, 1.19e3, "N s/m", "axial damping", NULL),
    KNUM("load", "mass", load_mass, R_POS, 60.526e3, "kg", "load with hook (built with the rope)",
         NULL),
    KBOOL("counterweight", "enabled", counterweight, 1, "build the counterweight", NULL),
    KNUM("counterweight", "mass", cw_mass, R_POS, 150e3, "kg", "counterweight mass", NULL),
    KVEC("counterweight", "pos", cw_pos, R_ANY, -6.0, 0, 1.5, "m", "position, platform frame",
         NULL),
    KBOOL("hydraulics", "enabled", hydraulics, 1,
          "build the hydraulic drive and PID; false: the platform's rate is prescribed", NULL),
    /* rad/s, about 1430 rpm */
    KNUM("hydraulics", "pump_speed", pump_speed, R_POS, 150.0, "rad/s", "pump drive speed", NULL),
    /* m^3/rev at x = 1: x = 0.05 on the plateau */
    KNUM("hydraulics", "pump_disp", pump_disp, R_POS, 0.1, "m^3/rev", "pump displacement at x = 1",
         NULL),
    /* m^3/(s Pa): 97 % volumetric efficiency at 30 MPa, x = 1 */
    KNUM("hydraulics", "pump_leak", pump_leak, R_NONNEG, 2.4e-9, "m^3/(s Pa)",
         "pump leakage coefficient", NULL),
    KNUM("hydraulics", "motor_disp", motor_disp, R_POS, 5e-3, "m^3/rev", "motor displacement",
         NULL),
    /* 97 % at 30 MPa and the plateau speed */
    KNUM("hydraulics", "motor_leak", motor_leak, R_NONNEG, 1.2e-10, "m^3/(s Pa)",
         "motor leakage coefficient", NULL),
    KNUM("hydraulics", "motor_inertia", motor_inertia, R_POS, 2.0, "kg m^2",
         "motor and gear input inertia", NULL),
    KNUM("hydraulics", "gear_ratio", gear_ratio, R_POS, 300.0, "", "motor turns per platform turn",
         NULL),
    /* m^3 each side */
    KNUM("hydraulics", "line_volume", line_volume, R_POS, 0.05, "m^3", "volume of each line", NULL),
    KNUM("hydraulics", "bulk_modulus", bulk_modulus, R_POS, 1.4e9, "Pa", "oil bulk modulus", NULL),
    KNUM("hydraulics", "charge_pressure", charge_pressure, R_NONNEG, 2e6, "Pa",
         "charge (boost) pressure of the low side", NULL),
    KNUM("hydraulics", "relief_pressure", relief_pressure, R_NONNEG, 3e7, "Pa",
         "cracking pressure difference of the cross-port relief valves (0: none)",
         "with them, anti-cavitation check valves from the charge pressure into both lines"),
    /* Hz: the swash plate's first-order lag (docs/crane.md) */
    KNUM("hydraulics", "pump_servo_bandwidth", pump_servo_bw, R_NONNEG, 0.8, "Hz",
         "bandwidth of the pump's displacement actuator (first-order lag); 0: instantaneous",
         "the swash plate follows the PID's command as a first-order lag (hyd_pump_servo); with "
         "kd_filter > 0 the drive's loop is unstable with any lag (docs/crane.md)"),
    KNUM("controller", "kp", kp, R_NONNEG, 5, "1/(rad/s)", "proportional gain",
         "x is the fraction of the pump's displacement"),
    KNUM("controller", "kd", kd, R_NONNEG, 50, "1/(rad/s^2)", "derivative gain", NULL),
    KNUM("controller", "ki", ki, R_NONNEG, 2, "1/rad", "integral gain", NULL),
    /* the paper's law: the measured acceleration (stable with the lag) */
    KNUM("controller", "kd_filter", kd_filter, R_NONNEG, 0, "s",
         "time constant of the rate filter of the derivative term; 0: the measured acceleration",
         NULL),
    /* the pump's full displacement */
    KNUM("controller", "x_limit", x_limit, R_NONNEG, 1, "", "smooth limit of |x|; 0: none", NULL),
    KNUM("reference", "t1", ref_t1, R_POS, 2, "s", "end of the ramp up", "0 < t1 <= t2 < t3"),
    KNUM("reference", "t2", ref_t2, R_POS, 10, "s", "end of the plateau", NULL),
    KNUM("reference", "t3", ref_t3, R_POS, 12, "s", "stop time (end of the ramp down)", NULL),
    KNUM("reference", "rate", ref_rate, R_ANY, 0.5, "rad/s", "plateau rate", NULL),
    KBOOL("initial", "static_start", static_start, 1,
          "start from the static equilibrium under gravity at theta = 0", NULL),
    KNUM("solver", "t_end", t_end, R_POS, 20, "s", "end time", NULL),
    KNUM("solver", "rtol", rtol, R_OPEN01, 1e-6, "", "relative tolerance", NULL),
    KNUM("solver", "atol", atol, R_POS, 1e-6, "", "absolute tolerance", NULL),
    KNUM("solver", "output_step", output_step, R_POS, 1e-3, "s", "output interval", NULL),
    KBOOL("solver", "nominal_scales", nominal_scales, 1,
          "absolute tolerance of each unknown atol times its nominal magnitude (false: atol in SI "
          "units)",
          "crane/crane_scene.h, Tolerances"),
    KNUM("solver", "nominal_length", nominal_length, R_NONNEG, 1, "m",
         "nominal magnitude of positions and stretch vectors (0: 1 m; a member keeps its length)",
         NULL),
    KNUM("solver", "nominal_velocity", nominal_velocity, R_NONNEG, 1, "m/s",
         "nominal magnitude of velocities (0: 1 m/s)", NULL),
    KNUM("solver", "nominal_angular_velocity", nominal_angular_velocity, R_NONNEG, 1, "rad/s",
         "nominal magnitude of angular velocities (0: 1 rad/s)", NULL),
    /* its fast modes are damped (crane_scene.h) */
    KBOOL("solver", "stability_guard", stability_guard, 0,
          "order lowered to 2 where undamped fast modes hold BDF orders 3..5 at their stability "
          "limit, which damps them (false: the order follows the error estimates alone)",
          "crane/crane_scene.h, Stability guard"),
    KINT("solver", "max_order", max_order, 1, 5, 5, "",
         "the highest BDF order",
         "orders 3..5 are not A-stable: at rtol 1e-8 lightly damped modes hold orders 4 and 5 of "
         "the paper scene at their stability limits, 19 697 steps against 12 257 with 3; "
         "docs/solver.md"),
    KNUM("solver", "newton_dgmax", newton_dgmax, R_UNIT0, 0.3, "",
         "the Newton matrix refactored from the saved Jacobian when 1/cj moved by more than "
         "this (0: only with a new Jacobian)",
         "0.3 is CVODE's value; bg_dae.h"),
    KINT("solver", "newton_jac_age", newton_jac_age, 0, 1000000, 51, "",
         "Jacobian evaluated again after this many steps or a Newton failure (with "
         "newton_dgmax > 0; 0: IDA's rule on 1/cj)",
         "the Newton rate carries from step to step; 51 is CVODE's value; IDA's rule: when 1/cj "
         "leaves [0.6, 1.67] of its value then; bg_dae.h"),
    KBOOL("solver", "newton_index2_scale_h", newton_index2_scale_h, 1,
          "index-2 unknowns weigh h times less in the Newton convergence test",
          "the hinge and joint reactions, the PID's output on the measured acceleration, the "
          "motor's torque; bg_dae.h"),
};
_Static_assert(sizeof crane_scene_keys / sizeof *crane_scene_keys == CRANE_SCENE_NKEYS,
               "CRANE_SCENE_NKEYS counts the table");

void crane_scene_default(crane_scene *s)
{
    memset(s, 0, sizeof *s);
    for (int i = 0; i < NKEYS; i++) {
        const key_def *k = &KEYS[i];
        switch (k->pub.type) {
        case CRANE_KEY_NUMBER:
            *dfield(s, k) = k->def[0];
            break;
        case CRANE_KEY_VECTOR:
            memcpy(dfield(s, k), k->def, sizeof k->def);
            break;
        case CRANE_KEY_INTEGER:
        case CRANE_KEY_BOOLEAN:
            *ifield(s, k) = (int)k->def[0];
            break;
        case CRANE_KEY_NAME:
            snprintf(s->name, sizeof s->name, "%s", k->def_name);
            break;
        }
    }
}

int crane_scene_nkeys(void)
{
    return NKEYS;
}

const crane_scene_key *crane_scene_key_at(int i)
{
    return i >= 0 && i < NKEYS ? &KEYS[i].pub : NULL;
}

/* ---------------------------------------------------------- names, distance ---- */

/* The section names in table order. */
static int section_count(const char **names, int max)
{
    int n = 0;
    for (int i = 0; i < NKEYS; i++) {
        int seen = 0;
        for (int j = 0; j < n && !seen; j++)
            seen = !strcmp(names[j], KEYS[i].pub.section);
        if (!seen && n < max) names[n++] = KEYS[i].pub.section;
    }
    return n;
}

const char *csk_known_section(const char *name)
{
    for (int i = 0; i < NKEYS; i++)
        if (pu_ini_ieq(KEYS[i].pub.section, name)) return KEYS[i].pub.section;
    return NULL;
}

const char *csk_nearest_section(const char *name, int *dist)
{
    const char *names[32];
    int n = section_count(names, 32), best = -1, bd = 1 << 30;
    for (int i = 0; i < n; i++) {
        int d = pu_cli_edit_distance(name, names[i]);
        if (d < bd) bd = d, best = i;
    }
    *dist = bd;
    return best >= 0 ? names[best] : "";
}

int csk_find_key(const char *section, const char *key)
{
    for (int i = 0; i < NKEYS; i++)
        if (pu_ini_ieq(KEYS[i].pub.section, section) && pu_ini_ieq(KEYS[i].pub.key, key)) return i;
    return -1;
}

/* Nearest key of section (-1 if it has none). */
int csk_nearest_key(const char *section, const char *key, int *dist)
{
    int best = -1, bd = 1 << 30;
    for (int i = 0; i < NKEYS; i++) {
        if (!pu_ini_ieq(KEYS[i].pub.section, section)) continue;
        int d = pu_cli_edit_distance(key, KEYS[i].pub.key);
        if (d < bd) bd = d, best = i;
    }
    *dist = bd;
    return best;
}

/* "elements, foot, length, ..." */
void csk_list_keys(const char *section, char *buf, size_t size)
{
    size_t len = 0;
    buf[0] = '\0';
    for (int i = 0; i < NKEYS && len < size; i++)
        if (pu_ini_ieq(KEYS[i].pub.section, section))
            len +=
                (size_t)snprintf(buf + len, size - len, "%s%s", len ? ", " : "", KEYS[i].pub.key);
}

void csk_list_sections(char *buf, size_t size)
{
    const char *names[32];
    int n = section_count(names, 32);
    size_t len = 0;
    buf[0] = '\0';
    for (int i = 0; i < n && len < size; i++)
        len += (size_t)snprintf(buf + len, size - len, "%s[%s]", len ? ", " : "", names[i]);
}

int csk_in_range(range_kind r, double x)
{
    switch (r) {
    case R_POS:
        return x > 0;
    case R_NONNEG:
        return x >= 0;
    case R_OPEN01:
        return x > 0 && x < 1;
    case R_UNIT0:
        return x >= 0 && x < 1;
    default:
        return isfinite(x);
    }
}

/* ------------------------------------------------------------ writing, comparing ---- */

/* Shortest text that reads back as x (whole numbers below 1e7 without exponent). */
static void fmt_double(double x, char *buf, size_t size)
{
    if (x == floor(x) && fabs(x) < 1e7) {
        snprintf(buf, size, "%.0f", x);
        if (strtod(buf, NULL) == x && !(x == 0 && signbit(x))) return;
    }
    for (int prec = 1; prec <= 17; prec++) {
        snprintf(buf, size, "%.*g", prec, x);
        if (strtod(buf, NULL) == x) return;
    }
}

static void value_text(const crane_scene *s, const key_def *k, char *buf, size_t size)
{
    char a[40], b[40], c[40];
    switch (k->pub.type) {
    case CRANE_KEY_NUMBER:
        fmt_double(*cdfield(s, k), buf, size);
        break;
    case CRANE_KEY_VECTOR:
        fmt_double(cdfield(s, k)[0], a, sizeof a);
        fmt_double(cdfield(s, k)[1], b, sizeof b);
        fmt_double(cdfield(s, k)[2], c, sizeof c);
        snprintf(buf, size, "%s, %s, %s", a, b, c);
        break;
    case CRANE_KEY_INTEGER:
        snprintf(buf, size, "%d", *cifield(s, k));
        break;
    case CRANE_KEY_BOOLEAN:
        snprintf(buf, size, "%s", *cifield(s, k) ? "true" : "false");
        break;
    case CRANE_KEY_NAME:
        snprintf(buf, size, "%.63s", s->name);
        break;
    }
}

int crane_scene_write(const crane_scene *s, FILE *f)
{
    if (!s || !f) return BG_ERR_ARGUMENT;
    const char *prev = NULL;
    fprintf(f, "; crane scene (every key; units SI; see crane/crane_scene.h)\n");
    for (int i = 0; i < NKEYS; i++) {
        const key_def *k = &KEYS[i];
        if (!prev || strcmp(prev, k->pub.section)) fprintf(f, "\n[%s]\n", k->pub.section);
        prev = k->pub.section;
        char v[160], line[200];
        value_text(s, k, v, sizeof v);
        int n = snprintf(line, sizeof line, "%s = %s", k->pub.key, v);
        fprintf(f, "%s%*s ; %s%s%s\n", line, n < 32 ? 32 - n : 0, "", k->pub.unit,
                k->pub.unit[0] ? ": " : "", k->pub.meaning);
    }
    return ferror(f) ? BG_ERR_IO : BG_OK;
}

int crane_scene_compare(const crane_scene *a, const crane_scene *b, char *what, size_t size)
{
    int n = 0;
    if (what && size) what[0] = '\0';
    for (int i = 0; i < NKEYS; i++) {
        const key_def *k = &KEYS[i];
        int same = 1;
        switch (k->pub.type) {
        case CRANE_KEY_NUMBER:
            same = *cdfield(a, k) == *cdfield(b, k);
            break;
        case CRANE_KEY_VECTOR:
            for (int j = 0; j < 3; j++)
                same = same && cdfield(a, k)[j] == cdfield(b, k)[j];
            break;
        case CRANE_KEY_INTEGER:
        case CRANE_KEY_BOOLEAN:
            same = *cifield(a, k) == *cifield(b, k);
            break;
        case CRANE_KEY_NAME:
            same = !strncmp(a->name, b->name, sizeof a->name);
            break;
        }
        if (!same) {
            if (!n && what && size) {
                char va[160], vb[160];
                value_text(a, k, va, sizeof va);
                value_text(b, k, vb, sizeof vb);
                snprintf(what, size, "[%s] %s: %s vs %s", k->pub.section, k->pub.key, va, vb);
            }
            n++;
        }
    }
    return n;
}

/* ------------------------------------------------------------------ key list ---- */

/* The value types as a scene file writes them (the parser's rules, crane_scene.c). */
static const struct {
    crane_key_type type;
    const char *name, *syntax;
} TYPES[] = {
    {CRANE_KEY_NUMBER, "number",
     "a finite decimal number, e.g. 76, 0.0443, 1.08e11 (not hexadecimal: 0x4c is refused, as are "
     "inf and nan)"},
    {CRANE_KEY_INTEGER, "integer", "decimal digits with an optional sign"},
    {CRANE_KEY_BOOLEAN, "boolean", "true/false, yes/no, on/off, 1/0"},
    {CRANE_KEY_VECTOR, "vector", "three numbers x, y, z"},
    {CRANE_KEY_NAME, "name", "1 to 63 characters of [A-Za-z0-9_.-] (it names the output folder)"},
};

/* Text in a Markdown table cell: '|' escaped, '<' as an entity (no HTML). */
static void md_text(FILE *f, const char *t)
{
    for (; *t; t++) {
        if (*t == '|')
            fputs("\\|", f);
        else if (*t == '<')
            fputs("&lt;", f);
        else
            fputc(*t, f);
    }
}

int crane_scene_keys_markdown(FILE *f)
{
    if (!f) return BG_ERR_ARGUMENT;
    fputs("<!-- Generated from the key table (crane/crane_scene_keys.c) by `crane --list-keys`; do "
          "not edit.\n     tests/crane/test_crane_scene_keys.c fails when this file and the table "
          "disagree. -->\n",
          f);
    fputs(
        "# Scene keys\n\n"
        "A scene file (INI text: `crane/crane_scene.h`) starts from the defaults below, the paper "
        "scene\n(`crane/scenes/paper.ini`), and changes what it states; every key is optional and "
        "may appear at\nmost once. Keys and sections are matched without regard to case. Units "
        "are SI: m, kg, s, N, Pa, rad.\n\n| type | written as |\n|---|---|\n",
        f);
    for (size_t i = 0; i < sizeof TYPES / sizeof *TYPES; i++) {
        fprintf(f, "| %s | ", TYPES[i].name);
        md_text(f, TYPES[i].syntax);
        fputs(" |\n", f);
    }
    /* the consistency checks of crane_scene_check (crane_scene.c) */
    fputs(
        "\nBesides each key's range, a scene must be consistent: the boom must reach its tip "
        "radius\n(|tip_radius - foot.x| < length), a flexible boom (elements > 0) must lean "
        "(tip_radius != foot.x:\na vertical beam has no luffing plane), the reference's times must "
        "be ordered (0 < t1 <= t2 < t3)\nand output_step <= t_end.\n",
        f);
    const char *prev = NULL;
    crane_scene dflt;
    crane_scene_default(&dflt);
    for (int i = 0; i < NKEYS; i++) {
        const key_def *k = &KEYS[i];
        if (!prev || strcmp(prev, k->pub.section))
            fprintf(
                f,
                "\n## [%s]\n\n| key | value | default | unit | meaning |\n|---|---|---|---|---|\n",
                k->pub.section);
        prev = k->pub.section;
        char v[160];
        value_text(&dflt, k, v, sizeof v);
        fprintf(f, "| `%s` | ", k->pub.key);
        md_text(f, k->pub.expected);
        fprintf(f, " | `%s` | ", v);
        md_text(f, k->pub.unit);
        fputs(" | ", f);
        md_text(f, k->pub.meaning);
        if (k->note) {
            fputs(" (", f);
            md_text(f, k->note);
            fputs(")", f);
        }
        fputs(" |\n", f);
    }
    return ferror(f) ? BG_ERR_IO : BG_OK;
}
