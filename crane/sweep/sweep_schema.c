/* The sweep file's schema (sweep_spec.h for the format, sweep_spec_impl.h for the parts): its
 * sections and their keys, the scene keys' check, the base scene, the [sweep] and [set]
 * sections, and the whole file checked once the parser has recorded it (spec_finish).
 *
 * Every value is checked where its section is finished, against the scene files' own check for
 * scene keys (crane_scene_set on a scratch copy of the base scene, [set] applied), so that a
 * message names the sweep file's line; the axes are finished in sweep_axes.c. A model sweep
 * ([sweep] model) has its base, [set] and quantities checked in sweep_model.c. */
#define _XOPEN_SOURCE 700 /* realpath */
#include <ctype.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "crane_scene.h"
#include "pu_cli.h"
#include "pu_fs.h"
#include "sweep_row.h"
#include "sweep_spec_impl.h"

/* ------------------------------------------------------------ the sections ---- */

const char *const SEC_NAMES[NSEC + 1] = {"sweep", "set", "axis", "lhs", NULL};
const char *const SWEEP_KEYS[] = {"name",         "scene", "time_limit", "report",
                                  "case_figures", "model", "quantities", "t_end",
                                  NULL};
const char *const AXIS_KEYS[] = {"key", "values", "from", "to", "count", "spacing", NULL};
const char *const LHS_KEYS[] = {"samples", "seed", NULL}; /* and SECTION.KEY */

const char *spec_nearest(const char *name, const char *const *cands, int *dist)
{
    const char *best = "";
    int bd = 1 << 30;
    for (int i = 0; cands[i]; i++) {
        int d = pu_cli_edit_distance(name, cands[i]);
        if (d < bd) bd = d, best = cands[i];
    }
    *dist = bd;
    return best;
}

void spec_join(const char *const *names, const char *pre, const char *post, char *buf, size_t size)
{
    size_t len = 0;
    buf[0] = '\0';
    for (int i = 0; names[i] && len < size; i++)
        len +=
            (size_t)snprintf(buf + len, size - len, "%s%s%s%s", i ? ", " : "", pre, names[i], post);
}

int spec_section_kind(const char *name)
{
    for (int k = 0; k < NSEC; k++)
        if (pu_ini_ieq(name, SEC_NAMES[k])) return k;
    return SEC_NONE;
}

/* ---------------------------------------------------------------- the keys ---- */

int spec_is_scene_key_name(const char *name)
{
    return strchr(name, '.') != NULL;
}

raw_kv *spec_get(raw_section *r, const char *key)
{
    for (int i = 0; i < r->n; i++)
        if (pu_ini_ieq(r->kv[i].key, key)) return &r->kv[i];
    return NULL;
}

int spec_bad_value(parse_ctx *c, const raw_kv *kv, const char *sec, const char *expected)
{
    char q[80];
    pu_ini_quote(kv->value, q, sizeof q);
    return spec_fail_line(c, kv->line, "key '%s' in [%s]: expected %s, got '%s'", kv->key, sec,
                          expected, q);
}

/* The scene key "section.key" (any case) -> its table entry; NULL with a message. */
const crane_scene_key *spec_scene_key(parse_ctx *c, const char *name, int line, const char *where)
{
    const char *dot = strchr(name, '.');
    char sec[64] = "", key[64] = "";
    if (dot && dot > name && dot[1] && (size_t)(dot - name) < sizeof sec &&
        strlen(dot + 1) < sizeof key) {
        snprintf(sec, sizeof sec, "%.*s", (int)(dot - name), name);
        snprintf(key, sizeof key, "%s", dot + 1);
        for (int i = 0; i < crane_scene_nkeys(); i++) {
            const crane_scene_key *k = crane_scene_key_at(i);
            if (pu_ini_ieq(k->section, sec) && pu_ini_ieq(k->key, key)) return k;
        }
    }
    int best = -1, bd = 1 << 30;
    for (int i = 0; i < crane_scene_nkeys(); i++) {
        const crane_scene_key *k = crane_scene_key_at(i);
        char full[132];
        snprintf(full, sizeof full, "%s.%s", k->section, k->key);
        int d = pu_cli_edit_distance(name, full);
        if (d < bd) bd = d, best = i;
    }
    const crane_scene_key *b = crane_scene_key_at(best);
    char q[80];
    pu_ini_quote(name, q, sizeof q);
    spec_fail_line(c, line,
                   "%s: unknown scene key '%s'; did you mean '%s.%s'? (scene keys are "
                   "SECTION.KEY as in crane --set, listed in crane/crane_scene.h)",
                   where, q, b ? b->section : "", b ? b->key : "");
    return NULL;
}

