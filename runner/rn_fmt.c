/* The numbers of results.csv as printf's "%.12g" writes them, without printf (rn_run.h).
 *
 * printf converts a double to decimal with multiple-precision arithmetic, a few hundred
 * nanoseconds a number; at a row every millisecond of a fast run that was a quarter of the CPU
 * time. Here: N = round(|x| 10^s) with s = 11 - floor(log10 |x|), a 12-digit integer, from the
 * exact product |x| 10^s = hi + lo (10^s is exact in a double for |s| <= 22; the product's
 * rounding error lo by fma, an error-free transformation: Ogita, Rump and Oishi, "Accurate sum
 * and dot product", SIAM J. Sci. Comput. 26, 2005) or, for s < 0, from the quotient
 * hi = |x| / 10^-s and its exact remainder |x| - hi 10^-s (also by fma), then the digits laid
 * out by the rules of %g (C11 7.21.6.1: precision P = 12, exponent X: "%f" style when
 * -4 <= X < P, else "%e" style; trailing zeros and a trailing point removed). Where the
 * fraction of |x| 10^s lies within 1e-7 of one half (the rounding direction in doubt), or
 * |s| > 22 (|x| < 1e-11 or >= 1e34), or x is 0, infinite or NaN, snprintf does it: the text is
 * printf's in every case (tests/crane/test_crane_fmt.c compares both on millions of numbers). */
#include <math.h>
#include <stdint.h>
#include <stdio.h>

#include "rn_run.h"

static const double POW10[23] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                 1e8,  1e9,  1e10, 1e11, 1e12, 1e13, 1e14, 1e15,
                                 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};

/* round(ax 10^s) into *N, 0; or -1 when it cannot be decided here. */
static int scaled(double ax, int s, uint64_t *N)
{
    if (s > 22 || s < -22) return -1;
    double hi, lo;
    if (s >= 0) {
        hi = ax * POW10[s];
        lo = fma(ax, POW10[s], -hi); /* ax 10^s = hi + lo exactly */
    } else {
        double P = POW10[-s];
        hi = ax / P;
        lo = fma(-hi, P, ax) / P; /* ax = hi P + r exactly; ax / P = hi + r / P */
    }
    double fl = floor(hi), frac = (hi - fl) + lo; /* hi - fl is exact */
    if (fabs(frac - 0.5) < 1e-7 || fabs(frac + 0.5) < 1e-7 || fabs(frac - 1.5) < 1e-7) return -1;
    double r = fl + floor(frac + 0.5);
    if (!(r >= 0 && r < 1e13)) return -1;
    *N = (uint64_t)r;
    return 0;
}

int rn_fmt_g12(char *buf, double x)
{
    if (!isfinite(x) || x == 0) return snprintf(buf, RN_FMT_SIZE, "%.12g", x);
    double ax = fabs(x);
    int X = (int)floor(log10(ax));
    uint64_t N = 0;
    for (int tries = 0;; tries++) {
        if (tries == 3 || scaled(ax, 11 - X, &N) != 0)
            return snprintf(buf, RN_FMT_SIZE, "%.12g", x);
        if (N >= 1000000000000ULL) /* rounded up to 10^12, or log10 one too low */
            X++;
        else if (N < 100000000000ULL) /* log10 one too high */
            X--;
        else
            break;
    }
    char d[12];
    for (int i = 11; i >= 0; i--) {
        d[i] = (char)('0' + N % 10);
        N /= 10;
    }
    int nd = 12;
    while (nd > 1 && d[nd - 1] == '0')
        nd--;
    char *p = buf;
    if (x < 0) *p++ = '-';
    if (X >= -4 && X < 12) {
        if (X >= 0) {
            for (int i = 0; i <= X; i++)
                *p++ = d[i];
            if (nd > X + 1) {
                *p++ = '.';
                for (int i = X + 1; i < nd; i++)
                    *p++ = d[i];
            }
        } else {
            *p++ = '0';
            *p++ = '.';
            for (int i = 0; i < -X - 1; i++)
                *p++ = '0';
            for (int i = 0; i < nd; i++)
                *p++ = d[i];
        }
    } else {
        *p++ = d[0];
        if (nd > 1) {
            *p++ = '.';
            for (int i = 1; i < nd; i++)
                *p++ = d[i];
        }
        *p++ = 'e';
        *p++ = X < 0 ? '-' : '+';
        int ex = X < 0 ? -X : X;
        if (ex >= 100) *p++ = (char)('0' + ex / 100);
        *p++ = (char)('0' + ex / 10 % 10);
        *p++ = (char)('0' + ex % 10);
    }
    *p = '\0';
    return (int)(p - buf);
}
