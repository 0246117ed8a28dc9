/* The document and its includes, the subsystem definitions, the model's parameters, and the
 * instance tree (mdl_priv.h): subsystems expanded, repetitions unrolled, names checked. */
#define _XOPEN_SOURCE 700 /* realpath */
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mdl_priv.h"

static const char *const top_keys[] = {"format", "name", "description", "include", "parameters",
                                       "subsystems", "components", "bonds", "outputs", "solver",
                                       "start", "initial", "trim"};
static const char *const include_keys[] = {"format", "name", "description", "include",
                                           "parameters", "subsystems"};
static const char *const sub_keys[] = {"description", "parameters", "ports", "signals",
                                       "components", "bonds"};

#define COUNT(a) ((int)(sizeof(a) / sizeof((a)[0])))

/* The most instances (components and subsystem instances) a model may have: far above any
 * machine (a 512-element boom has about 1 000), low enough that a hostile file cannot make the
 * reader run for minutes. The fuzz build sets a lower bound (fuzz/meson.build). */
#ifndef MDL_MAX_INSTANCES
#define MDL_MAX_INSTANCES 200000
#endif

static int add_doc(mdl_model *mm, mdl_y_doc *d)
{
    if (mm->ndocs == mm->capdocs) {
        int nc = mm->capdocs ? 2 * mm->capdocs : 4;
        mdl_y_doc **p = realloc(mm->docs, (size_t)nc * sizeof *p);
        if (!p) return BG_ERR_MEMORY;
        mm->docs = p;
        mm->capdocs = nc;
    }
    mm->docs[mm->ndocs++] = d;
    return BG_OK;
}

static int check_format(mdl_model *mm, const mdl_y_node *root)
{
    const mdl_y_node *f = mdl_y_get(root, "format");
    if (!f) return mdl_fail(mm, root, "format", "missing: the first line of a model file is 'format: bgsim 1'");
    if (f->kind != MDL_Y_SCALAR || strcmp(f->text, "bgsim 1"))
        return mdl_fail(mm, f, "format", "expected 'bgsim 1', got '%s'",
                        f->kind == MDL_Y_SCALAR ? f->text : mdl_y_kind_name(f->kind));
    return BG_OK;
}

static int add_sub(mdl_model *mm, const mdl_y_node *key, const mdl_y_node *def)
{
    for (int i = 0; i < mm->nsubs; i++)
        if (!strcmp(mm->subs[i].name, key->text)) return BG_OK; /* the including file's wins */
    if (mdl_type_find(key->text))
        return mdl_fail(mm, key, "subsystems", "'%s' is a library type's name", key->text);
    if (def->kind != MDL_Y_MAPPING)
        return mdl_fail(mm, def, key->text, "a subsystem is a mapping (parameters, ports, "
                        "components, bonds)");
    int r = mdl_check_keys(mm, def, key->text, sub_keys, COUNT(sub_keys));
    if (r != BG_OK) return r;
    if (mm->nsubs == mm->capsubs) {
        int nc = mm->capsubs ? 2 * mm->capsubs : 8;
        mdl_sub *p = realloc(mm->subs, (size_t)nc * sizeof *p);
        if (!p) return BG_ERR_MEMORY;
        mm->subs = p;
        mm->capsubs = nc;
    }
    mm->subs[mm->nsubs++] = (mdl_sub){key->text, def, key};
    return BG_OK;
}

static int is_word(const char *s)
{
    if (!s || !(*s == '_' || (*s >= 'A' && *s <= 'Z') || (*s >= 'a' && *s <= 'z'))) return 0;
    for (; *s; s++)
        if (!(*s == '_' || (*s >= 'A' && *s <= 'Z') || (*s >= 'a' && *s <= 'z') ||
              (*s >= '0' && *s <= '9')))
            return 0;
    return 1;
}

static int is_word_or_dash(const char *s)
{
    if (!s || !*s) return 0;
    for (; *s; s++)
        if (!(*s == '_' || *s == '-' || (*s >= 'A' && *s <= 'Z') || (*s >= 'a' && *s <= 'z') ||
              (*s >= '0' && *s <= '9')))
            return 0;
    return 1;
}

