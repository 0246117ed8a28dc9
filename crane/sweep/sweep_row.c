/* A case's row of sweep.csv from its folder (sweep_row.h). */
#include "sweep_row.h"

#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <signal.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/statvfs.h>
#include <sys/wait.h>
#include <unistd.h>

#include "crane_scene.h"
#include "pu_ini.h"
#include "sweep_engine.h" /* sweep_signal_count */

const sweep_quantity sweep_quantities[SWEEP_NQ] = {
    {"omega_err_max", "rad/s", "largest |omega - omega_ref| (platform rate against its reference)",
     1, 0},
    {"theta_end", "rad", "platform angle theta at the last output time", 1, 0},
    {"theta_err_end", "rad", "theta_ref - theta at the last output time", 0, 0},
    {"tip_radius_mean", "m", "mean distance of the boom tip from the slewing axis", 1, 0},
    {"defl_luff_max", "m", "largest |tip_defl_1|: tip deflection in the luffing plane", 1, 0},
    {"defl_side_max", "m", "largest |tip_defl_2|: tip deflection out of the luffing plane", 1, 0},
    {"p_high_max", "Pa", "largest pressure of the high-pressure line", 1, 0},
    {"p_low_max", "Pa", "largest pressure of the low-pressure line", 1, 0},
    {"p_min", "Pa", "smallest pressure of either line", 0, 0},
    {"rope_force_max", "N", "largest rope force", 0, 0},
    {"steps", "", "solver steps (solver_stats.txt)", 1, 0},
    {"cpu_s", "s", "CPU time of the case's crane process, user + system", 1, 1},
    {"wall_s", "s", "wall time of the case's crane process", 0, 1},
};

const char *sweep_report_name(const sweep_spec *s, int i)
{
    int q = s->report[i];
    return q < SWEEP_NQ ? sweep_quantities[q].name : s->mq[q - SWEEP_NQ].name;
}

const char *sweep_report_unit(const sweep_spec *s, int i)
{
    int q = s->report[i];
    return q < SWEEP_NQ ? sweep_quantities[q].unit : "";
}

const char *sweep_report_stem(const sweep_spec *s, int i)
{
    int q = s->report[i];
    return q < SWEEP_NQ ? sweep_quantities[q].name : s->mq[q - SWEEP_NQ].stem;
}

double sweep_report_value(const sweep_spec *s, const sweep_row *row, int i)
{
    int q = s->report[i];
    return q < SWEEP_NQ ? row->q[q] : row->mq[q - SWEEP_NQ];
}

int sweep_quantity_index(const char *name)
{
    for (int q = 0; q < SWEEP_NQ; q++)
        if (pu_ini_ieq(name, sweep_quantities[q].name)) return q;
    return -1;
}

const char *sweep_status_name(int status)
{
    static const char *const names[] = {"completed", "failed",      "invalid", "timeout",
                                        "crashed",   "interrupted", "not_run"};
    return status >= 0 && status <= SWEEP_NOT_RUN ? names[status] : "unknown";
}

static const char *sig_name(int sig)
{
    switch (sig) {
    case SIGINT:
        return "SIGINT";
    case SIGTERM:
        return "SIGTERM";
    case SIGHUP:
        return "SIGHUP";
    case SIGKILL:
        return "SIGKILL";
    case SIGSEGV:
        return "SIGSEGV";
    case SIGABRT:
        return "SIGABRT";
    case SIGBUS:
        return "SIGBUS";
    case SIGFPE:
        return "SIGFPE";
    case SIGILL:
        return "SIGILL";
    case SIGPIPE:
        return "SIGPIPE";
    case SIGXCPU:
        return "SIGXCPU";
    case SIGXFSZ:
        return "SIGXFSZ";
    default:
        return "a signal";
    }
}

/* ------------------------------------------------------------- the files ---- */

/* src into dst, cut to size - 1 characters. */
static void copy_text(char *dst, size_t size, const char *src)
{
    size_t n = strlen(src);
    if (n >= size) n = size - 1;
    memcpy(dst, src, n);
    dst[n] = '\0';
}

