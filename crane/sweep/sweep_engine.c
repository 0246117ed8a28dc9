/* Cases, rows and the local engine (sweep_engine.h). */
#include "sweep_engine.h"

#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "crane_scene.h"
#include "pu_fs.h"

void sweep_case_dir(const sweep_run *r, long index, char *buf, size_t size)
{
    snprintf(buf, size, "%s/cases/%04ld", r->outdir, index);
}

static void local_time(char *buf, size_t size)
{
    time_t now = time(NULL);
    struct tm tm;
    if (!localtime_r(&now, &tm) || !strftime(buf, size, "%Y-%m-%d %H:%M:%S %z", &tm))
        snprintf(buf, size, "%lld s after 1970", (long long)now);
}

/* case.txt: what the case is and, once over, how it ended. */
static void write_case_txt(const sweep_run *r, long index, const char *dir, const char *command,
                           const sweep_row *row)
{
    char *buf = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&buf, &len);
    if (!f) return;
    const sweep_spec *s = r->spec;
    char now[64];
    local_time(now, sizeof now);
    fprintf(f, "# crane-sweep case (the sweep's record; the %s's own is status.txt)\n",
            sweep_program(s));
    fprintf(f, "case: %ld\nsweep: %s\n", index, s->path);
    for (int p = 0; p < s->nparams; p++)
        fprintf(f, "%s: %s\n", s->params[p].name, sweep_case_value(s, index, p));
    char host[256] = "?";
    gethostname(host, sizeof host - 1);
    host[sizeof host - 1] = '\0';
    fprintf(f, "rank: %d\nhost: %s\n", r->rank, host);
    if (command) {
        fprintf(f, "command: %s\nstarted: %s\n", command, now);
    } else { /* the case is over: the command and the start from case.txt "running" */
        char path[SWEEP_DIR_SIZE + 16], cmd[8192], start[64];
        snprintf(path, sizeof path, "%s/case.txt", dir);
        if (sweep_read_field(path, "command", cmd, sizeof cmd)) fprintf(f, "command: %s\n", cmd);
        if (sweep_read_field(path, "started", start, sizeof start))
            fprintf(f, "started: %s\n", start);
    }
    if (row) {
        fprintf(f, "status: %s\nmessage: %s\nexit: %d\nended: %s\n", sweep_status_name(row->status),
                row->message[0] ? row->message : "-", row->exit_code, now);
        if (isfinite(row->q[SQ_CPU_S])) fprintf(f, "cpu_s: %.3f\n", row->q[SQ_CPU_S]);
        if (isfinite(row->q[SQ_WALL_S])) fprintf(f, "wall_s: %.3f\n", row->q[SQ_WALL_S]);
    } else {
        fprintf(f, "status: running\n");
    }
    if (fclose(f) == 0) {
        char path[SWEEP_DIR_SIZE + 16];
        snprintf(path, sizeof path, "%s/case.txt", dir);
        pu_write_atomic(path, buf, len); /* a record: its failure is not the case's */
    }
    free(buf);
}

/* The crane's command line, for case.txt (arguments with spaces quoted). */
static void format_command(char *const *argv, char *buf, size_t size)
{
    size_t n = 0;
    buf[0] = '\0';
    for (int i = 0; argv[i] && n < size; i++) {
        int plain = argv[i][0] && !strpbrk(argv[i], " \t'\"\\$`!*?;&|<>()");
        int k = snprintf(buf + n, size - n, "%s%s%s%s", i ? " " : "", plain ? "" : "'", argv[i],
                         plain ? "" : "'");
        if (k < 0) break;
        n += (size_t)k;
    }
}

/* The command line of case index in folder dir: argv (NULL-terminated) pointing into sets and
 * t_end, and into command as text. */
typedef struct case_command {
    char sets[SWEEP_MAX_SETS][SWEEP_SET_ARG_SIZE];
    char t_end[64];
    char *argv[2 * SWEEP_MAX_SETS + 16];
    char command[8192];
} case_command;

