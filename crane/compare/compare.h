/* crane-compare's parts (private to the program, prefix cc_): the controllers it compares, the
 * metrics it reads from each run's results.csv, the table and the figures. compare.c has the
 * program's contract (options, files, exit statuses). */
#ifndef CC_COMPARE_H
#define CC_COMPARE_H

#include <stdio.h>

#define CC_MAX_SETS 8
#define CC_MAX_CTL 16
#define CC_PATH 4096

/* A controller: a name and the model parameters that switch it on (bgsim --set PATH=VALUE).
 * "@f" in a value stands for the shaper's frequency (Hz). */
typedef struct cc_controller {
    const char *name, *what;
    const char *sets[CC_MAX_SETS];
} cc_controller;

extern const cc_controller cc_controllers[];
extern const int cc_ncontrollers;

/* The metrics of one run (NaN where a column is missing; sway_settle_s infinite when the sway
 * never stays within the band). */
typedef struct cc_metrics {
    double t_ref_end;                    /* s, the reference's last motion */
    double theta_err_max, theta_err_rms; /* rad, during the motion (t <= t_ref_end) */
    double omega_err_max, omega_err_rms; /* rad/s, during the motion */
    double theta_end_err;                /* rad, at the last row */
    double sway_max_m;                   /* m, the load's largest distance from rest, all along */
    double sway_residual_m;              /* m, the largest after the reference stops */
    double swing_residual_deg;           /* deg, the largest swing angle after it stops */
    double sway_settle_s;                /* s after the stop until it stays within the band */
    double defl_luff_max, defl_side_max; /* m, the tip's deflections (largest |.|) */
    double p_high_max, p_low_max, p_max; /* Pa */
    double energy_j;                     /* J, the pump's hydraulic energy, power > 0 integrated */
    double x_max;                        /* the largest |pump displacement| */
} cc_metrics;

/* The band of sway_settle_s (m). */
#define CC_SETTLE_BAND 0.1

/* results.csv read whole: names[ncols], values row by row (nrows x ncols). */
typedef struct cc_table {
    int ncols, nrows;
    char **names;
    double *v;
} cc_table;

/* 0, or -1 with the reason in msg. */
int cc_table_read(const char *path, cc_table *t, char *msg, size_t size);
void cc_table_free(cc_table *t);
/* The column named name, -1 if none. */
int cc_table_col(const cc_table *t, const char *name);

/* The metrics of a run's table. 0, or -1 (msg: a column it needs is missing). */
int cc_metrics_of(const cc_table *t, cc_metrics *m, char *msg, size_t size);

/* The metrics' names (the CSV's columns after `controller`), their units and their values. */
extern const char *const cc_metric_names[];
extern const char *const cc_metric_units[];
extern const int cc_nmetrics;
void cc_metric_values(const cc_metrics *m, double *v);

#endif
