/* The INI reading of the programs' text files (scene files, sweep files; libprogutil, prefix
 * pu_): inih (libinih-dev, <ini.h>) parses the text, pu_ini stands in front of it and numbers and
 * checks each line, so that every message can say what is wrong and where; and the values'
 * numbers (decimal only).
 *
 * pu_ini_parse runs inih's ini_parse_stream with pu_ini's reader: the text is split into lines
 * (LF, CR LF or a lone CR) and each line is checked before inih gets it. inih splits the lines it
 * is given into section, key and value (a key line "key = value" or "key : value", an inline
 * comment ';' after white space, a comment line ';' or '#' first, a UTF-8 byte order mark on
 * line 1 skipped) and calls the key handler; as inih handles each line as soon as it has read
 * it, the reader's count is the handler's line.
 *
 * Per line the reader refuses: a NUL character, a line longer than the caller's size (and inih's
 * buffer) allows, an indented line after a key (inih would take it as a continuation), a header
 * without ']' (before an inline comment) or with text after it, a line without '=' or ':', a key
 * missing before it. inih calls no handler on a section header (Debian builds it without
 * INI_CALL_HANDLER_ON_NEW_SECTION): the reader gives each checked header to the section handler
 * before inih reads it. The section names and keys themselves are the caller's to check.
 *
 * Messages are "FILE:LINE: what" (pu_ini_fail), values' "FILE:LINE: key 'K' in [S]: expected
 * E, got 'V'" (pu_ini_bad_value). No output, no exit, no global state. */
#ifndef PU_INI_H
#define PU_INI_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* The caller's handlers (user is passed to both); each returns nonzero to go on, or 0 to stop
 * the parse (the caller keeps its own message). */
typedef struct pu_ini_handler {
    /* A section header, checked: the name between its brackets, trimmed (cut to 127
     * characters), on line line. */
    int (*section)(void *user, const char *name, int line);
    /* A key line as inih gives it: inih's section (the last header's text between the brackets
     * as written: not trimmed, at most 49 characters; "" before any header), the key and the
     * value (trimmed, the value before an inline comment), on line line. */
    int (*key)(void *user, const char *section, const char *key, const char *value, int line);
    void *user;
} pu_ini_handler;

typedef enum pu_ini_status {
    PU_INI_OK = 0,
    PU_INI_REFUSED = -1, /* the reader refused a line: "FILE:LINE: what" in msg */
    PU_INI_STOPPED = -2, /* a handler returned 0 */
    PU_INI_SYNTAX = -3,  /* inih's own error on a line the reader let through: "FILE:LINE: syntax
                            error" in msg */
    PU_INI_NOMEM = -4    /* inih ran out of memory: "FILE: out of memory" in msg */
} pu_ini_status;

typedef struct pu_ini_result {
    int line;     /* the line of the refusal, the stop or inih's error (0: none) */
    int too_long; /* REFUSED: the line was longer than allowed */
    char key[64]; /* too_long: the line's key when it has one (cut to 63 characters), else "" */
} pu_ini_result;

/* Parses len bytes of text (not necessarily NUL-terminated; file for the messages, NULL:
 * "<string>") with inih, each line checked and numbered by pu_ini first, into h's handlers. A
 * line needs strlen + 2 <= line_size bytes (its "\n" and NUL; at most inih's buffer,
 * INI_MAX_LINE; 0: inih's). Stops at the first refusal or handler's 0. res (may be NULL) says
 * where. */
pu_ini_status pu_ini_parse(const char *text, size_t len, const char *file, size_t line_size,
                           const pu_ini_handler *h, pu_ini_result *res, char *msg, size_t msize);

/* The number of the line (1 = the first, lines as pu_ini_parse counts them) that holds byte pos
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
