/* The table-driven command line (pu_cli.h). */
#include "pu_cli.h"

#include <ctype.h>
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define NAME_MAX_LEN 63 /* longer names are unknown without a search */

#if defined(__GNUC__)
__attribute__((format(printf, 3, 4)))
#endif
static int
fail(char *msg, size_t size, const char *fmt, ...)
{
    if (msg && size) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(msg, size, fmt, ap);
        va_end(ap);
    }
    return PU_CLI_ERROR;
}

int pu_cli_edit_distance(const char *a, const char *b)
{
    enum { MAXL = 64 };
    size_t la = strlen(a), lb = strlen(b);
    if (la > MAXL) la = MAXL;
    if (lb > MAXL) lb = MAXL;
    int d[MAXL + 1][MAXL + 1];
    for (size_t i = 0; i <= la; i++)
        d[i][0] = (int)i;
    for (size_t j = 0; j <= lb; j++)
        d[0][j] = (int)j;
    for (size_t i = 1; i <= la; i++)
        for (size_t j = 1; j <= lb; j++) {
            int ca = tolower((unsigned char)a[i - 1]), cb = tolower((unsigned char)b[j - 1]);
            int v = d[i - 1][j - 1] + (ca != cb);
            if (d[i - 1][j] + 1 < v) v = d[i - 1][j] + 1;
            if (d[i][j - 1] + 1 < v) v = d[i][j - 1] + 1;
            if (i > 1 && j > 1 && ca == tolower((unsigned char)b[j - 2]) &&
                tolower((unsigned char)a[i - 2]) == cb && d[i - 2][j - 2] + 1 < v)
                v = d[i - 2][j - 2] + 1;
            d[i][j] = v;
        }
    return d[la][lb];
}

const pu_cli_option *pu_cli_find(const pu_cli *cli, const char *name)
{
    for (int k = 0; k < cli->noptions; k++) {
        const pu_cli_option *o = &cli->options[k];
        if (!strcmp(o->name, name) || (o->alias && !strcmp(o->alias, name))) return o;
    }
    return NULL;
}

const pu_cli_option *pu_cli_nearest(const pu_cli *cli, const char *name, int *dist)
{
    const pu_cli_option *best = NULL;
    int bd = INT_MAX;
    for (int k = 0; k < cli->noptions; k++) {
        if (cli->options[k].hidden) continue;
        int d = pu_cli_edit_distance(name, cli->options[k].name);
        if (d < bd) bd = d, best = &cli->options[k];
    }
    if (dist) *dist = bd;
    return best;
}

/* ------------------------------------------------------------------ values ---- */

static void *field(void *base, size_t at)
{
    return at ? (char *)base + (at - 1) : NULL;
}

/* The form of a decimal number: the characters of one, and strtod takes all of them. */
static int number_form(const char *v)
{
    if (!*v || strspn(v, "0123456789+-.eE") != strlen(v)) return 0;
    char *end;
    (void)strtod(v, &end);
    return end != v && !*end;
}

/* The form of an integer: an optional sign and digits (the sign is refused afterwards). */
static int integer_form(const char *v)
{
    if (*v == '-' || *v == '+') v++;
    return *v && strspn(v, "0123456789") == strlen(v);
}

static int is_choice(const char *choices, const char *v)
{
    size_t n = strlen(v);
    for (const char *p = choices; p && *p;) {
        const char *e = strchr(p, '|');
        size_t len = e ? (size_t)(e - p) : strlen(p);
        if (len == n && !strncmp(p, v, n)) return 1;
        p = e ? e + 1 : NULL;
    }
    return 0;
}

/* Whether the next argument v is taken as the optional value of o. */
static int takes_next(const pu_cli_option *o, const char *v)
{
    switch (o->kind) {
    case PU_CLI_INT:
    case PU_CLI_LLONG:
        return integer_form(v);
    case PU_CLI_DOUBLE:
        return number_form(v);
    case PU_CLI_CHOICE:
        return is_choice(o->choices, v);
    default:
        return v[0] != '-';
    }
}

static int in_range(const pu_cli_option *o, double x)
{
    if (o->kind != PU_CLI_DOUBLE && o->min == 0 && o->max == 0) return 1;
    if (o->min_open ? !(x > o->min) : !(x >= o->min)) return 0;
    if (o->max_open ? !(x < o->max) : !(x <= o->max)) return 0;
    return 1;
}