static void case_command_make(const sweep_run *r, long index, char *dir, case_command *cc)
{
    const sweep_spec *s = r->spec;
    int nsets = sweep_case_set_args(s, index, cc->sets);
    char **argv = cc->argv;
    int a = 0;
    argv[a++] = (char *)r->crane;
    argv[a++] = (char *)s->scene_path;
    argv[a++] = "--out";
    argv[a++] = dir;
    if (s->is_model) { /* bgsim MODEL --out DIR --quiet [--t-end T] --set PATH=VALUE ... */
        argv[a++] = "--quiet";
        if (s->t_end > 0) {
            snprintf(cc->t_end, sizeof cc->t_end, "%.17g", s->t_end);
            argv[a++] = "--t-end";
            argv[a++] = cc->t_end;
        }
    } else if (!s->case_figures) {
        argv[a++] = "--no-plots";
    }
    for (int i = 0; i < nsets; i++) {
        argv[a++] = "--set";
        argv[a++] = cc->sets[i];
    }
    argv[a] = NULL;
    format_command(argv, cc->command, sizeof cc->command);
}

/* The whole file at path (NUL-terminated, free() it) if it is a regular file of at most 64 MB,
 * or NULL. */
static char *read_text(const char *path, size_t *len)
{
    long long size = 0;
    FILE *f = sweep_open_regular(path, 64LL << 20, &size);
    if (!f) return NULL;
    char *buf = malloc((size_t)size + 1);
    size_t n = buf ? fread(buf, 1, (size_t)size, f) : 0;
    fclose(f);
    if (buf) buf[n] = '\0';
    *len = n;
    return buf;
}

int sweep_model_case_done(const sweep_run *r, long index, const char *dir)
{
    static case_command cc; /* large: not on the stack */
    char d[SWEEP_DIR_SIZE], path[SWEEP_DIR_SIZE + 32], cmd[8192];
    snprintf(d, sizeof d, "%s", dir);
    case_command_make(r, index, d, &cc);
    snprintf(path, sizeof path, "%s/case.txt", dir);
    if (!sweep_read_field(path, "command", cmd, sizeof cmd) || strcmp(cmd, cc.command)) return 0;
    snprintf(path, sizeof path, "%s/results.csv", dir);
    struct stat sb;
    if (stat(path, &sb) != 0) return 0;
    size_t nm = 0, nr = 0;
    snprintf(path, sizeof path, "%s/model.yaml", dir);
    char *model = read_text(r->spec->scene_path, &nm), *run = read_text(path, &nr);
    int same = model && run && nr >= nm && !memcmp(model, run, nm);
    free(model);
    free(run);
    return same;
}

/* The process pid runs with "--out dir" on its command line (/proc/PID/cmdline): 1; 0 if not; 1
 * when /proc cannot tell (the process exists: assumed to be the case's). */
static int runs_in(long pid, const char *dir)
{
    char path[64];
    snprintf(path, sizeof path, "/proc/%ld/cmdline", pid);
    FILE *f = fopen(path, "rb");
    if (!f) return 1;
    static char buf[65536]; /* a command line: NUL-separated arguments */
    size_t n = fread(buf, 1, sizeof buf - 1, f);
    fclose(f);
    buf[n] = '\0';
    for (size_t i = 0; i < n; i += strlen(buf + i) + 1) {
        const char *a = buf + i;
        if (!strcmp(a, "--out") && i + 6 < n && !strcmp(buf + i + 6, dir)) return 1;
        if (!strncmp(a, "--out=", 6) && !strcmp(a + 6, dir)) return 1;
    }
    return 0;
}

