/* The standard bond-graph elements' shared parts (bgr_elements.h for the elements): their
 * parameters, the binding of their variable ids, the declaration of their equations, their
 * addition to a model and the checks of their dimensions. Private to the element files: not
 * installed.
 *
 *   bgr_elements.c            these shared parts and the signal gain
 *   bgr_elements_storage.c    the storage and resistive elements I, C, R
 *   bgr_elements_sources.c    the sources Se, Sf
 *   bgr_elements_junctions.c  the transformer TF, the gyrator GY, the 0- and 1-junctions
 *
 * Each class declares its equations and partial derivatives once; residual and Jacobian then
 * only read the unknowns through the variable ids fixed at compilation (bgr_el_bind). */
#ifndef BGR_ELEMENTS_IMPL_H
#define BGR_ELEMENTS_IMPL_H

#include <stddef.h>

#include "bgr_elements.h"

typedef enum law {
    LAW_LINEAR, /* scalar coefficient k */
    LAW_MATRIX, /* d x d matrix */
    LAW_FN,     /* scalar function with derivative */
    LAW_CONST,  /* constant vector */
    LAW_TIME,   /* scalar function of t */
    LAW_SIGNAL  /* another unknown */
} law;

typedef struct par {
    int d;
    law kind;
    double k;
    double *vec; /* LAW_MATRIX: d*d; LAW_CONST: d */
    bgr_fn fn;
    bgr_time_fn tfn;
    void *user;
    bgr_ref ref;
    int refvar; /* resolved at declaration */
    /* variable ids, filled at declaration: ports' e and f, states, own unknowns */
    int *e, *f; /* nports*d each, port-major */
    int *x;     /* states or own unknowns */
    int *s;     /* orientation per port */
    int nports;
} par;

/* Frees a par (the classes' destroy). */
void bgr_el_par_free(void *p);
/* A par of dimension d, law kind, coefficient k; NULL when out of memory. */
par *bgr_el_par_new(int d, law kind, double k);
/* A par of dimension 1 that reads the unknown r (LAW_SIGNAL); NULL when out of memory. */
par *bgr_el_par_signal(bgr_ref r);
/* Resolves the element's variable ids into its parameters. */
int bgr_el_bind(bgr_element *el, bgr_model *m);
/* Declares neq equations labelled prefix0, prefix1, ... in groups of d (label(k) chooses). */
int bgr_el_declare_eqs(bgr_element *el, bgr_model *m, int neq,
                       const char *(*label)(int k, int d, int np), int d);
/* Adds the element (nports ports of dimension q->d) to m: its id, or an error status. */
int bgr_el_add(bgr_model *m, bgr_comp c, const char *name, const bgr_element_class *cls, par *q,
               int nports, int nstates, const char *const *snames, int nalg,
               const char *const *anames);
/* BG_ERR_ARGUMENT with a message naming the element unless 1 <= d <= max. */
int bgr_el_check_d(bgr_model *m, bgr_comp c, const char *name, const char *where, int d, int max);
/* BG_ERR_ARGUMENT with a message if something the element needs is not given (a NULL pointer). */
int bgr_el_check_given(bgr_model *m, bgr_comp c, const char *name, const char *where, int given,
                       const char *what);
/* The name of variable v into buf ("?" if none). */
void bgr_el_vname(const bgr_model *m, int v, char *buf, size_t n);

/* Declares the dependence of equation k on variable v (weight w) in a declare function (el, m
 * in scope); returns from it on an error. */
#define DEP(k, v, w)                                                                               \
    do {                                                                                           \
        int st_ = bgr_declare_dep(el, m, (k), (v), (w));                                           \
        if (st_ != BG_OK) return st_;                                                              \
    } while (0)

/* No limit on the dimension beyond the memory (I and C: 16, the names of their states). */
#define D_ANY 1000000

#endif
