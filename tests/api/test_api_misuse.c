/* Bad use of the library API: every public function of solver/ and bondgraph/, and the component
 * constructors, called with NULL pointers, sizes that are negative or do not fit, and in the
 * wrong order. Each call must return the documented status (exactly) and, where the object has an
 * error record, leave a message that names the fault; none may crash, print or abort (the test
 * runs under the sanitizers in CI, see tests/meson.build).
 *
 * Sections: status names; sparse matrices and the builder; colouring and finite differences;
 * linear solvers; the DAE solver (options, problem, call order, the state after a failure); the
 * bond-graph model (NULL model, building, compiling, queries before and after compilation);
 * element and component constructors. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bg_dae.h"
#include "bg_fdjac.h"
#include "bg_linsol.h"
#include "bg_modes.h"
#include "bg_sparse.h"
#include "bg_static.h"
#include "bgr_analysis.h"
#include "bgr_elements.h"
#include "bgr_model.h"
#include "ctl_feedforward.h"
#include "ctl_lqr.h"
#include "ctl_pid.h"
#include "ctl_shaper.h"
#include "ctl_sway.h"
#include "ctl_user.h"
#include "hyd_motor.h"
#include "hyd_pump.h"
#include "hyd_source.h"
#include "hyd_valve.h"
#include "hyd_volume.h"
#include "mech_axial.h"
#include "mech_beam.h"
#include "mech_body.h"
#include "mech_parts.h"
#include "mech_sensor.h"
#include "rot_damper.h"
#include "rot_gear.h"
#include "rot_inertia.h"
#include "sensors.h"
#include "sig_sources.h"
#include "tap.h"

/* 1 if msg contains sub (a NULL message never does). */
static int has(const char *msg, const char *sub)
{
    return msg && sub && strstr(msg, sub) != NULL;
}

static const char *msg_of(const bg_error *e)
{
    return e ? e->message : "(no record)";
}

/* Status got == want, and the message contains sub (sub NULL: no message check). */
static int expect(int got, int want, const char *msg, const char *sub, const char *what)
{
    int ok = got == want && (!sub || has(msg, sub));
    tap_ok(ok, "%s: %s (got %s), message has \"%s\"", what, bg_status_name(want),
           dae_return_name(got), sub ? sub : "");
    if (!ok) tap_diag("message: \"%s\"", msg ? msg : "(null)");
    return ok;
}

/* A 3 x 3 tridiagonal matrix with values (diagonally dominant). */
static sp_csc *tridiag3(void)
{
    sp_builder *b = sp_builder_create(3, 3, 7);
    for (int i = 0; b && i < 3; i++) {
        sp_builder_add(b, i, i, 4.0);
        if (i > 0) sp_builder_add(b, i, i - 1, -1.0);
        if (i < 2) sp_builder_add(b, i, i + 1, -1.0);
    }
    sp_csc *A = b ? sp_builder_finish(b, NULL) : NULL;
    sp_builder_free(&b);
    return A;
}

/* ------------------------------------------------------------ status names ---- */

static void test_status(void)
{
    tap_ok(!strcmp(bg_status_name(BG_ERR_STATE), "BG_ERR_STATE") &&
               !strcmp(dae_return_name(BG_ERR_STATE), "BG_ERR_STATE"),
           "status: BG_ERR_STATE has a name");
    tap_ok(BG_ERR_STATE < 0 && BG_ERR_STATE != BG_ERR_ARGUMENT && BG_ERR_STATE != BG_ERR_NONFINITE,
           "status: BG_ERR_STATE is a distinct error code (%d)", BG_ERR_STATE);
    tap_ok(bg_error_raise(NULL, BG_ERR_IO, "x", "no record %d", 1) == BG_ERR_IO,
           "status: bg_error_raise without a record returns the status");
    bg_error_clear(NULL);
    bg_error e = {0};
    bg_error_raise(&e, BG_ERR_STATE, "here", "order %s", "wrong");
    tap_ok(e.status == BG_ERR_STATE && !strcmp(e.message, "order wrong"),
           "status: the record keeps status and message");
    bg_error_clear(&e);
    tap_ok(e.status == BG_OK && e.message[0] == '\0', "status: bg_error_clear empties the record");
}

/* ------------------------------------------------------------------ sparse ---- */

static void test_sparse(void)
{
    bg_error e = {0};
    sp_csc *A = tridiag3(), *N = NULL;
    double D[9], x[3] = {1, 2, 3}, y[3];
    tap_ok(A != NULL, "sparse: test matrix");
    if (!A) return;
    tap_ok(!sp_csc_alloc(-1, 2, 0) && !sp_csc_alloc(2, -1, 0) && !sp_csc_alloc(2, 2, -1),
           "sparse: sp_csc_alloc with a negative size gives NULL");
    tap_ok(!sp_csc_copy(NULL) && !sp_csc_transpose(NULL), "sparse: copy / transpose of NULL");
    tap_ok(!sp_csc_from_dense(2, 2, NULL, 0) && !sp_csc_from_dense(-1, 2, D, 0),
           "sparse: sp_csc_from_dense with D NULL or a negative size gives NULL");
    sp_csc_free(NULL);
    sp_csc_free(&N);
    tap_ok(sp_csc_to_dense(NULL, D) == BG_ERR_ARGUMENT &&
               sp_csc_to_dense(A, NULL) == BG_ERR_ARGUMENT,
           "sparse: sp_csc_to_dense with NULL gives BG_ERR_ARGUMENT");
    tap_ok(sp_csc_to_dense(A, D) == BG_OK && D[0] == 4.0 && D[3] == -1.0,
           "sparse: sp_csc_to_dense works");
    tap_ok(sp_csc_find(NULL, 0, 0) == -1 && sp_csc_find(A, -1, 0) == -1 &&
               sp_csc_find(A, 3, 0) == -1 && sp_csc_find(A, 0, 3) == -1 &&
               sp_csc_find(A, 0, 2) == -1 && sp_csc_find(A, 1, 1) >= 0,
           "sparse: sp_csc_find gives -1 for NULL, out of range and absent entries");
    expect(sp_csc_check(NULL, &e), BG_ERR_ARGUMENT, e.message, "NULL", "sparse: check NULL");
    {
        int cp[3] = {0, 1, 2}, ri[2] = {0, 1};
        double v[2] = {1, 1};
        sp_csc B = {2, 2, 2, NULL, ri, v};
        expect(sp_csc_check(&B, &e), BG_ERR_PATTERN, e.message, "colptr", "sparse: colptr NULL");
        B.colptr = cp;
        B.nnz = -3;
        expect(sp_csc_check(&B, &e), BG_ERR_PATTERN, e.message, "negative entry count",
               "sparse: nnz < 0");
        B.nnz = 2;
        B.rowind = NULL;
        expect(sp_csc_check(&B, &e), BG_ERR_PATTERN, e.message, "rowind", "sparse: rowind NULL");
        B.rowind = ri;
        int cpbig[3] = {0, 5, 5};
        B.colptr = cpbig;
        expect(sp_csc_check(&B, &e), BG_ERR_PATTERN, e.message, "exceeds",
               "sparse: colptr beyond the entries");
        int cp2[3] = {0, 2, 2}, ri2[2] = {1, 0};
        sp_csc C = {2, 2, 2, cp2, ri2, v};
        expect(sp_csc_check(&C, &e), BG_ERR_PATTERN, e.message, "ascending",
               "sparse: rows not ascending");
        int ri3[2] = {0, 7};
        C.rowind = ri3;
        expect(sp_csc_check(&C, &e), BG_ERR_PATTERN, e.message, "out of range",
               "sparse: row out of range");
        tap_ok(sp_csc_check(A, &e) == BG_OK, "sparse: a valid matrix passes the check");
    }
    tap_ok(sp_csc_same_pattern(NULL, A) == 0 && sp_csc_same_pattern(A, NULL) == 0,
           "sparse: sp_csc_same_pattern with NULL is 0");
    tap_ok(sp_csc_zero(NULL) == BG_ERR_ARGUMENT, "sparse: sp_csc_zero(NULL)");
    tap_ok(sp_matvec(NULL, 1, x, 0, y) == BG_ERR_ARGUMENT &&
               sp_matvec(A, 1, NULL, 0, y) == BG_ERR_ARGUMENT &&
               sp_matvec(A, 1, x, 0, NULL) == BG_ERR_ARGUMENT &&
               sp_matvec_t(NULL, 1, x, 0, y) == BG_ERR_ARGUMENT &&
               sp_matvec_t(A, 1, NULL, 0, y) == BG_ERR_ARGUMENT &&
               sp_matvec_t(A, 1, x, 0, NULL) == BG_ERR_ARGUMENT,
           "sparse: products with NULL give BG_ERR_ARGUMENT");
    int rc0 = sp_matvec(A, 1, x, 0, y);
    tap_ok(rc0 == BG_OK && y[0] == 2.0 && y[1] == 4.0 && y[2] == 10.0,
           "sparse: sp_matvec works (%g %g %g)", y[0], y[1], y[2]);
    FILE *devnull = fopen("/dev/null", "w");
    tap_ok(sp_write_mm(NULL, devnull) == BG_ERR_ARGUMENT && sp_write_mm(A, NULL) == BG_ERR_ARGUMENT,
           "sparse: sp_write_mm with NULL");
    if (devnull) fclose(devnull);
    expect(sp_write_mm_file(NULL, "/dev/null", &e), BG_ERR_ARGUMENT, e.message, "matrix",
           "sparse: sp_write_mm_file(NULL matrix)");
    expect(sp_write_mm_file(A, NULL, &e), BG_ERR_ARGUMENT, e.message, "path",
           "sparse: sp_write_mm_file(NULL path)");
    expect(sp_write_mm_file(A, "/nonexistent-dir/a.mtx", &e), BG_ERR_IO, e.message,
           "/nonexistent-dir/a.mtx", "sparse: sp_write_mm_file to a missing directory");

    /* builder */
    tap_ok(!sp_builder_create(-1, 2, 0) && !sp_builder_create(2, -1, 0),
           "builder: negative dimensions give NULL");
    tap_ok(sp_builder_add(NULL, 0, 0, 1) == BG_ERR_ARGUMENT &&
               sp_builder_count(NULL) == BG_ERR_ARGUMENT && !sp_builder_finish(NULL, NULL) &&
               !sp_builder_error(NULL),
           "builder: NULL builder gives BG_ERR_ARGUMENT / NULL");
    sp_builder *b = sp_builder_create(2, 2, 0);
    int rc = sp_builder_add(b, 2, 0, 1.0);
    expect(rc, BG_ERR_ARGUMENT, msg_of(sp_builder_error(b)), "outside the 2 x 2",
           "builder: entry out of range");
    sp_builder_free(&b);
    sp_builder_free(&b);
    sp_builder_free(NULL);

    /* scatter */
    int slot[2] = {0, 6};
    double v[2] = {1, 1};
    double a0 = A->val[0];
    tap_ok(sp_scatter_add(NULL, slot, v, 1) == BG_ERR_ARGUMENT &&
               sp_scatter_add(A, NULL, v, 1) == BG_ERR_ARGUMENT &&
               sp_scatter_add(A, slot, NULL, 1) == BG_ERR_ARGUMENT &&
               sp_scatter_add(A, slot, v, -1) == BG_ERR_ARGUMENT,
           "scatter: NULL arrays or n < 0 give BG_ERR_ARGUMENT");
    slot[1] = A->nnz;
    tap_ok(sp_scatter_add(A, slot, v, 2) == BG_ERR_ARGUMENT && A->val[0] == a0,
           "scatter: a slot outside the entries gives BG_ERR_ARGUMENT and changes nothing");
    tap_ok(sp_scatter_add(A, slot, v, 0) == BG_OK && sp_scatter_add(A, slot, v, 1) == BG_OK &&
               A->val[0] == a0 + 1,
           "scatter: valid slots work");
    A->val[0] = a0;

    /* union */
    sp_csc *Z = sp_csc_alloc(3, 2, 0);
    tap_ok(!sp_union_create(NULL, A) && !sp_union_create(A, NULL) && !sp_union_create(A, Z),
           "union: NULL or shapes that differ give NULL");
    sp_csc *I3 = sp_csc_alloc(3, 3, 3);
    if (I3) {
        for (int j = 0; j < 3; j++) {
            I3->rowind[j] = j;
            I3->val[j] = 1.0;
            I3->colptr[j + 1] = j + 1;
        }
        I3->nnz = 3;
    }
    sp_union *u = I3 ? sp_union_create(A, I3) : NULL;
    tap_ok(u && sp_union_combine(NULL, A, 1, I3, 1) == BG_ERR_ARGUMENT &&
               sp_union_combine(u, NULL, 1, I3, 1) == BG_ERR_ARGUMENT &&
               sp_union_combine(u, A, 1, NULL, 1) == BG_ERR_ARGUMENT,
           "union: combine with NULL gives BG_ERR_ARGUMENT");
    tap_ok(u && sp_union_combine(u, I3, 1, A, 1) == BG_ERR_PATTERN,
           "union: combine with the operands swapped (other entry counts) gives BG_ERR_PATTERN");
    tap_ok(u && sp_union_combine(u, A, 1, I3, 2) == BG_OK && u->M->val[0] == 6.0,
           "union: combine works");
    sp_union_free(&u);
    sp_union_free(&u);
    sp_union_free(NULL);
    sp_csc_free(&I3);
    sp_csc_free(&Z);
    sp_csc_free(&A);
}

