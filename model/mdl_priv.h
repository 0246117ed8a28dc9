/* Private to the model reader (mdl_*.c): the instance tree, the scopes of names and the model
 * record behind mdl_model.h.
 *
 * The instance tree mirrors the file: the root stands for the model, an inner node for an
 * instance of a subsystem (it owns a bgr component), a leaf for an instance of a library type.
 * Scopes chain outward: a leaf's scope holds its loop variable (if it was repeated) and leads to
 * the scope of the node that contains it; a subsystem instance has two, its loop scope (the loop
 * variable; the values its entry gives are evaluated here, as written outside the subsystem) and
 * its own scope (the subsystem's parameters; defaults are evaluated here, inside). The root's
 * scope holds the model's parameters. */
#ifndef MDL_PRIV_H
#define MDL_PRIV_H

#include <stdarg.h>

#include "mdl_expr.h"
#include "mdl_impl.h"
#include "mdl_model.h"
#include "mdl_yaml.h"

typedef struct mdl_scope mdl_scope;

typedef struct mdl_var {
    char *name;
    const mdl_y_node *node; /* the value as written (scalar or sequence); NULL: text or value */
    const char *text;       /* a replacement (--set), an expression as text */
    mdl_scope *eval;        /* where its expression is evaluated */
    int state;              /* 0 not evaluated, 1 being evaluated, 2 done */
    int len;                /* 0: a number, > 0: a vector of len */
    double value;
    double *vec;
} mdl_var;

struct mdl_scope {
    mdl_scope *parent;
    mdl_var *vars;
    int n, cap;
};

typedef struct mdl_sub {
    const char *name;
    const mdl_y_node *def; /* its mapping */
    const mdl_y_node *key; /* its name in `subsystems` (position) */
} mdl_sub;

typedef struct mdl_inode mdl_inode;
struct mdl_inode {
    char *name;    /* "rod1", "seg[3]" */
    char *path;    /* "rod1/body" (the bgr path below the model) */
    char *dotpath; /* "rod1.body" (messages, --set) */
    mdl_inode *parent;
    const mdl_y_node *entry; /* its mapping in `components` (the root: the document) */
    const mdl_y_node *key;   /* its name there (position) */
    const mdl_type *type;    /* a library type; NULL: the root or a subsystem instance */
    const mdl_sub *sub;
    mdl_scope loop, scope; /* see above (a leaf uses scope only, holding its loop variable) */
    bgr_comp comp;         /* inner node: its component; leaf: the component it sits in */
    mdl_inode **kids;
    int nkids, capkids;
    mdl_instance inst; /* leaf */
    int state;         /* leaf: 0 not built, 1 being built, 2 built */
};

/* a port bonded: which bond (index into mm->bonds) takes port `port` of leaf */
typedef struct mdl_bond {
    mdl_inode *leaf[2];
    int port[2];
    const mdl_y_node *at;
} mdl_bond;

/* a bond read from the file, joined once both its elements are built (mdl_build.c) */
typedef struct mdl_pending_bond {
    mdl_inode *scope, *leaf[2]; /* leaf: the elements its paths name (NULL: an error later) */
    const mdl_y_node *at, *name;
    char *from, *to;
    int done;
} mdl_pending_bond;

typedef struct mdl_oname {
    char *name;
    int var;      /* >= 0: an unknown */
    int is_t;     /* the time */
    double value; /* a parameter */
} mdl_oname;

typedef struct mdl_output {
    char *name;
    mdl_expr *x;
    const mdl_y_node *node;
} mdl_output;

