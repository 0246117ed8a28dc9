/* Sweep files (sweep_spec.h): the parser, the axes and the cases, and the public entry points;
 * the parts are listed in sweep_spec_impl.h.
 *
 * inih does the INI syntax, as for the scene files (crane_scene.c): the text is fed to
 * ini_parse_stream through a reader of our own (sweep_ini.c) that counts lines and checks each
 * line (spec_check_line, here) before inih sees it, so that every message has its line; the
 * check also sees the section headers, which is how repeated [axis] sections become separate
 * axes. The handler only records the keys; the values are checked afterwards, section by section
 * (spec_finish, sweep_schema.c), so that the keys of a section may come in any order. Every
 * swept or set value is checked with crane_scene_set, the scene files' own check, and its
 * message is passed on behind "FILE:LINE: key '...' in [...]". */
#include <ctype.h>
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <ini.h>

#include "crane_scene.h"
#include "sweep_spec_impl.h"

/* ------------------------------------------------------------------ errors ---- */

#if defined(__GNUC__)
__attribute__((format(printf, 3, 4)))
#endif
int
spec_fail_line(parse_ctx *c, int line, const char *fmt, ...)
{
    if (c->failed) return -1;
    char msg[1536];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    c->failed = 1;
    if (line > 0)
        snprintf(c->err, c->errsize, "%s:%d: %s", c->file, line, msg);
    else
        snprintf(c->err, c->errsize, "%s: %s", c->file, msg);
    return -1;
}

/* ------------------------------------------------------------------- lines ---- */

int spec_check_line(parse_ctx *c, char *line)
{
    char *p = line, q[80];
    if (c->line == 1 && (unsigned char)p[0] == 0xEF && (unsigned char)p[1] == 0xBB &&
        (unsigned char)p[2] == 0xBF)
        p += 3;
    char *start = p;
    while (*p && isspace((unsigned char)*p))
        p++;
    if (!*p || *p == ';' || *p == '#') return 1;
    spec_quote(p, q, sizeof q);
    if (c->have_prev_key && p > start)
        return spec_fail_line(
                   c, c->line,
                   "indented line '%s': continuation lines are not supported (remove the "
                   "indentation)",
                   q),
               0;
    if (*p == '[') {
        const char *e = spec_find_chars_or_comment(p + 1, "]");
        if (*e != ']') return spec_fail_line(c, c->line, "section header without ']': '%s'", q), 0;
        char name[128];
        spec_trim_copy(p + 1, e, name, sizeof name);
        const char *rest = e + 1;
        while (*rest && isspace((unsigned char)*rest))
            rest++;
        if (*rest && *rest != ';' && *rest != '#')
            return spec_fail_line(c, c->line, "unexpected text after [%s]: '%s'", name, q), 0;
        int kind = spec_section_kind(name);
        if (kind == SEC_NONE) {
            int d;
            char all[128];
            const char *near = spec_nearest(name, SEC_NAMES, &d);
            spec_join(SEC_NAMES, "[", "]", all, sizeof all);
            return spec_fail_line(c, c->line,
                                  "unknown section [%s]; did you mean [%s]? (sections: %s)", name,
                                  near, all),
                   0;
        }
        if (kind != SEC_AXIS)
            for (int i = 0; i < c->nraw; i++)
                if (c->raw[i].kind == kind)
                    return spec_fail_line(c, c->line,
                                          "section [%s] given twice (first on line %d): one is "
                                          "allowed%s",
                                          SEC_NAMES[kind], c->raw[i].line,
                                          kind == SEC_LHS ? " (its keys are sampled together)"
                                                          : ""),
                           0;
        int naxis = 0;
        for (int i = 0; i < c->nraw; i++)
            naxis += c->raw[i].kind == SEC_AXIS;
        if (c->nraw >= NRAW || (kind == SEC_AXIS && naxis >= SWEEP_MAX_AXES - 1))
            return spec_fail_line(c, c->line, "too many [axis] sections (at most %d)",
                                  SWEEP_MAX_AXES - 1),
                   0;
        raw_section *r = &c->raw[c->nraw];
        memset(r, 0, sizeof *r);
        r->kind = kind;
        r->line = c->line;
        c->cur = c->nraw++;
        c->have_prev_key = 0;
        return 1;
    }
    const char *e = spec_find_chars_or_comment(p, "=:");
    if (*e != '=' && *e != ':')
        return spec_fail_line(c, c->line, "expected 'key = value' or '[section]', got '%s'", q), 0;
    char key[128];
    spec_trim_copy(p, e, key, sizeof key);
    if (!key[0]) return spec_fail_line(c, c->line, "key missing before '%c': '%s'", *e, q), 0;
    c->have_prev_key = 1;
    return 1;
}

