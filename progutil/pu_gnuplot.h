/* gnuplot as the programs run it (the crane program's figures and animation, crane-sweep's
 * pictures, the benchmark harness's work-precision plots): found in PATH, started without a
 * shell in the folder of its files, its messages kept, the PNG files it wrote checked to be
 * whole. Part of libprogutil (progutil/): no output, no exit, no global state.
 *
 * gnuplot is started by posix_spawn (with posix_spawn_file_actions_addchdir_np for its folder
 * where the C library has it, else fork and chdir): a process of an MPI job must not fork. Its
 * standard input and output are /dev/null; its standard error goes into a log file in its
 * folder (pu_gnuplot_job.log) or through a pipe into the caller's message (log NULL). The
 * signals the caller handles (SIGINT, SIGTERM, SIGHUP) and SIGPIPE are at their defaults in
 * gnuplot, its signal mask is empty. */
#ifndef PU_GNUPLOT_H
#define PU_GNUPLOT_H

#include <signal.h>
#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* The path of gnuplot, searched in PATH as the shell would (an empty PATH: /usr/local/bin,
 * /usr/bin, /bin), into buf. 1 found, 0 not. */
int pu_gnuplot_find(char *buf, size_t size);

/* A PNG file that is whole: it ends with the IEND chunk. 1 or 0. */
int pu_png_whole(const char *path);
/* A GIF file that is whole: it starts with "GIF87a" or "GIF89a" and ends with the trailer byte
 * 0x3B (GIF89a specification, section 27). 1 or 0. */
int pu_gif_whole(const char *path);

typedef struct pu_gnuplot_job {
    const char *exe;      /* gnuplot (pu_gnuplot_find) */
    const char *dir;      /* the folder it runs in: the names in its commands are relative to it */
    const char *script;   /* a script file (relative to dir): gnuplot SCRIPT; or NULL and ... */
    const char *commands; /* ... commands: gnuplot -e COMMANDS */
    const char *log;      /* its standard error into dir/log (created or emptied), or NULL: read
                             through a pipe, its last line with text into msg */
    const volatile sig_atomic_t *stop; /* when it becomes non-zero while gnuplot runs, gnuplot
                                          is sent SIGTERM (once); NULL: never */
} pu_gnuplot_job;

/* Runs the job and waits for gnuplot to end. Returns its wait status (waitpid: WIFEXITED ...),
 * or -1 if it could not be started (msg: why, with the system's error). msg (size > 0) is
 * otherwise "" or, with log NULL, the last line of text gnuplot wrote to its standard error
 * (of the first 2 kB). */
int pu_gnuplot_run(const pu_gnuplot_job *job, char *msg, size_t size);

/* The first line of dir/log (a gnuplot log) into buf ("" if none or empty); with remove_empty
 * the log is removed when it holds no text. */
void pu_gnuplot_log_first(const char *dir, const char *log, int remove_empty, char *buf,
                          size_t size);

#ifdef __cplusplus
}
#endif
#endif
