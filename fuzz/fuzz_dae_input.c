/* libFuzzer target: the input validation of the DAE solver (solver/bg_dae.h).
 *
 * The input bytes are decoded into a dae_problem and dae_options: the size n, the options
 * (tolerances, an absolute-tolerance vector, order, step limits, policies, stop time,
 * breakpoints, projection), the kinds of the unknowns, names, Jacobian patterns and a constraint
 * pattern that are either well formed (rows ascending, shapes right or off by one) or raw
 * (colptr and row indices taken from the bytes, arrays as long as the struct declares them),
 * constraint and event functions present or not. dae_create must accept or refuse this without
 * harm; a solver it creates then takes a few calls with values from the bytes (dae_init with
 * values that may be NaN, dae_consistent_init, a handful of steps, dense output inside and
 * outside the last step, dae_set_history, dae_reinit, the statistics into short buffers).
 * The residual is linear (F = Cy y + Cyp y' + f sin t on the declared patterns) so the steps
 * are cheap; integrations are capped at a few steps (max_steps from the bytes, at most 12).
 *
 * Properties checked besides "no crash, no leak, no undefined behaviour" (the documented
 * contract of dae_create, bg_dae.h):
 *   - a refusal returns NULL with a negative status and a message in err;
 *   - n < 1, no residual, max_order outside 0..5 (MEBDF 0..7), rtol not in [0, 1), a kind that is not a
 *     dae_var_kind, and a Jacobian pattern that sp_csc_check refuses or that is not n x n are
 *     refused;
 *   - functions called with a solver return a status, never something undocumented:
 *     dae_dense returns BG_OK or a negative status, dae_stats_line does not write past the size
 *     it is given.
 * A violated property ends the run with a message and __builtin_trap(). */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bg_dae.h"
#include "bg_sparse.h"

#define NMAX 12

static void fail(const char *what, const char *detail)
{
    fprintf(stderr, "fuzz_dae_input: %s%s%s\n", what, detail ? ": " : "", detail ? detail : "");
    __builtin_trap();
}

/* ------------------------------------------------------------------ the bytes ---- */

typedef struct reader {
    const uint8_t *p;
    size_t n;
} reader;

static unsigned u8(reader *r)
{
    if (!r->n) return 0;
    r->n--;
    return *r->p++;
}
static int flag(reader *r)
{
    return (int)(u8(r) & 1);
}
/* An integer in lo..hi. */
static int range(reader *r, int lo, int hi)
{
    if (hi <= lo) return lo;
    return lo + (int)(u8(r) % (unsigned)(hi - lo + 1));
}

static const double VALUES[] = {
    0.0,     1e-300,  1e-12,  1e-8,     1e-6,    1e-3,    0.1,       0.5,    1.0,      2.0,
    10.0,    1e3,     1e300,  -1e-6,    -1.0,    -1e300,  NAN,       INFINITY, -INFINITY, -0.0,
    5e-324,  2.2e-308, 1.7e308, 0.999999, 1e-100, 3.0,    -2.0,      0.25};
#define NVALUES (sizeof VALUES / sizeof *VALUES)

static double value(reader *r)
{
    unsigned b = u8(r);
    if (b < 2 * NVALUES) return VALUES[b % NVALUES];
    return ((double)b - 2.0 * NVALUES) / 16.0 - 4.0; /* small numbers around 0 */
}

/* --------------------------------------------------------------- the problem ---- */

typedef struct model {
    int n;
    double cy[NMAX][NMAX], cyp[NMAX][NMAX], f[NMAX], groot[4];
    long calls, fail_after;
    int fail_code, nroots;
} model;

static int res(void *user, double t, const double *y, const double *yp, double *F)
{
    model *m = user;
    if (m->fail_after >= 0 && m->calls++ >= m->fail_after) {
        if (m->fail_code == 0 && m->n > 0) {
            F[0] = NAN;
            return 0;
        }
        return m->fail_code;
    }
    for (int i = 0; i < m->n; i++) {
        double s = m->f[i] * sin(t);
        for (int j = 0; j < m->n; j++)
            s += m->cy[i][j] * y[j] + m->cyp[i][j] * yp[j];
        F[i] = s;
    }
    return 0;
}

static void fill(const model *m, double c[NMAX][NMAX], sp_csc *J)
{
    if (!J) return;
    for (int j = 0; j < J->ncol; j++)
        for (int p = J->colptr[j]; p < J->colptr[j + 1]; p++) {
            int i = J->rowind[p];
            J->val[p] = i >= 0 && i < m->n && j < m->n ? c[i][j] : 0.0;
        }
}

