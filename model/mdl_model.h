/* Model files: a bond-graph model described as a YAML document (docs/model-format.md), read,
 * checked and built into a compiled bgr_model with its start configuration, its declared outputs
 * and its solver settings.
 *
 * Reading happens in stages, each of which reports the first error with the file, line and
 * column, the component path and the key ("m.yaml:14:12: components.pump.leakage: -1 is out of
 * range (expected >= 0, in m^3/(s Pa))"):
 *   1. the document and its includes (mdl_yaml.h; a file included twice is read once, a loop is
 *      an error),
 *   2. the instance tree: subsystems expanded, repetitions unrolled, every parameter checked
 *      against its type (mdl_types.h) and evaluated (mdl_expr.h; names looked up from the
 *      instance outward; a cycle among parameters is named),
 *   3. the bond graph: elements built in the order their references need (a joint after the
 *      body that carries its axis, a controller after the sensor it reads), bonds joined by path
 *      with their dimension and domain checked, every port bonded exactly once, then compiled
 *      (bgr_compile; a structurally singular model is reported with the unmatched equations
 *      and unknowns),
 *   4. the start: the types' place() in rounds (mdl_types.h), then the `initial` values.
 * Nothing per step depends on the model having come from a file: the compiled bgr_model's
 * residual and Jacobian are the same code that a model built in C runs. */
#ifndef MDL_MODEL_H
#define MDL_MODEL_H

#include "bg_api.h"
#include "bg_dae.h"
#include "bg_static.h"
#include "bgr_model.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct mdl_model mdl_model;

/* A replacement of a parameter before evaluation: a model parameter ("L1") or a component's
 * ("rod1.m", "boom.seg[3].L"), the value an expression as the file would write it. */
typedef struct mdl_set {
    const char *path;
    const char *value;
} mdl_set;

/* The solver settings of the file (`solver:`), with their defaults. */
typedef struct mdl_solver_settings {
    double t_end, output_step, rtol, atol;
    int nominal_scales, max_order, stability_guard;
    double newton_dgmax;
    int newton_jac_age, newton_index2_scale_h;
} mdl_solver_settings;

typedef enum mdl_start { MDL_START_GIVEN = 0, MDL_START_STATIC = 1 } mdl_start;

/* Reads path (and its includes) with the replacements sets (nsets of them, NULL if none),
 * builds and compiles the model and places its start. NULL on failure with the message in err
 * (file:line:column: path: key: what was expected, what was found). */
BG_API mdl_model *mdl_load(const char *path, const mdl_set *sets, int nsets, bg_error *err);
/* The same from a text in memory; name stands for the file in messages (includes are read
 * relative to the current directory). */
BG_API mdl_model *mdl_load_string(const char *text, const char *name, const mdl_set *sets,
                                  int nsets, bg_error *err);
BG_API void mdl_free(mdl_model **mm);

/* The compiled bond graph (owned by the model). */
BG_API bgr_model *mdl_bgr(mdl_model *mm);
BG_API const char *mdl_name(const mdl_model *mm);
BG_API const char *mdl_file(const mdl_model *mm);
BG_API const mdl_solver_settings *mdl_solver(const mdl_model *mm);
/* Replaces the solver settings (a program's overrides of the file's: bgsim --t-end, --rtol,
 * ...); t_end, output_step, rtol and atol must be finite and > 0, max_order in 1..5. A model
 * mdl_static rebuilds for a trim has the file's settings again. BG_OK or BG_ERR_ARGUMENT. */
BG_API int mdl_solver_override(mdl_model *mm, const mdl_solver_settings *s);
BG_API mdl_start mdl_start_kind(const mdl_model *mm);

/* Outputs (`outputs:`): count, names (the columns of results.csv after t), and their values at
 * (t, y). BG_OK or an error with the output's name and expression. */
BG_API int mdl_noutputs(const mdl_model *mm);
BG_API const char *mdl_output_name(const mdl_model *mm, int i);
BG_API int mdl_outputs(const mdl_model *mm, double t, const double *y, double *out, bg_error *err);

/* The solver options of the file's settings: tolerances, stop time t_end, the breakpoints of
 * the model's sources in (0, t_end] (allocated into *breakpoints, free() it; NULL when none),
 * the error test on the differential unknowns only (exclude_alg), the stability guard and the
 * Newton settings, and the projection onto the model's position invariants when it has any
 * (bgr_model.h: a mech.revolute_angle's angle). dae_default_options is applied first. BG_OK or
 * BG_ERR_MEMORY. */
BG_API int mdl_dae_options(const mdl_model *mm, dae_options *o, double **breakpoints);
/* A dae_problem of the compiled model, with the nominal magnitudes when nominal_scales is on. */
BG_API int mdl_dae_problem(mdl_model *mm, dae_problem *p);

/* The static start (bgs --static, start: static): the equilibrium under the loads at t = 0
 * (bgr_static), written into the model's initial values. With the file's `trim:` the parameter it
 * names is adjusted until the output equals the value at the equilibrium (the Illinois variant of
 * regula falsi on the file's bracket, the model built again for every trial value): *mm is then
 * replaced by the model built with the value found. BG_OK, DAE_CONV_FAIL with the names and
 * values when the condition cannot be met, or bgr_static's status. rep (may be NULL) receives
 * the trim's figures and the last static solve's. */
typedef struct mdl_trim_report {
    int trimmed;            /* 1: a trim ran */
    char parameter[128];    /* what it adjusted, */
    char output[128];       /* the output it watched */
    double target;          /* and the value wanted; */
    double value, achieved; /* the parameter's value found and the output's there */
    int solves;             /* static solves */
    dae_static_result last; /* the last static solve */
} mdl_trim_report;
BG_API int mdl_static(mdl_model **mm, const dae_static_options *o, mdl_trim_report *rep,
                      bg_error *err);

/* The model drawn at state y for ParaView series (model/mdl_geom.c says what each mechanical
 * type draws: bodies, point masses, supports, axial members, cylinders, beam chains): points in
 * the global frame, polylines and marked points, each tagged with its part (an instance, by its
 * path and type). Fill with mdl_geometry (the arrays are reused from call to call), free with
 * mdl_geom_clear; start from a zeroed record. */
typedef struct mdl_geom {
    int npoints;
    double *x;       /* 3 per point */
    int *point_part; /* the part of each point */
    int nlines;
    int *line_start; /* line i: line_conn[line_start[i] .. line_start[i + 1]) (nlines + 1) */
    int *line_conn;
    int *line_part;
    int nmarks;
    int *mark_point, *mark_part;
    int nparts;
    const char **part_path, **part_type; /* owned by the model */
    int cap_x, cap_pp, cap_ls, cap_lc, cap_lp, cap_mp, cap_mk, cap_pa, cap_pt;
} mdl_geom;
BG_API int mdl_geometry(const mdl_model *mm, const double *y, mdl_geom *g, bg_error *err);
BG_API void mdl_geom_clear(mdl_geom *g);

/* The value of a model parameter (after the replacements) by name; BG_OK or BG_ERR_ARGUMENT. */
BG_API int mdl_parameter(const mdl_model *mm, const char *name, double *value);
/* The model as run: the file's text as read, followed by the replacements applied, as
 * comments. BG_OK or BG_ERR_IO. */
BG_API int mdl_write_as_run(const mdl_model *mm, FILE *f);

#ifdef __cplusplus
}
#endif
#endif