static const char *set_for(mdl_model *mm, const char *path)
{
    for (int i = 0; i < mm->nsets; i++)
        if (!strcmp(mm->sets[i].path, path)) {
            mm->set_used[i] = 1;
            return mm->sets[i].value;
        }
    return NULL;
}

/* parameters of the model (root scope): the including file's first, then what includes add */
static int add_params(mdl_model *mm, const mdl_y_node *params)
{
    if (!params) return BG_OK;
    if (params->kind != MDL_Y_MAPPING)
        return mdl_fail(mm, params, "parameters", "expected a mapping name: value");
    for (int i = 0; i < mdl_y_count(params); i++) {
        const mdl_y_node *k = mdl_y_key(params, i);
        if (!is_word(k->text))
            return mdl_fail(mm, k, "parameters", "'%s' is not a name ([A-Za-z_][A-Za-z0-9_]*)", k->text);
        if (mdl_expr_is_reserved(k->text) || !strcmp(k->text, "t"))
            return mdl_fail(mm, k, "parameters", "'%s' is a function or constant of the expressions "
                            "(or the time): choose another name", k->text);
        if (mdl_scope_find(&mm->top.scope, k->text, 0)) continue;
        int r = mdl_scope_add(&mm->top.scope, k->text, mdl_y_value(params, i), set_for(mm, k->text),
                              NULL);
        if (r != BG_OK) return r;
    }
    return BG_OK;
}

/* reads one file and, depth first, what it includes; stack: the files being read (a loop) */
static int read_file(mdl_model *mm, const char *path, const char *text, int is_main,
                     char **stack, int depth)
{
    mdl_y_doc *d = NULL;
    mdl_y_error e = {0};
    int r = text ? mdl_y_load_string(text, strlen(text), path, &d, &e) : mdl_y_load_file(path, &d, &e);
    if (r != 0) {
        bg_error_raise(mm->err, BG_ERR_ARGUMENT, "mdl_load", "%s", e.message);
        return BG_ERR_ARGUMENT;
    }
    if ((r = add_doc(mm, d)) != BG_OK) {
        mdl_y_free(d);
        return r;
    }
    const mdl_y_node *root = mdl_y_root(d);
    if (!root || root->kind != MDL_Y_MAPPING)
        return mdl_fail(mm, root, NULL, "a model file is a mapping (format, name, components, ...)");
    if ((r = check_format(mm, root)) != BG_OK) return r;
    r = is_main ? mdl_check_keys(mm, root, NULL, top_keys, COUNT(top_keys))
                : mdl_check_keys(mm, root, NULL, include_keys, COUNT(include_keys));
    if (r != BG_OK) return r;
    if (is_main) mm->root = root;
    if ((r = add_params(mm, mdl_y_get(root, "parameters"))) != BG_OK) return r;
    const mdl_y_node *subs = mdl_y_get(root, "subsystems");
    if (subs && subs->kind != MDL_Y_MAPPING)
        return mdl_fail(mm, subs, "subsystems", "expected a mapping name: definition");
    for (int i = 0; i < mdl_y_count(subs); i++)
        if ((r = add_sub(mm, mdl_y_key(subs, i), mdl_y_value(subs, i))) != BG_OK) return r;
    const mdl_y_node *inc = mdl_y_get(root, "include");
    if (!inc) return BG_OK;
    if (inc->kind != MDL_Y_SEQUENCE)
        return mdl_fail(mm, inc, "include", "expected a list of files");
    for (int i = 0; i < mdl_y_count(inc); i++) {
        const mdl_y_node *f = mdl_y_item(inc, i);
        if (f->kind != MDL_Y_SCALAR || !*f->text)
            return mdl_fail(mm, f, "include", "expected a file name");
        char full[PATH_MAX], real[PATH_MAX];
        const char *slash = strrchr(path, '/');
        if (f->text[0] == '/' || !slash)
            snprintf(full, sizeof full, "%s", f->text);
        else
            snprintf(full, sizeof full, "%.*s/%s", (int)(slash - path), path, f->text);
        if (!realpath(full, real))
            return mdl_fail(mm, f, "include", "cannot read '%s'", full);
        for (int j = 0; j < depth; j++)
            if (!strcmp(stack[j], real))
                return mdl_fail(mm, f, "include", "'%s' includes itself (an include loop)", f->text);
        int seen = 0;
        for (int j = 1; j < mm->ndocs && !seen; j++)
            seen = !strcmp(mdl_y_file(mm->docs[j]), full);
        if (seen) continue;
        if (depth >= 16) return mdl_fail(mm, f, "include", "includes nested more than 16 deep");
        stack[depth] = real;
        if ((r = read_file(mm, full, NULL, 0, stack, depth + 1)) != BG_OK) return r;
    }
    return BG_OK;
}