FILE *sweep_open_regular(const char *path, long long max, long long *size)
{
    int fd = open(path, O_RDONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC);
    if (fd < 0) return NULL;
    struct stat st;
    int e = 0;
    if (fstat(fd, &st) != 0)
        e = errno;
    else if (!S_ISREG(st.st_mode))
        e = S_ISDIR(st.st_mode) ? EISDIR : EINVAL;
    else if (max > 0 && (long long)st.st_size > max)
        e = EFBIG;
    FILE *f = e ? NULL : fdopen(fd, "r");
    if (!f) {
        if (!e) e = errno;
        close(fd);
        errno = e;
        return NULL;
    }
    if (size) *size = (long long)st.st_size;
    return f;
}

/* Read no further than the size the file had when opened (it may grow while the crane runs). */
static int within(FILE *f, long long size)
{
    long pos = ftell(f);
    return pos >= 0 && (long long)pos <= size;
}

int sweep_read_field(const char *path, const char *key, char *value, size_t size)
{
    value[0] = '\0';
    long long fsize = 0;
    FILE *f = sweep_open_regular(path, SWEEP_TEXT_MAX, &fsize);
    if (!f) return 0;
    char line[4096];
    size_t kl = strlen(key);
    int found = 0;
    while (!found && within(f, fsize) && fgets(line, sizeof line, f)) {
        if (strncmp(line, key, kl) || line[kl] != ':') continue;
        const char *v = line + kl + 1;
        while (*v == ' ')
            v++;
        snprintf(value, size, "%.*s", (int)strcspn(v, "\r\n"), v);
        found = 1;
    }
    fclose(f);
    return found;
}

/* The first non-empty line of a file (the crane's log: its error message), or "". */
static void first_line(const char *path, char *buf, size_t size)
{
    buf[0] = '\0';
    long long fsize = 0;
    FILE *f = sweep_open_regular(path, 0, &fsize);
    if (!f) return;
    if (fsize > SWEEP_TEXT_MAX) fsize = SWEEP_TEXT_MAX; /* the first line is at the top */
    char line[2048];
    while (within(f, fsize) && fgets(line, sizeof line, f)) {
        line[strcspn(line, "\r\n")] = '\0';
        if (line[0]) {
            copy_text(buf, size, line);
            break;
        }
    }
    fclose(f);
}

static double field_number(const char *path, const char *key)
{
    char v[256];
    if (!sweep_read_field(path, key, v, sizeof v) || !v[0]) return NAN;
    char *end;
    double x = strtod(v, &end);
    return end == v ? NAN : x;
}

/* The steps of solver_stats.txt's CSV part ("# CSV", a header, a row). */
static double solver_steps(const char *path)
{
    long long fsize = 0;
    FILE *f = sweep_open_regular(path, SWEEP_TEXT_MAX, &fsize);
    if (!f) return NAN;
    char line[4096], head[4096] = "";
    double steps = NAN;
    int state = 0;
    while (within(f, fsize) && fgets(line, sizeof line, f)) {
        line[strcspn(line, "\r\n")] = '\0';
        if (state == 0 && !strcmp(line, "# CSV"))
            state = 1;
        else if (state == 1) {
            snprintf(head, sizeof head, "%s", line);
            state = 2;
        } else if (state == 2) {
            int col = 0;
            char *save = NULL;
            for (char *t = strtok_r(head, ",", &save); t; t = strtok_r(NULL, ",", &save), col++)
                if (!strcmp(t, "steps")) break;
            char *p = line;
            for (int i = 0; i < col && p; i++) {
                p = strchr(p, ',');
                if (p) p++;
            }
            if (p && *p && *p != ',') steps = strtod(p, NULL);
            break;
        }
    }
    fclose(f);
    return steps;
}

