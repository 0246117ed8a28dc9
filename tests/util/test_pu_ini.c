/* pu_ini.h: lines (LF, CR LF, CR) numbered and checked in front of inih, the sections and the
 * keys and values as inih splits them, the refusals with FILE:LINE, the numbers. */
#include <stdio.h>
#include <string.h>

#include "pu_ini.h"
#include "tap.h"

static char msg[512];

/* What the handlers saw, one "LINE S name" or "LINE K [section] key=value" a line; stop_at: the
 * line whose handler says stop (0: none). */
static char seen[1024];
static int stop_at;

static int rec_section(void *user, const char *name, int line)
{
    (void)user;
    size_t n = strlen(seen);
    snprintf(seen + n, sizeof seen - n, "%d S %s\n", line, name);
    return line != stop_at;
}

static int rec_key(void *user, const char *section, const char *key, const char *value, int line)
{
    (void)user;
    size_t n = strlen(seen);
    snprintf(seen + n, sizeof seen - n, "%d K [%s] %s=%s\n", line, section, key, value);
    return line != stop_at;
}

static pu_ini_status parse(const char *text, size_t len, size_t line_size, pu_ini_result *res)
{
    pu_ini_handler h = {rec_section, rec_key, NULL};
    seen[0] = msg[0] = '\0';
    return pu_ini_parse(text, len, "f.ini", line_size, &h, res, msg, sizeof msg);
}

static void test_lines(void)
{
    const char *text = "\xEF\xBB\xBF; comment\r\n[solver]  ; note\rrtol = 1e-6 ; inline\n"
                       "name: paper\n[ Boom ]\n\n  E=2e11\n# end";
    pu_ini_result res;
    tap_ok(parse(text, strlen(text), 64, &res) == PU_INI_OK && res.line == 0, "parses: '%s'", msg);
    tap_ok(!strcmp(seen, "2 S solver\n"
                         "3 K [solver] rtol=1e-6\n"
                         "4 K [solver] name=paper\n"
                         "5 S Boom\n"
                         "7 K [ Boom ] E=2e11\n"),
           "byte order mark, CR LF, lone CR, inline comments, 'key : value', inih's section as "
           "written, an indented key after a header:\n%s",
           seen);
    stop_at = 4;
    tap_ok(parse(text, strlen(text), 64, &res) == PU_INI_STOPPED && res.line == 4 && !msg[0] &&
               !strcmp(seen, "2 S solver\n3 K [solver] rtol=1e-6\n4 K [solver] name=paper\n"),
           "a handler's 0 stops the parse at its line");
    stop_at = 5;
    tap_ok(parse(text, strlen(text), 64, &res) == PU_INI_STOPPED && res.line == 5,
           "a section handler's 0 too");
    stop_at = 0;
    tap_ok(parse("[a]\nk = 1\n[b]\nk = 2", 10, 64, &res) == PU_INI_OK &&
               !strcmp(seen, "1 S a\n2 K [a] k=1\n"),
           "len bytes only (not NUL-terminated)");
    tap_ok(parse("k = v ;c\n[a]\nk =;x\n", 19, 0, &res) == PU_INI_OK &&
               !strcmp(seen, "1 K [] k=v\n2 S a\n3 K [a] k=;x\n"),
           "a key before any header; ';' not after white space is text: '%s'", seen);
}

/* The first error of text, or "" if none. */
static const char *first_error(const char *text, size_t len)
{
    pu_ini_result res;
    return parse(text, len, 64, &res) == PU_INI_REFUSED && res.line > 0 ? msg : "";
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
    pu_ini_result res;
    const char *vals =
        "[axis]\nvalues = 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17\n";
    tap_ok(parse(vals, strlen(vals), 64, &res) == PU_INI_REFUSED && res.line == 2 && res.too_long &&
               !strcmp(res.key, "values"),
           "a line too long: its line and key in the result");
    tap_ok(!strcmp(first_error("[a ; ]\n", 7), "f.ini:1: section header without ']': '[a ; ]'") &&
               !strcmp(first_error("[a]\nk ; = 1\n", 12),
                       "f.ini:2: expected 'key = value' or '[section]', got 'k ; = 1'"),
           "a ']' or '=' after an inline comment does not count");
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