int mdl_read_document(mdl_model *mm, const char *path, const char *text)
{
    char *stack[17], real[PATH_MAX];
    stack[0] = realpath(path, real) ? real : (char *)path;
    int r = read_file(mm, path, text, 1, stack, 1);
    if (r != BG_OK) return r;
    const mdl_y_node *name = mdl_y_get(mm->root, "name");
    if (!name || name->kind != MDL_Y_SCALAR || !is_word_or_dash(name->text))
        return mdl_fail(mm, name ? name : mm->root, "name",
                        "expected the model's name (letters, digits, '-' and '_')");
    mm->name = strdup(name->text);
    return mm->name ? BG_OK : BG_ERR_MEMORY;
}

/* ---- the instance tree ---- */

static const mdl_sub *find_sub(const mdl_model *mm, const char *name)
{
    for (int i = 0; i < mm->nsubs; i++)
        if (!strcmp(mm->subs[i].name, name)) return &mm->subs[i];
    return NULL;
}

static int unknown_type(mdl_model *mm, const mdl_y_node *at, const char *where, const char *name)
{
    int n = mdl_type_count();
    const char **cand = malloc((size_t)(n + mm->nsubs) * sizeof *cand);
    if (!cand) return BG_ERR_MEMORY;
    for (int i = 0; i < n; i++)
        cand[i] = mdl_type_at(i)->name;
    for (int i = 0; i < mm->nsubs; i++)
        cand[n + i] = mm->subs[i].name;
    const char *near = mdl_nearest(name, cand, n + mm->nsubs);
    int r = mdl_fail(mm, at, where, "unknown type '%s'%s%s%s (bgsim --list-types lists the "
                     "library's)", name, *near ? " (did you mean '" : "", near, *near ? "'?)" : "");
    free(cand);
    return r;
}

static char *join(const char *a, const char *sep, const char *b)
{
    size_t n = (a ? strlen(a) + strlen(sep) : 0) + strlen(b) + 1;
    char *s = malloc(n);
    if (s) snprintf(s, n, "%s%s%s", a ? a : "", a ? sep : "", b);
    return s;
}

static int add_kid(mdl_inode *p, mdl_inode *k)
{
    if (p->nkids == p->capkids) {
        int nc = p->capkids ? 2 * p->capkids : 8;
        mdl_inode **q = realloc(p->kids, (size_t)nc * sizeof *q);
        if (!q) return BG_ERR_MEMORY;
        p->kids = q;
        p->capkids = nc;
    }
    p->kids[p->nkids++] = k;
    return BG_OK;
}

static int expand_components(mdl_model *mm, mdl_inode *node, const mdl_y_node *comps, int depth);

/* the subsystem's parameters: the instance's values (evaluated outside, in its loop scope), the
 * replacements, then the defaults (evaluated inside) */