enum {
    C_T,
    C_THETA,
    C_THETA_REF,
    C_OMEGA,
    C_OMEGA_REF,
    C_OMEGA_ERR,
    C_TIP_X,
    C_TIP_Y,
    C_DEFL1,
    C_DEFL2,
    C_P_HIGH,
    C_P_LOW,
    C_ROPE,
    NCOL
};
static const char *const COL_NAMES[NCOL] = {
    "t",     "theta",      "theta_ref",  "omega",  "omega_ref", "omega_err", "tip_x",
    "tip_y", "tip_defl_1", "tip_defl_2", "p_high", "p_low",     "rope_force"};

static void upd_max(double *m, double x)
{
    if (isfinite(x) && (!isfinite(*m) || x > *m)) *m = x;
}
static void upd_min(double *m, double x)
{
    if (isfinite(x) && (!isfinite(*m) || x < *m)) *m = x;
}

int sweep_parse_row(const char *line, double *v, int ncols)
{
    const char *p = line;
    int k = 0;
    for (; k < ncols; k++) {
        char *end;
        v[k] = strtod(p, &end);
        if (end == p) v[k] = NAN;
        p = strchr(end, ',');
        if (!p) return k + 1;
        p++;
    }
    return k;
}

/* The figures of results.csv (columns found by their names in the header). */
static void read_results(const char *dir, double *q)
{
    char path[SWEEP_DIR_SIZE + 32];
    snprintf(path, sizeof path, "%s/scene.ini", dir);
    crane_scene sc;
    bg_error e = {0};
    double ax = NAN, ay = NAN;
    if (crane_scene_load(&sc, path, &e) == BG_OK) ax = sc.joint_A[0], ay = sc.joint_A[1];
    snprintf(path, sizeof path, "%s/results.csv", dir);
    long long fsize = 0;
    FILE *f = sweep_open_regular(path, 0, &fsize);
    if (!f) return;
    char *line = NULL;
    size_t cap = 0;
    int col[NCOL], ncols = 0;
    for (int i = 0; i < NCOL; i++)
        col[i] = -1;
    if (getline(&line, &cap, f) > 0) {
        char *save = NULL;
        for (char *t = strtok_r(line, ",\r\n", &save); t; t = strtok_r(NULL, ",\r\n", &save)) {
            size_t n = strcspn(t, " [");
            for (int i = 0; i < NCOL; i++)
                if (strlen(COL_NAMES[i]) == n && !strncmp(t, COL_NAMES[i], n)) col[i] = ncols;
            ncols++;
        }
    }
    double *v = calloc((size_t)ncols + 1, sizeof *v), rsum = 0, last[NCOL];
    long rn = 0, rows = 0;
    for (int i = 0; i < NCOL; i++)
        last[i] = NAN;
    double omax = NAN, d1 = NAN, d2 = NAN, ph = NAN, pl = NAN, pmin = NAN, rope = NAN;
    while (v && within(f, fsize) && sweep_signal_count < 2 && getline(&line, &cap, f) > 0) {
        if (sweep_parse_row(line, v, ncols) < ncols) continue; /* not a whole row */
        rows++;
#define V(c) (col[c] >= 0 ? v[col[c]] : NAN)
        for (int i = 0; i < NCOL; i++)
            last[i] = V(i);
        double oe = col[C_OMEGA_ERR] >= 0 ? V(C_OMEGA_ERR) : V(C_OMEGA_REF) - V(C_OMEGA);
        upd_max(&omax, fabs(oe));
        upd_max(&d1, fabs(V(C_DEFL1)));
        upd_max(&d2, fabs(V(C_DEFL2)));
        upd_max(&ph, V(C_P_HIGH));
        upd_max(&pl, V(C_P_LOW));
        upd_min(&pmin, V(C_P_HIGH));
        upd_min(&pmin, V(C_P_LOW));
        upd_max(&rope, V(C_ROPE));
        double r = hypot(V(C_TIP_X) - ax, V(C_TIP_Y) - ay);
        if (isfinite(r)) rsum += r, rn++;
#undef V
    }
    free(v);
    free(line);
    fclose(f);
    if (rows == 0) return;
    q[SQ_OMEGA_ERR_MAX] = omax;
    q[SQ_THETA_END] = last[C_THETA];
    q[SQ_THETA_ERR_END] = last[C_THETA_REF] - last[C_THETA];
    q[SQ_TIP_RADIUS_MEAN] = rn ? rsum / (double)rn : NAN;
    q[SQ_DEFL_LUFF_MAX] = d1;
    q[SQ_DEFL_SIDE_MAX] = d2;
    q[SQ_P_HIGH_MAX] = ph;
    q[SQ_P_LOW_MAX] = pl;
    q[SQ_P_MIN] = pmin;
    q[SQ_ROPE_FORCE_MAX] = rope;
}