/* Checks value for scene key k with the scene files' own check (crane_scene_set on a scratch
 * copy of the base scene); what leads the message ("key 'values' in [axis]: value 3 of ..."). */
int spec_check_scene_value(parse_ctx *c, const crane_scene *base, const crane_scene_key *k,
                           const char *value, int line, const char *what)
{
    crane_scene tmp = *base;
    bg_error err = {0};
    char origin[1200];
    snprintf(origin, sizeof origin, "%s:%d: %s", c->file, line, what);
    if (crane_scene_set(&tmp, k->section, k->key, value, origin, &err) != BG_OK) {
        c->failed = 1;
        snprintf(c->err, c->errsize, "%s", err.message);
        return -1;
    }
    return 0;
}

/* ---------------------------------------------------------- the base scene ---- */

static int regular_file(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 && S_ISREG(st.st_mode);
}

/* The scene file for arg: relative to dir (the sweep file's folder), then a bare name in each
 * scene folder of roots, with or without .ini. 1 with the absolute path, or 0 with what was
 * tried; -1 with tried saying why a candidate that is there cannot be used (a folder, a
 * symbolic link loop, no permission). */
static int resolve_scene(const char *arg, const char *dir, const char *const *roots, char *out,
                         size_t size, char *tried, size_t tsize)
{
    char cand[SWEEP_PATH_SIZE + 16];
    size_t tl = 0;
    tried[0] = '\0';
    const char *suf[2] = {"", ".ini"};
    for (int pass = 0; pass < 2; pass++) {
        int nroots = 1;
        if (pass == 1) {
            if (strchr(arg, '/')) break;
            nroots = 0;
            while (roots && roots[nroots])
                nroots++;
        }
        for (int r = 0; r < nroots; r++)
            for (int f = 0; f < 2; f++) {
                const char *base = pass == 0 ? (arg[0] == '/' ? "" : dir) : roots[r];
                int n =
                    snprintf(cand, sizeof cand, "%s%s%s%s", base, base[0] ? "/" : "", arg, suf[f]);
                if (n < 0 || (size_t)n >= sizeof cand) continue;
                if (regular_file(cand) && realpath(cand, out) && strlen(out) < size) return 1;
                struct stat st;
                const char *kind = "";
                if (stat(cand, &st) != 0 && errno != ENOENT && errno != ENOTDIR) {
                    /* there, but cannot be read: a symbolic link loop, no permission */
                    snprintf(tried, tsize, "%.1500s: %s", cand, strerror(errno));
                    return -1;
                }
                if (lstat(cand, &st) == 0 && !S_ISREG(st.st_mode) && !S_ISLNK(st.st_mode))
                    kind = pu_fs_kind((unsigned)st.st_mode);
                if (tl < tsize) {
                    n = snprintf(tried + tl, tsize - tl, "%s%s%s%s%s", tl ? ", " : "", cand,
                                 kind[0] ? " (" : "", kind, kind[0] ? ")" : "");
                    tl = n < 0 ? tsize : tl + (size_t)n;
                }
            }
    }
    return 0;
}

/* ------------------------------------------------------- [sweep] and [set] ---- */

