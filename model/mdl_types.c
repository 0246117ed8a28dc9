/* The type table (mdl_types.h): the parts of each domain (mdl_types_*.c) in one index, and the
 * descriptions generated from it. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "mdl_impl.h"

typedef struct part {
    const mdl_type *const *types;
    const int *count;
} part;

static const part parts[] = {
    {mdl_types_mech, &mdl_types_mech_count}, {mdl_types_hyd, &mdl_types_hyd_count},
    {mdl_types_rot, &mdl_types_rot_count},   {mdl_types_ctl, &mdl_types_ctl_count},
    {mdl_types_beam, &mdl_types_beam_count},   {mdl_types_drive, &mdl_types_drive_count}, {mdl_types_bg, &mdl_types_bg_count},
};

int mdl_type_count(void)
{
    int n = 0;
    for (size_t p = 0; p < sizeof parts / sizeof parts[0]; p++)
        n += *parts[p].count;
    return n;
}

const mdl_type *mdl_type_at(int i)
{
    if (i < 0) return NULL;
    for (size_t p = 0; p < sizeof parts / sizeof parts[0]; p++) {
        if (i < *parts[p].count) return parts[p].types[i];
        i -= *parts[p].count;
    }
    return NULL;
}

const mdl_type *mdl_type_find(const char *name)
{
    if (!name) return NULL;
    for (int i = 0, n = mdl_type_count(); i < n; i++)
        if (!strcmp(mdl_type_at(i)->name, name)) return mdl_type_at(i);
    return NULL;
}

const mdl_param_def *mdl_type_param(const mdl_type *t, const char *name)
{
    if (!t || !name) return NULL;
    for (int i = 0; i < t->nparams; i++)
        if (!strcmp(t->params[i].name, name)) return &t->params[i];
    return NULL;
}

static const char *kind_name(mdl_kind k)
{
    switch (k) {
    case MDL_NUMBER: return "number";
    case MDL_INTEGER: return "integer";
    case MDL_FLAG: return "true/false";
    case MDL_VECTOR: return "vector";
    case MDL_CHOICE: return "choice";
    case MDL_ELEMENT: return "element path";
    case MDL_SIGNAL: return "signal path";
    case MDL_POINTS: return "points";
    case MDL_NAMES: return "list of names";
    case MDL_NODE_PORTS: return "node ports";
    }
    return "?";
}

static const char *domain_name(mdl_domain d)
{
    switch (d) {
    case MDL_GENERIC: return "generic";
    case MDL_MECH6: return "mechanical 6D";
    case MDL_MECH3: return "mechanical 3D";
    case MDL_HYDRAULIC: return "hydraulic";
    case MDL_ROTATIONAL: return "rotational";
    }
    return "?";
}

/* The range of a parameter as text: "> 0", "[0, 1]", "finite", "" (none). */
static void range_text(const mdl_param_def *p, char *buf, size_t size)
{
    buf[0] = 0;
    if (p->kind == MDL_CHOICE) {
        snprintf(buf, size, "%s", p->choices ? p->choices : "");
        return;
    }
    if (p->kind != MDL_NUMBER && p->kind != MDL_INTEGER && p->kind != MDL_VECTOR) return;
    if (p->flags & MDL_FINITE) {
        snprintf(buf, size, "finite");
        return;
    }
    int lo = isfinite(p->lo), hi = isfinite(p->hi);
    const char *lop = p->flags & MDL_LO_OPEN ? ">" : ">=", *hip = p->flags & MDL_HI_OPEN ? "<" : "<=";
    if (lo && hi)
        snprintf(buf, size, "%s%g, %g%s", p->flags & MDL_LO_OPEN ? "(" : "[", p->lo, p->hi,
                 p->flags & MDL_HI_OPEN ? ")" : "]");
    else if (lo)
        snprintf(buf, size, "%s %g", lop, p->lo);
    else if (hi)
        snprintf(buf, size, "%s %g", hip, p->hi);
    else
        snprintf(buf, size, "finite");
}

static void kind_text(const mdl_param_def *p, char *buf, size_t size)
{
    if (p->kind == MDL_VECTOR && p->len > 0)
        snprintf(buf, size, "vector of %d", p->len);
    else
        snprintf(buf, size, "%s", kind_name(p->kind));
}

static const char *dflt_text(const mdl_param_def *p)
{
    if (p->dflt) return p->dflt;
    return p->flags & MDL_OPTIONAL ? "(optional)" : "(required)";
}

