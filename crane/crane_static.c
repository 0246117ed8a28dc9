/* The crane's static start and checks, equilibrium.csv, and its modes (crane_static.h). */
#include "bg_trim.h"
#include "crane_static.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "bgr_analysis.h"
#include "mech_axial.h"
#include "mech_parts.h"
#include "crane_model_impl.h"
#include "crane_setup.h"

/* ------------------------------------------------------------------ helpers ---- */

static void add_key(crane_start_report *rep, const char *key)
{
    if (strstr(rep->keys, key)) return;
    size_t l = strlen(rep->keys);
    snprintf(rep->keys + l, sizeof rep->keys - l, "%s%s", l ? ", " : "", key);
}

/* The scene keys of the part an unknown or equation belongs to (its path under crane/). */
static void keys_of_path(crane_start_report *rep, const crane_scene *s, const char *name)
{
    if (!name) return;
    if (strstr(name, "/ties")) {
        add_key(rep, "[ties] gantry_top");
        add_key(rep, "[ties] E");
        add_key(rep, "[ties] A");
    }
    if (strstr(name, "/boom")) {
        add_key(rep, "[boom] tip_radius");
        add_key(rep, "[boom] E");
        add_key(rep, "[boom] I_luff");
        if (s->ties) add_key(rep, "[ties] gantry_top");
    }
    if (strstr(name, "/rope") || strstr(name, "/load")) {
        add_key(rep, "[rope] length");
        add_key(rep, "[rope] E");
        add_key(rep, "[load] mass");
    }
    if (strstr(name, "/hydraulics")) {
        add_key(rep, "[hydraulics] bulk_modulus");
        add_key(rep, "[hydraulics] line_volume");
    }
    if (strstr(name, "/platform") || strstr(name, "/slewing") || strstr(name, "/base") ||
        strstr(name, "/counterweight")) {
        add_key(rep, "[platform] com");
        if (s->counterweight) add_key(rep, "[counterweight] mass");
    }
}

/* The tip's distance from the slewing axis at the state y. */
static double tip_radius_at(const crane *c, const double *y, double *tip, double *foot)
{
    const crane_scene *s = crane_get_scene(c);
    crane_tip_foot(c, y, tip, foot);
    return hypot(tip[0] - s->joint_A[0], tip[1] - s->joint_A[1]);
}

/* ------------------------------------------------------------ static start ---- */

static void checks(crane *c, crane_start_report *rep)
{
    const crane_scene *s = crane_get_scene(c);
    bgr_model *m = crane_model(c);
    const double *y = bgr_y0(m);
    double tip[3], foot[3];
    rep->radius = tip_radius_at(c, y, tip, foot);
    rep->tip_z = tip[2];
    rep->foot_z = foot[2];
    rep->ground_z = s->joint_A[2];
    crane_geom *g = malloc(sizeof *g);
    rep->straightness = NAN;
    rep->load_z = NAN;
    rep->tie_tension_min = NAN;
    if (g && crane_geometry(c, 0.0, y, NULL, g) == BG_OK) {
        double d[3] = {tip[0] - foot[0], tip[1] - foot[1], tip[2] - foot[2]};
        double L2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2], worst = 0;
        for (int k = 0; k < g->nodes; k++) {
            double p[3] = {g->node[k][0] - foot[0], g->node[k][1] - foot[1],
                           g->node[k][2] - foot[2]};
            double t = L2 > 0 ? (p[0] * d[0] + p[1] * d[1] + p[2] * d[2]) / L2 : 0;
            double q[3] = {p[0] - t * d[0], p[1] - t * d[1], p[2] - t * d[2]};
            worst = fmax(worst, sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]));
        }
        rep->straightness = worst;
        if (g->rope) rep->load_z = g->load[2];
        for (int k = 0; k < g->nties; k++)
            rep->tie_tension_min = k ? fmin(rep->tie_tension_min, g->tie_tension[k])
                                     : g->tie_tension[k];
    }
    free(g);
    rep->straightness_tol = 0.05 * s->boom_length;
    double T = NAN, V, U, out[CRANE_NOUT];
    crane_energy(c, y, &T, &V, &U);
    rep->kinetic = T;
    rep->kinetic_tol = 1e-6;
    double *yp = calloc((size_t)bgr_n(m), sizeof *yp);
    if (yp) {
        crane_outputs(c, 0.0, y, yp, out);
        rep->hinge_gap = out[CRANE_NOUT - 1];
        free(yp);
    }
    rep->ok_radius = fabs(rep->radius - rep->radius_want) <= rep->radius_tol;
    rep->ok_boom = rep->tip_z > rep->foot_z && rep->straightness <= rep->straightness_tol;
    rep->ok_load = !s->rope || rep->load_z > rep->ground_z;
    rep->ok_rest = rep->kinetic <= rep->kinetic_tol;
    /* in tension, or slack within the rounding of a tie's force (E A times one unit of
     * rounding of its strain: an unloaded crane, g = 0, leaves them at +-1e-18 N) */
    rep->ok_ties = !s->ties || rep->tie_tension_min > -DBL_EPSILON * s->tie_E * s->tie_A;
}