/* ------------------------------------------------------- finite differences ---- */

static int lin3(void *user, const double *x, double *f)
{
    (void)user;
    f[0] = 4 * x[0] - x[1];
    f[1] = -x[0] + 4 * x[1] - x[2];
    f[2] = -x[1] + 4 * x[2];
    return 0;
}

static void test_fdjac(void)
{
    sp_csc *A = tridiag3(), *B = sp_csc_alloc(3, 3, 0);
    double x[3] = {1, 2, 3}, f0[3], mx;
    sp_jac_entry w[2];
    if (!A || !B) {
        tap_ok(0, "fdjac: test matrices");
        return;
    }
    lin3(NULL, x, f0);
    tap_ok(!sp_colour(NULL) && sp_colouring_valid(NULL, A) == 0, "colour: NULL pattern");
    sp_colouring_free(NULL);
    tap_ok(!sp_fdjac_create(NULL) && sp_fdjac_ngroups(NULL) == BG_ERR_ARGUMENT &&
               sp_fdjac_calls(NULL) == BG_ERR_ARGUMENT,
           "fdjac: NULL pattern / object");
    sp_fdjac *d = sp_fdjac_create(A);
    tap_ok(d && sp_fdjac_eval(NULL, lin3, NULL, x, f0, NULL, A) == BG_ERR_ARGUMENT &&
               sp_fdjac_eval(d, NULL, NULL, x, f0, NULL, A) == BG_ERR_ARGUMENT &&
               sp_fdjac_eval(d, lin3, NULL, NULL, f0, NULL, A) == BG_ERR_ARGUMENT &&
               sp_fdjac_eval(d, lin3, NULL, x, NULL, NULL, A) == BG_ERR_ARGUMENT &&
               sp_fdjac_eval(d, lin3, NULL, x, f0, NULL, NULL) == BG_ERR_ARGUMENT,
           "fdjac: sp_fdjac_eval with NULL arguments gives BG_ERR_ARGUMENT");
    tap_ok(d && sp_fdjac_eval(d, lin3, NULL, x, f0, NULL, B) == BG_ERR_PATTERN,
           "fdjac: a Jacobian with another pattern gives BG_ERR_PATTERN");
    tap_ok(d && sp_fdjac_eval(d, lin3, NULL, x, f0, NULL, A) == 0 && sp_fdjac_calls(d) == 3 &&
               fabs(A->val[0] - 4) < 1e-6,
           "fdjac: a valid call works");
    sp_fdjac_free(&d);
    sp_fdjac_free(NULL);
    tap_ok(sp_jac_check(NULL, lin3, NULL, 3, x, 1e-6, 1e-3, w, 2, &mx) == BG_ERR_ARGUMENT &&
               sp_jac_check(A, NULL, NULL, 3, x, 1e-6, 1e-3, w, 2, &mx) == BG_ERR_ARGUMENT &&
               sp_jac_check(A, lin3, NULL, 3, NULL, 1e-6, 1e-3, w, 2, &mx) == BG_ERR_ARGUMENT &&
               sp_jac_check(A, lin3, NULL, 2, x, 1e-6, 1e-3, w, 2, &mx) == BG_ERR_ARGUMENT &&
               sp_jac_check(A, lin3, NULL, 3, x, 0.0, 1e-3, w, 2, &mx) == BG_ERR_ARGUMENT &&
               sp_jac_check(A, lin3, NULL, 3, x, NAN, 1e-3, w, 2, &mx) == BG_ERR_ARGUMENT &&
               sp_jac_check(A, lin3, NULL, 3, x, 1e-6, 1e-3, w, -1, &mx) == BG_ERR_ARGUMENT &&
               sp_jac_check(A, lin3, NULL, 3, x, 1e-6, 1e-3, NULL, 2, &mx) == BG_ERR_ARGUMENT,
           "jac_check: NULL arguments, m other than the rows, floor not > 0, bad nworst");
    tap_ok(sp_jac_check(A, lin3, NULL, 3, x, 1e-6, 1e-3, w, 2, NULL) == 0,
           "jac_check: a valid call works (max_err may be NULL)");
    sp_csc_free(&A);
    sp_csc_free(&B);
}

/* ---------------------------------------------------------- linear solvers ---- */

