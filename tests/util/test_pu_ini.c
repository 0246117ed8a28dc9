/* pu_ini.h: lines (LF, CR LF, CR), sections, keys and values, the refusals with FILE:LINE, the
 * numbers. */
#include <string.h>

#include "pu_ini.h"
#include "tap.h"

static char buf[64], msg[512];

static void test_lines(void)
{
    const char *text = "\xEF\xBB\xBF; comment\r\n[solver]  ; note\rrtol = 1e-6 ; inline\n"
                       "name: paper\n\n# end";
    pu_ini_reader r;
    pu_ini_line ln;
    pu_ini_init(&r, text, strlen(text), "s.ini");
    tap_ok(pu_ini_next(&r, buf, sizeof buf, &ln, msg, sizeof msg) == PU_INI_BLANK && ln.line == 1,
           "line 1: a comment after the byte order mark");
    tap_ok(pu_ini_next(&r, buf, sizeof buf, &ln, msg, sizeof msg) == PU_INI_SECTION &&
               !strcmp(ln.name, "solver") && ln.line == 2 && ln.header_len == 6 &&
               !strncmp(ln.header, "solver", 6),
           "line 2 (after CR LF): [solver] with a comment");
    pu_ini_kind k = pu_ini_next(&r, buf, sizeof buf, &ln, msg, sizeof msg);
    tap_ok(k == PU_INI_KEY && !strcmp(ln.name, "rtol") && ln.value_len == 4 &&
               !strncmp(ln.value, "1e-6", 4) && ln.line == 3,
           "line 3 (after a lone CR): key and value before the inline comment");
    tap_ok(!strcmp(ln.key, "rtol") && !strcmp(ln.value, "1e-6"),
           "key and value NUL-terminated in buf");
    k = pu_ini_next(&r, buf, sizeof buf, &ln, msg, sizeof msg);
    tap_ok(k == PU_INI_KEY && !strcmp(ln.name, "name") && !strncmp(ln.value, "paper", 5) &&
               ln.value_len == 5,
           "key : value");
    tap_ok(pu_ini_next(&r, buf, sizeof buf, &ln, msg, sizeof msg) == PU_INI_BLANK &&
               pu_ini_next(&r, buf, sizeof buf, &ln, msg, sizeof msg) == PU_INI_BLANK &&
               ln.line == 6 && pu_ini_next(&r, buf, sizeof buf, &ln, msg, sizeof msg) == PU_INI_END,
           "blank, comment without a newline, end");
}

/* The first error of text, or "" if none. */
static const char *first_error(const char *text, size_t len)
{
    pu_ini_reader r;
    pu_ini_line ln;
    pu_ini_init(&r, text, len, "f.ini");
    msg[0] = '\0';
    for (;;) {
        pu_ini_kind k = pu_ini_next(&r, buf, sizeof buf, &ln, msg, sizeof msg);
        if (k == PU_INI_END) return "";
        if (k == PU_INI_ERROR) return msg;
    }
}

static void test_errors(void)
{
    struct {
        const char *text, *want;
    } bad[] = {
        {"[a]\nk = 1\n  more\n",
         "f.ini:3: indented line 'more': continuation lines are not supported (remove the "
         "indentation)"},
        {"[a\n", "f.ini:1: section header without ']': '[a'"},
        {"[a] x\n", "f.ini:1: unexpected text after [a]: '[a] x'"},
        {"[a]\njust words\n", "f.ini:2: expected 'key = value' or '[section]', got 'just words'"},
        {"[a]\n = 3\n", "f.ini:2: key missing before '=': '= 3'"},
        {"[a]\nvalues = 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17\n",
         "f.ini:2: line longer than 62 characters (key 'values')"},
        {"[a]\n; 1234567890123456789012345678901234567890123456789012345678901234567\n",
         "f.ini:2: line longer than 62 characters"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
        const char *got = first_error(bad[i].text, strlen(bad[i].text));
        tap_ok(!strcmp(got, bad[i].want), "error %zu: '%s'", i, got);
    }
    const char nul[] = "[a]\nk = 1\0x\n";
    tap_ok(!strcmp(first_error(nul, sizeof nul - 1),
                   "f.ini:2: the line contains a NUL character (not a text file?)"),
           "a NUL character: '%s'", msg);
    tap_ok(!strcmp(first_error("[a]\n\n  ; indented comment\nk = 1\n", 30), ""),
           "an indented comment and blank lines are fine");
}

static void test_values(void)
{
    double x = 0;
    long long v = 0;
    tap_ok(pu_ini_parse_double(" 1.5e3 ", &x) && x == 1500, "decimal number with spaces");
    tap_ok(!pu_ini_parse_double("0x10", &x) && !pu_ini_parse_double("inf", &x) &&
               !pu_ini_parse_double("nan", &x) && !pu_ini_parse_double("1e999", &x) &&
               !pu_ini_parse_double("1 2", &x) && !pu_ini_parse_double("", &x),
           "hexadecimal, inf, nan, overflow, two numbers, empty refused");
    tap_ok(pu_ini_parse_double("1e-999", &x) && x == 0, "an underflow is harmless");
    tap_ok(pu_ini_parse_llong(" -7 ", -10, 10, &v) && v == -7, "integer in range");
    tap_ok(!pu_ini_parse_llong("11", -10, 10, &v) && !pu_ini_parse_llong("1.5", 0, 10, &v) &&
               !pu_ini_parse_llong("99999999999999999999", 0, 10, &v),
           "out of range, not whole, overflow refused");
    pu_ini_bad_value(msg, sizeof msg, "s.ini", 7, "rtol", "solver", "a number in (0, 1)", "0x1", 1);
    tap_ok(!strcmp(msg, "s.ini:7: key 'rtol' in [solver]: expected a number in (0, 1), got '0x1' "
                        "(numbers are decimal: hexadecimal is not accepted)"),
           "value message with the hexadecimal note: '%s'", msg);
    pu_ini_fail(msg, sizeof msg, "s.ini", 0, "cannot open: %s", "No such file");
    tap_ok(!strcmp(msg, "s.ini: cannot open: No such file"), "a message without a line");
    char q[80];
    pu_ini_quote("0123456789012345678901234567890123456789012345678901234567890123456789", q,
                 sizeof q);
    tap_ok(strlen(q) == 63 && !strcmp(q + 60, "..."), "quote: 60 characters and '...'");
    tap_ok(pu_ini_ieq("Solver", "sOLVER") && !pu_ini_ieq("solver", "solve"), "names any case");
    tap_ok(pu_ini_looks_hex("1, 0x4c") && !pu_ini_looks_hex("ax0x"), "hexadecimal inside");
    char t[16];
    pu_ini_trim_copy("  ab c  ", "  ab c  " + 8, t, sizeof t);
    tap_ok(!strcmp(t, "ab c"), "trim");
}

int main(void)
{
    test_lines();
    test_errors();
    test_values();
    return tap_done();
}
