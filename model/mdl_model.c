/* Loading a model file in its stages (mdl_model.h) and the loaded model's accessors. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mdl_priv.h"

void mdl_free(mdl_model **pmm)
{
    if (!pmm || !*pmm) return;
    mdl_model *mm = *pmm;
    mdl_tree_free(mm);
    for (int i = 0; i < mm->nouts; i++) {
        free(mm->outs[i].name);
        mdl_expr_free(mm->outs[i].x);
    }
    free(mm->outs);
    for (int i = 0; i < mm->nonames; i++)
        free(mm->onames[i].name);
    free(mm->onames);
    free(mm->ohash);
    free(mm->bonds);
    for (int i = 0; i < mm->npend; i++)
        free(mm->pend[i].from), free(mm->pend[i].to);
    free(mm->pend);
    free(mm->leaves);
    free(mm->subs);
    for (int i = 0; i < mm->nsets; i++) {
        free((char *)mm->sets[i].path);
        free((char *)mm->sets[i].value);
    }
    free(mm->sets);
    free(mm->set_used);
    for (int i = 0; i < mm->ndocs; i++)
        mdl_y_free(mm->docs[i]);
    free(mm->docs);
    bgr_model_free(&mm->m);
    free(mm->file);
    free(mm->name);
    free(mm->text);
    free(mm);
    *pmm = NULL;
}

static char *read_all(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    size_t cap = 4096, n = 0;
    char *s = malloc(cap);
    while (s) {
        size_t k = fread(s + n, 1, cap - n - 1, f);
        n += k;
        if (n < cap - 1) break;
        char *t = cap < ((size_t)64 << 20) ? realloc(s, cap * 2) : NULL;
        if (!t) {
            free(s);
            s = NULL;
            break;
        }
        s = t;
        cap *= 2;
    }
    fclose(f);
    if (s) s[n] = 0;
    return s;
}

static mdl_model *load(const char *path, const char *text, const mdl_set *sets, int nsets,
                       bg_error *err)
{
    bg_error_clear(err);
    if (!path || nsets < 0 || (nsets > 0 && !sets)) {
        bg_error_raise(err, BG_ERR_ARGUMENT, "mdl_load", "no file, or replacements without a list");
        return NULL;
    }
    mdl_model *mm = calloc(1, sizeof *mm);
    if (!mm) {
        bg_error_raise(err, BG_ERR_MEMORY, "mdl_load", "out of memory");
        return NULL;
    }
    mm->err = err;
    mm->top.inst.main = -1;
    mm->file = strdup(path);
    mm->sets = calloc((size_t)(nsets ? nsets : 1), sizeof *mm->sets);
    mm->set_used = calloc((size_t)(nsets ? nsets : 1), sizeof *mm->set_used);
    int r = mm->file && mm->sets && mm->set_used ? BG_OK : BG_ERR_MEMORY;
    for (int i = 0; r == BG_OK && i < nsets; i++) {
        if (!sets[i].path || !sets[i].value) {
            r = bg_error_raise(err, BG_ERR_ARGUMENT, "mdl_load", "--set: replacement %d is empty", i);
            break;
        }
        mm->sets[i].path = strdup(sets[i].path);
        mm->sets[i].value = strdup(sets[i].value);
        mm->nsets = i + 1;
        if (!mm->sets[i].path || !mm->sets[i].value) r = BG_ERR_MEMORY;
    }
    if (r == BG_OK) {
        mm->text = text ? strdup(text) : read_all(path);
        if (!mm->text)
            r = text ? BG_ERR_MEMORY
                     : bg_error_raise(err, BG_ERR_IO, "mdl_load", "%s: cannot read the model file", path);
    }
    if (r == BG_OK) r = mdl_read_document(mm, path, mm->text);
    if (r == BG_OK) {
        mm->m = bgr_model_create(mm->name);
        if (!mm->m) r = BG_ERR_MEMORY;
    }
    if (r == BG_OK) r = mdl_read_solver(mm);
    if (r == BG_OK) r = mdl_expand(mm);
    if (r == BG_OK) r = mdl_build_all(mm);
    if (r == BG_OK) r = mdl_place_all(mm);
    if (r == BG_OK) r = mdl_read_initial(mm);
    if (r == BG_OK) r = mdl_read_outputs(mm);
    if (r == BG_OK) r = mdl_read_trim(mm);
    if (r != BG_OK) {
        if (r == BG_ERR_MEMORY && (!err || !err->message[0]))
            bg_error_raise(err, BG_ERR_MEMORY, "mdl_load", "out of memory");
        mdl_free(&mm);
        return NULL;
    }
    mm->err = NULL;
    return mm;
}

mdl_model *mdl_load(const char *path, const mdl_set *sets, int nsets, bg_error *err)
{
    return load(path, NULL, sets, nsets, err);
}

mdl_model *mdl_load_string(const char *text, const char *name, const mdl_set *sets, int nsets,
                           bg_error *err)
{
    if (!text) {
        bg_error_raise(err, BG_ERR_ARGUMENT, "mdl_load_string", "no text");
        return NULL;
    }
    return load(name ? name : "model", text, sets, nsets, err);
}

bgr_model *mdl_bgr(mdl_model *mm)
{
    return mm ? mm->m : NULL;
}

const char *mdl_name(const mdl_model *mm)
{
    return mm ? mm->name : NULL;
}

const char *mdl_file(const mdl_model *mm)
{
    return mm ? mm->file : NULL;
}

const mdl_solver_settings *mdl_solver(const mdl_model *mm)
{
    return mm ? &mm->solver : NULL;
}

int mdl_solver_override(mdl_model *mm, const mdl_solver_settings *s)
{
    if (!mm || !s) return BG_ERR_ARGUMENT;
    const double v[4] = {s->t_end, s->output_step, s->rtol, s->atol};
    for (int i = 0; i < 4; i++)
        if (!isfinite(v[i]) || !(v[i] > 0)) return BG_ERR_ARGUMENT;
    if (s->max_order < 1 || s->max_order > 5) return BG_ERR_ARGUMENT;
    mm->solver = *s;
    return BG_OK;
}

mdl_start mdl_start_kind(const mdl_model *mm)
{
    return mm ? mm->start : MDL_START_GIVEN;
}

int mdl_noutputs(const mdl_model *mm)
{
    return mm ? mm->nouts : 0;
}

const char *mdl_output_name(const mdl_model *mm, int i)
{
    return mm && i >= 0 && i < mm->nouts ? mm->outs[i].name : NULL;
}

int mdl_dae_options(const mdl_model *mm, dae_options *o, double **breakpoints)
{
    if (!mm || !o || !breakpoints) return BG_ERR_ARGUMENT;
    *breakpoints = NULL;
    int r = dae_options_default(o);
    if (r != BG_OK) return r;
    const mdl_solver_settings *s = &mm->solver;
    o->rtol = s->rtol;
    o->atol = s->atol;
    o->max_order = s->max_order;
    o->has_t_stop = 1;
    o->t_stop = s->t_end;
    o->exclude_alg = 1;
    o->projection = bgr_ninvariants(mm->m) > 0; /* the position invariants held (mech_parts.h) */
    o->stability_guard = s->stability_guard;
    o->newton_dgmax = s->newton_dgmax;
    o->newton_jac_age = s->newton_dgmax > 0 ? s->newton_jac_age : 0;
    o->newton_index2_scale_h = s->newton_index2_scale_h;
    int n = bgr_breakpoints(mm->m, 0.0, s->t_end, NULL, 0);
    if (n < 0) return n;
    if (n > 0) {
        double *bk = malloc((size_t)n * sizeof *bk);
        if (!bk) return BG_ERR_MEMORY;
        int k = bgr_breakpoints(mm->m, 0.0, s->t_end, bk, n);
        if (k < 0) {
            free(bk);
            return k;
        }
        *breakpoints = bk;
        o->breakpoints = bk;
        o->nbreakpoints = k < n ? k : n;
    }
    return BG_OK;
}