static void test_linsol(void)
{
    bg_error e = {0};
    sp_csc *A = tridiag3(), *B = sp_csc_alloc(3, 3, 0), *R = sp_csc_alloc(2, 3, 0);
    double b[3] = {1, 2, 3};
    if (!A || !B || !R) {
        tap_ok(0, "linsol: test matrices");
        return;
    }
    tap_ok(!ls_create(LS_KLU, NULL, &e) && e.status == BG_ERR_ARGUMENT && has(e.message, "square"),
           "ls_create(NULL pattern): NULL, BG_ERR_ARGUMENT ('%s')", e.message);
    tap_ok(!ls_create(LS_DENSE, R, &e) && e.status == BG_ERR_ARGUMENT && has(e.message, "2 x 3"),
           "ls_create(2 x 3): NULL, BG_ERR_ARGUMENT ('%s')", e.message);
    tap_ok(!ls_create((ls_kind)7, A, &e) && e.status == BG_ERR_ARGUMENT &&
               has(e.message, "unknown linear solver kind 7"),
           "ls_create(kind 7): NULL, BG_ERR_ARGUMENT ('%s')", e.message);
    {
        int cp[3] = {0, 2, 2}, ri[2] = {1, 0};
        double v[2] = {1, 1};
        sp_csc bad = {2, 2, 2, cp, ri, v};
        tap_ok(!ls_create(LS_KLU, &bad, &e) && e.status == BG_ERR_PATTERN &&
                   has(e.message, "ascending"),
               "ls_create(rows not ascending): NULL, BG_ERR_PATTERN ('%s')", e.message);
        tap_ok(!aat_create(&bad, &e) && e.status == BG_ERR_PATTERN && has(e.message, "ascending"),
               "aat_create(rows not ascending): NULL, BG_ERR_PATTERN ('%s')", e.message);
    }
    for (int k = 0; k < 2; k++) {
        ls_kind kind = k ? LS_DENSE : LS_KLU;
        const char *kn = k ? "dense" : "KLU";
        ls_solver *s = ls_create(kind, A, &e);
        b[0] = 1, b[1] = 2, b[2] = 3;
        if (!s) {
            tap_ok(0, "%s: solver", kn);
            continue;
        }
        int rc = ls_solve(s, b, 1);
        expect(rc, BG_ERR_STATE, ls_get_error(s)->message, "ls_factor first",
               k ? "dense: ls_solve before ls_factor" : "KLU: ls_solve before ls_factor");
        tap_ok(b[0] == 1 && b[1] == 2 && b[2] == 3, "%s: a refused solve leaves b alone", kn);
        tap_ok(ls_factor(NULL, A) == BG_ERR_ARGUMENT, "%s: ls_factor(NULL solver)", kn);
        rc = ls_factor(s, NULL);
        expect(rc, BG_ERR_ARGUMENT, ls_get_error(s)->message, "NULL",
               k ? "dense: ls_factor(NULL matrix)" : "KLU: ls_factor(NULL matrix)");
        rc = ls_factor(s, B);
        expect(rc, BG_ERR_PATTERN, ls_get_error(s)->message, "pattern",
               k ? "dense: ls_factor(other pattern)" : "KLU: ls_factor(other pattern)");
        tap_ok(ls_factor(s, A) == BG_OK, "%s: ls_factor works", kn);
        rc = ls_solve(s, NULL, 1);
        expect(rc, BG_ERR_ARGUMENT, ls_get_error(s)->message, "right-hand side",
               k ? "dense: ls_solve(b NULL)" : "KLU: ls_solve(b NULL)");
        rc = ls_solve(s, b, 0);
        expect(rc, BG_ERR_ARGUMENT, ls_get_error(s)->message, "nrhs 0",
               k ? "dense: ls_solve(nrhs 0)" : "KLU: ls_solve(nrhs 0)");
        tap_ok(ls_solve(NULL, b, 1) == BG_ERR_ARGUMENT, "%s: ls_solve(NULL solver)", kn);
        tap_ok(ls_solve(s, b, 1) == BG_OK, "%s: ls_solve after ls_factor works", kn);
        /* a singular matrix: the last factorization failed, solving is refused */
        sp_csc *S = sp_csc_copy(A);
        if (S) sp_csc_zero(S);
        tap_ok(S && ls_factor(s, S) == BG_ERR_SINGULAR && ls_singular_col(s) >= 0,
               "%s: a zero matrix is singular (column %d)", kn, ls_singular_col(s));
        rc = ls_solve(s, b, 1);
        expect(rc, BG_ERR_STATE, ls_get_error(s)->message, "failed",
               k ? "dense: ls_solve after a failed factorization"
                 : "KLU: ls_solve after a failed factorization");
        sp_csc_free(&S);
        rc = ls_set_rcond_min(s, -1.0);
        expect(rc, BG_ERR_ARGUMENT, ls_get_error(s)->message, "rcond_min",
               k ? "dense: ls_set_rcond_min(-1)" : "KLU: ls_set_rcond_min(-1)");
        tap_ok(ls_set_rcond_min(s, NAN) == BG_ERR_ARGUMENT && ls_set_rcond_min(s, 1e-10) == BG_OK,
               "%s: ls_set_rcond_min(NaN) refused, 1e-10 taken", kn);
        tap_ok(ls_force_full(s) == BG_OK && ls_get_kind(s) == kind && ls_get_stats(s) != NULL,
               "%s: getters work", kn);
        ls_free(&s);
        ls_free(&s);
    }
    tap_ok(ls_force_full(NULL) == BG_ERR_ARGUMENT && ls_set_rcond_min(NULL, 1) == BG_ERR_ARGUMENT &&
               ls_singular_col(NULL) == -1 && ls_get_stats(NULL) == NULL &&
               ls_get_kind(NULL) == LS_NONE && ls_get_error(NULL) == NULL,
           "linsol: NULL solver in the setters and getters");
    ls_free(NULL);

    /* CHOLMOD A A^T */
    tap_ok(!aat_create(NULL, &e) && e.status == BG_ERR_ARGUMENT && has(e.message, "NULL"),
           "aat_create(NULL): NULL, BG_ERR_ARGUMENT");
    aat_solver *q = aat_create(A, &e);
    if (q) {
        double x[3];
        int rc = aat_solve(q, b, x);
        expect(rc, BG_ERR_STATE, aat_get_error(q)->message, "aat_factor first",
               "aat: aat_solve before aat_factor");
        rc = aat_factor(q, NULL, 0);
        expect(rc, BG_ERR_ARGUMENT, aat_get_error(q)->message, "NULL", "aat: aat_factor(NULL)");
        rc = aat_factor(q, A, -1);
        expect(rc, BG_ERR_ARGUMENT, aat_get_error(q)->message, "beta", "aat: beta = -1");
        rc = aat_factor(q, A, INFINITY);
        expect(rc, BG_ERR_ARGUMENT, aat_get_error(q)->message, "beta", "aat: beta = inf");
        rc = aat_factor(q, B, 0);
        expect(rc, BG_ERR_PATTERN, aat_get_error(q)->message, "pattern",
               "aat: aat_factor(other pattern)");
        rc = aat_solve(q, b, x);
        expect(rc, BG_ERR_STATE, aat_get_error(q)->message, "aat_factor first",
               "aat: aat_solve after a refused factorization");
        tap_ok(aat_factor(q, A, 0) == BG_OK && aat_solve(q, b, x) == BG_OK,
               "aat: factor and solve work");
        rc = aat_solve(q, NULL, x);
        expect(rc, BG_ERR_ARGUMENT, aat_get_error(q)->message, "right-hand side",
               "aat: aat_solve(b NULL)");
        rc = aat_solve(q, b, NULL);
        expect(rc, BG_ERR_ARGUMENT, aat_get_error(q)->message, "solution",
               "aat: aat_solve(x NULL)");
        tap_ok(aat_factor_count(q) == 1, "aat: refused factorizations are not counted (%ld)",
               aat_factor_count(q));
    } else {
        tap_ok(0, "aat: solver (%s)", e.message);
    }
    aat_free(&q);
    aat_free(&q);
    aat_free(NULL);
    tap_ok(aat_factor(NULL, A, 0) == BG_ERR_ARGUMENT && aat_solve(NULL, b, b) == BG_ERR_ARGUMENT &&
               aat_get_error(NULL) == NULL && aat_factor_count(NULL) == BG_ERR_ARGUMENT,
           "aat: NULL solver");
    sp_csc_free(&A);
    sp_csc_free(&B);
    sp_csc_free(&R);
}

/* ------------------------------------------------------------- DAE solver ---- */

/* x' = -x, y = x (y algebraic); after t_fatal the residual fails fatally. */
static double t_fatal = INFINITY;
static int small_res(void *user, double t, const double *y, const double *yp, double *F)
{
    (void)user;
    if (t > t_fatal) return -1;
    F[0] = yp[0] + y[0];
    F[1] = y[1] - y[0];
    return 0;
}

static const char *const small_names[2] = {"plant.x", "plant.y"};
static const char *const small_eqs[2] = {"plant.decay", "plant.output"};
static const int small_kind[2] = {DAE_DIFF, DAE_ALG};

/* Patterns of small_res: dF/dy = [1 0; -1 1], dF/dy' = [1 0; 0 0]. */
static void small_patterns(sp_csc **Jy, sp_csc **Jyp)
{
    sp_builder *b = sp_builder_create(2, 2, 3);
    sp_builder_add(b, 0, 0, 0);
    sp_builder_add(b, 1, 0, 0);
    sp_builder_add(b, 1, 1, 0);
    *Jy = sp_builder_finish(b, NULL);
    sp_builder_free(&b);
    b = sp_builder_create(2, 2, 1);
    sp_builder_add(b, 0, 0, 0);
    *Jyp = sp_builder_finish(b, NULL);
    sp_builder_free(&b);
}

static void small_problem(dae_problem *p, const sp_csc *Jy, const sp_csc *Jyp)
{
    memset(p, 0, sizeof *p);
    p->n = 2;
    p->res = small_res;
    p->jac_y_pattern = Jy;
    p->jac_yp_pattern = Jyp;
    p->kind = small_kind;
    p->names = small_names;
    p->eq_names = small_eqs;
}

static int dummy_cons(void *user, double t, const double *y, double *g, sp_csc *G)
{
    (void)user, (void)t, (void)G;
    g[0] = y[0];
    return 0;
}

static int dummy_roots(void *user, double t, const double *y, const double *yp, double *g)
{
    (void)user, (void)t, (void)yp;
    g[0] = y[0] - 0.5;
    return 0;
}

/* dae_create with one change to a valid problem or options: expect NULL, status, message. */
static void create_fails(const dae_problem *p, const dae_options *o, int want, const char *sub,
                         const char *what)
{
    bg_error e = {0};
    dae_solver *s = dae_create(p, o, &e);
    expect(s ? BG_OK : e.status, want, e.message, sub, what);
    dae_free(&s);
}

