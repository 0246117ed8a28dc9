/* The INI line reader and the values' numbers (pu_ini.h). */
#include "pu_ini.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int pu_ini_fail(char *msg, size_t size, const char *file, int line, const char *fmt, ...)
{
    if (!msg || !size) return -1;
    char text[1536];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(text, sizeof text, fmt, ap);
    va_end(ap);
    if (line > 0)
        snprintf(msg, size, "%s:%d: %s", file, line, text);
    else
        snprintf(msg, size, "%s: %s", file, text);
    return -1;
}

void pu_ini_quote(const char *v, char *buf, size_t size)
{
    size_t n = 0, max = size - 4 < 60 ? size - 4 : 60;
    for (; v[n] && v[n] != '\n' && v[n] != '\r' && n < max; n++)
        buf[n] = v[n];
    buf[n] = '\0';
    if (v[n] && v[n] != '\n' && v[n] != '\r') strcat(buf, "...");
}

void pu_ini_trim_copy(const char *a, const char *b, char *out, size_t size)
{
    while (a < b && isspace((unsigned char)*a))
        a++;
    while (b > a && isspace((unsigned char)b[-1]))
        b--;
    size_t n = (size_t)(b - a) < size - 1 ? (size_t)(b - a) : size - 1;
    memcpy(out, a, n);
    out[n] = '\0';
}

int pu_ini_ieq(const char *a, const char *b)
{
    for (; *a && *b; a++, b++)
        if (tolower((unsigned char)*a) != tolower((unsigned char)*b)) return 0;
    return *a == *b;
}

int pu_ini_looks_hex(const char *v)
{
    for (const char *p = v; *p; p++)
        if (*p == '0' && (p[1] == 'x' || p[1] == 'X') && (p == v || !isalnum((unsigned char)p[-1])))
            return 1;
    return 0;
}

int pu_ini_bad_value(char *msg, size_t size, const char *file, int line, const char *key,
                     const char *section, const char *expected, const char *got, int numeric)
{
    char q[80];
    pu_ini_quote(got, q, sizeof q);
    return pu_ini_fail(msg, size, file, line, "key '%s' in [%s]: expected %s, got '%s'%s", key,
                       section, expected, q,
                       numeric && pu_ini_looks_hex(got)
                           ? " (numbers are decimal: hexadecimal is not accepted)"
                           : "");
}

/* strtod alone would also take hexadecimal ("0x4c", "0x1p3"), "inf" and "nan": the characters
 * are checked first. An underflow is harmless, an overflow is refused. */
int pu_ini_parse_double(const char *v, double *out)
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

int pu_ini_parse_llong(const char *v, long long lo, long long hi, long long *out)
{
    while (isspace((unsigned char)*v))
        v++;
    if (!*v || strspn(v, "+-0123456789") == 0) return 0;
    char *end;
    errno = 0;
    long long x = strtoll(v, &end, 10);
    while (isspace((unsigned char)*end))
        end++;
    if (*end || end == v || errno == ERANGE || x < lo || x > hi) return 0;
    *out = x;
    return 1;
}

/* ------------------------------------------------------------------ lines ---- */

void pu_ini_init(pu_ini_reader *r, const char *text, size_t len, const char *file)
{
    memset(r, 0, sizeof *r);
    r->text = text;
    r->len = len;
    r->file = file ? file : "<string>";
}

/* Like inih's find_chars_or_comment: the first of chars, or an inline comment (';' after white
 * space), or the end. */
static char *find_chars_or_comment(char *s, const char *chars)
{
    int was_space = 0;
    while (*s && (!chars || !strchr(chars, *s)) && !(was_space && *s == ';')) {
        was_space = isspace((unsigned char)*s);
        s++;
    }
    return s;
}

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

int pu_ini_line_at(const char *text, size_t pos)
{
    int line = 1;
    for (size_t i = 0, e; (i += line_length(text + i, pos - i)) < pos; i += e, line++)
        e = line_end_length(text + i, pos - i);
    return line;
}

