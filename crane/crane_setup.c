/* The solver options of a crane scene (crane_setup.h). */
#include "crane_setup.h"

#include <stdlib.h>

void crane_solver_settings(const crane_scene *s, dae_options *o)
{
    o->stability_guard = s->stability_guard;
    o->max_order = s->max_order;
    o->newton_dgmax = s->newton_dgmax;
    o->newton_jac_age = s->newton_dgmax > 0 ? s->newton_jac_age : 0; /* needs newton_dgmax */
    o->newton_index2_scale_h = s->newton_index2_scale_h;
}

/* The breakpoints are counted first (crane_breakpoints returns how many there are even when
 * fewer fit), then fetched into an array of that size: no bound, no truncation. */
int crane_solver_setup(const crane_scene *s, const crane *c, dae_options *o,
                       double **breakpoints_owned, bg_error *err)
{
    dae_options_default(o);
    o->rtol = s->rtol;
    o->atol = s->atol;
    o->has_t_stop = 1;
    o->t_stop = s->t_end;
    o->exclude_alg = 1;
    crane_solver_settings(s, o);
    o->breakpoints = NULL;
    o->nbreakpoints = 0;
    if (breakpoints_owned) *breakpoints_owned = NULL;
    if (!c || !breakpoints_owned) return BG_OK;
    double probe;
    int n = crane_breakpoints(c, &probe, 0);
    if (n <= 0) return BG_OK;
    double *bk = malloc((size_t)n * sizeof *bk);
    if (!bk) return bg_error_raise(err, BG_ERR_MEMORY, "crane_solver_setup", "out of memory");
    int got = crane_breakpoints(c, bk, n);
    if (got > n) got = n; /* the same reference: never more the second time */
    if (got < 0) got = 0;
    *breakpoints_owned = bk;
    o->breakpoints = bk;
    o->nbreakpoints = got;
    return BG_OK;
}
