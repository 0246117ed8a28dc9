/* Acausal bond graphs compiled into a semi-explicit DAE F(t, y, y') = 0 for bg_dae.
 *
 * A model holds components (name spaces, nested to any depth), elements and bonds. A bond joins
 * two ports and carries an effort vector e and a flow vector f of dimension d >= 1; its power
 * e.f flows from the port it starts at to the port it ends at (the half arrow). No causality is
 * assigned: every element states its constitutive equations, one equation per port component
 * and one per state of its own, so the compiled system is square. Signals (information only, no
 * power) are plain unknowns that one element defines and others read.
 *
 * Unknowns: the e and f of every bond (algebraic), the states of the elements (momenta,
 * displacements: differential), signals (algebraic). Which algebraic unknowns are index 2
 * (constraint efforts and whatever depends on them) is found from the structure by dae_classify;
 * an element may also declare an unknown index 2 itself.
 *
 * Compilation numbers unknowns and equations, gives each a hierarchical name
 * (rig/beam/element07/node_b/vy), builds the patterns of dF/dy and dF/dy' once from the
 * dependencies the elements declare, and assigns every declared partial derivative a fixed slot.
 * The residual and Jacobian callbacks then loop over the elements and scatter: no allocation and
 * no finite differences on that path.
 *
 * Writing an element: fill a bgr_element_class (bgr_elements.h has the standard ones). Its
 * declare() states the equations and, for each equation, the unknowns it depends on (y or y');
 * residual() writes the element's equations; jacobian() writes the partial derivatives in the
 * order they were declared. Elements reach their unknowns through bgr_ev/bgr_fv (port effort and
 * flow components), bgr_sv (states) and the variable ids they keep.
 *
 * Errors. Functions that return a status return BG_OK or a negative bg_status code with the
 * message in bgr_model_error(m) (also for queries that take the model const: the error record is
 * the one thing they write). A NULL model gives BG_ERR_ARGUMENT (no message), or NULL, -1, 0 or an
 * invalid port from the functions that return those, as stated below; a NULL name, array or
 * function the call needs, or an id or size out of range, gives BG_ERR_ARGUMENT. The model has
 * three states: building (components, elements, bonds, exports may be added), compiled (the
 * queries, the residual and the solver problem), and failed (a compilation that failed: only
 * freeing). A call in the wrong state gives BG_ERR_STATE: adding to a model that is compiled or
 * whose compilation failed, compiling twice, asking a model that is not compiled for its problem,
 * statistics, listing, residual, Jacobian or Jacobian check, and the bgr_declare_* functions
 * outside an element's declare() during bgr_compile. bgr_model_free(NULL) is harmless. */
#ifndef BGR_MODEL_H
#define BGR_MODEL_H

#include <stddef.h>
#include <stdio.h>

#include "bg_api.h"
#include "bg_dae.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct bgr_model bgr_model;
typedef struct bgr_element bgr_element;

/* Handles are small integers, valid for the model that issued them; negative means failure. */
typedef int bgr_comp; /* component (0 = the root) */
typedef struct bgr_port {
    int elem, port; /* elem < 0: invalid */
} bgr_port;

