/* The static start of a model file, with its trim condition (mdl_model.h: mdl_static).
 *
 * Without `trim:` the static start is bgr_static on the model as built. With it, a model
 * parameter p is adjusted until an output o at the static equilibrium equals a value v:
 * f(p) = o(equilibrium of the model built with p) - v = 0 on the bracket [a, b] the file gives.
 * The model is built again for every trial value (a parameter may change what is built).
 * First the secant method from the parameter's own value (and a step of 1e-4 of the bracket
 * from it): a file states a value near the answer, and static solves near the answer are cheap
 * (they start close to rest). When a secant step leaves the bracket or 12 steps do not meet the
 * tolerance, the bracket itself is used: the Illinois variant of regula falsi (M. Dowell and
 * P. Jarratt, BIT 11 (1971) 168), the secant through the bracket's ends with the value at an
 * end that stays twice halved, which keeps the bracket and converges superlinearly. It stops
 * when |f| is within the tolerance (default: the solver's rtol times max(1, |v|)) or the
 * bracket is narrower than 1e-12 of its width. A bracket whose ends give f of one sign is
 * refused with both values, the parameter, the output and the value named: the condition
 * cannot be met there. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

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
    int col = output_col(mm, outname);
    double a = mm->trim_lo, b = mm->trim_hi, want = mm->trim_value, tol = mm->trim_tol;
    snprintf(rep->parameter, sizeof rep->parameter, "%s", param);
    snprintf(rep->output, sizeof rep->output, "%s", outname);
    rep->target = want;
    /* the secant from the file's own value */
    double p0 = (a + b) / 2, f0, f1, v;
    if (mdl_parameter(mm, param, &v) == BG_OK && v > a && v < b) p0 = v;
    double h = 1e-4 * (b - a), p1 = p0 + h <= b ? p0 + h : p0 - h;
    mdl_model *m0 = rebuild(mm, param, p0, err), *m1 = NULL;
    if (!m0) return BG_ERR_ARGUMENT;
    int r = equilibrium(m0, o, col, &v, &rep->last, err);
    rep->solves++;
    f0 = v - want;
    if (r == BG_OK && fabs(f0) <= tol) {
        m1 = m0, p1 = p0, f1 = f0;
    } else if (r == BG_OK) {
        for (int it = 0; it < 12; it++) {
            mdl_free(&m1);
            if (!(m1 = rebuild(mm, param, p1, err))) break;
            r = equilibrium(m1, o, col, &v, &rep->last, err);
            rep->solves++;
            f1 = v - want;
            if (r != BG_OK || fabs(f1) <= tol) break;
            double p2 = p1 - f1 * (p1 - p0) / (f1 - f0);
            if (!(p2 >= a && p2 <= b) || f1 == f0) break; /* out of the bracket: use it */
            mdl_free(&m0);
            m0 = m1, m1 = NULL;
            p0 = p1, f0 = f1, p1 = p2;
        }
    }
    if (m1 && r == BG_OK && fabs(f1) <= tol) {
        if (m0 != m1) mdl_free(&m0);
        rep->trimmed = 1;
        rep->value = p1;
        rep->achieved = f1 + want;
        mdl_free(pmm);
        *pmm = m1;
        return BG_OK;
    }
    if (m0 != m1) mdl_free(&m0);
    mdl_free(&m1);
    bg_error_clear(err);

    double fa, fb, va, vb;
    mdl_model *ma = rebuild(mm, param, a, err);
    if (!ma) return BG_ERR_ARGUMENT;
    r = equilibrium(ma, o, col, &va, &rep->last, err);
    rep->solves++;
    mdl_free(&ma);
    if (r != BG_OK) return r;
    mdl_model *mb = rebuild(mm, param, b, err);
    if (!mb) return BG_ERR_ARGUMENT;
    r = equilibrium(mb, o, col, &vb, &rep->last, err);
    rep->solves++;
    if (r != BG_OK) {
        mdl_free(&mb);
        return r;
    }
    fa = va - want;
    fb = vb - want;
    if (fa * fb > 0) {
        mdl_free(&mb);
        return bg_error_raise(err, DAE_CONV_FAIL, "mdl_static",
                              "trim: %s goes from %.9g to %.9g as %s goes from %.9g to %.9g; %.9g "
                              "is not between them: the condition %s = %.9g cannot be met in that "
                              "bracket (trim.between)", outname, va, vb, param, a, b, want, outname, want);
    }
    mdl_model *best = mb;
    double pbest = b, fbest = fb;
    for (int it = 0; it < 60 && fabs(fbest) > tol && fabs(b - a) > 1e-12 * fabs(mm->trim_hi - mm->trim_lo);
         it++) {
        double p = b - fb * (b - a) / (fb - fa);
        mdl_model *mp = rebuild(mm, param, p, err);
        if (!mp) {
            mdl_free(&best);
            return BG_ERR_ARGUMENT;
        }
        r = equilibrium(mp, o, col, &v, &rep->last, err);
        rep->solves++;
        if (r != BG_OK) {
            mdl_free(&mp);
            mdl_free(&best);
            return r;
        }
        double fp = v - want;
        if (fp * fb < 0) /* the root between p and b: the old b becomes the kept end */
            a = b, fa = fb;
        else /* the kept end a stays again: its value halved (Illinois) */
            fa /= 2;
        b = p, fb = fp;
        mdl_free(&best);
        best = mp, pbest = p, fbest = fp;
    }
    rep->trimmed = 1;
    rep->value = pbest;
    rep->achieved = fbest + want;
    if (fabs(fbest) > tol) {
        mdl_free(&best);
        return bg_error_raise(err, DAE_CONV_FAIL, "mdl_static",
                              "trim: %s = %.9g is not reached within %.3g by adjusting %s (last "
                              "%.12g gives %.12g after %d static solves)", outname, want, tol, param,
                              pbest, fbest + want, rep->solves);
    }
    mdl_free(pmm);
    *pmm = best;
    return BG_OK;
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
