/* Static (equilibrium) solutions of DAEs F(t, y, y') = 0 of the integrator's form (bg_dae.h).
 *
 * What "at rest" means. An equilibrium is a state y with F(t, y, yp_s) = 0 where yp_s is zero
 * (the default: every differential unknown at rest) or a given vector of constant rates (steady
 * motion under constant prescribed rates: a shaft angle that grows at a constant speed while
 * everything else is at rest, options.yp_steady). For a model whose constraints hold at velocity
 * level (the joints of the mechanical components: v_A = v_B, not x_A = x_B; axial elements that
 * integrate their own stretch vector d' = v_B - v_A) the equations at rest do not determine the
 * state: with every velocity zero the constraint rows are satisfied whatever the positions, and
 * the positions of two bodies joined by a joint, or a member's d and its end points, are free
 * to drift apart. Such a model keeps invariants instead (x_A - x_B, d - (x_B - x_A), |q| of a
 * quaternion, an integrated angle against the body it measures): combinations of the rows of
 * dF/dy' whose rows of dF/dy vanish. The equilibrium sought is the one that keeps them at the
 * values of the starting state y (the model as assembled): momenta and velocities zero,
 * positions free but joined, constraint forces free.
 *
 * Method. Pseudo-transient continuation (Kelley and Keyes, SIAM J. Numer. Anal. 35 (1998) 508;
 * for DAEs Coffey, Kelley and Keyes, SIAM J. Sci. Comput. 25 (2003) 553) combined with load
 * continuation. Each step solves
 *     G(y) = F(t, y, yp_s + (y - y_prev)/H) - (1 - lambda) F(t, y_start, yp_s) = 0
 * by Newton's method: a backward-Euler step of pseudo-time H from the last accepted state, which
 * keeps every invariant of the kind above (exactly where it is linear, to second order in the
 * step's rotations otherwise) and makes the Newton matrix dF/dy + dF/dy'/H regular where dF/dy
 * alone is singular; and a Newton homotopy in the load factor lambda from 0 (y_start solves it)
 * to 1 (the equations themselves). For a structure assembled unstressed, F(t, y_start, yp_s) is
 * exactly minus the applied loads (gravity, forces of sources), so lambda is the load factor of
 * structural mechanics without any help from the model; a model that scales its own loads may
 * give a callback instead (options.load: then the offset term is dropped). lambda grows in steps
 * that adapt to the Newton iterations I of the last one (times sqrt(max_newton / I) within
 * [1/2, 2], Crisfield, Comput. Struct. 13 (1981) 55; not grown right after a rejection;
 * quartered after a failed one), each started from the secant predictor through the last two
 * states at rest (Allgower and Georg, Introduction to Numerical Continuation Methods, 2003,
 * sec. 2.2), and H grows by switched evolution relaxation (tenfold after an easy step) up to
 * options.h_max; once lambda = 1 the steps go on until a step changes the state by less than
 * the tolerance. A step is at rest when
 * the Newton correction towards the equilibrium at its load factor (y' = yp_s exactly) is small
 * against the step's change; beyond a limit point the pseudo-time steps would follow the motion
 * (the structure falls), so a step that ends moving is followed by up to 8 settling steps at the
 * same load factor and, still moving, is given up for a smaller increment from the last state at
 * rest: the load factor reached is that of the limit point. Each
 * Newton step is damped by the affine-invariant monotonicity test of Deuflhard (the next
 * simplified correction must be smaller than (1 - alpha/4) times the current one; alpha halved
 * down to 0.1 on a step the continuation can shrink, where a smaller increment is cheaper than a
 * long damped iteration, else down to 1e-4), so a large deflection is followed instead of jumped
 * over. Modified Newton: the factored matrix is kept across iterations and steps with the
 * integrator's refresh rules (formed again from the saved Jacobian when H has moved by more than
 * 30 % from the H it was factored with, CVODE's dgmax; the Jacobian evaluated again at the
 * current iterate when a kept matrix contracts at a rate worse than 0.5, would not converge
 * within the iteration budget at its rate, fails the damping test or follows a damped step), and
 * a fresh matrix at every iterate on a step without a predictor (the first, and continuation =
 * 0). An iteration may run past max_newton while its rate says it converges within
 * 2 max_newton; without continuation (nothing to shrink) the limits are five times larger. The
 * matrix is factored by the integrator's linear solvers (KLU by default); Jacobians come from
 * the problem's analytic ones, or coloured finite differences without them. The elastica (a
 * cantilever of 64 elements under a dead tip load P L^2 / EI = 10) takes 131 factorizations
 * (393 with a fresh matrix at every iteration and the earlier step rule), and continuation = 0
 * solves it up to P L^2 / EI = 3 (tests/components/mechanics/test_static_elastica.c).
 *
 * Nonlinear invariants. The backward-Euler steps keep linear invariants exactly and nonlinear
 * ones (a joint's closure through rotating bodies, the length of a pendulum held at velocity
 * level) to second order in each step's rotation: a structure loaded from its assembled state
 * (small rotations) keeps them, a pendulum started 40 degrees off its rest loses
 * 23 % of its length (tests/solver/test_static.c). Problems that declare their position
 * constraints (dae_problem.cons, ncons, cons_pattern) are projected back onto g(y) = g(y_start)
 * after every step (minimum-norm Gauss-Newton by CHOLMOD), which keeps them exactly.
 *
 * Tolerances: the weight of unknown i is rtol |y_i| + atol nominal_i (dae_problem.nominal, else
 * 1); a Newton iteration has converged when its correction is at most 1 in that weighted max
 * norm, the equilibrium when a step at lambda = 1 changes y by at most 1 too. The residual
 * reached is reported per equation in the same units: |F_i| divided by sum_j |M_ij| w_j, the
 * change of equation i when every unknown moves by its weight (an equation within 1 is satisfied
 * to the tolerance of its unknowns).
 *
 * Steady motion. Constant rates yp_s describe a steady motion only if the state stays a solution
 * along it (motion along ignorable coordinates: a shaft angle growing, a mass dragged at constant
 * speed through linear members). A structure spinning in the inertial frame has no such state
 * (its positions move along rotating directions, its velocities turn): the state found solves
 * F(t, y, yp_s) = 0 at one instant only, and is refused (BG_ERR_ARGUMENT naming the equation
 * that changes along the motion; bg_jaceval_steadiness, ratio above 1e-4; y holds it).
 *
 * Co-moving frames (options.frame = S, bg_modes.h "Co-moving frames"). The state sought is at
 * rest in the frame: y' = S y + c with c = options.yp_steady (NULL: 0), found as the state at rest
 * of the problem in the frame, G(t, z, z') = F(t, z, S z + c + z'), by the method above (its
 * pseudo-time steps are backward-Euler steps in the frame, its load factor ramps the centrifugal
 * loads with the others), then checked to stay a solution along the frame's flow (refused as
 * above, "the frame gives no steady motion": a load or support that does not turn with the
 * frame). yp receives S y + c. A spinning cantilever on a driven hub: the tension that stiffens it
 * and the root's centripetal force rho A Omega^2 L^2 / 2 (to the stretch, 1e-7;
 * tests/components/mechanics/test_modes_rotating.c). A relative equilibrium that is neutral along
 * the frame's motion (a free orbit: its phase drifts when its radius is perturbed) may not come
 * to rest in the pseudo-time steps when the model has algebraic unknowns: give its state
 * directly.
 *
 * Errors: BG_ERR_ARGUMENT (a NULL problem, y or result, n < 1, no residual, options out of
 * range, constant rates that give no steady motion (above), a nominal magnitude that is not finite
 * and > 0 (dae_create's rule): the message names them, the unknown by dae_problem.names),
 * BG_ERR_NONFINITE (a starting value of y not finite: the message names the unknown),
 * BG_ERR_PATTERN, BG_ERR_MEMORY, BG_ERR_SINGULAR (the Newton matrix is singular: the message names
 * the unknown of the singular column, which nothing determines at rest even with the pseudo-time
 * term: a mechanism or a free rigid motion under a load), BG_ERR_CALLBACK (the residual or Jacobian
 * returned < 0), DAE_CONV_FAIL (the continuation could not reach lambda = 1 or the equilibrium: the
 * message gives the load factor reached and names the equation with the largest scaled residual and
 * the unknown with the largest weighted Newton correction; res has them as indices; the message
 * says which of these stopped it: the load factor could not be raised even by dlambda_min (a limit
 * point, a mechanism, a part that cannot carry the load), the full load did not come to rest, or
 * continuation = 0 did not converge at once), DAE_TOO_MUCH_WORK (the budget of max_steps
 * continuation steps ran out: the message gives the counts and the load factor reached, and
 * blames nothing else). On failure y holds the last accepted state (the equilibrium under the
 * load factor res->lambda). The library never prints. */
