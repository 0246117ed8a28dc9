/* A model sweep (sweep_spec.h: [sweep] model = FILE): its cases are runs of bgsim on a model file
 * (docs/model-format.md) with the swept parameters replaced (bgsim --set PATH=VALUE).
 *
 * The checks are the model reader's own: the model is loaded (mdl_load) with the replacements a
 * case would get, so that a name the model does not have or a value out of its parameter's
 * range is refused when the sweep file is read (--list included), with the reader's
 * "FILE:LINE:COL: path: ..." message behind the sweep file's line and the axis's name. Each
 * [set] line is checked with the lines before it, each axis value with every [set] line (one
 * load per value, not per case: the values of different axes are not checked together; a
 * Latin-hypercube key is checked at both ends of its interval).
 *
 * The summary quantities are FUNC(COLUMN) or FUNC(abs(COLUMN)) of the case's results.csv, the
 * columns checked against the model's outputs (and t) when the file is read:
 *   max, min   the largest, smallest value of the column
 *   end        its value at the last row (t_end)
 *   mean       its time average over the run, the trapezoidal rule on the rows:
 *              int x dt / (t_last - t_first) (the value itself for one row)
 *   rms        the root of the time average of its square, the same rule
 *   maxabs     max(abs(COLUMN))
 * A value that is not a number in the rows used leaves the quantity empty (NaN), as does a case
 * that did not complete. */
#define _XOPEN_SOURCE 700 /* realpath */
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "mdl_model.h"
#include "pu_fs.h"
#include "sweep_engine.h" /* sweep_signal_count */
#include "sweep_row.h"
#include "sweep_spec_impl.h"

const char *sweep_program(const sweep_spec *s)
{
    return s->is_model ? "bgsim" : "crane";
}

const char *sweep_log_name(const sweep_spec *s)
{
    return s->is_model ? "bgsim.log" : "crane.log";
}

/* --------------------------------------------------------- the checks ---- */

/* Loads the model with [set]'s first nsets lines and, when path is given, path = value. 0, or
 * -1 with the reader's message in err. */
static int load_with(const parse_ctx *c, int nsets, const char *path, const char *value,
                     char *err, size_t errsize)
{
    const sweep_spec *s = c->s;
    mdl_set sets[SWEEP_MAX_SETS + 1];
    int n = 0;
    for (int i = 0; i < nsets && i < s->nsets; i++)
        sets[n].path = s->sets[i].key, sets[n++].value = s->sets[i].value;
    if (path) sets[n].path = path, sets[n++].value = value;
    bg_error e = {0};
    mdl_model *mm = mdl_load(s->scene_path, sets, n, &e);
    if (!mm) {
        snprintf(err, errsize, "%s", e.message);
        return -1;
    }
    mdl_free(&mm);
    return 0;
}

int spec_check_model_value(parse_ctx *c, const char *path, const char *value, int line,
                           const char *what)
{
    char err[BG_MESSAGE_SIZE];
    if (load_with(c, c->s->nsets, path, value, err, sizeof err) == 0) return 0;
    return spec_fail_line(c, line, "%s: %s", what, err);
}

int spec_model_path(parse_ctx *c, const char *name, int line, const char *where)
{
    size_t n = strlen(name);
    if (n == 0 || n >= 64)
        return spec_fail_line(c, line, "%s: a model parameter's path of 1 to 63 characters, got "
                                       "'%s'",
                              where, name);
    for (size_t i = 0; i < n; i++) {
        int ch = (unsigned char)name[i];
        if (!isalnum(ch) && !strchr("_.[]", ch))
            return spec_fail_line(c, line,
                                  "%s: '%s' is not a parameter's path (PARAM or PATH.PARAM, as "
                                  "bgsim --set takes them)",
                                  where, name);
    }
    return 0;
}

/* The model file: relative to dir (the sweep file's folder) unless absolute; loaded as it is
 * (its outputs kept for the quantities). 0, or -1 with the error recorded. */