/* -------------------------------------------------------------------- keys ---- */

static int handler(void *user, const char *section, const char *name, const char *value)
{
    parse_ctx *c = user;
    if (c->failed) return 0;
    (void)section; /* the reader's c->cur says which section instance it is */
    if (c->cur < 0) {
        spec_fail_line(
            c, c->line,
            "key '%s' before any section; a sweep file starts with [sweep], [set], [axis] "
            "or [lhs]",
            name);
        return 0;
    }
    raw_section *r = &c->raw[c->cur];
    const char *sec = SEC_NAMES[r->kind];
    const char *const *known = r->kind == SEC_SWEEP  ? SWEEP_KEYS
                               : r->kind == SEC_AXIS ? AXIS_KEYS
                                                     : LHS_KEYS;
    int scene_key = r->kind == SEC_SET || (r->kind == SEC_LHS && spec_is_scene_key_name(name));
    if (!scene_key) {
        int found = 0;
        for (int i = 0; known[i] && !found; i++)
            found = spec_ieq(known[i], name);
        if (!found) {
            int d;
            char all[160];
            const char *near = spec_nearest(name, known, &d);
            spec_join(known, "", "", all, sizeof all);
            if (r->kind == SEC_LHS)
                spec_fail_line(
                    c, c->line,
                    "unknown key '%s' in [lhs]; did you mean '%s'? (keys of [lhs]: %s, and "
                    "the sampled scene keys as SECTION.KEY = LO, HI)",
                    name, near, all);
            else if (r->kind == SEC_AXIS && spec_is_scene_key_name(name))
                spec_fail_line(c, c->line,
                               "unknown key '%s' in [axis]: an axis names its scene key with "
                               "'key = %s' and its values with 'values' or 'from', 'to', 'count'",
                               name, name);
            else if (d <= 3 && (size_t)d < strlen(name))
                spec_fail_line(c, c->line, "unknown key '%s' in [%s]; did you mean '%s'?", name,
                               sec, near);
            else
                spec_fail_line(c, c->line,
                               "unknown key '%s' in [%s]; did you mean '%s'? (keys of [%s]: %s)",
                               name, sec, near, sec, all);
            return 0;
        }
    }
    for (int i = 0; i < r->n; i++)
        if (spec_ieq(r->kv[i].key, name)) {
            spec_fail_line(c, c->line, "key '%s' in [%s] given twice (first on line %d)", name, sec,
                           r->kv[i].line);
            return 0;
        }
    if (r->n >= RAW_MAX) {
        spec_fail_line(c, c->line, "too many keys in [%s] (at most %d)", sec, RAW_MAX);
        return 0;
    }
    if (strlen(name) >= sizeof r->kv[0].key) {
        spec_fail_line(c, c->line, "key name longer than %d characters",
                       (int)sizeof r->kv[0].key - 1);
        return 0;
    }
    raw_kv *kv = &r->kv[r->n++];
    snprintf(kv->key, sizeof kv->key, "%s", name);
    snprintf(kv->value, sizeof kv->value, "%s", value);
    kv->line = c->line;
    return 1;
}

/* ---------------------------------------------------------- the swept keys ---- */