static int bad_value(const pu_cli_option *o, const char *value, char *msg, size_t size)
{
    if (o->bad) {
#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wformat-nonliteral"
#endif
        return fail(msg, size, o->bad, o->name, value);
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif
    }
    return fail(msg, size, "option %s needs %s (got '%s')", o->name, o->what ? o->what : "a value",
                value);
}

/* Stores value into the option's field by its kind. */
static int store(const pu_cli_option *o, const char *value, void *base, char *msg, size_t size)
{
    void *f = field(base, o->at);
    switch (o->kind) {
    case PU_CLI_STRING:
        if (f) *(const char **)f = value;
        return 0;
    case PU_CLI_CHOICE:
        if (!is_choice(o->choices, value)) return bad_value(o, value, msg, size);
        if (f) *(const char **)f = value;
        return 0;
    case PU_CLI_INT:
    case PU_CLI_LLONG: {
        char *end;
        errno = 0;
        long long v = strtoll(value, &end, 10);
        int ok = *value && strspn(value, "0123456789") == strlen(value) && !*end && errno != ERANGE;
        if (o->kind == PU_CLI_INT && (v < INT_MIN || v > INT_MAX)) ok = 0;
        if (!ok || !in_range(o, (double)v)) return bad_value(o, value, msg, size);
        if (f && o->kind == PU_CLI_INT) *(int *)f = (int)v;
        if (f && o->kind == PU_CLI_LLONG) *(long long *)f = v;
        return 0;
    }
    case PU_CLI_DOUBLE: {
        char *end;
        errno = 0;
        double v = number_form(value) ? strtod(value, &end) : NAN;
        if (!isfinite(v) || (errno == ERANGE && fabs(v) > 1) || !in_range(o, v))
            return bad_value(o, value, msg, size);
        if (f) *(double *)f = v;
        return 0;
    }
    case PU_CLI_CALL:
        return o->take && o->take(o, value, base, msg, size) != 0 ? PU_CLI_ERROR : 0;
    default:
        return 0;
    }
}

/* ------------------------------------------------------------------- parse ---- */

static int unknown(const pu_cli *cli, const char *name, char *msg, size_t size)
{
    const pu_cli_option *near = cli->suggest ? pu_cli_nearest(cli, name, NULL) : NULL;
    if (near) return fail(msg, size, "unknown option '%s'; did you mean %s?", name, near->name);
    return fail(msg, size, "unknown option '%s'", name);
}

int pu_cli_parse(const pu_cli *cli, int argc, char **argv, void *base,
                 const pu_cli_option **stopped, char *msg, size_t size)
{
    int positional_only = 0;
    if (stopped) *stopped = NULL;
    if (msg && size) msg[0] = '\0';
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (positional_only || a[0] != '-' || !strcmp(a, "-")) {
            const char **pos = field(base, cli->positional);
            if (!pos) return fail(msg, size, "unexpected argument '%s'", a);
            if (*pos) {
#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wformat-nonliteral"
#endif
                if (cli->positional_many) return fail(msg, size, cli->positional_many, *pos, a);
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif
                return fail(msg, size, "more than one argument given ('%s' and '%s')", *pos, a);
            }
            *pos = a;
            continue;
        }
        if (!strcmp(a, "--")) {
            positional_only = 1;
            continue;
        }
        char name[NAME_MAX_LEN + 1];
        const char *eq = strchr(a, '='), *value = NULL;
        size_t n = eq ? (size_t)(eq - a) : strlen(a);
        if (n > NAME_MAX_LEN) return fail(msg, size, "unknown option '%.40s...'", a);
        memcpy(name, a, n);
        name[n] = '\0';
        const pu_cli_option *o = pu_cli_find(cli, name);
        if (!o) return unknown(cli, name, msg, size);
        name[0] = '\0';
        snprintf(name, sizeof name, "%s", o->name); /* an alias is named by its option */
        int none = o->kind == PU_CLI_FLAG || o->kind == PU_CLI_STOP || o->value == PU_CLI_NONE;
        if (none && eq) return fail(msg, size, "option %s takes no value (got '%s')", name, eq + 1);
        int *seen = field(base, o->seen);
        if (seen) *seen = 1;
        if (o->kind == PU_CLI_STOP) {
            if (stopped) *stopped = o;
            return PU_CLI_STOPPED;
        }
        if (o->kind == PU_CLI_FLAG) {
            int *f = field(base, o->at);
            if (f) *f = 1;
            continue;
        }
        if (none) {
            if (store(o, NULL, base, msg, size) != 0) return PU_CLI_ERROR;
            continue;
        }
        if (o->value == PU_CLI_OPTIONAL) {
            value = eq ? eq + 1 : i + 1 < argc && takes_next(o, argv[i + 1]) ? argv[++i] : NULL;
            if (!value) {
                if (o->kind == PU_CLI_CALL && store(o, NULL, base, msg, size) != 0)
                    return PU_CLI_ERROR;
                continue;
            }
        } else {
            if (eq)
                value = eq + 1;
            else if (i + 1 < argc)
                value = argv[++i];
            else
                return fail(msg, size, "option %s needs a value", name);
            if (!*value) return fail(msg, size, "option %s needs a value (got '')", name);
            if (!eq && !strncmp(value, "--", 2))
                return fail(msg, size, "option %s needs a value (got the option '%s')", name,
                            value);
        }
        if (store(o, value, base, msg, size) != 0) return PU_CLI_ERROR;
    }
    return PU_CLI_DONE;
}

