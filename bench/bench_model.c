/* The cost of model files against integration (bench_model.h). */
#include "bench_model.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_util.h"
#include "bg_dae.h"
#include "mdl_model.h"

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

static double median(double *x, int n)
{
    qsort(x, (size_t)n, sizeof *x, cmp_double);
    return n % 2 ? x[n / 2] : 0.5 * (x[n / 2 - 1] + x[n / 2]);
}

/* the integration over the file's t_end with its options: CPU seconds, or < 0 */
static double integrate(mdl_model *mm, long *steps)
{
    dae_problem p;
    dae_options o;
    double *bk = NULL, t = 0;
    bg_error e = {0};
    if (mdl_dae_problem(mm, &p) != BG_OK || mdl_dae_options(mm, &o, &bk) != BG_OK) return -1;
    bgr_model *m = mdl_bgr(mm);
    int n = bgr_n(m);
    double *y = malloc((size_t)n * sizeof *y), *yp = malloc((size_t)n * sizeof *yp);
    double t0 = bench_cpu_now(), tend = mdl_solver(mm)->t_end, cpu = -1;
    dae_solver *s = y && yp ? dae_create(&p, &o, &e) : NULL;
    int rc = s ? dae_init(s, 0, bgr_y0(m), bgr_yp0(m)) : -1;
    if (rc == BG_OK || rc == DAE_WARNING) rc = dae_consistent_init(s);
    if (rc == DAE_WARNING) rc = BG_OK;
    while (rc >= 0 && t < tend)
        rc = dae_step(s, tend, &t, y, yp);
    if (rc >= 0) {
        cpu = bench_cpu_now() - t0;
        *steps = dae_get_stats(s)->steps;
    }
    dae_free(&s);
    free(y), free(yp), free(bk);
    return cpu;
}

/* a 512-element boom as a model text: a clamped foot, the chain, a load on its tip */
static const char BOOM[] = "format: bgsim 1\n"
                           "name: boom512\n"
                           "parameters: {n: 512, L: 20}\n"
                           "components:\n"
                           "  base: {type: mech.support}\n"
                           "  boom:\n"
                           "    type: mech.beam_chain\n"
                           "    elements: n\n"
                           "    start: [0, 0, 0]\n"
                           "    end: [L, 0, 0]\n"
                           "    E: 2.1e11\n"
                           "    G: 8.1e10\n"
                           "    A: 0.01\n"
                           "    Iy: 1e-4\n"
                           "    Iz: 2e-4\n"
                           "    J: 1e-4\n"
                           "    rho: 7850\n"
                           "    gravity: [0, 0, -9.81]\n"
                           "    ports: {foot: {node: 0}, tip: {node: n, dim: 3}}\n"
                           "  load: {type: mech.point_mass, mass: 500, gravity: [0, 0, -9.81]}\n"
                           "bonds: [base.p -> boom.foot, boom.tip -> load.p]\n";

int bench_model_files(const char *models_dir, int runs, const char *outdir, FILE *report)
{
    enum { MAXRUNS = 64 };
    if (runs < 1) runs = 1;
    if (runs > MAXRUNS) runs = MAXRUNS;
    double load[MAXRUNS], start[MAXRUNS], integ[MAXRUNS], boom[MAXRUNS];
    char path[4096];
    snprintf(path, sizeof path, "%s/paper.yaml", models_dir);
    int n = 0, nb = 0, failures = 0;
    long steps = 0;
    bg_error e = {0};
    for (int k = 0; k < runs; k++) {
        double t0 = bench_cpu_now();
        mdl_model *mm = mdl_load(path, NULL, 0, &e);
        double t1 = bench_cpu_now();
        if (!mm) break;
        n = mdl_static(&mm, NULL, NULL, &e) == BG_OK ? n : -1;
        double t2 = bench_cpu_now();
        if (n < 0) {
            mdl_free(&mm);
            break;
        }
        load[k] = t1 - t0, start[k] = t2 - t1;
        nb = bgr_n(mdl_bgr(mm));
        integ[k] = integrate(mm, &steps);
        mdl_free(&mm);
        if (integ[k] < 0) {
            n = -1;
            break;
        }
        n = k + 1;
    }
    if (n <= 0) {
        fprintf(stderr, "bench: model files: %s: %s\n", path, e.message[0] ? e.message : "the run failed");
        return 1;
    }
    int nboom = 0, unknowns_boom = 0;
    for (int k = 0; k < runs; k++) {
        double t0 = bench_cpu_now();
        mdl_model *mm = mdl_load_string(BOOM, "boom512.yaml", NULL, 0, &e);
        boom[k] = bench_cpu_now() - t0;
        if (!mm) {
            fprintf(stderr, "bench: model files: the 512-element boom: %s\n", e.message);
            failures++;
            break;
        }
        unknowns_boom = bgr_n(mdl_bgr(mm));
        mdl_free(&mm);
        nboom = k + 1;
    }
    double ml = median(load, n), ms = median(start, n), mi = median(integ, n);
    double mb = nboom ? median(boom, nboom) : -1;
    snprintf(path, sizeof path, "%s/model_files.csv", outdir);
    FILE *f = fopen(path, "w");
    if (f) {
        fprintf(f, "model,unknowns,runs,read_build_s,static_start_s,integration_s,steps,"
                   "read_build_fraction\n"
                   "crane/models/paper.yaml,%d,%d,%.6g,%.6g,%.6g,%ld,%.4g\n",
                nb, n, ml, ms, mi, steps, ml / mi);
        if (nboom) fprintf(f, "boom512 (beam chain),%d,%d,%.6g,,,,\n", unknowns_boom, nboom, mb);
        if (fclose(f) != 0) failures++;
    } else {
        fprintf(stderr, "bench: cannot write %s\n", path);
        failures++;
    }
    if (report) {
        fprintf(report,
                "## Model files\n\n"
                "Reading and building a model from its file (mdl_load: the YAML, the checks, the "
                "build, the compilation, the start) against integrating it (CPU, median of %d "
                "runs; model_files.csv):\n\n"
                "| model | unknowns | read and build | static start (trim) | integration | "
                "steps | read and build / integration | target |\n|---|---|---|---|---|---|---|---|\n"
                "| crane/models/paper.yaml | %d | %.4f s | %.4f s | %.3f s | %ld | %.2f %% | <= 10 %% "
                "(%s) |\n",
                n, nb, ml, ms, mi, steps, 100 * ml / mi, ml / mi <= 0.10 ? "met" : "MISSED");
        if (nboom)
            fprintf(report, "| a 512-element boom (generated) | %d | %.4f s | | | | | < 1 s (%s) |\n",
                    unknowns_boom, mb, mb < 1 ? "met" : "MISSED");
        fprintf(report, "\n");
    }
    return failures;
}
