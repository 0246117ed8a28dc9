/* Sweep files of crane-sweep: INI text -> the cases of a parameter sweep (the manual:
 * docs/sweeps.md; the example crane/sweeps/pid-kp-kd.ini).
 *
 * The syntax is the scene files' (crane_scene.h): "key = value" lines, "[section]" headers,
 * comments from ';' or '#' at the start of a line or " ;" after a value, LF, CR LF or CR line
 * ends, at most 198 characters a line, keys and sections matched without regard to case, each key
 * at most once in its section. Sections:
 *
 *   [sweep]   name          name           results go to results/sweeps/<name>/ (default: the
 *                                          file's name without .ini)
 *             scene         text           the base scene: a file (relative to the sweep file's
 *                                          folder) or a name in crane/scenes/ (default paper)
 *             model         text           or a model file (relative to the sweep file's folder):
 *                                          the cases are bgsim runs (sweep_model.c: the keys are
 *                                          the model's parameters PARAM or PATH.PARAM as bgsim
 *                                          --set takes them, the values expressions)
 *             quantities    list           a model sweep's summary quantities: FUNC(COLUMN) or
 *                                          FUNC(abs(COLUMN)) of results.csv's columns, FUNC one of
 *                                          max, min, end, mean, rms, maxabs; and steps, cpu_s,
 *                                          wall_s (default: end(C) of every output, steps, cpu_s)
 *             t_end         number > 0     a model sweep's end time (bgsim --t-end; default the
 *                                          model file's)
 *             time_limit    number >= 0    s of wall time per case (0: none; default 0); a case
 *                                          still running then gets SIGTERM, 5 s later SIGKILL
 *             report        names          the summary quantities of sweep.csv, in order, from
 *                                          the table of sweep_row.h (default: all but
 *                                          theta_err_end, p_min, rope_force_max, wall_s)
 *             case_figures  boolean        each case draws the crane's figures (default false)
 *   [set]     SECTION.KEY = VALUE          a scene key for every case (as crane --set; a model
 *                                          sweep's PARAM or PATH.PARAM = VALUE, as bgsim --set)
 *   [axis]    key           SECTION.KEY    the swept scene key (repeat [axis] for more axes; a
 *                                          model sweep's PARAM or PATH.PARAM)
 *             values        list           the values: "0.5, 1, 2" (vectors: "0,0,1 | 0,0,2")
 *             from, to      numbers        or a range: count values from .. to (to included)
 *             count         1..100000
 *             spacing       linear | log   of the range (log: from, to > 0; default linear)
 *   [lhs]     samples       1..100000      a Latin-hypercube sample of the keys below
 *             seed          0..2^63-1      of the sample (default 1): the same seed, the same
 *                                          sample (a generator of our own, splitmix64; values
 *                                          written with 8 digits)
 *             SECTION.KEY = LO, HI [, log] each sampled key's interval (integer keys: rounded)
 *
 * The cases are the product of the axes in file order (the first axis varies slowest), the
 * [lhs] sample (at most one) as a last axis whose points set all its keys at once; case k is
 * numbered from 0. Every value is checked against its key's range when the file is read (an
 * error of the sweep file); whether a case's scene as a whole is consistent (reference times in
 * order, a boom that reaches its tip radius, ...) is the crane's check when the case runs.
 * A swept key may appear in one axis only and not in [set]; [set] and the swept keys together
 * are at most 64 (the crane's --set limit), the cases at most 100000.
 *
 * Errors name the file, the line and the key, and what was expected:
 *   sweep.ini:7: key 'count' in [axis]: expected an integer in 1..100000, got '0'
 *   sweep.ini:9: key 'values' in [axis]: value 3 of controller.kp: key 'kp' in [controller]:
 *     expected a number >= 0 (1/(rad/s)), got '-1'
 *   sweep.ini:4: unknown key 'valeus' in [axis]; did you mean 'values'? */
#ifndef SWEEP_SPEC_H
#define SWEEP_SPEC_H

#include <stddef.h>

#include "crane_model.h"

#define SWEEP_PATH_SIZE 4096
#define SWEEP_DIR_SIZE (SWEEP_PATH_SIZE + 32) /* a case's folder OUT/cases/NNNN */
#define SWEEP_MAX_PARAMS 32                   /* swept keys */
#define SWEEP_MAX_SETS 64                     /* [set] keys + swept keys (crane --set) */
#define SWEEP_MAX_AXES 16                     /* [axis] sections (+ [lhs]) */
#define SWEEP_MAX_CASES 100000L
#define SWEEP_VALUE_SIZE 200 /* a value's text */
#define SWEEP_MAX_REPORT 32

typedef enum sweep_axis_kind { SWEEP_AXIS_LIST, SWEEP_AXIS_RANGE, SWEEP_AXIS_LHS } sweep_axis_kind;

