/* The numbers of results.csv as printf's "%.12g" writes them, without printf (rn_run.h).
 *
 * printf converts a double to decimal with multiple-precision arithmetic, a few hundred
 * nanoseconds a number; at a row every millisecond of a fast run that was a quarter of the CPU
 * time. Here the conversion is exact in integers. A finite x != 0 is m 2^e (m < 2^53, the
 * significand as an integer). With X = floor(log10 |x|) and s = 11 - X, the 12 digits are
 * N = round(|x| 10^s), the rounding to nearest with ties to even as printf's in the default
 * rounding mode:
 *   - s >= 0: |x| 10^s = (m 10^s) 2^e with m 10^s < 2^53 10^22 < 2^127, an unsigned 128-bit
 *     integer, and e < 0 (|x| < 10^12 < 2^52 has fraction bits): N is that integer shifted
 *     right by -e, rounded by the bits shifted out against one half;
 *   - s < 0: |x| 10^s = m 2^e / 10^-s, a quotient of 128-bit integers and its remainder against
 *     half the divisor.
 * X is first taken from the binary exponent, floor((e + 52) log10 2) by the integer product
 * with 78913 / 2^18 (the approximation of log10 2 of Ryu: U. Adams, "Ryu: fast float-to-string
 * conversion", PLDI 2018), which is X or X - 1, and raised when N reaches 10^12 (also when the
 * rounding carries into a 13th digit: %g takes the exponent after the rounding, C11 7.21.6.1).
 * The digits are then laid out by the rules of %g (precision P = 12: "%f" style when
 * -4 <= X < P, else "%e" style; trailing zeros and a trailing point removed). 0 and -0 are
 * written here; infinities, NaN, |s| > 22 (|x| < 1e-11 or >= 1e34) and subnormals by snprintf:
 * the text is printf's in every case (tests/crane/test_crane_fmt.c compares both on millions
 * of numbers and on the decimal ties). */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "rn_run.h"

__extension__ typedef unsigned __int128 rn_u128;

#define P10_19 10000000000000000000ULL
static const rn_u128 POW10[23] = {1ULL,
                                  10ULL,
                                  100ULL,
                                  1000ULL,
                                  10000ULL,
                                  100000ULL,
                                  1000000ULL,
                                  10000000ULL,
                                  100000000ULL,
                                  1000000000ULL,
                                  10000000000ULL,
                                  100000000000ULL,
                                  1000000000000ULL,
                                  10000000000000ULL,
                                  100000000000000ULL,
                                  1000000000000000ULL,
                                  10000000000000000ULL,
                                  100000000000000000ULL,
                                  1000000000000000000ULL,
                                  P10_19,
                                  (rn_u128)P10_19 * 10,
                                  (rn_u128)P10_19 * 100,
                                  (rn_u128)P10_19 * 1000};

/* 10^k for k = -12 .. 22 as doubles (POW10D[k + 12]) */
static const double POW10D[35] = {1e-12, 1e-11, 1e-10, 1e-9, 1e-8, 1e-7, 1e-6, 1e-5, 1e-4,
                                  1e-3,  1e-2,  1e-1,  1e0,  1e1,  1e2,  1e3,  1e4,  1e5,
                                  1e6,   1e7,   1e8,   1e9,  1e10, 1e11, 1e12, 1e13, 1e14,
                                  1e15,  1e16,  1e17,  1e18, 1e19, 1e20, 1e21, 1e22};

static const char DIGITS2[201] = "00010203040506070809"
                                 "10111213141516171819"
                                 "20212223242526272829"
                                 "30313233343536373839"
                                 "40414243444546474849"
                                 "50515253545556575859"
                                 "60616263646566676869"
                                 "70717273747576777879"
                                 "80818283848586878889"
                                 "90919293949596979899";

/* round(m 2^e 10^s) to nearest, ties to even, into *N; -1 when out of this method's range
 * (then N is not needed: the caller goes to snprintf). */
static int scaled(uint64_t m, int e, int s, uint64_t *N)
{
    if (s > 22 || s < -22) return -1;
    rn_u128 q, r, half2, twice_r;
    if (s >= 0) {
        if (e >= 0 || e <= -127) return -1; /* not met for |x| in [1e-11, 1e12) */
        rn_u128 P = (rn_u128)m * POW10[s];
        int k = -e;
        q = P >> k;
        r = P - (q << k);
        half2 = (rn_u128)1 << k; /* compare 2 r with the divisor 2^k */
        twice_r = r << 1;
    } else {
        rn_u128 D = POW10[-s], Q = m;
        if (e >= 0) {
            if (e > 60) return -1; /* not met for |x| < 1e34 */
            Q <<= e;
        } else {
            if (e < -40) return -1; /* not met for |x| >= 1e11 */
            D <<= -e;
        }
        q = Q / D;
        r = Q - q * D;
        half2 = D;
        twice_r = r << 1;
    }
    if (twice_r > half2 || (twice_r == half2 && (q & 1))) q++;
    if (q >= (rn_u128)10000000000000ULL) return -1;
    *N = (uint64_t)q;
    return 0;
}

int rn_fmt_g12(char *buf, double x)
{
    uint64_t bits;
    memcpy(&bits, &x, sizeof bits);
    int neg = (int)(bits >> 63), eb = (int)(bits >> 52 & 0x7ff);
    uint64_t frac = bits & ((1ULL << 52) - 1);
    if (eb == 0 && frac == 0) { /* zero: "0" or "-0" */
        char *p = buf;
        if (neg) *p++ = '-';
        *p++ = '0';
        *p = '\0';
        return (int)(p - buf);
    }
    if (eb == 0 || eb == 0x7ff) return snprintf(buf, RN_FMT_SIZE, "%.12g", x);
    uint64_t m = frac | 1ULL << 52;
    int e = eb - 1075, E2 = eb - 1023; /* |x| = m 2^e, 2^E2 <= |x| < 2^(E2 + 1) */
    /* floor(E2 log10 2): X or X - 1; one up where |x| reaches the next power of ten (the
     * doubles nearest 10^k: a miss at the boundary is corrected below) */
    int X = E2 >= 0 ? (E2 * 78913) >> 18 : -((-E2 * 78913 + (1 << 18) - 1) >> 18);
    if (X >= -12 && X <= 21 && fabs(x) >= POW10D[X + 13]) X++;
    uint64_t N = 0;
    for (int tries = 0;; tries++) {
        if (tries == 3 || scaled(m, e, 11 - X, &N) != 0)
            return snprintf(buf, RN_FMT_SIZE, "%.12g", x);
        if (N >= 1000000000000ULL) /* 13 digits: X one too low, or rounded up to 10^12 */
            X++;
        else if (N < 100000000000ULL) /* X one too high */
            X--;
        else
            break;
    }
    char d[12];
    uint32_t half[2] = {(uint32_t)(N / 1000000), (uint32_t)(N % 1000000)};
    for (int h = 0; h < 2; h++) {
        uint32_t v = half[h];
        for (int i = 6 * h + 4; i >= 6 * h; i -= 2) {
            uint32_t two = v % 100;
            v /= 100;
            memcpy(d + i, DIGITS2 + 2 * two, 2);
        }
    }
    int nd = 12;
    while (nd > 1 && d[nd - 1] == '0')
        nd--;
    char *p = buf;
    if (neg) *p++ = '-';
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
