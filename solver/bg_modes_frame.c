/* Modes in a co-moving frame (bg_modes.h, "Co-moving frames"): the steadiness along the
 * frame's flow, the problem in the frame (bg_frame.h) handed to dae_modes_compute, and the modes
 * at rest in the inertial frame told apart. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bg_frame.h"
#include "bg_modes_impl.h"

int mode_fastest(const dae_problem *p, const double *y, const double *yp)
{
    int fast = 0;
    double best = -1;
    for (int i = 0; i < p->n; i++) {
        double r = fabs(yp[i]) / (fabs(y[i]) + (p->nominal ? p->nominal[i] : 1.0));
        if (r > best) best = r, fast = i;
    }
    return fast;
}

/* The modes of the problem in the frame that are at rest in the inertial frame: s z = -S z (a
 * displacement fixed in space, seen turning at the frame's rate: the invariants of velocity-level
 * joints and members, the position of a driven hub, which are semisimple zeros, constraint
 * modes, in the inertial frame) become constraint modes here too; by the residual
 * |(s + S) z| / (|s| |z|) (weights 1 / nominal_i) below MODES_FRAME_REST (a motion of the
 * structure has about 1 or more; the computed vectors of rest modes, a cluster of equal
 * eigenvalues, 1e-5 to 2e-4 on a spinning cantilever). Sorted again. */
#define MODES_FRAME_REST 1e-2
static int frame_rest_modes(dae_modes *M, const sp_csc *S)
{
    int n = M->n, changed = 0;
    double *a = malloc((size_t)n * sizeof *a), *b = malloc((size_t)n * sizeof *b);
    if (!a || !b) {
        free(a);
        free(b);
        return BG_ERR_MEMORY;
    }
    for (int k = 0; k < M->nmodes; k++) {
        dae_mode *md = &M->modes[k];
        if (md->kind != DAE_MODE_ELASTIC) continue;
        const double *zr = M->vre + (size_t)k * n, *zi = M->vim + (size_t)k * n;
        /* (s + S) z, real part a, imaginary part b */
        for (int i = 0; i < n; i++) {
            a[i] = md->re * zr[i] - md->im * zi[i];
            b[i] = md->re * zi[i] + md->im * zr[i];
        }
        sp_matvec(S, 1.0, zr, 1.0, a);
        sp_matvec(S, 1.0, zi, 1.0, b);
        double num = 0, zz = 0;
        for (int i = 0; i < n; i++) {
            double w = mode_nominal(M, i);
            num += (a[i] * a[i] + b[i] * b[i]) / (w * w);
            zz += (zr[i] * zr[i] + zi[i] * zi[i]) / (w * w);
        }
        double mag = hypot(md->re, md->im);
        if (mag > 0 && zz > 0 && sqrt(num / zz) <= MODES_FRAME_REST * mag) {
            md->kind = DAE_MODE_CONSTRAINT;
            M->counts[DAE_MODE_ELASTIC]--;
            M->counts[DAE_MODE_CONSTRAINT]++;
            changed = 1;
        }
    }
    free(a);
    free(b);
    if (changed) mode_sort(M);
    return BG_OK;
}

/* Modes in a co-moving frame (bg_modes.h, "Co-moving frames"): the state must be steady in the
 * frame (bg_jaceval_steadiness along the frame's flow) unless o->frozen; then the modes of the
 * problem in the frame, G(t, z, z') = F(t, z, S z + c + z') with c = yp - S y, at rest. */
int mode_in_frame(const dae_problem *p, double t, const double *y, const double *yp,
                  const dae_modes_options *o, dae_modes **out, bg_error *err)
{
    const char *where = "dae_modes_compute";
    int n = p->n, st;
    double *ypz = yp ? NULL : calloc((size_t)n, sizeof *ypz), *c = malloc((size_t)n * sizeof *c);
    bg_frame f;
    memset(&f, 0, sizeof f);
    if ((!yp && !ypz) || !c) {
        st = bg_error_raise(err, BG_ERR_MEMORY, where, "out of memory");
        goto done;
    }
    if (!yp) yp = ypz;
    if ((st = bg_frame_init(&f, p, o->frame, NULL, where, err)) != BG_OK) goto done;
    if (!o->frozen) {
        double ratio;
        int row;
        st = bg_frame_steadiness(p, o->frame, t, y, yp, &ratio, &row, where, err);
        if (st != BG_OK) goto done;
        if (ratio > MODES_STEADY_TOL) {
            char eb[256], vb[256];
            st = bg_error_raise(err, BG_ERR_ARGUMENT, where,
                                "the state is not steady in the co-moving frame: %s changes "
                                "along the frame's motion (%.3g of its terms; the fastest unknown "
                                "is %s), so the linearisation in that frame has no constant "
                                "coefficients (a state that is not at rest in the frame, or "
                                "unknowns whose kinds the frame's generator S does not follow; "
                                "options.frozen = 1 gives the frame's pencil at this instant "
                                "anyway)",
                                bg_eq_label(p, row, eb, sizeof eb), ratio,
                                bg_var_label(p, mode_fastest(p, y, yp), vb, sizeof vb));
            goto done;
        }
    }
    /* c = yp - S y: the state is the frame's own motion */
    memcpy(c, yp, (size_t)n * sizeof *c);
    sp_matvec(o->frame, -1.0, y, 1.0, c);
    memcpy(f.c, c, (size_t)n * sizeof *c);
    /* the Jacobian of the problem in the frame: differences of its residual unless the
     * problem's own is asked for (options.jacobian) */
    if (o->jacobian != DAE_MODES_JAC_PROBLEM) f.q.jac = NULL;
    dae_modes_options oi = *o;
    oi.frame = NULL;
    oi.frozen = 0;
    st = dae_modes_compute(&f.q, t, y, NULL, &oi, out, err);
    if ((st == BG_OK || st == DAE_CONV_FAIL) && frame_rest_modes(*out, o->frame) != BG_OK) {
        dae_modes_free(out);
        st = bg_error_raise(err, BG_ERR_MEMORY, where, "out of memory");
    }
done:
    bg_frame_free(&f);
    free(ypz);
    free(c);
    return st;
}
