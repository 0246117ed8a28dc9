/* The axes of a sweep file (sweep_spec.h for the format, sweep_spec_impl.h for the parts): an
 * [axis] section's values (a list, or a range generated here), the [lhs] section's
 * Latin-hypercube sample, and the cases as the product of the axes.
 *
 * Every generated value is kept as the text the crane gets (--set) and sweep.csv shows, and is
 * checked against its key's range when generated (a model sweep's: by loading the model with it,
 * sweep_model.c; its keys are parameters' paths, taken as numbers). Case k's point on each axis is k written in
 * the mixed radix of the axes' lengths, the last axis varying fastest. */
#include <limits.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "crane_scene.h"
#include "sweep_spec_impl.h"

/* ---------------------------------------------------------- the swept keys ---- */

/* A swept key: a scene key (k), or a model's parameter (k NULL, section "", key its path). */
typedef struct swept_key {
    const crane_scene_key *k;
    char section[64], key[64];
    int type;             /* crane_key_type (a model's: a number) */
    const char *expected; /* what its values are */
} swept_key;

/* The key called name ([axis] key, an [lhs] line): 0 with *out, or -1 with the error recorded. */
static int lookup_key(parse_ctx *c, const char *name, int line, const char *where, swept_key *out)
{
    memset(out, 0, sizeof *out);
    if (c->s->is_model) {
        if (spec_model_path(c, name, line, where)) return -1;
        snprintf(out->key, sizeof out->key, "%s", name);
        out->type = CRANE_KEY_NUMBER;
        out->expected = "an expression";
        return 0;
    }
    const crane_scene_key *k = spec_scene_key(c, name, line, where);
    if (!k) return -1;
    out->k = k;
    snprintf(out->section, sizeof out->section, "%s", k->section);
    snprintf(out->key, sizeof out->key, "%s", k->key);
    out->type = (int)k->type;
    out->expected = k->expected;
    return 0;
}

/* A value of key k: the scene files' check, or the model loaded with it. */
static int check_value(parse_ctx *c, const crane_scene *base, const swept_key *k,
                       const char *value, int line, const char *what)
{
    if (!k->k) return spec_check_model_value(c, k->key, value, line, what);
    return spec_check_scene_value(c, base, k->k, value, line, what);
}

static int add_param(parse_ctx *c, const swept_key *k, int axis, int line)
{
    sweep_spec *s = c->s;
    for (int i = 0; i < s->nparams; i++)
        if (!strcmp(s->params[i].section, k->section) && !strcmp(s->params[i].key, k->key))
            return spec_fail_line(c, line,
                                  "%s%s%s is swept twice (also on line %d): a key belongs to "
                                  "one axis",
                                  k->section, k->section[0] ? "." : "", k->key,
                                  s->params[i].line);
    for (int i = 0; i < s->nsets; i++)
        if (!strcmp(s->sets[i].section, k->section) && !strcmp(s->sets[i].key, k->key))
            return spec_fail_line(c, line,
                                  "%s%s%s is swept here and set in [set] (line %d): remove one",
                                  k->section, k->section[0] ? "." : "", k->key, s->sets[i].line);
    if (s->nparams >= SWEEP_MAX_PARAMS)
        return spec_fail_line(c, line, "too many swept keys (at most %d)", SWEEP_MAX_PARAMS);
    sweep_param *p = &s->params[s->nparams];
    memset(p, 0, sizeof *p);
    snprintf(p->section, sizeof p->section, "%s", k->section);
    snprintf(p->key, sizeof p->key, "%s", k->key);
    if (k->section[0])
        snprintf(p->name, sizeof p->name, "%s.%s", k->section, k->key);
    else
        snprintf(p->name, sizeof p->name, "%s", k->key);
    p->type = k->type;
    p->axis = axis;
    p->line = line;
    return s->nparams++;
}

/* The axes before this one with npoints more: at most SWEEP_MAX_CASES cases, checked before the
 * values are made and checked one by one (16 axes of 100000 values would take that long only to
 * be refused). 0, or -1 with the error recorded at line. */
static int within_cases(parse_ctx *c, long long npoints, int line)
{
    double n = (double)npoints;
    for (int a = 0; a < c->s->naxes; a++)
        n *= c->s->axes[a].npoints;
    if (n > SWEEP_MAX_CASES)
        return spec_fail_line(c, line, "the axes make %.0f cases, more than %ld", n,
                              SWEEP_MAX_CASES);
    return 0;
}

