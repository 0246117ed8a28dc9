/* Linearisation and modes of a DAE F(t, y, y') = 0 at a state (t, y, y').
 *
 * The linearisation is the pencil (B, A) = (dF/dy, dF/dy'): dy = z e^(s t) solves
 * A dy' + B dy = 0 when (s A + B) z = 0. Its eigenvalues s are the modes: a frequency
 * |s| / (2 pi) (the undamped natural frequency; Hz when the model's time unit is the second) and
 * a damping ratio -Re(s) / |s| (0 undamped, 1 critically damped or a real decay, < 0 unstable).
 * Conjugate pairs are listed once (Im s > 0).
 *
 * The algebraic part. A is singular: the algebraic unknowns (its zero columns) and the hidden
 * constraints of index-2 systems give infinite eigenvalues, which a generalized eigensolver
 * (QZ, LAPACK dggev) returns beside the finite ones, those of index 2 as ill-conditioned
 * Jordan blocks. Here they never mix with the finite ones: with a shift sigma that is not an
 * eigenvalue and X = (B + sigma A)^-1, (s A + B) z = 0 is X A z = z / (sigma - s), so the finite
 * eigenvalues are sigma - 1/mu for the nonzero eigenvalues mu of X A and the infinite ones are
 * its zeros. A = A_d P_d^T has nonzero columns only at the d differential unknowns, so the
 * nonzero mu are those of the d x d matrix C = P_d^T X A_d (a reduction to the differential
 * states: one sparse LU of B + sigma A and d solves), z = X A_d u for C u = mu u. The algebraic
 * unknowns' infinite eigenvalues are thus removed exactly; the index-2 ones remain as mu = 0 of C
 * and are reported as constraint modes at infinite frequency.
 *
 * Kinds. elastic: a finite, nonzero eigenvalue (oscillations, real decays, anything with a
 * time scale). rigid: s = 0 and defective (a Jordan chain: position and velocity, the motion of
 * a free body or mechanism at constant speed). constraint: s = infinite (index-2 constraints), or
 * s = 0 and semisimple (non-defective): an invariant of the model rather than a motion, which is
 * what velocity-level constraints leave (two bodies of a joint drifting apart, the stretch state
 * of an axial element against its end points, the norm of a quaternion, an integrated angle
 * against the body it measures: the spurious rigid modes of such models). The two kinds of zero
 * eigenvalue are told apart by the multiplicities at zero: m computed eigenvalues there, a null
 * space of dimension g of C - I/sigma (singular values below 1e-10 of the largest), hence
 * m - g Jordan chains, the rigid motions; rounding splits each chain into a pair of nearly
 * parallel eigenvectors, and the m - g pairs at the smallest angles are the rigid ones. (The
 * eigenvalues' reciprocal condition numbers, dae_mode.rcond, tell the same in isolation, O(1)
 * against sqrt(machine epsilon), but not inside a cluster of dozens of semisimple zeros.)
 *
 * Naming. Each mode is described by the differential unknowns that dominate it: amplitude
 * |z_i| / nominal_i (the problem's nominal magnitudes, else 1), shares of the squared amplitudes
 * summed by component path (the unknown's name cut after `depth` segments: rig/beam,
 * rig/hydraulics), and the leading unknowns (dae_modes_describe).
 *
 * Methods. Dense (by default up to options.dense_max = 1200 differential unknowns, then
 * sparse: DAE_MODES_AUTO): every eigenvalue of C by
 * LAPACK dgeevx with left and right eigenvectors, all three kinds. Sparse (larger models, or on
 * request): the nev modes of a window by ARPACK (dnaupd/dneupd, implicitly restarted Arnoldi)
 * on the operator X A - sigma (X A)^2, applied with the sparse LU of B + sigma A (KLU): two
 * solves per product. Its eigenvalue is -s/(sigma - s)^2, zero for s = 0 and s = infinite, so
 * the hundreds of zero modes of a model with many bodies (one quaternion norm each) and the
 * infinite ones never crowd the wanted modes; its magnitude peaks at |s| = sigma and is the same
 * for |s| and sigma^2/|s|, so the nev largest are the modes in a band of |s| around sigma (a
 * window), and for sigma^2 <= |s_1| |s_nev| they are the nev lowest: options.sigma = 0 asks for
 * the lowest nev elastic modes, sigma then chosen (from 1) and lowered until that condition holds
 * (s is told from sigma^2/s by the pencil residual of the Ritz vector). options.sigma > 0 asks
 * for (at most) nev modes nearest the frequency sigma (rad per time unit) by complex
 * shift-invert, OP = (B + i sigma A)^-1 A with KLU's complex LU and ARPACK znaupd: the zero modes
 * are at distance sigma from the shift, so every mode in the disc |s - i sigma| < sigma comes
 * before them. Every eigenvalue found is refined by Rayleigh-quotient iteration with KLU's complex
 * LU of s A + B (the real shift's rounding along the drift directions of a model with many bodies
 * limits the Ritz values to a relative accuracy of about 1e-4; a solve with the shift at the mode
 * itself has no such limit, and the refined damping ratios of undamped modes come out at the
 * rounding level). A repeated eigenvalue (the two bending planes of a symmetric section, identical
 * subsystems) is returned once per independent eigenvector: a mode found twice is told by its
 * vector lying in the span of the kept ones of that eigenvalue (sine of the angle below 1e-3,
 * modified Gram-Schmidt), never by its eigenvalue alone. The sparse method finds elastic modes
 * only.
 *
 * States in motion. The pencil describes small motions about (t, y, yp) with constant
 * coefficients only when the state stays a solution along its own motion (y' = yp constant
 * along ignorable coordinates: a shaft turning at a constant rate, a mass dragged at constant
 * speed). A structure spinning steadily in the inertial frame is not such a state (its positions
 * move along directions that rotate, and the pencil with them): its frozen pencil gives spurious
 * modes at Omega/2 and in-plane frequencies equal to the flapwise ones. Such a moving state is
 * refused (BG_ERR_ARGUMENT, naming the equation that changes along the motion and the fastest
 * unknown) unless a co-moving frame is given (options.frame, below) or options.frozen asks for
 * the frozen pencil's modes. yp NULL or zero: at rest, accepted.
 *
 * Co-moving frames (options.frame). A frame that moves by a linear flow: unknowns y = Phi_t(z),
 * Phi_t the flow of y' = S y + c with a constant generator S (n x n) and a constant c, so that
 * y' = S y + c + Q(t) z' (Q = e^(S t)). For a frame turning at the constant angular velocity
 * Omega (bgr_frame_rotation builds S from the kinds of unknowns the components declare): a
 * global vector u (a velocity, a force, a moment, a relative position) has u' = Omega x u, a
 * position x' = Omega x (x - p) (p on the axis: the affine part c = -Omega x p), an orientation
 * quaternion (body to global) q' = (0, Omega/2) (x) q, and what is measured in a body's own frame
 * (its angular velocity) or is a scalar does not change (0 in S). Substituted into F, the problem
 * in the frame at the instant the frame passes the state (y = z) is
 *     G(t, z, z') = F(t, z, S z + c + z'),
 * whose state at rest (z' = 0, that is y' = S y + c) is a steady motion in the frame, and whose
 * pencil there, (dF/dy + dF/dy' S, dF/dy'), has constant coefficients (those at a later instant
 * are the same rotated: equations whose rows turn with the frame keep their solutions): the
 * Coriolis (gyroscopic) and centrifugal terms come out of dF/dy' S by themselves, and its
 * eigenvalues are the modes in the frame (the linearisation of the equations of motion relative
 * to a rotating frame about a relative equilibrium: L. Meirovitch, Methods of Analytical
 * Dynamics, 1970, gyroscopic systems; M. Geradin and A. Cardona, Flexible Multibody Dynamics,
 * 2001, rotating structures). The state given must be at rest in the frame: yp = S y + c for some
 * constant c (c = yp - S y is taken from it), and it must stay a solution along the frame's flow
 * (bg_jaceval_steadiness along (1, yp, S yp): y moves along yp, yp turns along S yp), else
 * BG_ERR_ARGUMENT naming the equation (a load that does not turn with the frame, gravity across
 * the axis; unknowns whose kinds S does not follow); options.frozen = 1 skips that check. The
 * static solver finds such states (bg_static.h, options.frame). Modes at rest in the inertial
 * frame, s z = -S z (weighted residual |(s + S) z| / (|s| |z|) below 1e-2, where a motion of the
 * structure has about 1): the invariants of velocity-level joints (a driven hub's position, a
 * joint's two bodies drifting apart), which are semisimple zeros in the inertial frame, seen
 * turning at the frame's rate: constraint modes. Jacobians: the pencil needs dF/dy exact at the
 * moving state; by default (options.jacobian = DAE_MODES_JAC_AUTO) the problem in the frame is
 * differentiated by coloured differences of its residual (about 1e-7 on the frequencies), since
 * an analytic Jacobian may be exact only at rest (mech_beam.h: the consistent beam element leaves
 * out terms of its inertia loads in motion, 3.5e-3 on the frequencies of a cantilever at
 * gamma = 12); DAE_MODES_JAC_PROBLEM uses the problem's own when it is known to be exact in
 * motion. Southwell's rotating cantilever (flapwise and lead-lag, gamma up to 12) and the orbit
 * of a mass on a spring are checked against independent references in
 * tests/components/mechanics/test_modes_rotating.c and tests/solver/test_steady.c.
 *
 * Errors: BG_ERR_ARGUMENT (NULL problem, state or result; a moving state that is not steady (see
 * above), or not steady in the given frame; a frame's S that is not a well-formed n x n matrix of
 * finite values; an option out of range: the message
 * names the field, its value and its range; a nominal magnitude that is not finite and > 0: the
 * message names the unknown and the value), BG_ERR_NONFINITE (a value of y or yp not finite: the
 * message names the unknown), BG_ERR_PATTERN,
 * BG_ERR_MEMORY, BG_ERR_CALLBACK (the Jacobian failed), BG_ERR_SINGULAR (B + sigma A singular
 * for several shifts: the message names the unknown), BG_ERR_LIBRARY (LAPACK or ARPACK failed,
 * or the library was built without ARPACK and the sparse method is needed), DAE_CONV_FAIL
 * (ARPACK did not converge within maxiter restarts; the converged modes are returned). */