static int sub_params(mdl_model *mm, mdl_inode *k)
{
    const mdl_y_node *def = mdl_y_get(k->sub->def, "parameters");
    if (def && def->kind != MDL_Y_MAPPING)
        return mdl_fail(mm, def, k->sub->name, "parameters: expected a mapping name: default");
    /* keys of the entry other than type and for must be the subsystem's parameters */
    for (int i = 0; i < mdl_y_count(k->entry); i++) {
        const mdl_y_node *key = mdl_y_key(k->entry, i);
        if (!strcmp(key->text, "type") || !strcmp(key->text, "for")) continue;
        if (!mdl_y_get(def, key->text)) {
            int n = mdl_y_count(def);
            const char **cand = malloc((size_t)(n > 0 ? n : 1) * sizeof *cand);
            if (!cand) return BG_ERR_MEMORY;
            for (int j = 0; j < n; j++)
                cand[j] = mdl_y_key(def, j)->text;
            const char *near = mdl_nearest(key->text, cand, n);
            int r = mdl_fail(mm, key, k->dotpath, "subsystem '%s' has no parameter '%s'%s%s%s",
                             k->sub->name, key->text, *near ? " (did you mean '" : "", near,
                             *near ? "'?)" : "");
            free(cand);
            return r;
        }
    }
    for (int i = 0; i < mdl_y_count(def); i++) {
        const mdl_y_node *key = mdl_y_key(def, i);
        if (!is_word(key->text) || mdl_expr_is_reserved(key->text))
            return mdl_fail(mm, key, k->sub->name, "'%s' cannot name a parameter", key->text);
        char *sp = join(k->dotpath, ".", key->text);
        if (!sp) return BG_ERR_MEMORY;
        const char *set = set_for(mm, sp);
        free(sp);
        const mdl_y_node *given = mdl_y_get(k->entry, key->text);
        int r;
        if (set)
            r = mdl_scope_add(&k->scope, key->text, given ? given : mdl_y_value(def, i), set, &k->loop);
        else if (given)
            r = mdl_scope_add(&k->scope, key->text, given, NULL, &k->loop);
        else
            r = mdl_scope_add(&k->scope, key->text, mdl_y_value(def, i), NULL, &k->scope);
        if (r != BG_OK) return r;
    }
    return BG_OK;
}

static int make_kid(mdl_model *mm, mdl_inode *node, const mdl_y_node *key, const mdl_y_node *entry,
                    const char *name, const char *loopvar, long loopval, int depth)
{
    if (++mm->ninstances > MDL_MAX_INSTANCES)
        return mdl_fail(mm, key, node->dotpath, "more than %d instances: a model this large is "
                        "refused", MDL_MAX_INSTANCES);
    mdl_inode *k = calloc(1, sizeof *k);
    if (!k) return BG_ERR_MEMORY;
    k->inst.main = -1;
    int r = add_kid(node, k);
    if (r != BG_OK) {
        free(k);
        return r;
    }
    k->parent = node;
    k->entry = entry;
    k->key = key;
    k->name = strdup(name);
    k->path = join(node->path, "/", name);
    k->dotpath = join(node->dotpath, ".", name);
    if (!k->name || !k->path || !k->dotpath) return BG_ERR_MEMORY;
    k->loop.parent = &node->scope;
    k->scope.parent = &k->loop;
    if (loopvar) {
        char v[32];
        snprintf(v, sizeof v, "%ld", loopval);
        if ((r = mdl_scope_add(&k->loop, loopvar, NULL, NULL, NULL)) != BG_OK) return r;
        k->loop.vars[0].state = 2;
        k->loop.vars[0].value = (double)loopval;
    }
    const mdl_y_node *tn = mdl_y_get(entry, "type");
    k->type = mdl_type_find(tn->text);
    k->sub = k->type ? NULL : find_sub(mm, tn->text);
    if (!k->type && !k->sub) return unknown_type(mm, tn, k->dotpath, tn->text);
    if (k->type) { /* a leaf: its parameters are read when it is built (mdl_build.c) */
        k->comp = node->comp;
        for (int i = 0; i < mdl_y_count(entry); i++) {
            const mdl_y_node *pk = mdl_y_key(entry, i);
            if (!strcmp(pk->text, "type") || !strcmp(pk->text, "for")) continue;
            if (!mdl_type_param(k->type, pk->text)) {
                const char **cand = malloc((size_t)(k->type->nparams + 1) * sizeof *cand);
                if (!cand) return BG_ERR_MEMORY;
                for (int j = 0; j < k->type->nparams; j++)
                    cand[j] = k->type->params[j].name;
                const char *near = mdl_nearest(pk->text, cand, k->type->nparams);
                r = mdl_fail(mm, pk, k->dotpath, "type %s has no parameter '%s'%s%s%s (bgsim "
                             "--describe %s)", k->type->name, pk->text, *near ? " (did you mean '" : "",
                             near, *near ? "'?)" : "", k->type->name);
                free(cand);
                return r;
            }
        }
        return BG_OK;
    }
    /* a subsystem instance: never inside itself */
    for (mdl_inode *a = node; a; a = a->parent)
        if (a->sub == k->sub)
            return mdl_fail(mm, tn, k->dotpath, "subsystem '%s' contains itself", k->sub->name);
    if (depth > 32) return mdl_fail(mm, tn, k->dotpath, "subsystems nested more than 32 deep");
    k->comp = bgr_component(mm->m, node->comp, name);
    if (k->comp < 0) return mdl_fail(mm, key, k->dotpath, "%s", bgr_model_error(mm->m)->message);
    if ((r = sub_params(mm, k)) != BG_OK) return r;
    return expand_components(mm, k, mdl_y_get(k->sub->def, "components"), depth + 1);
}