/* The interface an element type implements. */
typedef struct bgr_element_class {
    const char *type; /* "I", "C", "R", "Se", ... */
    /* Declare equations and dependencies with bgr_declare_*; return 0 or a BG_ERR_* code
     * (message through bgr_model_error). Called by bgr_compile once bonds are numbered. */
    int (*declare)(bgr_element *el, bgr_model *m);
    /* F[k] for the element's equations k = 0 .. neq-1 (F points at its first equation). */
    int (*residual)(const bgr_element *el, double t, const double *y, const double *yp, double *F);
    /* Partial derivatives in declaration order into v. */
    int (*jacobian)(const bgr_element *el, double t, const double *y, const double *yp, double *v);
    /* Optional: the text of equation k with variable names (for listings). */
    void (*describe)(const bgr_element *el, const bgr_model *m, int k, char *buf, size_t size);
    void (*destroy)(void *params); /* frees params (may be NULL) */
    /* Optional: times in (t0, t1] where the element's equations are not smooth in t (corners of
     * a reference profile, steps); writes at most max of them into t, returns how many there are
     * (may exceed max). bgr_breakpoints collects them for the solver. */
    int (*breakpoints)(const bgr_element *el, double t0, double t1, double *t, int max);
    /* Optional: the branch of a sharp but smooth characteristic the element is on at y, a small
     * integer (cmp_regime in components/cmp_internal.h: 0 off, 1 nearly off, 2 between, 3 on,
     * from the slope of its smooth switch). bgr_regimes collects them; the solver evaluates a
     * fresh Jacobian when one changes (bg_dae.h, dae_problem.regimes). */
    int (*regime)(const bgr_element *el, const double *y);
    /* Optional: the element's position invariants (declared in declare() with
     * bgr_declare_invariants): their values g(t, y) into g and, when dg is not NULL, their
     * partial derivatives with respect to the unknowns declared by bgr_declare_invariant_dep, in
     * declaration order, into dg. Returns 0, or a status (nonzero: the solver stops with
     * DAE_CALLBACK_FAIL). See "Position invariants" below. */
    int (*invariant)(const bgr_element *el, double t, const double *y, double *g, double *dg);
} bgr_element_class;

/* Orientation of a bond at a port, as the element sees it. */
enum { BGR_IN = 1, BGR_OUT = -1 };

struct bgr_element {
    const bgr_element_class *cls;
    void *params; /* owned, freed by cls->destroy */
    int id, comp;
    int nports;
    int *bond;           /* bond at each port (-1: unconnected) */
    int *sign;           /* BGR_IN if the bond ends here, BGR_OUT if it starts */
    int *dim;            /* required dimension of each port (0: any) */
    int nstates, state0; /* own differential unknowns */
    int nalg, alg0;      /* own algebraic unknowns (signals, multipliers) */
    int neq, eq0;        /* equations, first global row */
    int ndep, dep0;      /* declared partial derivatives, first slot index */
    char *name;
    int ninv, inv0;   /* position invariants, first row (bgr_declare_invariants) */
    int nidep, idep0; /* their declared partial derivatives, first slot */
};

/* ---- building ---- */
/* A new model named name (NULL or "": "model"); NULL if out of memory. */
BG_API bgr_model *bgr_model_create(const char *name);
BG_API void bgr_model_free(bgr_model **m);
/* Last error (file-free: the message names the component, element, bond or port); NULL if m is
 * NULL. */
BG_API const bg_error *bgr_model_error(const bgr_model *m);
BG_API bg_error *bgr_model_error_mut(bgr_model *m);

/* A component named name inside parent (0 = the model itself). Names are unique among the
 * siblings and may not contain '/'. Returns the component (> 0), BG_ERR_ARGUMENT (bad name or
 * parent, a duplicate), BG_ERR_STATE (model compiled) or BG_ERR_MEMORY. */
BG_API bgr_comp bgr_component(bgr_model *m, bgr_comp parent, const char *name);
/* Full path of a component, e.g. "rig/beam/element07"; NULL for an unknown one. */
BG_API const char *bgr_component_path(const bgr_model *m, bgr_comp c);

/* An element of class cls in component c. params is owned by the element from here on (freed by
 * cls->destroy, also on failure). nports ports; dims[k] the dimension port k needs (0: any;
 * dims NULL: all any). nstates differential and nalg algebraic unknowns of its own, with names
 * (suffixes under the element's path; NULL: "x0", "x1", ...). Returns the element id, or
 * BG_ERR_ARGUMENT (NULL model or name, a name with '/', a duplicate, an unknown component, an
 * incomplete class, a negative count or dimension), BG_ERR_STATE (model compiled) or
 * BG_ERR_MEMORY; params are destroyed on every failure. */
BG_API int bgr_element_add(bgr_model *m, bgr_comp c, const char *name, const bgr_element_class *cls,
                           void *params, int nports, const int *dims, int nstates,
                           const char *const *state_names, int nalg, const char *const *alg_names);
/* Port port of element elem; {-1, -1} if either does not exist. */
BG_API bgr_port bgr_port_of(const bgr_model *m, int elem, int port);
/* The element, NULL if it does not exist. */
BG_API bgr_element *bgr_element_get(bgr_model *m, int elem);

