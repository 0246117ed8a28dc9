/* The static start of a model file, with its trim condition (mdl_model.h: mdl_static).
 *
 * Without `trim:` the static start is bgr_static on the model as built. With it, a model
 * parameter p is adjusted until an output o at the static equilibrium equals a value v:
 * f(p) = o(equilibrium of the model built with p) - v = 0 on the bracket [a, b] the file gives,
 * by dae_trim_solve (bg_trim.h: the secant from the parameter's own value, then Illinois on the
 * bracket). The model is built again for every trial value (a parameter may change what is
 * built); the last one built is the answer's. The tolerance defaults to the solver's rtol times
 * max(1, |v|). A bracket whose ends give f of one sign is refused with both values, the
 * parameter, the output and the value named: the condition cannot be met there. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bg_trim.h"
#include "bgr_analysis.h"
#include "mdl_priv.h"

/* the equilibrium of mm: bgr_static; the output's value there (col < 0: none) */
static int equilibrium(mdl_model *mm, const dae_static_options *o, int col, double *value,
                       dae_static_result *res, bg_error *err)
{
    bgr_model *m = mdl_bgr(mm);
    int r = bgr_static(m, o, 0.0, res, err);
    if (r != BG_OK || col < 0) return r;
    int n = mdl_noutputs(mm);
    double *out = malloc((size_t)(n ? n : 1) * sizeof *out);
    if (!out) return BG_ERR_MEMORY;
    r = mdl_outputs(mm, 0.0, bgr_y0(m), out, err);
    *value = out[col];
    free(out);
    return r;
}

static int output_col(const mdl_model *mm, const char *name)
{
    for (int i = 0; i < mm->nouts; i++)
        if (!strcmp(mm->outs[i].name, name)) return i;
    return -1;
}

/* the model again with p = value (and the file's own replacements) */
static mdl_model *rebuild(const mdl_model *mm, const char *param, double value, bg_error *err)
{
    mdl_set *sets = malloc((size_t)(mm->nsets + 1) * sizeof *sets);
    if (!sets) {
        bg_error_raise(err, BG_ERR_MEMORY, "mdl_static", "out of memory");
        return NULL;
    }
    char v[64];
    snprintf(v, sizeof v, "%.17g", value);
    int n = 0;
    for (int i = 0; i < mm->nsets; i++)
        if (strcmp(mm->sets[i].path, param)) sets[n++] = mm->sets[i];
    sets[n++] = (mdl_set){param, v};
    mdl_model *nm = mdl_load_string(mm->text, mm->file, sets, n, err);
    free(sets);
    return nm;
}

/* what a trial of the trim needs, and the model its last trial built */
typedef struct trial_ctx {
    const mdl_model *mm;
    const char *param;
    int col;
    double want;
    const dae_static_options *o;
    mdl_model *last;
    mdl_trim_report *rep;
    int status; /* the last trial's */
} trial_ctx;

static int trial(void *ctx, double p, double *f, bg_error *err)
{
    trial_ctx *c = ctx;
    mdl_free(&c->last);
    if (!(c->last = rebuild(c->mm, c->param, p, err))) return BG_ERR_ARGUMENT;
    double v = NAN;
    int r = equilibrium(c->last, c->o, c->col, &v, &c->rep->last, err);
    c->rep->solves++;
    *f = v - c->want;
    return c->status = r;
}