/* A swept scene key: a column of sweep.csv. */
typedef struct sweep_param {
    char section[64], key[64]; /* as the scene table spells them */
    char name[132];            /* "controller.kp" */
    int type;                  /* crane_key_type */
    int axis;                  /* the axis that sets it */
    int line;                  /* where it is named */
    double lo, hi;             /* [lhs]: the interval */
    int log;                   /* log spacing (range, [lhs]) */
} sweep_param;

typedef struct sweep_axis {
    sweep_axis_kind kind;
    int line;                         /* of its section header */
    int npoints;                      /* values along it */
    int nparams;                      /* keys it sets (1 except [lhs]) */
    int param[SWEEP_MAX_PARAMS];      /* indices into sweep_spec.params */
    char (*values)[SWEEP_VALUE_SIZE]; /* npoints * nparams texts, point-major */
    int log;                          /* range spacing log (pictures: log axis) */
} sweep_axis;

typedef struct sweep_set {
    char section[64], key[64], value[SWEEP_VALUE_SIZE]; /* a model's: section "", key PATH */
    int line;
} sweep_set;

/* A model sweep's summary quantity FUNC(COLUMN) of results.csv (sweep_model.c). */
typedef enum sweep_mfunc {
    SWEEP_MF_MAX,
    SWEEP_MF_MIN,
    SWEEP_MF_END,
    SWEEP_MF_MEAN,
    SWEEP_MF_RMS,
    SWEEP_MF_MAXABS
} sweep_mfunc;
typedef struct sweep_mquantity {
    int func;        /* sweep_mfunc */
    int absval;      /* FUNC(abs(COLUMN)) */
    char column[64]; /* an output of the model, or t */
    char name[160];  /* "max(abs(z))": sweep.csv's header */
    char stem[160];  /* "max_abs_z": the picture's file plot_<stem>.png */
} sweep_mquantity;

typedef struct sweep_spec {
    char path[SWEEP_PATH_SIZE];       /* the sweep file as given */
    char name[64];                    /* [sweep] name */
    int is_model;                     /* [sweep] model: the cases are bgsim runs */
    char scene_arg[SWEEP_PATH_SIZE];  /* [sweep] scene (or model) as written */
    char scene_path[SWEEP_PATH_SIZE]; /* resolved, absolute */
    double t_end;                     /* a model sweep's --t-end (0: the file's) */
    double time_limit;                /* s, 0: none */
    int case_figures;
    int nsets;
    sweep_set sets[SWEEP_MAX_SETS];
    int nparams;
    sweep_param params[SWEEP_MAX_PARAMS];
    int naxes;
    sweep_axis axes[SWEEP_MAX_AXES];
    int nreport;
    int report[SWEEP_MAX_REPORT]; /* quantity indices (sweep_row.h); SWEEP_NQ + i: mq[i] */
    int nmq;
    sweep_mquantity mq[SWEEP_MAX_REPORT]; /* a model sweep's FUNC(COLUMN) quantities */
    int lhs_samples;
    unsigned long long seed;
    long ncases;
    char *text; /* the file's text (copied into the output folder) */
    size_t text_len;
} sweep_spec;

/* Reads, checks and expands the sweep file at path; scene_roots are the folders in which a bare
 * scene name is looked up as crane/scenes/NAME(.ini) after the sweep file's own folder (NULL
 * ends the list). 0, or -1 with the message in err ("FILE:LINE: ..."); an unreadable file is
 * -2 (the message says why). sweep_spec_free afterwards in both cases. */
int sweep_spec_load(sweep_spec *s, const char *path, const char *const *scene_roots, char *err,
                    size_t errsize);
/* The same from text (file names the messages; the scene is resolved as from a file in the
 * current folder). */
int sweep_spec_parse(sweep_spec *s, const char *text, const char *file,
                     const char *const *scene_roots, char *err, size_t errsize);
void sweep_spec_free(sweep_spec *s);

/* The point along each axis of case c (coord[naxes]). */
void sweep_case_coords(const sweep_spec *s, long c, int *coord);
/* The value text of swept key p in case c. */
const char *sweep_case_value(const sweep_spec *s, long c, int p);
/* The scene of case c: the base scene, [set], the case's values (0, or -1 with err: the scene
 * is inconsistent or the base scene cannot be read). */
int sweep_case_scene(const sweep_spec *s, long c, crane_scene *scene, char *err, size_t errsize);
/* "SECTION.KEY=VALUE" for the crane's --set ("PATH=VALUE" for bgsim's): [set] first, then the
 * case's values; returns the count (<= SWEEP_MAX_SETS), each item of size SWEEP_VALUE_SIZE + 140. */
#define SWEEP_SET_ARG_SIZE (SWEEP_VALUE_SIZE + 140)
int sweep_case_set_args(const sweep_spec *s, long c, char (*out)[SWEEP_SET_ARG_SIZE]);

/* The program a case runs ("crane" or "bgsim") and its log in the case's folder. */
const char *sweep_program(const sweep_spec *s);
const char *sweep_log_name(const sweep_spec *s);

#endif