/* -------------------------------------------------------- lists and ranges ---- */

/* A generated value's text, 12 significant digits (a range's 0.30000000000000004 is written
 * 0.3): the text is the value the crane gets and sweep.csv shows. */
static void fmt_value(double x, char *buf, size_t size)
{
    snprintf(buf, size, "%.12g", x);
}

/* The first repeat among the n texts v[0..n-1]: the smallest i that equals an earlier v[j] (the
 * first such j in *j); -1 if every text differs, -2 out of memory. Sorted indices (by text, then
 * index) put equal texts side by side: O(n log n) comparisons, not the n^2 / 2 of comparing each
 * with every earlier one (100000 values: 1.7e6 against 5e9). */
static int by_text(const void *a, const void *b)
{
    const char *sa = *(const char *const *)a, *sb = *(const char *const *)b;
    int d = strcmp(sa, sb);
    return d ? d : (sa > sb) - (sa < sb); /* the texts lie in one array: address = index order */
}

int spec_first_repeat(const char (*v)[SWEEP_VALUE_SIZE], int n, int *j)
{
    if (n < 2) return -1;
    const char **ptr = malloc((size_t)n * sizeof *ptr);
    if (!ptr) return -2;
    for (int i = 0; i < n; i++)
        ptr[i] = v[i];
    qsort(ptr, (size_t)n, sizeof *ptr, by_text);
    int best = -1;
    for (int k = 1; k < n; k++) { /* in a run of equal texts, its first two: the first repeat */
        if (strcmp(ptr[k], ptr[k - 1]) || (k >= 2 && !strcmp(ptr[k - 1], ptr[k - 2]))) continue;
        int i = (int)((ptr[k] - v[0]) / SWEEP_VALUE_SIZE);
        if (best < 0 || i < best) {
            best = i;
            *j = (int)((ptr[k - 1] - v[0]) / SWEEP_VALUE_SIZE);
        }
    }
    free(ptr);
    return best;
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
    swept_key key, *k = &key;
    if (lookup_key(c, kkey->value, kkey->line, "key 'key' in [axis]", k)) return -1;
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
        if (within_cases(c, n, kvals->line)) return -1;
        a->values = calloc((size_t)n, sizeof *a->values);
        if (!a->values) return spec_fail_line(c, kvals->line, "out of memory");
        const char *q = kvals->value;
        for (int i = 0; i < n; i++) {
            const char *e = strchr(q, sep);
            pu_ini_trim_copy(q, e ? e : q + strlen(q), a->values[i], SWEEP_VALUE_SIZE);
            q = e ? e + 1 : q + strlen(q);
        }
        /* a number's value, not its text, repeats: "1" and "1.0" (a list is short: a copy) */
        char(*canon)[SWEEP_VALUE_SIZE] = calloc((size_t)n, sizeof *canon);
        if (!canon) return spec_fail_line(c, kvals->line, "out of memory");
        for (int i = 0; i < n; i++) {
            double x;
            if (numeric_type(k->type) && pu_ini_parse_double(a->values[i], &x))
                snprintf(canon[i], SWEEP_VALUE_SIZE, "%.17g", x == 0 ? 0.0 : x); /* -0 = 0 */
            else
                memcpy(canon[i], a->values[i], SWEEP_VALUE_SIZE);
        }
        int rj = 0, ri = spec_first_repeat((const char(*)[SWEEP_VALUE_SIZE])canon, n, &rj);
        free(canon);
        if (ri == -2) return spec_fail_line(c, kvals->line, "out of memory");
        for (int i = 0; i < n; i++) {
            if (!a->values[i][0])
                return spec_fail_line(c, kvals->line,
                                      "key 'values' in [axis]: value %d of %s is empty (values are "
                                      "separated by '%c'%s)",
                                      i + 1, s->params[p].name, sep,
                                      sep == '|' ? ": a vector's values are 'x, y, z | x, y, z'"
                                                 : "");
            if (i == ri)
                return spec_fail_line(
                    c, kvals->line,
                    "key 'values' in [axis]: value %d of %s ('%s') repeats value %d ('%s')", i + 1,
                    s->params[p].name, a->values[i], rj + 1, a->values[rj]);
            snprintf(what, sizeof what, "key 'values' in [axis]: value %d of %s", i + 1,
                     s->params[p].name);
            if (check_value(c, base, k, a->values[i], kvals->line, what)) return -1;
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
        if (!pu_ini_parse_double(kfrom->value, &from))
            return spec_bad_value(c, kfrom, "axis", "a decimal number (the range's first value)");
        if (!kcount)
            return spec_fail_line(c, r->line,
                                  "[axis] %s: a range needs 'count' (the number of values, "
                                  "'to' included)",
                                  s->params[p].name);
        if (!pu_ini_parse_llong(kcount->value, 1, SWEEP_MAX_CASES, &count))
            return spec_bad_value(c, kcount, "axis", "an integer in 1..100000");
        if (count > 1 && !kto)
            return spec_fail_line(c, r->line, "[axis] %s: a range of %lld values needs 'to'",
                                  s->params[p].name, count);
        if (kto && !pu_ini_parse_double(kto->value, &to))
            return spec_bad_value(c, kto, "axis", "a decimal number (the range's last value)");
        if (!kto) to = from;
        if (count > 1 && to == from)
            return spec_fail_line(c, kto->line,
                                  "key 'to' in [axis]: equal to 'from': %lld equal values", count);
        if (kspace) {
            if (pu_ini_ieq(kspace->value, "log"))
                a->log = 1;
            else if (!pu_ini_ieq(kspace->value, "linear"))
                return spec_bad_value(c, kspace, "axis", "linear or log");
        }
        if (a->log && !(from > 0 && to > 0))
            return spec_fail_line(c, kspace->line,
                                  "key 'spacing' in [axis]: log spacing needs 'from' and 'to' > 0 "
                                  "(got %g and %g)",
                                  from, to);
        if (within_cases(c, count, kcount->line)) return -1;
        a->npoints = (int)count;
        a->values = calloc((size_t)count, sizeof *a->values);
        if (!a->values) return spec_fail_line(c, kcount->line, "out of memory");
        double *xs = malloc((size_t)count * sizeof *xs);
        if (!xs) return spec_fail_line(c, kcount->line, "out of memory");
        for (int i = 0; i < a->npoints; i++) { /* the texts, then the checks in order */
            double f = count > 1 ? (double)i / (double)(count - 1) : 0, x;
            /* the ends' difference or ratio may overflow (-1e308 .. 1e308, 1e-300 .. 1e300):
             * then the weighted mean of the ends (of their logarithms), which stays finite */
            if (i == a->npoints - 1 && count > 1)
                x = to;
            else if (a->log)
                x = isfinite(to / from) && to / from > 0 ? from * pow(to / from, f)
                                                         : exp((1 - f) * log(from) + f * log(to));
            else
                x = isfinite(to - from) ? from + f * (to - from) : (1 - f) * from + f * to;
            xs[i] = x;
            if (k->type == CRANE_KEY_INTEGER)
                snprintf(a->values[i], SWEEP_VALUE_SIZE, "%.0f", fabs(x) < 1e15 ? round(x) : 0.0);
            else
                fmt_value(x, a->values[i], SWEEP_VALUE_SIZE);
        }
        int rj = 0,
            ri = spec_first_repeat((const char(*)[SWEEP_VALUE_SIZE])a->values, a->npoints, &rj);
        for (int i = 0; i < a->npoints; i++) {
            double x = xs[i];
            if (k->type == CRANE_KEY_INTEGER) {
                double rx = round(x);
                if (!(fabs(x - rx) <= 1e-9 * fmax(1, fabs(x)))) {
                    free(xs);
                    return spec_fail_line(
                        c, kcount->line,
                        "[axis] %s is an integer key: the range %g .. %g in %lld "
                        "values gives %.6g (choose 'count' so that the step is whole, "
                        "or list the values)",
                        s->params[p].name, from, to, count, x);
                }
                if (fabs(rx) > 1e9) {
                    free(xs);
                    return spec_bad_value(c, kfrom, "axis", k->expected);
                }
            }
            if (i == ri || ri == -2) {
                free(xs);
                if (ri == -2) return spec_fail_line(c, kcount->line, "out of memory");
                return spec_fail_line(c, kcount->line,
                                      "[axis] %s: the range gives the value %s twice (values %d "
                                      "and %d; fewer values, or a wider range)",
                                      s->params[p].name, a->values[i], rj + 1, i + 1);
            }
            raw_kv *at = i == a->npoints - 1 && kto ? kto : kfrom;
            snprintf(what, sizeof what, "key '%s' in [axis]: value %d of the range of %s", at->key,
                     i + 1, s->params[p].name);
            if (check_value(c, base, k, a->values[i], at->line, what)) {
                free(xs);
                return -1;
            }
        }
        free(xs);
    }
    s->params[p].log = a->log;
    if (s->is_model) /* a model's value is an expression: drawn as a number if each is one */
        for (int i = 0; i < a->npoints; i++) {
            double x;
            if (!pu_ini_parse_double(a->values[i], &x)) s->params[p].type = CRANE_KEY_NAME;
        }
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
    if (!pu_ini_parse_llong(ks->value, 1, SWEEP_MAX_CASES, &n))
        return spec_bad_value(c, ks, "lhs", "an integer in 1..100000");
    if (kseed && !pu_ini_parse_llong(kseed->value, 0, LLONG_MAX, &seed))
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
        int own = 0;
        for (int j = 0; LHS_KEYS[j]; j++)
            own |= pu_ini_ieq(kv->key, LHS_KEYS[j]);
        if (own) continue;
        if (!s->is_model && !spec_is_scene_key_name(kv->key)) { /* as the parser said before */
            int d;
            char all[160];
            const char *near = spec_nearest(kv->key, LHS_KEYS, &d);
            spec_join(LHS_KEYS, "", "", all, sizeof all);
            return spec_fail_line(
                c, kv->line,
                "unknown key '%s' in [lhs]; did you mean '%s'? (keys of [lhs]: %s, and "
                "the sampled scene keys as SECTION.KEY = LO, HI)",
                kv->key, near, all);
        }
        swept_key key, *k = &key;
        if (lookup_key(c, kv->key, kv->line, "[lhs]", k)) return -1;
        char name[160];
        snprintf(name, sizeof name, "%.63s%s%.63s", k->section, k->section[0] ? "." : "", k->key);
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
            pu_ini_trim_copy(q, e ? e : q + strlen(q), parts[np++], SWEEP_VALUE_SIZE);
            if (!e) break;
            q = e + 1;
            if (np == 3) np = 4; /* a fourth part */
        }
        double lo, hi;
        char qv[80];
        pu_ini_quote(kv->value, qv, sizeof qv);
        if (np < 2 || np > 3 || !pu_ini_parse_double(parts[0], &lo) ||
            !pu_ini_parse_double(parts[1], &hi) ||
            (np == 3 && !pu_ini_ieq(parts[2], "log") && !pu_ini_ieq(parts[2], "linear")))
            return spec_fail_line(c, kv->line,
                                  "[lhs] %s: expected 'LO, HI' or 'LO, HI, log' (the interval to "
                                  "sample), got '%s'",
                                  name, qv);
        if (!(hi > lo))
            return spec_fail_line(c, kv->line, "[lhs] %s: expected LO < HI, got '%s'", name, qv);
        int lg = np == 3 && pu_ini_ieq(parts[2], "log");
        if (lg && !(lo > 0))
            return spec_fail_line(c, kv->line, "[lhs] %s: log sampling needs LO > 0, got '%s'",
                                  name, qv);
        char what[300];
        snprintf(what, sizeof what, "[lhs] %s: LO", name);
        if (check_value(c, base, k, parts[0], kv->line, what)) return -1;
        snprintf(what, sizeof what, "[lhs] %s: HI", name);
        if (check_value(c, base, k, parts[1], kv->line, what)) return -1;
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
    for (int i = 0; i < s->nsets; i++) /* a model's: section "" */
        snprintf(out[n++], SWEEP_SET_ARG_SIZE, "%s%s%s=%s", s->sets[i].section,
                 s->sets[i].section[0] ? "." : "", s->sets[i].key, s->sets[i].value);
    for (int p = 0; p < s->nparams; p++)
        snprintf(out[n++], SWEEP_SET_ARG_SIZE, "%s%s%s=%s", s->params[p].section,
                 s->params[p].section[0] ? "." : "", s->params[p].key, sweep_case_value(s, c, p));
    return n;
}