/* Expose an inner port as a named port of component c (any depth); bgr_comp_port finds it.
 * BG_OK, BG_ERR_ARGUMENT (invalid component, name or port, a duplicate), BG_ERR_STATE (model
 * compiled) or BG_ERR_MEMORY. */
BG_API int bgr_export(bgr_model *m, bgr_comp c, const char *name, bgr_port inner);
/* The port exported as name from c; {-1, -1} if there is none. */
BG_API bgr_port bgr_comp_port(const bgr_model *m, bgr_comp c, const char *name);

/* A bond of dimension d from port a to port b (power a -> b), named in component c.
 * labels: d names for the effort components and d for the flow components (NULL: "e", "f" for
 * d = 1, "e0".."e{d-1}", "f0".. otherwise). Returns the bond id, or BG_ERR_ARGUMENT (port
 * already used, dimension mismatch, invalid port or name, a duplicate), BG_ERR_STATE (model
 * compiled) or BG_ERR_MEMORY. */
BG_API int bgr_bond(bgr_model *m, bgr_comp c, const char *name, int d, bgr_port a, bgr_port b,
                    const char *const *effort_labels, const char *const *flow_labels);

/* A reference to an unknown that is numbered only at compilation: a component of a bond's
 * effort or flow, or an element's state or own algebraic unknown (a signal). */
typedef enum bgr_ref_type { BGR_EFFORT, BGR_FLOW, BGR_STATE, BGR_OWN } bgr_ref_type;
typedef struct bgr_ref {
    bgr_ref_type type;
    int id; /* bond id (BGR_EFFORT, BGR_FLOW) or element id (BGR_STATE, BGR_OWN) */
    int i;  /* component */
} bgr_ref;
/* The variable id of a reference (from the numbering step of bgr_compile on), or -1 (not
 * numbered yet, no such unknown, or m NULL). */
BG_API int bgr_ref_var(const bgr_model *m, bgr_ref r);

/* Initial values for the solver (defaults 0): by variable id after compilation, or by name.
 * The id of the unknown / equation with this path, -1 if there is none or the model is not
 * compiled. */
BG_API int bgr_find_var(const bgr_model *m, const char *path);
BG_API int bgr_find_eq(const bgr_model *m, const char *path);

/* ---- used by element classes (inside declare/residual/jacobian) ---- */
/* Variable ids of effort / flow component i at port k, of state i, of own algebraic i; -1 for
 * an element or port that does not exist, an unconnected port, a component out of range, or
 * before the unknowns are numbered (bgr_sv, bgr_av: -1 only for el NULL). */
BG_API int bgr_ev(const bgr_element *el, const bgr_model *m, int k, int i);
BG_API int bgr_fv(const bgr_element *el, const bgr_model *m, int k, int i);
static inline int bgr_sv(const bgr_element *el, int i)
{
    return el ? el->state0 + i : -1;
}
static inline int bgr_av(const bgr_element *el, int i)
{
    return el ? el->alg0 + i : -1;
}
/* Dimension of port k (of its bond, else the one required, 0: any); BG_ERR_ARGUMENT for a NULL
 * argument or k out of range. */
BG_API int bgr_port_dim(const bgr_element *el, const bgr_model *m, int k);
/* Number of unknowns, from the numbering step of bgr_compile on (0 before, or m NULL). */
BG_API int bgr_nvars(const bgr_model *m);
/* Declare: the element has neq equations (labels: suffixes of their names; NULL: "eq0", ...).
 * The bgr_declare_* functions return BG_OK, BG_ERR_ARGUMENT (an element of another model, an
 * equation or variable out of range, neq < 0), BG_ERR_PATTERN (more equations than unknowns),
 * BG_ERR_STATE (called outside declare() during bgr_compile) or BG_ERR_MEMORY. */
BG_API int bgr_declare_equations(bgr_element *el, bgr_model *m, int neq, const char *const *labels);
/* Declare that equation k depends on variable var through y (wrt_yp = 0) or y' (1). The order
 * of these calls is the order jacobian() writes its values in. */