int mdl_static(mdl_model **pmm, const dae_static_options *o, mdl_trim_report *rep, bg_error *err)
{
    if (!pmm || !*pmm) return BG_ERR_ARGUMENT;
    mdl_model *mm = *pmm;
    mdl_trim_report local;
    if (!rep) rep = &local;
    memset(rep, 0, sizeof *rep);
    const mdl_y_node *tr = mdl_y_get(mm->root, "trim");
    if (!tr) {
        rep->solves = 1;
        return equilibrium(mm, o, -1, NULL, &rep->last, err);
    }
    /* the trim's keys were checked by mdl_read_trim at load */
    const char *param = mdl_y_get(tr, "adjust")->text, *outname = mdl_y_get(tr, "until")->text;
    snprintf(rep->parameter, sizeof rep->parameter, "%s", param);
    snprintf(rep->output, sizeof rep->output, "%s", outname);
    rep->target = mm->trim_value;
    trial_ctx c = {mm, param, output_col(mm, outname), mm->trim_value, o, NULL, rep, BG_OK};
    dae_trim_options to = {NAN, mm->trim_lo, mm->trim_hi, mm->trim_tol};
    double v;
    if (mdl_parameter(mm, param, &v) == BG_OK) to.p0 = v;
    dae_trim_result res;
    int r = dae_trim_solve(trial, &c, &to, &res, err);
    rep->trimmed = 1;
    rep->value = res.p;
    rep->achieved = res.f + c.want;
    if (r == BG_OK) {
        mdl_free(pmm);
        *pmm = c.last;
        return BG_OK;
    }
    mdl_free(&c.last);
    if (c.status != BG_OK && err) { /* the static solve of the last trial failed: say that */
        char why[sizeof err->message];
        snprintf(why, sizeof why, "%s", err->message);
        return bg_error_raise(err, c.status, "mdl_static",
                              "trim: the static solve with %s = %.12g failed: %s", param, res.p,
                              why);
    }
    if (r != DAE_CONV_FAIL) return r;
    if (res.f_lo * res.f_hi > 0)
        return bg_error_raise(err, DAE_CONV_FAIL, "mdl_static",
                              "trim: %s goes from %.9g to %.9g as %s goes from %.9g to %.9g; %.9g "
                              "is not between them: the condition %s = %.9g cannot be met in that "
                              "bracket (trim.between)", outname, res.f_lo + c.want,
                              res.f_hi + c.want, param, to.lo, to.hi, c.want, outname, c.want);
    return bg_error_raise(err, DAE_CONV_FAIL, "mdl_static",
                          "trim: %s = %.9g is not reached within %.3g by adjusting %s (last "
                          "%.12g gives %.12g after %d static solves)", outname, c.want, to.tol,
                          param, res.p, res.f + c.want, rep->solves);
}

int mdl_read_trim(mdl_model *mm)
{
    const mdl_y_node *tr = mdl_y_get(mm->root, "trim");
    if (!tr) return BG_OK;
    static const char *const keys[] = {"adjust", "until", "equals", "between", "tolerance"};
    if (tr->kind != MDL_Y_MAPPING)
        return mdl_fail(mm, tr, "trim", "expected {adjust: PARAM, until: OUTPUT, equals: VALUE, "
                        "between: [a, b]}");
    int r = mdl_check_keys(mm, tr, "trim", keys, 5);
    if (r != BG_OK) return r;
    for (int i = 0; i < 4; i++)
        if (!mdl_y_get(tr, keys[i]) || mdl_y_get(tr, keys[i])->kind != (i == 3 ? MDL_Y_SEQUENCE : MDL_Y_SCALAR))
            return mdl_fail(mm, mdl_y_get(tr, keys[i]) ? mdl_y_get(tr, keys[i]) : tr, "trim",
                            "%s: expected %s", keys[i], i == 3 ? "[a, b]" : i == 2 ? "a value" : "a name");
    const mdl_y_node *adj = mdl_y_get(tr, "adjust"), *until = mdl_y_get(tr, "until");
    mdl_var *v = mdl_scope_find(&mm->top.scope, adj->text, 0);
    if (!v || v->len) return mdl_fail(mm, adj, "trim.adjust", "'%s' is not a number parameter of the model", adj->text);
    if (output_col(mm, until->text) < 0)
        return mdl_fail(mm, until, "trim.until", "'%s' is not one of the outputs", until->text);
    double *ab = NULL;
    int len;
    if ((r = mdl_eval_vector(mm, &mm->top.scope, mdl_y_get(tr, "between"), NULL, "trim.between", &ab, &len)) != BG_OK)
        return r;
    int ok = len == 2 && ab[0] < ab[1];
    if (ok) mm->trim_lo = ab[0], mm->trim_hi = ab[1];
    free(ab);
    if (!ok) return mdl_fail(mm, mdl_y_get(tr, "between"), "trim.between", "expected [a, b] with a < b");
    if ((r = mdl_eval_number(mm, &mm->top.scope, mdl_y_get(tr, "equals"), NULL, "trim.equals", &mm->trim_value)) != BG_OK)
        return r;
    mm->trim_tol = mm->solver.rtol * fmax(1, fabs(mm->trim_value));
    if (mdl_y_get(tr, "tolerance")) {
        if ((r = mdl_eval_number(mm, &mm->top.scope, mdl_y_get(tr, "tolerance"), NULL, "trim.tolerance", &mm->trim_tol)) != BG_OK)
            return r;
        if (!(mm->trim_tol > 0)) return mdl_fail(mm, mdl_y_get(tr, "tolerance"), "trim.tolerance", "expected > 0");
    }
    return BG_OK;
}
