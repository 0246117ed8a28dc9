/* The crane program's results.csv (crane_program.h): one row per output time, formatted into a
 * buffer of 64 kB and written with write(2) when the buffer is full or a second has passed since
 * the last write: no write or flush per row. A failed write is cut back to the last whole row
 * (ftruncate), so that the file holds whole rows at every moment; a signal stops the run between
 * two steps and the rows formatted until then are written whole (cp_csv_close). */
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "crane_program.h"

#define CSV_BUF_SIZE (1 << 16)
/* a row's text at most: its numbers, the commas and the newline */
#define CSV_ROW_MAX ((CP_FMT_SIZE + 1) * CRANE_NOUT + 1)

/* Column of output a, or of b if the model has no a (-1: neither). */
static int col_any(const char *a, const char *b)
{
    int c = crane_output_index(a);
    return c >= 0 || !b ? c : crane_output_index(b);
}

int cp_csv_open(cp_run *r)
{
    char path[CP_PATH_SIZE];
    cp_path_in(r, "results.csv", path, sizeof path);
    r->col_d1 = col_any("tip_defl_1", "defl_luff");
    r->col_d2 = col_any("tip_defl_2", "defl_side");
    r->col_tx = crane_output_index("tip_x");
    r->col_ty = crane_output_index("tip_y");
    r->csv_buf = malloc(CSV_BUF_SIZE);
    if (!r->csv_buf) return cp_fail_run(r, "memory", "out of memory");
    r->csv_cap = CSV_BUF_SIZE;
    r->csv_len = 0;
    r->csv_fd = open(path, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (r->csv_fd < 0) return cp_write_failed(r, path, errno);
    for (int i = 0; i < CRANE_NOUT; i++)
        r->csv_len += (size_t)snprintf(r->csv_buf + r->csv_len, r->csv_cap - r->csv_len, "%s%s",
                                       i ? "," : "", crane_output_names[i]);
    r->csv_buf[r->csv_len++] = '\n';
    return 0;
}

/* Writes the rows formatted so far to results.csv. 0, or the failure (CP_EXIT_RUN), after which
 * the file is cut back to the last whole row that reached it. */
int cp_csv_flush(cp_run *r)
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
        char path[CP_PATH_SIZE], what[CP_PATH_SIZE + 32], msg[256];
        cp_path_in(r, "results.csv", path, sizeof path);
        snprintf(what, sizeof what, "cannot write %s", path);
        snprintf(msg, sizeof msg, "%s (%ld whole rows kept, up to t = %.9g s)", strerror(e),
                 r->rows_disk, r->rows_disk ? r->t_disk : 0.0);
        return cp_fail_run(r, what, msg);
    }
    r->csv_size += (off_t)r->csv_len;
    r->csv_len = 0;
    r->rows_disk = r->rows;
    r->t_disk = r->t_row;
    r->csv_written = cp_wall_now();
    if (cp_phase() == CP_PHASE_LOOP) cp_arm_loop(r);
    return 0;
}

/* One row: the numbers as %.12g (cp_fmt_g12), and the peaks and reach the figures and the
 * summary use. */
int cp_csv_row(cp_run *r, double t, const double *out)
{
    if (r->csv_cap - r->csv_len < CSV_ROW_MAX) {
        int rc = cp_csv_flush(r);
        if (rc) return rc;
    }
    char *p = r->csv_buf + r->csv_len;
    size_t n = (size_t)cp_fmt_g12(p, t);
    for (int i = 1; i < CRANE_NOUT; i++) {
        p[n++] = ',';
        n += (size_t)cp_fmt_g12(p + n, out[i]);
    }
    p[n++] = '\n';
    r->csv_len += n;
    r->rows++;
    r->t_row = t;
    int d1 = r->col_d1, d2 = r->col_d2, tx = r->col_tx, ty = r->col_ty;
    if (d1 >= 0 && fabs(out[d1]) > r->peak[0]) r->peak[0] = fabs(out[d1]);
    if (d2 >= 0 && fabs(out[d2]) > r->peak[1]) r->peak[1] = fabs(out[d2]);
    if (tx >= 0 && ty >= 0) {
        double ex = fabs(out[tx] - r->scene.joint_A[0]), ey = fabs(out[ty] - r->scene.joint_A[1]);
        if (isfinite(ex) && ex > r->reach) r->reach = ex;
        if (isfinite(ey) && ey > r->reach) r->reach = ey;
    }
    if (r->rows == 1) memcpy(r->first_out, out, sizeof r->first_out);
    memcpy(r->final_out, out, sizeof r->final_out);
    r->final_out[0] = t;
    r->have_final = 1;
    return cp_wall_now() - r->csv_written >= 1.0 ? cp_csv_flush(r) : 0;
}

/* Writes the rows still buffered, makes them durable and closes results.csv. */
int cp_csv_close(cp_run *r)
{
    if (r->csv_fd < 0) return 0;
    char path[CP_PATH_SIZE];
    cp_path_in(r, "results.csv", path, sizeof path);
    int rc = cp_csv_flush(r);
    if (!rc && fsync(r->csv_fd) != 0) rc = cp_write_failed(r, path, errno);
    if (close(r->csv_fd) != 0 && !rc) rc = cp_write_failed(r, path, errno);
    r->csv_fd = -1;
    free(r->csv_buf);
    r->csv_buf = NULL;
    return rc;
}