#ifndef BG_MODES_H
#define BG_MODES_H

#include <stddef.h>

#include "bg_api.h"
#include "bg_dae.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum dae_mode_kind {
    DAE_MODE_ELASTIC = 0,
    DAE_MODE_RIGID = 1,
    DAE_MODE_CONSTRAINT = 2
} dae_mode_kind;

/* "elastic", "rigid", "constraint"; "unknown" for other values. */
BG_API const char *dae_mode_kind_name(int kind);

typedef enum dae_modes_method {
    DAE_MODES_AUTO = 0, /* dense up to options.dense_max differential unknowns (every mode,
                           all three kinds), else sparse (the nev elastic modes of the window:
                           the lowest 20 by default): the number of modes returned changes at
                           that size, and dae_modes_info tells which method was used */
    DAE_MODES_DENSE = 1,
    DAE_MODES_SPARSE = 2
} dae_modes_method;

/* Where the Jacobians of the linearisation come from (dae_modes_options.jacobian). */
typedef enum dae_modes_jacobian {
    DAE_MODES_JAC_AUTO = 0,       /* the problem's own (its analytic Jacobian, else differences),
                                     except in a co-moving frame: differences (see there) */
    DAE_MODES_JAC_PROBLEM = 1,    /* the problem's own, in a frame too */
    DAE_MODES_JAC_DIFFERENCES = 2 /* coloured forward differences of the residual on the
                                     problem's patterns (bg_fdjac.h), everywhere */
} dae_modes_jacobian;

