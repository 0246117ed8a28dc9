/* The YAML document of a model file as an immutable tree with positions (private to model/).
 *
 * A file or a string is loaded through libyaml's event parser into a tree of three node kinds:
 * scalar (text, and whether it was written plain or not), sequence and mapping (pairs in the
 * document's order). Every node, mapping keys included, carries its file name, line and column
 * (1-based, as editors show them; columns count characters). Loading refuses, with a message
 * "FILE:LINE:COL: ...":
 *   - a syntax error (libyaml's problem, with its context),
 *   - a duplicate key in a mapping ("duplicate key 'mass' (first at line 3)"),
 *   - a key that is not a scalar, a scalar holding a NUL character, a tag other than !!str,
 *   - a second document in the file,
 *   - an alias to an anchor not defined before it (or to a collection that encloses it),
 *   - more than MDL_Y_MAX_NODES nodes once aliases are expanded (the "billion laughs"), more
 *     than MDL_Y_MAX_DEPTH nested collections, more than MDL_Y_MAX_BYTES of input.
 * Anchors and aliases are otherwise allowed: an alias shares the anchored node (and its
 * position), so the tree is a DAG whose expansion the node budget bounds. Merge keys ("<<") are
 * not interpreted: they are ordinary keys to the caller.
 *
 * No global state, no printing. A document is immutable once loaded; its nodes live as long as
 * it does. */
#ifndef BG_MODEL_MDL_YAML_H
#define BG_MODEL_MDL_YAML_H

#include <stddef.h>

#define MDL_Y_MAX_BYTES (16 << 20) /* largest input */
#define MDL_Y_MAX_DEPTH 64         /* most nested collections */
#define MDL_Y_MAX_NODES 1000000    /* most nodes with aliases expanded */
#define MDL_Y_MSG_SIZE 512

typedef enum mdl_y_kind { MDL_Y_SCALAR, MDL_Y_SEQUENCE, MDL_Y_MAPPING } mdl_y_kind;

typedef struct mdl_y_node mdl_y_node;
typedef struct mdl_y_doc mdl_y_doc;

typedef struct mdl_y_pair {
    const mdl_y_node *key; /* always a scalar */
    const mdl_y_node *value;
} mdl_y_pair;

struct mdl_y_node {
    mdl_y_kind kind;
    const char *file; /* the document's name */
    int line, column; /* 1-based start of the node (of its anchor or tag when it has one) */
    /* scalar */
    const char *text; /* NUL-terminated, no NUL inside */
    size_t len;
    int quoted; /* 1: written quoted, as a block scalar (| >) or tagged !!str; 0: plain */
    /* sequence (items) and mapping (pairs) */
    int n;
    const mdl_y_node *const *items;
    const mdl_y_pair *pairs;
};

typedef struct mdl_y_error {
    int line, column;             /* 1-based position of the problem; 0 when none applies */
    char message[MDL_Y_MSG_SIZE]; /* "FILE:LINE:COL: message" (or "FILE: message") */
} mdl_y_error;

/* Loads the file at path (named so in positions). 0 with *out set, or < 0 with e filled (e may
 * be NULL); *out is NULL then. */
int mdl_y_load_file(const char *path, mdl_y_doc **out, mdl_y_error *e);

/* Loads len bytes of text (NUL bytes in them are refused), named name in positions. */
int mdl_y_load_string(const char *text, size_t len, const char *name, mdl_y_doc **out,
                      mdl_y_error *e);

void mdl_y_free(mdl_y_doc *doc);

/* The root node; NULL for a stream without a document (an empty file, only comments). */
const mdl_y_node *mdl_y_root(const mdl_y_doc *doc);
const char *mdl_y_file(const mdl_y_doc *doc);

/* The value of key in a mapping (NULL: no such key, or node is not a mapping); the key node
 * itself with mdl_y_get_key. */
const mdl_y_node *mdl_y_get(const mdl_y_node *map, const char *key);
const mdl_y_node *mdl_y_get_key(const mdl_y_node *map, const char *key);

/* Iteration: the number of items or pairs (0 for a scalar), the i-th item of a sequence, the
 * i-th key and value of a mapping (NULL when out of range or of another kind). */
int mdl_y_count(const mdl_y_node *n);
const mdl_y_node *mdl_y_item(const mdl_y_node *seq, int i);
const mdl_y_node *mdl_y_key(const mdl_y_node *map, int i);
const mdl_y_node *mdl_y_value(const mdl_y_node *map, int i);

/* 1 for a plain scalar that YAML reads as null: empty, "~", "null", "Null", "NULL". */
int mdl_y_is_null(const mdl_y_node *n);

/* "scalar", "sequence" or "mapping", for messages. */
const char *mdl_y_kind_name(mdl_y_kind kind);

/* Writes "FILE:LINE:COL" of node into buf and returns buf ("?" for NULL). */
const char *mdl_y_where(const mdl_y_node *node, char *buf, size_t size);

#endif