int mdl_dae_problem(mdl_model *mm, dae_problem *p)
{
    if (!mm || !p) return BG_ERR_ARGUMENT;
    int r = bgr_dae_problem(mm->m, p);
    if (r == BG_OK && !mm->solver.nominal_scales) p->nominal = NULL;
    return r;
}

int mdl_parameter(const mdl_model *mm, const char *name, double *value)
{
    if (!mm || !name || !value) return BG_ERR_ARGUMENT;
    for (int i = 0; i < mm->top.scope.n; i++) {
        const mdl_var *v = &mm->top.scope.vars[i];
        if (strcmp(v->name, name)) continue;
        if (v->state != 2 || v->len) return BG_ERR_ARGUMENT; /* not evaluated (unused) or a vector */
        *value = v->value;
        return BG_OK;
    }
    return BG_ERR_ARGUMENT;
}

int mdl_write_as_run(const mdl_model *mm, FILE *f)
{
    if (!mm || !f) return BG_ERR_ARGUMENT;
    fputs(mm->text, f);
    if (mm->text[0] && mm->text[strlen(mm->text) - 1] != '\n') fputc('\n', f);
    if (mm->nsets) fprintf(f, "# run with these replacements (bgsim --set):\n");
    for (int i = 0; i < mm->nsets; i++)
        fprintf(f, "#   %s = %s\n", mm->sets[i].path, mm->sets[i].value);
    return ferror(f) ? BG_ERR_IO : BG_OK;
}