/* The case's folder dir has no room left: its file system has less than SWEEP_ROOM_MIN bytes
 * or no inode free, or the crane's reason or log says so (ENOSPC, EDQUOT). 1 with what was
 * found in room. */
#define SWEEP_ROOM_MIN 16384
static int no_room(const char *dir, const char *reason, const char *logline, char *room,
                   size_t size)
{
    static const char *const says[] = {"No space left on device", "Disk quota exceeded"};
    for (int i = 0; i < 2; i++)
        if (strstr(reason, says[i]) || strstr(logline, says[i])) {
            snprintf(room, size, "%s", says[i]);
            return 1;
        }
    struct statvfs v;
    if (statvfs(dir, &v) != 0) return 0;
    unsigned long long avail = (unsigned long long)v.f_bavail * (unsigned long long)v.f_frsize;
    if (avail < SWEEP_ROOM_MIN) {
        snprintf(room, size, "no space left on device: %llu bytes free", avail);
        return 1;
    }
    if (v.f_files > 0 && v.f_favail == 0) {
        snprintf(room, size, "no space left on device: no inode free");
        return 1;
    }
    return 0;
}

/* ------------------------------------------------------------------ the row ---- */

#if defined(__GNUC__)
__attribute__((format(printf, 2, 3)))
#endif
static void
set_message(sweep_row *row, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(row->message, sizeof row->message, fmt, ap);
    va_end(ap);
    for (char *p = row->message; *p; p++) /* one line */
        if ((unsigned char)*p < 32 || *p == 127) *p = ' ';
}

static void row_init(sweep_row *row, long index)
{
    memset(row, 0, sizeof *row);
    row->index = index;
    row->exit_code = -1;
    row->t_reached = NAN;
    for (int q = 0; q < SWEEP_NQ; q++)
        row->q[q] = NAN;
    for (int q = 0; q < SWEEP_MAX_REPORT; q++)
        row->mq[q] = NAN;
}

void sweep_row_not_run(sweep_row *row, long index, const char *why)
{
    row_init(row, index);
    row->status = SWEEP_NOT_RUN;
    set_message(row, "%s", why);
}

/* The figures of a completed case's results.csv: the crane's quantities or the model's. */
static void read_figures(const sweep_spec *s, const char *dir, sweep_row *row)
{
    if (s->is_model)
        sweep_model_results(s, dir, row->mq);
    else
        read_results(dir, row->q);
}