static int add_param(parse_ctx *c, const crane_scene_key *k, int axis, int line)
{
    sweep_spec *s = c->s;
    for (int i = 0; i < s->nparams; i++)
        if (!strcmp(s->params[i].section, k->section) && !strcmp(s->params[i].key, k->key))
            return spec_fail_line(c, line,
                                  "%s.%s is swept twice (also on line %d): a key belongs to "
                                  "one axis",
                                  k->section, k->key, s->params[i].line);
    for (int i = 0; i < s->nsets; i++)
        if (!strcmp(s->sets[i].section, k->section) && !strcmp(s->sets[i].key, k->key))
            return spec_fail_line(c, line,
                                  "%s.%s is swept here and set in [set] (line %d): remove one",
                                  k->section, k->key, s->sets[i].line);
    if (s->nparams >= SWEEP_MAX_PARAMS)
        return spec_fail_line(c, line, "too many swept keys (at most %d)", SWEEP_MAX_PARAMS);
    sweep_param *p = &s->params[s->nparams];
    memset(p, 0, sizeof *p);
    snprintf(p->section, sizeof p->section, "%s", k->section);
    snprintf(p->key, sizeof p->key, "%s", k->key);
    snprintf(p->name, sizeof p->name, "%s.%s", k->section, k->key);
    p->type = (int)k->type;
    p->axis = axis;
    p->line = line;
    return s->nparams++;
}

/* -------------------------------------------------------- lists and ranges ---- */

/* A generated value's text, 12 significant digits (a range's 0.30000000000000004 is written
 * 0.3): the text is the value the crane gets and sweep.csv shows. */
static void fmt_value(double x, char *buf, size_t size)
{
    snprintf(buf, size, "%.12g", x);
}

static int numeric_type(int type)
{
    return type == CRANE_KEY_NUMBER || type == CRANE_KEY_INTEGER;
}

