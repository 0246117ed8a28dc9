/* Unit tests of bg_sparse: builder (duplicates, slot map, errors), pattern union, products,
 * transpose, dense conversions, copy, structure check and the MatrixMarket writer.
 *
 * Every value is compared against an independent dense computation done here. Values in the
 * builder tests are multiples of 1/8 with small numerators, so sums are exact in any order and
 * comparisons can be bitwise. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "bg_sparse.h"
#include "tap.h"
#include "testutil.h"

/* ---- helpers ---- */

/* A value k/8 with k in [-40, 40] \ {0}: exact sums in any order. */
static double exact_val(tap_rng *r)
{
    int k = tap_rng_int(r, 80) - 40;
    if (k >= 0) k++;
    return k / 8.0;
}

/* Independent structural check: colptr[0] == 0, monotone, nnz == colptr[ncol], rows in range and
 * strictly ascending in each column. */
static int structure_ok(const sp_csc *A)
{
    int j, p;
    if (!A || A->nrow < 0 || A->ncol < 0 || !A->colptr) return 0;
    if (A->colptr[0] != 0 || A->colptr[A->ncol] != A->nnz) return 0;
    for (j = 0; j < A->ncol; j++) {
        if (A->colptr[j + 1] < A->colptr[j]) return 0;
        for (p = A->colptr[j]; p < A->colptr[j + 1]; p++) {
            if (A->rowind[p] < 0 || A->rowind[p] >= A->nrow) return 0;
            if (p > A->colptr[j] && A->rowind[p] <= A->rowind[p - 1]) return 0;
        }
    }
    return 1;
}

/* a == b entry by entry (== on doubles: +0 and -0 are equal). */
static int dense_equal(const double *a, const double *b, size_t n)
{
    size_t k;
    for (k = 0; k < n; k++)
        if (!(a[k] == b[k])) return 0;
    return 1;
}

/* Position of (i,j) in A found by a linear scan, -1 if absent. */
static int linear_find(const sp_csc *A, int i, int j)
{
    int p;
    for (p = A->colptr[j]; p < A->colptr[j + 1]; p++)
        if (A->rowind[p] == i) return p;
    return -1;
}

/* ---- builder ---- */

