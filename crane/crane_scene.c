/* Scene files of the rotary crane (see crane_scene.h): a table of keys (section, name, type,
 * range, unit, field offset) drives parsing, checking, writing and comparing.
 *
 * inih does the INI syntax. It reports no line numbers to the handler (INI_HANDLER_LINENO is a
 * build option of the library, off in Debian's), so the text is fed to ini_parse_stream through
 * a reader of our own that counts lines; inih handles each line as soon as it has read it, so the
 * reader's count is the handler's line. The reader also checks each line before inih sees it
 * (section names, lines without '=', indented continuation lines, over-long lines), so that every
 * message can say what is wrong, and stops the parse at the first error. */
#include "crane_scene.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <ini.h>

/* ------------------------------------------------------------------ the keys ---- */

typedef enum range_kind {
    R_ANY,    /* finite */
    R_POS,    /* > 0 */
    R_NONNEG, /* >= 0 */
    R_OPEN01, /* in (0, 1) */
    R_UNIT0,  /* in [0, 1) */
    R_INT     /* integer in lo..hi */
} range_kind;

typedef struct key_def {
    crane_scene_key pub;
    size_t off;
    range_kind range;
    int lo, hi; /* R_INT */
} key_def;

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

static const key_def KEYS[] = {
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
#define NKEYS ((int)(sizeof KEYS / sizeof *KEYS))

int crane_scene_nkeys(void)
{
    return NKEYS;
}

const crane_scene_key *crane_scene_key_at(int i)
{
    return i >= 0 && i < NKEYS ? &KEYS[i].pub : NULL;
}

static double *dfield(crane_scene *s, const key_def *k)
{
    return (double *)(void *)((char *)s + k->off);
}
static const double *cdfield(const crane_scene *s, const key_def *k)
{
    return (const double *)(const void *)((const char *)s + k->off);
}
static int *ifield(crane_scene *s, const key_def *k)
{
    return (int *)(void *)((char *)s + k->off);
}
static const int *cifield(const crane_scene *s, const key_def *k)
{
    return (const int *)(const void *)((const char *)s + k->off);
}

/* ---------------------------------------------------------- names, distance ---- */

static int ieq(const char *a, const char *b)
{
    for (; *a && *b; a++, b++)
        if (tolower((unsigned char)*a) != tolower((unsigned char)*b)) return 0;
    return *a == *b;
}

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

static const char *known_section(const char *name)
{
    for (int i = 0; i < NKEYS; i++)
        if (ieq(KEYS[i].pub.section, name)) return KEYS[i].pub.section;
    return NULL;
}

static const char *nearest_section(const char *name, int *dist)
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

static int find_key(const char *section, const char *key)
{
    for (int i = 0; i < NKEYS; i++)
        if (ieq(KEYS[i].pub.section, section) && ieq(KEYS[i].pub.key, key)) return i;
    return -1;
}

/* Nearest key of section (-1 if it has none). */
static int nearest_key(const char *section, const char *key, int *dist)
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
static void list_keys(const char *section, char *buf, size_t size)
{
    size_t len = 0;
    buf[0] = '\0';
    for (int i = 0; i < NKEYS && len < size; i++)
        if (ieq(KEYS[i].pub.section, section))
            len +=
                (size_t)snprintf(buf + len, size - len, "%s%s", len ? ", " : "", KEYS[i].pub.key);
}

static void list_sections(char *buf, size_t size)
{
    const char *names[32];
    int n = section_count(names, 32);
    size_t len = 0;
    buf[0] = '\0';
    for (int i = 0; i < n && len < size; i++)
        len += (size_t)snprintf(buf + len, size - len, "%s[%s]", len ? ", " : "", names[i]);
}

/* A value quoted for a message: at most 60 characters, no line break. */
static void quote(const char *v, char *buf, size_t size)
{
    size_t n = 0, max = size - 4 < 60 ? size - 4 : 60;
    for (; v[n] && v[n] != '\n' && v[n] != '\r' && n < max; n++)
        buf[n] = v[n];
    buf[n] = '\0';
    if (v[n] && v[n] != '\n' && v[n] != '\r') strcat(buf, "...");
}

/* ------------------------------------------------------------------ values ---- */

/* A decimal number: strtod alone would also take hexadecimal ("0x4c", "0x1p3"), "inf" and
 * "nan"; the scene files' numbers are decimal (digits, sign, point, exponent) and finite. */
static int parse_double(const char *v, double *out)
{
    while (isspace((unsigned char)*v))
        v++;
    if (!*v) return 0;
    const char *q = v;
    while (*q && !isspace((unsigned char)*q))
        if (!strchr("0123456789+-.eE", *q++)) return 0;
    char *end;
    errno = 0;
    double x = strtod(v, &end);
    while (isspace((unsigned char)*end))
        end++;
    if (*end || end == v) return 0;
    if (!isfinite(x)) return 0;
    if (errno == ERANGE && fabs(x) > 1) return 0; /* overflow; underflow is harmless */
    *out = x;
    return 1;
}

static int in_range(range_kind r, double x)
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

static void expected_text(const key_def *k, char *buf, size_t size)
{
    if (k->pub.unit[0])
        snprintf(buf, size, "%s (%s)", k->pub.expected, k->pub.unit);
    else
        snprintf(buf, size, "%s", k->pub.expected);
}

/* A value written in hexadecimal ("0x4c", also inside a vector), which strtod and strtol with
 * base 0 would take: the message then says that numbers are decimal. */
static int looks_hex(const char *v)
{
    for (const char *p = v; *p; p++)
        if (*p == '0' && (p[1] == 'x' || p[1] == 'X') && (p == v || !isalnum((unsigned char)p[-1])))
            return 1;
    return 0;
}

static int value_error(bg_error *err, const char *origin, const key_def *k, const char *got)
{
    char exp[160], q[80];
    expected_text(k, exp, sizeof exp);
    quote(got, q, sizeof q);
    int hex = k->pub.type != CRANE_KEY_NAME && k->pub.type != CRANE_KEY_BOOLEAN && looks_hex(got);
    return bg_error_raise(err, BG_ERR_ARGUMENT, "crane_scene",
                          "%s%skey '%s' in [%s]: expected %s, got '%s'%s", origin ? origin : "",
                          origin ? ": " : "", k->pub.key, k->pub.section, exp, q,
                          hex ? " (numbers are decimal: hexadecimal is not accepted)" : "");
}

static int valid_name(const char *v)
{
    size_t n = strlen(v);
    if (n < 1 || n > 63) return 0;
    for (size_t i = 0; i < n; i++) {
        int c = (unsigned char)v[i];
        if (!(isalnum(c) || c == '_' || c == '.' || c == '-')) return 0;
    }
    return strcmp(v, ".") && strcmp(v, "..");
}

/* Parse value for key k into s. */
static int set_value(crane_scene *s, const key_def *k, const char *value, const char *origin,
                     bg_error *err)
{
    switch (k->pub.type) {
    case CRANE_KEY_NUMBER: {
        double x;
        if (!parse_double(value, &x) || !in_range(k->range, x))
            return value_error(err, origin, k, value);
        *dfield(s, k) = x;
        return BG_OK;
    }
    case CRANE_KEY_VECTOR: {
        double x[3];
        const char *p = value;
        char part[128];
        for (int i = 0; i < 3; i++) {
            const char *e = strchr(p, ',');
            size_t n = e ? (size_t)(e - p) : strlen(p);
            if ((i < 2) != (e != NULL) || n >= sizeof part)
                return value_error(err, origin, k, value);
            memcpy(part, p, n);
            part[n] = '\0';
            if (!parse_double(part, &x[i]) || !in_range(k->range, x[i]))
                return value_error(err, origin, k, value);
            p = e ? e + 1 : p + n;
        }
        memcpy(dfield(s, k), x, sizeof x);
        return BG_OK;
    }
    case CRANE_KEY_INTEGER: {
        const char *v = value;
        char *end;
        while (isspace((unsigned char)*v))
            v++;
        errno = 0;
        long x = strtol(v, &end, 10);
        while (isspace((unsigned char)*end))
            end++;
        if (!*v || *end || errno == ERANGE || x < k->lo || x > k->hi)
            return value_error(err, origin, k, value);
        *ifield(s, k) = (int)x;
        return BG_OK;
    }
    case CRANE_KEY_BOOLEAN: {
        static const char *yes[] = {"true", "yes", "on", "1"}, *no[] = {"false", "no", "off", "0"};
        for (int i = 0; i < 4; i++) {
            if (ieq(value, yes[i])) {
                *ifield(s, k) = 1;
                return BG_OK;
            }
            if (ieq(value, no[i])) {
                *ifield(s, k) = 0;
                return BG_OK;
            }
        }
        return value_error(err, origin, k, value);
    }
    case CRANE_KEY_NAME:
        if (!valid_name(value)) return value_error(err, origin, k, value);
        memset(s->name, 0, sizeof s->name);
        memcpy(s->name, value, strlen(value));
        return BG_OK;
    }
    return BG_ERR_ARGUMENT;
}

int crane_scene_set(crane_scene *s, const char *section, const char *key, const char *value,
                    const char *origin, bg_error *err)
{
    const char *o = origin ? origin : "", *sep = origin ? ": " : "";
    if (!s || !section || !key || !value)
        return bg_error_raise(err, BG_ERR_ARGUMENT, "crane_scene_set", "%s%snull argument", o, sep);
    if (!known_section(section)) {
        int d;
        const char *near = nearest_section(section, &d);
        return bg_error_raise(err, BG_ERR_ARGUMENT, "crane_scene_set",
                              "%s%sunknown section [%s]; did you mean [%s]?", o, sep, section,
                              near);
    }
    int i = find_key(section, key);
    if (i < 0) {
        int d;
        int j = nearest_key(section, key, &d);
        return bg_error_raise(err, BG_ERR_ARGUMENT, "crane_scene_set",
                              "%s%sunknown key '%s' in [%s]; did you mean '%s'?", o, sep, key,
                              known_section(section), j >= 0 ? KEYS[j].pub.key : "");
    }
    return set_value(s, &KEYS[i], value, origin, err);
}

/* ------------------------------------------------------------- consistency ---- */

/* Where a key was set: a "FILE:LINE" of the parse, or the caller's origin. */
typedef struct origin_map {
    const char *file; /* NULL: use fixed */
    const int *line;  /* NKEYS lines (0: not in the file) */
    const char *fixed;
} origin_map;

static const char *origin_of(const origin_map *om, int key, char *buf, size_t size)
{
    if (om->file && om->line && om->line[key] > 0) {
        snprintf(buf, size, "%s:%d", om->file, om->line[key]);
        return buf;
    }
    if (om->file) {
        snprintf(buf, size, "%s", om->file);
        return buf;
    }
    return om->fixed;
}

/* The first of keys a, b, c that the file sets (a if none). */
static int blame(const origin_map *om, int a, int b, int c)
{
    if (!om->line) return a;
    if (om->line[a] > 0) return a;
    if (b >= 0 && om->line[b] > 0) return b;
    if (c >= 0 && om->line[c] > 0) return c;
    return a;
}

static int key_index(const char *section, const char *key)
{
    return find_key(section, key);
}

static int check_scene(const crane_scene *s, const origin_map *om, bg_error *err)
{
    char ob[1200], got[64];
    /* every field in its range */
    for (int i = 0; i < NKEYS; i++) {
        const key_def *k = &KEYS[i];
        int ok = 1;
        switch (k->pub.type) {
        case CRANE_KEY_NUMBER:
            ok = in_range(k->range, *cdfield(s, k));
            snprintf(got, sizeof got, "%.17g", *cdfield(s, k));
            break;
        case CRANE_KEY_VECTOR:
            for (int j = 0; j < 3; j++)
                ok = ok && in_range(k->range, cdfield(s, k)[j]);
            snprintf(got, sizeof got, "%.6g, %.6g, %.6g", cdfield(s, k)[0], cdfield(s, k)[1],
                     cdfield(s, k)[2]);
            break;
        case CRANE_KEY_INTEGER:
        case CRANE_KEY_BOOLEAN:
            ok = *cifield(s, k) >= k->lo && *cifield(s, k) <= k->hi;
            snprintf(got, sizeof got, "%d", *cifield(s, k));
            break;
        case CRANE_KEY_NAME:
            ok = memchr(s->name, '\0', sizeof s->name) != NULL && valid_name(s->name);
            snprintf(got, sizeof got, "%.*s", (int)sizeof s->name - 1, s->name);
            break;
        }
        if (!ok) return value_error(err, origin_of(om, i, ob, sizeof ob), k, got);
    }
    /* the boom reaches its tip radius */
    double dx = s->boom_tip_radius - s->boom_foot[0];
    if (!(fabs(dx) < s->boom_length)) {
        int k = blame(om, key_index("boom", "tip_radius"), key_index("boom", "length"),
                      key_index("boom", "foot"));
        const char *o = origin_of(om, k, ob, sizeof ob);
        return bg_error_raise(err, BG_ERR_ARGUMENT, "crane_scene_check",
                              "%s%skey '%s' in [boom]: expected a boom that reaches its tip "
                              "(|tip_radius - foot.x| < length), got tip_radius %g m, foot.x %g "
                              "m, length %g m",
                              o ? o : "", o ? ": " : "", KEYS[k].pub.key, s->boom_tip_radius,
                              s->boom_foot[0], s->boom_length);
    }
    /* a flexible boom leans: a vertical one (tip_radius = foot.x) has no luffing plane to orient
     * its cross-section by (mech_beam_chain: "an up vector not along the beam") */
    if (s->boom_elements > 0 && !(fabs(dx) > 1e-9 * s->boom_length)) {
        int k = blame(om, key_index("boom", "tip_radius"), key_index("boom", "foot"),
                      key_index("boom", "elements"));
        const char *o = origin_of(om, k, ob, sizeof ob);
        return bg_error_raise(err, BG_ERR_ARGUMENT, "crane_scene_check",
                              "%s%skey '%s' in [boom]: expected a boom that leans (tip_radius != "
                              "foot.x), got tip_radius %g m = foot.x %g m: a vertical flexible "
                              "boom (elements = %d) has no luffing plane; move [boom] tip_radius "
                              "or foot, or make it rigid (elements = 0)",
                              o ? o : "", o ? ": " : "", KEYS[k].pub.key, s->boom_tip_radius,
                              s->boom_foot[0], s->boom_elements);
    }
    /* the reference's times are ordered: 0 < t1 <= t2 < t3 */
    if (!(s->ref_t1 <= s->ref_t2 && s->ref_t2 < s->ref_t3)) {
        int i1 = key_index("reference", "t1"), i2 = key_index("reference", "t2"),
            i3 = key_index("reference", "t3");
        int k = s->ref_t1 > s->ref_t2 ? blame(om, i2, i1, -1) : blame(om, i3, i2, -1);
        const char *o = origin_of(om, k, ob, sizeof ob);
        return bg_error_raise(err, BG_ERR_ARGUMENT, "crane_scene_check",
                              "%s%skey '%s' in [reference]: expected times 0 < t1 <= t2 < t3, got "
                              "t1 = %g s, t2 = %g s, t3 = %g s",
                              o ? o : "", o ? ": " : "", KEYS[k].pub.key, s->ref_t1, s->ref_t2,
                              s->ref_t3);
    }
    if (!(s->output_step <= s->t_end)) {
        int k = blame(om, key_index("solver", "output_step"), key_index("solver", "t_end"), -1);
        const char *o = origin_of(om, k, ob, sizeof ob);
        return bg_error_raise(err, BG_ERR_ARGUMENT, "crane_scene_check",
                              "%s%skey '%s' in [solver]: expected output_step <= t_end, got "
                              "output_step = %g s, t_end = %g s",
                              o ? o : "", o ? ": " : "", KEYS[k].pub.key, s->output_step, s->t_end);
    }
    return BG_OK;
}

int crane_scene_check(const crane_scene *s, const char *origin, bg_error *err)
{
    if (!s) return bg_error_raise(err, BG_ERR_ARGUMENT, "crane_scene_check", "null scene");
    origin_map om = {NULL, NULL, origin};
    return check_scene(s, &om, err);
}

/* ------------------------------------------------------------------ parsing ---- */

typedef struct parse_ctx {
    crane_scene *s;
    const char *file;
    bg_error *err;
    const char *text;
    size_t pos, len;
    int line; /* number of the line last read */
    int failed;
    int have_prev_key; /* inih treats an indented line after a key as a continuation */
    int seen[NKEYS];   /* line that set each key (0: none) */
} parse_ctx;

#if defined(__GNUC__)
__attribute__((format(printf, 2, 3)))
#endif
static int
fail_at(parse_ctx *c, const char *fmt, ...)
{
    char msg[BG_MESSAGE_SIZE];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    c->failed = 1;
    return bg_error_raise(c->err, BG_ERR_ARGUMENT, "crane_scene_parse", "%s:%d: %s", c->file,
                          c->line, msg);
}

/* Like inih's find_chars_or_comment: the first of chars, or an inline comment (';' after white
 * space), or the end. */
static const char *find_chars_or_comment(const char *s, const char *chars)
{
    int was_space = 0;
    while (*s && (!chars || !strchr(chars, *s)) && !(was_space && *s == ';')) {
        was_space = isspace((unsigned char)*s);
        s++;
    }
    return s;
}

static void trim_copy(const char *a, const char *b, char *out, size_t size)
{
    while (a < b && isspace((unsigned char)*a))
        a++;
    while (b > a && isspace((unsigned char)b[-1]))
        b--;
    size_t n = (size_t)(b - a) < size - 1 ? (size_t)(b - a) : size - 1;
    memcpy(out, a, n);
    out[n] = '\0';
}

/* Checks one line before inih sees it; 0 on error (the message is set). */
static int check_line(parse_ctx *c, char *line)
{
    char *p = line, q[80];
    if (c->line == 1 && (unsigned char)p[0] == 0xEF && (unsigned char)p[1] == 0xBB &&
        (unsigned char)p[2] == 0xBF)
        p += 3;
    char *start = p;
    while (*p && isspace((unsigned char)*p))
        p++;
    if (!*p || *p == ';' || *p == '#') return 1; /* blank or comment */
    quote(p, q, sizeof q);
    if (c->have_prev_key && p > start) {
        fail_at(c,
                "indented line '%s': continuation lines are not supported (remove the "
                "indentation)",
                q);
        return 0;
    }
    if (*p == '[') {
        const char *e = find_chars_or_comment(p + 1, "]");
        if (*e != ']') {
            fail_at(c, "section header without ']': '%s'", q);
            return 0;
        }
        char name[128];
        trim_copy(p + 1, e, name, sizeof name);
        const char *rest = e + 1;
        while (*rest && isspace((unsigned char)*rest))
            rest++;
        if (*rest && *rest != ';' && *rest != '#') {
            fail_at(c, "unexpected text after [%s]: '%s'", name, q);
            return 0;
        }
        if (!known_section(name)) {
            int d;
            const char *near = nearest_section(name, &d);
            if (d <= 3 && (size_t)d < strlen(name))
                fail_at(c, "unknown section [%s]; did you mean [%s]?", name, near);
            else {
                char all[400];
                list_sections(all, sizeof all);
                fail_at(c, "unknown section [%s]; did you mean [%s]? (sections: %s)", name, near,
                        all);
            }
            return 0;
        }
        c->have_prev_key = 0;
        return 1;
    }
    const char *e = find_chars_or_comment(p, "=:");
    if (*e != '=' && *e != ':') {
        fail_at(c, "expected 'key = value' or '[section]', got '%s'", q);
        return 0;
    }
    char key[128];
    trim_copy(p, e, key, sizeof key);
    if (!key[0]) {
        fail_at(c, "key missing before '%c': '%s'", *e, q);
        return 0;
    }
    c->have_prev_key = 1;
    return 1;
}

/* Lines end with LF, CR LF or a lone CR (old Mac files): the length of the line at p (without
 * its end) and of the line end that follows it (0 at the end of the text). */
static size_t line_length(const char *p, size_t rest)
{
    size_t n = 0;
    while (n < rest && p[n] != '\n' && p[n] != '\r')
        n++;
    return n;
}

static size_t line_end_length(const char *p, size_t rest)
{
    if (rest == 0) return 0;
    return p[0] == '\r' && rest > 1 && p[1] == '\n' ? 2 : 1;
}

/* The fgets-style reader for inih: one line of the text per call. */
static char *reader(char *str, int num, void *stream)
{
    parse_ctx *c = stream;
    if (c->failed || c->pos >= c->len) return NULL;
    const char *p = c->text + c->pos;
    size_t rest = c->len - c->pos, n = line_length(p, rest);
    c->line++;
    c->pos += n + line_end_length(p + n, rest - n);
    if (memchr(p, '\0', n)) {
        fail_at(c, "the line contains a NUL character (not a text file?)");
        return NULL;
    }
    if (n + 2 > (size_t)num) {
        /* name the key if the line has one */
        char key[64] = "";
        const char *e = memchr(p, '=', n);
        if (e && p[0] != '[' && p[0] != ';' && p[0] != '#') trim_copy(p, e, key, sizeof key);
        if (key[0])
            fail_at(c, "line longer than %d characters (key '%s')", num - 2, key);
        else
            fail_at(c, "line longer than %d characters", num - 2);
        return NULL;
    }
    memcpy(str, p, n);
    str[n] = '\n';
    str[n + 1] = '\0';
    if (!check_line(c, str)) return NULL;
    return str;
}

static int handler(void *user, const char *section, const char *name, const char *value)
{
    parse_ctx *c = user;
    if (c->failed) return 0;
    if (!section[0]) {
        int best = -1, bd = 1 << 30;
        for (int i = 0; i < NKEYS; i++) {
            int d = crane_scene_edit_distance(name, KEYS[i].pub.key);
            if (d < bd) bd = d, best = i;
        }
        fail_at(c, "key '%s' before any [section]; did you mean '%s' in [%s]?", name,
                KEYS[best].pub.key, KEYS[best].pub.section);
        return 0;
    }
    const char *sec = known_section(section);
    if (!sec) { /* the reader has rejected it already */
        fail_at(c, "key '%s' in unknown section [%s]", name, section);
        return 0;
    }
    int i = find_key(sec, name);
    if (i < 0) {
        int d, j = nearest_key(sec, name, &d);
        char other[200] = "";
        size_t len = 0;
        for (int k = 0; k < NKEYS; k++)
            if (ieq(KEYS[k].pub.key, name) && len < sizeof other)
                len += (size_t)snprintf(other + len, sizeof other - len, "%s[%s]", len ? ", " : "",
                                        KEYS[k].pub.section);
        if (other[0])
            fail_at(c, "unknown key '%s' in [%s]; did you mean '%s'? ('%s' is a key of %s)", name,
                    sec, KEYS[j].pub.key, name, other);
        else if (d <= 3 && (size_t)d < strlen(name))
            fail_at(c, "unknown key '%s' in [%s]; did you mean '%s'?", name, sec, KEYS[j].pub.key);
        else {
            char all[400];
            list_keys(sec, all, sizeof all);
            fail_at(c, "unknown key '%s' in [%s]; did you mean '%s'? (keys of [%s]: %s)", name, sec,
                    KEYS[j].pub.key, sec, all);
        }
        return 0;
    }
    if (c->seen[i]) {
        fail_at(c, "key '%s' in [%s] given twice (first on line %d)", KEYS[i].pub.key, sec,
                c->seen[i]);
        return 0;
    }
    char origin[1100];
    snprintf(origin, sizeof origin, "%s:%d", c->file, c->line);
    if (set_value(c->s, &KEYS[i], value, origin, c->err) != BG_OK) {
        c->failed = 1;
        return 0;
    }
    c->seen[i] = c->line;
    return 1;
}

/* The number of keys set (*nkeys, may be NULL) besides the statuses of parse_string. */
static int parse_counted(crane_scene *s, const char *text, const char *filename, int *nkeys,
                         bg_error *err)
{
    const char *file = filename ? filename : "<string>";
    if (nkeys) *nkeys = 0;
    if (!s || !text)
        return bg_error_raise(err, BG_ERR_ARGUMENT, "crane_scene_parse", "%s: null argument", file);
    parse_ctx c;
    memset(&c, 0, sizeof c);
    c.s = s;
    c.file = file;
    c.err = err;
    c.text = text;
    c.len = strlen(text);
    int r = ini_parse_stream(reader, &c, handler, &c);
    if (c.failed) return err && err->status != BG_OK ? err->status : BG_ERR_ARGUMENT;
    if (r == -2)
        return bg_error_raise(err, BG_ERR_MEMORY, "crane_scene_parse", "%s: out of memory", file);
    if (r != 0) {
        c.line = r;
        return fail_at(&c, "syntax error");
    }
    if (nkeys)
        for (int i = 0; i < NKEYS; i++)
            *nkeys += c.seen[i] > 0;
    origin_map om = {file, c.seen, NULL};
    return check_scene(s, &om, err);
}

int crane_scene_parse_string(crane_scene *s, const char *text, const char *filename, bg_error *err)
{
    return parse_counted(s, text, filename, NULL, err);
}

static int parse_file_counted(crane_scene *s, FILE *f, const char *filename, int *nkeys,
                              bg_error *err)
{
    if (nkeys) *nkeys = 0;
    const char *file = filename ? filename : "<file>";
    if (!s || !f)
        return bg_error_raise(err, BG_ERR_ARGUMENT, "crane_scene_parse", "%s: null argument", file);
    size_t cap = 4096, len = 0;
    char *buf = malloc(cap);
    if (!buf) return bg_error_raise(err, BG_ERR_MEMORY, "crane_scene_parse", "out of memory");
    for (;;) {
        if (len + 1 >= cap) {
            if (cap >= (size_t)16 << 20) {
                free(buf);
                return bg_error_raise(err, BG_ERR_ARGUMENT, "crane_scene_parse",
                                      "%s: larger than 16 MB: not a scene file", file);
            }
            char *nb = realloc(buf, cap * 2);
            if (!nb) {
                free(buf);
                return bg_error_raise(err, BG_ERR_MEMORY, "crane_scene_parse", "out of memory");
            }
            buf = nb;
            cap *= 2;
        }
        size_t got = fread(buf + len, 1, cap - 1 - len, f);
        len += got;
        if (got == 0) break;
    }
    if (ferror(f)) {
        free(buf);
        return bg_error_raise(err, BG_ERR_IO, "crane_scene_parse", "%s: read error: %s", file,
                              strerror(errno));
    }
    buf[len] = '\0';
    /* a NUL inside the text would end it early: report it at its line */
    size_t z = strlen(buf);
    int r;
    if (z < len) {
        int line = 1;
        for (size_t i = 0, e; (i += line_length(buf + i, z - i)) < z; i += e, line++)
            e = line_end_length(buf + i, z - i);
        r = bg_error_raise(err, BG_ERR_ARGUMENT, "crane_scene_parse",
                           "%s:%d: the line contains a NUL character (not a text file?)", file,
                           line);
    } else {
        r = parse_counted(s, buf, file, nkeys, err);
    }
    free(buf);
    return r;
}

int crane_scene_parse_file(crane_scene *s, FILE *f, const char *filename, bg_error *err)
{
    return parse_file_counted(s, f, filename, NULL, err);
}

const char *crane_file_kind(unsigned mode)
{
    mode_t m = (mode_t)mode;
    return S_ISREG(m)    ? "a regular file"
           : S_ISDIR(m)  ? "a directory"
           : S_ISFIFO(m) ? "a FIFO (named pipe)"
           : S_ISCHR(m)  ? "a character device"
           : S_ISBLK(m)  ? "a block device"
           : S_ISSOCK(m) ? "a socket"
           : S_ISLNK(m)  ? "a symbolic link"
                         : "not a regular file";
}

int crane_scene_load(crane_scene *s, const char *path, bg_error *err)
{
    return crane_scene_load_counted(s, path, NULL, err);
}

int crane_scene_load_counted(crane_scene *s, const char *path, int *nkeys, bg_error *err)
{
    if (nkeys) *nkeys = 0;
    if (!s || !path)
        return bg_error_raise(err, BG_ERR_ARGUMENT, "crane_scene_load", "null argument");
    crane_scene_default(s);
    /* the scene is named after its file unless it says otherwise */
    const char *base = strrchr(path, '/');
    base = base ? base + 1 : path;
    char stem[sizeof s->name];
    size_t n = 0;
    for (; base[n] && n < sizeof stem - 1; n++) {
        int ch = (unsigned char)base[n];
        stem[n] = (char)(isalnum(ch) || ch == '_' || ch == '.' || ch == '-' ? ch : '_');
    }
    stem[n] = '\0';
    if (n > 4 && !strcmp(stem + n - 4, ".ini")) stem[n - 4] = '\0';
    if (valid_name(stem)) strcpy(s->name, stem);
    /* opened without blocking (a FIFO without a writer would wait for ever), then only a
     * regular file is read: a directory, FIFO or device is named as what it is */
    int fd = open(path, O_RDONLY | O_NONBLOCK);
    if (fd < 0)
        return bg_error_raise(err, BG_ERR_IO, "crane_scene_load", "%s: cannot open: %s", path,
                              strerror(errno));
    struct stat st;
    int e = fstat(fd, &st) != 0 ? errno : 0;
    if (e || !S_ISREG(st.st_mode)) {
        close(fd);
        if (e)
            return bg_error_raise(err, BG_ERR_IO, "crane_scene_load", "%s: cannot open: %s", path,
                                  strerror(e));
        return bg_error_raise(err, BG_ERR_IO, "crane_scene_load", "%s: %s, not a scene file", path,
                              crane_file_kind((unsigned)st.st_mode));
    }
    FILE *f = fdopen(fd, "r");
    if (!f) {
        e = errno;
        close(fd);
        return bg_error_raise(err, BG_ERR_IO, "crane_scene_load", "%s: cannot open: %s", path,
                              strerror(e));
    }
    int r = parse_file_counted(s, f, path, nkeys, err);
    fclose(f);
    return r;
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
