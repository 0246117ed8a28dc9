/* results.csv of a run (rn_run.h): one row per output time, formatted into a buffer of 64 kB
 * and written with write(2) when the buffer is full or a second has passed since the last
 * write: no write or flush per row. A failed write is cut back to the last whole row
 * (ftruncate), so that the file holds whole rows at every moment; a signal stops the run
 * between two steps and the rows formatted until then are written whole (rn_csv_close). */
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "rn_run.h"

#define CSV_BUF_SIZE (1 << 16)

/* a row's text at most: its numbers, the commas and the newline */
static size_t row_max(const rn_run *r)
{
    return (RN_FMT_SIZE + 1) * (size_t)r->csv_ncols + 1;
}

int rn_csv_open(rn_run *r, const char *const *names, int ncols)
{
    char path[RN_PATH_SIZE];
    rn_path_in(r, "results.csv", path, sizeof path);
    size_t head = 1;
    for (int i = 0; i < ncols; i++)
        head += strlen(names[i]) + 1;
    r->csv_ncols = ncols;
    r->csv_cap = CSV_BUF_SIZE;
    if (r->csv_cap < head + 2 * row_max(r)) r->csv_cap = head + 2 * row_max(r);
    r->csv_buf = malloc(r->csv_cap);
    if (!r->csv_buf) return rn_fail_run(r, "memory", "out of memory");
    r->csv_len = 0;
    r->csv_fd = open(path, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (r->csv_fd < 0) return rn_write_failed(r, path, errno);
    for (int i = 0; i < ncols; i++)
        r->csv_len += (size_t)snprintf(r->csv_buf + r->csv_len, r->csv_cap - r->csv_len, "%s%s",
                                       i ? "," : "", names[i]);
    r->csv_buf[r->csv_len++] = '\n';
    return 0;
}

/* Writes the rows formatted so far to results.csv. 0, or the failure (RN_EXIT_RUN), after which
 * the file is cut back to the last whole row that reached it. */
int rn_csv_flush(rn_run *r)
{
    if (r->csv_len == 0) return 0;
    size_t done = 0;
    int e = 0;
    while (done < r->csv_len && !e) {
        ssize_t w = write(r->csv_fd, r->csv_buf + done, r->csv_len - done);
        if (w > 0)
            done += (size_t)w;
        else if (w == 0 || errno != EINTR)
            e = w == 0 ? EIO : errno;
    }
    if (e) {
        /* keep the whole lines written (the first holds the header), cut the rest */
        size_t keep = done, rows = 0, start = 0;
        while (keep > 0 && r->csv_buf[keep - 1] != '\n')
            keep--;
        for (size_t i = 0; i < keep; i++)
            if (r->csv_buf[i] == '\n') {
                if (i + 1 < keep) start = i + 1; /* the last line kept starts here */
                rows++;
            }
        if (r->csv_size == 0 && rows > 0) rows--; /* the header */
        if (rows > 0) {
            r->rows_disk += (long)rows;
            r->t_disk = strtod(r->csv_buf + start, NULL);
        }
        r->csv_size += (off_t)keep;
        if (ftruncate(r->csv_fd, r->csv_size) != 0 || lseek(r->csv_fd, r->csv_size, SEEK_SET) < 0)
            e = errno;
        r->csv_len = 0;
        char path[RN_PATH_SIZE], what[RN_PATH_SIZE + 32], msg[256];
        rn_path_in(r, "results.csv", path, sizeof path);
        snprintf(what, sizeof what, "cannot write %s", path);
        snprintf(msg, sizeof msg, "%s (%ld whole rows kept, up to t = %.9g s)", strerror(e),
                 r->rows_disk, r->rows_disk ? r->t_disk : 0.0);
        return rn_fail_run(r, what, msg);
    }
    r->csv_size += (off_t)r->csv_len;
    r->csv_len = 0;
    r->rows_disk = r->rows;
    r->t_disk = r->t_row;
    r->csv_written = rn_wall_now();
    if (rn_phase() == RN_PHASE_LOOP) rn_arm_loop(r);
    return 0;
}

/* One row: the numbers as %.12g (rn_fmt_g12). */
int rn_csv_row(rn_run *r, double t, const double *out)
{
    if (r->csv_cap - r->csv_len < row_max(r)) {
        int rc = rn_csv_flush(r);
        if (rc) return rc;
    }
    char *p = r->csv_buf + r->csv_len;
    size_t n = (size_t)rn_fmt_g12(p, t);
    for (int i = 1; i < r->csv_ncols; i++) {
        p[n++] = ',';
        n += (size_t)rn_fmt_g12(p + n, out[i]);
    }
    p[n++] = '\n';
    r->csv_len += n;
    r->rows++;
    r->t_row = t;
    return rn_wall_now() - r->csv_written >= 1.0 ? rn_csv_flush(r) : 0;
}

/* Writes the rows still buffered, makes them durable and closes results.csv. */
int rn_csv_close(rn_run *r)
{
    if (r->csv_fd < 0) return 0;
    char path[RN_PATH_SIZE];
    rn_path_in(r, "results.csv", path, sizeof path);
    int rc = rn_csv_flush(r);
    if (!rc && fsync(r->csv_fd) != 0) rc = rn_write_failed(r, path, errno);
    if (close(r->csv_fd) != 0 && !rc) rc = rn_write_failed(r, path, errno);
    r->csv_fd = -1;
    free(r->csv_buf);
    r->csv_buf = NULL;
    return rc;
}