static void test_builder_random(tap_rng *r, int nrow, int ncol, int ncells, int nadd, int hint)
{
    size_t nd = (size_t)nrow * ncol;
    int *ci = malloc(sizeof(int) * ncells), *cj = malloc(sizeof(int) * ncells);
    int *I = malloc(sizeof(int) * (nadd + 20)), *J = malloc(sizeof(int) * (nadd + 20));
    double *V = malloc(sizeof(double) * (nadd + 20)), *W = malloc(sizeof(double) * (nadd + 20));
    int *slot = malloc(sizeof(int) * (nadd + 20));
    double *D = calloc(nd, sizeof(double)), *Dw = calloc(nd, sizeof(double));
    double *Dout = calloc(nd, sizeof(double));
    unsigned char *present = calloc(nd, 1);
    int k, i, j, p, ndistinct = 0, ok, nextra;
    sp_builder *b = sp_builder_create(nrow, ncol, hint);
    sp_csc *A = NULL, *A2 = NULL;
    bg_error err;
    char tag[96];

    snprintf(tag, sizeof tag, "builder %dx%d, %d adds on %d cells", nrow, ncol, nadd, ncells);
    if (!tap_ok(b != NULL, "%s: sp_builder_create", tag)) goto out;

    /* Random cells; draws from the cells give many duplicates. A quarter of the draws fall
     * anywhere. */
    for (k = 0; k < ncells; k++) {
        ci[k] = tap_rng_int(r, nrow);
        cj[k] = tap_rng_int(r, ncol);
    }
    ok = 1;
    for (k = 0; k < nadd; k++) {
        int rc;
        if (tap_rng_unif(r) < 0.75) {
            int c = tap_rng_int(r, ncells);
            I[k] = ci[c];
            J[k] = cj[c];
        } else {
            I[k] = tap_rng_int(r, nrow);
            J[k] = tap_rng_int(r, ncol);
        }
        V[k] = exact_val(r);
        rc = sp_builder_add(b, I[k], J[k], V[k]);
        if (rc != k) {
            if (ok) tap_diag("add #%d (%d,%d) returned %d", k, I[k], J[k], rc);
            ok = 0;
        }
        D[I[k] + (size_t)J[k] * nrow] += V[k];
        if (!present[I[k] + (size_t)J[k] * nrow]) ndistinct++;
        present[I[k] + (size_t)J[k] * nrow] = 1;
    }
    tap_ok(ok, "%s: sp_builder_add returns 0,1,2,... in order", tag);
    tap_ok(sp_builder_count(b) == nadd, "%s: sp_builder_count == %d (got %d)", tag, nadd,
           sp_builder_count(b));

    for (k = 0; k < nadd; k++)
        slot[k] = -12345;
    A = sp_builder_finish(b, slot);
    if (!tap_ok(A != NULL, "%s: sp_builder_finish", tag)) goto out;
    tap_ok(A->nrow == nrow && A->ncol == ncol, "%s: dimensions", tag);
    bg_error_clear(&err);
    err.handler = NULL;
    tap_ok(sp_csc_check(A, &err) == BG_OK, "%s: sp_csc_check passes", tag);
    tap_ok(structure_ok(A), "%s: rows strictly ascending in each column (own check)", tag);
    tap_ok(A->nnz == ndistinct, "%s: nnz == distinct positions (%d, got %d)", tag, ndistinct,
           A->nnz);

    /* Pattern == set of added positions, values == dense accumulation (bitwise). */
    ok = 1;
    for (j = 0; j < ncol && ok; j++)
        for (p = A->colptr[j]; p < A->colptr[j + 1]; p++) {
            i = A->rowind[p];
            if (i < 0 || i >= nrow || !present[i + (size_t)j * nrow]) {
                tap_diag("stored (%d,%d) was never added", i, j);
                ok = 0;
                break;
            }
            if (A->val[p] != D[i + (size_t)j * nrow]) {
                tap_diag("(%d,%d): val %.17g, dense sum %.17g", i, j, A->val[p],
                         D[i + (size_t)j * nrow]);
                ok = 0;
                break;
            }
        }
    tap_ok(ok, "%s: duplicates summed, pattern == added positions", tag);
    sp_csc_to_dense(A, Dout);
    tap_ok(dense_equal(Dout, D, nd), "%s: sp_csc_to_dense == dense accumulation", tag);

    /* Slot map. */
    ok = 1;
    for (k = 0; k < nadd; k++) {
        int s = slot[k];
        if (s < A->colptr[J[k]] || s >= A->colptr[J[k] + 1] || A->rowind[s] != I[k]) {
            tap_diag("entry %d (%d,%d): slot %d is not its position", k, I[k], J[k], s);
            ok = 0;
            break;
        }
    }
    tap_ok(ok, "%s: slot[k] lies in column j_k with row i_k", tag);
    ok = 1;
    for (k = 0; k < nadd; k++)
        if (sp_csc_find(A, I[k], J[k]) != slot[k]) {
            tap_diag("entry %d (%d,%d): find %d, slot %d", k, I[k], J[k],
                     sp_csc_find(A, I[k], J[k]), slot[k]);
            ok = 0;
            break;
        }
    tap_ok(ok, "%s: sp_csc_find(i_k, j_k) == slot[k]", tag);
    ok = 1;
    for (j = 0; j < ncol && ok; j++)
        for (i = 0; i < nrow; i++) {
            int want = linear_find(A, i, j), got = sp_csc_find(A, i, j);
            if (want != got) {
                tap_diag("find(%d,%d) = %d, want %d", i, j, got, want);
                ok = 0;
                break;
            }
        }
    tap_ok(ok, "%s: sp_csc_find on every position (-1 where absent)", tag);

    /* Zero, then re-scatter new values through the slots. */
    sp_csc_zero(A);
    ok = 1;
    for (p = 0; p < A->nnz; p++)
        if (A->val[p] != 0.0) ok = 0;
    tap_ok(ok && A->nnz == ndistinct, "%s: sp_csc_zero zeroes values, keeps pattern", tag);
    for (k = 0; k < nadd; k++) {
        W[k] = exact_val(r);
        Dw[I[k] + (size_t)J[k] * nrow] += W[k];
    }
    sp_scatter_add(A, slot, W, nadd);
    tu_dense(A, Dout);
    tap_ok(dense_equal(Dout, Dw, nd), "%s: sp_scatter_add after zero == dense sum of new values",
           tag);
    sp_scatter_add(A, slot, W, nadd);
    ok = 1;
    for (j = 0; j < ncol && ok; j++)
        for (p = A->colptr[j]; p < A->colptr[j + 1]; p++)
            if (A->val[p] != 2.0 * Dw[A->rowind[p] + (size_t)j * nrow]) {
                ok = 0;
                break;
            }
    tap_ok(ok, "%s: second sp_scatter_add accumulates", tag);

    /* The builder stays valid: add more, finish again. */
    nextra = 20;
    for (k = nadd; k < nadd + nextra; k++) {
        I[k] = (k % 2) ? I[k - nadd] : tap_rng_int(r, nrow); /* duplicates and new ones */
        J[k] = (k % 2) ? J[k - nadd] : tap_rng_int(r, ncol);
        V[k] = exact_val(r);
        if (!present[I[k] + (size_t)J[k] * nrow]) ndistinct++;
        present[I[k] + (size_t)J[k] * nrow] = 1;
        D[I[k] + (size_t)J[k] * nrow] += V[k];
        sp_builder_add(b, I[k], J[k], V[k]);
    }
    tap_ok(sp_builder_count(b) == nadd + nextra, "%s: count after more adds", tag);
    A2 = sp_builder_finish(b, slot);
    if (tap_ok(A2 != NULL, "%s: second sp_builder_finish", tag)) {
        ok = A2->nnz == ndistinct && structure_ok(A2);
        tu_dense(A2, Dout);
        ok = ok && dense_equal(Dout, D, nd);
        for (k = 0; k < nadd + nextra && ok; k++)
            if (slot[k] < A2->colptr[J[k]] || slot[k] >= A2->colptr[J[k] + 1] ||
                A2->rowind[slot[k]] != I[k])
                ok = 0;
        tap_ok(ok, "%s: second finish sums all entries, slots right", tag);
    }

out:
    sp_csc_free(&A);
    sp_csc_free(&A2);
    tap_ok(A == NULL && A2 == NULL, "%s: sp_csc_free sets the pointer to NULL", tag);
    sp_builder_free(&b);
    tap_ok(b == NULL, "%s: sp_builder_free sets the pointer to NULL", tag);
    free(ci);
    free(cj);
    free(I);
    free(J);
    free(V);
    free(W);
    free(slot);
    free(D);
    free(Dw);
    free(Dout);
    free(present);
}