BG_API int bgr_declare_dep(bgr_element *el, bgr_model *m, int k, int var, int wrt_yp);
/* Declare one of the element's own algebraic unknowns index 2 (a constraint effort). */
BG_API int bgr_declare_index2(bgr_element *el, bgr_model *m, int var);
/* Declare the nominal magnitude of unknown var (any unknown of the model: a bond's effort or
 * flow at one of the element's ports, a state, a signal), in its own units: the size it takes in
 * the model's normal operation, from the element's parameters (a relief valve's full-flow
 * pressure, a load's weight, a member's length). The solver's absolute tolerance of the unknown
 * is then options.atol * nominal (dae_problem.nominal, the convention of Modelica tools): in the
 * local error test and in the Newton convergence test alike, so that one atol means the same for
 * a pressure of 1e7 Pa, a force of 1e5 N and an angle of 1 rad. With rtol = atol = 1e-6 every
 * unknown is then controlled to about a millionth of its own size, |y| or its nominal, whichever
 * is larger (error weight rtol |y_i| + atol nominal_i), instead of to 1e-6 in SI units, which is
 * no error at all for a pressure and a sizeable one for a strain. Several declarations of one
 * unknown (a bond's effort seen from both of its ends): the largest wins; an unknown no element
 * declares gets 1 (SI units). BG_ERR_ARGUMENT (besides the errors above) if nominal is not
 * finite and > 0, with a message that names the element and the unknown. Elements without a
 * physical scale declare nothing. */
BG_API int bgr_declare_nominal(bgr_element *el, bgr_model *m, int var, double nominal);

/* Position invariants. An element whose equations hold a quantity only through its rate (a
 * drive that prescribes a joint's rate so that its angle follows a profile, a constraint written
 * on velocities) may state the position-level relation as an invariant g(t, y) = 0 with its
 * gradient G = dg/dy. bgr_dae_problem passes the model's invariants to the solver as its
 * position constraints (dae_problem.ncons, cons, cons_pattern): the solver records their largest
 * value after each step (dae_stats.max_drift) and, with dae_options.projection = 1, projects
 * every accepted step and every interpolated output back onto g = 0 by the minimum-norm
 * Gauss-Newton correction y -= G^T (G G^T)^-1 g (dae_out.c). This is the coordinate projection
 * of Hairer, Lubich and Roche (The Numerical Solution of Differential-Algebraic Systems by
 * Runge-Kutta Methods, Springer LNM 1409, 1989) and of Eich (SIAM J. Numer. Anal. 30 (1993)
 * 1467-1482), who shows that BDF on the index-2 (velocity-level) formulation followed by the
 * projection onto the position constraints keeps the order of the method and removes the drift
 * of the positions. The alternative, the stabilised index-2 formulation of Gear, Gupta and
 * Leimkuhler (J. Comput. Appl. Math. 12/13 (1985) 77-90), holds both levels by a second
 * multiplier mu in the kinematic equations (q' = ... - G^T mu): those are other elements'
 * equations (a body's), which an element of this layer cannot write into; the projection needs
 * nothing of them and costs one factorisation of G G^T (of the invariants' size) per step.
 * bgr_static keeps the invariants at their values at its start. The
 * invariants are not equations of the DAE: the system stays square and of index 2, and
 * dae_options.index2 = DAE_I2_REDUCE (which projects onto constraints of its own) refuses a
 * problem that has them (set dae_problem.ncons = 0 there to go without them).
 * The gradient an element declares is that with respect to the coordinates the projection may
 * move (orientations, positions): the solver corrects those only.
 *
 * In declare(): ninv invariants, labelled (suffixes of their names; NULL: "inv0", ...). Statuses
 * as for bgr_declare_equations; BG_ERR_ARGUMENT when the class has no invariant() hook or the
 * element declares its invariants twice. */
BG_API int bgr_declare_invariants(bgr_element *el, bgr_model *m, int ninv,
                                  const char *const *labels);
/* In declare(): invariant k depends on variable var (the order of these calls is the order
 * invariant() writes its partial derivatives in). */
