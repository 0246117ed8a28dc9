/* The records an instance's build() reads (its evaluated arguments) and fills (the ports, signals
 * and elements it offers): mdl_impl.h. */
#include <stdlib.h>
#include <string.h>

#include "mdl_impl.h"

static const mdl_value *val(const mdl_args *a, const char *name, mdl_kind kind)
{
    if (!a || !a->type || !name) return NULL;
    for (int i = 0; i < a->type->nparams; i++)
        if (!strcmp(a->type->params[i].name, name))
            return a->type->params[i].kind == kind && a->v[i].has ? &a->v[i] : NULL;
    return NULL;
}

int mdl_arg_has(const mdl_args *a, const char *name)
{
    if (!a || !a->type || !name) return 0;
    for (int i = 0; i < a->type->nparams; i++)
        if (!strcmp(a->type->params[i].name, name)) return a->v[i].has;
    return 0;
}

double mdl_arg_num(const mdl_args *a, const char *name)
{
    const mdl_value *v = val(a, name, MDL_NUMBER);
    return v ? v->num : 0.0;
}

int mdl_arg_int(const mdl_args *a, const char *name)
{
    const mdl_value *v = val(a, name, MDL_INTEGER);
    return v ? (int)v->num : 0;
}

int mdl_arg_flag(const mdl_args *a, const char *name)
{
    const mdl_value *v = val(a, name, MDL_FLAG);
    return v ? v->num != 0 : 0;
}

const double *mdl_arg_vec(const mdl_args *a, const char *name, int *len)
{
    const mdl_value *v = val(a, name, MDL_VECTOR);
    if (len) *len = v ? v->len : 0;
    return v ? v->vec : NULL;
}

const char *mdl_arg_choice(const mdl_args *a, const char *name)
{
    const mdl_value *v = val(a, name, MDL_CHOICE);
    return v ? v->word : NULL;
}

int mdl_arg_element(const mdl_args *a, const char *name)
{
    const mdl_value *v = val(a, name, MDL_ELEMENT);
    return v ? v->elem : -1;
}

bgr_ref mdl_arg_signal(const mdl_args *a, const char *name)
{
    const mdl_value *v = val(a, name, MDL_SIGNAL);
    return v ? v->sig : (bgr_ref){BGR_OWN, -1, 0};
}

int mdl_arg_npoints(const mdl_args *a, const char *name)
{
    const mdl_value *v = val(a, name, MDL_POINTS);
    if (!v) v = val(a, name, MDL_NODE_PORTS);
    return v ? v->npts : 0;
}

const char *mdl_arg_point(const mdl_args *a, const char *name, int i, double r[3], int *dim)
{
    const mdl_value *v = val(a, name, MDL_POINTS);
    if (!v) v = val(a, name, MDL_NODE_PORTS);
    if (!v || i < 0 || i >= v->npts) return NULL;
    if (r) memcpy(r, v->pr + 3 * i, 3 * sizeof *r);
    if (dim) *dim = v->pdim[i];
    return v->pname[i];
}

const char *const *mdl_arg_names(const mdl_args *a, const char *name, int *n)
{
    const mdl_value *v = val(a, name, MDL_NAMES);
    if (n) *n = v ? v->npts : 0;
    return v ? (const char *const *)v->pname : NULL;
}

const char *mdl_arg_path(const mdl_args *a)
{
    return a && a->path ? a->path : "";
}

/* ---- instances ---- */

static int grow(void **p, int *cap, int n, size_t size)
{
    if (n < *cap) return 0;
    int nc = *cap ? 2 * *cap : 8;
    void *q = realloc(*p, (size_t)nc * size);
    if (!q) return -1;
    *p = q;
    *cap = nc;
    return 0;
}

int mdl_instance_port(mdl_instance *in, const char *name, bgr_port p, int dim, mdl_domain domain)
{
    if (!in || !name || p.elem < 0) return BG_ERR_ARGUMENT;
    if (mdl_instance_find_port(in, name) >= 0) return BG_ERR_ARGUMENT;
    if (grow((void **)&in->ports, &in->capports, in->nports, sizeof *in->ports)) return BG_ERR_MEMORY;
    char *s = strdup(name);
    if (!s) return BG_ERR_MEMORY;
    in->ports[in->nports++] = (mdl_iport){s, p, dim, domain};
    return BG_OK;
}