static void test_dae_create(void)
{
    sp_csc *Jy = NULL, *Jyp = NULL;
    small_patterns(&Jy, &Jyp);
    dae_problem p;
    dae_options o;
    small_problem(&p, Jy, Jyp);
    tap_ok(dae_options_default(NULL) == BG_ERR_ARGUMENT && dae_options_default(&o) == BG_OK,
           "dae_options_default: NULL refused, defaults set");
    {
        int kind[2];
        sp_csc *R = sp_csc_alloc(3, 3, 0);
        tap_ok(dae_classify(NULL, Jyp, kind) == BG_ERR_ARGUMENT &&
                   dae_classify(Jy, NULL, kind) == BG_ERR_ARGUMENT &&
                   dae_classify(Jy, Jyp, NULL) == BG_ERR_ARGUMENT &&
                   dae_classify(Jy, R, kind) == BG_ERR_PATTERN,
               "dae_classify: NULL arguments and patterns of different sizes");
        tap_ok(dae_classify(Jy, Jyp, kind) == 0 && kind[0] == DAE_DIFF && kind[1] == DAE_ALG,
               "dae_classify: works");
        sp_csc_free(&R);
    }
    create_fails(NULL, &o, BG_ERR_ARGUMENT, "residual", "dae_create(NULL problem)");
    dae_problem q = p;
    q.n = 0;
    create_fails(&q, &o, BG_ERR_ARGUMENT, "n >= 1", "dae_create(n = 0)");
    q = p;
    q.res = NULL;
    create_fails(&q, &o, BG_ERR_ARGUMENT, "residual", "dae_create(no residual)");

    /* options */
    struct {
        const char *field, *sub;
        int want;
    } opt[] = {
        {"rtol", "tolerances", BG_ERR_ARGUMENT},
        {"h_init", "h_init", BG_ERR_ARGUMENT},
        {"h_min", "h_min", BG_ERR_ARGUMENT},
        {"h_max", "h_max", BG_ERR_ARGUMENT},
        {"h_order", "exceeds h_max", BG_ERR_ARGUMENT},
        {"max_order", "max_order", BG_ERR_ARGUMENT},
        {"index2", "index2 = 5", BG_ERR_ARGUMENT},
        {"linsol", "linsol = 9", BG_ERR_ARGUMENT},
        {"t_stop", "t_stop", BG_ERR_ARGUMENT},
        {"nbkpt", "nbreakpoints = 2", BG_ERR_ARGUMENT},
        {"bkpt", "breakpoint 1", BG_ERR_ARGUMENT},
        {"projection", "projection", BG_ERR_ARGUMENT},
        {"fixed_step", "h_init > 0", BG_ERR_ARGUMENT},
        {"atol_vec", "atol[1]", BG_ERR_ARGUMENT},
    };
    const double bk[2] = {0.5, NAN}, av[2] = {1e-8, -1.0};
    for (size_t k = 0; k < sizeof opt / sizeof *opt; k++) {
        dae_options_default(&o);
        const char *f = opt[k].field;
        if (!strcmp(f, "rtol")) o.rtol = -1;
        if (!strcmp(f, "h_init")) o.h_init = -1;
        if (!strcmp(f, "h_min")) o.h_min = NAN;
        if (!strcmp(f, "h_max")) o.h_max = INFINITY;
        if (!strcmp(f, "h_order")) o.h_min = 1, o.h_max = 0.5;
        if (!strcmp(f, "max_order")) o.max_order = -1;
        if (!strcmp(f, "index2")) o.index2 = (dae_index2_policy)5;
        if (!strcmp(f, "linsol")) o.linsol = (ls_kind)9;
        if (!strcmp(f, "t_stop")) o.has_t_stop = 1, o.t_stop = NAN;
        if (!strcmp(f, "nbkpt")) o.nbreakpoints = 2;
        if (!strcmp(f, "bkpt")) o.nbreakpoints = 2, o.breakpoints = bk;
        if (!strcmp(f, "projection")) o.projection = 1;
        if (!strcmp(f, "fixed_step")) o.fixed_step = 1;
        if (!strcmp(f, "atol_vec")) o.atol_vec = av;
        char what[96];
        snprintf(what, sizeof what, "dae_create: bad option %s", f);
        create_fails(&p, &o, opt[k].want, opt[k].sub, what);
    }
    dae_options_default(&o);

    /* problem */
    q = p;
    q.ncons = -1;
    create_fails(&q, &o, BG_ERR_ARGUMENT, "ncons = -1", "dae_create: ncons < 0");
    q = p;
    q.nroots = -2;
    create_fails(&q, &o, BG_ERR_ARGUMENT, "nroots = -2", "dae_create: nroots < 0");
    q = p;
    q.ncons = 1;
    create_fails(&q, &o, BG_ERR_ARGUMENT, "constraint function", "dae_create: ncons without cons");
    q = p;
    q.nroots = 1;
    create_fails(&q, &o, BG_ERR_ARGUMENT, "root function", "dae_create: nroots without roots");
    {
        sp_csc *G = sp_csc_alloc(2, 2, 0); /* 2 rows for ncons = 1 */
        q = p;
        q.ncons = 1;
        q.cons = dummy_cons;
        q.cons_pattern = G;
        create_fails(&q, &o, BG_ERR_PATTERN, "constraint pattern is 2 x 2",
                     "dae_create: cons_pattern rows other than ncons");
        sp_csc_free(&G);
        sp_csc *J3 = sp_csc_alloc(3, 3, 0);
        q = p;
        q.jac_y_pattern = J3;
        create_fails(&q, &o, BG_ERR_PATTERN, "3 x 3", "dae_create: dF/dy pattern 3 x 3 for n = 2");
        sp_csc_free(&J3);
        int cp[3] = {0, 1, 1}, ri[1] = {5};
        double v[1] = {0};
        sp_csc bad = {2, 2, 1, cp, ri, v};
        q = p;
        q.jac_yp_pattern = &bad;
        create_fails(&q, &o, BG_ERR_PATTERN, "dF/dy'", "dae_create: invalid dF/dy' pattern");
    }
    {
        int kind[2] = {DAE_DIFF, 7};
        q = p;
        q.kind = kind;
        create_fails(&q, &o, BG_ERR_ARGUMENT, "kind[1] = 7", "dae_create: kind out of range");
        kind[1] = DAE_DIFF;
        create_fails(&q, &o, BG_ERR_ARGUMENT, "plant.y is declared differential",
                     "dae_create: a differential unknown without y'");
    }
    {
        /* equation 1 depends on nothing: dF/dy has only (0,0) */
        sp_builder *b = sp_builder_create(2, 2, 2);
        sp_builder_add(b, 0, 0, 0);
        sp_builder_add(b, 0, 1, 0);
        sp_csc *J = sp_builder_finish(b, NULL);
        sp_builder_free(&b);
        q = p;
        q.jac_y_pattern = J;
        create_fails(&q, &o, BG_ERR_PATTERN, "plant.output depends on no variable",
                     "dae_create: an empty equation, named by eq_names");
        q.eq_names = NULL;
        create_fails(&q, &o, BG_ERR_PATTERN, "equation 1 depends on no variable",
                     "dae_create: an empty equation without eq_names, named by its number");
        sp_csc_free(&J);
    }
    q = p;
    q.ncons = 1;
    q.cons = dummy_cons;
    q.nroots = 1;
    q.roots = dummy_roots;
    {
        sp_csc *G = sp_csc_alloc(1, 2, 1);
        if (G) {
            G->rowind[0] = 0;
            G->colptr[1] = G->colptr[2] = 1;
            G->nnz = 1;
        }
        q.cons_pattern = G;
        bg_error e = {0};
        dae_solver *s = dae_create(&q, &o, &e);
        tap_ok(s != NULL, "dae_create: a valid problem with constraints and events ('%s')",
               e.message);
        dae_free(&s);
        sp_csc_free(&G);
    }
    dae_free(NULL);
    sp_csc_free(&Jy);
    sp_csc_free(&Jyp);
}