static int jac(void *user, double t, const double *y, const double *yp, sp_csc *Jy, sp_csc *Jyp)
{
    (void)t, (void)y, (void)yp;
    model *m = user;
    fill(m, m->cy, Jy);
    fill(m, m->cyp, Jyp);
    return 0;
}

static int cons(void *user, double t, const double *y, double *g, sp_csc *G)
{
    (void)user, (void)t;
    (void)y;
    (void)g;
    if (G)
        for (int p = 0; p < G->nnz; p++)
            G->val[p] = 1.0;
    return 0;
}

/* g_k = sum of y over the pattern row k (the constraint function needs the pattern: it is kept
 * in a global, set before dae_create). */
static const sp_csc *cons_pat;
static int cons_ncons;
static int cons_eval(void *user, double t, const double *y, double *g, sp_csc *G)
{
    const sp_csc *P = cons_pat;
    for (int k = 0; k < cons_ncons; k++)
        g[k] = 0;
    if (P && P->nrow == cons_ncons)
        for (int j = 0; j < P->ncol; j++)
            for (int p = P->colptr[j]; p < P->colptr[j + 1]; p++)
                g[P->rowind[p]] += y[j];
    return cons(user, t, y, g, G);
}

static int roots(void *user, double t, const double *y, const double *yp, double *g)
{
    (void)yp;
    model *m = user;
    for (int k = 0; k < m->nroots && k < 4; k++)
        g[k] = y[0] - m->groot[k] - 0.1 * t;
    return 0;
}

/* A pattern nrow x ncol. Well formed: each column's rows from a bit mask, ascending; raw: the
 * declared sizes with colptr and row indices from the bytes. mask[i][j] receives the entries of
 * a well-formed pattern (for the residual). */
typedef struct pattern {
    sp_csc A;
    int colptr[NMAX + 2];
    int rowind[(NMAX + 1) * (NMAX + 1) + 4];
    double val[(NMAX + 1) * (NMAX + 1) + 4];
    int well_formed;
} pattern;

static void make_pattern(reader *r, pattern *P, int nrow, int ncol, unsigned char mask[][NMAX])
{
    memset(P, 0, sizeof *P);
    P->A.nrow = nrow;
    P->A.ncol = ncol;
    P->A.colptr = P->colptr;
    P->A.rowind = P->rowind;
    P->A.val = P->val;
    int maxnnz = (int)(sizeof P->rowind / sizeof *P->rowind);
    if (flag(r) || nrow < 0 || ncol < 0) {
        /* raw: what the bytes say, arrays as long as declared (within the buffers) */
        int nnz = range(r, -1, maxnnz);
        P->A.nnz = nnz;
        for (int j = 0; j <= (ncol > NMAX + 1 ? NMAX + 1 : ncol); j++)
            P->colptr[j] = range(r, -1, nnz + 1);
        if (flag(r)) P->colptr[0] = 0;
        for (int k = 0; k < (nnz > 0 ? nnz : 0); k++)
            P->rowind[k] = range(r, -1, nrow);
        P->well_formed = sp_csc_check(&P->A, NULL) == BG_OK;
        if (P->well_formed && mask)
            for (int j = 0; j < ncol && j < NMAX; j++)
                for (int p = P->colptr[j]; p < P->colptr[j + 1]; p++)
                    if (P->rowind[p] < NMAX) mask[P->rowind[p]][j] = 1;
        return;
    }
    int nnz = 0;
    for (int j = 0; j < ncol; j++) {
        P->colptr[j] = nnz;
        unsigned bits = u8(r) | (u8(r) << 8);
        if (j < nrow) bits |= 1u << j; /* the diagonal mostly present */
        if (flag(r)) bits &= ~(1u << j);
        for (int i = 0; i < nrow && i < 16; i++)
            if (bits & (1u << i)) {
                P->rowind[nnz++] = i;
                if (mask && i < NMAX && j < NMAX) mask[i][j] = 1;
            }
    }
    P->colptr[ncol] = nnz;
    P->A.nnz = nnz;
    P->well_formed = 1;
}

/* ------------------------------------------------------------------ the run ---- */

static const char LONG_NAME[] =
    "a_very_long_name_of_an_unknown_that_goes_on_and_on_well_past_any_buffer_of_sixty_four_or_"
    "one_hundred_and_twenty_eight_characters_that_a_message_might_use_for_it_and_further_still_"
    "so_that_truncation_is_exercised_somewhere_in_the_formatting_of_the_messages_of_the_solver";
static const char *const NAME_POOL[] = {"x", "", "crane/boom/b3/f", "%s%n%d", LONG_NAME, "y[0]"};