int mdl_instance_signal(mdl_instance *in, const char *name, bgr_ref r)
{
    if (!in || !name || r.id < 0) return BG_ERR_ARGUMENT;
    if (mdl_instance_find_signal(in, name)) return BG_ERR_ARGUMENT;
    if (grow((void **)&in->sigs, &in->capsigs, in->nsigs, sizeof *in->sigs)) return BG_ERR_MEMORY;
    char *s = strdup(name);
    if (!s) return BG_ERR_MEMORY;
    in->sigs[in->nsigs++] = (mdl_isignal){s, r};
    return BG_OK;
}

int mdl_instance_add(mdl_instance *in, int elem)
{
    if (!in || elem < 0) return BG_ERR_ARGUMENT;
    if (grow((void **)&in->elems, &in->capelems, in->nelems, sizeof *in->elems)) return BG_ERR_MEMORY;
    in->elems[in->nelems++] = elem;
    return BG_OK;
}

int mdl_instance_element(mdl_instance *in, int elem)
{
    if (!in || elem < 0) return BG_ERR_ARGUMENT;
    in->main = elem;
    for (int i = 0; i < in->nelems; i++)
        if (in->elems[i] == elem) return BG_OK;
    return mdl_instance_add(in, elem);
}

int mdl_instance_main(const mdl_instance *in)
{
    return in ? in->main : -1;
}

int mdl_instance_nelements(const mdl_instance *in)
{
    return in ? in->nelems : 0;
}

int mdl_instance_elem(const mdl_instance *in, int i)
{
    return in && i >= 0 && i < in->nelems ? in->elems[i] : -1;
}

int mdl_instance_nports(const mdl_instance *in)
{
    return in ? in->nports : 0;
}

const char *mdl_instance_port_name(const mdl_instance *in, int i)
{
    return in && i >= 0 && i < in->nports ? in->ports[i].name : NULL;
}

const mdl_iport *mdl_instance_port_at(const mdl_instance *in, int i)
{
    return in && i >= 0 && i < in->nports ? &in->ports[i] : NULL;
}

int mdl_instance_find_port(const mdl_instance *in, const char *name)
{
    if (!in || !name) return -1;
    for (int i = 0; i < in->nports; i++)
        if (!strcmp(in->ports[i].name, name)) return i;
    return -1;
}

const mdl_isignal *mdl_instance_find_signal(const mdl_instance *in, const char *name)
{
    if (!in || !name) return NULL;
    for (int i = 0; i < in->nsigs; i++)
        if (!strcmp(in->sigs[i].name, name)) return &in->sigs[i];
    return NULL;
}

static void value_clear(mdl_value *v)
{
    free(v->vec);
    free(v->word);
    for (int i = 0; i < v->npts; i++)
        free(v->pname[i]);
    free(v->pname);
    free(v->pr);
    free(v->pdim);
    memset(v, 0, sizeof *v);
}

void mdl_instance_clear(mdl_instance *in)
{
    if (!in) return;
    for (int i = 0; i < in->nports; i++)
        free(in->ports[i].name);
    for (int i = 0; i < in->nsigs; i++)
        free(in->sigs[i].name);
    if (in->args.v && in->type)
        for (int i = 0; i < in->type->nparams; i++)
            value_clear(&in->args.v[i]);
    free(in->args.v);
    free(in->ports);
    free(in->sigs);
    free(in->elems);
    free(in->path);
    memset(in, 0, sizeof *in);
    in->main = -1;
}

int mdl_locate(mdl_locator *loc, int port, double x[3])
{
    if (!loc || !loc->locate || !x) return BG_ERR_ARGUMENT;
    return loc->locate(loc->ctx, loc->self, port, x);
}

int mdl_fail_model(bg_error *err, bgr_model *m, int status)
{
    const bg_error *e = bgr_model_error(m);
    if (e) bg_error_raise(err, status, "model", "%s", e->message);
    return status;
}