static void test_dae_order(void)
{
    sp_csc *Jy = NULL, *Jyp = NULL;
    small_patterns(&Jy, &Jyp);
    dae_problem p;
    dae_options o;
    small_problem(&p, Jy, Jyp);
    dae_options_default(&o);
    bg_error e = {0};
    dae_solver *s = dae_create(&p, &o, &e);
    if (!s) {
        tap_ok(0, "dae order: solver (%s)", e.message);
        return;
    }
    double y[2] = {1, 1}, yp[2] = {-1, 0}, t = -1, Y[6] = {0};
    const char *msg = dae_get_error(s)->message;
    char buf[256];

    /* before dae_init */
    expect(dae_solve_to(s, 1.0, &t, y, yp), BG_ERR_STATE, msg, "dae_init",
           "dae_solve_to before dae_init");
    expect(dae_step(s, 1.0, &t, y, yp), BG_ERR_STATE, msg, "dae_init", "dae_step before dae_init");
    expect(dae_consistent_init(s), BG_ERR_STATE, msg, "dae_init",
           "dae_consistent_init before dae_init");
    tap_ok(dae_dense(s, 0.0, y, yp) == BG_ERR_STATE, "dae_dense before dae_init: BG_ERR_STATE");
    tap_ok(isnan(dae_current_time(s)) && isnan(dae_current_time(NULL)),
           "dae_current_time before dae_init and for NULL is NaN");

    /* dae_init arguments */
    tap_ok(dae_init(NULL, 0, y, yp) == BG_ERR_ARGUMENT, "dae_init(NULL solver)");
    expect(dae_init(s, 0, NULL, yp), BG_ERR_ARGUMENT, msg, "y0", "dae_init(y0 NULL)");
    expect(dae_init(s, NAN, y, yp), BG_ERR_ARGUMENT, msg, "t0", "dae_init(t0 NaN)");
    double ybad[2] = {1, NAN};
    expect(dae_init(s, 0, ybad, yp), BG_ERR_NONFINITE, msg, "plant.y",
           "dae_init(a NaN value) names the unknown");
    tap_ok(dae_reinit(NULL, 0, y, yp) == BG_ERR_ARGUMENT, "dae_reinit(NULL solver)");
    tap_ok(dae_set_history(NULL, 0, 0.1, 1, Y) == BG_ERR_ARGUMENT, "dae_set_history(NULL solver)");
    expect(dae_set_history(s, 0, 0.1, 9, Y), BG_ERR_ARGUMENT, msg, "k = 9",
           "dae_set_history(k = 9)");
    expect(dae_set_history(s, 0, 0.1, 1, NULL), BG_ERR_ARGUMENT, msg, "needs",
           "dae_set_history(Y NULL)");
    Y[3] = NAN;
    expect(dae_set_history(s, 0, 0.1, 2, Y), BG_ERR_NONFINITE, msg, "y(t0 - 1 h) of unknown 1",
           "dae_set_history(a NaN in the history)");
    Y[3] = 0.0;

    /* a proper start */
    tap_ok(dae_init(s, 0, y, yp) == BG_OK && dae_consistent_init(s) == BG_OK &&
               dae_consistent_init(s) == BG_OK && dae_current_time(s) == 0.0,
           "dae_init, dae_consistent_init (twice) work");
    expect(dae_solve_to(s, 1.0, NULL, y, yp), BG_ERR_ARGUMENT, msg, "tret",
           "dae_solve_to(tret NULL)");
    expect(dae_solve_to(s, NAN, &t, y, yp), BG_ERR_ARGUMENT, msg, "not finite",
           "dae_solve_to(tout NaN)");
    tap_ok(dae_solve_to(NULL, 1.0, &t, y, yp) == BG_ERR_ARGUMENT &&
               dae_step(NULL, 1.0, &t, y, yp) == BG_ERR_ARGUMENT,
           "dae_solve_to / dae_step (NULL solver)");
    int rc = dae_solve_to(s, 0.5, &t, NULL, NULL);
    tap_ok(rc == DAE_SUCCESS && t == 0.5, "dae_solve_to with y, yp NULL works (%s)",
           dae_return_name(rc));
    expect(dae_consistent_init(s), BG_ERR_STATE, msg, "dae_reinit",
           "dae_consistent_init after the first step");
    expect(dae_solve_to(s, 0.1, &t, y, yp), BG_ERR_ARGUMENT, msg, "behind",
           "dae_solve_to(tout behind the last step)");
    rc = dae_solve_to(s, 1.0, &t, y, yp);
    tap_ok(rc == DAE_SUCCESS && fabs(y[0] - exp(-1.0)) < 1e-4,
           "an argument error does not stop the integration (%s, x(1) = %.6f)", dae_return_name(rc),
           y[0]);
    tap_ok(dae_dense(NULL, 1.0, y, yp) == BG_ERR_ARGUMENT &&
               dae_dense(s, 7.0, y, yp) == BG_ERR_ARGUMENT && dae_dense(s, 1.0, y, NULL) == BG_OK,
           "dae_dense: NULL solver, t outside the last step");
    tap_ok(dae_roots_found(NULL, NULL) == BG_ERR_ARGUMENT &&
               dae_roots_found(s, NULL) == BG_ERR_ARGUMENT,
           "dae_roots_found with NULL");
    tap_ok(dae_get_error(NULL) == NULL && dae_get_stats(NULL) == NULL && dae_get_stats(s) != NULL,
           "dae getters with NULL");
    tap_ok(dae_stats_line(NULL, buf, sizeof buf) == BG_ERR_ARGUMENT &&
               dae_stats_line(dae_get_stats(s), NULL, 8) == BG_ERR_ARGUMENT &&
               dae_stats_csv(NULL, buf, sizeof buf) == BG_ERR_ARGUMENT &&
               dae_stats_csv_header(NULL, 8) == BG_ERR_ARGUMENT &&
               dae_stats_line(dae_get_stats(s), buf, sizeof buf) > 0,
           "dae statistics output with NULL");

    /* a failure stops the solver until dae_reinit */
    t_fatal = 1.5;
    rc = dae_solve_to(s, 3.0, &t, y, yp);
    expect(rc, DAE_CALLBACK_FAIL, msg, "fatal status -1", "a fatal residual after t = 1.5");
    tap_ok(t <= 1.5 && t > 1.0, "the last good state is returned (t = %.6g)", t);
    rc = dae_solve_to(s, 3.0, &t, y, yp);
    expect(rc, BG_ERR_STATE, msg, "DAE_CALLBACK_FAIL", "dae_solve_to after a failure");
    tap_ok(has(msg, "dae_reinit"), "the message says what to do: '%s'", msg);
    expect(dae_step(s, 3.0, &t, y, yp), BG_ERR_STATE, msg, "stopped with DAE_CALLBACK_FAIL",
           "dae_step after a failure");
    double tf = dae_current_time(s);
    tap_ok(dae_dense(s, tf, y, yp) == BG_OK && fabs(y[0] - exp(-tf)) < 1e-4,
           "the state at the failure stays readable (x(%.4g) = %.6f)", tf, y[0]);
    t_fatal = INFINITY;
    rc = dae_reinit(s, tf, y, yp);
    int rc2 = rc == BG_OK ? dae_solve_to(s, 3.0, &t, y, yp) : rc;
    tap_ok(rc == BG_OK && rc2 == DAE_SUCCESS && fabs(y[0] - exp(-3.0)) < 1e-4,
           "dae_reinit clears the failure (%s, x(3) = %.6f)", dae_return_name(rc2), y[0]);
    dae_free(&s);

    /* DAE_TOO_MUCH_WORK does not stop the solver */
    o.max_steps = 3;
    s = dae_create(&p, &o, &e);
    y[0] = y[1] = 1;
    yp[0] = -1;
    yp[1] = 0;
    rc = s ? dae_init(s, 0, y, yp) : -1000;
    if (rc == BG_OK) rc = dae_solve_to(s, 1.0, &t, y, yp);
    rc2 = s ? dae_solve_to(s, 1.0, &t, y, yp) : -1000;
    tap_ok(rc == DAE_TOO_MUCH_WORK && (rc2 == DAE_TOO_MUCH_WORK || rc2 == DAE_SUCCESS),
           "DAE_TOO_MUCH_WORK (%s) may be continued (%s)", dae_return_name(rc),
           dae_return_name(rc2));
    /* dae_set_history then dae_consistent_init */
    for (int i = 0; i < 6; i++)
        Y[i] = 1.0;
    rc = s ? dae_set_history(s, 0.0, 0.01, 2, Y) : -1000;
    tap_ok(rc == BG_OK, "dae_set_history works (%s)", dae_return_name(rc));
    if (s)
        expect(dae_consistent_init(s), BG_ERR_STATE, dae_get_error(s)->message, "dae_set_history",
               "dae_consistent_init after dae_set_history");
    dae_free(&s);
    sp_csc_free(&Jy);
    sp_csc_free(&Jyp);
}

/* ------------------------------------------------------------ bond graphs ---- */

static int destroyed;
static void count_destroy(void *p)
{
    destroyed++;
    free(p);
}

static int nop_declare(bgr_element *el, bgr_model *m)
{
    (void)el, (void)m;
    return BG_OK;
}
static int nop_res(const bgr_element *el, double t, const double *y, const double *yp, double *F)
{
    (void)el, (void)t, (void)y, (void)yp, (void)F;
    return 0;
}
static int nop_jac(const bgr_element *el, double t, const double *y, const double *yp, double *v)
{
    (void)el, (void)t, (void)y, (void)yp, (void)v;
    return 0;
}
static const bgr_element_class nop_class = {.type = "nop",
                                            .declare = nop_declare,
                                            .residual = nop_res,
                                            .jacobian = nop_jac,
                                            .destroy = count_destroy};

static bgr_port P(const bgr_model *m, int e, int k)
{
    return bgr_port_of(m, e, k);
}

/* Se -> R: two unknowns (e, f), two equations. */
static bgr_model *se_r(const char *name)
{
    bgr_model *m = bgr_model_create(name);
    double one = 1.0;
    int S = bgr_Se(m, 0, "S", 1, &one), R = bgr_R(m, 0, "R", 1, 2.0);
    bgr_bond(m, 0, "b", 1, P(m, S, 0), P(m, R, 0), NULL, NULL);
    return m;
}

static void test_bondgraph_null(void)
{
    bgr_model *m = NULL;
    dae_problem p;
    bgr_stats st;
    double y[2] = {0}, v[2];
    char rep[64];
    bgr_ref r = {BGR_EFFORT, 0, 0};
    bgr_model_free(NULL);
    bgr_model_free(&m);
    tap_ok(bgr_component(NULL, 0, "c") == BG_ERR_ARGUMENT && bgr_compile(NULL) == BG_ERR_ARGUMENT &&
               bgr_dae_problem(NULL, &p) == BG_ERR_ARGUMENT &&
               bgr_get_stats(NULL, &st) == BG_ERR_ARGUMENT &&
               bgr_stats_print(NULL, stdout) == BG_ERR_ARGUMENT &&
               bgr_list_equations(NULL, stdout) == BG_ERR_ARGUMENT &&
               bgr_check_jacobian(NULL, 0, y, y, 1e-6, rep, sizeof rep) == BG_ERR_ARGUMENT &&
               bgr_residual(NULL, 0, y, y, v) == BG_ERR_ARGUMENT &&
               bgr_jacobian(NULL, 0, y, y, NULL, NULL) == BG_ERR_ARGUMENT &&
               bgr_breakpoints(NULL, 0, 1, v, 2) == BG_ERR_ARGUMENT &&
               bgr_export(NULL, 0, "p", P(NULL, 0, 0)) == BG_ERR_ARGUMENT &&
               bgr_bond(NULL, 0, "b", 1, P(NULL, 0, 0), P(NULL, 1, 0), NULL, NULL) ==
                   BG_ERR_ARGUMENT,
           "bond graph: NULL model gives BG_ERR_ARGUMENT (and prints nothing)");
    tap_ok(bgr_n(NULL) == 0 && bgr_nvars(NULL) == 0 && !bgr_var_name(NULL, 0) &&
               !bgr_eq_name(NULL, 0) && !bgr_kinds(NULL) && !bgr_y0(NULL) && !bgr_yp0(NULL) &&
               bgr_find_var(NULL, "x") == -1 && bgr_find_eq(NULL, "x") == -1 &&
               !bgr_component_path(NULL, 0) && P(NULL, 0, 0).elem == -1 &&
               !bgr_element_get(NULL, 0) && bgr_comp_port(NULL, 0, "p").elem == -1 &&
               bgr_ref_var(NULL, r) == -1 && !bgr_model_error(NULL) && !bgr_model_error_mut(NULL),
           "bond graph: queries of a NULL model give 0 / NULL / -1");
    tap_ok(bgr_ev(NULL, NULL, 0, 0) == -1 && bgr_fv(NULL, NULL, 0, 0) == -1 &&
               bgr_sv(NULL, 0) == -1 && bgr_av(NULL, 0) == -1 &&
               bgr_port_dim(NULL, NULL, 0) == BG_ERR_ARGUMENT,
           "bond graph: element helpers with NULL");
    destroyed = 0;
    int id = bgr_element_add(NULL, 0, "x", &nop_class, malloc(8), 0, NULL, 0, NULL, 0, NULL);
    tap_ok(id == BG_ERR_ARGUMENT && destroyed == 1,
           "bgr_element_add(NULL model): BG_ERR_ARGUMENT, parameters destroyed (%d)", destroyed);
}