static void test_builder_errors(void)
{
    sp_builder *b = sp_builder_create(5, 4, 0);
    const bg_error *e;
    int rc;
    sp_csc *A;
    int slot[2];
    struct {
        int i, j;
        const char *needle;
    } bad[] = {{1234567, 2, "1234567"}, {-98765, 1, "98765"}, {2, 7654321, "7654321"},
               {3, -4321, "4321"},      {5, 0, "5"},          {0, 4, "4"}};
    size_t t;

    if (!tap_ok(b != NULL, "builder errors: create")) return;
    tap_ok(sp_builder_add(b, 4, 3, 1.5) == 0, "builder errors: valid add returns 0");
    for (t = 0; t < sizeof bad / sizeof bad[0]; t++) {
        rc = sp_builder_add(b, bad[t].i, bad[t].j, 1.0);
        e = sp_builder_error(b);
        tap_ok(rc == BG_ERR_ARGUMENT,
               "builder errors: add(%d,%d) on 5x4 returns BG_ERR_ARGUMENT (got %d)", bad[t].i,
               bad[t].j, rc);
        if (tap_ok(e != NULL, "builder errors: sp_builder_error not NULL")) {
            tap_ok(e->status == BG_ERR_ARGUMENT, "builder errors: error status recorded (%d)",
                   e->status);
            if (!tap_ok(strstr(e->message, bad[t].needle) != NULL,
                        "builder errors: message mentions the index %s", bad[t].needle))
                tap_diag("message: \"%s\"", e->message);
        }
        tap_ok(sp_builder_count(b) == 1, "builder errors: failed add does not count (count %d)",
               sp_builder_count(b));
    }
    tap_ok(sp_builder_add(b, 0, 0, 2.5) == 1, "builder errors: next valid add returns 1");
    A = sp_builder_finish(b, slot);
    if (tap_ok(A != NULL, "builder errors: finish")) {
        tap_ok(A->nnz == 2 && sp_csc_find(A, 4, 3) == slot[0] && sp_csc_find(A, 0, 0) == slot[1] &&
                   A->val[slot[0]] == 1.5 && A->val[slot[1]] == 2.5,
               "builder errors: only the valid entries are in the matrix");
        sp_csc_free(&A);
    }
    sp_builder_free(&b);
}

static void test_builder_empty(void)
{
    sp_builder *b = sp_builder_create(4, 3, 0);
    sp_csc *A;
    int j, ok = 1;
    if (!tap_ok(b != NULL, "empty builder: create")) return;
    tap_ok(sp_builder_count(b) == 0, "empty builder: count 0");
    A = sp_builder_finish(b, NULL);
    if (tap_ok(A != NULL, "empty builder: finish")) {
        for (j = 0; j <= 3; j++)
            ok = ok && A->colptr[j] == 0;
        tap_ok(ok && A->nnz == 0 && A->nrow == 4 && A->ncol == 3 && sp_csc_check(A, NULL) == BG_OK,
               "empty builder: 4x3 with nnz 0, colptr all 0");
        sp_csc_free(&A);
    }
    sp_builder_free(&b);
    sp_builder_free(&b); /* NULL pointer: no-op */
    sp_csc_free(&A);
    tap_ok(b == NULL && A == NULL, "free functions accept a NULL object");
}

/* ---- sp_csc_check on corrupted matrices ---- */