/* The keys of one kind of sweep given in the other: refused, naming the other's key. */
static int foreign_keys(parse_ctx *c, raw_section *r, int model)
{
    static const char *const crane_only[] = {"scene", "report", "case_figures", NULL},
                             *const model_only[] = {"quantities", "t_end", NULL};
    const char *const *keys = model ? crane_only : model_only;
    for (int i = 0; r && keys[i]; i++) {
        raw_kv *kv = spec_get(r, keys[i]);
        if (!kv) continue;
        if (model)
            return spec_fail_line(c, kv->line,
                                  "key '%s' in [sweep]: a sweep of a model file (key 'model') "
                                  "has no %s%s",
                                  kv->key, kv->key,
                                  strcmp(kv->key, "report")
                                      ? " (bgsim runs a model file; the crane a scene)"
                                      : ": name its quantities with 'quantities = max(COLUMN), "
                                        "...'");
        return spec_fail_line(c, kv->line,
                              "key '%s' in [sweep]: only a sweep of a model file (key 'model') "
                              "has %s%s",
                              kv->key, kv->key,
                              strcmp(kv->key, "t_end")
                                  ? "; a scene's sweep names its quantities with 'report'"
                                  : "; a scene's sweep sets solver.t_end in [set]");
    }
    return 0;
}

/* The base scene ([sweep] scene kv, default paper) resolved and loaded into base. */
static int base_scene(parse_ctx *c, raw_kv *kv, const char *dir, const char *const *roots,
                      crane_scene *base)
{
    sweep_spec *s = c->s;
    char tried[2048];
    snprintf(s->scene_arg, sizeof s->scene_arg, "%s", kv ? kv->value : "paper");
    if (!s->scene_arg[0]) return spec_bad_value(c, kv, "sweep", "a scene file or a scene's name");
    int found = resolve_scene(s->scene_arg, dir, roots, s->scene_path, sizeof s->scene_path, tried,
                              sizeof tried);
    if (found < 0)
        return spec_fail_line(c, kv ? kv->line : 0, "%s '%s': cannot use the scene file: %s",
                              kv ? "key 'scene' in [sweep]" : "the base scene (default)",
                              s->scene_arg, tried);
    if (!found)
        return spec_fail_line(c, kv ? kv->line : 0, "%s '%s': scene file not found (tried %s)",
                              kv ? "key 'scene' in [sweep]" : "the base scene (default)",
                              s->scene_arg, tried);
    bg_error e = {0};
    int nkeys = 0;
    if (crane_scene_load_counted(base, s->scene_path, &nkeys, &e) != BG_OK)
        return spec_fail_line(c, kv ? kv->line : 0, "key 'scene' in [sweep]: the base scene: %s",
                              e.message);
    return 0;
}