static int expand_components(mdl_model *mm, mdl_inode *node, const mdl_y_node *comps, int depth)
{
    const char *where = node->parent ? node->dotpath : "components";
    if (!comps) return node->parent ? BG_OK : mdl_fail(mm, mm->root, "components", "missing");
    if (comps->kind != MDL_Y_MAPPING)
        return mdl_fail(mm, comps, where, "components: expected a mapping name: {type: ..., ...}");
    for (int i = 0; i < mdl_y_count(comps); i++) {
        const mdl_y_node *key = mdl_y_key(comps, i), *entry = mdl_y_value(comps, i);
        if (!is_word(key->text))
            return mdl_fail(mm, key, where, "'%s' is not a name ([A-Za-z_][A-Za-z0-9_]*)", key->text);
        if (entry->kind != MDL_Y_MAPPING || !mdl_y_get(entry, "type"))
            return mdl_fail(mm, entry, key->text, "expected a mapping with a type: {type: ..., ...}");
        const mdl_y_node *tn = mdl_y_get(entry, "type");
        if (tn->kind != MDL_Y_SCALAR)
            return mdl_fail(mm, tn, key->text, "type: expected a type's name");
        const mdl_y_node *forn = mdl_y_get(entry, "for");
        int r;
        if (!forn) {
            r = make_kid(mm, node, key, entry, key->text, NULL, 0, depth);
        } else {
            const char *var;
            long a, b;
            if ((r = mdl_read_for(mm, &node->scope, forn, key->text, &var, &a, &b)) != BG_OK) return r;
            for (long v = a; r == BG_OK && v <= b; v++) {
                char nm[160];
                snprintf(nm, sizeof nm, "%s[%ld]", key->text, v);
                r = make_kid(mm, node, key, entry, nm, var, v, depth);
            }
        }
        if (r != BG_OK) return r;
    }
    return BG_OK;
}

int mdl_expand(mdl_model *mm)
{
    mdl_inode *t = &mm->top;
    t->entry = mm->root;
    t->comp = 0;
    t->inst.main = -1;
    /* every model parameter, used or not, is evaluated: an error anywhere is found */
    for (int i = 0; i < t->scope.n; i++) {
        int r = mdl_var_eval(mm, &t->scope.vars[i], t->scope.vars[i].name);
        if (r != BG_OK) return r;
    }
    int r = expand_components(mm, t, mdl_y_get(mm->root, "components"), 0);
    if (r != BG_OK) return r;
    for (int i = 0; i < mm->nsets; i++)
        if (!mm->set_used[i] && !strchr(mm->sets[i].path, '.')) {
            const mdl_y_node *params = mdl_y_get(mm->root, "parameters");
            int n = mdl_y_count(params);
            const char **cand = malloc((size_t)(n > 0 ? n : 1) * sizeof *cand);
            if (!cand) return BG_ERR_MEMORY;
            for (int j = 0; j < n; j++)
                cand[j] = mdl_y_key(params, j)->text;
            const char *near = mdl_nearest(mm->sets[i].path, cand, n);
            r = mdl_fail(mm, NULL, "--set", "the model has no parameter '%s'%s%s%s", mm->sets[i].path,
                         *near ? " (did you mean '" : "", near, *near ? "'?)" : "");
            free(cand);
            return r;
        }
    return BG_OK;
}