#ifndef BG_STATIC_H
#define BG_STATIC_H

#include "bg_api.h"
#include "bg_dae.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The model's own load factor (options.load): scale every applied load (gravity, sources) by
 * lambda in [0, 1] for the residual calls that follow. 0 success, < 0 fatal. */
typedef int (*dae_load_fn)(void *user, double lambda);

typedef struct dae_static_options {
    double rtol;             /* default 1e-8 */
    double atol;             /* default 1e-8 (times the problem's nominal magnitudes) */
    int max_newton;          /* Newton iterations per step, 1 .. 10000, default 12 (up to
                                twice as many at a good rate; five times without continuation) */
    long max_steps;          /* continuation steps, default 400 */
    int continuation;        /* 1 (default): lambda from 0 to 1 in adaptive steps; 0: the full
                                load at once (pseudo-time steps only); no other value */
    double dlambda;          /* first load increment, default 1 (the whole load, quartered
                                until Newton converges) */
    double dlambda_min;      /* smallest increment before giving up, default 1e-5 */
    double h0;               /* first pseudo-time step, default 1e3 (the problem's time unit) */
    double h_max;            /* largest pseudo-time step, default 1e9 */
    const double *yp_steady; /* n constant rates (NULL: all zero) */
    dae_load_fn load;        /* NULL: the Newton homotopy above; a status other than 0 from
                                it stops the solve (BG_ERR_CALLBACK, naming it) */
    void *load_user;
    ls_kind linsol;          /* default LS_KLU */
    const sp_csc *frame;     /* NULL (default): at rest or constant rates yp_steady. Else the
                                generator S (n x n) of a co-moving frame (bg_modes.h): the state
                                sought is at rest in that frame, y' = S y + yp_steady (see
                                "Co-moving frames" above) */
} dae_static_options;