long sweep_case_busy(const char *dir)
{
    char path[SWEEP_DIR_SIZE + 16], status[64], pid_s[64];
    snprintf(path, sizeof path, "%s/status.txt", dir);
    if (!sweep_read_field(path, "status", status, sizeof status) || strcmp(status, "running"))
        return 0;
    if (!sweep_read_field(path, "pid", pid_s, sizeof pid_s)) return 0;
    char *end;
    long pid = strtol(pid_s, &end, 10);
    if (end == pid_s || *end || pid <= 1 || pid == (long)getpid() || pid > (long)INT_MAX) return 0;
    if (kill((pid_t)pid, 0) != 0 && errno != EPERM) return 0;
    return runs_in(pid, dir) ? pid : 0;
}

int sweep_case_start(sweep_run *r, sweep_proc *p, long index)
{
    const sweep_spec *s = r->spec;
    char dir[SWEEP_DIR_SIZE], msg[SWEEP_DIR_SIZE + 64], path[SWEEP_DIR_SIZE + 32];
    sweep_case_dir(r, index, dir, sizeof dir);
    memset(p, 0, sizeof *p);
    p->index = index;
    snprintf(p->dir, sizeof p->dir, "%s", dir);
    if (pu_mkdir_p(dir, 0777, msg, sizeof msg) != 0) {
        p->out.errno_start = errno ? errno : EIO;
        snprintf(p->out.why, sizeof p->out.why, "its folder cannot be used: %.*s",
                 (int)sizeof p->out.why - 32, msg);
        return -1;
    }
    /* a crane of an earlier sweep (killed, its cranes left running) still writes here: a second
     * one would mix their files; the case is left to it */
    long busy = sweep_case_busy(dir);
    if (busy) {
        p->out.busy_pid = busy;
        p->out.errno_start = EBUSY;
        return -1;
    }
    /* the program writes its status.txt first thing; an older one must not stand for this run,
     * nor an older results.csv for its results; the log is made anew (not a link's target) */
    static const char *const stale[] = {"status.txt", "case.txt", "results.csv", "solver_stats.txt",
                                        NULL};
    for (int i = 0; stale[i]; i++) {
        snprintf(path, sizeof path, "%s/%s", dir, stale[i]);
        unlink(path);
    }
    snprintf(path, sizeof path, "%s/%s", dir, sweep_log_name(s));
    unlink(path);
    case_command *cc = malloc(sizeof *cc);
    if (!cc) {
        p->out.errno_start = ENOMEM;
        return -1;
    }
    case_command_make(r, index, dir, cc);
    write_case_txt(r, index, dir, cc->command, NULL);
    int rc =
        sweep_proc_start(p, index, r->crane, cc->argv, dir, sweep_log_name(s), r->time_limit);
    free(cc);
    return rc;
}

void sweep_case_finish(sweep_run *r, const sweep_proc *p, sweep_row *row)
{
    sweep_row_read(r->spec, row, p->index, p->dir, &p->out);
    if (!p->out.busy_pid) write_case_txt(r, p->index, p->dir, NULL, row); /* not the other's */
}