int mdl_type_describe(const mdl_type *t, int markdown, FILE *f)
{
    if (!t || !f) return BG_ERR_ARGUMENT;
    char range[128], kind[32];
    if (markdown) {
        fprintf(f, "## `%s`\n\n%s\n\n```\n%s\n```\n\n", t->name, t->summary, t->equations);
        if (t->nparams) {
            fprintf(f, "| parameter | kind | unit | default | range | meaning |\n"
                       "|---|---|---|---|---|---|\n");
            for (int i = 0; i < t->nparams; i++) {
                const mdl_param_def *p = &t->params[i];
                range_text(p, range, sizeof range);
                kind_text(p, kind, sizeof kind);
                fprintf(f, "| `%s` | %s | %s | %s | %s | %s |\n", p->name, kind, p->unit ? p->unit : "",
                        dflt_text(p), range, p->meaning);
            }
            fprintf(f, "\n");
        }
        if (t->nports) {
            fprintf(f, "| port | dimension | domain | meaning |\n|---|---|---|---|\n");
            for (int i = 0; i < t->nports; i++) {
                const mdl_port_def *p = &t->ports[i];
                char dim[16];
                if (p->dim) snprintf(dim, sizeof dim, "%d", p->dim);
                else snprintf(dim, sizeof dim, "`dim`");
                fprintf(f, "| `%s` | %s | %s | %s |\n", p->name, dim, domain_name(p->domain), p->meaning);
            }
            fprintf(f, "\n");
        }
        if (t->nsignals) {
            fprintf(f, "| signal | unit | meaning |\n|---|---|---|\n");
            for (int i = 0; i < t->nsignals; i++)
                fprintf(f, "| `%s` | %s | %s |\n", t->signals[i].name, t->signals[i].unit,
                        t->signals[i].meaning);
            fprintf(f, "\n");
        }
    } else {
        fprintf(f, "%s: %s\n\nequations:\n", t->name, t->summary);
        const char *s = t->equations;
        while (*s) {
            const char *e = strchr(s, '\n');
            int n = e ? (int)(e - s) : (int)strlen(s);
            fprintf(f, "  %.*s\n", n, s);
            s += n + (e ? 1 : 0);
        }
        if (t->nparams) fprintf(f, "\nparameters:\n");
        for (int i = 0; i < t->nparams; i++) {
            const mdl_param_def *p = &t->params[i];
            range_text(p, range, sizeof range);
            kind_text(p, kind, sizeof kind);
            fprintf(f, "  %-16s %s%s%s, default %s%s%s\n      %s\n", p->name, kind,
                    p->unit && *p->unit ? " in " : "", p->unit ? p->unit : "", dflt_text(p),
                    range[0] ? ", " : "", range, p->meaning);
        }
        if (t->nports) fprintf(f, "\nports:\n");
        for (int i = 0; i < t->nports; i++) {
            const mdl_port_def *p = &t->ports[i];
            if (p->dim)
                fprintf(f, "  %-16s %dD %s: %s\n", p->name, p->dim, domain_name(p->domain), p->meaning);
            else
                fprintf(f, "  %-16s (dim)D %s: %s\n", p->name, domain_name(p->domain), p->meaning);
        }
        if (t->nsignals) fprintf(f, "\nsignals:\n");
        for (int i = 0; i < t->nsignals; i++)
            fprintf(f, "  %-16s %s: %s\n", t->signals[i].name, t->signals[i].unit, t->signals[i].meaning);
    }
    return ferror(f) ? BG_ERR_IO : BG_OK;
}

int mdl_types_markdown(FILE *f)
{
    if (!f) return BG_ERR_ARGUMENT;
    fprintf(f, "# Model file types\n\n"
               "Generated from the library's type table (`bgsim --list-types --markdown`); a test "
               "fails when\nthis page and the table disagree. The format: docs/model-format.md.\n\n");
    for (int i = 0, n = mdl_type_count(); i < n; i++)
        fprintf(f, "- [`%s`](#%s): %s\n", mdl_type_at(i)->name, mdl_type_at(i)->name, mdl_type_at(i)->summary);
    fprintf(f, "\n");
    for (int i = 0, n = mdl_type_count(); i < n; i++)
        if (mdl_type_describe(mdl_type_at(i), 1, f) != BG_OK) return BG_ERR_IO;
    return ferror(f) ? BG_ERR_IO : BG_OK;
}