static int finish_sweep(parse_ctx *c, raw_section *r, const char *const *roots, crane_scene *base)
{
    sweep_spec *s = c->s;
    raw_kv *kv;
    raw_kv *kmodel = r ? spec_get(r, "model") : NULL;
    if (foreign_keys(c, r, kmodel != NULL)) return -1;
    char dir[SWEEP_PATH_SIZE]; /* the sweep file's folder */
    snprintf(dir, sizeof dir, "%s", c->file);
    char *slash = strrchr(dir, '/');
    if (slash)
        *slash = '\0';
    else
        snprintf(dir, sizeof dir, ".");
    if (r && (kv = spec_get(r, "name")) != NULL) {
        crane_scene tmp;
        crane_scene_default(&tmp);
        bg_error e = {0};
        if (crane_scene_set(&tmp, "scene", "name", kv->value, NULL, &e) != BG_OK)
            return spec_bad_value(c, kv, "sweep",
                                  "a name of 1 to 63 characters from [A-Za-z0-9_.-]");
        snprintf(s->name, sizeof s->name, "%s", tmp.name);
    }
    if (r && (kv = spec_get(r, "time_limit")) != NULL &&
        (!pu_ini_parse_double(kv->value, &s->time_limit) || s->time_limit < 0))
        return spec_bad_value(c, kv, "sweep", "a number >= 0 (s; 0: no limit)");
    if (r && (kv = spec_get(r, "case_figures")) != NULL) {
        static const char *yes[] = {"true", "yes", "on", "1"}, *no[] = {"false", "no", "off", "0"};
        int v = -1;
        for (int i = 0; i < 4; i++) {
            if (pu_ini_ieq(kv->value, yes[i])) v = 1;
            if (pu_ini_ieq(kv->value, no[i])) v = 0;
        }
        if (v < 0)
            return spec_bad_value(c, kv, "sweep", "a boolean (true/false, yes/no, on/off, 1/0)");
        s->case_figures = v;
    }
    if (r && (kv = spec_get(r, "t_end")) != NULL &&
        (!pu_ini_parse_double(kv->value, &s->t_end) || !(s->t_end > 0)))
        return spec_bad_value(c, kv, "sweep", "a number > 0 (s; bgsim --t-end)");
    s->nreport = 0;
    if (kmodel) { /* the model file, its quantities */
        if (spec_model_base(c, kmodel, dir) || spec_model_quantities(c, spec_get(r, "quantities")))
            return -1;
    } else if (r && (kv = spec_get(r, "report")) != NULL) {
        const char *p = kv->value;
        for (int i = 1;; i++) {
            const char *e = strchr(p, ',');
            char name[64];
            pu_ini_trim_copy(p, e ? e : p + strlen(p), name, sizeof name);
            int q = sweep_quantity_index(name);
            if (!name[0])
                return spec_fail_line(c, kv->line,
                                      "key 'report' in [sweep]: quantity %d is empty (expected "
                                      "the names of summary quantities separated by ',', e.g. "
                                      "'theta_end, steps')",
                                      i);
            if (q < 0) {
                const char *names[SWEEP_NQ + 1];
                for (int j = 0; j < SWEEP_NQ; j++)
                    names[j] = sweep_quantities[j].name;
                names[SWEEP_NQ] = NULL;
                int d;
                char all[400];
                spec_join(names, "", "", all, sizeof all);
                return spec_fail_line(c, kv->line,
                                      "key 'report' in [sweep]: quantity %d '%s' is not one of the "
                                      "summary quantities; did you mean '%s'? (quantities: %s)",
                                      i, name, spec_nearest(name, names, &d), all);
            }
            for (int j = 0; j < s->nreport; j++)
                if (s->report[j] == q)
                    return spec_fail_line(c, kv->line, "key 'report' in [sweep]: '%s' named twice",
                                          sweep_quantities[q].name);
            if (s->nreport >= SWEEP_MAX_REPORT)
                return spec_fail_line(c, kv->line, "key 'report' in [sweep]: too many quantities");
            s->report[s->nreport++] = q;
            if (!e) break;
            p = e + 1;
        }
    } else {
        for (int q = 0; q < SWEEP_NQ; q++)
            if (sweep_quantities[q].is_default) s->report[s->nreport++] = q;
    }
    if (!kmodel && base_scene(c, r ? spec_get(r, "scene") : NULL, dir, roots, base)) return -1;
    if (!s->name[0]) { /* the sweep file's name without .ini */
        const char *b = strrchr(c->file, '/');
        b = b ? b + 1 : c->file;
        size_t n = 0;
        char stem[64];
        for (; b[n] && n < sizeof stem - 1; n++) {
            int ch = (unsigned char)b[n];
            stem[n] = (char)(isalnum(ch) || ch == '_' || ch == '.' || ch == '-' ? ch : '_');
        }
        stem[n] = '\0';
        if (n > 4 && !strcmp(stem + n - 4, ".ini")) stem[n - 4] = '\0';
        snprintf(s->name, sizeof s->name, "%s", stem[0] && strcmp(stem, ".") ? stem : "sweep");
    }
    return 0;
}