static void say(crane_start_report *rep, const char *fmt, double a, double b, double c2)
{
    size_t l = strlen(rep->message);
    if (l) l += (size_t)snprintf(rep->message + l, sizeof rep->message - l, "; ");
    if (l < sizeof rep->message)
        snprintf(rep->message + l, sizeof rep->message - l, fmt, a, b, c2);
}

/* One static solve of the crane built with tie length L0 (0: geometric) and the PID's
 * integral at I0; the crane built is kept (the last one is the start). */
typedef struct start_ctx {
    const crane_scene *sc;
    const dae_static_options *o;
    crane_start_report *rep;
    crane *cur;        /* the crane of the last solve, built with cur_L0 and cur_I0 */
    double cur_L0, cur_I0;
    double I0;
    int vI, vth;       /* the integral's and the platform angle's unknowns (-1: none) */
    int static_status; /* the last solve's */
} start_ctx;

/* the trim's bracket: the ties' unstretched length down to 1 % below the geometric one (a steel
 * tie breaks at about 1 % strain) */
#define TIE_STRAIN_MAX 1e-2

static int solve_at(start_ctx *x, double L0, bg_error *serr)
{
    /* the same crane solved again gives the same state: the last solve's (the trim's first
     * trial repeats the integral's last solve) */
    if (x->cur && x->static_status == BG_OK && L0 == x->cur_L0 && x->I0 == x->cur_I0)
        return BG_OK;
    crane_free(&x->cur);
    x->cur_L0 = L0, x->cur_I0 = x->I0;
    bg_error berr = {0};
    x->cur = crane_build_ties(x->sc, L0, &berr);
    if (!x->cur) {
        *serr = berr;
        return x->static_status = berr.status < 0 ? berr.status : BG_ERR_ARGUMENT;
    }
    bgr_model *mc = crane_model(x->cur);
    x->vI = bgr_find_var(mc, "crane/hydraulics/pid/integral");
    x->vth = bgr_find_var(mc, "crane/platform_sensor/angle");
    if (x->vI >= 0) bgr_y0(mc)[x->vI] = x->I0;
    bg_error_clear(serr);
    x->rep->solves++;
    return x->static_status = bgr_static(mc, x->o, 0.0, &x->rep->solve, serr);
}

/* the trim's condition: the tip's radius at the equilibrium minus the scene's */
static int trial(void *ctx, double L0, double *f, bg_error *serr)
{
    start_ctx *x = ctx;
    int st = solve_at(x, L0, serr);
    if (st != BG_OK) return st;
    double tip[3], foot[3];
    *f = tip_radius_at(x->cur, bgr_y0(crane_model(x->cur)), tip, foot) - x->sc->boom_tip_radius;
    return BG_OK;
}

/* A weightless load (crane_load_weightless, crane_static_start): the crane with the rope and
 * the load, in the state of the crane without them (every unknown the two share, by name), the
 * load at rest below the tip where the rope's smoothed force k eps log(1 + e^(x / eps)) equals
 * its weight W (x = eps log(expm1(W / (k eps))): a 1e-300 kg load hangs on a rope slack by
 * about 700 eps), or, weightless (g = 0), where that force is the rounding of the rope's force
 * at rest length, DBL_EPSILON k eps (slack by eps log(1 / DBL_EPSILON), about 36 eps). NULL if
 * the crane cannot be built (err says why). */
