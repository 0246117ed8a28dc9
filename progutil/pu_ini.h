/* The INI line reader of the programs' text files (scene files, sweep files; libprogutil,
 * prefix pu_): the text split into lines (LF, CR LF or a lone CR), each line classified and
 * checked and read as inih (the INI parser the programs used before) reads it, so that every
 * message can say what is wrong and where; and the values' numbers (decimal only).
 *
 * A line is blank or a comment (';' or '#' first), a section header "[name]" (a comment may
 * follow), or "key = value" (or "key : value"; an inline comment is ';' after white space). Per
 * line the reader refuses: a NUL character, a line longer than the caller's buffer allows, an
 * indented line after a key (inih would take it as a continuation), a header without ']' or
 * with text after it, a line without '=' or ':', a key missing before it. A UTF-8 byte order
 * mark on line 1 is skipped. The section names and keys themselves are the caller's to check.
 *
 * Messages are "FILE:LINE: what" (pu_ini_fail), values' "FILE:LINE: key 'K' in [S]: expected
 * E, got 'V'" (pu_ini_bad_value). No output, no exit, no global state. */
#ifndef PU_INI_H
#define PU_INI_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct pu_ini_reader {
    const char *file; /* for the messages */
    const char *text; /* the whole text (not necessarily NUL-terminated), len bytes */
    size_t len, pos;
    int line;          /* the number of the line last read (1 = the first) */
    int have_prev_key; /* a key line came since the last header */
} pu_ini_reader;

typedef enum pu_ini_kind {
    PU_INI_ERROR = -1, /* the message is in msg */
    PU_INI_END = 0,    /* no more lines */
    PU_INI_BLANK,      /* blank or a comment */
    PU_INI_SECTION,    /* name: the section's name, trimmed */
    PU_INI_KEY         /* name: the key, trimmed; value, value_len: its value */
} pu_ini_kind;

typedef struct pu_ini_line {
    int line;           /* its number */
    char name[128];     /* the section's name or the key (cut to 127 characters); after a line
                           that is too long, its key when it has one ("" otherwise) */
    const char *key;    /* KEY: the key in buf, trimmed, whole, NUL-terminated there */
    const char *value;  /* KEY: the value in buf, trimmed, before an inline comment,
                           NUL-terminated there */
    size_t value_len;   /* strlen(value) */
    const char *header; /* SECTION: the text between the brackets as written (not trimmed, not
                           NUL-terminated), header_len bytes */
    size_t header_len;
    int too_long; /* ERROR: the line was longer than buf allows */
} pu_ini_line;

void pu_ini_init(pu_ini_reader *r, const char *text, size_t len, const char *file);
/* The next line: copied into buf with "\n" and a NUL after it, classified into ln; a key line's
 * key and value are then cut out in buf (NUL after each, as inih does). A line needs strlen + 2
 * <= size. PU_INI_ERROR with "FILE:LINE: what" in msg. */
pu_ini_kind pu_ini_next(pu_ini_reader *r, char *buf, size_t size, pu_ini_line *ln, char *msg,
                        size_t msize);

/* The number of the line (1 = the first, lines as pu_ini_next counts them) that holds byte pos
 * of text. */
int pu_ini_line_at(const char *text, size_t pos);

/* "FILE:LINE: " (line <= 0: "FILE: ") and the message into msg. Returns -1. */
#if defined(__GNUC__)
__attribute__((format(printf, 5, 6)))
#endif
int pu_ini_fail(char *msg, size_t size, const char *file, int line, const char *fmt, ...);
/* "FILE:LINE: key 'K' in [S]: expected E, got 'V'" with V quoted (pu_ini_quote); numeric: a
 * value written in hexadecimal gets " (numbers are decimal: hexadecimal is not accepted)".
 * Returns -1. */
int pu_ini_bad_value(char *msg, size_t size, const char *file, int line, const char *key,
                     const char *section, const char *expected, const char *got, int numeric);

/* A value for a message: its first line, at most 60 characters, "..." when cut. */
void pu_ini_quote(const char *v, char *buf, size_t size);
/* [a, b) without the white space around it into out (cut to size - 1). */
void pu_ini_trim_copy(const char *a, const char *b, char *out, size_t size);
/* Names equal but for case. */
int pu_ini_ieq(const char *a, const char *b);
/* A hexadecimal number inside v ("0x4c", also within a list). */
int pu_ini_looks_hex(const char *v);
/* A decimal number (digits, sign, point, exponent; white space around it): finite, not an
 * overflow. 1 with *out, or 0. */
int pu_ini_parse_double(const char *v, double *out);
/* A decimal integer (sign, digits; white space around it) in [lo, hi]. 1 with *out, or 0. */
int pu_ini_parse_llong(const char *v, long long lo, long long hi, long long *out);

#ifdef __cplusplus
}
#endif
#endif
