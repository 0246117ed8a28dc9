/* crane --error-estimate (crane_program.h): the crane's part of the estimate the runner keeps
 * (rn_run.h, rn_estimate.c: the companion run at rtol / K, atol / K beside the dynamic run,
 * compared at every row, error_estimate.csv, the lines of status.txt and solver_stats.txt, the
 * summary's line). Here what is the crane's: the companion's outputs are crane_outputs of the
 * same model, and the summary's largest relative error is among the model's quantities. */
#include <string.h>

#include "crane_program.h"

/* The companion's outputs: crane_outputs of the same model. */
static void outputs(void *ctx, double t, const double *y, const double *yp, double *out)
{
    crane_outputs(ctx, t, y, yp, out);
}

/* Not the references (*_ref, exact functions of t), not the errors against them (*_err) nor the
 * joints' drift (constraint_drift), whose size is the error itself. */
static int ranked(const char *name)
{
    return !strstr(name, "_ref ") && !strstr(name, "_err ") && !strstr(name, "drift");
}

void cp_errest_open(cp_run *r, const dae_problem *p, const dae_options *dopt, const double *y0,
                    const double *yp0)
{
    rn_estimate_spec sp = {p, dopt, y0, yp0, crane_output_names, CRANE_NOUT, outputs, r->c, ranked};
    rn_estimate_open(&r->rn, &sp);
}