static crane *hang_weightless_load(const crane_scene *sc, double tie_L0, const crane *bare,
                                   bg_error *err)
{
    crane *full = crane_build_ties(sc, tie_L0, err);
    if (!full) return NULL;
    bgr_model *mf = crane_model(full);
    const bgr_model *mb = crane_model((crane *)bare);
    const double *yb = bgr_y0((bgr_model *)mb), *ypb = bgr_yp0((bgr_model *)mb);
    double *yf = bgr_y0(mf), *ypf = bgr_yp0(mf);
    for (int i = 0; i < bgr_n(mb); i++) {
        int j = bgr_find_var(mf, bgr_var_name(mb, i));
        if (j >= 0) yf[j] = yb[i], ypf[j] = ypb[i];
    }
    double tip[3], foot[3], load[3];
    crane_tip_foot(full, yf, tip, foot);
    const double eps = 1e-4 * sc->rope_length; /* mech_rope's default width */
    const double keps = sc->rope_E * sc->rope_A * 1e-4, W = sc->load_mass * fabs(sc->g);
    double x = W > 0 ? eps * log(expm1(W / keps)) : -INFINITY;
    if (!isfinite(x)) x = eps * log(DBL_EPSILON); /* g = 0 (or W / (k eps) underflows) */
    memcpy(load, tip, sizeof load);
    load[2] -= sc->rope_length + x;
    if (mech_axial_set(mf, full->rope, tip, load) != BG_OK ||
        mech_point_mass_set(mf, full->load, load, NULL) != BG_OK) {
        crane_free(&full);
        bg_error_raise(err, BG_ERR_ARGUMENT, "crane_static_start", "the load could not be hung");
        return NULL;
    }
    return full;
}