static void test_check_faults(void)
{
    /* 4x3: col0 rows {0,2}, col1 rows {1,2,3}, col2 row {0} */
    static const int cp[] = {0, 2, 5, 6};
    static const int ri[] = {0, 2, 1, 2, 3, 0};
    static const double va[] = {1, 2, 3, 4, 5, 6};
    const char *what[] = {"rows not ascending", "duplicate row",       "row == nrow",
                          "negative row",       "colptr not monotone", "colptr[0] != 0"};
    int t;
    for (t = -1; t < 6; t++) {
        sp_csc *A = sp_csc_alloc(4, 3, 6);
        bg_error err;
        int rc;
        if (!A) {
            tap_ok(0, "sp_csc_alloc(4,3,6)");
            return;
        }
        memcpy(A->colptr, cp, sizeof cp);
        memcpy(A->rowind, ri, sizeof ri);
        memcpy(A->val, va, sizeof va);
        A->nnz = 6;
        switch (t) {
        case 0:
            A->rowind[2] = 3;
            A->rowind[4] = 1;
            break;
        case 1:
            A->rowind[3] = 1;
            break;
        case 2:
            A->rowind[4] = 4;
            break;
        case 3:
            A->rowind[0] = -1;
            break;
        case 4:
            A->colptr[1] = 6;
            break;
        case 5:
            A->colptr[0] = 1;
            break;
        default:
            break;
        }
        bg_error_clear(&err);
        err.handler = NULL;
        rc = sp_csc_check(A, &err);
        if (t < 0) {
            tap_ok(rc == BG_OK, "sp_csc_check: valid 4x3 passes");
            tap_ok(sp_csc_check(A, NULL) == BG_OK, "sp_csc_check: err may be NULL");
        } else {
            tap_ok(rc == BG_ERR_PATTERN, "sp_csc_check: %s -> BG_ERR_PATTERN (got %d)", what[t],
                   rc);
            tap_ok(err.message[0] != '\0', "sp_csc_check: %s -> message", what[t]);
            tap_ok(sp_csc_check(A, NULL) == BG_ERR_PATTERN, "sp_csc_check: %s, err NULL", what[t]);
        }
        sp_csc_free(&A);
    }
}

/* ---- union ---- */

static void test_union(tap_rng *r, int nrow, int ncol)
{
    size_t nd = (size_t)nrow * ncol, k;
    unsigned char *ma = calloc(nd, 1), *mb = calloc(nd, 1);
    double *va = calloc(nd, sizeof(double)), *vb = calloc(nd, sizeof(double));
    sp_csc *A = NULL, *B = NULL;
    sp_union *u = NULL;
    int i, j, p, ndistinct = 0, ok, n_a = 0, n_b = 0, n_ab = 0, rep;
    char tag[64];

    snprintf(tag, sizeof tag, "union %dx%d", nrow, ncol);
    for (k = 0; k < nd; k++) {
        double t = tap_rng_unif(r);
        int col = (int)(k / (size_t)nrow);
        if (col == 0)
            t = 0.0; /* column 0 empty in both */
        else if (col == 1 && t > 0.5)
            t = 0.65; /* column 1: only A */
        else if (col == 2 && t > 0.5)
            t = 0.8;                                /* column 2: only B */
        ma[k] = (t > 0.55 && t < 0.75) || t >= 0.9; /* A only: (.55,.75), both: >= .9 */
        mb[k] = (t >= 0.75);                        /* B only: [.75,.9) */
        if (col == 1) mb[k] = 0;
        if (col == 2) ma[k] = 0;
        va[k] = tap_rng_range(r, 0.1, 2.0) * (tap_rng_unif(r) < 0.5 ? -1 : 1);
        vb[k] = tap_rng_range(r, 0.1, 2.0) * (tap_rng_unif(r) < 0.5 ? -1 : 1);
        ndistinct += ma[k] || mb[k];
        n_a += ma[k] && !mb[k];
        n_b += mb[k] && !ma[k];
        n_ab += ma[k] && mb[k];
    }
    tap_ok(n_a > 0 && n_b > 0 && n_ab > 0,
           "%s: has entries only in A (%d), only in B (%d), in both (%d)", tag, n_a, n_b, n_ab);
    A = tu_csc_from_mask(nrow, ncol, ma, va);
    B = tu_csc_from_mask(nrow, ncol, mb, vb);
    if (!A || !B) {
        tap_ok(0, "%s: alloc", tag);
        goto out;
    }
    u = sp_union_create(A, B);
    if (!tap_ok(u != NULL && u->M != NULL, "%s: sp_union_create", tag)) goto out;
    tap_ok(u->M->nrow == nrow && u->M->ncol == ncol, "%s: dimensions", tag);
    tap_ok(u->M->nnz == ndistinct, "%s: nnz == distinct positions (%d, got %d)", tag, ndistinct,
           u->M->nnz);
    tap_ok(structure_ok(u->M) && sp_csc_check(u->M, NULL) == BG_OK, "%s: structure valid", tag);
    ok = 1;
    for (j = 0; j < ncol && ok; j++)
        for (p = u->M->colptr[j]; p < u->M->colptr[j + 1]; p++) {
            i = u->M->rowind[p];
            if (!(ma[i + (size_t)j * nrow] || mb[i + (size_t)j * nrow])) {
                ok = 0;
                break;
            }
        }
    tap_ok(ok, "%s: pattern == union of the patterns", tag);
    ok = 1;
    for (j = 0; j < ncol && ok; j++)
        for (p = A->colptr[j]; p < A->colptr[j + 1]; p++) {
            int q = u->map_a[p];
            if (q < u->M->colptr[j] || q >= u->M->colptr[j + 1] ||
                u->M->rowind[q] != A->rowind[p]) {
                ok = 0;
                break;
            }
        }
    tap_ok(ok, "%s: map_a points at A's positions", tag);
    ok = 1;
    for (j = 0; j < ncol && ok; j++)
        for (p = B->colptr[j]; p < B->colptr[j + 1]; p++) {
            int q = u->map_b[p];
            if (q < u->M->colptr[j] || q >= u->M->colptr[j + 1] ||
                u->M->rowind[q] != B->rowind[p]) {
                ok = 0;
                break;
            }
        }
    tap_ok(ok, "%s: map_b points at B's positions", tag);

    for (rep = 0; rep < 4; rep++) {
        double ca, cb;
        switch (rep) {
        case 0:
            ca = 1.0;
            cb = 1.0;
            break;
        case 1:
            ca = tap_rng_range(r, -3, 3);
            cb = tap_rng_range(r, -3, 3);
            break;
        case 2:
            ca = 0.0;
            cb = 1.0;
            break; /* must clear the previous values */
        default:
            ca = tap_rng_range(r, -3, 3);
            cb = 1.0 / 3.0;
            for (p = 0; p < A->nnz; p++)
                A->val[p] *= 1.5; /* new values, same pattern */
            for (j = 0; j < ncol; j++)
                for (p = A->colptr[j]; p < A->colptr[j + 1]; p++)
                    va[A->rowind[p] + (size_t)j * nrow] = A->val[p];
            break;
        }
        sp_union_combine(u, A, ca, B, cb);
        ok = 1;
        for (j = 0; j < ncol && ok; j++)
            for (p = u->M->colptr[j]; p < u->M->colptr[j + 1]; p++) {
                size_t c;
                double a, bb, want;
                i = u->M->rowind[p];
                c = i + (size_t)j * nrow;
                a = ma[c] ? va[c] : 0.0;
                bb = mb[c] ? vb[c] : 0.0;
                want = ca * a + cb * bb;
                if (u->M->val[p] != want) {
                    tap_diag("(%d,%d) A? %d B? %d: got %.17g want %.17g", i, j, ma[c], mb[c],
                             u->M->val[p], want);
                    ok = 0;
                    break;
                }
            }
        tap_ok(ok, "%s: combine %g*A + %g*B bitwise equal to the dense sum", tag, ca, cb);
    }

out:
    sp_union_free(&u);
    tap_ok(u == NULL, "%s: sp_union_free sets NULL", tag);
    sp_csc_free(&A);
    sp_csc_free(&B);
    free(ma);
    free(mb);
    free(va);
    free(vb);
}

