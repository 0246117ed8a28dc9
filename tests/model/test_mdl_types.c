/* The type table of the model files (model/mdl_types.h), every type of it:
 *   1. the table is well formed: names unique (types; a type's parameters, ports, signals),
 *      kinds valid, defaults that parse as their kind and lie in range, ranges lo <= hi, every
 *      port of dimension 0 has a `dim` parameter (or its points give the dimensions), every "*"
 *      port family has a parameter that names the ports (MDL_POINTS or MDL_NAMES);
 *   2. each type builds: a tiny model (mdl_load_string) with the type's required parameters,
 *      every port bonded to a source of its dimension (bg.Se, bg.Sf, mech.support, mech.free)
 *      and every signal of the type read by a sig.gain, compiles, and the element(s) contribute
 *      the number of equations the component's header gives (stated per case below, counted
 *      independently of the build: one per port component and one per own unknown);
 *   3. parameters out of range (the table's or the constructor's) give a message that names the
 *      instance's path and the parameter;
 *   4. docs/model-types.md equals a fresh mdl_types_markdown(). To regenerate it:
 *        build/tests/model/test_mdl_types --write docs/model-types.md
 * DOCS_DIR (from meson) is the source tree's docs/ folder. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mdl_model.h"
#include "mdl_types.h"
#include "tap.h"

#ifndef DOCS_DIR
#define DOCS_DIR "docs"
#endif

/* ---- 1. the table ---- */

static int is_word(const char *s, size_t n)
{
    if (n == 0 || !(s[0] == '_' || (s[0] >= 'a' && s[0] <= 'z') || (s[0] >= 'A' && s[0] <= 'Z')))
        return 0;
    for (size_t i = 1; i < n; i++)
        if (!(s[i] == '_' || (s[i] >= 'a' && s[i] <= 'z') || (s[i] >= 'A' && s[i] <= 'Z') ||
              (s[i] >= '0' && s[i] <= '9')))
            return 0;
    return 1;
}

static int in_range(const mdl_param_def *p, double x)
{
    if (!isfinite(x)) return 0;
    if (p->flags & MDL_FINITE) return 1;
    if (p->flags & MDL_LO_OPEN ? !(x > p->lo) : !(x >= p->lo)) return 0;
    if (p->flags & MDL_HI_OPEN ? !(x < p->hi) : !(x <= p->hi)) return 0;
    return 1;
}

/* the entries of "[x, y, z]" (numbers or words) one by one: returns 0 at the end, -1 if
 * malformed; *s advances */
static int list_item(const char **s, const char **item, size_t *n)
{
    const char *p = *s;
    while (*p == ' ' || *p == ',')
        p++;
    if (*p == ']') return 0;
    if (!*p) return -1;
    *item = p;
    while (*p && *p != ',' && *p != ']' && *p != ' ')
        p++;
    *n = (size_t)(p - *item);
    *s = p;
    return 1;
}