int spec_finish_axis(parse_ctx *c, raw_section *r, const crane_scene *base)
{
    sweep_spec *s = c->s;
    raw_kv *kkey = spec_get(r, "key"), *kvals = spec_get(r, "values"), *kfrom = spec_get(r, "from"),
           *kto = spec_get(r, "to"), *kcount = spec_get(r, "count"),
           *kspace = spec_get(r, "spacing");
    if (!kkey)
        return spec_fail_line(c, r->line,
                              "[axis] without 'key': name the swept scene key, e.g. "
                              "'key = controller.kp'");
    const crane_scene_key *k = spec_scene_key(c, kkey->value, kkey->line, "key 'key' in [axis]");
    if (!k) return -1;
    int ax = s->naxes;
    sweep_axis *a = &s->axes[ax];
    memset(a, 0, sizeof *a);
    a->line = r->line;
    int p = add_param(c, k, ax, kkey->line);
    if (p < 0) return -1;
    a->nparams = 1;
    a->param[0] = p;
    char what[400];
    if (kvals) {
        if (kfrom || kto || kcount || kspace) {
            raw_kv *other = kfrom ? kfrom : kto ? kto : kcount ? kcount : kspace;
            return spec_fail_line(c, other->line,
                                  "key '%s' in [axis]: an axis has either 'values' (line %d) or a "
                                  "range ('from', 'to', 'count'), not both",
                                  other->key, kvals->line);
        }
        a->kind = SWEEP_AXIS_LIST;
        char sep = k->type == CRANE_KEY_VECTOR ? '|' : ',';
        int n = 1;
        for (const char *q = kvals->value; *q; q++)
            n += *q == sep;
        a->values = calloc((size_t)n, sizeof *a->values);
        if (!a->values) return spec_fail_line(c, kvals->line, "out of memory");
        const char *q = kvals->value;
        for (int i = 0; i < n; i++) {
            const char *e = strchr(q, sep);
            spec_trim_copy(q, e ? e : q + strlen(q), a->values[i], SWEEP_VALUE_SIZE);
            if (!a->values[i][0])
                return spec_fail_line(c, kvals->line,
                                      "key 'values' in [axis]: value %d of %s is empty (values are "
                                      "separated by '%c'%s)",
                                      i + 1, s->params[p].name, sep,
                                      sep == '|' ? ": a vector's values are 'x, y, z | x, y, z'"
                                                 : "");
            for (int j = 0; j < i; j++)
                if (!strcmp(a->values[j], a->values[i]))
                    return spec_fail_line(
                        c, kvals->line,
                        "key 'values' in [axis]: value %d of %s ('%s') repeats value %d", i + 1,
                        s->params[p].name, a->values[i], j + 1);
            snprintf(what, sizeof what, "key 'values' in [axis]: value %d of %s", i + 1,
                     s->params[p].name);
            if (spec_check_scene_value(c, base, k, a->values[i], kvals->line, what)) return -1;
            q = e ? e + 1 : q + strlen(q);
        }
        a->npoints = n;
    } else {
        if (!kfrom)
            return spec_fail_line(c, r->line,
                                  "[axis] %s has no values: give 'values = v1, v2, ...' or a range "
                                  "'from', 'to', 'count'",
                                  s->params[p].name);
        if (!numeric_type(k->type))
            return spec_fail_line(
                c, kfrom->line,
                "key 'from' in [axis]: %s is %s, not a number: list its values with "
                "'values'",
                s->params[p].name, k->expected);
        a->kind = SWEEP_AXIS_RANGE;
        double from, to = 0;
        long long count = 0;
        if (!spec_parse_double(kfrom->value, &from))
            return spec_bad_value(c, kfrom, "axis", "a decimal number (the range's first value)");
        if (!kcount)
            return spec_fail_line(c, r->line,
                                  "[axis] %s: a range needs 'count' (the number of values, "
                                  "'to' included)",
                                  s->params[p].name);
        if (!spec_parse_long(kcount->value, 1, SWEEP_MAX_CASES, &count))
            return spec_bad_value(c, kcount, "axis", "an integer in 1..100000");
        if (count > 1 && !kto)
            return spec_fail_line(c, r->line, "[axis] %s: a range of %lld values needs 'to'",
                                  s->params[p].name, count);
        if (kto && !spec_parse_double(kto->value, &to))
            return spec_bad_value(c, kto, "axis", "a decimal number (the range's last value)");
        if (!kto) to = from;
        if (count > 1 && to == from)
            return spec_fail_line(c, kto->line,
                                  "key 'to' in [axis]: equal to 'from': %lld equal values", count);
        if (kspace) {
            if (spec_ieq(kspace->value, "log"))
                a->log = 1;
            else if (!spec_ieq(kspace->value, "linear"))
                return spec_bad_value(c, kspace, "axis", "linear or log");
        }
        if (a->log && !(from > 0 && to > 0))
            return spec_fail_line(c, kspace->line,
                                  "key 'spacing' in [axis]: log spacing needs 'from' and 'to' > 0 "
                                  "(got %g and %g)",
                                  from, to);
        a->npoints = (int)count;
        a->values = calloc((size_t)count, sizeof *a->values);
        if (!a->values) return spec_fail_line(c, kcount->line, "out of memory");
        for (int i = 0; i < a->npoints; i++) {
            double f = count > 1 ? (double)i / (double)(count - 1) : 0, x;
            if (i == a->npoints - 1 && count > 1)
                x = to;
            else if (a->log)
                x = from * pow(to / from, f);
            else
                x = from + f * (to - from);
            if (k->type == CRANE_KEY_INTEGER) {
                double rx = round(x);
                if (fabs(x - rx) > 1e-9 * fmax(1, fabs(x)))
                    return spec_fail_line(
                        c, kcount->line,
                        "[axis] %s is an integer key: the range %g .. %g in %lld "
                        "values gives %.6g (choose 'count' so that the step is whole, "
                        "or list the values)",
                        s->params[p].name, from, to, count, x);
                if (fabs(rx) > 1e9) return spec_bad_value(c, kfrom, "axis", k->expected);
                snprintf(a->values[i], SWEEP_VALUE_SIZE, "%.0f", rx);
            } else {
                fmt_value(x, a->values[i], SWEEP_VALUE_SIZE);
            }
            for (int j = 0; j < i; j++)
                if (!strcmp(a->values[j], a->values[i]))
                    return spec_fail_line(
                        c, kcount->line,
                        "[axis] %s: the range gives the value %s twice (fewer values, "
                        "or a wider range)",
                        s->params[p].name, a->values[i]);
            raw_kv *at = i == a->npoints - 1 && kto ? kto : kfrom;
            snprintf(what, sizeof what, "key '%s' in [axis]: value %d of the range of %s", at->key,
                     i + 1, s->params[p].name);
            if (spec_check_scene_value(c, base, k, a->values[i], at->line, what)) return -1;
        }
    }
    s->params[p].log = a->log;
    s->naxes++;
    return 0;
}