static void test_bondgraph_states(void)
{
    bgr_model *m = se_r("m1");
    const char *msg = bgr_model_error(m)->message;
    dae_problem p = {0};
    bgr_stats st;
    double y[2] = {0, 0}, yp[2] = {0, 0}, F[2], t[4];
    char rep[128];
    FILE *devnull = fopen("/dev/null", "w");

    /* building: bad arguments */
    int dims[1] = {-1};
    destroyed = 0;
    int id = bgr_element_add(m, 0, "neg", &nop_class, malloc(8), 1, dims, 0, NULL, 0, NULL);
    expect(id, BG_ERR_ARGUMENT, msg, "dimension -1", "bgr_element_add: negative port dimension");
    tap_ok(destroyed == 1, "the refused element's parameters are destroyed");
    expect(bgr_I_matrix(m, 0, "Im", 2, NULL), BG_ERR_ARGUMENT, msg, "mass matrix",
           "bgr_I_matrix(M NULL)");
    expect(bgr_R_fn(m, 0, "Rf", NULL, NULL), BG_ERR_ARGUMENT, msg, "function", "bgr_R_fn(NULL)");
    expect(bgr_Sf_fn(m, 0, "Sf", NULL, NULL), BG_ERR_ARGUMENT, msg, "function", "bgr_Sf_fn(NULL)");
    bgr_port bad = {99, 0};
    expect(bgr_export(m, 0, "p", bad), BG_ERR_ARGUMENT, msg, "inner port",
           "bgr_export(an element that does not exist)");

    /* queries before compilation */
    expect(bgr_dae_problem(m, &p), BG_ERR_STATE, msg, "compile", "bgr_dae_problem before compile");
    expect(bgr_dae_problem(m, NULL), BG_ERR_ARGUMENT, msg, "NULL", "bgr_dae_problem(p NULL)");
    expect(bgr_get_stats(m, &st), BG_ERR_STATE, msg, "not compiled",
           "bgr_get_stats before compile");
    tap_ok(st.elements == 2 && st.bonds == 1 && st.equations == 0,
           "bgr_get_stats before compile still counts elements and bonds (%d, %d)", st.elements,
           st.bonds);
    expect(bgr_stats_print(m, devnull), BG_ERR_STATE, msg, "bgr_compile",
           "bgr_stats_print before compile");
    expect(bgr_list_equations(m, devnull), BG_ERR_STATE, msg, "not compiled",
           "bgr_list_equations before compile");
    expect(bgr_check_jacobian(m, 0, y, yp, 1e-6, rep, sizeof rep), BG_ERR_STATE, msg,
           "not compiled", "bgr_check_jacobian before compile");
    expect(bgr_residual(m, 0, y, yp, F), BG_ERR_STATE, msg, "not compiled",
           "bgr_residual before compile");
    expect(bgr_jacobian(m, 0, y, yp, NULL, NULL), BG_ERR_STATE, msg, "not compiled",
           "bgr_jacobian before compile");
    bgr_element *el = bgr_element_get(m, 1);
    expect(bgr_declare_equations(el, m, 1, NULL), BG_ERR_STATE, msg, "declare()",
           "bgr_declare_equations outside bgr_compile");
    expect(bgr_declare_dep(el, m, 0, 0, 0), BG_ERR_STATE, msg, "declare()",
           "bgr_declare_dep outside bgr_compile");
    expect(bgr_declare_index2(el, m, 0), BG_ERR_STATE, msg, "declare()",
           "bgr_declare_index2 outside bgr_compile");
    expect(bgr_declare_nominal(el, m, 0, 1.0), BG_ERR_STATE, msg, "declare()",
           "bgr_declare_nominal outside bgr_compile");
    expect(bgr_set_nominal(m, 0, 1.0), BG_ERR_STATE, msg, "not compiled",
           "bgr_set_nominal before compile");
    tap_ok(bgr_nominals(m) == NULL, "bgr_nominals before compile is NULL");
    tap_ok(bgr_ev(el, m, 0, 0) == -1, "bgr_ev before numbering gives -1");
    expect(bgr_breakpoints(m, 0, 1, NULL, 2), BG_ERR_ARGUMENT, msg, "room",
           "bgr_breakpoints(t NULL, max 2)");
    expect(bgr_breakpoints(m, 0, 1, t, -1), BG_ERR_ARGUMENT, msg, "max -1",
           "bgr_breakpoints(max -1)");
    tap_ok(bgr_breakpoints(m, 0, 1, t, 4) == 0, "bgr_breakpoints works before compilation");

    /* an element of another model */
    bgr_model *other = se_r("other");
    expect(bgr_declare_dep(bgr_element_get(other, 0), m, 0, 0, 0), BG_ERR_ARGUMENT, msg,
           "not one of model m1", "bgr_declare_dep with an element of another model");
    bgr_model_free(&other);

    /* compiled */
    tap_ok(bgr_compile(m) == BG_OK, "the model compiles ('%s')", msg);
    expect(bgr_compile(m), BG_ERR_STATE, msg, "compiled already", "bgr_compile twice");
    destroyed = 0;
    id = bgr_element_add(m, 0, "late", &nop_class, malloc(8), 0, NULL, 0, NULL, 0, NULL);
    expect(id, BG_ERR_STATE, msg, "compiled", "bgr_element_add after compile");
    tap_ok(destroyed == 1, "its parameters are destroyed");
    expect(bgr_R(m, 0, "R2", 1, 1.0), BG_ERR_STATE, msg, "compiled", "bgr_R after compile");
    expect(bgr_component(m, 0, "late"), BG_ERR_STATE, msg, "compiled",
           "bgr_component after compile");
    expect(bgr_bond(m, 0, "late", 1, P(m, 0, 0), P(m, 1, 0), NULL, NULL), BG_ERR_STATE, msg,
           "compiled", "bgr_bond after compile");
    expect(bgr_export(m, 0, "late", P(m, 0, 0)), BG_ERR_STATE, msg, "compiled",
           "bgr_export after compile");
    expect(bgr_declare_equations(bgr_element_get(m, 0), m, 1, NULL), BG_ERR_STATE, msg, "declare()",
           "bgr_declare_equations after compile");
    int pst = bgr_dae_problem(m, &p); /* first: the arguments below read p */
    tap_ok(pst == BG_OK && p.n == 2 && p.eq_names &&
               !strcmp(p.eq_names[0], bgr_eq_name(m, 0)) && p.names &&
               !strcmp(p.names[0], "m1/b/e"),
           "bgr_dae_problem gives the names of the unknowns and equations (%s, %s)",
           p.names ? p.names[0] : "-", p.eq_names ? p.eq_names[0] : "-");
    expect(bgr_residual(m, 0, NULL, yp, F), BG_ERR_ARGUMENT, msg, "must be given",
           "bgr_residual(y NULL)");
    {
        sp_csc *J1 = sp_csc_alloc(2, 2, 0);
        expect(bgr_jacobian(m, 0, y, yp, J1, J1), BG_ERR_PATTERN, msg, "patterns",
               "bgr_jacobian with matrices of other patterns");
        expect(bgr_jacobian(m, 0, y, yp, NULL, J1), BG_ERR_ARGUMENT, msg, "must be given",
               "bgr_jacobian(Jy NULL)");
        sp_csc_free(&J1);
    }
    expect(bgr_check_jacobian(m, 0, NULL, yp, 1e-6, rep, sizeof rep), BG_ERR_ARGUMENT, msg,
           "y NULL", "bgr_check_jacobian(y NULL)");
    expect(bgr_check_jacobian(m, 0, y, yp, 0.0, rep, sizeof rep), BG_ERR_ARGUMENT, msg, "tol 0",
           "bgr_check_jacobian(tol 0)");
    tap_ok(bgr_check_jacobian(m, 0, y, yp, 1e-6, rep, sizeof rep) == 0,
           "bgr_check_jacobian works ('%s')", rep);
    expect(bgr_list_equations(m, NULL), BG_ERR_ARGUMENT, msg, "file", "bgr_list_equations(f NULL)");
    expect(bgr_stats_print(m, NULL), BG_ERR_ARGUMENT, msg, "file", "bgr_stats_print(f NULL)");
    expect(bgr_get_stats(m, NULL), BG_ERR_ARGUMENT, msg, "NULL", "bgr_get_stats(st NULL)");
    tap_ok(bgr_get_stats(m, &st) == BG_OK && bgr_stats_print(m, devnull) == BG_OK &&
               bgr_list_equations(m, devnull) == BG_OK,
           "statistics and listing work after compilation");
    el = bgr_element_get(m, 1);
    tap_ok(bgr_ev(el, m, 0, 0) == 0 && bgr_fv(el, m, 0, 0) == 1 && bgr_ev(el, m, 1, 0) == -1 &&
               bgr_ev(el, m, 0, 1) == -1 && bgr_fv(el, m, -1, 0) == -1 &&
               bgr_port_dim(el, m, 0) == 1 && bgr_port_dim(el, m, 3) == BG_ERR_ARGUMENT,
           "bgr_ev / bgr_fv / bgr_port_dim: ports and components out of range");
    bgr_model_free(&m);

    /* a failed compilation: only freeing */
    m = bgr_model_create("broken");
    msg = bgr_model_error(m)->message;
    bgr_R(m, 0, "R", 1, 1.0);
    tap_ok(bgr_compile(m) == BG_ERR_PATTERN, "an unconnected port fails to compile ('%s')", msg);
    expect(bgr_R(m, 0, "R2", 1, 1.0), BG_ERR_STATE, msg, "earlier compilation failed",
           "adding to a model whose compilation failed");
    expect(bgr_dae_problem(m, &p), BG_ERR_STATE, msg, "compile",
           "bgr_dae_problem after a failed compilation");
    expect(bgr_list_equations(m, devnull), BG_ERR_STATE, msg, "compilation of model broken failed",
           "bgr_list_equations after a failed compilation");
    bgr_model_free(&m);
    if (devnull) fclose(devnull);
}