static void test_union_shapes(tap_rng *r)
{
    sp_csc *A = tu_random_csc(r, 3, 4, 0.5, -1.0, 1.0, 0),
           *B = tu_random_csc(r, 4, 3, 0.5, -1.0, 1.0, 0),
           *C = tu_random_csc(r, 3, 5, 0.5, -1.0, 1.0, 0);
    sp_union *u = sp_union_create(A, B), *v = sp_union_create(A, C), *w = sp_union_create(A, A);
    tap_ok(u == NULL, "sp_union_create 3x4 with 4x3 returns NULL");
    tap_ok(v == NULL, "sp_union_create 3x4 with 3x5 returns NULL");
    if (tap_ok(w != NULL, "sp_union_create A with A")) {
        tap_ok(sp_csc_same_pattern(w->M, A), "union of A with itself has A's pattern");
        sp_union_combine(w, A, 2.0, A, -1.0);
        tap_ok(w->M->nnz == A->nnz && dense_equal(w->M->val, A->val, (size_t)A->nnz),
               "union of A with itself: 2A - A == A");
    }
    sp_union_free(&u);
    sp_union_free(&v);
    sp_union_free(&w);
    sp_csc_free(&A);
    sp_csc_free(&B);
    sp_csc_free(&C);
}

/* ---- products ---- */