void sweep_row_read(const sweep_spec *s, sweep_row *row, long index, const char *dir,
                    const sweep_outcome *o)
{
    const char *prog = sweep_program(s);
    row_init(row, index);
    char status_path[SWEEP_DIR_SIZE + 32], log_path[SWEEP_DIR_SIZE + 32],
        stats_path[SWEEP_DIR_SIZE + 32], case_path[SWEEP_DIR_SIZE + 32];
    snprintf(status_path, sizeof status_path, "%s/status.txt", dir);
    snprintf(log_path, sizeof log_path, "%s/%s", dir, sweep_log_name(s));
    snprintf(stats_path, sizeof stats_path, "%s/solver_stats.txt", dir);
    snprintf(case_path, sizeof case_path, "%s/case.txt", dir);
    char cstatus[64] = "", reason[1024] = "", logline[1024] = "";
    sweep_read_field(status_path, "status", cstatus, sizeof cstatus);
    sweep_read_field(status_path, "reason", reason, sizeof reason);
    if (!strcmp(reason, "-")) reason[0] = '\0';
    first_line(log_path, logline, sizeof logline);
    double tr = field_number(status_path, "t_reached");

    if (!o) { /* found completed by --resume */
        row->status = SWEEP_COMPLETED;
        row->exit_code = 0;
        row->t_reached = tr;
        row->q[SQ_STEPS] = solver_steps(stats_path);
        row->q[SQ_CPU_S] = field_number(case_path, "cpu_s");
        row->q[SQ_WALL_S] = field_number(case_path, "wall_s");
        read_figures(s, dir, row);
        return;
    }
    row->q[SQ_CPU_S] = o->cpu_s;
    row->q[SQ_WALL_S] = o->wall_s;
    if (!o->started && o->busy_pid) {
        row->status = SWEEP_NOT_RUN;
        set_message(row,
                    "not run: its folder is in use by the %s (pid %ld) of an earlier sweep, still "
                    "running (status.txt: running); run --resume once it has ended, or stop it",
                    prog, o->busy_pid);
        return;
    }
    if (!o->started) {
        row->status = SWEEP_FAILED;
        set_message(row, "the %s program could not be started: %s", prog,
                    o->why[0] ? o->why : strerror(o->errno_start));
        return;
    }
    int ws = o->wait_status, code = -1, sig = 0;
    if (WIFEXITED(ws)) code = WEXITSTATUS(ws);
    if (WIFSIGNALED(ws)) sig = WTERMSIG(ws);
    row->exit_code = code >= 0 ? code : 128 + sig;
    if (code == 2) { /* refused: the program wrote nothing (the folder's files are not its) */
        row->status = SWEEP_INVALID;
        if (logline[0])
            set_message(row, "%s", logline);
        else
            set_message(row, "the %s refused the case (exit status 2)", prog);
        return;
    }
    row->t_reached = tr;
    row->q[SQ_STEPS] = solver_steps(stats_path);
    char at[64] = "";
    if (isfinite(tr)) snprintf(at, sizeof at, " at t = %.9g s", tr);
    if (o->timed_out) {
        row->status = SWEEP_TIMEOUT;
        if (sig)
            set_message(row, "time limit of %g s: SIGTERM, then killed by %s%s%s", o->time_limit,
                        sig_name(sig), o->killed ? " 5 s later" : "",
                        !strcmp(cstatus, "running") ? " (status.txt: running)" : "");
        else
            set_message(row, "stopped at the time limit of %g s%s (%s)", o->time_limit, at,
                        reason[0] ? reason : "SIGTERM");
        return;
    }
    if (o->stopped_by) {
        row->status = SWEEP_INTERRUPTED;
        set_message(row, "the sweep was stopped by %s: the case %s%s", sig_name(o->stopped_by),
                    sig ? "was killed by " : "stopped", sig ? sig_name(sig) : at);
        return;
    }
    if (sig == SIGXFSZ) { /* a write beyond RLIMIT_FSIZE: the limit, not the program */
        row->status = SWEEP_FAILED;
        set_message(row,
                    "a file of the case outgrew the file size limit (SIGXFSZ: ulimit -f, "
                    "RLIMIT_FSIZE)%s",
                    isfinite(tr) ? at : "");
        return;
    }
    if (sig) {
        row->status = SWEEP_CRASHED;
        set_message(row, "the %s was ended by %s (signal %d)%s%s", prog, sig_name(sig), sig,
                    !strcmp(cstatus, "running") ? "; status.txt still says running" : "",
                    isfinite(tr) ? at : "");
        return;
    }
    if (code == 0 && !strcmp(cstatus, "completed")) {
        row->status = SWEEP_COMPLETED;
        read_figures(s, dir, row);
        return;
    }
    if (code > 128 && code < 128 + 65) {
        row->status = SWEEP_INTERRUPTED;
        set_message(row, "%s", reason[0] ? reason : "interrupted by a signal");
        return;
    }
    if (code == 126 || code == 127) {
        row->status = SWEEP_FAILED;
        set_message(row, "the %s program could not be run (exit status %d)%s%s", prog, code,
                    logline[0] ? ": " : "", logline);
        return;
    }
    char room[128];
    if (code != 0 && no_room(dir, reason, logline, room, sizeof room)) {
        row->status = SWEEP_FAILED; /* the disk, not the program: status.txt may not be final */
        set_message(row, "the disk is full (%s): the %s ended with exit status %d%s%s%s", room,
                    prog, code,
                    !strcmp(cstatus, "running") ? ", status.txt still saying running"
                    : !cstatus[0]               ? " without a status.txt"
                                                : "",
                    reason[0] || logline[0] ? ": " : "", reason[0] ? reason : logline);
        return;
    }
    if (!strcmp(cstatus, "running") || !cstatus[0]) {
        row->status = SWEEP_CRASHED;
        set_message(row, "the %s ended with exit status %d %s%s%s", prog, code,
                    cstatus[0] ? "and status.txt still saying running" : "without a status.txt",
                    logline[0] ? ": " : "", logline);
        return;
    }
    row->status = SWEEP_FAILED;
    if (code == 0)
        set_message(row, "exit status 0 but status.txt says %s%s%s", cstatus, reason[0] ? ": " : "",
                    reason);
    else
        set_message(row, "%s", reason[0] ? reason : logline[0] ? logline : "failed");
}

