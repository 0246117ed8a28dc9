/* bgsim: runs a bond-graph model described by a model file (docs/model-format.md) and writes the
 * results; the crane program's machinery (runner/rn_run.h) for any model (docs/bgsim.md).
 *
 *   bgsim MODEL [--out DIR] [--set PATH=VALUE]... [--t-end T] [--rtol R] [--atol A]
 *         [--output-step DT] [--max-rows N] [--static] [--modes [T]] [--quiet]
 *         [--list-types [--markdown]] [--describe TYPE] [--list-unknowns] [--help] [--version]
 *
 * Flow: the model file (mdl_load with the --set replacements: read, checked, built, compiled,
 * its start placed) -> the command line's solver settings -> the output folder made ready
 * (status.txt "running" first) -> model.yaml, model_stats.txt -> the static start with the
 * file's trim (start: static, or --static: static.txt, equilibrium.csv) -> mdl_dae_problem,
 * mdl_dae_options -> consistent initial values -> the runner's loop (rn_loop: dae_step up to
 * each output time, a row of t and the declared outputs there, buffered, whole rows only) ->
 * solver_stats.txt, summary, status.txt at the end. --modes [T]: bgr_modes at the start (after
 * the static start when the file asks for it) or at time T of a run: modes.csv. Per step the
 * solver runs the compiled bgr_model's residual and Jacobian only. This flow is bs_file.c's
 * (bs_run_file), which the crane program runs as well for a model file SCENE
 * (docs/crane-program.md); here only the command line.
 *
 * Writes into DIR (default results/<model name>/): status.txt ("running" with the pid, the
 * model, the command line and the start time; at the end completed, interrupted or failed with
 * the reason), model.yaml (the model as run), model_stats.txt, results.csv, solver_stats.txt;
 * static.txt, equilibrium.csv, modes.csv as asked. The files of an earlier run in DIR are
 * removed first; a DIR whose status.txt names a bgsim still running is refused. Every write is
 * checked; status.txt and the small files are replaced atomically.
 * Signals: SIGINT, SIGTERM and SIGHUP stop the integration between two solver steps (the rows
 * written stay, status.txt says when); during set-up and on a second signal the program writes
 * status.txt and ends at once.
 * Exit status: 0 completed; 1 the model's run or the solver failed, or a file could not be
 * written; 2 bad command line or model file (nothing written: the reader's FILE:LINE:COL
 * message on stderr); 128 + signal number when interrupted. */
#include <errno.h>
#include <stdio.h>
#include <string.h>

#include "bgsim.h"

int main(int argc, char **argv)
{
    /* signals first: one while the model is read ends the program before it writes anything */
    rn_signals_install("bgsim");

    bs_options o;
    int rc = bs_parse_args(argc, argv, &o);
    if (rc >= 0) {
        if (fflush(stdout) != 0 || ferror(stdout)) {
            fprintf(stderr, "bgsim: cannot write the standard output: %s\n", strerror(errno));
            return RN_EXIT_RUN;
        }
        return rc;
    }
    /* the run itself is bs_file.c's, shared with the crane program */
    return bs_run_file("bgsim", &o, argc, argv, NULL);
}