int crane_static_start(crane *c, crane_start_report *rep_out, bg_error *err)
{
    crane_start_report rl;
    crane_start_report *rep = rep_out ? rep_out : &rl;
    memset(rep, 0, sizeof *rep);
    if (!c) return bg_error_raise(err, BG_ERR_ARGUMENT, "crane_static_start", "no crane");
    const crane_scene *s = crane_get_scene(c);
    crane_scene sc = *s; /* c is replaced below */
    const double R = sc.boom_tip_radius;
    /* A load whose weight is below the rounding of the rope's force at its rest length
     * (crane_load_weightless: the tension-only rope is smoothed at slack, mech_axial.h: k eps
     * ln 2 there, eps = 1e-4 L0, decaying as k eps e^(x / eps) when slack by x) hangs where that
     * force equals its weight, at a stiffness lost in the rounding, or (g = 0) nowhere: no
     * static solve finds it. It carries nothing, so the crane is brought to rest without the
     * rope and the load, which are then hung on it at rest (hang_weightless_load). */
    const int weightless = crane_load_weightless(&sc);
    crane_scene bare = sc;
    if (weightless) bare.rope = 0;
    rep->radius_want = R;
    rep->radius_tol = 1e-6 * fmax(R, 1.0);
    rep->tie_L0_geometric = rep->tie_L0 = crane_tie_length(c);
    struct timespec t0, t1;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    dae_static_options o;
    dae_static_options_default(&o);
    o.max_steps = 150; /* a crane that can stand needs 3 to 10; a failure is known by then */
    start_ctx sx = {&bare, &o, rep, NULL, 0.0, 0.0, 0.0, -1, -1, BG_OK};
    bg_error serr = {0};
    int st = BG_OK, tie_fail = 0;
    /* The drive holds the platform through the PID's integral, whose state and the platform's
     * angle keep their sum (both integrate the same rate): at rest the integral supplies the
     * leakage flow, so a start from zero would leave the platform a fraction of a microradian
     * off theta = 0. The integral starts instead from the holding value: solves at the
     * geometric tie length, each restarting the integral from the last one's value (a bumpless
     * start), until the platform rests at theta = 0 (crane/models/paper.yaml states the value
     * found, pid_integral0). */
    const double Lg = rep->tie_L0;
    for (int it = 0; it < 12; it++) {
        double I_in = sx.I0;
        st = solve_at(&sx, sc.ties ? Lg : 0.0, &serr);
        if (st != BG_OK || sx.vI < 0 || sx.vth < 0) break;
        const double *yc = bgr_y0(crane_model(sx.cur));
        if (fabs(yc[sx.vth]) <= 1e-12) {
            sx.I0 = I_in;
            break;
        }
        sx.I0 = yc[sx.vI];
    }
    /* The ties' unstretched length until the tip stands at the radius: the trim of the model
     * files (bg_trim.h: the secant from the geometric length, then Illinois on the bracket),
     * each trial a static solve of the crane built with that length, the integral held */
    if (st == BG_OK && sc.ties) {
        dae_trim_options to = {Lg, (1 - TIE_STRAIN_MAX) * Lg, Lg, 1e-9 * fmax(R, 1.0)};
        dae_trim_result tres;
        int tr = dae_trim_solve(trial, &sx, &to, &tres, &serr);
        if (tr != BG_OK && sx.static_status == BG_OK) tie_fail = 1; /* the radius not met */
        st = sx.static_status;
        rep->tie_L0 = tres.p;
    }
    rep->pid_integral0 = sx.I0;
    crane *cur = sx.cur;
    if (weightless && st == BG_OK) {
        cur = hang_weightless_load(&sc, sx.cur_L0, sx.cur, &serr);
        crane_free(&sx.cur);
        if (!cur) st = serr.status < 0 ? serr.status : BG_ERR_ARGUMENT;
    }
    if (st != BG_OK && st != DAE_CONV_FAIL && st != DAE_TOO_MUCH_WORK && st != BG_ERR_SINGULAR) {
        crane_free(&cur);
        return bg_error_raise(err, st, "crane_static_start", "static equilibrium: %s",
                              serr.message);
    }
    /* the state reached (the equilibrium, or the last state at rest) becomes the model's */
    crane_replace(c, &cur);
    crane_set_reference_tip(c);
    rep->ok_solve = st == BG_OK;
    checks(c, rep);
    clock_gettime(CLOCK_MONOTONIC, &t1);
    rep->seconds = (double)(t1.tv_sec - t0.tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0.tv_nsec);
    /* the verdict */
    bgr_model *m = crane_model(c);
    if (!sc.ties && (!rep->ok_solve || !rep->ok_boom || !rep->ok_radius)) {
        add_key(rep, "[ties] enabled");
        add_key(rep, "[boom] tip_radius");
        add_key(rep, "[environment] g");
        say(rep, "nothing holds the boom up without ties", 0, 0, 0);
    }
    if (!rep->ok_solve) {
        /* the ties' moment about the hinge against that of the weights (luffing plane): a tie
         * anchor behind the boom pulls the tip back; one in front or on the boom's line cannot
         * hold it */
        if (sc.ties) {
            double tip[3], foot[3];
            crane *g0 = crane_build_ties(&sc, 0.0, NULL);
            if (g0) {
                crane_tip_foot(g0, bgr_y0(crane_model(g0)), tip, foot);
                crane_free(&g0);
                double gx = sc.gantry_top[0], gz = sc.gantry_top[2];
                double ux = gx - tip[0], uz = gz - tip[2], lu = hypot(ux, uz);
                double rx = tip[0] - sc.boom_foot[0], rz = tip[2] - sc.boom_foot[2];
                /* y-moments about B: tie r x u (per unit tension), weight r x (0, 0, -1) */
                double mt = lu > 0 ? (rz * ux - rx * uz) / lu : 0, mw = rx;
                if (!(mt * mw < 0) || fabs(mt) < 0.01 * sc.boom_length) {
                    add_key(rep, "[ties] gantry_top");
                    add_key(rep, "[boom] tip_radius");
                    say(rep, "the ties cannot hold the boom: their moment arm about the hinge is "
                             "%.3g m ",
                        fabs(mt), 0, 0);
                    size_t l = strlen(rep->message);
                    snprintf(rep->message + l, sizeof rep->message - l, "%s",
                             mt * mw < 0 ? "(too short)"
                                         : "on the side of the load (they pull the tip over)");
                }
            }
        }
        if (sc.ties) {
            add_key(rep, "[ties] gantry_top");
            add_key(rep, "[ties] E");
        }
        add_key(rep, "[boom] E");
        add_key(rep, "[boom] I_luff");
        /* the part whose equation is out of balance (the unknown with the largest correction
         * is mostly whatever moves most, the load or the drive) */
        const char *e = rep->solve.residual_eq >= 0 ? bgr_eq_name(m, rep->solve.residual_eq)
                                                    : NULL;
        keys_of_path(rep, &sc, e);
        add_key(rep, "[environment] g");
        if (sc.rope) add_key(rep, "[load] mass");
        if (rep->solve.lambda >= 1)
            say(rep, "no static equilibrium: the solve reached the full load but did not "
                     "converge there",
                0, 0, 0);
        else
            say(rep, "no static equilibrium: the structure carries only %.3g of the scene's loads",
                rep->solve.lambda, 0, 0);
        size_t l = strlen(rep->message);
        snprintf(rep->message + l, sizeof rep->message - l, " (%s)", serr.message);
    } else {
        if (tie_fail || !rep->ok_radius) {
            add_key(rep, "[boom] tip_radius");
            if (sc.ties) {
                add_key(rep, "[ties] gantry_top");
                add_key(rep, "[ties] E");
            }
            if (sc.rope) add_key(rep, "[load] mass");
            /* the radius is measured from the slewing axis, through joint A */
            if (sc.joint_A[0] != 0 || sc.joint_A[1] != 0) add_key(rep, "[platform] joint_A");
            say(rep, "the tip is at %.6g m from the axis, not at the radius %.6g m (within %.2g m)",
                rep->radius, R, rep->radius_tol);
            if (tie_fail && sc.ties) {
                size_t l = strlen(rep->message);
                snprintf(rep->message + l, sizeof rep->message - l,
                         " for any unstretched tie length from %.6g m to the geometric %.6g m",
                         (1 - TIE_STRAIN_MAX) * rep->tie_L0_geometric, rep->tie_L0_geometric);
            }
        }
        if (!rep->ok_boom) {
            add_key(rep, "[boom] tip_radius");
            add_key(rep, "[boom] E");
            add_key(rep, "[boom] I_luff");
            if (sc.ties) add_key(rep, "[ties] gantry_top");
            if (sc.rope) add_key(rep, "[load] mass");
            if (!(rep->tip_z > rep->foot_z))
                say(rep, "the boom hangs below its foot (tip at z = %.4g m, foot at z = %.4g m)",
                    rep->tip_z, rep->foot_z, 0);
            else
                say(rep, "the boom is not straight: a node %.4g m off the line foot-tip (at most "
                         "%.4g m, 5 %% of the length: buckled)",
                    rep->straightness, rep->straightness_tol, 0);
        }
        if (!rep->ok_load) {
            /* the rope's strain at rest: beyond 5 % (steel breaks at about 1 %) the rope's
             * stiffness is what is wrong, not the geometry */
            double hang = rep->tip_z - rep->load_z, strain = hang / sc.rope_length - 1;
            if (strain > 0.05) {
                add_key(rep, "[rope] A");
                add_key(rep, "[rope] E");
                add_key(rep, "[load] mass");
                say(rep, "the rope stretches to %.4g m (unstretched %.4g m, strain %.3g)", hang,
                    sc.rope_length, strain);
                say(rep, "the load hangs at z = %.4g m, below the ground (z = %.4g m at the slewing "
                         "joint)",
                    rep->load_z, rep->ground_z, 0);
            } else {
                add_key(rep, "[rope] length");
                add_key(rep, "[boom] length");
                add_key(rep, "[boom] tip_radius");
                add_key(rep, "[platform] joint_A"); /* the ground's height */
                say(rep, "the load hangs at z = %.4g m, below the ground (z = %.4g m at the slewing "
                         "joint)",
                    rep->load_z, rep->ground_z, 0);
            }
        }
        if (!rep->ok_ties) {
            add_key(rep, "[ties] gantry_top");
            add_key(rep, "[boom] tip_radius");
            say(rep, "the ties push instead of pulling (tension %.4g N): anchored there they are "
                     "struts, not ties",
                rep->tie_tension_min, 0, 0);
        }
        if (!rep->ok_rest) {
            add_key(rep, "[environment] g");
            say(rep, "the bodies are not at rest (kinetic energy %.3g J, at most %.3g J)",
                rep->kinetic, rep->kinetic_tol, 0);
        }
    }
    rep->ok = rep->ok_solve && rep->ok_radius && rep->ok_boom && rep->ok_load && rep->ok_rest &&
              rep->ok_ties;
    if (!rep->ok)
        return bg_error_raise(err, CRANE_ERR_START, "crane_static_start",
                              "scene %s: the keys %s cannot be met together: %s", sc.name,
                              rep->keys, rep->message);
    return BG_OK;
}