/* the default parses as the parameter's kind and lies in its range */
static int default_ok(const mdl_param_def *p, char *why, size_t size)
{
    const char *d = p->dflt;
    char *end;
    switch (p->kind) {
    case MDL_NUMBER:
    case MDL_INTEGER: {
        double x = strtod(d, &end);
        if (*end || end == d) return snprintf(why, size, "'%s' is no number", d), 0;
        if (p->kind == MDL_INTEGER && x != floor(x))
            return snprintf(why, size, "'%s' is no integer", d), 0;
        if (!in_range(p, x)) return snprintf(why, size, "'%s' out of its range", d), 0;
        return 1;
    }
    case MDL_FLAG:
        return !strcmp(d, "true") || !strcmp(d, "false") || (snprintf(why, size, "'%s'", d), 0);
    case MDL_CHOICE: {
        size_t n = strlen(d);
        for (const char *c = p->choices; c && *c;) {
            size_t k = strcspn(c, "|");
            if (k == n && !strncmp(c, d, n)) return 1;
            c += k + (c[k] ? 1 : 0);
        }
        return snprintf(why, size, "'%s' not one of %s", d, p->choices ? p->choices : "(none)"), 0;
    }
    case MDL_VECTOR:
    case MDL_NAMES: {
        if (d[0] != '[') return snprintf(why, size, "'%s' is no list", d), 0;
        const char *s = d + 1, *it;
        size_t n;
        int count = 0, r;
        while ((r = list_item(&s, &it, &n)) == 1) {
            count++;
            char buf[64];
            snprintf(buf, sizeof buf, "%.*s", (int)n, it);
            if (p->kind == MDL_NAMES && !is_word(it, n))
                return snprintf(why, size, "'%s': '%s'", d, buf), 0;
            if (p->kind == MDL_VECTOR) {
                double x = strtod(buf, &end);
                if (*end || end == buf || !in_range(p, x))
                    return snprintf(why, size, "'%s': '%s'", d, buf), 0;
            }
        }
        if (r < 0 || count == 0) return snprintf(why, size, "'%s' malformed or empty", d), 0;
        if (p->kind == MDL_VECTOR && p->len > 0 && count != p->len)
            return snprintf(why, size, "'%s' has %d entries, expected %d", d, count, p->len), 0;
        return 1;
    }
    case MDL_ELEMENT:
    case MDL_SIGNAL:
    case MDL_POINTS:
    case MDL_NODE_PORTS:
        return snprintf(why, size, "a %d-kind parameter has no default", (int)p->kind), 0;
    }
    return 0;
}

static int names_param(const mdl_type *t)
{
    for (int i = 0; i < t->nparams; i++)
        if (t->params[i].kind == MDL_POINTS || t->params[i].kind == MDL_NAMES ||
            t->params[i].kind == MDL_NODE_PORTS)
            return i;
    return -1;
}

static void check_table(const mdl_type *t)
{
    char why[256] = "";
    int ok = t->name && t->summary && *t->summary && t->equations && *t->equations && t->build;
    tap_ok(ok, "%s: name, summary, equations and build()", t->name ? t->name : "?");
    for (int j = 0, n = mdl_type_count(); j < n; j++)
        if (mdl_type_at(j) != t && !strcmp(mdl_type_at(j)->name, t->name))
            tap_ok(0, "%s: the name is taken twice", t->name);
    ok = 1;
    for (int i = 0; i < t->nparams && ok; i++) {
        const mdl_param_def *p = &t->params[i];
        for (int j = 0; j < i; j++)
            if (!strcmp(t->params[j].name, p->name))
                ok = 0, snprintf(why, sizeof why, "%s twice", p->name);
        if (ok && !(p->kind >= MDL_NUMBER && p->kind <= MDL_NODE_PORTS))
            ok = 0, snprintf(why, sizeof why, "%s: kind %d", p->name, (int)p->kind);
        if (ok && (!p->unit || !p->meaning || !*p->meaning))
            ok = 0, snprintf(why, sizeof why, "%s: unit or meaning missing", p->name);
        if (ok && p->kind == MDL_CHOICE && (!p->choices || !*p->choices))
            ok = 0, snprintf(why, sizeof why, "%s: a choice without choices", p->name);
        if (ok && (p->kind == MDL_NUMBER || p->kind == MDL_INTEGER || p->kind == MDL_VECTOR) &&
            !(p->flags & MDL_FINITE) && !(p->lo <= p->hi))
            ok = 0, snprintf(why, sizeof why, "%s: range [%g, %g]", p->name, p->lo, p->hi);
        if (ok && p->dflt && (p->flags & MDL_OPTIONAL))
            ok = 0, snprintf(why, sizeof why, "%s: optional with a default", p->name);
        char sub[200];
        if (ok && p->dflt && !default_ok(p, sub, sizeof sub))
            ok = 0, snprintf(why, sizeof why, "%s: default %s", p->name, sub);
    }
    tap_ok(ok, "%s: parameters well formed%s%s", t->name, ok ? "" : ": ", ok ? "" : why);
    ok = 1;
    for (int i = 0; i < t->nports && ok; i++) {
        const mdl_port_def *p = &t->ports[i];
        for (int j = 0; j < i; j++)
            if (!strcmp(t->ports[j].name, p->name))
                ok = 0, snprintf(why, sizeof why, "%s twice", p->name);
        if (ok && p->dim != 0 && p->dim != 1 && p->dim != 3 && p->dim != 6)
            ok = 0, snprintf(why, sizeof why, "%s: dim %d", p->name, p->dim);
        int np = names_param(t);
        int points = np >= 0 && (t->params[np].kind == MDL_POINTS || t->params[np].kind == MDL_NODE_PORTS);
        if (ok && p->dim == 0 && !(!strcmp(p->name, "*") && points)) {
            const mdl_param_def *d = mdl_type_param(t, "dim");
            if (!d || d->kind != MDL_INTEGER)
                ok = 0, snprintf(why, sizeof why, "%s: dim 0 without `dim`", p->name);
        }
        if (ok && !strcmp(p->name, "*") && np < 0)
            ok = 0, snprintf(why, sizeof why, "a port family without a parameter naming it");
        if (ok && (!p->meaning || !*p->meaning))
            ok = 0, snprintf(why, sizeof why, "%s: no meaning", p->name);
    }
    tap_ok(ok, "%s: ports well formed%s%s", t->name, ok ? "" : ": ", ok ? "" : why);
    ok = 1;
    for (int i = 0; i < t->nsignals && ok; i++) {
        for (int j = 0; j < i; j++)
            if (!strcmp(t->signals[j].name, t->signals[i].name)) ok = 0;
        if (!t->signals[i].unit || !t->signals[i].meaning) ok = 0;
        if (!ok) snprintf(why, sizeof why, "%s", t->signals[i].name);
    }
    tap_ok(ok, "%s: signals well formed%s%s", t->name, ok ? "" : ": ", ok ? "" : why);
}

