/* Private to the model reader and the type table: the records behind mdl_args, mdl_instance and
 * mdl_locator, and what build(), place() and port_position() of a type (mdl_types.h) use to read
 * their arguments and to state what an instance offers. */
#ifndef MDL_IMPL_H
#define MDL_IMPL_H

#include "mdl_types.h"

/* One evaluated parameter. */
typedef struct mdl_value {
    const mdl_param_def *def;
    int has;     /* given, or defaulted */
    double num;  /* MDL_NUMBER, MDL_INTEGER, MDL_FLAG */
    double *vec; /* MDL_VECTOR (owned) */
    int len;
    char *word; /* MDL_CHOICE (owned) */
    int elem;   /* MDL_ELEMENT: the main element of the referenced instance */
    bgr_ref sig;
    int npts; /* MDL_POINTS: names (owned), r (3 each), dims; MDL_NAMES: the names only */
    char **pname;
    double *pr;
    int *pdim;
} mdl_value;

struct mdl_args {
    const mdl_type *type;
    const char *path;
    mdl_value *v; /* one per parameter of the type, in the type's order */
};

typedef struct mdl_iport {
    char *name;
    bgr_port p;
    int dim;
    mdl_domain domain;
} mdl_iport;

typedef struct mdl_isignal {
    char *name;
    bgr_ref r;
} mdl_isignal;

struct mdl_instance {
    const mdl_type *type;
    char *path; /* "rod1/body" */
    int main;
    int *elems, nelems, capelems;
    mdl_iport *ports;
    int nports, capports;
    mdl_isignal *sigs;
    int nsigs, capsigs;
    mdl_args args;
    int placed;
};

/* The locator hands place() the positions at the neighbours (mdl_place.c). */
struct mdl_locator {
    void *ctx; /* the reader's placement state */
    const mdl_instance *self;
    int (*locate)(void *ctx, const mdl_instance *self, int port, double x[3]);
};

/* ---- for build() and place(): reading the arguments ---- */
/* Whether the parameter was given or has a default (0 for a left-out MDL_OPTIONAL one). */
int mdl_arg_has(const mdl_args *a, const char *name);
double mdl_arg_num(const mdl_args *a, const char *name);   /* MDL_NUMBER */
int mdl_arg_int(const mdl_args *a, const char *name);      /* MDL_INTEGER */
int mdl_arg_flag(const mdl_args *a, const char *name);     /* MDL_FLAG */
/* MDL_VECTOR: the entries (len of them into *len if len not NULL); NULL if absent. */
const double *mdl_arg_vec(const mdl_args *a, const char *name, int *len);
const char *mdl_arg_choice(const mdl_args *a, const char *name); /* MDL_CHOICE */
/* MDL_ELEMENT: the element id of the referenced instance's main element (-1 if absent). */
int mdl_arg_element(const mdl_args *a, const char *name);
/* MDL_SIGNAL: the unknown (bgr_ref) of the referenced signal ({BGR_OWN, -1, 0} if absent). */
bgr_ref mdl_arg_signal(const mdl_args *a, const char *name);
/* MDL_POINTS: how many points, and point i's name, position r[3] and dimension; MDL_NODE_PORTS:
 * the same with the node's index in r[0]. */
int mdl_arg_npoints(const mdl_args *a, const char *name);
const char *mdl_arg_point(const mdl_args *a, const char *name, int i, double r[3], int *dim);
/* MDL_NAMES: the names (how many into *n if n not NULL); NULL if absent. */
const char *const *mdl_arg_names(const mdl_args *a, const char *name, int *n);
/* The instance's path ("boom/element03"), for messages. */
const char *mdl_arg_path(const mdl_args *a);

/* ---- for build(): what the instance offers ---- */
/* A port named name: an element's port, its dimension and domain. BG_OK, BG_ERR_ARGUMENT (a
 * duplicate name), BG_ERR_MEMORY. */
int mdl_instance_port(mdl_instance *in, const char *name, bgr_port p, int dim, mdl_domain domain);
/* A signal named name: the unknown it is. */
int mdl_instance_signal(mdl_instance *in, const char *name, bgr_ref r);
/* The main element (what an MDL_ELEMENT parameter elsewhere resolves to; a body, an inertia);
 * also recorded as the instance's first element. */
int mdl_instance_element(mdl_instance *in, int elem);
/* Further elements the instance made (for energies, ParaView): stored in order. */
int mdl_instance_add(mdl_instance *in, int elem);
/* Reading them back. */
int mdl_instance_main(const mdl_instance *in);
int mdl_instance_nelements(const mdl_instance *in);
int mdl_instance_elem(const mdl_instance *in, int i);
int mdl_instance_nports(const mdl_instance *in);
const char *mdl_instance_port_name(const mdl_instance *in, int i);
int mdl_instance_find_port(const mdl_instance *in, const char *name);
const mdl_iport *mdl_instance_port_at(const mdl_instance *in, int i);
const mdl_isignal *mdl_instance_find_signal(const mdl_instance *in, const char *name);
void mdl_instance_clear(mdl_instance *in);

/* ---- for place(): positions at the neighbours ---- */
/* The world position at the start of what port `port` of the instance is bonded to (through
 * joints); BG_OK, MDL_NOT_YET (not placed yet), BG_ERR_ARGUMENT (no such port, unconnected). */
int mdl_locate(mdl_locator *loc, int port, double x[3]);

/* ---- for place(): sources ---- */
/* What a source imposes: the efforts at its port 0, the flows there, its own signal. */
typedef enum mdl_source_output { MDL_SRC_EFFORT, MDL_SRC_FLOW, MDL_SRC_SIGNAL } mdl_source_output;
/* The start of source element elem: its own equations made to hold at t = 0 (a general rule:
 * the assembled start satisfies the sources' equations, so a static solve's load homotopy does
 * not ramp a supply pressure or a reference). Equation i is solved for the i-th unknown of
 * `what` (the element's equations are linear in them with a nonzero coefficient: a value
 * against what it imposes); nothing else moves. follows: the signal a signal-driven source
 * reads (NULL: none): a signal source (sig.*) there is set to its own start first, any other
 * signal is taken at its start value as assembled. BG_OK or BG_ERR_ARGUMENT with the message. */
int mdl_place_source(bgr_model *m, int elem, mdl_source_output what, const bgr_ref *follows,
                     bg_error *err);

/* ---- the type table's parts (mdl_types_*.c) ---- */
extern const mdl_type *const mdl_types_mech[];
extern const int mdl_types_mech_count;
extern const mdl_type *const mdl_types_hyd[];
extern const int mdl_types_hyd_count;
extern const mdl_type *const mdl_types_rot[];
extern const int mdl_types_rot_count;
extern const mdl_type *const mdl_types_ctl[];
extern const int mdl_types_ctl_count;
extern const mdl_type *const mdl_types_beam[];
extern const int mdl_types_beam_count;
extern const mdl_type *const mdl_types_drive[];
extern const int mdl_types_drive_count;
extern const mdl_type *const mdl_types_bg[];
extern const int mdl_types_bg_count;

/* Builders' common failure: the message of the model's error record into err. */
int mdl_fail_model(bg_error *err, bgr_model *m, int status);

#endif