int crane_settle(crane *c, bg_error *err)
{
    return crane_static_start(c, NULL, err);
}

int crane_start_print(const crane_start_report *r, FILE *f)
{
    const char *ok[2] = {"FAILED", "ok"};
    fprintf(f, "static start: %s\n", r->ok ? "verified" : "FAILED");
    fprintf(f, "  static solves                       %d in %.3f s (the integral's, then the "
               "trim's)\n", r->solves, r->seconds);
    fprintf(f, "  last solve: load factor %.6g, %ld steps (%ld rejected), %ld Newton iterations, "
               "scaled residual %.3g\n",
            r->solve.lambda, r->solve.steps, r->solve.rejected, r->solve.newton_iters,
            r->solve.residual);
    fprintf(f, "  ties' unstretched length            %.9g m (geometric %.9g m)\n", r->tie_L0,
            r->tie_L0_geometric);
    fprintf(f, "  PID's holding integral              %.17g rad\n", r->pid_integral0);
    fprintf(f, "checks:\n");
    fprintf(f, "  %-6s the static solve reached the full load and rest\n", ok[r->ok_solve]);
    fprintf(f, "  %-6s tip at the scene's radius: %.9g m, wanted %.9g m within %.3g m\n",
            ok[r->ok_radius], r->radius, r->radius_want, r->radius_tol);
    fprintf(f, "  %-6s boom above its foot: tip at z = %.6g m, foot at z = %.6g m; straight: "
               "nodes within %.3g m of the line foot-tip (at most %.3g m)\n",
            ok[r->ok_boom], r->tip_z, r->foot_z, r->straightness, r->straightness_tol);
    fprintf(f, "  %-6s load above the ground: z = %.6g m, ground (slewing joint) at z = %.6g m\n",
            ok[r->ok_load], r->load_z, r->ground_z);
    fprintf(f, "  %-6s every body at rest: kinetic energy %.3g J (at most %.3g J)\n",
            ok[r->ok_rest], r->kinetic, r->kinetic_tol);
    if (isfinite(r->tie_tension_min))
        fprintf(f, "  %-6s ties in tension: %.6g N (the smaller)\n", ok[r->ok_ties],
                r->tie_tension_min);
    fprintf(f, "  (the hinge's position mismatch: %.3g m)\n", r->hinge_gap);
    if (!r->ok) fprintf(f, "keys that cannot be met together: %s\nwhy: %s\n", r->keys, r->message);
    return ferror(f) ? BG_ERR_IO : BG_OK;
}