struct mdl_model {
    char *file, *name;
    mdl_y_doc **docs;
    int ndocs, capdocs;
    char *text; /* the main file's text, for the model as run */
    const mdl_y_node *root;
    mdl_sub *subs;
    int nsubs, capsubs;
    mdl_inode top;
    mdl_set *sets;
    int nsets;
    int *set_used;
    bgr_model *m;
    mdl_solver_settings solver;
    mdl_start start;
    mdl_output *outs;
    int nouts;
    mdl_oname *onames;
    int nonames, caponames;
    int *ohash; /* the names by hash (open addressing, index + 1; 0 empty), nohash slots */
    int nohash;
    mdl_bond *bonds;
    int nbonds, capbonds;
    mdl_pending_bond *pend;
    int npend, cappend;
    mdl_inode **leaves;
    int nleaves, capleaves;
    long ninstances;
    double trim_lo, trim_hi, trim_value, trim_tol; /* trim: (mdl_trim.c) */
    /* the chain of parameters being evaluated (cycle messages) */
    mdl_var *chain[64];
    int nchain;
    bg_error *err;
};

/* ---- mdl_read.c: errors, scopes, evaluation ---- */
/* Records "FILE:LINE:COL: where: message" (at may be NULL: no position) and returns
 * BG_ERR_ARGUMENT. */
int mdl_fail(mdl_model *mm, const mdl_y_node *at, const char *where, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));
/* The nearest of the candidates to name (edit distance), "" if none is near. */
const char *mdl_nearest(const char *name, const char *const *cand, int n);
int mdl_scope_add(mdl_scope *s, const char *name, const mdl_y_node *node, const char *text,
                  mdl_scope *eval);
mdl_var *mdl_scope_find(mdl_scope *s, const char *name, int outward);
void mdl_scope_clear(mdl_scope *s);
/* Evaluates a variable (once; a cycle is an error that lists it). */
int mdl_var_eval(mdl_model *mm, mdl_var *v, const char *where);
/* Evaluates a scalar node or text as a number in scope s. */
int mdl_eval_number(mdl_model *mm, mdl_scope *s, const mdl_y_node *node, const char *text,
                    const char *where, double *value);
/* A scalar or a sequence (or a name of a vector parameter) as a vector: *vec allocated. */
int mdl_eval_vector(mdl_model *mm, mdl_scope *s, const mdl_y_node *node, const char *text,
                    const char *where, double **vec, int *len);
/* A path with index expressions ("seg[k+1].b") with the indices evaluated in s. */
int mdl_eval_path(mdl_model *mm, mdl_scope *s, const mdl_y_node *node, const char *where,
                  char *out, size_t size);
/* Reads `for: {k: [first, last]}`: the variable's name and the range (first > last: none). */
int mdl_read_for(mdl_model *mm, mdl_scope *s, const mdl_y_node *forn, const char *where,
                 const char **var, long *first, long *last);
/* A mapping's keys against the allowed ones: an unknown key is an error naming the nearest. */
int mdl_check_keys(mdl_model *mm, const mdl_y_node *map, const char *where,
                   const char *const *allowed, int nallowed);

/* ---- mdl_tree.c: the document, includes and the instance tree ---- */
int mdl_read_document(mdl_model *mm, const char *path, const char *text);
int mdl_expand(mdl_model *mm);
/* The leaf (or inner node, rest NULL) a path names, walking from node; *rest gets the part after
 * a leaf ("a" of "rod1.body.a"), NULL when the path ends at the node. */
int mdl_resolve(mdl_model *mm, mdl_inode *from, const char *path, const mdl_y_node *at,
                const char *where, mdl_inode **leaf, const char **rest);
void mdl_tree_free(mdl_model *mm);

/* ---- mdl_build.c: elements, bonds, compilation ---- */
int mdl_build_all(mdl_model *mm);

/* ---- mdl_start.c: start configuration, initial values, outputs, settings ---- */
int mdl_place_all(mdl_model *mm);
/* The position at state y of what port `port` of leaf is bonded to (through joints). */
int mdl_neighbour_position(const mdl_model *mm, const mdl_inode *leaf, int port, const double *y,
                           double x[3]);
int mdl_read_initial(mdl_model *mm);
int mdl_read_outputs(mdl_model *mm);
int mdl_read_solver(mdl_model *mm);

/* ---- mdl_trim.c ---- */
int mdl_read_trim(mdl_model *mm);

#endif