/* --------------------------------------------------------- Latin hypercube ---- */

/* splitmix64 (Steele, Lea, Flood 2014): a small generator that gives the same numbers on every
 * machine, so that a seed names one sample. */
static uint64_t next_u64(uint64_t *state)
{
    uint64_t z = (*state += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
}

static double next_unit(uint64_t *state) /* in [0, 1) */
{
    return (double)(next_u64(state) >> 11) * (1.0 / 9007199254740992.0);
}

int spec_finish_lhs(parse_ctx *c, raw_section *r, const crane_scene *base)
{
    sweep_spec *s = c->s;
    raw_kv *ks = spec_get(r, "samples"), *kseed = spec_get(r, "seed");
    long long n = 0, seed = 1;
    if (!ks)
        return spec_fail_line(c, r->line,
                              "[lhs] without 'samples': give the number of cases to sample");
    if (!spec_parse_long(ks->value, 1, SWEEP_MAX_CASES, &n))
        return spec_bad_value(c, ks, "lhs", "an integer in 1..100000");
    if (kseed && !spec_parse_long(kseed->value, 0, LLONG_MAX, &seed))
        return spec_bad_value(c, kseed, "lhs", "an integer >= 0");
    if (s->naxes >= SWEEP_MAX_AXES) return spec_fail_line(c, r->line, "too many axes");
    int ax = s->naxes;
    sweep_axis *a = &s->axes[ax];
    memset(a, 0, sizeof *a);
    a->kind = SWEEP_AXIS_LHS;
    a->line = r->line;
    a->npoints = (int)n;
    for (int i = 0; i < r->n; i++) {
        raw_kv *kv = &r->kv[i];
        if (!spec_is_scene_key_name(kv->key)) continue;
        const crane_scene_key *k = spec_scene_key(c, kv->key, kv->line, "[lhs]");
        if (!k) return -1;
        char name[132];
        snprintf(name, sizeof name, "%s.%s", k->section, k->key);
        if (!numeric_type(k->type))
            return spec_fail_line(c, kv->line,
                                  "[lhs] %s is %s: only number and integer keys can be "
                                  "sampled",
                                  name, k->expected);
        /* LO, HI [, log] */
        char parts[3][SWEEP_VALUE_SIZE];
        int np = 0;
        const char *q = kv->value;
        while (np < 3) {
            const char *e = strchr(q, ',');
            spec_trim_copy(q, e ? e : q + strlen(q), parts[np++], SWEEP_VALUE_SIZE);
            if (!e) break;
            q = e + 1;
            if (np == 3) np = 4; /* a fourth part */
        }
        double lo, hi;
        char qv[80];
        spec_quote(kv->value, qv, sizeof qv);
        if (np < 2 || np > 3 || !spec_parse_double(parts[0], &lo) ||
            !spec_parse_double(parts[1], &hi) ||
            (np == 3 && !spec_ieq(parts[2], "log") && !spec_ieq(parts[2], "linear")))
            return spec_fail_line(c, kv->line,
                                  "[lhs] %s: expected 'LO, HI' or 'LO, HI, log' (the interval to "
                                  "sample), got '%s'",
                                  name, qv);
        if (!(hi > lo))
            return spec_fail_line(c, kv->line, "[lhs] %s: expected LO < HI, got '%s'", name, qv);
        int lg = np == 3 && spec_ieq(parts[2], "log");
        if (lg && !(lo > 0))
            return spec_fail_line(c, kv->line, "[lhs] %s: log sampling needs LO > 0, got '%s'",
                                  name, qv);
        char what[300];
        snprintf(what, sizeof what, "[lhs] %s: LO", name);
        if (spec_check_scene_value(c, base, k, parts[0], kv->line, what)) return -1;
        snprintf(what, sizeof what, "[lhs] %s: HI", name);
        if (spec_check_scene_value(c, base, k, parts[1], kv->line, what)) return -1;
        int p = add_param(c, k, ax, kv->line);
        if (p < 0) return -1;
        s->params[p].lo = lo;
        s->params[p].hi = hi;
        s->params[p].log = lg;
        a->param[a->nparams++] = p;
    }
    if (a->nparams == 0)
        return spec_fail_line(c, r->line,
                              "[lhs] samples no key: add the keys as 'SECTION.KEY = LO, HI'");
    a->values = calloc((size_t)n * (size_t)a->nparams, sizeof *a->values);
    int *perm = malloc((size_t)n * sizeof *perm);
    if (!a->values || !perm) {
        free(perm);
        return spec_fail_line(c, r->line, "out of memory");
    }
    uint64_t st = (uint64_t)seed;
    for (int j = 0; j < a->nparams; j++) {
        sweep_param *pp = &s->params[a->param[j]];
        for (int i = 0; i < (int)n; i++)
            perm[i] = i;
        for (int i = (int)n - 1; i > 0; i--) { /* Fisher-Yates */
            int m = (int)(next_unit(&st) * (double)(i + 1));
            if (m > i) m = i;
            int t = perm[i];
            perm[i] = perm[m];
            perm[m] = t;
        }
        for (int i = 0; i < (int)n; i++) {
            double u = ((double)perm[i] + next_unit(&st)) / (double)n, x;
            x = pp->log ? exp(log(pp->lo) + u * (log(pp->hi) - log(pp->lo)))
                        : pp->lo + u * (pp->hi - pp->lo);
            char *v = a->values[(size_t)i * (size_t)a->nparams + (size_t)j];
            if (pp->type == CRANE_KEY_INTEGER)
                snprintf(v, SWEEP_VALUE_SIZE, "%.0f", round(x));
            else
                snprintf(v, SWEEP_VALUE_SIZE, "%.8g", x);
        }
    }
    free(perm);
    s->lhs_samples = (int)n;
    s->seed = (unsigned long long)seed;
    s->naxes++;
    return 0;
}

/* ------------------------------------------------------------------ public ---- */

int sweep_spec_parse(sweep_spec *s, const char *text, const char *file,
                     const char *const *scene_roots, char *err, size_t errsize)
{
    memset(s, 0, sizeof *s);
    snprintf(s->path, sizeof s->path, "%s", file);
    s->seed = 1;
    parse_ctx *c = calloc(1, sizeof *c);
    if (!c) {
        snprintf(err, errsize, "%s: out of memory", file);
        return -1;
    }
    c->s = s;
    c->file = file;
    c->text = text;
    c->len = strlen(text);
    c->cur = -1;
    c->err = err;
    c->errsize = errsize;
    int r = ini_parse_stream(spec_reader, c, handler, c);
    int rc = 0;
    if (c->failed)
        rc = -1;
    else if (r == -2)
        rc = spec_fail_line(c, 0, "out of memory");
    else if (r != 0)
        rc = spec_fail_line(c, r, "syntax error");
    else
        rc = spec_finish(c, scene_roots);
    free(c);
    return rc;
}

int sweep_spec_load(sweep_spec *s, const char *path, const char *const *scene_roots, char *err,
                    size_t errsize)
{
    memset(s, 0, sizeof *s);
    int fd = open(path, O_RDONLY | O_NONBLOCK);
    if (fd < 0) {
        snprintf(err, errsize, "%s: cannot open: %s", path, strerror(errno));
        return -2;
    }
    struct stat st;
    if (fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
        int e = errno;
        close(fd);
        if (!S_ISREG(st.st_mode))
            snprintf(err, errsize, "%s: %s, not a sweep file", path,
                     crane_file_kind((unsigned)st.st_mode));
        else
            snprintf(err, errsize, "%s: cannot open: %s", path, strerror(e));
        return -2;
    }
    if (st.st_size > (off_t)1 << 20) {
        close(fd);
        snprintf(err, errsize, "%s: larger than 1 MB: not a sweep file", path);
        return -2;
    }
    size_t cap = (size_t)st.st_size + 1, len = 0;
    char *buf = malloc(cap + 1);
    if (!buf) {
        close(fd);
        snprintf(err, errsize, "%s: out of memory", path);
        return -2;
    }
    for (;;) {
        ssize_t n = read(fd, buf + len, cap - len);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) {
            int e = errno;
            close(fd);
            free(buf);
            snprintf(err, errsize, "%s: read error: %s", path, strerror(e));
            return -2;
        }
        if (n == 0 || len + (size_t)n >= cap) {
            len += (size_t)n;
            break;
        }
        len += (size_t)n;
    }
    close(fd);
    buf[len] = '\0';
    if (strlen(buf) < len) {
        int line = 1;
        for (size_t i = 0; i < strlen(buf); i++)
            line += buf[i] == '\n';
        free(buf);
        snprintf(err, errsize, "%s:%d: the line contains a NUL character (not a text file?)", path,
                 line);
        return -1;
    }
    int rc = sweep_spec_parse(s, buf, path, scene_roots, err, errsize);
    s->text = buf;
    s->text_len = len;
    return rc;
}

