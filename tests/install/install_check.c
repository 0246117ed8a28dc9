/* Built by tools/test.sh against the installed library through pkg-config (bgdae.pc), with a
 * single header: solves a 3x3 system with KLU and checks the answer. */
#include <math.h>
#include <stdio.h>

#include <bgdae/bg_linsol.h>

int main(void)
{
    double D[9] = {4, 1, 0, 1, 4, 1, 0, 1, 4}; /* symmetric, column-major */
    double b[3] = {5, 6, 5};                   /* solution (1, 1, 1) */
    sp_csc *A = sp_csc_from_dense(3, 3, D, 0.0);
    ls_solver *s = ls_create(LS_KLU, A, NULL);
    int st = s ? ls_factor(s, A) : -1;
    if (st == BG_OK) st = ls_solve(s, b, 1);
    int ok =
        st == BG_OK && fabs(b[0] - 1) < 1e-14 && fabs(b[1] - 1) < 1e-14 && fabs(b[2] - 1) < 1e-14;
    ls_free(&s);
    sp_csc_free(&A);
    if (!ok) fprintf(stderr, "install_check: wrong result (status %d)\n", st);
    return ok ? 0 : 1;
}