typedef struct dae_modes_options {
    int method;            /* dae_modes_method, default DAE_MODES_AUTO */
    int dense_max;         /* the largest number of differential unknowns DAE_MODES_AUTO
                              solves densely (see there), default 1200 (>= 1) */
    double sigma;          /* shift (1/time unit). Dense: any real that is not an eigenvalue,
                              default 0: 1 (raised by 1.618 if B + sigma A is singular). Sparse:
                              > 0 the frequency (rad per time unit) the window is centred on, 0
                              (default) the lowest nev modes */
    int nev;               /* sparse: modes wanted, default 20 */
    int ncv;               /* sparse: Arnoldi basis, default max(2 nev + 1, nev + 20) */
    double tol;            /* sparse: ARPACK's relative tolerance (finite, >= 0), default 1e-10 */
    int maxiter;           /* sparse: ARPACK's restarts, default 500 */
    double zero_tol;       /* |s| <= zero_tol * sigma: a zero eigenvalue, in [0, 1), default 1e-6 */
    double inf_tol;        /* |mu| <= inf_tol * max |mu|: an infinite eigenvalue, in [0, 1),
                              default 1e-9 */
    ls_kind linsol;        /* default LS_KLU */
    int frozen;            /* 0 (default): a moving state (yp given, not zero) is linearised only
                              if it is steady, i.e. stays a solution along its own motion
                              (bg_jaceval_steadiness: a motion along ignorable coordinates);
                              else BG_ERR_ARGUMENT. 1: the frozen pencil at that instant anyway
                              (with a frame: the frame's pencil, steady or not) */
    const sp_csc *frame;   /* NULL (default): the inertial frame. Else the generator S (n x n)
                              of a co-moving frame (see "Co-moving frames" above; bgr_frame_rotation
                              builds it for a steady rotation): the modes are those of small
                              motions in that frame about a state steady in it, yp = S y + c */
    int jacobian;          /* dae_modes_jacobian, default DAE_MODES_JAC_AUTO */
} dae_modes_options;

