/* The output folder of a run (rn_run.h): its name, the check that no run of the same program
 * still uses it, status.txt "running" first, then the files of an earlier run removed; the
 * command line quoted for status.txt; the exit status. */
#include <errno.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "pu_fs.h"
#include "rn_run.h"

void rn_init(rn_run *r, const char *program, const char *subject)
{
    memset(r, 0, sizeof *r);
    r->program = program;
    r->subject = subject;
    r->name = r->path = "";
    r->wall0 = rn_wall_now();
    r->status = "running";
    r->csv_fd = -1;
}

void rn_format_command(rn_run *r, int argc, char **argv)
{
    char *b = r->command;
    size_t n = 0, size = sizeof r->command - 8;
    for (int i = 0; i < argc && n < size; i++) {
        const char *a = argv[i];
        int plain = a[0] && strspn(a, "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz"
                                      "0123456789-_./=:,+@%") == strlen(a);
        if (i) b[n++] = ' ';
        if (!plain) b[n++] = '\'';
        for (; *a && n < size; a++) {
            if (*a == '\'' && n + 4 < size) {
                memcpy(b + n, "'\\''", 4);
                n += 4;
            } else {
                b[n++] = (unsigned char)*a < 32 || *a == 127 ? '?' : *a;
            }
        }
        if (!plain && n < size) b[n++] = '\'';
    }
    if (n >= size) memcpy(b + n, " ...", 4), n += 4;
    b[n] = '\0';
}

int rn_set_outdir(rn_run *r, const char *out)
{
    if (out && strlen(out) > RN_OUT_MAX) {
        fprintf(stderr, "%s: --out: the folder's name is %zu characters long, more than %d\n",
                r->program, strlen(out), RN_OUT_MAX);
        return RN_EXIT_USAGE;
    }
    if (!out && strlen(r->name) > RN_OUT_MAX - 16) {
        fprintf(stderr, "%s: the %s's name is %zu characters long, more than %d\n", r->program,
                r->subject, strlen(r->name), RN_OUT_MAX - 16);
        return RN_EXIT_USAGE;
    }
    if (out)
        snprintf(r->outdir, sizeof r->outdir, "%s", out);
    else
        snprintf(r->outdir, sizeof r->outdir, "results/%s", r->name);
    size_t ol = strlen(r->outdir);
    while (ol > 1 && r->outdir[ol - 1] == '/')
        r->outdir[--ol] = '\0';
    return 0;
}

/* The status.txt in the folder names a run still going (its pid is alive and, where /proc
 * tells, called as this program): 1, with its pid and start in msg. */
static int folder_in_use(const rn_run *r, char *msg, size_t size)
{
    char path[RN_PATH_SIZE], text[8192];
    rn_path_in(r, "status.txt", path, sizeof path);
    FILE *f = fopen(path, "r");
    if (!f) return 0;
    size_t len = fread(text, 1, sizeof text - 1, f);
    fclose(f);
    text[len] = '\0';
    const char *p = strstr(text, "\npid: "), *st = strstr(text, "\nstarted: ");
    if (strncmp(text, "status: running\n", 16) || !p) return 0;
    long pid = strtol(p + 6, NULL, 10);
    if (pid <= 0 || pid == (long)getpid() || (kill((pid_t)pid, 0) != 0 && errno != EPERM)) return 0;
    char comm[RN_PATH_SIZE], name[64] = "";
    snprintf(comm, sizeof comm, "/proc/%ld/comm", pid);
    if ((f = fopen(comm, "r")) != NULL) {
        if (!fgets(name, sizeof name, f)) name[0] = '\0';
        fclose(f);
        if (strncmp(name, r->program, strlen(r->program))) return 0; /* another program's now */
    }
    char started[64] = "?";
    if (st) snprintf(started, sizeof started, "%.*s", (int)strcspn(st + 10, "\n"), st + 10);
    snprintf(msg, size, "pid %ld, started %s", pid, started);
    return 1;
}

/* The files of an earlier run, with their temporary names (status.txt itself is ours, new). */
static int remove_old_outputs(rn_run *r, const char *const *files)
{
    char path[RN_PATH_SIZE + 16], msg[RN_PATH_SIZE + 128];
    for (int i = 0; files && files[i]; i++)
        for (int tmp = 0; tmp < 3; tmp++) {
            if (!strcmp(files[i], "status.txt") && tmp == 0) continue;
            rn_path_in(r, files[i], path, sizeof path);
            if (tmp) strcat(path, tmp == 1 ? ".tmp" : ".signal.tmp");
            if (unlink(path) != 0 && errno != ENOENT) {
                snprintf(msg, sizeof msg, "cannot remove %s, left by an earlier run", path);
                return rn_fail_run(r, msg, strerror(errno));
            }
        }
    return 0;
}

int rn_prepare_folder(rn_run *r, const char *const *files)
{
    if (rn_signal()) {
        fprintf(stderr, "%s: %s received before the run started: nothing written\n", r->program,
                rn_signal_name(rn_signal()));
        return 128 + rn_signal();
    }
    char msg[RN_PATH_SIZE + 256];
    if (pu_mkdir_p(r->outdir, 0777, msg, sizeof msg) != 0) {
        fprintf(stderr, "%s: cannot use the output folder %s: %s\n", r->program, r->outdir, msg);
        return RN_EXIT_RUN;
    }
    if (folder_in_use(r, msg, sizeof msg)) {
        fprintf(stderr,
                "%s: the output folder %s is in use: its status.txt names a %s still "
                "running there (%s). Choose another --out, or stop that run (if it is gone, "
                "remove %s/status.txt)\n",
                r->program, r->outdir, r->program, msg, r->outdir);
        return RN_EXIT_RUN;
    }
    /* status.txt "running" first (it replaces an earlier run's), then the earlier results go */
    rn_local_time(r->started, sizeof r->started);
    if (rn_write_status(r, 0) != 0) return RN_EXIT_RUN;
    rn_status_ready(r, 1);
    rn_set_phase(r, RN_PHASE_SETUP, "preparing the output folder");
    remove_old_outputs(r, files);
    return 0;
}

int rn_exit_status(const rn_run *r, int usage_error)
{
    return !strcmp(r->status, "completed")     ? RN_EXIT_OK
           : !strcmp(r->status, "interrupted") ? 128 + r->sig
           : usage_error                       ? RN_EXIT_USAGE
                                               : RN_EXIT_RUN;
}