static void test_matvec(tap_rng *r, int nrow, int ncol, double density)
{
    sp_csc *A = tu_random_csc(r, nrow, ncol, density, -1.0, 1.0, 0);
    double *D = malloc(sizeof(double) * ((size_t)nrow * ncol + 1));
    int nmax = nrow > ncol ? nrow : ncol;
    double *x = malloc(sizeof(double) * nmax), *y = malloc(sizeof(double) * nmax);
    double *y0 = malloc(sizeof(double) * nmax);
    static const double ab[][2] = {{1.3, 0.7}, {-2.0, 1.0}, {1.0, 0.0}, {0.5, -1.0}, {-0.75, 0.0}};
    int t, tr, i, j;
    char tag[64];

    snprintf(tag, sizeof tag, "matvec %dx%d", nrow, ncol);
    if (!A) {
        tap_ok(0, "%s: alloc", tag);
        goto out;
    }
    tu_dense(A, D);
    for (tr = 0; tr < 2; tr++) {
        int nin = tr ? nrow : ncol, nout = tr ? ncol : nrow;
        for (t = 0; t < 5; t++) {
            double alpha = ab[t][0], beta = ab[t][1];
            int ok = 1;
            for (j = 0; j < nin; j++)
                x[j] = tap_rng_range(r, -1, 1);
            for (i = 0; i < nout; i++)
                y[i] = y0[i] = beta == 0.0 ? NAN : tap_rng_range(r, -1, 1);
            if (tr)
                sp_matvec_t(A, alpha, x, beta, y);
            else
                sp_matvec(A, alpha, x, beta, y);
            for (i = 0; i < nout; i++) {
                double s = 0.0, sabs = 0.0, want, bound;
                for (j = 0; j < nin; j++) {
                    double a = tr ? D[j + (size_t)i * nrow] : D[i + (size_t)j * nrow];
                    s += a * x[j];
                    sabs += fabs(a * x[j]);
                }
                want = alpha * s + (beta == 0.0 ? 0.0 : beta * y0[i]);
                bound = 1e-14 * (fabs(alpha) * sabs + (beta == 0.0 ? 0.0 : fabs(beta * y0[i]))) +
                        1e-300;
                if (!(fabs(y[i] - want) <= bound)) {
                    if (ok) tap_diag("y[%d] = %.17g, want %.17g", i, y[i], want);
                    ok = 0;
                }
            }
            tap_ok(ok, "%s: %s alpha=%g beta=%g%s matches dense", tag,
                   tr ? "sp_matvec_t" : "sp_matvec", alpha, beta,
                   beta == 0.0 ? " (y = NaN before)" : "");
        }
    }
out:
    sp_csc_free(&A);
    free(D);
    free(x);
    free(y);
    free(y0);
}

/* ---- transpose, dense round trip, copy, same_pattern ---- */

static void test_transpose(tap_rng *r, int nrow, int ncol, double density)
{
    sp_csc *A = tu_random_csc(r, nrow, ncol, density, -1.0, 1.0, 0), *T = NULL;
    double *DA = malloc(sizeof(double) * ((size_t)nrow * ncol + 1));
    double *DT = malloc(sizeof(double) * ((size_t)nrow * ncol + 1));
    int i, j, ok = 1;
    if (!A) goto out;
    T = sp_csc_transpose(A);
    if (!tap_ok(T != NULL, "transpose %dx%d: not NULL", nrow, ncol)) goto out;
    tap_ok(T->nrow == ncol && T->ncol == nrow && T->nnz == A->nnz,
           "transpose %dx%d: dimensions %dx%d and nnz", nrow, ncol, T->nrow, T->ncol);
    tap_ok(structure_ok(T) && sp_csc_check(T, NULL) == BG_OK,
           "transpose %dx%d: structure valid, rows ascending", nrow, ncol);
    tu_dense(A, DA);
    tu_dense(T, DT);
    for (i = 0; i < nrow; i++)
        for (j = 0; j < ncol; j++)
            if (DT[j + (size_t)i * ncol] != DA[i + (size_t)j * nrow]) ok = 0;
    tap_ok(ok, "transpose %dx%d: T(j,i) == A(i,j)", nrow, ncol);
out:
    sp_csc_free(&A);
    sp_csc_free(&T);
    free(DA);
    free(DT);
}

static void test_dense_round_trip(tap_rng *r, int nrow, int ncol)
{
    size_t nd = (size_t)nrow * ncol, k;
    double *D = malloc(sizeof(double) * nd), *E = malloc(sizeof(double) * nd);
    static const double drops[] = {-1.0, 0.0, 0.5};
    int t;
    for (k = 0; k < nd; k++) {
        double u = tap_rng_unif(r);
        D[k] = u < 0.4 ? 0.0 : tap_rng_range(r, -1, 1);
    }
    D[0] = 0.5; /* |a| == drop is dropped at drop = 0.5 */
    D[1] = -0.5;
    for (t = 0; t < 3; t++) {
        double drop = drops[t];
        sp_csc *A = sp_csc_from_dense(nrow, ncol, D, drop);
        int want_nnz = 0, ok = 1, j, p;
        for (k = 0; k < nd; k++)
            want_nnz += (drop < 0.0) || fabs(D[k]) > drop;
        if (!tap_ok(A != NULL, "from_dense %dx%d drop=%g: not NULL", nrow, ncol, drop)) continue;
        tap_ok(A->nrow == nrow && A->ncol == ncol && A->nnz == want_nnz,
               "from_dense %dx%d drop=%g: nnz %d (got %d)", nrow, ncol, drop, want_nnz, A->nnz);
        tap_ok(structure_ok(A), "from_dense %dx%d drop=%g: structure valid", nrow, ncol, drop);
        for (j = 0; j < ncol && ok; j++)
            for (p = A->colptr[j]; p < A->colptr[j + 1]; p++)
                if (A->val[p] != D[A->rowind[p] + (size_t)j * nrow]) ok = 0;
        tap_ok(ok, "from_dense %dx%d drop=%g: stored values are D's", nrow, ncol, drop);
        for (k = 0; k < nd; k++)
            E[k] = 12345.0;
        sp_csc_to_dense(A, E);
        ok = 1;
        for (k = 0; k < nd; k++) {
            double want = ((drop < 0.0) || fabs(D[k]) > drop) ? D[k] : 0.0;
            if (E[k] != want) ok = 0;
        }
        tap_ok(ok, "from_dense/to_dense %dx%d drop=%g: round trip", nrow, ncol, drop);
        sp_csc_free(&A);
    }
    free(D);
    free(E);
}

