/* The solver options of a crane scene, built in one place for every program that runs one (the
 * crane program's run, its --modes run, the bench's crane runs, the tests), so that each runs
 * the scene as the crane program does.
 *
 * crane_solver_setup fills, after dae_options_default:
 *   rtol, atol           the scene's [solver] rtol and atol (absolute tolerances in the units
 *                        of the problem: nominal scales, [solver] nominal_scales, are the
 *                        problem's own, crane_dae_problem, not options)
 *   has_t_stop, t_stop   1 and the scene's t_end
 *   breakpoints          every breakpoint of the reference in (0, t_end] (crane_breakpoints), in
 *                        an array allocated here without a bound (*breakpoints_owned, free());
 *                        none when c or breakpoints_owned is NULL
 *   exclude_alg          1: forces follow the states they are functions of; the index-2 policy
 *                        stays the default (DAE_I2_EXCLUDE)
 *   the scene's settings stability_guard, max_order, newton_dgmax, newton_jac_age (only with
 *                        newton_dgmax > 0, which it needs), newton_index2_scale_h
 *                        (crane_solver_settings)
 * A caller changes what it runs otherwise (t_stop of a shorter run, its own tolerances,
 * max_steps) afterwards; the breakpoints beyond its t_stop are then never reached. */
#ifndef CRANE_SETUP_H
#define CRANE_SETUP_H

#include "crane_model.h"

#ifdef __cplusplus
extern "C" {
#endif

/* BG_OK, or BG_ERR_MEMORY with err (o is then filled but for the breakpoints: none). */
int crane_solver_setup(const crane_scene *s, const crane *c, dae_options *o,
                       double **breakpoints_owned, bg_error *err);
/* The scene's solver settings alone into o (stability guard, Newton matrix refresh, index-2
 * scaling), the rest of o as it is. */
void crane_solver_settings(const crane_scene *s, dae_options *o);

#ifdef __cplusplus
}
#endif
#endif
