/* A tiny header-only TAP (Test Anything Protocol) harness for the unit tests.
 *
 *   tap_ok(cond, fmt, ...)                    "ok N - name" or "not ok N - name" + "# " diagnostic
 *   tap_close(got, want, rtol, atol, fmt, ...) passes when |got - want| <= atol + rtol*|want|
 *                                              (NaN never passes); prints got/want on failure
 *   tap_diag(fmt, ...)                        a "# " comment line
 *   tap_done()                                prints the plan "1..N", returns 0 if all passed
 *
 * Everything goes to stdout (meson's TAP parser reads stdout only). A deterministic PRNG
 * (splitmix64) keeps the tests reproducible; rand() is never used. */
#ifndef BG_TESTS_TAP_H
#define BG_TESTS_TAP_H

#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>

#if defined(__GNUC__)
#define TAP_UNUSED __attribute__((unused))
#define TAP_PRINTF(a, b) __attribute__((unused, format(printf, a, b)))
#else
#define TAP_UNUSED
#define TAP_PRINTF(a, b)
#endif

static int tap_count_ = 0;
static int tap_failed_ = 0;

TAP_PRINTF(1, 2) static void tap_diag(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    fputs("# ", stdout);
    vprintf(fmt, ap);
    fputc('\n', stdout);
    va_end(ap);
    fflush(stdout);
}

#define TAP_NAME_SIZE 512

TAP_UNUSED static void tap_name_(char *name, const char *fmt, va_list ap)
{
    int i;
    vsnprintf(name, TAP_NAME_SIZE, fmt, ap);
    /* '#' would start a TAP directive, a newline would break the line protocol. */
    for (i = 0; name[i]; i++)
        if (name[i] == '#' || name[i] == '\n') name[i] = ' ';
}

/* Counts and prints one test point; the failure line gets no newline when more follows. */
TAP_UNUSED static void tap_point_(int cond, const char *name)
{
    tap_count_++;
    if (!cond) tap_failed_++;
    printf("%sok %d - %s\n", cond ? "" : "not ", tap_count_, name);
    if (!cond) printf("# Failed test %d: %s", tap_count_, name);
}

/* Returns cond != 0 so that callers can add details after a failure. */
TAP_PRINTF(2, 3) static int tap_ok(int cond, const char *fmt, ...)
{
    char name[TAP_NAME_SIZE];
    va_list ap;
    va_start(ap, fmt);
    tap_name_(name, fmt, ap);
    va_end(ap);
    tap_point_(cond, name);
    if (!cond) printf("\n");
    fflush(stdout);
    return cond != 0;
}

TAP_PRINTF(5, 6)
static int tap_close(double got, double want, double rtol, double atol, const char *fmt, ...)
{
    char name[TAP_NAME_SIZE];
    va_list ap;
    double diff = fabs(got - want);
    int cond = !isnan(got) && !isnan(want) && diff <= atol + rtol * fabs(want);
    /* Infinities: only an exact match passes. */
    if (isinf(got) || isinf(want)) cond = (got == want);
    va_start(ap, fmt);
    tap_name_(name, fmt, ap);
    va_end(ap);
    tap_point_(cond, name);
    if (!cond)
        printf(": got %.17g, want %.17g (|diff| %.3g > atol %.3g + rtol %.3g * |want|)\n", got,
               want, diff, atol, rtol);
    fflush(stdout);
    return cond;
}

TAP_UNUSED static int tap_done(void)
{
    printf("1..%d\n", tap_count_);
    if (tap_failed_) printf("# %d of %d tests failed\n", tap_failed_, tap_count_);
    fflush(stdout);
    return (tap_failed_ || tap_count_ == 0) ? 1 : 0;
}

/* ---- deterministic PRNG: splitmix64 ---- */
typedef struct tap_rng {
    uint64_t s;
} tap_rng;

TAP_UNUSED static tap_rng tap_rng_seed(uint64_t seed)
{
    tap_rng r;
    r.s = seed;
    return r;
}

TAP_UNUSED static uint64_t tap_rng_u64(tap_rng *r)
{
    uint64_t z = (r->s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

/* Uniform in [0, 1) with 53 random bits. */
TAP_UNUSED static double tap_rng_unif(tap_rng *r)
{
    return (double)(tap_rng_u64(r) >> 11) * (1.0 / 9007199254740992.0);
}

/* Uniform in [lo, hi). */
TAP_UNUSED static double tap_rng_range(tap_rng *r, double lo, double hi)
{
    return lo + (hi - lo) * tap_rng_unif(r);
}

/* Uniform integer in [0, n), n > 0. */
TAP_UNUSED static int tap_rng_int(tap_rng *r, int n)
{
    return (int)(tap_rng_u64(r) % (uint64_t)n);
}

#endif