/* ------------------------------------------------------------ equilibrium ---- */

static void row3(FILE *f, const char *name, const double *p, double value, const char *unit)
{
    fprintf(f, "%s,%.10g,%.10g,%.10g,", name, p[0], p[1], p[2]);
    if (isfinite(value))
        fprintf(f, "%.10g,%s\n", value, unit);
    else
        fprintf(f, ",%s\n", unit);
}

static void row1(FILE *f, const char *name, double value, const char *unit)
{
    fprintf(f, "%s,,,,%.10g,%s\n", name, value, unit);
}

/* A bond's six efforts by name: force and moment. 0 if absent. */
static int bond6(const bgr_model *m, const double *y, const char *bond, double *F, double *M)
{
    char nm[128];
    for (int i = 0; i < 6; i++) {
        snprintf(nm, sizeof nm, "crane/%s/e%d", bond, i);
        int v = bgr_find_var(m, nm);
        if (v < 0) return 0;
        (i < 3 ? F : M)[i % 3] = y[v];
    }
    return 1;
}

int crane_equilibrium_write(const crane *c, const crane_start_report *rep, FILE *f)
{
    const crane_scene *s = crane_get_scene(c);
    bgr_model *m = crane_model((crane *)c);
    const double *y = bgr_y0(m);
    crane_geom *g = malloc(sizeof *g);
    if (!g || crane_geometry(c, 0.0, y, NULL, g) != BG_OK) {
        free(g);
        return BG_ERR_ARGUMENT;
    }
    fprintf(f, "name,x [m],y [m],z [m],value,unit\n");
    char nm[64];
    /* positions */
    row3(f, "platform_com", g->platform_x, NAN, "m");
    row3(f, "boom_hinge", g->hinge, NAN, "m");
    for (int k = 0; k < g->ngantry; k++) {
        snprintf(nm, sizeof nm, g->ngantry == 2 ? (k ? "gantry_right" : "gantry_left") : "gantry");
        row3(f, nm, g->gantry[k], NAN, "m");
    }
    for (int k = 0; k < g->nodes; k++) {
        snprintf(nm, sizeof nm, "boom_node%02d", k);
        double p = hypot(g->node[k][0] - s->joint_A[0], g->node[k][1] - s->joint_A[1]);
        row3(f, nm, g->node[k], p, "m (position; value: distance from the slewing axis)");
    }
    row3(f, "boom_tip", g->node[g->nodes - 1], rep ? rep->radius : NAN,
         "m (value: the tip's radius)");
    if (g->rope) row3(f, "load", g->load, g->load_mass, "m (value: mass in kg)");
    if (g->counterweight) row3(f, "counterweight", g->cw, g->cw_mass, "m (value: mass in kg)");
    /* tensions */
    if (g->rope) row1(f, "rope_tension", g->rope_tension, "N");
    for (int k = 0; k < g->nties; k++)
        row1(f, g->nties == 2 ? (k ? "tie_right_tension" : "tie_left_tension") : "tie_tension",
             g->tie_tension[k], "N");
    /* support forces */
    double F[3], M[3];
    if (bond6(m, y, "b_base", F, M)) {
        row3(f, "base_force_on_crane", F, sqrt(F[0] * F[0] + F[1] * F[1] + F[2] * F[2]), "N");
        row3(f, "base_moment_on_crane", M, sqrt(M[0] * M[0] + M[1] * M[1] + M[2] * M[2]), "N m");
    }
    if (bond6(m, y, "b_hinge_b", F, M)) {
        row3(f, "hinge_force_on_boom", F, sqrt(F[0] * F[0] + F[1] * F[1] + F[2] * F[2]), "N");
        row3(f, "hinge_moment_on_boom", M, sqrt(M[0] * M[0] + M[1] * M[1] + M[2] * M[2]), "N m");
    }
    if (g->beam) {
        row3(f, "boom_section_force_foot", g->force_local[0], NAN,
             "N (along the boom (tension > 0), in the luffing plane, sideways)");
        row3(f, "boom_section_moment_foot", g->moment_local[0], NAN, "N m (boom axes)");
    }
    /* drive */
    if (isfinite(g->p_high)) {
        row1(f, "p_high", g->p_high, "Pa");
        row1(f, "p_low", g->p_low, "Pa");
        row1(f, "pump_x", g->pump_x, "-");
    }
    row1(f, "theta", g->theta, "rad");
    if (rep) {
        row1(f, "tie_unstretched_length", rep->tie_L0, "m");
        row1(f, "kinetic_energy", rep->kinetic, "J");
        row1(f, "hinge_position_mismatch", rep->hinge_gap, "m");
        row1(f, "static_residual", rep->solve.residual, "tolerance units");
    }
    free(g);
    return ferror(f) ? BG_ERR_IO : BG_OK;
}