void sweep_spec_free(sweep_spec *s)
{
    for (int a = 0; a < s->naxes && a < SWEEP_MAX_AXES; a++) {
        free(s->axes[a].values);
        s->axes[a].values = NULL;
    }
    /* an axis that failed half-way is not counted in naxes */
    if (s->naxes < SWEEP_MAX_AXES) {
        free(s->axes[s->naxes].values);
        s->axes[s->naxes].values = NULL;
    }
    free(s->text);
    s->text = NULL;
}

/* --------------------------------------------------------------- the cases ---- */

void sweep_case_coords(const sweep_spec *s, long c, int *coord)
{
    for (int a = s->naxes - 1; a >= 0; a--) {
        coord[a] = (int)(c % s->axes[a].npoints);
        c /= s->axes[a].npoints;
    }
}

const char *sweep_case_value(const sweep_spec *s, long c, int p)
{
    int coord[SWEEP_MAX_AXES];
    sweep_case_coords(s, c, coord);
    const sweep_param *pp = &s->params[p];
    const sweep_axis *a = &s->axes[pp->axis];
    int j = 0;
    while (j < a->nparams && a->param[j] != p)
        j++;
    return a->values[(size_t)coord[pp->axis] * (size_t)a->nparams + (size_t)j];
}

int sweep_case_scene(const sweep_spec *s, long c, crane_scene *scene, char *err, size_t errsize)
{
    bg_error e = {0};
    if (crane_scene_load(scene, s->scene_path, &e) != BG_OK) {
        snprintf(err, errsize, "%s", e.message);
        return -1;
    }
    for (int i = 0; i < s->nsets; i++)
        if (crane_scene_set(scene, s->sets[i].section, s->sets[i].key, s->sets[i].value, "[set]",
                            &e) != BG_OK) {
            snprintf(err, errsize, "%s", e.message);
            return -1;
        }
    for (int p = 0; p < s->nparams; p++)
        if (crane_scene_set(scene, s->params[p].section, s->params[p].key,
                            sweep_case_value(s, c, p), "case", &e) != BG_OK) {
            snprintf(err, errsize, "%s", e.message);
            return -1;
        }
    if (crane_scene_check(scene, "case", &e) != BG_OK) {
        snprintf(err, errsize, "%s", e.message);
        return -1;
    }
    return 0;
}

int sweep_case_set_args(const sweep_spec *s, long c, char (*out)[SWEEP_SET_ARG_SIZE])
{
    int n = 0;
    for (int i = 0; i < s->nsets; i++)
        snprintf(out[n++], SWEEP_SET_ARG_SIZE, "%s.%s=%s", s->sets[i].section, s->sets[i].key,
                 s->sets[i].value);
    for (int p = 0; p < s->nparams; p++)
        snprintf(out[n++], SWEEP_SET_ARG_SIZE, "%s.%s=%s", s->params[p].section, s->params[p].key,
                 sweep_case_value(s, c, p));
    return n;
}