static void test_copy_same_pattern(tap_rng *r)
{
    sp_csc *A = tu_random_csc(r, 9, 7, 0.4, -1.0, 1.0, 0), *C = sp_csc_copy(A), *T = NULL,
           *M = NULL;
    double keep;
    int p;
    if (!tap_ok(A && C, "copy: not NULL")) goto out;
    tap_ok(C->nrow == 9 && C->ncol == 7 && C->nnz == A->nnz, "copy: dimensions and nnz");
    tap_ok(memcmp(C->colptr, A->colptr, sizeof(int) * 8) == 0 &&
               memcmp(C->rowind, A->rowind, sizeof(int) * A->nnz) == 0 &&
               dense_equal(C->val, A->val, (size_t)A->nnz),
           "copy: identical arrays");
    tap_ok(C->colptr != A->colptr && C->rowind != A->rowind && C->val != A->val,
           "copy: owns its arrays");
    tap_ok(sp_csc_same_pattern(A, C) == 1, "same_pattern(A, copy) == 1");
    keep = A->val[0];
    C->val[0] += 1.0;
    tap_ok(A->val[0] == keep, "copy: changing the copy leaves A alone");
    tap_ok(sp_csc_same_pattern(A, C) == 1, "same_pattern ignores values");
    T = sp_csc_transpose(A);
    tap_ok(T && sp_csc_same_pattern(A, T) == 0, "same_pattern(9x7, 7x9) == 0");
    /* Same nnz, one row index moved. */
    M = sp_csc_copy(A);
    if (M) {
        int moved = 0, j;
        for (j = 0; j < 7 && !moved; j++)
            for (p = M->colptr[j]; p < M->colptr[j + 1]; p++) {
                int nxt = (p + 1 < M->colptr[j + 1]) ? M->rowind[p + 1] : 9;
                if (M->rowind[p] + 1 < nxt) {
                    M->rowind[p]++;
                    moved = 1;
                    break;
                }
            }
        tap_ok(moved && sp_csc_same_pattern(A, M) == 0, "same_pattern: one row moved -> 0");
    }
out:
    sp_csc_free(&A);
    sp_csc_free(&C);
    sp_csc_free(&T);
    sp_csc_free(&M);
}

static void test_alloc(void)
{
    sp_csc *A = sp_csc_alloc(6, 5, 10);
    int j, ok = 1;
    if (!tap_ok(A != NULL, "sp_csc_alloc(6,5,10)")) return;
    for (j = 0; j <= 5; j++)
        ok = ok && A->colptr[j] == 0;
    tap_ok(ok && A->nrow == 6 && A->ncol == 5, "sp_csc_alloc: 6x5, colptr zero");
    sp_csc_free(&A);
}

/* ---- MatrixMarket ---- */

/* Reads a MatrixMarket file written by sp_write_mm and compares it with A. */
static void check_mm(FILE *f, const sp_csc *A, const char *tag)
{
    char line[256];
    int m = -1, n = -1, nz = -1, k, ok = 1, extra;
    size_t nd = (size_t)A->nrow * A->ncol;
    double *D = calloc(nd + 1, sizeof(double)), *W = calloc(nd + 1, sizeof(double));
    unsigned char *seen = calloc(nd + 1, 1);

    rewind(f);
    if (!fgets(line, sizeof line, f)) line[0] = '\0';
    line[strcspn(line, "\r\n")] = '\0';
    if (!tap_ok(strcmp(line, "%%MatrixMarket matrix coordinate real general") == 0,
                "%s: header line", tag))
        tap_diag("header: \"%s\"", line);
    /* Comments, then the size line. */
    do {
        if (!fgets(line, sizeof line, f)) {
            line[0] = '\0';
            break;
        }
    } while (line[0] == '%');
    tap_ok(sscanf(line, "%d %d %d", &m, &n, &nz) == 3 && m == A->nrow && n == A->ncol &&
               nz == A->nnz,
           "%s: size line %d %d %d (got \"%.40s\")", tag, A->nrow, A->ncol, A->nnz, line);
    for (k = 0; k < A->nnz; k++) {
        int i, j;
        double v;
        if (fscanf(f, "%d %d %lf", &i, &j, &v) != 3) {
            tap_diag("entry %d unreadable", k);
            ok = 0;
            break;
        }
        if (i < 1 || i > A->nrow || j < 1 || j > A->ncol) {
            tap_diag("entry %d: (%d,%d) out of 1-based range", k, i, j);
            ok = 0;
            break;
        }
        if (seen[(i - 1) + (size_t)(j - 1) * A->nrow]) {
            tap_diag("entry (%d,%d) written twice", i, j);
            ok = 0;
            break;
        }
        seen[(i - 1) + (size_t)(j - 1) * A->nrow] = 1;
        D[(i - 1) + (size_t)(j - 1) * A->nrow] = v;
    }
    tap_ok(ok, "%s: %d entries read, 1-based, each once", tag, A->nnz);
    extra = fscanf(f, "%d", &m);
    tap_ok(extra == EOF, "%s: nothing after the last entry", tag);
    tu_dense(A, W);
    ok = 1;
    {
        int j, p;
        for (j = 0; j < A->ncol && ok; j++)
            for (p = A->colptr[j]; p < A->colptr[j + 1]; p++) {
                size_t c = A->rowind[p] + (size_t)j * A->nrow;
                if (!seen[c] || !(fabs(D[c] - W[c]) <= 1e-15 * fabs(W[c]))) {
                    tap_diag("(%d,%d): read %.17g, want %.17g", A->rowind[p] + 1, j + 1, D[c],
                             W[c]);
                    ok = 0;
                    break;
                }
            }
    }
    tap_ok(ok, "%s: every value read back to 1e-15 relative", tag);
    free(D);
    free(W);
    free(seen);
}

