/* KLU timings on block-banded matrices, the shape of multibody Newton matrices: n/b blocks of
 * size b on the block diagonal, coupled to their neighbours by dense b x b blocks (block
 * tridiagonal), made diagonally dominant. For each n it reports the median over several
 * repetitions of the symbolic analysis, a full numeric factorization, a refactorization with the
 * same pivots (new values, same pattern), and one solve, and checks the relative residual.
 *
 * usage: klu_bench [--reps R] [--block B] [--csv] [n ...]   (default n = 1e3 1e4 1e5) */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "bench_util.h"
#include "bg_linsol.h"

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static uint64_t rng = 0x9e3779b97f4a7c15ull;
static double urand(void) /* splitmix64 in [-1, 1) */
{
    uint64_t z = (rng += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    z ^= z >> 31;
    return (double)(z >> 11) * 0x1.0p-52 - 1.0;
}

static sp_csc *block_banded(int n, int b)
{
    sp_builder *bl = sp_builder_create(n, n, 3 * n * b);
    if (!bl) return NULL;
    for (int j = 0; j < n; j++) {
        int blk = j / b;
        for (int nb = blk - 1; nb <= blk + 1; nb++) {
            for (int r = 0; r < b; r++) {
                int i = nb * b + r;
                if (i < 0 || i >= n) continue;
                sp_builder_add(bl, i, j, i == j ? 4.0 * b : urand());
            }
        }
    }
    sp_csc *A = sp_builder_finish(bl, NULL);
    sp_builder_free(&bl);
    return A;
}

int main(int argc, char **argv)
{
    int reps = 5, b = 6, csv = 0, nn = 0;
    int ns[32];
    for (int a = 1; a < argc; a++) {
        if (!strcmp(argv[a], "--reps") && a + 1 < argc)
            reps = atoi(argv[++a]);
        else if (!strcmp(argv[a], "--block") && a + 1 < argc)
            b = atoi(argv[++a]);
        else if (!strcmp(argv[a], "--csv"))
            csv = 1;
        else if (argv[a][0] != '-' && nn < 32)
            ns[nn++] = (int)strtod(argv[a], NULL);
        else {
            fprintf(stderr,
                    "klu_bench: unknown argument '%s'\n"
                    "usage: klu_bench [--reps R] [--block B] [--csv] [n ...]\n",
                    argv[a]);
            return 2;
        }
    }
    if (reps < 1 || b < 1) {
        fprintf(stderr, "klu_bench: --reps and --block need positive integers\n");
        return 2;
    }
    if (nn == 0) {
        ns[0] = 1000;
        ns[1] = 10000;
        ns[2] = 100000;
        nn = 3;
    }
    if (csv)
        printf("n,nnz,block,reps,analyze_s,factor_s,refactor_s,solve_s,residual\n");
    else
        printf("KLU on block-tridiagonal matrices, block %d, median of %d runs\n"
               "%9s %10s %11s %11s %11s %11s %9s\n",
               b, reps, "n", "nnz", "analyze ms", "factor ms", "refactor ms", "solve ms",
               "residual");
    int status = 0;
    for (int k = 0; k < nn; k++) {
        int n = ns[k];
        if (n < 1) {
            fprintf(stderr, "klu_bench: n must be positive (got '%d')\n", n);
            return 2;
        }
        sp_csc *A = block_banded(n, b);
        double *x = malloc((size_t)n * sizeof *x), *rhs = malloc((size_t)n * sizeof *rhs);
        double *ta = malloc((size_t)reps * 4 * sizeof *ta);
        if (!A || !x || !rhs || !ta) {
            fprintf(stderr, "klu_bench: out of memory at n = %d\n", n);
            return 1;
        }
        double *tf = ta + reps, *tr = tf + reps, *ts = tr + reps, resid = 0;
        bg_error err = {0};
        for (int r = 0; r < reps; r++) {
            double t0 = now();
            ls_solver *s = ls_create(LS_KLU, A, &err);
            double t1 = now();
            if (!s || ls_factor(s, A) != BG_OK) {
                fprintf(stderr, "klu_bench: n = %d: %s\n", n,
                        s ? ls_get_error(s)->message : err.message);
                ls_free(&s);
                status = 1;
                break;
            }
            double t2 = now();
            for (int p = 0; p < A->nnz; p++)
                A->val[p] *= 1.0 + 0.01 * urand(); /* new values */
            double t3 = now();
            ls_factor(s, A);
            double t4 = now();
            for (int i = 0; i < n; i++)
                x[i] = rhs[i] = urand();
            double t5 = now();
            ls_solve(s, x, 1);
            double t6 = now();
            ta[r] = t1 - t0;
            tf[r] = t2 - t1;
            tr[r] = t4 - t3;
            ts[r] = t6 - t5;
            if (ls_get_stats(s)->refactor != 1 || ls_get_stats(s)->fallback != 0) status = 1;
            /* residual ||A x - rhs|| / (||A|| ||x||), infinity norms */
            double *ax = malloc((size_t)n * sizeof *ax);
            if (!ax) return 1;
            sp_matvec(A, 1.0, x, 0.0, ax);
            double rn = 0, xn = 0, an = 0;
            for (int i = 0; i < n; i++) {
                rn = fmax(rn, fabs(ax[i] - rhs[i]));
                xn = fmax(xn, fabs(x[i]));
            }
            for (int p = 0; p < A->nnz; p++)
                an = fmax(an, fabs(A->val[p]));
            resid = fmax(resid, rn / (an * xn * 3 * b));
            free(ax);
            ls_free(&s);
        }
        if (!status) {
            double ma = bench_median(ta, reps), mf = bench_median(tf, reps),
                   mr = bench_median(tr, reps), ms = bench_median(ts, reps);
            if (csv)
                printf("%d,%d,%d,%d,%.6g,%.6g,%.6g,%.6g,%.3g\n", n, A->nnz, b, reps, ma, mf, mr, ms,
                       resid);
            else
                printf("%9d %10d %11.3f %11.3f %11.3f %11.3f %9.1e\n", n, A->nnz, 1e3 * ma,
                       1e3 * mf, 1e3 * mr, 1e3 * ms, resid);
            if (resid > 1e-12) status = 1;
        }
        free(x);
        free(rhs);
        free(ta);
        sp_csc_free(&A);
        if (status) break;
    }
    return status;
}