/* Classifies the line in buf (with its "\n"). */
static pu_ini_kind classify(pu_ini_reader *r, char *buf, pu_ini_line *ln, char *msg, size_t msize)
{
    char *p = buf, q[80];
    if (r->line == 1 && (unsigned char)p[0] == 0xEF && (unsigned char)p[1] == 0xBB &&
        (unsigned char)p[2] == 0xBF)
        p += 3;
    char *start = p;
    while (*p && isspace((unsigned char)*p))
        p++;
    if (!*p || *p == ';' || *p == '#') return PU_INI_BLANK;
    pu_ini_quote(p, q, sizeof q);
    if (r->have_prev_key && p > start) {
        pu_ini_fail(msg, msize, r->file, r->line,
                    "indented line '%s': continuation lines are not supported (remove the "
                    "indentation)",
                    q);
        return PU_INI_ERROR;
    }
    if (*p == '[') {
        const char *e = find_chars_or_comment(p + 1, "]");
        if (*e != ']') {
            pu_ini_fail(msg, msize, r->file, r->line, "section header without ']': '%s'", q);
            return PU_INI_ERROR;
        }
        pu_ini_trim_copy(p + 1, e, ln->name, sizeof ln->name);
        const char *rest = e + 1;
        while (*rest && isspace((unsigned char)*rest))
            rest++;
        if (*rest && *rest != ';' && *rest != '#') {
            pu_ini_fail(msg, msize, r->file, r->line, "unexpected text after [%s]: '%s'", ln->name,
                        q);
            return PU_INI_ERROR;
        }
        ln->header = p + 1;
        ln->header_len = (size_t)(e - (p + 1));
        r->have_prev_key = 0;
        return PU_INI_SECTION;
    }
    char *e = find_chars_or_comment(p, "=:");
    if (*e != '=' && *e != ':') {
        pu_ini_fail(msg, msize, r->file, r->line, "expected 'key = value' or '[section]', got '%s'",
                    q);
        return PU_INI_ERROR;
    }
    pu_ini_trim_copy(p, e, ln->name, sizeof ln->name);
    if (!ln->name[0]) {
        pu_ini_fail(msg, msize, r->file, r->line, "key missing before '%c': '%s'", *e, q);
        return PU_INI_ERROR;
    }
    char *v = e + 1, *ve = find_chars_or_comment(v, NULL), *ke = e;
    while (v < ve && isspace((unsigned char)*v))
        v++;
    while (ve > v && isspace((unsigned char)ve[-1]))
        ve--;
    while (ke > p && isspace((unsigned char)ke[-1]))
        ke--;
    *ke = '\0'; /* at '=' or after the key: before the value */
    *ve = '\0';
    ln->key = p;
    ln->value = v;
    ln->value_len = (size_t)(ve - v);
    r->have_prev_key = 1;
    return PU_INI_KEY;
}

pu_ini_kind pu_ini_next(pu_ini_reader *r, char *buf, size_t size, pu_ini_line *ln, char *msg,
                        size_t msize)
{
    memset(ln, 0, sizeof *ln);
    if (r->pos >= r->len) return PU_INI_END;
    const char *p = r->text + r->pos;
    size_t rest = r->len - r->pos, n = line_length(p, rest);
    r->line++;
    ln->line = r->line;
    r->pos += n + line_end_length(p + n, rest - n);
    if (memchr(p, '\0', n)) {
        pu_ini_fail(msg, msize, r->file, r->line,
                    "the line contains a NUL character (not a text file?)");
        return PU_INI_ERROR;
    }
    if (n + 2 > size) { /* name the key if the line has one */
        ln->too_long = 1;
        const char *e = memchr(p, '=', n);
        if (e && p[0] != '[' && p[0] != ';' && p[0] != '#')
            pu_ini_trim_copy(p, e, ln->name, sizeof ln->name < 64 ? sizeof ln->name : 64);
        if (ln->name[0])
            pu_ini_fail(msg, msize, r->file, r->line, "line longer than %d characters (key '%s')",
                        (int)size - 2, ln->name);
        else
            pu_ini_fail(msg, msize, r->file, r->line, "line longer than %d characters",
                        (int)size - 2);
        return PU_INI_ERROR;
    }
    memcpy(buf, p, n);
    buf[n] = '\n';
    buf[n + 1] = '\0';
    return classify(r, buf, ln, msg, msize);
}