BG_API int bgr_declare_invariant_dep(bgr_element *el, bgr_model *m, int k, int var);
/* The number of invariants of a compiled model (0: none, or not compiled, or m NULL). */
BG_API int bgr_ninvariants(const bgr_model *m);
/* Name of invariant k ("model/.../element/label"); NULL for k out of range or not compiled. */
BG_API const char *bgr_invariant_name(const bgr_model *m, int k);
/* The ncons x n pattern of their gradient; NULL when there are none or not compiled. */
BG_API const sp_csc *bgr_invariant_pattern(const bgr_model *m);
/* The invariants as a dae_cons_fn (user = the model): g (bgr_ninvariants values) and, if G is not
 * NULL, the values of dg/dy on bgr_invariant_pattern. BG_OK, an element's status, BG_ERR_ARGUMENT
 * (a NULL argument, G of another shape), BG_ERR_STATE (not compiled). */
BG_API int bgr_invariants(void *model, double t, const double *y, double *g, sp_csc *G);

/* Declare the kind of a group of unknowns under the rigid motion of a co-moving frame (a
 * steady rotation: bgr_frame_rotation in bgr_analysis.h builds the frame's generator from these
 * declarations): BGR_FRAME_VECTOR, 3 unknowns, the global components of a vector (a velocity,
 * an angular velocity, a force, a moment, the vector between two points); BGR_FRAME_POSITION,
 * 3, the global coordinates of a point; BGR_FRAME_QUATERNION, 4, an orientation body to global
 * (q0 the scalar part; R(q) v = q v q*). Unknowns that no element declares do not change under
 * the frame's motion (scalars, components in a body's own frame). Several declarations of one
 * group (a bond's unknowns seen from both of its ends) are one; an unknown declared in two
 * different groups or kinds gives BG_ERR_ARGUMENT naming it. Besides the errors of the
 * bgr_declare_* functions above: BG_ERR_ARGUMENT for another kind or a NULL vars. */
enum { BGR_FRAME_VECTOR = 1, BGR_FRAME_POSITION = 2, BGR_FRAME_QUATERNION = 3 };
BG_API int bgr_declare_frame(bgr_element *el, bgr_model *m, int kind, const int *vars);

/* ---- compiling and solving ---- */
/* Checks that every port is connected with the dimension it needs, numbers unknowns and
 * equations, classifies the unknowns, builds the patterns and slots. BG_OK or an error whose
 * message names the element and port at fault (BG_ERR_PATTERN, BG_ERR_ARGUMENT, BG_ERR_MEMORY,
 * or an element's status); BG_ERR_STATE if the model is compiled already or an earlier
 * compilation failed. After a failure the model can only be freed. */
BG_API int bgr_compile(bgr_model *m);

typedef struct bgr_stats {
    int equations; /* = unknowns */
    int nnz_dy;    /* entries of dF/dy (the "partial derivative matrix") */
    int nnz_dyp;   /* entries of dF/dy' (the "time-rate matrix") */
    int differential, algebraic, index2;
    int elements, bonds, components;
} bgr_stats;
/* BG_OK; BG_ERR_STATE before compilation (the element, bond and component counts are filled
 * all the same), BG_ERR_ARGUMENT for a NULL argument. */
BG_API int bgr_get_stats(const bgr_model *m, bgr_stats *st);
/* The statistics as text: BG_OK, BG_ERR_ARGUMENT (f NULL), BG_ERR_STATE (not compiled),
 * BG_ERR_IO. */
BG_API int bgr_stats_print(const bgr_model *m, FILE *f);

/* A dae_problem for the compiled model (user = the model; the model must outlive the solver),
 * with the names of the unknowns and of the equations, the nominal magnitudes of the unknowns
 * (p->nominal = bgr_nominals(m); set it to NULL for the absolute tolerance in SI units) and the
 * position invariants as its constraints (ncons = bgr_ninvariants(m), cons = bgr_invariants;
 * projection onto them is the caller's choice: dae_options.projection). BG_OK,
 * BG_ERR_ARGUMENT (p NULL) or BG_ERR_STATE (not compiled). */
BG_API int bgr_dae_problem(bgr_model *m, dae_problem *p);
/* The regimes of the elements that have one (bgr_element_class.regime), in element order, into
 * r (room for the count; r NULL: the count only). Returns how many, or < 0: BG_ERR_ARGUMENT (m
 * NULL, y NULL with r given), BG_ERR_STATE (not compiled). bgr_dae_problem passes them on as
 * dae_problem.regimes when there are any. */