/* The defaults above; BG_OK, or BG_ERR_ARGUMENT if o is NULL. */
BG_API int dae_static_options_default(dae_static_options *o);

typedef struct dae_static_result {
    int status;          /* as returned */
    double lambda;       /* load factor reached (1 on success) */
    double residual;     /* largest scaled residual |F_i| / sum_j |M_ij| w_j at the end (see
                            above; <= 1: within the tolerance) */
    int residual_eq;     /* its equation (-1: none evaluated) */
    double residual_abs; /* |F_i| of that equation, in its own units */
    double correction;   /* weighted max norm of the last Newton correction */
    int worst_var;       /* unknown with the largest weighted correction in the last Newton
                            iteration (-1: none) */
    double change;       /* weighted max norm of the last accepted step's change */
    double h;            /* pseudo-time step of the last step */
    long steps, rejected, newton_iters, res_evals, jac_evals, factorizations;
    double seconds;      /* wall time */
} dae_static_result;

/* The equilibrium of p at time t, from y (n values: the starting state, the model as
 * assembled; the result on return). yp (may be NULL) receives yp_s (zeros by default). res may
 * be NULL; err receives the message (may be NULL). o NULL: the defaults. Returns BG_OK or an
 * error above. */
BG_API int dae_static_solve(const dae_problem *p, const dae_static_options *o, double t, double *y,
                            double *yp, dae_static_result *res, bg_error *err);

#ifdef __cplusplus
}
#endif
#endif