int spec_model_base(parse_ctx *c, const raw_kv *kv, const char *dir)
{
    sweep_spec *s = c->s;
    char cand[SWEEP_PATH_SIZE + 8];
    s->is_model = 1;
    snprintf(s->scene_arg, sizeof s->scene_arg, "%s", kv->value);
    if (!kv->value[0]) return spec_bad_value(c, kv, "sweep", "a model file");
    int n = snprintf(cand, sizeof cand, "%s%s%s", kv->value[0] == '/' ? "" : dir,
                     kv->value[0] == '/' ? "" : "/", kv->value);
    struct stat st;
    if (n < 0 || (size_t)n >= sizeof cand)
        return spec_fail_line(c, kv->line, "key 'model' in [sweep]: the name is too long");
    if (stat(cand, &st) != 0 && errno != ENOENT)
        return spec_fail_line(c, kv->line, "key 'model' in [sweep]: model file '%s': %s", cand,
                              strerror(errno));
    if (stat(cand, &st) == 0 && !S_ISREG(st.st_mode))
        return spec_fail_line(c, kv->line, "key 'model' in [sweep]: model file '%s' is %s", cand,
                              pu_fs_kind((unsigned)st.st_mode));
    if (stat(cand, &st) != 0 || !realpath(cand, s->scene_path))
        return spec_fail_line(c, kv->line, "key 'model' in [sweep]: model file '%s' not found",
                              cand);
    bg_error e = {0};
    mdl_model *mm = mdl_load(s->scene_path, NULL, 0, &e);
    if (!mm)
        return spec_fail_line(c, kv->line, "key 'model' in [sweep]: the model: %s", e.message);
    int no = mdl_noutputs(mm);
    c->outputs = calloc((size_t)no + 1, sizeof *c->outputs);
    if (!c->outputs) {
        mdl_free(&mm);
        return spec_fail_line(c, kv->line, "out of memory");
    }
    snprintf(c->outputs[0], sizeof c->outputs[0], "t");
    for (int i = 0; i < no; i++)
        snprintf(c->outputs[i + 1], sizeof c->outputs[0], "%s", mdl_output_name(mm, i));
    c->noutputs = no + 1;
    mdl_free(&mm);
    return 0;
}

int spec_model_set(parse_ctx *c, raw_section *r)
{
    sweep_spec *s = c->s;
    for (int i = 0; i < r->n; i++) {
        raw_kv *kv = &r->kv[i];
        if (spec_model_path(c, kv->key, kv->line, "[set]")) return -1;
        for (int j = 0; j < s->nsets; j++)
            if (!strcmp(s->sets[j].key, kv->key))
                return spec_fail_line(c, kv->line, "[set]: %s given twice (first on line %d)",
                                      kv->key, s->sets[j].line);
        if (s->nsets >= SWEEP_MAX_SETS)
            return spec_fail_line(c, kv->line, "[set]: too many keys (at most %d)",
                                  SWEEP_MAX_SETS);
        char err[BG_MESSAGE_SIZE];
        if (load_with(c, s->nsets, kv->key, kv->value, err, sizeof err))
            return spec_fail_line(c, kv->line, "[set] %s: %s", kv->key, err);
        sweep_set *st = &s->sets[s->nsets++];
        st->section[0] = '\0';
        snprintf(st->key, sizeof st->key, "%s", kv->key);
        snprintf(st->value, sizeof st->value, "%s", kv->value);
        st->line = kv->line;
    }
    return 0;
}

/* ----------------------------------------------------- the quantities ---- */

static const char *const MFUNC_NAMES[] = {"max", "min", "end", "mean", "rms", "maxabs", NULL};

/* "max(abs(z))" -> "max_abs_z": letters, digits, '_', '-' and '.' kept, runs of others one '_'. */
static void make_stem(const char *name, char *stem, size_t size)
{
    size_t n = 0;
    for (const char *p = name; *p && n + 1 < size; p++) {
        int ch = (unsigned char)*p;
        if (isalnum(ch) || ch == '_' || ch == '-' || ch == '.')
            stem[n++] = (char)ch;
        else if (n && stem[n - 1] != '_')
            stem[n++] = '_';
    }
    while (n && stem[n - 1] == '_')
        n--;
    stem[n] = '\0';
}

/* Removes the spaces of text (in place). */
static void squeeze(char *text)
{
    char *w = text;
    for (char *p = text; *p; p++)
        if (!isspace((unsigned char)*p)) *w++ = *p;
    *w = '\0';
}

