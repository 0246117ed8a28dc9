/* The INI reading in front of inih and the values' numbers (pu_ini.h). */
#include "pu_ini.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <ini.h>

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

/* Lines end with LF, CR LF or a lone CR: the length of the line at p (without its end) and of the
 * line end that follows it (0 at the end of the text). */
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

/* ------------------------------------------------------- in front of inih ---- */

/* One pu_ini_parse: the reader's place in the text and the first refusal or stop. */
typedef struct reader_state {
    const char *file, *text;
    size_t len, pos, line_size;
    const pu_ini_handler *h;
    int line;          /* the number of the line last read (1 = the first) */
    int have_prev_key; /* a key line came since the last header */
    pu_ini_status status;
    pu_ini_result *res;
    char *msg;
    size_t msize;
} reader_state;

#if defined(__GNUC__)
__attribute__((format(printf, 2, 3)))
#endif
static int
refuse(reader_state *st, const char *fmt, ...)
{
    char text[1024];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(text, sizeof text, fmt, ap);
    va_end(ap);
    st->status = PU_INI_REFUSED;
    st->res->line = st->line;
    pu_ini_fail(st->msg, st->msize, st->file, st->line, "%s", text);
    return 0;
}

/* Where an inline comment starts in the text s (a line from its first non-blank character): the
 * first ';' that follows white space, as inih is built (INI_ALLOW_INLINE_COMMENTS,
 * INI_INLINE_COMMENT_PREFIXES ";"); the end of s if none. */
static const char *comment_start(const char *s)
{
    size_t i = 0;
    while (s[i] && !(i > 0 && s[i] == ';' && isspace((unsigned char)s[i - 1])))
        i++;
    return s + i;
}

/* The first character of [a, b) that is one of chars, or NULL. */
static const char *first_of(const char *a, const char *b, const char *chars)
{
    for (; a < b; a++)
        if (strchr(chars, *a)) return a;
    return NULL;
}

/* Checks the line in buf (with its "\n") before inih reads it; a header goes to the section
 * handler. 1 to hand it on, 0 with st->status set. */
static int check_line(reader_state *st, const char *buf)
{
    const char *p = buf, *start;
    char q[80];
    if (st->line == 1 && (unsigned char)p[0] == 0xEF && (unsigned char)p[1] == 0xBB &&
        (unsigned char)p[2] == 0xBF)
        p += 3;
    start = p;
    while (*p && isspace((unsigned char)*p))
        p++;
    if (!*p || *p == ';' || *p == '#') return 1; /* blank or a comment */
    pu_ini_quote(p, q, sizeof q);
    if (st->have_prev_key && p > start)
        return refuse(st,
                      "indented line '%s': continuation lines are not supported (remove the "
                      "indentation)",
                      q);
    const char *text_end = comment_start(p);
    if (*p == '[') {
        const char *close = first_of(p + 1, text_end, "]");
        if (!close) return refuse(st, "section header without ']': '%s'", q);
        char name[128];
        pu_ini_trim_copy(p + 1, close, name, sizeof name);
        const char *rest = close + 1;
        while (*rest && isspace((unsigned char)*rest))
            rest++;
        if (*rest && *rest != ';' && *rest != '#')
            return refuse(st, "unexpected text after [%s]: '%s'", name, q);
        st->have_prev_key = 0;
        if (st->h->section && !st->h->section(st->h->user, name, st->line)) {
            st->status = PU_INI_STOPPED;
            st->res->line = st->line;
            return 0;
        }
        return 1;
    }
    const char *sep = first_of(p, text_end, "=:");
    if (!sep) return refuse(st, "expected 'key = value' or '[section]', got '%s'", q);
    if (sep == p) return refuse(st, "key missing before '%c': '%s'", *sep, q);
    st->have_prev_key = 1;
    return 1;
}

/* inih's ini_reader: the next line of the text into str (num bytes) with "\n" and NUL, once
 * checked; NULL at the end of the text or after a refusal or a stop. */
static char *reader(char *str, int num, void *stream)
{
    reader_state *st = stream;
    if (st->status != PU_INI_OK || st->pos >= st->len) return NULL;
    const char *p = st->text + st->pos;
    size_t rest = st->len - st->pos, n = line_length(p, rest);
    size_t size = num > 0 && (size_t)num < st->line_size ? (size_t)num : st->line_size;
    st->line++;
    st->pos += n + line_end_length(p + n, rest - n);
    if (memchr(p, '\0', n)) {
        refuse(st, "the line contains a NUL character (not a text file?)");
        return NULL;
    }
    if (n + 2 > size) { /* name the key if the line has one */
        pu_ini_result *res = st->res;
        res->too_long = 1;
        const char *e = memchr(p, '=', n);
        if (e && p[0] != '[' && p[0] != ';' && p[0] != '#')
            pu_ini_trim_copy(p, e, res->key, sizeof res->key);
        if (res->key[0])
            refuse(st, "line longer than %d characters (key '%s')", (int)size - 2, res->key);
        else
            refuse(st, "line longer than %d characters", (int)size - 2);
        return NULL;
    }
    memcpy(str, p, n);
    str[n] = '\n';
    str[n + 1] = '\0';
    return check_line(st, str) ? str : NULL;
}

/* inih's ini_handler: a key line as inih split it, with the reader's line. */
static int key_handler(void *user, const char *section, const char *name, const char *value)
{
    reader_state *st = user;
    if (st->status != PU_INI_OK) return 0;
    if (st->h->key && !st->h->key(st->h->user, section, name, value, st->line)) {
        st->status = PU_INI_STOPPED;
        st->res->line = st->line;
        return 0;
    }
    return 1;
}

pu_ini_status pu_ini_parse(const char *text, size_t len, const char *file, size_t line_size,
                           const pu_ini_handler *h, pu_ini_result *res, char *msg, size_t msize)
{
    pu_ini_result scratch;
    if (!res) res = &scratch;
    memset(res, 0, sizeof *res);
    reader_state st;
    memset(&st, 0, sizeof st);
    st.file = file ? file : "<string>";
    st.text = text;
    st.len = len;
    st.line_size = line_size ? line_size : (size_t)-1;
    st.h = h;
    st.res = res;
    st.msg = msg;
    st.msize = msize;
    int r = ini_parse_stream(reader, &st, key_handler, &st);
    if (st.status != PU_INI_OK) return st.status;
    if (r == 0) return PU_INI_OK;
    if (r == -2) {
        pu_ini_fail(msg, msize, st.file, 0, "out of memory");
        return PU_INI_NOMEM;
    }
    res->line = r > 0 ? r : 0;
    pu_ini_fail(msg, msize, st.file, res->line, "syntax error");
    return PU_INI_SYNTAX;
}
