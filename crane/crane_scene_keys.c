/* The scene keys (crane_scene.h): the table of keys (section, name, type, range, unit, field
 * offset) that drives parsing, checking, writing and comparing; the look-ups by name with the
 * suggestions' edit distance; writing and comparing scenes. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "crane_scene_impl.h"

#define OFF(field) offsetof(crane_scene, field)
#define KNUM(sec, key, field, rng, expected, unit, meaning)                                        \
    {                                                                                              \
        {sec, key, CRANE_KEY_NUMBER, unit, expected, meaning}, OFF(field), rng, 0, 0               \
    }
#define KVEC(sec, key, field, rng, expected, unit, meaning)                                        \
    {                                                                                              \
        {sec, key, CRANE_KEY_VECTOR, unit, expected, meaning}, OFF(field), rng, 0, 0               \
    }
#define KBOOL(sec, key, field, meaning)                                                            \
    {                                                                                              \
        {sec, key, CRANE_KEY_BOOLEAN, "", "a boolean (true/false, yes/no, on/off, 1/0)", meaning}, \
            OFF(field), R_INT, 0, 1                                                                \
    }
#define KINT(sec, key, field, lo, hi, expected, unit, meaning)                                     \
    {                                                                                              \
        {sec, key, CRANE_KEY_INTEGER, unit, expected, meaning}, OFF(field), R_INT, lo, hi          \
    }

#define EXP_POS "a number > 0"
#define EXP_NONNEG "a number >= 0"
#define EXP_ANY "a finite number"
#define EXP_VPOS "three numbers > 0 'x, y, z'"
#define EXP_VANY "three finite numbers 'x, y, z'"

const key_def crane_scene_keys[] = {
    {{"scene", "name", CRANE_KEY_NAME, "", "a name of 1 to 63 characters from [A-Za-z0-9_.-]",
      "results go to results/<name>/"},
     OFF(name),
     R_ANY,
     0,
     0},
    KNUM("environment", "g", g, R_NONNEG, EXP_NONNEG, "m/s^2", "gravity, along -Z0"),
    KNUM("platform", "mass", platform_mass, R_POS, EXP_POS, "kg", "platform mass"),
    KVEC("platform", "inertia", platform_inertia, R_POS, EXP_VPOS, "kg m^2",
         "principal moments of inertia about the mass centre"),
    KVEC("platform", "com", platform_com, R_ANY, EXP_VANY, "m", "mass centre, platform frame"),
    KVEC("platform", "joint_A", joint_A, R_ANY, EXP_VANY, "m",
         "slewing joint A on the axis, global frame"),
    KINT("boom", "elements", boom_elements, 0, 512, "an integer in 0..512", "",
         "beam elements; 0: the boom is one rigid body"),
    KVEC("boom", "foot", boom_foot, R_ANY, EXP_VANY, "m", "boom foot (hinge) B, platform frame"),
    KNUM("boom", "length", boom_length, R_POS, EXP_POS, "m", "boom length"),
    KNUM("boom", "tip_radius", boom_tip_radius, R_NONNEG, EXP_NONNEG, "m",
         "distance of the tip from the slewing axis (sets the luffing angle)"),
    KNUM("boom", "E", boom_E, R_POS, EXP_POS, "Pa", "Young's modulus"),
    KNUM("boom", "G", boom_G, R_POS, EXP_POS, "Pa", "shear modulus"),
    KNUM("boom", "A", boom_A, R_POS, EXP_POS, "m^2", "cross-section area"),
    KNUM("boom", "I_luff", boom_I_luff, R_POS, EXP_POS, "m^4",
         "second moment of area, bending in the luffing plane"),
    KNUM("boom", "I_side", boom_I_side, R_POS, EXP_POS, "m^4",
         "second moment of area, bending out of the luffing plane"),
    KNUM("boom", "J", boom_J, R_POS, EXP_POS, "m^4", "torsion constant"),
    KNUM("boom", "rho", boom_rho, R_POS, EXP_POS, "kg/m^3", "density"),
    KNUM("boom", "beta", boom_beta, R_NONNEG, EXP_NONNEG, "s",
         "stiffness-proportional damping; 0: none"),
    KBOOL("ties", "enabled", ties, "build the suspension ties"),
    KVEC("ties", "gantry_top", gantry_top, R_ANY, EXP_VANY, "m",
         "upper end of the ties on the platform, platform frame"),
    KNUM("ties", "spread", tie_spread, R_NONNEG, EXP_NONNEG, "m",
         "half the lateral distance of a pair of ties at the gantry (0: one tie)"),
    KNUM("ties", "E", tie_E, R_POS, EXP_POS, "Pa", "Young's modulus"),
    KNUM("ties", "A", tie_A, R_POS, EXP_POS, "m^2", "cross-section area"),
    KNUM("ties", "rho", tie_rho, R_NONNEG, EXP_NONNEG, "kg/m^3",
         "density: each tie's mass lumped half at each end; 0: massless"),
    KNUM("ties", "beta", tie_beta, R_NONNEG, EXP_NONNEG, "s",
         "stiffness-proportional damping (c = beta E A / length); 0: none"),
    KBOOL("rope", "enabled", rope, "build the rope and the load"),
    KNUM("rope", "length", rope_length, R_POS, EXP_POS, "m", "unstretched length"),
    KNUM("rope", "E", rope_E, R_POS, EXP_POS, "Pa", "Young's modulus (stiffness E A / length)"),
    KNUM("rope", "A", rope_A, R_POS, EXP_POS, "m^2", "cross-section area"),
    KNUM("rope", "damping", rope_damping, R_NONNEG, EXP_NONNEG, "N s/m", "axial damping"),
    KNUM("load", "mass", load_mass, R_POS, EXP_POS, "kg", "load with hook (built with the rope)"),
    KBOOL("counterweight", "enabled", counterweight, "build the counterweight"),
    KNUM("counterweight", "mass", cw_mass, R_POS, EXP_POS, "kg", "counterweight mass"),
    KVEC("counterweight", "pos", cw_pos, R_ANY, EXP_VANY, "m", "position, platform frame"),
    KBOOL("hydraulics", "enabled", hydraulics,
          "build the hydraulic drive and PID; false: the platform's rate is prescribed"),
    KNUM("hydraulics", "pump_speed", pump_speed, R_POS, EXP_POS, "rad/s", "pump drive speed"),
    KNUM("hydraulics", "pump_disp", pump_disp, R_POS, EXP_POS, "m^3/rev",
         "pump displacement at x = 1"),
    KNUM("hydraulics", "pump_leak", pump_leak, R_NONNEG, EXP_NONNEG, "m^3/(s Pa)",
         "pump leakage coefficient"),
    KNUM("hydraulics", "motor_disp", motor_disp, R_POS, EXP_POS, "m^3/rev", "motor displacement"),
    KNUM("hydraulics", "motor_leak", motor_leak, R_NONNEG, EXP_NONNEG, "m^3/(s Pa)",
         "motor leakage coefficient"),
    KNUM("hydraulics", "motor_inertia", motor_inertia, R_POS, EXP_POS, "kg m^2",
         "motor and gear input inertia"),
    KNUM("hydraulics", "gear_ratio", gear_ratio, R_POS, EXP_POS, "",
         "motor turns per platform turn"),
    KNUM("hydraulics", "line_volume", line_volume, R_POS, EXP_POS, "m^3", "volume of each line"),
    KNUM("hydraulics", "bulk_modulus", bulk_modulus, R_POS, EXP_POS, "Pa", "oil bulk modulus"),
    KNUM("hydraulics", "charge_pressure", charge_pressure, R_NONNEG, EXP_NONNEG, "Pa",
         "charge (boost) pressure of the low side"),
    KNUM("hydraulics", "relief_pressure", relief_pressure, R_NONNEG, EXP_NONNEG, "Pa",
         "cracking pressure difference of the cross-port relief valves (0: none)"),
    KNUM("hydraulics", "pump_servo_bandwidth", pump_servo_bw, R_NONNEG, EXP_NONNEG, "Hz",
         "bandwidth of the pump's displacement actuator (first-order lag); 0: instantaneous"),
    KNUM("controller", "kp", kp, R_NONNEG, EXP_NONNEG, "1/(rad/s)", "proportional gain"),
    KNUM("controller", "kd", kd, R_NONNEG, EXP_NONNEG, "1/(rad/s^2)", "derivative gain"),
    KNUM("controller", "ki", ki, R_NONNEG, EXP_NONNEG, "1/rad", "integral gain"),
    KNUM("controller", "kd_filter", kd_filter, R_NONNEG, EXP_NONNEG, "s",
         "time constant of the rate filter of the derivative term; 0: the measured acceleration"),
    KNUM("controller", "x_limit", x_limit, R_NONNEG, EXP_NONNEG, "",
         "smooth limit of |x|; 0: none"),
    KNUM("reference", "t1", ref_t1, R_POS, EXP_POS, "s", "end of the ramp up"),
    KNUM("reference", "t2", ref_t2, R_POS, EXP_POS, "s", "end of the plateau"),
    KNUM("reference", "t3", ref_t3, R_POS, EXP_POS, "s", "stop time (end of the ramp down)"),
    KNUM("reference", "rate", ref_rate, R_ANY, EXP_ANY, "rad/s", "plateau rate"),
    KBOOL("initial", "static_start", static_start,
          "start from the static equilibrium under gravity at theta = 0"),
    KNUM("solver", "t_end", t_end, R_POS, EXP_POS, "s", "end time"),
    KNUM("solver", "rtol", rtol, R_OPEN01, "a number in (0, 1)", "", "relative tolerance"),
    KNUM("solver", "atol", atol, R_POS, EXP_POS, "", "absolute tolerance"),
    KNUM("solver", "output_step", output_step, R_POS, EXP_POS, "s", "output interval"),
    KBOOL("solver", "nominal_scales", nominal_scales,
          "absolute tolerance of each unknown atol times its nominal magnitude (false: atol in SI "
          "units)"),
    KNUM("solver", "nominal_length", nominal_length, R_NONNEG, EXP_NONNEG, "m",
         "nominal magnitude of positions and stretch vectors (0: 1 m; a member keeps its length)"),
    KNUM("solver", "nominal_velocity", nominal_velocity, R_NONNEG, EXP_NONNEG, "m/s",
         "nominal magnitude of velocities (0: 1 m/s)"),
    KNUM("solver", "nominal_angular_velocity", nominal_angular_velocity, R_NONNEG, EXP_NONNEG,
         "rad/s", "nominal magnitude of angular velocities (0: 1 rad/s)"),
    KBOOL("solver", "stability_guard", stability_guard,
          "order lowered to 2 where undamped fast modes hold BDF orders 3..5 at their stability "
          "limit, which damps them (false: the order follows the error estimates alone)"),
    KNUM("solver", "newton_dgmax", newton_dgmax, R_UNIT0, "a number in [0, 1)", "",
         "the Newton matrix refactored from the saved Jacobian when 1/cj moved by more than "
         "this (0: only with a new Jacobian)"),
    KINT("solver", "newton_jac_age", newton_jac_age, 0, 1000000, "an integer in 0..1000000", "",
         "Jacobian evaluated again after this many steps or a Newton failure (with "
         "newton_dgmax > 0; 0: IDA's rule on 1/cj)"),
    KBOOL("solver", "newton_index2_scale_h", newton_index2_scale_h,
          "index-2 unknowns weigh h times less in the Newton convergence test"),
};
_Static_assert(sizeof crane_scene_keys / sizeof *crane_scene_keys == CRANE_SCENE_NKEYS,
               "CRANE_SCENE_NKEYS counts the table");

int crane_scene_nkeys(void)
{
    return NKEYS;
}

const crane_scene_key *crane_scene_key_at(int i)
{
    return i >= 0 && i < NKEYS ? &KEYS[i].pub : NULL;
}

/* ---------------------------------------------------------- names, distance ---- */