/* One item of the list: steps, cpu_s, wall_s, or FUNC(COL), FUNC(abs(COL)). */
static int add_quantity(parse_ctx *c, const raw_kv *kv, int item, const char *text)
{
    sweep_spec *s = c->s;
    char t[SWEEP_VALUE_SIZE], all[400];
    snprintf(t, sizeof t, "%s", text);
    squeeze(t);
    int q = -1;
    if (!strcmp(t, "steps")) q = SQ_STEPS;
    if (!strcmp(t, "cpu_s")) q = SQ_CPU_S;
    if (!strcmp(t, "wall_s")) q = SQ_WALL_S;
    if (q < 0) {
        char *open = strchr(t, '('), *close = strrchr(t, ')');
        if (!open || !close || close < open || close[1])
            return spec_fail_line(c, kv->line,
                                  "key 'quantities' in [sweep]: quantity %d '%s': expected "
                                  "FUNC(COLUMN) or FUNC(abs(COLUMN)) with FUNC one of max, min, "
                                  "end, mean, rms, maxabs; or steps, cpu_s, wall_s",
                                  item, t);
        *open = '\0';
        *close = '\0';
        int f = -1, d;
        for (int i = 0; MFUNC_NAMES[i]; i++)
            if (!strcmp(t, MFUNC_NAMES[i])) f = i;
        if (f < 0)
            return spec_fail_line(c, kv->line,
                                  "key 'quantities' in [sweep]: quantity %d: unknown function "
                                  "'%s'; did you mean '%s'? (max, min, end, mean, rms, maxabs)",
                                  item, t, spec_nearest(t, MFUNC_NAMES, &d));
        char *col = open + 1;
        int absval = 0;
        size_t cl = strlen(col);
        if (!strncmp(col, "abs(", 4) && cl > 5 && col[cl - 1] == ')') {
            absval = 1;
            col[cl - 1] = '\0';
            col += 4;
        }
        if (f == SWEEP_MF_MAXABS) absval = 0; /* maxabs(x) is max(abs(x)) already */
        int found = 0;
        for (int i = 0; i < c->noutputs && !found; i++)
            found = !strcmp(c->outputs[i], col);
        if (!found) {
            const char *names[SWEEP_MAX_REPORT * 4 + 2];
            int nn = 0;
            for (int i = 0; i < c->noutputs && nn < (int)(sizeof names / sizeof *names) - 1; i++)
                names[nn++] = c->outputs[i];
            names[nn] = NULL;
            spec_join(names, "", "", all, sizeof all);
            return spec_fail_line(c, kv->line,
                                  "key 'quantities' in [sweep]: quantity %d: the model has no "
                                  "output '%s'; did you mean '%s'? (the columns of results.csv: "
                                  "%s)",
                                  item, col, spec_nearest(col, names, &d), all);
        }
        if (s->nmq >= SWEEP_MAX_REPORT)
            return spec_fail_line(c, kv->line, "key 'quantities' in [sweep]: too many quantities");
        sweep_mquantity *m = &s->mq[s->nmq];
        m->func = f;
        m->absval = absval;
        snprintf(m->column, sizeof m->column, "%s", col);
        snprintf(m->name, sizeof m->name, "%s(%s%s%s)", MFUNC_NAMES[f], absval ? "abs(" : "", col,
                 absval ? ")" : "");
        make_stem(m->name, m->stem, sizeof m->stem);
        q = SWEEP_NQ + s->nmq;
        for (int j = 0; j < s->nreport; j++)
            if (s->report[j] >= SWEEP_NQ && !strcmp(s->mq[s->report[j] - SWEEP_NQ].name, m->name))
                return spec_fail_line(c, kv->line, "key 'quantities' in [sweep]: '%s' named twice",
                                      m->name);
        s->nmq++;
    }
    for (int j = 0; j < s->nreport; j++)
        if (s->report[j] == q && q < SWEEP_NQ)
            return spec_fail_line(c, kv->line, "key 'quantities' in [sweep]: '%s' named twice", t);
    if (s->nreport >= SWEEP_MAX_REPORT)
        return spec_fail_line(c, kv->line, "key 'quantities' in [sweep]: too many quantities");
    s->report[s->nreport++] = q;
    return 0;
}

int spec_model_quantities(parse_ctx *c, const raw_kv *kv)
{
    sweep_spec *s = c->s;
    s->nreport = 0;
    s->nmq = 0;
    if (!kv) { /* end(C) of every output (as many as fit), steps, cpu_s */
        raw_kv dflt = {"quantities", "", 0};
        for (int i = 1; i < c->noutputs && s->nreport < SWEEP_MAX_REPORT - 2; i++) {
            char item[SWEEP_VALUE_SIZE];
            snprintf(item, sizeof item, "end(%.60s)", c->outputs[i]);
            if (add_quantity(c, &dflt, i, item)) return -1;
        }
        s->report[s->nreport++] = SQ_STEPS;
        s->report[s->nreport++] = SQ_CPU_S;
        return 0;
    }
    /* the items split at the commas outside parentheses */
    const char *p = kv->value;
    for (int item = 1;; item++) {
        int depth = 0;
        const char *e = p;
        while (*e && !(*e == ',' && depth == 0)) {
            depth += *e == '(' ? 1 : *e == ')' ? -1 : 0;
            e++;
        }
        char text[SWEEP_VALUE_SIZE];
        pu_ini_trim_copy(p, e, text, sizeof text);
        if (!text[0])
            return spec_fail_line(c, kv->line, "key 'quantities' in [sweep]: quantity %d is empty",
                                  item);
        if (add_quantity(c, kv, item, text)) return -1;
        if (!*e) break;
        p = e + 1;
    }
    return 0;
}