/* ------------------------------------------------------------------ modes ---- */

int crane_modes(crane *c, double T, dae_modes **out, double *yout, bg_error *err)
{
    if (out) *out = NULL;
    if (!c || !out || !(T >= 0))
        return bg_error_raise(err, BG_ERR_ARGUMENT, "crane_modes", "bad arguments (T = %g)", T);
    const crane_scene *s = crane_get_scene(c);
    bgr_model *m = crane_model(c);
    dae_problem p;
    if (bgr_dae_problem(m, &p) != BG_OK)
        return bg_error_raise(err, BG_ERR_STATE, "crane_modes", "model not compiled");
    int n = p.n, st = BG_OK;
    double *y = malloc((size_t)n * sizeof *y), *yp = calloc((size_t)n, sizeof *yp);
    if (!y || !yp) {
        free(y);
        free(yp);
        return bg_error_raise(err, BG_ERR_MEMORY, "crane_modes", "out of memory");
    }
    memcpy(y, bgr_y0(m), (size_t)n * sizeof *y);
    if (T > 0) { /* the dynamic run to T, as the crane program sets it up */
        double *bk = NULL;
        dae_options o;
        st = crane_solver_setup(s, c, &o, &bk, err);
        o.t_stop = T;
        o.max_steps = 100000000;
        dae_solver *sol = st == BG_OK ? dae_create(&p, &o, err) : NULL;
        double tr;
        if (!sol) {
            st = err && err->status < 0 ? err->status : BG_ERR_ARGUMENT;
        } else if ((st = dae_init(sol, 0.0, bgr_y0(m), bgr_yp0(m))) != BG_OK ||
                   (st = dae_consistent_init(sol)) < 0 ||
                   (st = dae_solve_to(sol, T, &tr, y, yp)) < 0) {
            bg_error_raise(err, st < 0 ? st : BG_ERR_ARGUMENT, "crane_modes",
                           "the run to t = %g: %s", T, dae_get_error(sol)->message);
            st = st < 0 ? st : BG_ERR_ARGUMENT;
        } else {
            st = BG_OK;
        }
        dae_free(&sol);
        free(bk);
    }
    if (st == BG_OK) {
        dae_modes_options mo;
        dae_modes_options_default(&mo);
        mo.dense_max = 1200;
        mo.nev = 20;
        /* at T > 0 the run's state moves (slewing, transients): the library refuses such a
         * state; --modes T asks for the frozen linearisation at that instant */
        mo.frozen = T > 0;
        st = dae_modes_compute(&p, T, y, yp, &mo, out, err);
    }
    if (yout && st == BG_OK) memcpy(yout, y, (size_t)n * sizeof *y);
    free(y);
    free(yp);
    return st;
}

