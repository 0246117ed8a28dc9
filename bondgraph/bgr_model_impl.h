/* The bond-graph model's records, shared by bgr_model.c (building), bgr_compile.c (compilation)
 * and bgr_eval.c (evaluation, statistics, check). Private: not installed. */
#ifndef BGR_MODEL_IMPL_H
#define BGR_MODEL_IMPL_H

#include "bgr_model.h"

typedef struct comp_rec {
    char *name, *path;
    int parent;
} comp_rec;

typedef struct export_rec {
    int comp;
    char *name;
    bgr_port port;
} export_rec;

typedef struct bond_rec {
    char *name;
    int comp, d, var0;
    bgr_port a, b;
    char **elab, **flab;
} bond_rec;

typedef struct dep_rec {
    int eq, var, wrt_yp;
} dep_rec;

struct bgr_model {
    bg_error err;
    comp_rec *comp;
    int ncomp, capcomp;
    export_rec *exp;
    int nexp, capexp;
    bgr_element **el;
    int nel, capel;
    bond_rec *bond;
    int nbond, capbond;
    char **state_names, **alg_names; /* per element, flattened later */
    /* compiled */
    int compiled, n, neq_declared;
    int compiling; /* inside the declare() hooks of bgr_compile */
    char **vname, **ename;
    int *eq_owner;
    int *kind, *declared_i2;
    double *y0, *yp0;
    double *nominal; /* nominal magnitudes: 0 while undeclared during compilation, then 1 */
    dep_rec *dep;
    int ndep, capdep;
    sp_csc *Jy, *Jyp;
    int *slot;
    double *vals;
    /* per element own unknown names (kept until compile) */
    char ***el_state_names, ***el_alg_names;
    /* position invariants (bgr_invariant.c) */
    int ninv, capinv;
    char **iname;
    dep_rec *idep; /* eq: the invariant's row */
    int nidep, capidep;
    sp_csc *G;
    int *islot;
    double *ivals;
    /* kinds of unknowns under a frame's motion (bgr_declare_frame): groups of kind and up to
     * four unknowns, and each unknown's group + 1 (0: none; NULL until the first declaration) */
    int (*fgroup)[5];
    int nfgroup, capfgroup;
    int *fkind;
    /* for the Jacobian check */
    double ck_t;
    const double *ck_y, *ck_yp;
};

/* Records the error in the model's record (m may be NULL) and returns status. */
int bgri_fail(bgr_model *m, int status, const char *where, const char *fmt, ...);
/* The same for queries that take the model const: the error record is the only thing they
 * write (the model is always allocated by bgr_model_create, never a const object). */
int bgri_fail_c(const bgr_model *m, int status, const char *where, const char *fmt, ...);
/* BG_OK if the model is compiled, else BG_ERR_STATE with a message. */
int bgri_need_compiled(const bgr_model *m, const char *where);
/* The checks of the bgr_declare_* functions (bgr_model.c). */
int bgri_check_declare(const bgr_element *el, bgr_model *m, const char *what);
/* a "/" b, or b when a is empty (malloc'd; NULL when out of memory). */
char *bgri_join(const char *a, const char *b);
/* "component/element port k" of a port, into buf, for messages. */
const char *bgri_port_desc(const bgr_model *m, bgr_port p, char *buf, size_t size);
/* Full path of an element (malloc'd; NULL when out of memory). */
char *bgri_elem_path(const bgr_model *m, const bgr_element *el);
/* Invariants (bgr_invariant.c): after the declare() hooks, the pattern of their gradient and its
 * slots; and their records freed. */
int bgri_invariants_finish(bgr_model *m);
void bgri_invariants_free(bgr_model *m);

#endif