/* ------------------------------------------------------------------ the CSV ---- */

#if defined(__GNUC__)
__attribute__((format(printf, 4, 5)))
#endif
static int
put(char *buf, size_t size, size_t *len, const char *fmt, ...)
{
    if (*len >= size) return -1;
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(buf + *len, size - *len, fmt, ap);
    va_end(ap);
    if (n < 0 || (size_t)n >= size - *len) {
        *len = size;
        return -1;
    }
    *len += (size_t)n;
    return 0;
}

/* A field quoted as CSV wants it when it holds a comma, a quote or a space at its ends. */
static void put_text(char *buf, size_t size, size_t *len, const char *text)
{
    int plain = !strpbrk(text, ",\"\n\r");
    if (plain) {
        put(buf, size, len, "%s", text);
        return;
    }
    put(buf, size, len, "\"");
    for (const char *p = text; *p; p++)
        if (*p == '"')
            put(buf, size, len, "\"\"");
        else
            put(buf, size, len, "%c", *p);
    put(buf, size, len, "\"");
}

int sweep_csv_header(const sweep_spec *s, char *buf, size_t size)
{
    size_t len = 0;
    put(buf, size, &len, "case");
    for (int p = 0; p < s->nparams; p++)
        put(buf, size, &len, ",%s", s->params[p].name);
    put(buf, size, &len, ",status,message,t_reached");
    for (int i = 0; i < s->nreport; i++)
        put(buf, size, &len, ",%s", sweep_report_name(s, i));
    put(buf, size, &len, "\n");
    return len < size ? (int)len : -1;
}

int sweep_csv_row(const sweep_spec *s, const sweep_row *row, char *buf, size_t size)
{
    size_t len = 0;
    put(buf, size, &len, "%ld", row->index);
    for (int p = 0; p < s->nparams; p++) {
        put(buf, size, &len, ",");
        put_text(buf, size, &len, sweep_case_value(s, row->index, p));
    }
    put(buf, size, &len, ",%s,", sweep_status_name(row->status));
    put_text(buf, size, &len, row->message);
    if (isfinite(row->t_reached))
        put(buf, size, &len, ",%.9g", row->t_reached);
    else
        put(buf, size, &len, ",");
    for (int i = 0; i < s->nreport; i++) {
        int q = s->report[i];
        double x = sweep_report_value(s, row, i);
        if (!isfinite(x))
            put(buf, size, &len, ",");
        else if (q == SQ_STEPS)
            put(buf, size, &len, ",%.0f", x);
        else if (q == SQ_CPU_S || q == SQ_WALL_S)
            put(buf, size, &len, ",%.3f", x);
        else
            put(buf, size, &len, ",%.10g", x);
    }
    put(buf, size, &len, "\n");
    return len < size ? (int)len : -1;
}