void sweep_record(sweep_run *r, const sweep_row *row, int from_rank)
{
    if (row->index < 0 || row->index >= r->spec->ncases) return;
    r->rows[row->index] = *row;
    if (!r->have[row->index]) r->ndone++;
    r->have[row->index] = 1;
    char line[16384];
    int n = sweep_csv_row(r->spec, row, line, sizeof line);
    if (n > 0 && r->csv_fd >= 0 && !r->write_failed) {
        /* one write per row, O_APPEND: the file holds whole rows; a short write is cut back */
        off_t size = lseek(r->csv_fd, 0, SEEK_END);
        ssize_t w;
        do
            w = write(r->csv_fd, line, (size_t)n);
        while (w < 0 && errno == EINTR);
        if (w != n) {
            int e = w < 0 ? errno : ENOSPC;
            if (size >= 0 && ftruncate(r->csv_fd, size) != 0) {
            }
            r->write_failed = 1;
            snprintf(r->write_msg, sizeof r->write_msg, "cannot write %s/sweep.csv: %s", r->outdir,
                     strerror(e));
            fprintf(stderr,
                    "crane-sweep: %s (the rows stay in memory and are written at the "
                    "end)\n",
                    r->write_msg);
        }
    }
    if (r->quiet) return;
    const sweep_spec *s = r->spec;
    char params[1024] = "";
    size_t len = 0;
    for (int p = 0; p < s->nparams && len < sizeof params; p++)
        len += (size_t)snprintf(params + len, sizeof params - len, "%s%s=%s", p ? " " : "",
                                s->params[p].name, sweep_case_value(s, row->index, p));
    char where[32] = "";
    if (r->size > 1) snprintf(where, sizeof where, " (rank %d)", from_rank);
    printf("[%ld/%ld] case %ld %s: %s%s%s", r->ndone, s->ncases, row->index, params,
           sweep_status_name(row->status), row->message[0] ? ": " : "", row->message);
    if (isfinite(row->q[SQ_WALL_S])) printf(", %.1f s", row->q[SQ_WALL_S]);
    printf("%s\n", where);
    fflush(stdout);
}

static void sleep_ms(int ms)
{
    struct timespec ts = {0, (long)ms * 1000000L};
    nanosleep(&ts, NULL);
}

void sweep_engine_local(sweep_run *r)
{
    int jobs = r->jobs;
    sweep_proc *slots = calloc((size_t)jobs, sizeof *slots);
    if (!slots) {
        fprintf(stderr, "crane-sweep: out of memory\n");
        return;
    }
    long next = 0;
    int stopping = 0, hard = 0;
    for (;;) {
        int busy = 0, events = 0;
        if (sweep_signal && !stopping) stopping = 1;
        if (sweep_signal_count > 1) hard = 1;
        for (int j = 0; j < jobs; j++)
            if (slots[j].pid > 0 && stopping) sweep_proc_stop(&slots[j], (int)sweep_signal, hard);
        for (int j = 0; j < jobs; j++) {
            sweep_proc *p = &slots[j];
            if (p->pid > 0 && sweep_proc_poll(p)) {
                sweep_row row;
                sweep_case_finish(r, p, &row);
                sweep_record(r, &row, 0);
                events++;
            }
            if (p->pid <= 0 && !stopping && next < r->nqueue) {
                long index = r->queue[next++];
                r->nrun++;
                if (sweep_case_start(r, p, index) != 0) {
                    sweep_row row;
                    sweep_case_finish(r, p, &row);
                    sweep_record(r, &row, 0);
                }
                events++;
            }
            busy += p->pid > 0;
        }
        if (!busy && (stopping || next >= r->nqueue)) break;
        if (!events) sleep_ms(10);
    }
    free(slots);
}

int sweep_write_file(const char *path, const char *data, size_t len)
{
    if (pu_write_atomic(path, data, len) == 0) return 0;
    int e = errno;
    if (e != ENOSPC && e != EDQUOT) return -1;
    int fd = open(path, O_WRONLY | O_TRUNC | O_NOFOLLOW | O_CLOEXEC);
    if (fd < 0) {
        errno = e;
        return -1;
    }
    size_t done = 0;
    while (done < len) {
        ssize_t w = write(fd, data + done, len - done);
        if (w < 0 && errno == EINTR) continue;
        if (w <= 0) break;
        done += (size_t)w;
    }
    if (done < len) {
        size_t whole = done;
        while (whole > 0 && data[whole - 1] != '\n')
            whole--;
        if (ftruncate(fd, (off_t)whole) != 0) {
        }
    }
    if (close(fd) != 0 && done == len) done = 0;
    if (done < len) {
        errno = e;
        return -1;
    }
    fprintf(stderr, "crane-sweep: %s: %s: rewritten in place (not atomically)\n", path,
            strerror(e));
    return 0;
}
