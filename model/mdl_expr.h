/* Arithmetic expressions of the model files (private to model/).
 *
 * An expression is parsed once into a tree and evaluated many times; names are resolved at each
 * evaluation through a lookup callback, so the same tree serves every instance of a repeated
 * subsystem. The grammar, loosest binding first:
 *
 *   expr    := or
 *   or      := and ('||' and)*              (lazy: the right side only when the left is 0)
 *   and     := eq ('&&' eq)*                (lazy: the right side only when the left is not 0)
 *   eq      := rel (('==' | '!=') rel)*     (0 or 1)
 *   rel     := add (('<' | '<=' | '>' | '>=') add)*
 *   add     := mul (('+' | '-') mul)*
 *   mul     := unary (('*' | '/') unary)*
 *   unary   := ('-' | '+' | '!') unary | power
 *   power   := primary ('^' unary)?         (right-associative; -2^2 = -4, 2^-1 = 0.5)
 *   primary := NUMBER | '(' expr ')' | FUNC '(' expr (',' expr)* ')' | PATH
 *   PATH    := SEG ('.' SEG)*,  SEG := [A-Za-z_][A-Za-z0-9_]* ('[' expr ']')?
 *
 * Numbers have C's decimal syntax (1, 1.5, .5, 1., 1e-3). Functions: sqrt exp log log10 sin cos
 * tan asin acos atan atan2 sinh cosh tanh hypot abs min max (one or more arguments) floor ceil
 * round pow if(c, a, b) (lazy: only the chosen branch is evaluated). Constants: pi, deg = pi/180,
 * bar = 1e5, MPa = 1e6, mm = 1e-3, lpm = 1e-3/60 (m^3/s), rpm = 2 pi/60 (rad/s), g0 = 9.80665. A
 * lone constant name is folded at parse time; every other path is a name for the lookup.
 *
 * Errors carry a message and the 0-based column in the text where it went wrong; a column named
 * inside a message ("expected ')' to close '(' at column 4") is 0-based too. Evaluation refuses
 * a non-finite result of finite inputs (division by zero, sqrt(-1), log(0), overflow) with the
 * operation and its sub-expression text. The nesting of the tree is limited (MDL_EXPR_MAX_DEPTH)
 * so that hostile input cannot exhaust the stack of the recursive parser and evaluator.
 *
 * No global state, no printing; an mdl_expr is immutable after parsing (evaluate it from any
 * number of threads). */
#ifndef BG_MODEL_MDL_EXPR_H
#define BG_MODEL_MDL_EXPR_H

#include <stddef.h>

#define MDL_EXPR_MSG_SIZE 256
#define MDL_EXPR_NAME_MAX 256   /* longest name passed to the lookup, with its NUL */
#define MDL_EXPR_MAX_DEPTH 256  /* deepest tree or parenthesis nesting */
#define MDL_EXPR_MAX_TEXT 65536 /* longest expression text */

typedef struct mdl_expr mdl_expr;

typedef struct mdl_expr_error {
    int column;                      /* 0-based offset within the text */
    char message[MDL_EXPR_MSG_SIZE]; /* without position */
} mdl_expr_error;

/* Resolves a name, the full path with every index evaluated ("seg[3].L"): stores its value and
 * returns 0, or returns < 0 with a message in msg (may be left empty: "unknown name 'x'"). */
typedef int (*mdl_expr_lookup)(void *user, const char *name, double *value, char *msg, size_t msz);

/* Parses text; NULL with e filled on a syntax error, a too long or too deep text, or no memory.
 * e may be NULL. */
mdl_expr *mdl_expr_parse(const char *text, mdl_expr_error *e);
void mdl_expr_free(mdl_expr *x);

/* The text the expression was parsed from. */
const char *mdl_expr_text(const mdl_expr *x);

/* Evaluates x: 0 with *value set, or -1 with e filled (a name the lookup refused, an index that
 * is not an integer in int's range, a non-finite result). fn may be NULL for an expression
 * without names. */
int mdl_expr_eval(const mdl_expr *x, mdl_expr_lookup fn, void *user, double *value,
                  mdl_expr_error *e);

/* Calls visit for every name the expression refers to, in text order, names inside an index
 * first: "k" and then "seg[*].L" for seg[k].L. An index that is a constant integer is written
 * as such (seg[2].L); any other index as "[*]". Returns the number of names visited. */
int mdl_expr_names(const mdl_expr *x, void (*visit)(void *user, const char *name_pattern),
                   void *user);

/* 1 when x refers to no name (only numbers, constants and functions), else 0. */
int mdl_expr_is_constant(const mdl_expr *x);

/* Evaluates the [...] indices of a path ("seg[k+1].b") and writes the path with integer indices
 * ("seg[4].b") into out. 0, or -1 with e filled (a malformed path, an index error, out too
 * small). Surrounding blanks are ignored. */
int mdl_expr_subst(const char *path_text, mdl_expr_lookup fn, void *user, char *out, size_t osz,
                   mdl_expr_error *e);

/* Levenshtein distance of the first limit (<= 64) characters of a and b: the nearest names of
 * the messages (the reader's and the expressions'). */
int mdl_expr_edit_distance(const char *a, const char *b, int limit);

/* 1 when name is a function or a constant of the language (a user parameter may not be called
 * so), else 0. */
int mdl_expr_is_reserved(const char *name);

#endif
