/* The INI text of a sweep file (sweep_spec_impl.h): the line reader that feeds inih, trimming,
 * quoting, numbers. The one place that knows the text line by line; the parser (sweep_spec.c)
 * and the schema (sweep_schema.c) see only keys and values.
 *
 * The reader hands inih one line at a time from the text in memory, so that c->line is the
 * number of the line inih is reading: LF, CR LF and CR end a line, a NUL or a line longer than
 * inih's buffer is an error of its own, and every line is checked (spec_check_line) before inih
 * parses it. */
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sweep_spec_impl.h"

/* -------------------------------------------------------------------- text ---- */

int spec_ieq(const char *a, const char *b)
{
    for (; *a && *b; a++, b++)
        if (tolower((unsigned char)*a) != tolower((unsigned char)*b)) return 0;
    return *a == *b;
}

/* A value quoted for a message: at most 60 characters. */
void spec_quote(const char *v, char *buf, size_t size)
{
    size_t n = 0, max = size - 4 < 60 ? size - 4 : 60;
    for (; v[n] && v[n] != '\n' && v[n] != '\r' && n < max; n++)
        buf[n] = v[n];
    buf[n] = '\0';
    if (v[n] && v[n] != '\n' && v[n] != '\r') strcat(buf, "...");
}

void spec_trim_copy(const char *a, const char *b, char *out, size_t size)
{
    while (a < b && isspace((unsigned char)*a))
        a++;
    while (b > a && isspace((unsigned char)b[-1]))
        b--;
    size_t n = (size_t)(b - a) < size - 1 ? (size_t)(b - a) : size - 1;
    memcpy(out, a, n);
    out[n] = '\0';
}

/* Like inih's: the first of chars, or an inline comment (';' after white space), or the end. */
const char *spec_find_chars_or_comment(const char *s, const char *chars)
{
    int was_space = 0;
    while (*s && (!chars || !strchr(chars, *s)) && !(was_space && *s == ';')) {
        was_space = isspace((unsigned char)*s);
        s++;
    }
    return s;
}

/* -------------------------------------------------------------- the reader ---- */

static size_t line_length(const char *p, size_t rest)
{
    size_t n = 0;
    while (n < rest && p[n] != '\n' && p[n] != '\r')
        n++;
    return n;
}

static size_t line_end_length(const char *p, size_t rest)
{
    if (rest == 0) return 0;
    return p[0] == '\r' && rest > 1 && p[1] == '\n' ? 2 : 1;
}

char *spec_reader(char *str, int num, void *stream)
{
    parse_ctx *c = stream;
    if (c->failed || c->pos >= c->len) return NULL;
    const char *p = c->text + c->pos;
    size_t rest = c->len - c->pos, n = line_length(p, rest);
    c->line++;
    c->pos += n + line_end_length(p + n, rest - n);
    if (memchr(p, '\0', n)) {
        spec_fail_line(c, c->line, "the line contains a NUL character (not a text file?)");
        return NULL;
    }
    if (n + 2 > (size_t)num) {
        char key[64] = "";
        const char *e = memchr(p, '=', n);
        if (e && p[0] != '[' && p[0] != ';' && p[0] != '#') spec_trim_copy(p, e, key, sizeof key);
        if (key[0])
            spec_fail_line(c, c->line, "line longer than %d characters (key '%s')%s", num - 2, key,
                           spec_ieq(key, "values")
                               ? ": split the values over several [axis] sections or "
                                 "give a range (from, to, count)"
                               : "");
        else
            spec_fail_line(c, c->line, "line longer than %d characters", num - 2);
        return NULL;
    }
    memcpy(str, p, n);
    str[n] = '\n';
    str[n + 1] = '\0';
    if (!spec_check_line(c, str)) return NULL;
    return str;
}

/* ------------------------------------------------------------------ values ---- */

/* A decimal number (as the scene files': no hexadecimal, inf or nan). */
int spec_parse_double(const char *v, double *out)
{
    while (isspace((unsigned char)*v))
        v++;
    if (!*v) return 0;
    const char *q = v;
    while (*q && !isspace((unsigned char)*q))
        if (!strchr("0123456789+-.eE", *q++)) return 0;
    char *end;
    errno = 0;
    double x = strtod(v, &end);
    while (isspace((unsigned char)*end))
        end++;
    if (*end || end == v || !isfinite(x)) return 0;
    if (errno == ERANGE && fabs(x) > 1) return 0;
    *out = x;
    return 1;
}

int spec_parse_long(const char *v, long long lo, long long hi, long long *out)
{
    while (isspace((unsigned char)*v))
        v++;
    if (!*v || strspn(v, "+-0123456789") == 0) return 0;
    char *end;
    errno = 0;
    long long x = strtoll(v, &end, 10);
    while (isspace((unsigned char)*end))
        end++;
    if (*end || errno == ERANGE || x < lo || x > hi) return 0;
    *out = x;
    return 1;
}