/* -------------------------------------------------------------------- help ---- */

/* Writes text from column col (the cursor is there) wrapped at width, continuation lines
 * indented to indent; words are kept whole, "\n" breaks the line. Ends with a newline. */
static void wrap(FILE *f, const char *text, int col, int indent, int width)
{
    const char *p = text;
    int at = col, first = 1; /* first word on this line */
    while (*p) {
        if (*p == '\n') {
            fprintf(f, "\n%*s", indent, "");
            at = indent, first = 1, p++;
            continue;
        }
        if (*p == ' ') {
            p++;
            continue;
        }
        int len = (int)strcspn(p, " \n");
        if (!first && at + 1 + len > width) {
            fprintf(f, "\n%*s", indent, "");
            at = indent, first = 1;
        }
        if (!first) fputc(' ', f), at++;
        fwrite(p, 1, (size_t)len, f);
        at += len, first = 0, p += len;
    }
    fputc('\n', f);
}

char *pu_cli_help(const pu_cli *cli)
{
    int col = cli->column > 0 ? cli->column : 23, width = cli->width > 0 ? cli->width : 92;
    char *buf = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&buf, &len);
    if (!f) return NULL;
    fprintf(f, "usage: %s ", cli->program);
    if (cli->usage) {
        fprintf(f, "%s\n", cli->usage);
    } else { /* the synopsis: every option of the help */
        int indent = (int)strlen(cli->program) + 8, at = indent;
        for (int k = 0; k < cli->noptions; k++) {
            const pu_cli_option *o = &cli->options[k];
            if (o->hidden) continue;
            int n = (int)strlen(o->name) + 2 + (o->arg ? 1 + (int)strlen(o->arg) : 0);
            if (at > indent && at + 1 + n > width) fprintf(f, "\n%*s", indent, ""), at = indent;
            fprintf(f, "%s[%s%s%s]", at > indent ? " " : "", o->name, o->arg ? " " : "",
                    o->arg ? o->arg : "");
            at += n + (at > indent);
        }
        fputc('\n', f);
    }
    if (cli->intro) fprintf(f, "\n%s", cli->intro);
    if (cli->intro || cli->options_title) fputc('\n', f);
    if (cli->options_title) fprintf(f, "%s\n", cli->options_title);
    for (int k = 0; k < cli->noptions; k++) {
        const pu_cli_option *o = &cli->options[k];
        if (o->hidden) continue;
        int n = fprintf(f, "  %s%s%s", o->name, o->arg ? " " : "", o->arg ? o->arg : "");
        if (!o->help || !*o->help) {
            fputc('\n', f);
            continue;
        }
        if (n + 1 > col)
            fprintf(f, "\n%*s", col, "");
        else
            fprintf(f, "%*s", col - n, "");
        wrap(f, o->help, col, col, width);
    }
    if (cli->epilogue) fprintf(f, "\n%s", cli->epilogue);
    int bad = ferror(f);
    if (fclose(f) != 0 || bad) {
        free(buf);
        return NULL;
    }
    return buf;
}