static int finish_set(parse_ctx *c, raw_section *r, crane_scene *base)
{
    sweep_spec *s = c->s;
    if (s->is_model) return spec_model_set(c, r);
    for (int i = 0; i < r->n; i++) {
        raw_kv *kv = &r->kv[i];
        const crane_scene_key *k = spec_scene_key(c, kv->key, kv->line, "[set]");
        if (!k) return -1;
        for (int j = 0; j < s->nsets; j++)
            if (!strcmp(s->sets[j].section, k->section) && !strcmp(s->sets[j].key, k->key))
                return spec_fail_line(c, kv->line, "[set]: %s.%s given twice (first on line %d)",
                                      k->section, k->key, s->sets[j].line);
        char what[200];
        snprintf(what, sizeof what, "[set] %s.%s", k->section, k->key);
        if (spec_check_scene_value(c, base, k, kv->value, kv->line, what)) return -1;
        bg_error e = {0};
        crane_scene_set(base, k->section, k->key, kv->value, NULL, &e);
        sweep_set *st = &s->sets[s->nsets++];
        snprintf(st->section, sizeof st->section, "%s", k->section);
        snprintf(st->key, sizeof st->key, "%s", k->key);
        snprintf(st->value, sizeof st->value, "%s", kv->value);
        st->line = kv->line;
    }
    return 0;
}

/* ---------------------------------------------------------------- the file ---- */

int spec_finish(parse_ctx *c, const char *const *roots)
{
    sweep_spec *s = c->s;
    static const crane_scene zero;
    crane_scene base = zero; /* a model sweep has none */
    raw_section *sw = NULL, *set = NULL;
    for (int i = 0; i < c->nraw; i++) {
        if (c->raw[i].kind == SEC_SWEEP) sw = &c->raw[i];
        if (c->raw[i].kind == SEC_SET) set = &c->raw[i];
    }
    if (finish_sweep(c, sw, roots, &base)) return -1;
    if (set && finish_set(c, set, &base)) return -1;
    for (int i = 0; i < c->nraw; i++)
        if (c->raw[i].kind == SEC_AXIS && spec_finish_axis(c, &c->raw[i], &base)) return -1;
    for (int i = 0; i < c->nraw; i++)
        if (c->raw[i].kind == SEC_LHS && spec_finish_lhs(c, &c->raw[i], &base)) return -1;
    if (s->naxes == 0)
        return spec_fail_line(c, 0,
                              "nothing to sweep: add an [axis] (key and values, or a range) or "
                              "an [lhs] sample");
    if (s->nsets + s->nparams > SWEEP_MAX_SETS)
        return spec_fail_line(c, 0,
                              "[set] and the swept keys are %d keys, more than the %s's %d "
                              "(--set)",
                              s->nsets + s->nparams, sweep_program(s), SWEEP_MAX_SETS);
    double n = 1;
    for (int a = 0; a < s->naxes; a++)
        n *= s->axes[a].npoints;
    if (n > SWEEP_MAX_CASES)
        return spec_fail_line(c, s->axes[s->naxes - 1].line,
                              "the axes make %.0f cases, more than %ld", n, SWEEP_MAX_CASES);
    s->ncases = (long)n;
    /* every sampled value against its key's range (the interval's ends were checked) */
    for (int a = 0; a < s->naxes; a++) {
        sweep_axis *ax = &s->axes[a];
        if (ax->kind != SWEEP_AXIS_LHS || s->is_model) continue; /* a model's: the ends */
        for (int i = 0; i < ax->npoints; i++)
            for (int j = 0; j < ax->nparams; j++) {
                sweep_param *pp = &s->params[ax->param[j]];
                const crane_scene_key *k = NULL;
                for (int q = 0; q < crane_scene_nkeys() && !k; q++) {
                    const crane_scene_key *t = crane_scene_key_at(q);
                    if (!strcmp(t->section, pp->section) && !strcmp(t->key, pp->key)) k = t;
                }
                char what[300];
                snprintf(what, sizeof what, "[lhs] %s: sample %d", pp->name, i + 1);
                if (!k || spec_check_scene_value(
                              c, &base, k, ax->values[(size_t)i * (size_t)ax->nparams + (size_t)j],
                              pp->line, what))
                    return -1;
            }
    }
    return 0;
}
