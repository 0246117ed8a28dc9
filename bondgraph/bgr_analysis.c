/* Static equilibrium and modes of a compiled bond-graph model (bgr_analysis.h). */
#include "bgr_analysis.h"

#include <stdlib.h>
#include <string.h>

static int problem_of(bgr_model *m, dae_problem *p, const char *where, bg_error *err)
{
    if (!m) return bg_error_raise(err, BG_ERR_ARGUMENT, where, "the model is NULL");
    if (bgr_dae_problem(m, p) != BG_OK)
        return bg_error_raise(err, BG_ERR_STATE, where, "the model is not compiled");
    return BG_OK;
}

int bgr_static(bgr_model *m, const dae_static_options *o, double t, dae_static_result *res,
               bg_error *err)
{
    dae_problem p;
    int st = problem_of(m, &p, "bgr_static", err);
    if (st != BG_OK) return st;
    size_t sz = (size_t)p.n * sizeof(double);
    double *y = malloc(sz), *yp = malloc(sz);
    if (!y || !yp) {
        free(y);
        free(yp);
        return bg_error_raise(err, BG_ERR_MEMORY, "bgr_static", "out of memory");
    }
    memcpy(y, bgr_y0(m), sz);
    st = dae_static_solve(&p, o, t, y, yp, res, err);
    if (st == BG_OK) {
        memcpy(bgr_y0(m), y, sz);
        memcpy(bgr_yp0(m), yp, sz);
    } else if (st == DAE_CONV_FAIL || st == DAE_TOO_MUCH_WORK) {
        memcpy(bgr_y0(m), y, sz); /* the last state at rest, for a look at what went wrong */
    }
    free(y);
    free(yp);
    return st;
}

int bgr_modes(bgr_model *m, double t, const double *y, const double *yp,
              const dae_modes_options *o, dae_modes **out, bg_error *err)
{
    if (out) *out = NULL;
    dae_problem p;
    int st = problem_of(m, &p, "bgr_modes", err);
    if (st != BG_OK) return st;
    return dae_modes_compute(&p, t, y ? y : bgr_y0(m), yp, o, out, err);
}