/* The defaults above; BG_OK, or BG_ERR_ARGUMENT if o is NULL. */
BG_API int dae_modes_options_default(dae_modes_options *o);

typedef struct dae_mode {
    double re, im;    /* the eigenvalue s (im >= 0); INFINITY for a constraint at infinity */
    double freq_hz;   /* |s| / (2 pi) (INFINITY at infinity, 0 for s = 0) */
    double damping;   /* -re / |s| (NaN for s = 0 and at infinity) */
    int kind;         /* dae_mode_kind */
    double rcond;     /* reciprocal condition number of the eigenvalue (dense), else NaN */
    double residual;  /* ||(s A + B) z|| / ((|s| ||A|| + ||B||) ||z||), NaN at infinity */
} dae_mode;

typedef struct dae_modes dae_modes;

/* The modes of p at (t, y, yp) (yp NULL: zero). *out receives the result (free it with
 * dae_modes_free), also on DAE_CONV_FAIL. o NULL: the defaults. */
BG_API int dae_modes_compute(const dae_problem *p, double t, const double *y, const double *yp,
                             const dae_modes_options *o, dae_modes **out, bg_error *err);
BG_API void dae_modes_free(dae_modes **m);
/* Number of modes (conjugate pairs once), in the order: elastic by increasing frequency, then
 * rigid, then constraint; 0 for NULL. */
BG_API int dae_modes_count(const dae_modes *m);
/* Mode k, NULL out of range. */
BG_API const dae_mode *dae_modes_get(const dae_modes *m, int k);
/* Counts by kind (any pointer may be NULL), the shift used, the number of differential
 * unknowns d and the method used (dae_modes_method); BG_OK or BG_ERR_ARGUMENT. */
BG_API int dae_modes_info(const dae_modes *m, int *elastic, int *rigid, int *constraint,
                          double *sigma, int *d, int *method);
/* The eigenvector of mode k (n values each, real and imaginary parts; im may be NULL), scaled
 * to a largest weighted amplitude |z_i| / nominal_i of 1 among the differential unknowns.
 * BG_OK or BG_ERR_ARGUMENT. */
BG_API int dae_modes_vector(const dae_modes *m, int k, double *re, double *im);
/* "rig/beam 93%, rig/ties 4%, ... | rig/beam/node16/x0, ..." : the shares of the
 * component paths cut after depth segments (depth < 1: whole names) above 1 %, at most ngroups
 * of them, then the top leading unknowns. The result keeps the problem's names array (it must
 * stay valid, as a compiled bond-graph model's does) and a copy of its nominal magnitudes. The
 * snprintf count, or BG_ERR_ARGUMENT. */
BG_API int dae_modes_describe(const dae_modes *m, int k, int depth, int ngroups, int top,
                              char *buf, size_t size);
/* The share (0..1) of mode k's squared amplitude among the differential unknowns in those whose
 * names start with prefix. NaN for bad arguments. */
BG_API double dae_modes_share(const dae_modes *m, int k, const char *prefix);

#ifdef __cplusplus
}
#endif
#endif
