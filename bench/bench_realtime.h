/* The crane's real-time check (realtime.csv): how much faster than real time our solver
 * integrates the crane's scenes, and how the cost grows with the boom's mesh.
 *
 * Scenes: each over its t_end (paper: 20 s) at its tolerances (paper: rtol = atol = 1e-6), K runs
 * of each, every run in a fresh process (this program started with --realtime-child
 * [--crane-scene FILE]) for its peak memory: set-up (build, static start, consistent values) and
 * integration timed apart, the integration's CPU time the measure (the machine is shared: wall
 * time beside it), output at the scene's output step computed and not written (crane_outputs),
 * the solver as the crane program runs it (exclude_alg, the scene's stability guard, the
 * reference's breakpoints). Medians of the K runs; the steps within 0.25 s after each corner of
 * the reference (t = 0 and the breakpoints), where the drive's transients are, counted apart.
 *
 * Mesh series: the first scene with 8 .. 512 boom elements (the list given) over a short horizon
 * (1 s: the 512-element run stays short), one run each in this process: CPU time per step and
 * its log-log least-squares slope against the elements (target <= 1.1: linear) and against the
 * unknowns, the steps (target: independent of the mesh within 30 %, max / min <= 1.3).
 *
 * Targets (the crane issue): the paper scene at least 50 times faster than real time on CPU time
 * with at most 8 000 steps; paper-undamped at least 7.5 times. */
#ifndef BG_BENCH_REALTIME_H
#define BG_BENCH_REALTIME_H

#include <stdio.h>

#include "crane_model.h"

/* One scene of the check. */
typedef struct bench_rt_scene {
    const char *file;  /* the scene file the child loads (NULL: crane_scene_default) */
    const char *label; /* its name in the report and realtime.csv */
    crane_scene s;     /* the scene (loaded from file) */
    double target;     /* real-time factor target on CPU time (0: none) */
    long max_steps;    /* step target (0: none) */
} bench_rt_scene;

typedef struct bench_rt_result {
    double rt_factor, rt_factor_cpu, rt_factor_all; /* medians: simulated / wall, / CPU time of
                                                      the integration, / wall with the set-up */
    double peak_mb, bookkeeping, wall_int, cpu_int;  /* largest peak RSS; medians */
    double res_s_med, jac_s_med, lin_s_med, out_s_med; /* parts of the run nearest the median */
    long steps, newton, jac, steps_corners;          /* of the last completed run */
    int runs, n;
} bench_rt_result;

#define BENCH_MESH_MAX 16
typedef struct bench_mesh_result {
    int n;                                   /* meshes measured */
    int elements[BENCH_MESH_MAX], unknowns[BENCH_MESH_MAX];
    long steps[BENCH_MESH_MAX];
    double cpu_per_step[BENCH_MESH_MAX];
    double slope_el, slope_n; /* NaN with fewer than 2 meshes */
    double steps_spread;      /* largest / smallest step count */
} bench_mesh_result;

/* The check: K runs of each of the nsc scenes (exe: this program, for the children), then the
 * mesh series over mesh_t_end with the element counts elems (nel of them; 0: none) on the first
 * scene. realtime.csv into dir (a row per run and a median row per scene, case "scene"; a row per
 * mesh, case "mesh"), a report section into rep; res receives nsc results, mesh the series.
 * Returns the number of failed runs. */
int bench_crane_realtime(const char *exe, const bench_rt_scene *sc, int nsc, int K, const int *elems,
                         int nel, double mesh_t_end, const char *dir, FILE *rep,
                         bench_rt_result *res, bench_mesh_result *mesh);
/* The child's side: runs scene s once and prints one line of results on stdout. Exit status 0,
 * or 1 if the run failed. */
int bench_crane_realtime_child(const crane_scene *s);

#endif
