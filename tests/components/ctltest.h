/* Helpers of the controller tests (header-only, all static): a model file given as text, loaded
 * (mdl_load_string), run by the solver with the file's breakpoints, and its outputs read by
 * name. The numbers the tests compare against are derived in the tests. */
#ifndef CMP_TESTS_CTLTEST_H
#define CMP_TESTS_CTLTEST_H

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bg_dae.h"
#include "mdl_model.h"
#include "modeltest.h"
#include "tap.h"

typedef struct ctl_run {
    mdl_model *mm;
    dae_solver *s;
    double *y, *yp, *out, *bk;
    int n, nout;
} ctl_run;

TAP_UNUSED static void cr_close(ctl_run *r)
{
    dae_free(&r->s);
    mdl_free(&r->mm);
    free(r->y);
    free(r->yp);
    free(r->out);
    free(r->bk);
    memset(r, 0, sizeof *r);
}

/* Loads text and starts the solver at t = 0 with tolerances rtol, atol. 1 on success. */
TAP_UNUSED static int cr_open(ctl_run *r, const char *text, double rtol, double atol)
{
    memset(r, 0, sizeof *r);
    bg_error e;
    memset(&e, 0, sizeof e);
    r->mm = mdl_load_string(text, "test.yaml", NULL, 0, &e);
    if (!r->mm) {
        tap_diag("mdl_load_string: %s", e.message);
        return 0;
    }
    dae_options o;
    if (mdl_dae_options(r->mm, &o, &r->bk) != BG_OK) return 0;
    o.rtol = rtol;
    o.atol = atol;
    bgr_model *m = mdl_bgr(r->mm);
    r->s = model_solver(m, &o, NULL, 0.0);
    if (!r->s) return 0;
    r->n = bgr_nvars(m);
    r->nout = mdl_noutputs(r->mm);
    r->y = calloc((size_t)r->n, sizeof *r->y);
    r->yp = calloc((size_t)r->n, sizeof *r->yp);
    r->out = calloc((size_t)r->nout + 1, sizeof *r->out);
    return r->y && r->yp && r->out;
}

/* Integrates to t and evaluates the outputs there. 1 on success. */
TAP_UNUSED static int cr_to(ctl_run *r, double t)
{
    double tret;
    int st = dae_solve_to(r->s, t, &tret, r->y, r->yp);
    if (st < 0) {
        tap_diag("dae_solve_to(%g): %s: %s", t, dae_return_name(st), dae_get_error(r->s)->message);
        return 0;
    }
    bg_error e;
    memset(&e, 0, sizeof e);
    if (mdl_outputs(r->mm, t, r->y, r->out, &e) != BG_OK) {
        tap_diag("mdl_outputs: %s", e.message);
        return 0;
    }
    return 1;
}

/* The output named name at the last cr_to (NaN if there is none). */
TAP_UNUSED static double cr_out(const ctl_run *r, const char *name)
{
    for (int i = 0; i < r->nout; i++)
        if (!strcmp(mdl_output_name(r->mm, i), name)) return r->out[i];
    tap_diag("no output %s", name);
    return NAN;
}

#endif