/* --------------------------------------------------- element constructors ---- */

static int user_fn(void *user, double t, const double *x, double *u, double *jac)
{
    (void)user, (void)t, (void)jac;
    u[0] = x[0];
    return 0;
}

static void test_constructors(void)
{
    const double g[3] = {0, 0, -9.81}, J[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1}, r3[3] = {0, 0, 0};
    const double E0[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1}, p1[3] = {1, 0, 0}, up[3] = {0, 0, 1};
    const double tt[2] = {0, 1}, vv[2] = {0, 1}, one = 1.0;
    const mech_section sec = {2e11, 8e10, 1e-2, 1e-5, 1e-5, 2e-5, 7800, 0, 0, MECH_BEAM_LUMPED};
    ctl_pid_spec spec;
    memset(&spec, 0, sizeof spec);
    ctl_ff_spec ffs = {.ratio = 1, .motor_disp = 1, .pump_disp = 1, .pump_speed = 1};
    ctl_sf_spec sfs = {.n = 1, .gain = {1}};
    ctl_sway_spec sws = {.cx = 0};
    ctl_user_spec us = {.n_in = 1, .n_out = 1, .fn = user_fn};
    bgr_ref ref = {BGR_EFFORT, 0, 0};
    int nodes[3] = {0, 1, 2}, elems[2] = {0, 0};

    /* every constructor with a NULL model */
    struct {
        const char *what;
        int rc;
    } null_model[] = {
        {"bgr_I", bgr_I(NULL, 0, "x", 1, 1.0)},
        {"bgr_I_matrix", bgr_I_matrix(NULL, 0, "x", 3, J)},
        {"bgr_C", bgr_C(NULL, 0, "x", 1, 1.0)},
        {"bgr_R", bgr_R(NULL, 0, "x", 1, 1.0)},
        {"bgr_Se", bgr_Se(NULL, 0, "x", 1, &one)},
        {"bgr_Sf", bgr_Sf(NULL, 0, "x", 1, &one)},
        {"bgr_Se_signal", bgr_Se_signal(NULL, 0, "x", ref)},
        {"bgr_Sf_signal", bgr_Sf_signal(NULL, 0, "x", ref)},
        {"bgr_TF", bgr_TF(NULL, 0, "x", 1, 2.0)},
        {"bgr_TF_signal", bgr_TF_signal(NULL, 0, "x", ref)},
        {"bgr_GY", bgr_GY(NULL, 0, "x", 1, 2.0)},
        {"bgr_zero", bgr_zero(NULL, 0, "x", 3, 1)},
        {"bgr_one", bgr_one(NULL, 0, "x", 3, 1)},
        {"bgr_gain", bgr_gain(NULL, 0, "x", ref, 2.0)},
        {"ctl_pid", ctl_pid(NULL, 0, "x", &spec)},
        {"ctl_feedforward", ctl_feedforward(NULL, 0, "x", &ffs)},
        {"ctl_shaped_pwl", ctl_shaped_pwl(NULL, 0, "x", 2, tt, vv, CTL_SHAPER_ZV, 1.0, 0.0,
                                          SIG_VALUE)},
        {"ctl_state_feedback", ctl_state_feedback(NULL, 0, "x", &sfs)},
        {"ctl_sway", ctl_sway(NULL, 0, "x", &sws)},
        {"ctl_user", ctl_user(NULL, 0, "x", &us)},
        {"hyd_motor", hyd_motor(NULL, 0, "x", 1e-4, 0, 0)},
        {"hyd_pump", hyd_pump(NULL, 0, "x", 1e-4, 0, ref)},
        {"hyd_tank", hyd_tank(NULL, 0, "x", 1e5)},
        {"hyd_pressure_source_signal", hyd_pressure_source_signal(NULL, 0, "x", ref)},
        {"hyd_flow_source", hyd_flow_source(NULL, 0, "x", 1e-3)},
        {"hyd_flow_source_signal", hyd_flow_source_signal(NULL, 0, "x", ref)},
        {"hyd_leakage", hyd_leakage(NULL, 0, "x", 1e-12)},
        {"hyd_relief_valve", hyd_relief_valve(NULL, 0, "x", 1e7, 1.1e7, 1e-3, 1e4)},
        {"hyd_volume", hyd_volume(NULL, 0, "x", 2, 1e-3, 1e9)},
        {"rot_damper", rot_damper(NULL, 0, "x", 1.0)},
        {"rot_gear", rot_gear(NULL, 0, "x", 2.0)},
        {"rot_inertia", rot_inertia(NULL, 0, "x", 1.0)},
        {"rot_sensor", rot_sensor(NULL, 0, "x", 0, ROT_ANGLE)},
        {"sig_trapezoid", sig_trapezoid(NULL, 0, "x", 0, 1, 2, 3, 1, SIG_VALUE)},
        {"sig_pwl", sig_pwl(NULL, 0, "x", 2, tt, vv, SIG_VALUE)},
        {"sig_step", sig_step(NULL, 0, "x", 1, 0, 1, SIG_VALUE)},
        {"sig_ramp", sig_ramp(NULL, 0, "x", 1, 1, 0, SIG_VALUE)},
        {"sig_sine", sig_sine(NULL, 0, "x", 1, 1, 0, 0, SIG_VALUE)},
        {"sig_constant", sig_constant(NULL, 0, "x", 1, SIG_VALUE)},
        {"sig_evaluate", sig_evaluate(NULL, 0, 0, NULL, NULL, NULL)},
        {"mech_spring", mech_spring(NULL, 0, "x", 1, 0, 1)},
        {"mech_truss", mech_truss(NULL, 0, "x", 2e11, 1e-4, 1, 0)},
        {"mech_rope", mech_rope(NULL, 0, "x", 1e6, 0, 1, 0)},
        {"mech_axial_set", mech_axial_set(NULL, 0, r3, p1)},
        {"mech_beam", mech_beam(NULL, 0, "x", 0, 1, &sec, E0, 1)},
        {"mech_beam_chain",
         mech_beam_chain(NULL, 0, "x", 2, r3, p1, up, &sec, g, NULL, NULL, nodes, elems)},
        {"mech_beam_chain_set", mech_beam_chain_set(NULL, nodes, 2, r3, p1)},
        {"mech_body", mech_body(NULL, 0, "x", 1, J, g, 1, r3, NULL)},
        {"mech_body_set", mech_body_set(NULL, 0, r3, r3, r3, NULL)},
        {"mech_point_mass", mech_point_mass(NULL, 0, "x", 1, g)},
        {"mech_point_mass_set", mech_point_mass_set(NULL, 0, r3, r3)},
        {"mech_support", mech_support(NULL, 0, "x", 3)},
        {"mech_spherical", mech_spherical(NULL, 0, "x", 3)},
        {"mech_revolute", mech_revolute(NULL, 0, "x", -1, up, 1)},
        {"mech_rotation_sensor", mech_rotation_sensor(NULL, 0, "x", 0, up)},
        {"mech_set_nominal", mech_set_nominal(NULL, 0, 1, 1, 1)},
        {"hyd_volume_set_nominal", hyd_volume_set_nominal(NULL, 0, 1e7)},
        {"hyd_pump_set_nominal", hyd_pump_set_nominal(NULL, 0, 1e7, 100)},
        {"hyd_motor_set_nominal", hyd_motor_set_nominal(NULL, 0, 1e7, 100)},
        {"rot_inertia_set_nominal", rot_inertia_set_nominal(NULL, 0, 100)},
        {"bgr_set_nominal", bgr_set_nominal(NULL, 0, 1)},
    };
    int bad = 0;
    for (size_t k = 0; k < sizeof null_model / sizeof *null_model; k++)
        if (null_model[k].rc != BG_ERR_ARGUMENT) {
            bad++;
            tap_diag("%s(NULL model) returned %d", null_model[k].what, null_model[k].rc);
        }
    tap_ok(bad == 0, "%zu constructors and setters with a NULL model give BG_ERR_ARGUMENT",
           sizeof null_model / sizeof *null_model);
    tap_ok(mech_body_var(NULL, 0, 'x') == -1 && isnan(mech_axial_energy(NULL, 0, r3)) &&
               isnan(mech_axial_tension(NULL, 0, r3)) && isnan(mech_beam_energy(NULL, 0, r3)) &&
               mech_beam_chain_port(NULL, nodes, 2, NULL, 0, 0).elem == -1 &&
               rot_inertia_moment(NULL) == 0.0,
           "component queries with a NULL model give -1 / NaN / an invalid port");

    /* NULL pointers the component needs */
    bgr_model *m = bgr_model_create("parts");
    const char *msg = bgr_model_error(m)->message;
    expect(ctl_pid(m, 0, "pid", NULL), BG_ERR_ARGUMENT, msg, "specification", "ctl_pid(spec NULL)");
    expect(ctl_feedforward(m, 0, "ff", NULL), BG_ERR_ARGUMENT, msg, "specification",
           "ctl_feedforward(spec NULL)");
    expect(ctl_state_feedback(m, 0, "sf", NULL), BG_ERR_ARGUMENT, msg, "specification",
           "ctl_state_feedback(spec NULL)");
    expect(ctl_sway(m, 0, "sway", NULL), BG_ERR_ARGUMENT, msg, "specification",
           "ctl_sway(spec NULL)");
    expect(ctl_user(m, 0, "user", NULL), BG_ERR_ARGUMENT, msg, "callback",
           "ctl_user(spec NULL)");
    expect(ctl_shaped_pwl(m, 0, "shaper", 2, NULL, vv, CTL_SHAPER_ZV, 1.0, 0.0, SIG_VALUE),
           BG_ERR_ARGUMENT, msg, "knots", "ctl_shaped_pwl(t NULL)");
    bg_error le = {0};
    expect(ctl_lqr(2, 1, NULL, NULL, NULL, NULL, NULL, NULL, &le), BG_ERR_ARGUMENT, le.message,
           "NULL", "ctl_lqr(matrices NULL)");
    expect(mech_body(m, 0, "body", 1, NULL, g, 1, r3, NULL), BG_ERR_ARGUMENT, msg, "inertia",
           "mech_body(inertia NULL)");
    expect(mech_body(m, 0, "body", 1, J, g, 1, NULL, NULL), BG_ERR_ARGUMENT, msg, "points",
           "mech_body(points NULL)");
    expect(mech_beam(m, 0, "beam", 0, 1, NULL, E0, 1), BG_ERR_ARGUMENT, msg, "section",
           "mech_beam(section NULL)");
    expect(mech_beam(m, 0, "beam", 0, 1, &sec, NULL, 1), BG_ERR_ARGUMENT, msg, "frame",
           "mech_beam(frame NULL)");
    expect(mech_beam_chain(m, 0, "ch", 2, r3, p1, NULL, &sec, g, NULL, NULL, nodes, elems),
           BG_ERR_ARGUMENT, msg, "up vector", "mech_beam_chain(up NULL)");
    expect(mech_beam_chain(m, 0, "ch", 2, r3, p1, up, &sec, g, NULL, NULL, NULL, elems),
           BG_ERR_ARGUMENT, msg, "node and element ids", "mech_beam_chain(nodes NULL)");
    {
        int extra[3] = {0, -1, 0};
        expect(mech_beam_chain(m, 0, "ch", 2, r3, p1, up, &sec, g, extra, NULL, nodes, elems),
               BG_ERR_ARGUMENT, msg, "negative number of extra ports",
               "mech_beam_chain(a negative extra count)");
    }
    expect(mech_beam_chain_set(m, NULL, 2, r3, p1), BG_ERR_ARGUMENT, msg, "node ids",
           "mech_beam_chain_set(nodes NULL)");
    expect(mech_revolute(m, 0, "rev", -1, NULL, 1), BG_ERR_ARGUMENT, msg, "axis",
           "mech_revolute(axis NULL)");
    expect(mech_rotation_sensor(m, 0, "rs", 0, NULL), BG_ERR_ARGUMENT, msg, "axis",
           "mech_rotation_sensor(axis NULL)");
    expect(sig_pwl(m, 0, "pwl", 2, NULL, vv, SIG_VALUE), BG_ERR_ARGUMENT, msg, "points",
           "sig_pwl(t NULL)");
    expect(hyd_volume(m, 0, NULL, 2, 1e-3, 1e9), BG_ERR_ARGUMENT, msg, "name",
           "hyd_volume(name NULL)");
    expect(mech_axial_set(m, 0, r3, p1), BG_ERR_ARGUMENT, msg, "compiled model",
           "mech_axial_set before compilation");
    {
        double K, V;
        tap_ok(mech_body_energy(m, 0, r3, &K, &V) == BG_ERR_ARGUMENT &&
                   mech_point_mass_energy(m, 0, r3, NULL, &V) == BG_ERR_ARGUMENT,
               "energies of a model that is not compiled (or with NULL outputs)");
    }
    /* a compiled model refuses components */
    int pm = mech_point_mass(m, 0, "pm", 1.0, g), sup = mech_support(m, 0, "sup", 3);
    int sp = mech_spring(m, 0, "spring", 100.0, 1.0, 1.0);
    int b1 = bgr_bond(m, 0, "b1", 3, P(m, sup, 0), P(m, sp, 0), NULL, NULL);
    int b2 = bgr_bond(m, 0, "b2", 3, P(m, sp, 1), P(m, pm, 0), NULL, NULL);
    int rc = pm >= 0 && sup >= 0 && sp >= 0 && b1 >= 0 && b2 >= 0 ? bgr_compile(m) : -1000;
    tap_ok(rc == BG_OK, "a mass on a spring compiles ('%s')", msg);
    expect(hyd_volume(m, 0, "vol", 2, 1e-3, 1e9), BG_ERR_STATE, msg, "compiled",
           "hyd_volume after compilation");
    expect(mech_body(m, 0, "body2", 1, J, g, 1, r3, NULL), BG_ERR_STATE, msg, "compiled",
           "mech_body after compilation");
    expect(mech_beam_chain(m, 0, "ch2", 2, r3, p1, up, &sec, g, NULL, NULL, nodes, elems),
           BG_ERR_STATE, msg, "compiled", "mech_beam_chain after compilation");
    expect(sig_step(m, 0, "step", 1, 0, 1, SIG_VALUE), BG_ERR_STATE, msg, "compiled",
           "sig_step after compilation");
    expect(mech_axial_set(m, sp, NULL, p1), BG_ERR_ARGUMENT, msg, "end points",
           "mech_axial_set(xa NULL)");
    tap_ok(mech_axial_set(m, sp, r3, p1) == BG_OK && isnan(mech_axial_energy(m, sp, NULL)) &&
               isnan(mech_axial_tension(m, sp, NULL)),
           "mech_axial_set works; energy and tension of y NULL are NaN");
    {
        double K, V;
        tap_ok(mech_point_mass_energy(m, pm, bgr_y0(m), &K, NULL) == BG_ERR_ARGUMENT &&
                   mech_point_mass_energy(m, pm, bgr_y0(m), &K, &V) == BG_OK,
               "mech_point_mass_energy: NULL output refused, valid call works");
    }
    bgr_model_free(&m);
}