BG_API int bgr_regimes(const bgr_model *m, const double *y, int *r);
/* Number of unknowns (= equations) of the compiled model; 0 before compilation or for NULL. */
BG_API int bgr_n(const bgr_model *m);
/* Name of an unknown / equation; NULL for an id out of range or a model not compiled. */
BG_API const char *bgr_var_name(const bgr_model *m, int var);
BG_API const char *bgr_eq_name(const bgr_model *m, int eq);
/* Kinds of the unknowns (dae_var_kind); NULL before compilation. */
BG_API const int *bgr_kinds(const bgr_model *m);
/* Initial values: y0 and yp0 arrays of the model (n each), zero after compile; set freely. NULL
 * before compilation. */
BG_API double *bgr_y0(bgr_model *m);
BG_API double *bgr_yp0(bgr_model *m);
/* The n nominal magnitudes of the unknowns (see bgr_declare_nominal: the largest declaration,
 * 1 for undeclared unknowns); bgr_dae_problem passes them as dae_problem.nominal. NULL before
 * compilation. */
BG_API const double *bgr_nominals(const bgr_model *m);
/* Override the nominal magnitude of unknown var after compilation (a user who knows the scale
 * of an unknown better than its elements, or 1 to get SI units back). Problems made by
 * bgr_dae_problem see the change (they point at the model's array), solvers already created do
 * not (dae_create copies the tolerances). BG_OK, BG_ERR_ARGUMENT (var out of range, nominal not
 * finite and > 0), BG_ERR_STATE (not compiled). */
BG_API int bgr_set_nominal(bgr_model *m, int var, double nominal);

/* The residual and Jacobian of the compiled model (dae_res_fn / dae_jac_fn with user = model).
 * Besides the elements' statuses: BG_ERR_ARGUMENT (a NULL argument), BG_ERR_STATE (not
 * compiled), BG_ERR_PATTERN (Jy, Jyp without the model's shapes and entry counts). */
BG_API int bgr_residual(void *model, double t, const double *y, const double *yp, double *F);
BG_API int bgr_jacobian(void *model, double t, const double *y, const double *yp, sp_csc *Jy,
                        sp_csc *Jyp);

/* The breakpoints of all elements in (t0, t1], sorted, duplicates removed; at most max written
 * into t. Returns how many there are (may exceed max), or BG_ERR_ARGUMENT (max < 0, t NULL with
 * max > 0, t0 or t1 NaN), BG_ERR_MEMORY. Works before compilation as well. */
BG_API int bgr_breakpoints(const bgr_model *m, double t0, double t1, double *t, int max);

/* Structural check: a maximum matching of the equations to the unknowns on the pattern of
 * dF/dy + dF/dy' (dae_structure_check). Returns 0 when the system is structurally regular, else
 * how many equations (and unknowns) are left unmatched, with the first of them named in report
 * (equations and unknowns by path); < 0: BG_ERR_ARGUMENT (m NULL, report NULL with size > 0),
 * BG_ERR_STATE (not compiled), BG_ERR_MEMORY. */
BG_API int bgr_check_structure(const bgr_model *m, char *report, size_t size);

/* Listing: one line per equation: its name, its text (if the class describes it) and the
 * variables it depends on. BG_OK, BG_ERR_ARGUMENT (f NULL), BG_ERR_STATE (not compiled),
 * BG_ERR_IO. */
BG_API int bgr_list_equations(const bgr_model *m, FILE *f);

/* Check mode: every element's analytic partial derivatives against central differences of the
 * whole residual at (t, y, yp), entries missing from the declarations included. Errors are
 * relative to |finite difference| + max(1e-6, 1e-9 * largest entry). Returns the
 * number of mismatches (> tol relative), or < 0 on failure (BG_ERR_ARGUMENT: y or yp NULL, tol
 * not > 0, report NULL with size > 0; BG_ERR_STATE: not compiled; an element's status); the
 * worst is described in report (element, equation, variable, analytic, finite difference). */
BG_API int bgr_check_jacobian(bgr_model *m, double t, const double *y, const double *yp, double tol,
                              char *report, size_t size);

#ifdef __cplusplus
}
#endif
#endif