static void run(reader *r)
{
    model *m = calloc(1, sizeof *m);
    pattern *Py = malloc(sizeof *Py), *Pyp = malloc(sizeof *Pyp), *Pc = malloc(sizeof *Pc);
    if (!m || !Py || !Pyp || !Pc) goto done;

    int n = range(r, -2, NMAX);
    m->n = n > 0 ? n : 0;
    dae_options o;
    dae_options_default(&o);
    dae_problem p;
    memset(&p, 0, sizeof p);
    p.n = n;
    p.res = (flag(r) || flag(r)) ? res : NULL;
    p.user = m;

    /* options: each field kept at its default or taken from the bytes */
    double atol_vec[NMAX], bkpt[6];
    unsigned which = u8(r) | (u8(r) << 8);
    if (which & 1) o.rtol = value(r);
    if (which & 2) o.atol = value(r);
    if (which & 4) {
        for (int i = 0; i < NMAX; i++)
            atol_vec[i] = flag(r) ? value(r) : 1e-6;
        o.atol_vec = atol_vec;
    }
    if (which & 8) o.max_order = range(r, -1, 7);
    if (which & 16) o.h_init = value(r);
    if (which & 32) o.h_min = value(r);
    if (which & 64) o.h_max = value(r);
    if (which & 128) o.index2 = (dae_index2_policy)range(r, -1, 2);
    if (which & 256) o.linsol = (ls_kind)range(r, -2, 2);
    if (which & 512) {
        o.has_t_stop = 1;
        o.t_stop = value(r);
    }
    if (which & 1024) {
        o.nbreakpoints = range(r, -1, 6);
        for (int k = 0; k < 6; k++)
            bkpt[k] = value(r);
        o.breakpoints = flag(r) && o.nbreakpoints > 0 ? NULL : bkpt;
    }
    if (which & 2048) o.projection = 1;
    if (which & 4096) o.max_newton = range(r, -2, 6);
    if (which & 8192) o.fixed_step = 1;
    o.exclude_alg = (which >> 14) & 1;
    o.newton_index2_scale_h = (which >> 15) & 1;
    o.max_steps = range(r, 1, 12); /* < 1 would mean the default, 100000 */

    /* kinds and names */
    int kind[NMAX];
    int bad_kind = 0;
    const char *names[NMAX];
    for (int i = 0; i < NMAX; i++) {
        int k = range(r, 0, 7);
        kind[i] = k <= 2 ? k : k <= 5 ? DAE_DIFF : k == 6 ? -1 : 3;
        if (i < n && (kind[i] < 0 || kind[i] > 2)) bad_kind = 1;
        names[i] = NAME_POOL[range(r, 0, 5)];
    }
    if (flag(r))
        p.kind = kind;
    else
        bad_kind = 0;
    if (flag(r)) p.names = names;

    /* patterns and the residual's coefficients on them */
    static unsigned char my[NMAX][NMAX], myp[NMAX][NMAX];
    memset(my, 0, sizeof my);
    memset(myp, 0, sizeof myp);
    int shape = range(r, 0, 7); /* 0..5: n x n; 6, 7: off by one */
    int pn = shape == 6 ? n + 1 : shape == 7 ? n - 1 : n;
    int bad_pattern = 0;
    if (flag(r)) {
        make_pattern(r, Py, pn, n, my);
        make_pattern(r, Pyp, n, n, myp);
        p.jac_y_pattern = &Py->A;
        p.jac_yp_pattern = &Pyp->A;
        bad_pattern = !Py->well_formed || !Pyp->well_formed || pn != n;
        if (flag(r)) p.jac = jac;
    } else {
        for (int i = 0; i < m->n; i++)
            for (int j = 0; j < m->n; j++) {
                my[i][j] = 1;
                myp[i][j] = !p.kind || kind[j] == DAE_DIFF;
            }
        if (flag(r)) p.jac = jac;
    }
    for (int i = 0; i < m->n; i++) {
        m->f[i] = value(r);
        if (!isfinite(m->f[i])) m->f[i] = 1.0;
        for (int j = 0; j < m->n; j++) {
            m->cy[i][j] = my[i][j] ? (i == j ? 1.0 : 0.25 * range(r, -2, 2)) : 0.0;
            m->cyp[i][j] = myp[i][j] ? (i == j ? 1.0 : 0.0) : 0.0;
        }
    }
    m->fail_after = flag(r) ? range(r, 0, 20) : -1;
    m->fail_code = range(r, -1, 1);

    /* constraints and events */
    p.ncons = range(r, -1, 3);
    if (flag(r)) p.cons = cons_eval;
    if (flag(r)) {
        int d = range(r, 0, 5); /* 4, 5: a row too many or too few */
        make_pattern(r, Pc, p.ncons + (d == 4) - (d == 5), n, NULL);
        bad_pattern |= p.ncons > 0 && (!Pc->well_formed || Pc->A.nrow != p.ncons);
        p.cons_pattern = &Pc->A;
        cons_pat = Pc->well_formed && Pc->A.ncol <= NMAX ? &Pc->A : NULL;
    } else {
        cons_pat = NULL;
    }
    cons_ncons = p.ncons > 0 ? p.ncons : 0;
    p.nroots = range(r, -1, 4);
    if (flag(r)) p.roots = roots;
    m->nroots = p.nroots;
    for (int k = 0; k < 4; k++)
        m->groot[k] = value(r);

    /* the structural classification on the patterns (its header checks the shapes only, so
     * only well-formed patterns are given) */
    if (p.jac_y_pattern && Py->well_formed && Pyp->well_formed) {
        int ck[NMAX + 2];
        int r2 = dae_classify(p.jac_y_pattern, p.jac_yp_pattern, ck);
        if (r2 > NMAX + 1) fail("dae_classify counts more index-2 unknowns than there are", NULL);
    }

    bg_error err = {0};
    dae_solver *s = dae_create(&p, &o, &err);
    if (!s) {
        if (err.status >= 0 || !err.message[0])
            fail("dae_create refused without a negative status and a message", err.message);
        goto done;
    }
    /* the contract: these must have been refused */
    if (n < 1 || !p.res) fail("dae_create accepted n < 1 or no residual", NULL);
    if (o.max_order < 0 || o.max_order > (o.method == DAE_MEBDF ? 7 : 5))
        fail("dae_create accepted max_order", NULL);
    if (!(o.rtol >= 0 && o.rtol < 1)) fail("dae_create accepted rtol", NULL);
    if (bad_kind) fail("dae_create accepted a kind that is not a dae_var_kind", NULL);
    if (bad_pattern) fail("dae_create accepted a malformed or misshapen pattern", NULL);

    /* a few calls on the solver */
    double y[NMAX], yp[NMAX], Y[8 * NMAX];
    for (int i = 0; i < NMAX; i++) {
        y[i] = flag(r) ? value(r) : 0.0;
        yp[i] = flag(r) ? value(r) : 0.0;
    }
    for (int i = 0; i < 8 * NMAX; i++)
        Y[i] = 0.01 * i;
    double t0 = flag(r) ? value(r) : 0.0;
    int rc = dae_init(s, t0, y, flag(r) ? yp : NULL);
    if (rc == BG_OK && flag(r)) rc = dae_consistent_init(s);
    if (flag(r)) rc = dae_set_history(s, t0, value(r), range(r, -1, 7), Y);
    double tret = 0;
    int nsteps = range(r, 0, 3);
    for (int k = 0; k < nsteps; k++) {
        double tout = t0 + value(r);
        rc = flag(r) ? dae_step(s, tout, &tret, y, yp) : dae_solve_to(s, tout, &tret, y, yp);
        if (rc < 0 && flag(r)) rc = dae_reinit(s, t0, y, yp);
    }
    double yd[NMAX], ypd[NMAX];
    double tc = dae_current_time(s);
    rc = dae_dense(s, isfinite(tc) ? tc - value(r) : value(r), flag(r) ? yd : NULL,
                   flag(r) ? ypd : NULL);
    if (rc > 0) fail("dae_dense returned a positive status", NULL);
    int found[4];
    dae_roots_found(s, found);
    const dae_stats *st = dae_get_stats(s);
    char buf[80];
    size_t size = (size_t)range(r, 0, 72);
    memset(buf, 'Z', sizeof buf);
    if (st) {
        dae_stats_line(st, size ? buf : NULL, size);
        dae_stats_csv(st, size ? buf : NULL, size);
    }
    dae_stats_csv_header(size ? buf : NULL, size);
    for (size_t k = size; k < sizeof buf; k++)
        if (buf[k] != 'Z') fail("statistics written past the buffer's size", NULL);
    if (!dae_return_name(range(r, -40, 10))) fail("dae_return_name returned NULL", NULL);
    dae_get_error(s);
    dae_free(&s);
    if (s) fail("dae_free left the pointer set", NULL);
    dae_free(&s);
done:
    free(m);
    free(Py);
    free(Pyp);
    free(Pc);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    reader r = {data, size};
    run(&r);
    return 0;
}