#include "test_mdl_types_cases.h"

/* ---- 4. the reference page ---- */

static char *read_all(const char *path, size_t *n)
{
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    size_t cap = 1 << 16, len = 0;
    char *s = malloc(cap);
    size_t k;
    while (s && (k = fread(s + len, 1, cap - len - 1, f)) > 0)
        if ((len += k) + 1 == cap) {
            char *t = realloc(s, cap *= 2);
            if (!t) free(s);
            s = t;
        }
    fclose(f);
    if (s) s[len] = 0;
    *n = len;
    return s;
}

static void check_docs(void)
{
    char *fresh = NULL;
    size_t nfresh = 0, nfile = 0;
    FILE *m = open_memstream(&fresh, &nfresh);
    int r = m ? mdl_types_markdown(m) : BG_ERR_MEMORY;
    if (m) fclose(m);
    tap_ok(r == BG_OK && fresh, "mdl_types_markdown writes the reference");
    char *file = read_all(DOCS_DIR "/model-types.md", &nfile);
    int same = file && fresh && nfile == nfresh && !memcmp(file, fresh, nfile);
    if (!same && file && fresh) {
        int line = 1;
        size_t i = 0;
        for (; i < nfile && i < nfresh && file[i] == fresh[i]; i++)
            line += file[i] == '\n';
        tap_diag("first difference at line %d", line);
    }
    tap_ok(same,
           "docs/model-types.md is the table's reference (%s; regenerate: test_mdl_types "
           "--write docs/model-types.md)",
           file ? "differs" : "not found");
    free(fresh);
    free(file);
}

int main(int argc, char **argv)
{
    if (argc == 3 && !strcmp(argv[1], "--write")) {
        FILE *f = fopen(argv[2], "w");
        int r = f ? mdl_types_markdown(f) : BG_ERR_IO;
        if (f && fclose(f)) r = BG_ERR_IO;
        if (r != BG_OK) fprintf(stderr, "cannot write %s\n", argv[2]);
        return r == BG_OK ? 0 : 1;
    }
    tap_ok(mdl_type_count() > 0, "the table has %d types", mdl_type_count());
    for (int i = 0, n = mdl_type_count(); i < n; i++)
        check_table(mdl_type_at(i));
    check_builds();
    check_errors();
    check_docs();
    return tap_done();
}