/* ------------------------------------------- static equilibrium and modes ---- */

static void test_static_modes(void)
{
    bg_error err = {0};
    sp_csc *Jy, *Jyp;
    small_patterns(&Jy, &Jyp);
    dae_problem p;
    small_problem(&p, Jy, Jyp);
    double y[2] = {1, 0}, yp[2];
    dae_static_result r;
    tap_ok(dae_static_options_default(NULL) == BG_ERR_ARGUMENT &&
               dae_modes_options_default(NULL) == BG_ERR_ARGUMENT,
           "static, modes: options_default(NULL) = BG_ERR_ARGUMENT");
    expect(dae_static_solve(NULL, NULL, 0, y, yp, &r, &err), BG_ERR_ARGUMENT, err.message,
           "problem", "dae_static_solve(NULL problem)");
    expect(dae_static_solve(&p, NULL, 0, NULL, yp, &r, &err), BG_ERR_ARGUMENT, err.message, "y",
           "dae_static_solve(NULL y)");
    expect(dae_static_solve(&p, NULL, NAN, y, yp, &r, &err), BG_ERR_ARGUMENT, err.message, "t",
           "dae_static_solve(t NaN)");
    dae_static_options so;
    dae_static_options_default(&so);
    so.max_newton = 0;
    expect(dae_static_solve(&p, &so, 0, y, yp, &r, &err), BG_ERR_ARGUMENT, err.message,
           "max_newton", "dae_static_solve(max_newton 0)");
    dae_static_options_default(&so);
    so.h0 = -1;
    expect(dae_static_solve(&p, &so, 0, y, yp, &r, &err), BG_ERR_ARGUMENT, err.message, "h0",
           "dae_static_solve(h0 < 0)");
    dae_static_options_default(&so);
    so.dlambda = 2;
    expect(dae_static_solve(&p, &so, 0, y, yp, &r, &err), BG_ERR_ARGUMENT, err.message,
           "dlambda", "dae_static_solve(dlambda 2)");
    double bad[2] = {NAN, 0};
    expect(dae_static_solve(&p, NULL, 0, bad, yp, &r, &err), BG_ERR_NONFINITE, err.message,
           "starting value of plant.x", "dae_static_solve(y NaN)");
    dae_modes *M = NULL;
    expect(dae_modes_compute(NULL, 0, y, NULL, NULL, &M, &err), BG_ERR_ARGUMENT, err.message,
           "problem", "dae_modes_compute(NULL problem)");
    expect(dae_modes_compute(&p, 0, y, NULL, NULL, NULL, &err), BG_ERR_ARGUMENT, err.message,
           "out", "dae_modes_compute(NULL out)");
    dae_modes_options mo;
    dae_modes_options_default(&mo);
    mo.nev = 0;
    expect(dae_modes_compute(&p, 0, y, NULL, &mo, &M, &err), BG_ERR_ARGUMENT, err.message,
           "options", "dae_modes_compute(nev 0)");
    tap_ok(!M && dae_modes_count(NULL) == 0 && !dae_modes_get(NULL, 0) &&
               dae_modes_info(NULL, NULL, NULL, NULL, NULL, NULL, NULL) == BG_ERR_ARGUMENT &&
               dae_modes_vector(NULL, 0, y, NULL) == BG_ERR_ARGUMENT &&
               dae_modes_describe(NULL, 0, 1, 1, 1, NULL, 0) == BG_ERR_ARGUMENT &&
               isnan(dae_modes_share(NULL, 0, "x")) && !strcmp(dae_mode_kind_name(7), "unknown"),
           "modes: the queries of NULL and out of range are refused");
    dae_modes_free(&M);
    dae_modes_free(NULL);
    expect(bgr_static(NULL, NULL, 0, NULL, &err), BG_ERR_ARGUMENT, err.message, "model",
           "bgr_static(NULL)");
    bgr_model *m = bgr_model_create("uncompiled");
    expect(bgr_static(m, NULL, 0, NULL, &err), BG_ERR_STATE, err.message, "compiled",
           "bgr_static(not compiled)");
    expect(bgr_modes(m, 0, NULL, NULL, NULL, &M, &err), BG_ERR_STATE, err.message, "compiled",
           "bgr_modes(not compiled)");
    bgr_model_free(&m);
    sp_csc_free(&Jy);
    sp_csc_free(&Jyp);
}

int main(void)
{
    test_status();
    test_sparse();
    test_fdjac();
    test_linsol();
    test_dae_create();
    test_dae_order();
    test_bondgraph_null();
    test_bondgraph_states();
    test_constructors();
    test_static_modes();
    return tap_done();
}
