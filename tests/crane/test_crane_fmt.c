/* The numbers of results.csv (runner/rn_fmt.c, rn_fmt_g12) against the C library's
 * snprintf "%.12g", the text results.csv had before and the truth here: the same characters for
 *   - numbers chosen at the edges: 0, -0, infinities, NaN, powers of ten, 12-digit integers and
 *     their neighbours, values that round up to the next power of ten, the limits of the fast
 *     path (1e-11, 1e34), the %f/%e switch of %g (1e-4 and 1e12), subnormals, DBL_MAX;
 *   - decimal ties (a 12-digit integer and a half, times powers of ten) and the doubles next to
 *     them;
 *   - two million random numbers m 10^k (m uniform in [1, 10), k in -40..40, either sign) and a
 *     million random bit patterns (every kind of double). */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "rn_run.h"
#include "tap.h"

static uint64_t state = 0x9e3779b97f4a7c15ULL;

static uint64_t next(void) /* splitmix64 */
{
    uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
}

static double uniform(void)
{
    return (double)(next() >> 11) * 0x1.0p-53;
}

/* 1 if rn_fmt_g12 writes x as snprintf does; the first mismatch is kept in bad. */
static long checked, wrong;
static char bad[256];

static void check(double x)
{
    char a[64], b[64];
    int na = rn_fmt_g12(a, x), nb = snprintf(b, sizeof b, "%.12g", x);
    checked++;
    if (na != nb || strcmp(a, b)) {
        if (!wrong++) snprintf(bad, sizeof bad, "%a: '%s' (%d) instead of '%s'", x, a, na, b);
    }
}

static void check_both(double x)
{
    check(x);
    check(-x);
    check(nextafter(x, INFINITY));
    check(nextafter(x, -INFINITY));
}

int main(void)
{
    /* the edges */
    checked = wrong = 0;
    check(0.0);
    check(-0.0);
    check(INFINITY);
    check(-INFINITY);
    check(NAN);
    check(-NAN);
    check(DBL_MAX);
    check(DBL_MIN);
    check(DBL_TRUE_MIN);
    check(DBL_EPSILON);
    for (int k = -40; k <= 40; k++) {
        double p = pow(10.0, k);
        check_both(p);
        check_both(9.99999999999 * p);
        check_both(9.999999999995 * p);
        check_both(9.9999999999949 * p);
        check_both(1.00000000001 * p);
        check_both(1.23456789012 * p);
        check_both(5 * p);
    }
    for (double x = 1e-12; x < 1e36; x *= 1.37)
        check_both(x);
    check_both(999999999999.0);
    check_both(999999999999.5);
    check_both(999999999999.4);
    check_both(123456789012.0);
    check_both(0.0001);
    check_both(0.00009999999999995);
    check_both(1e12);
    check_both(0.5);
    check_both(12.0); /* the crane's tip radius */
    check_both(77.7526673696);
    tap_ok(wrong == 0, "%ld numbers at the edges written as %%.12g writes them%s%s", checked,
           wrong ? ": " : "", bad);

    /* decimal ties N + 1/2 (N of 12 digits) scaled by powers of ten, and their neighbours */
    checked = wrong = 0;
    for (int i = 0; i < 200000; i++) {
        uint64_t N = 100000000000ULL + next() % 900000000000ULL;
        double tie = (double)(2 * N + 1) / 2; /* exact: below 2^53 */
        int k = (int)(next() % 41) - 20;
        check_both(tie * pow(10.0, k));
        check_both(tie);
    }
    tap_ok(wrong == 0, "%ld decimal ties and their neighbours written as %%.12g writes them%s%s",
           checked, wrong ? ": " : "", bad);

    /* random magnitudes */
    checked = wrong = 0;
    for (int i = 0; i < 2000000; i++) {
        double m = 1 + 9 * uniform();
        int k = (int)(next() % 81) - 40;
        double x = m * pow(10.0, k);
        check(next() & 1 ? x : -x);
    }
    tap_ok(wrong == 0, "%ld random numbers m 10^k (k in -40..40) written as %%.12g writes them%s%s",
           checked, wrong ? ": " : "", bad);

    /* random bit patterns: every kind of double */
    checked = wrong = 0;
    for (int i = 0; i < 1000000; i++) {
        uint64_t u = next();
        double x;
        memcpy(&x, &u, sizeof x);
        check(x);
    }
    tap_ok(wrong == 0, "%ld random bit patterns written as %%.12g writes them%s%s", checked,
           wrong ? ": " : "", bad);

    /* the buffer: the longest text fits RN_FMT_SIZE with room */
    char buf[RN_FMT_SIZE];
    int len = rn_fmt_g12(buf, -1.23456789012e-300);
    tap_ok(len == (int)strlen(buf) && len < RN_FMT_SIZE && !strcmp(buf, "-1.23456789012e-300"),
           "the longest text, '%s', fits RN_FMT_SIZE = %d", buf, RN_FMT_SIZE);
    return tap_done();
}