static void test_mm(tap_rng *r)
{
    sp_csc *A = tu_random_csc(r, 9, 6, 0.5, -1.0, 1.0, 0), *E = sp_csc_alloc(3, 2, 0);
    FILE *f;
    bg_error err;
    char path[] = "/tmp/bg_test_sparse_XXXXXX";
    int fd, p;

    if (!A || !E) {
        tap_ok(0, "mm: alloc");
        goto out;
    }
    /* Values of every magnitude and sign. */
    for (p = 0; p < A->nnz; p++)
        A->val[p] *= pow(10.0, (double)(tap_rng_int(r, 61) - 30));
    if (A->nnz > 1) {
        A->val[0] = -1.0 / 3.0;
        A->val[1] = 1e-300;
    }
    f = tmpfile();
    if (tap_ok(f != NULL, "mm: tmpfile")) {
        tap_ok(sp_write_mm(A, f) == BG_OK, "mm: sp_write_mm returns BG_OK");
        fflush(f);
        check_mm(f, A, "mm 9x6");
        fclose(f);
    }
    f = tmpfile();
    if (f) {
        tap_ok(sp_write_mm(E, f) == BG_OK, "mm: empty 3x2 returns BG_OK");
        fflush(f);
        check_mm(f, E, "mm empty 3x2");
        fclose(f);
    }
    fd = mkstemp(path);
    if (tap_ok(fd >= 0, "mm: mkstemp")) {
        close(fd);
        bg_error_clear(&err);
        err.handler = NULL;
        tap_ok(sp_write_mm_file(A, path, &err) == BG_OK, "mm: sp_write_mm_file returns BG_OK");
        f = fopen(path, "r");
        if (tap_ok(f != NULL, "mm: file exists")) {
            check_mm(f, A, "mm file");
            fclose(f);
        }
        remove(path);
    }
    bg_error_clear(&err);
    err.handler = NULL;
    tap_ok(sp_write_mm_file(A, "/nonexistent-bg-dir/sub/x.mtx", &err) == BG_ERR_IO,
           "mm: unwritable path returns BG_ERR_IO");
    tap_ok(err.status == BG_ERR_IO && err.message[0] != '\0', "mm: unwritable path: message set");
out:
    sp_csc_free(&A);
    sp_csc_free(&E);
}

int main(void)
{
    tap_rng r = tap_rng_seed(20240611u);

    test_alloc();
    test_builder_empty();
    test_builder_errors();
    test_builder_random(&r, 1, 1, 1, 5, 0);
    test_builder_random(&r, 5, 7, 6, 40, 0);
    test_builder_random(&r, 20, 13, 30, 300, 8);
    test_builder_random(&r, 100, 100, 400, 3000, 0);
    test_builder_random(&r, 60, 200, 150, 500, 500);
    test_builder_random(&r, 200, 50, 2000, 5000, 100000);
    test_check_faults();
    test_union(&r, 6, 5);
    test_union(&r, 40, 30);
    test_union(&r, 150, 200);
    test_union_shapes(&r);
    test_matvec(&r, 1, 1, 1.0);
    test_matvec(&r, 7, 5, 0.5);
    test_matvec(&r, 30, 45, 0.2);
    test_matvec(&r, 120, 80, 0.05);
    test_matvec(&r, 10, 8, 0.0);
    test_transpose(&r, 1, 1, 1.0);
    test_transpose(&r, 7, 5, 0.5);
    test_transpose(&r, 50, 80, 0.1);
    test_transpose(&r, 6, 4, 0.0);
    test_dense_round_trip(&r, 7, 5);
    test_dense_round_trip(&r, 20, 31);
    test_copy_same_pattern(&r);
    test_mm(&r);
    return tap_done();
}