/* ---- paths ---- */

static mdl_inode *kid_named(const mdl_inode *n, const char *name, size_t len)
{
    for (int i = 0; i < n->nkids; i++)
        if (strlen(n->kids[i]->name) == len && !strncmp(n->kids[i]->name, name, len)) return n->kids[i];
    return NULL;
}

int mdl_resolve(mdl_model *mm, mdl_inode *from, const char *path, const mdl_y_node *at,
                const char *where, mdl_inode **leaf, const char **rest)
{
    mdl_inode *cur = from;
    const char *p = path;
    *leaf = NULL;
    *rest = NULL;
    for (int hops = 0; hops < 64; hops++) {
        size_t len = strcspn(p, ".");
        if (cur->type) { /* a leaf: the rest names its port, signal or unknown */
            *leaf = cur;
            *rest = p;
            return BG_OK;
        }
        mdl_inode *k = kid_named(cur, p, len);
        if (!k && cur != from && cur->sub) {
            /* an exported name: ports or signals of the subsystem map it to an inner path */
            const char *sec[2] = {"ports", "signals"};
            for (int s = 0; s < 2 && !k; s++) {
                const mdl_y_node *ex = mdl_y_get(cur->sub->def, sec[s]);
                for (int i = 0; i < mdl_y_count(ex); i++) {
                    const mdl_y_node *key = mdl_y_key(ex, i), *val = mdl_y_value(ex, i);
                    if (strlen(key->text) != len || strncmp(key->text, p, len)) continue;
                    if (p[len])
                        return mdl_fail(mm, at, where, "'%s': '%.*s' is an outer %s of %s and ends "
                                        "the path", path, (int)len, p, s ? "signal" : "port", cur->dotpath);
                    if (val->kind != MDL_Y_SCALAR)
                        return mdl_fail(mm, val, cur->sub->name, "%s.%s: expected an inner path",
                                        sec[s], key->text);
                    return mdl_resolve(mm, cur, val->text, val, cur->sub->name, leaf, rest);
                }
            }
        }
        if (!k) {
            int n = cur->nkids;
            const char **cand = malloc((size_t)(n > 0 ? n : 1) * sizeof *cand);
            if (!cand) return BG_ERR_MEMORY;
            for (int i = 0; i < n; i++)
                cand[i] = cur->kids[i]->name;
            char name[160];
            snprintf(name, sizeof name, "%.*s", (int)(len < 159 ? len : 159), p);
            const char *near = mdl_nearest(name, cand, n);
            int r = mdl_fail(mm, at, where, "'%s': no component '%s' in %s%s%s%s", path, name,
                             cur->parent ? cur->dotpath : "the model", *near ? " (did you mean '" : "",
                             near, *near ? "'?)" : "");
            free(cand);
            return r;
        }
        cur = k;
        if (!p[len]) {
            *leaf = cur;
            *rest = NULL;
            return BG_OK;
        }
        p += len + 1;
    }
    return mdl_fail(mm, at, where, "'%s': the path goes round in circles through exported names", path);
}

static void free_node(mdl_inode *n)
{
    for (int i = 0; i < n->nkids; i++) {
        free_node(n->kids[i]);
        free(n->kids[i]);
    }
    free(n->kids);
    mdl_scope_clear(&n->loop);
    mdl_scope_clear(&n->scope);
    mdl_instance_clear(&n->inst);
    free(n->name);
    free(n->path);
    free(n->dotpath);
}

void mdl_tree_free(mdl_model *mm)
{
    free_node(&mm->top);
    memset(&mm->top, 0, sizeof mm->top);
}
