/* The internals shared by the parser (mdl_expr.c) and the evaluator (mdl_expr_eval.c) of the
 * model files' expressions: the tree and the parser's state. Private to model/.
 *
 * The tree lives in two growable arrays owned by the mdl_expr (nodes and path segments); children
 * are array indices. The arguments of a call and the segments of a path are singly linked lists
 * (field next), because nested expressions interleave their own entries with them while they
 * are being parsed. Every node's height (1 + the height of its highest child) is at most
 * MDL_EXPR_MAX_DEPTH, which bounds the recursion of every walk over the tree. */
#ifndef BG_MODEL_MDL_EXPR_IMPL_H
#define BG_MODEL_MDL_EXPR_IMPL_H

#include "mdl_expr.h"

enum { K_NUM, K_NAME, K_NEG, K_POS, K_NOT, K_BIN, K_CALL };
enum { B_ADD, B_SUB, B_MUL, B_DIV, B_POW, B_LT, B_LE, B_GT, B_GE, B_EQ, B_NE, B_AND, B_OR };
enum {
    F_SQRT,
    F_EXP,
    F_LOG,
    F_LOG10,
    F_SIN,
    F_COS,
    F_TAN,
    F_ASIN,
    F_ACOS,
    F_ATAN,
    F_ATAN2,
    F_SINH,
    F_COSH,
    F_TANH,
    F_HYPOT,
    F_ABS,
    F_MIN,
    F_MAX,
    F_FLOOR,
    F_CEIL,
    F_ROUND,
    F_POW,
    F_IF,
    F_COUNT
};

/* name and number of arguments (-1: one or more) of each function, in the order of the enum */

typedef struct node {
    unsigned char kind, op; /* op: B_* of K_BIN, F_* of K_CALL */
    short height;
    int start, end; /* text span */
    double num;     /* K_NUM */
    int a, b;       /* K_BIN, unary: children (b unused by unary); K_CALL: first argument, count;
                       K_NAME: first segment */
    int next;       /* next argument of a call, -1 at the end */
} node;

typedef struct seg {
    int start, len; /* the identifier's text */
    int index;      /* node of the [...] expression or -1 */
    int next;       /* next segment of the path or -1 */
} seg;

struct mdl_expr {
    char *text;
    node *nodes;
    int nn, ncap;
    seg *segs;
    int ns, scap;
    int root;
    int nnames;
};

typedef struct parser {
    mdl_expr *x;
    const char *s;
    int pos;
    int depth; /* recursion of parse_or and parse_unary */
    mdl_expr_error *e;
    int failed;
} parser;

void mdl_expri_set_error(mdl_expr_error *e, int column, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));
/* The text of [start, end) for a message: at most 60 characters, longer ones cut with "...". */
const char *mdl_expri_snippet(const char *text, int start, int end, char *buf, size_t size);
/* Records the parser's first error (later ones are ignored); returns -1. */
int mdl_expri_fail(parser *p, int column, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));
int mdl_expri_is_id0(int c);
void mdl_expri_skip_ws(parser *p);
/* Reports what stands at the current position as unexpected; returns -1. */
int mdl_expri_unexpected(parser *p);
/* A new node of the given height spanning [start, current position): its index, or -1. */
int mdl_expri_new_node(parser *p, int kind, int op, int start, int height);
/* A path at the current position (an identifier there): its first segment in *first, its
 * height (1 + the highest index) in *h. 0 or -1. */
int mdl_expri_parse_path(parser *p, int *first, int *h);
/* A new empty expression holding a copy of text (NULL with e filled). */
mdl_expr *mdl_expri_new_expr(const char *text, mdl_expr_error *e);

#endif
