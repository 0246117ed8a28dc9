/* The table of the library's element and component types, as model files name them.
 *
 * Every type a model file can use is registered once here: its name ("hyd.volume"), a summary,
 * its equations as text, its parameters (name, kind, SI unit, default, range, meaning), its ports
 * (name, dimension, domain), the signals it offers to other elements and the function that builds
 * it in a bgr_model. The model reader (mdl_model.h), its checks, `bgsim --list-types`,
 * `bgsim --describe TYPE` and docs/model-types.md all read this table; a test regenerates the
 * page and fails when it and the table disagree.
 *
 * Domains of ports (what a bond between two ports must agree on besides the dimension):
 *   mechanical 6D   velocity and angular velocity / force and moment (the conventions of
 *                   mech_body.h: global frame, the moment about the port's point)
 *   mechanical 3D   velocity / force (a point: rope ends, point masses)
 *   hydraulic       volume flow (m^3/s) / pressure (Pa)
 *   rotational      angular velocity (rad/s) / torque (N m): shafts, gears, drives
 *   generic         any: the bond-graph elements (I, C, R, Se, Sf, TF, GY, junctions), which take
 *                   the domain of what they are bonded to (checked for consistency)
 * Signals are not ports: an element offers named signals (its own algebraic unknowns or states:
 * a sensor's measured rate, a controller's output, a source's value); another element reads one
 * through a parameter of kind MDL_SIGNAL holding its path ("sensor.omega").
 *
 * Start configuration. Mechanical elements need a consistent initial geometry. A type may give
 *   place(): its states from its own parameters (a body's position and orientation, a chain's
 *            end points), and port_position(): the world position of one of its ports at a state;
 * elements whose states follow from their neighbours (an axial element's vector from A to B, a
 * point mass sitting at what it is bonded to) give place() and ask mdl_locate() for the position
 * at a port. The reader calls place() in rounds until every element is placed or no round
 * progresses (then it names the elements that could not be placed). Joints pass positions
 * through (MDL_PASS_POSITION): the position at one port is that of the neighbour at the other.
 *
 * The table is static and read-only: no registration at run time, no global mutable state. */
#ifndef MDL_TYPES_H
#define MDL_TYPES_H

#include "bg_api.h"
#include "bgr_model.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum mdl_kind {
    MDL_NUMBER,  /* a real number (an expression of parameters) */
    MDL_INTEGER, /* a whole number (an expression whose value is an integer) */
    MDL_FLAG,    /* true or false */
    MDL_VECTOR,  /* a list of numbers (expressions), len of them (len 0: one or more) */
    MDL_CHOICE,  /* one word of choices ("value|rate|integral") */
    MDL_ELEMENT, /* the path of another element of the model (the body that carries an axis) */
    MDL_SIGNAL,  /* the path of a signal another element offers ("platform_sensor.omega") */
    MDL_POINTS,  /* a mapping name -> {r: [x, y, z], dim: 3 or 6}: named attachment points, each a
                  * port of the element (a body's points in its own frame) */
    MDL_NAMES,   /* a list of distinct words ([a, b, c]): the names of the element's ports (a
                  * volume's, a junction's), at least one */
    MDL_NODE_PORTS /* a mapping name -> {node: k, dim: 6 or 3}: named ports at nodes of a chain
                    * (k from 0), each a port of the element */
} mdl_kind;

typedef enum mdl_domain {
    MDL_GENERIC = 0,
    MDL_MECH6,
    MDL_MECH3,
    MDL_HYDRAULIC,
    MDL_ROTATIONAL
} mdl_domain;

/* flags of a parameter */
enum {
    MDL_LO_OPEN = 1,  /* lo itself excluded */
    MDL_HI_OPEN = 2,  /* hi itself excluded */
    MDL_OPTIONAL = 4, /* may be left out and has no default (the type then does without) */
    MDL_FINITE = 8    /* only the finiteness is checked (lo, hi unused) */
};

typedef struct mdl_param_def {
    const char *name;
    mdl_kind kind;
    int len;             /* MDL_VECTOR: the number of entries (0: one or more) */
    const char *unit;    /* SI unit ("m", "Pa", "m^3/(s Pa)"; "1": a pure number) */
    const char *dflt;    /* the default as a model file would write it; NULL: required (or
                          * MDL_OPTIONAL) */
    double lo, hi;       /* range of the number, the integer or each vector entry */
    unsigned flags;      /* MDL_LO_OPEN, MDL_HI_OPEN, MDL_OPTIONAL, MDL_FINITE */
    const char *choices; /* MDL_CHOICE: the words, separated by '|' */
    const char *meaning;
} mdl_param_def;

typedef struct mdl_port_def {
    const char *name; /* a fixed port name; "*" : the ports are named by a parameter (a volume's
                       * `ports` list, a body's `points`, a junction's `ports`) */
    int dim;          /* 1, 3 or 6; 0: the parameter `dim` gives it */
    mdl_domain domain;
    const char *meaning;
} mdl_port_def;

typedef struct mdl_signal_def {
    const char *name;
    const char *unit;
    const char *meaning;
} mdl_signal_def;

/* The evaluated parameters of one instance, handed to build() and place(). */
typedef struct mdl_args mdl_args;
/* What an instance offers the rest of the model: its ports, signals and main element. */
typedef struct mdl_instance mdl_instance;
/* The start configuration's positions (see place()). */
typedef struct mdl_locator mdl_locator;

enum { MDL_PASS_POSITION = 1 /* a joint: positions pass through from one port to the other */ };

typedef struct mdl_type {
    const char *name;      /* "mech.body", "hyd.volume" */
    const char *summary;   /* one line */
    const char *equations; /* the equations the type contributes, as text (several lines) */
    const mdl_param_def *params;
    int nparams;
    const mdl_port_def *ports;
    int nports;
    const mdl_signal_def *signals;
    int nsignals;
    unsigned flags; /* MDL_PASS_POSITION */
    /* Adds the element(s) named name in component c and records ports, signals and the main
     * element into out (mdl_instance_*). BG_OK or a status with the message in err (the reader
     * adds the file position and the path). */
    int (*build)(bgr_model *m, bgr_comp c, const char *name, const mdl_args *a, mdl_instance *out,
                 bg_error *err);
    /* Optional: sets the instance's initial states after compilation. Returns BG_OK (placed),
     * MDL_NOT_YET (a position it needs is not known yet: asked again next round) or an error. */
    int (*place)(bgr_model *m, const mdl_instance *in, const mdl_args *a, mdl_locator *loc,
                 bg_error *err);
    /* Optional: the world position of port `port` (its index in the instance) at state y.
     * BG_OK or MDL_NOT_YET. */
    int (*port_position)(const bgr_model *m, const mdl_instance *in, int port, const double *y,
                         double x[3]);
} mdl_type;

enum { MDL_NOT_YET = 1 };

/* ---- the table ---- */
BG_API int mdl_type_count(void);
BG_API const mdl_type *mdl_type_at(int i);
/* The type named name, NULL if there is none. */
BG_API const mdl_type *mdl_type_find(const char *name);
/* The parameter of t named name, NULL if there is none. */
BG_API const mdl_param_def *mdl_type_param(const mdl_type *t, const char *name);
/* The type's description as Markdown (the section of docs/model-types.md) or as plain text
 * (bgsim --describe), written to f. BG_OK or BG_ERR_IO. */
BG_API int mdl_type_describe(const mdl_type *t, int markdown, FILE *f);
/* The whole reference (docs/model-types.md). */
BG_API int mdl_types_markdown(FILE *f);

#ifdef __cplusplus
}
#endif
#endif