int crane_modes_drift(crane *c, double T, double *hz, bg_error *err)
{
    if (hz) *hz = 0;
    if (!c || !hz || !(T >= 0))
        return bg_error_raise(err, BG_ERR_ARGUMENT, "crane_modes_drift", "bad arguments (T = %g)",
                              T);
    if (T == 0) return BG_OK;
    dae_modes *M0 = NULL;
    int st = crane_modes(c, 0.0, &M0, NULL, err);
    if (st == BG_OK || st == DAE_CONV_FAIL) {
        st = BG_OK;
        for (int k = 0; k < dae_modes_count(M0); k++) { /* elastic first, by frequency */
            const dae_mode *md = dae_modes_get(M0, k);
            if (md->kind == DAE_MODE_ELASTIC && md->freq_hz > 0) {
                *hz = CRANE_DRIFT_RATIO * md->freq_hz;
                break;
            }
        }
    }
    dae_modes_free(&M0);
    return st;
}

const char *crane_mode_part(const dae_modes *M, int k, char *buf, size_t size)
{
    char d[256];
    snprintf(buf, size, "other");
    if (dae_modes_describe(M, k, 2, 1, 0, d, sizeof d) <= 0) return buf;
    const char *a = strchr(d, '/');
    if (!a) return buf;
    a++;
    size_t l = strcspn(a, " /");
    char part[64];
    snprintf(part, sizeof part, "%.*s", (int)(l < 63 ? l : 63), a);
    if (!strncmp(part, "ties", 4)) snprintf(part, sizeof part, "ties");
    if (!strncmp(part, "platform", 8) || !strncmp(part, "slewing", 7)) snprintf(part, sizeof part, "platform");
    if (!strncmp(part, "boom", 4)) snprintf(part, sizeof part, "boom");
    snprintf(buf, size, "%s", part);
    return buf;
}

int crane_modes_plot_script(const dae_modes *M, const char *scene, double T, double drift_hz,
                            FILE *f)
{
    /* the parts present among the elastic modes */
    enum { MAXP = 16 };
    char parts[MAXP][64];
    int np = 0, ne = 0, nr = 0, nc = 0, nd = 0;
    dae_modes_info(M, &ne, &nr, &nc, NULL, NULL, NULL);
    for (int k = 0; k < dae_modes_count(M); k++) {
        const dae_mode *md = dae_modes_get(M, k);
        if (md->kind != DAE_MODE_ELASTIC) continue;
        if (md->freq_hz < drift_hz) {
            nd++;
            continue;
        }
        char part[64];
        crane_mode_part(M, k, part, sizeof part);
        int j = 0;
        while (j < np && strcmp(parts[j], part))
            j++;
        if (j == np && np < MAXP) snprintf(parts[np++], sizeof parts[0], "%s", part);
    }
    fprintf(f, "# The crane's modes (modes.csv): damping ratio against frequency, by part.\n"
               "#   gnuplot modes.gp\n"
               "set terminal png size 900,600 noenhanced\nset output 'modes.png'\n"
               "set datafile separator ','\nset grid\nset key outside right top\n"
               "set logscale x\nset xlabel 'natural frequency |s|/(2 pi) [Hz]'\n"
               "set ylabel 'damping ratio -Re(s)/|s|'\n");
    char drift[96] = "";
    if (nd) snprintf(drift, sizeof drift, ", %d drift (below %.3g Hz)", nd, drift_hz);
    fprintf(f, "set title 'crane modes, scene %s, t = %g s: %d elastic (plotted)%s, %d rigid, %d "
               "constraint'\n",
            scene, T, ne - nd, drift, nr, nc);
    /* labels of the lowest five */
    int lab = 0;
    for (int k = 0; k < dae_modes_count(M) && lab < 5; k++) {
        const dae_mode *md = dae_modes_get(M, k);
        if (md->kind != DAE_MODE_ELASTIC || !(md->freq_hz > 0) || md->freq_hz < drift_hz)
            continue;
        char part[64];
        fprintf(f, "set label %d '%d %s %.3g Hz' at %.9g,%.9g offset 1,%d font ',8'\n", lab + 1,
                k + 1, crane_mode_part(M, k, part, sizeof part), md->freq_hz, md->freq_hz,
                md->damping, lab % 2 ? -1 : 1);
        lab++;
    }
    /* one series per part */
    fprintf(f, "plot ");
    for (int j = 0; j < np; j++)
        fprintf(f,
                "%s'modes.csv' skip 1 using (strcol(4) eq 'elastic' && strcol(5) eq '%s' ? $2 : "
                "1/0):3 title '%s' with points pt 7 ps 1.2",
                j ? ", \\\n     " : "", parts[j], parts[j]);
    if (np == 0) fprintf(f, "1/0 title 'no elastic mode'");
    fprintf(f, "\n");
    return ferror(f) ? BG_ERR_IO : BG_OK;
}