/* ------------------------------------------------ a case's figures ---- */

/* The quantities of results.csv in dir into mq (NaN where not available). Method: one pass over
 * the rows; per quantity the running max/min, the last value, and the trapezoidal integrals of
 * x and x^2 over t (mean = int x dt / T, rms = sqrt(int x^2 dt / T), T = t_last - t_first). */
void sweep_model_results(const sweep_spec *s, const char *dir, double *mq)
{
    for (int i = 0; i < SWEEP_MAX_REPORT; i++)
        mq[i] = NAN;
    char path[SWEEP_DIR_SIZE + 32];
    snprintf(path, sizeof path, "%s/results.csv", dir);
    long long fsize = 0;
    FILE *f = sweep_open_regular(path, 0, &fsize);
    if (!f) return;
    char *line = NULL;
    size_t cap = 0;
    int col[SWEEP_MAX_REPORT], tcol = -1, ncols = 0;
    for (int i = 0; i < s->nmq; i++)
        col[i] = -1;
    if (getline(&line, &cap, f) > 0) {
        char *save = NULL;
        for (char *t = strtok_r(line, ",\r\n", &save); t; t = strtok_r(NULL, ",\r\n", &save)) {
            if (!strcmp(t, "t")) tcol = ncols;
            for (int i = 0; i < s->nmq; i++)
                if (!strcmp(t, s->mq[i].column)) col[i] = ncols;
            ncols++;
        }
    }
    double *v = calloc((size_t)ncols + 1, sizeof *v);
    double mx[SWEEP_MAX_REPORT], mn[SWEEP_MAX_REPORT], last[SWEEP_MAX_REPORT];
    double i1[SWEEP_MAX_REPORT], i2[SWEEP_MAX_REPORT], prev[SWEEP_MAX_REPORT];
    int bad[SWEEP_MAX_REPORT];
    double t0 = NAN, tprev = NAN;
    long rows = 0;
    for (int i = 0; i < s->nmq; i++)
        mx[i] = -INFINITY, mn[i] = INFINITY, last[i] = prev[i] = NAN, i1[i] = i2[i] = 0,
        bad[i] = col[i] < 0;
    while (v && tcol >= 0 && ftell(f) <= fsize && sweep_signal_count < 2 &&
           getline(&line, &cap, f) > 0) {
        if (sweep_parse_row(line, v, ncols) < ncols) continue; /* not a whole row */
        double t = v[tcol];
        if (rows == 0) t0 = t;
        for (int i = 0; i < s->nmq; i++) {
            if (bad[i]) continue;
            double x = v[col[i]];
            if (s->mq[i].absval || s->mq[i].func == SWEEP_MF_MAXABS) x = fabs(x);
            if (!isfinite(x)) {
                bad[i] = 1;
                continue;
            }
            if (x > mx[i]) mx[i] = x;
            if (x < mn[i]) mn[i] = x;
            if (rows > 0) {
                double dt = t - tprev;
                i1[i] += 0.5 * dt * (x + prev[i]);
                i2[i] += 0.5 * dt * (x * x + prev[i] * prev[i]);
            }
            prev[i] = last[i] = x;
        }
        tprev = t;
        rows++;
    }
    free(v);
    free(line);
    fclose(f);
    if (rows == 0) return;
    double span = tprev - t0;
    for (int i = 0; i < s->nmq; i++) {
        if (bad[i]) continue;
        switch (s->mq[i].func) {
        case SWEEP_MF_MAX:
        case SWEEP_MF_MAXABS:
            mq[i] = mx[i];
            break;
        case SWEEP_MF_MIN:
            mq[i] = mn[i];
            break;
        case SWEEP_MF_END:
            mq[i] = last[i];
            break;
        case SWEEP_MF_MEAN:
            mq[i] = rows > 1 && span > 0 ? i1[i] / span : last[i];
            break;
        default: /* SWEEP_MF_RMS */
            mq[i] = rows > 1 && span > 0 ? sqrt(i2[i] / span) : fabs(last[i]);
            break;
        }
    }
}