int crane_scene_edit_distance(const char *a, const char *b)
{
    enum { MAXL = 64 };
    size_t la = strlen(a), lb = strlen(b);
    if (la > MAXL) la = MAXL;
    if (lb > MAXL) lb = MAXL;
    int d[MAXL + 1][MAXL + 1];
    for (size_t i = 0; i <= la; i++)
        d[i][0] = (int)i;
    for (size_t j = 0; j <= lb; j++)
        d[0][j] = (int)j;
    for (size_t i = 1; i <= la; i++)
        for (size_t j = 1; j <= lb; j++) {
            int ca = tolower((unsigned char)a[i - 1]), cb = tolower((unsigned char)b[j - 1]);
            int cost = ca != cb, v = d[i - 1][j - 1] + cost;
            if (d[i - 1][j] + 1 < v) v = d[i - 1][j] + 1;
            if (d[i][j - 1] + 1 < v) v = d[i][j - 1] + 1;
            if (i > 1 && j > 1 && ca == tolower((unsigned char)b[j - 2]) &&
                tolower((unsigned char)a[i - 2]) == cb && d[i - 2][j - 2] + 1 < v)
                v = d[i - 2][j - 2] + 1;
            d[i][j] = v;
        }
    return d[la][lb];
}

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
        if (ieq(KEYS[i].pub.section, name)) return KEYS[i].pub.section;
    return NULL;
}

const char *csk_nearest_section(const char *name, int *dist)
{
    const char *names[32];
    int n = section_count(names, 32), best = -1, bd = 1 << 30;
    for (int i = 0; i < n; i++) {
        int d = crane_scene_edit_distance(name, names[i]);
        if (d < bd) bd = d, best = i;
    }
    *dist = bd;
    return best >= 0 ? names[best] : "";
}

int csk_find_key(const char *section, const char *key)
{
    for (int i = 0; i < NKEYS; i++)
        if (ieq(KEYS[i].pub.section, section) && ieq(KEYS[i].pub.key, key)) return i;
    return -1;
}

/* Nearest key of section (-1 if it has none). */
int csk_nearest_key(const char *section, const char *key, int *dist)
{
    int best = -1, bd = 1 << 30;
    for (int i = 0; i < NKEYS; i++) {
        if (!ieq(KEYS[i].pub.section, section)) continue;
        int d = crane_scene_edit_distance(key, KEYS[i].pub.key);
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
        if (ieq(KEYS[i].pub.section, section))
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
