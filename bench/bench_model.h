/* The cost of model files (issue "Models as files", item 8): reading and building a model from
 * its file against integrating it, measured by the harness (never by a timed test).
 *
 *   the paper crane (crane/models/paper.yaml): mdl_load (read, check, build, compile, place),
 *   the static start with its trim (mdl_static), and the integration of its 20 s (dae_step to
 *   t_end with the file's options), each the median of `runs` runs, CPU time of this process;
 *   the target: reading and building at most 10 % of the integration;
 *   a boom of 512 beam elements (a model text made here: a support, the chain, a load): mdl_load,
 *   median of `runs`; the target: under 1 s.
 * model_files.csv in the output folder and a section of the report. Nothing per step depends on
 * the model having come from a file (the compiled bgr_model runs), so the integration's cost is
 * the C model's: the C crane's runs are in realtime.csv. */
#ifndef BENCH_MODEL_H
#define BENCH_MODEL_H

#include <stdio.h>

/* Runs the measurements (runs >= 1), writes outdir/model_files.csv and the report's section into
 * report. The number of failures (a model that does not load or run, a file not written; a
 * target missed is reported, not counted). */
int bench_model_files(const char *models_dir, int runs, const char *outdir, FILE *report);

#endif
