/* MEBDFI's published run statistics beside our solver's (bench_mebdfi.h). */
#include "bench_mebdfi.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bench_util.h"

/* The end statistics printed by J. R. Cash's test drivers for MEBDFI (cranki.f, pumpi.f,
 * transi.f, chemakzoi.f, nandi.f: output files cranki.out, pumpi.out, transi.out, akzoi.out,
 * nandi.out) and MEBDFDAE (pendul2.f: pendul2.res), copied from docs/mebdfi_stats.md, which names
 * their source (the GitHub repository fons/JavaOdeInt, folders fodeint/mebdfi/txt and
 * fodeint/mebdfdae/txt, commit aadacb92feb292409ea755ddccff65345ec5b337, BSD-3-Clause) and
 * explains each column. Fields: problem, rtol, atol, steps, failed steps, residual (function)
 * evaluations, Jacobians, LU factorizations, back-solves, highest order, the driver's scd. */
static const mebdfi_stat table[] = {
    {"crank", 1e-2, 1e-2, 75, 5, 584, 12, 12, 283, 3, -0.85},
    {"crank", 3.16e-3, 3.16e-3, 103, 8, 942, 22, 22, 391, 3, -0.52},
    {"crank", 1e-3, 1e-3, 146, 7, 1100, 22, 22, 549, 3, -0.03},
    {"crank", 3.16e-4, 3.16e-4, 278, 6, 1943, 38, 38, 992, 6, -0.19},
    {"crank", 1e-4, 1e-4, 258, 13, 1681, 29, 29, 955, 4, -0.03},
    {"crank", 3.16e-5, 3.16e-5, 456, 12, 2539, 36, 36, 1638, 4, -1.07},
    {"crank", 1e-5, 1e-5, 1941, 10, 10337, 155, 155, 6461, 7, -0.93},
    {"crank", 3.16e-6, 3.16e-6, 2587, 6, 13056, 183, 183, 8480, 7, -0.10},
    {"crank", 1e-6, 1e-6, 3463, 4, 15353, 160, 160, 11352, 7, 0.08},
    {"crank", 3.16e-7, 3.16e-7, 3934, 0, 19515, 268, 268, 12814, 7, 0.28},
    {"crank", 1e-7, 1e-7, 4709, 1, 23678, 334, 334, 15327, 7, 1.21},
    {"crank", 3.16e-8, 3.16e-8, 5372, 1, 26732, 369, 369, 17506, 7, 1.87},
    {"crank", 1e-8, 1e-8, 6326, 1, 27445, 274, 274, 20594, 7, 1.75},
    {"crank", 3.16e-9, 3.16e-9, 7009, 1, 26539, 149, 149, 22813, 7, 1.75},
    {"crank", 1e-9, 1e-9, 8316, 1, 37327, 410, 410, 27076, 7, 1.84},
    {"pump", 1e-1, 1e-7, 452, 187, 4201, 239, 239, 1771, 1, 0.14},
    {"pump", 3.16e-2, 3.16e-8, 684, 252, 6221, 350, 350, 2681, 1, 2.94},
    {"pump", 1e-2, 1e-8, 812, 286, 7802, 450, 450, 3262, 1, 15.40},
    {"pump", 3.16e-3, 3.16e-9, 1031, 341, 10282, 589, 589, 4352, 2, 15.40},
    {"pump", 1e-3, 1e-9, 1156, 350, 10699, 557, 557, 5089, 3, 15.40},
    {"pump", 3.16e-4, 3.16e-10, 1572, 460, 14654, 774, 774, 6874, 2, 15.40},
    {"pump", 1e-4, 1e-10, 1524, 408, 13179, 660, 660, 6539, 3, 15.40},
    {"pump", 3.16e-5, 3.16e-11, 1899, 530, 17886, 924, 924, 8606, 2, 15.40},
    {"pump", 1e-5, 1e-11, 1754, 468, 15221, 769, 769, 7491, 3, 15.40},
    {"pump", 3.16e-6, 3.16e-12, 2289, 588, 20086, 1022, 1022, 9826, 3, 15.40},
    {"pump", 1e-6, 1e-12, 2323, 546, 19179, 916, 916, 9979, 4, 15.40},
    {"pump", 3.16e-7, 3.16e-13, 2747, 659, 23322, 1159, 1159, 11692, 4, 15.40},
    {"pump", 1e-7, 1e-13, 2689, 601, 21633, 1032, 1032, 11273, 4, 15.40},
    {"pump", 3.16e-8, 3.16e-14, 3232, 708, 26965, 1305, 1305, 13875, 6, 15.40},
    {"pump", 1e-8, 1e-14, 3197, 667, 25813, 1182, 1182, 13953, 5, 15.40},
    {"pump", 3.16e-9, 3.16e-15, 3707, 743, 29843, 1392, 1392, 15883, 6, 15.40},
    {"pump", 1e-9, 1e-15, 3732, 729, 28934, 1302, 1302, 15874, 6, 15.40},
    {"transamp", 1e-2, 1e-2, 734, 113, 5411, 225, 225, 3385, 5, 1.12},
    {"transamp", 3.16e-3, 3.16e-3, 899, 104, 6041, 221, 221, 4051, 5, 3.13},
    {"transamp", 1e-3, 1e-3, 1072, 98, 6579, 224, 224, 4562, 7, 3.13},
    {"transamp", 3.16e-4, 3.16e-4, 1309, 126, 7819, 268, 268, 5406, 6, 3.95},
    {"transamp", 1e-4, 1e-4, 1481, 104, 8231, 246, 246, 6016, 7, 4.58},
    {"transamp", 3.16e-5, 3.16e-5, 1867, 123, 10054, 297, 297, 7380, 7, 5.03},
    {"transamp", 1e-5, 1e-5, 2032, 101, 10505, 289, 289, 7903, 7, 5.26},
    {"transamp", 3.16e-6, 3.16e-6, 2350, 96, 11845, 306, 306, 9090, 7, 6.61},
    {"transamp", 1e-6, 1e-6, 2748, 123, 13662, 375, 375, 10286, 7, 6.43},
    {"transamp", 3.16e-7, 3.16e-7, 3078, 106, 15246, 373, 373, 11888, 7, 7.04},
    {"transamp", 1e-7, 1e-7, 3468, 113, 16814, 399, 399, 13222, 7, 7.26},
    {"transamp", 3.16e-8, 3.16e-8, 4022, 116, 18821, 441, 441, 14851, 7, 7.59},
    {"transamp", 1e-8, 1e-8, 4592, 97, 21022, 488, 488, 16629, 7, 7.59},
    {"transamp", 3.16e-9, 3.16e-9, 5166, 95, 23487, 536, 536, 18662, 7, 8.21},
    {"transamp", 1e-9, 1e-9, 5952, 110, 25877, 624, 624, 20260, 7, 8.92},
    {"transamp", 3.16e-10, 3.16e-10, 6683, 89, 28284, 656, 656, 22379, 7, 10.14},
    {"transamp", 1e-10, 1e-10, 7767, 54, 32162, 713, 713, 25744, 7, 10.12},
    {"chemakzo", 1e-2, 1e-2, 24, 0, 76, 11, 11, 75, 2, 1.65},
    {"chemakzo", 3.16e-3, 3.16e-3, 28, 0, 92, 8, 8, 91, 3, 2.01},
    {"chemakzo", 1e-3, 1e-3, 35, 1, 121, 9, 9, 120, 3, 1.84},
    {"chemakzo", 3.16e-4, 3.16e-4, 43, 2, 147, 11, 11, 146, 3, 2.90},
    {"chemakzo", 1e-4, 1e-4, 50, 0, 162, 12, 12, 161, 4, 3.88},
    {"chemakzo", 3.16e-5, 3.16e-5, 59, 1, 200, 12, 12, 199, 4, 4.51},
    {"chemakzo", 1e-5, 1e-5, 73, 1, 250, 12, 12, 249, 5, 4.87},
    {"chemakzo", 3.16e-6, 3.16e-6, 87, 2, 306, 12, 12, 305, 5, 5.66},
    {"chemakzo", 1e-6, 1e-6, 97, 2, 335, 16, 16, 334, 6, 5.69},
    {"chemakzo", 3.16e-7, 3.16e-7, 110, 1, 383, 16, 16, 382, 6, 6.28},
    {"chemakzo", 1e-7, 1e-7, 129, 1, 446, 18, 18, 445, 7, 7.05},
    {"chemakzo", 3.16e-8, 3.16e-8, 139, 1, 453, 19, 19, 452, 7, 7.70},
    {"chemakzo", 1e-8, 1e-8, 157, 1, 522, 24, 24, 521, 7, 7.96},
    {"chemakzo", 3.16e-9, 3.16e-9, 180, 1, 607, 24, 24, 606, 7, 8.51},
    {"chemakzo", 1e-9, 1e-9, 201, 0, 677, 24, 24, 676, 7, 8.52},
    {"chemakzo", 3.16e-10, 3.16e-10, 229, 0, 765, 28, 28, 764, 7, 9.65},
    {"chemakzo", 1e-10, 1e-10, 273, 1, 916, 32, 32, 915, 7, 9.76},
    {"nand", 1e-1, 1e-1, 237, 21, 2500, 109, 109, 849, 1, 2.55},
    {"nand", 3.16e-2, 3.16e-2, 295, 26, 2898, 119, 119, 1097, 2, 2.28},
    {"nand", 1e-2, 1e-2, 399, 36, 3856, 151, 151, 1575, 2, 2.72},
    {"nand", 3.16e-3, 3.16e-3, 501, 39, 4566, 172, 172, 1970, 3, 2.95},
    {"nand", 1e-3, 1e-3, 657, 70, 5988, 228, 228, 2552, 3, 3.12},
    {"nand", 3.16e-4, 3.16e-4, 814, 73, 6844, 247, 247, 3123, 4, 3.66},
    {"nand", 1e-4, 1e-4, 1034, 113, 8878, 319, 319, 4077, 4, 4.30},
    {"nand", 3.16e-5, 3.16e-5, 1317, 144, 11055, 387, 387, 5234, 5, 4.58},
    {"nand", 1e-5, 1e-5, 1656, 188, 13514, 464, 464, 6538, 6, 4.99},
    {"nand", 3.16e-6, 3.16e-6, 2040, 237, 16394, 556, 556, 8038, 5, 6.30},
    {"nand", 1e-6, 1e-6, 2460, 268, 18905, 622, 622, 9559, 6, 6.22},
    {"nand", 3.16e-7, 3.16e-7, 2910, 301, 21590, 693, 693, 11179, 7, 8.57},
    {"nand", 1e-7, 1e-7, 3378, 342, 24792, 794, 794, 12866, 7, 7.37},
    {"nand", 3.16e-8, 3.16e-8, 3922, 362, 27787, 858, 858, 14901, 7, 7.93},
    {"nand", 1e-8, 1e-8, 4543, 410, 31413, 949, 949, 17162, 7, 8.51},
    {"nand", 3.16e-9, 3.16e-9, 5198, 450, 35213, 1046, 1046, 19507, 7, 9.85},
    {"nand", 1e-9, 1e-9, 5810, 492, 38777, 1128, 1128, 21841, 7, 10.00},
    {"nand", 3.16e-10, 3.16e-10, 6559, 529, 43221, 1253, 1253, 24410, 7, 10.33},
    {"nand", 1e-10, 1e-10, 7435, 581, 47953, 1363, 1363, 27492, 7, 10.43},
    {"pendulum2", 1e-2, 1e-2, 13, 0, 38, 4, 4, 39, 2, 2.425},
    {"pendulum2", 3.16e-3, 3.16e-3, 15, 0, 44, 3, 3, 54, 3, 2.199},
    {"pendulum2", 1e-3, 1e-3, 16, 0, 43, 4, 4, 50, 3, 3.288},
    {"pendulum2", 3.16e-4, 3.16e-4, 18, 0, 45, 4, 4, 56, 4, 3.500},
    {"pendulum2", 1e-4, 1e-4, 21, 0, 51, 4, 4, 68, 4, 4.545},
    {"pendulum2", 3.16e-5, 3.16e-5, 24, 0, 62, 4, 4, 84, 4, 4.836},
    {"pendulum2", 1e-5, 1e-5, 28, 0, 72, 4, 4, 102, 4, 5.074},
    {"pendulum2", 3.16e-6, 3.16e-6, 32, 1, 92, 5, 5, 124, 4, 5.206},
    {"pendulum2", 1e-6, 1e-6, 39, 0, 90, 6, 6, 129, 5, 5.933},
    {"pendulum2", 3.16e-7, 3.16e-7, 38, 0, 97, 7, 7, 130, 6, 6.575},
    {"pendulum2", 1e-7, 1e-7, 45, 0, 109, 8, 8, 150, 5, 7.536},
    {"pendulum2", 3.16e-8, 3.16e-8, 58, 0, 146, 9, 9, 207, 5, 8.164},
    {"pendulum2", 1e-8, 1e-8, 69, 0, 165, 9, 9, 248, 6, 7.691},
    {"pendulum2", 3.16e-9, 3.16e-9, 87, 2, 195, 10, 10, 310, 6, 7.960},
    {"pendulum2", 1e-9, 1e-9, 84, 4, 213, 15, 15, 294, 6, 9.412},
    {"pendulum2", 3.16e-10, 3.16e-10, 92, 0, 220, 15, 15, 313, 7, 9.544},
    {"pendulum2", 1e-10, 1e-10, 113, 5, 275, 19, 19, 391, 6, 9.745},
};

#define NTABLE ((int)(sizeof table / sizeof table[0]))

const mebdfi_stat *bench_mebdfi_table(int *n)
{
    *n = NTABLE;
    return table;
}

/* The drivers (checked in the published sources): the Jacobian (MF = 21: analytic, PDERV; 22:
 * finite differences, whose n residuals per Jacobian are in the residual count), the initial
 * step and the tolerance convention. */
typedef struct driver {
    const char *problem, *file;
    int mf;
    const char *h0, *tolerances;
} driver;

static const driver drivers[] = {
    {"crank", "MEBDFI, cranki.f", 22, "1e-2 rtol", "atol = rtol (as the bench's crank runs)"},
    {"pump", "MEBDFI, pumpi.f", 22, "1e-6 tol",
     "rtol = tol on y1..y8; atol 1e-6 tol on y1, 1e-12 tol on y2..y5 (as the driver's loop is "
     "written), tol on y6..y8; y9 out of the error control (rtol = atol = 1000); stops at the 40 "
     "breakpoints. Ours: the same atol vector, y9 with atol 1000 (and, index 2, out of our error "
     "test), one scalar rtol on all; breakpoints as options"},
    {"transamp", "MEBDFI, transi.f", 22, "1e-2 rtol", "atol = rtol (the bench's: 1e-2 rtol)"},
    {"chemakzo", "MEBDFI, chemakzoi.f", 21, "rtol", "atol = rtol (the bench's: 1e-2 rtol)"},
    {"nand", "MEBDFI, nandi.f", 22, "1e-2 rtol at each of its 16 segments",
     "atol = rtol (the bench's: 1e-2 rtol); the driver restarts the code at t = 5, 10, ..., 75 "
     "(counters summed), ours lands on the same 15 breakpoints without a restart"},
    {"pendulum2", "MEBDFDAE, pendul2.f", 22, "1e-6",
     "atol = rtol (the bench's: 1e-2 rtol); MEBDFDAE with lam declared index 2"},
};
#define NDRIVERS ((int)(sizeof drivers / sizeof drivers[0]))

static const driver *driver_of(const char *name)
{
    for (int i = 0; i < NDRIVERS; i++)
        if (!strcmp(drivers[i].problem, name)) return &drivers[i];
    return NULL;
}

static const mebdfi_stat *published(const char *name, double rtol)
{
    for (int i = 0; i < NTABLE; i++)
        if (!strcmp(table[i].problem, name) && fabs(table[i].rtol - rtol) <= 1e-6 * rtol)
            return &table[i];
    return NULL;
}

/* The drivers' scalar atol = rtol. */
static void atol_equal(const bench_case *bc, double rtol, double *atol, double *atolv)
{
    *atol = rtol;
    if (atolv)
        for (int i = 0; i < bc->n; i++)
            atolv[i] = rtol;
}

/* pumpi.f: y1 1e-6 tol, y2..y5 1e-12 tol, y6..y8 tol, y9 1000 (mescd with atol = rtol). */
static void atol_pump(const bench_case *bc, double rtol, double *atol, double *atolv)
{
    *atol = rtol;
    if (atolv)
        for (int i = 0; i < bc->n; i++)
            atolv[i] = i == 0 ? 1e-6 * rtol : i < 5 ? 1e-12 * rtol : i < 8 ? rtol : 1000.0;
}

static void ratio(FILE *f, long ours, long theirs)
{
    if (theirs > 0)
        fprintf(f, " %.2f |", (double)ours / (double)theirs);
    else
        fprintf(f, " - |");
}

int bench_mebdfi_compare(const char *dir, FILE *rep, bench_case *const *cases, int nc,
                         const double *rtols, int nr)
{
    bench_file bf;
    FILE *c = bench_file_open(&bf, dir, "mebdfi_compare.csv") == 0 ? bf.f : NULL;
    if (c)
        fprintf(c,
                "problem,code,rtol,atol,status,steps,failed_steps,res_evals,res_evals_without_fd_"
                "jacobians,jacobians,lu_factorizations,max_order,scd,scd_measure\n");
    const solver_def *oursv[2] = {bench_solver_find("bgdae-klu"),
                                  bench_solver_find("bgdae-mebdf")};
    int fails = 0, any = 0;
    fprintf(rep,
            "## MEBDFI's published run statistics beside ours\n\n"
            "J. R. Cash's MEBDFI (MEBDFDAE for the pendulum) as its test drivers printed them "
            "(docs/mebdfi_stats.md: source, licence and caveats) beside one run of bgdae-klu "
            "and one of bgdae-mebdf (Cash's method in our code, options.method = DAE_MEBDF) "
            "with the driver's tolerance convention (below) at each tolerance of this run that "
            "the drivers also used, from the bench's consistent start (the drivers start from "
            "the published values: crank's satisfy its constraints to about 1e-7 only) with our "
            "own first step. Ratios are ours / MEBDFI. Failed steps: MEBDFI's count (error test "
            "or Newton failure) against our error-test and Newton failures. Residual "
            "evaluations: where the driver uses finite-difference Jacobians (MF = 22) MEBDFI's "
            "count includes them; 'w/o FD' subtracts n per Jacobian (an estimate) and the ratio "
            "in brackets is against it. Ours always has the analytic Jacobian. scd: the "
            "driver's own measure for MEBDFI (crank: over all 23 non-zero components; pump: y1 "
            "only; the pendulum: a weighted rms), the bench's (the test set's scored "
            "components) for ours. mebdfi_compare.csv has the rows.\n\n");
    for (int ci = 0; ci < nc * 2; ci++) {
        const solver_def *ours = oursv[ci % 2];
        const bench_case *bc = cases[ci / 2];
        const driver *d = driver_of(bc->name);
        if (!d || !ours) continue;
        int header = 0;
        for (int k = 0; k < nr; k++) {
            const mebdfi_stat *m = published(bc->name, rtols[k]);
            if (!m) continue;
            bench_case b2 = *bc; /* the case with the driver's tolerances */
            b2.atol_fn = !strcmp(bc->name, "pump") ? atol_pump : atol_equal;
            run_out o;
            if (bench_run_alloc(&o, bc->n) != 0) continue;
            run_opts ro = {0};
            ro.rtol = rtols[k];
            bench_run(&b2, ours, &ro, &o);
            bp_score sc;
            double atol;
            bench_case_atol(&b2, rtols[k], &atol, NULL);
            if (o.status >= 0 && bc->yref)
                bc->score(bc, o.y, o.yp, rtols[k], atol, &sc);
            else
                sc.scd = NAN;
            if (o.status < 0) fails++;
            long failed = o.rejected + o.conv_fail;
            long m_nofd = d->mf == 22 ? m->res - (long)bc->n * m->jac : m->res;
            if (c && ci % 2 == 0) /* the driver's row once, beside bgdae-klu's */
                fprintf(c, "%s,\"%s\",%g,%g,%d,%ld,%ld,%ld,%ld,%ld,%ld,%d,%.2f,driver\n", bc->name,
                        d->file, m->rtol, m->atol, 0, m->steps, m->failed, m->res, m_nofd, m->jac,
                        m->lu, m->max_order, m->scd);
            if (c)
                fprintf(c, "%s,%s,%g,%g,%d,%ld,%ld,%ld,%ld,%ld,%ld,%d,%.2f,bench\n",
                        bc->name, ours->name, rtols[k], atol, o.status, o.steps, failed, o.res,
                        o.res, o.jac, o.fact, o.max_order, sc.scd);
            fprintf(stderr, "mebdfi: %-9s rtol %-6g %s %s %ld steps (MEBDFI %ld)\n", bc->name,
                    rtols[k], ours->name, o.status < 0 ? "FAIL" : "ok", o.steps, m->steps);
            if (!header) {
                fprintf(rep,
                        "### %s, %s (%s; Jacobian %s; first step %s)\n\nTolerances: %s.\n\n"
                        "| rtol | steps MEBDFI | ours | ratio | failed MEBDFI | ours | ratio | "
                        "residuals MEBDFI | w/o FD | ours | ratio | Jacobians MEBDFI | ours | "
                        "ratio | scd MEBDFI | ours |\n"
                        "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n",
                        bc->name, ours->name, d->file,
                        d->mf == 22 ? "by finite differences (MF = 22)" : "analytic (MF = 21)",
                        d->h0, d->tolerances);
                header = 1;
            }
            any = 1;
            if (o.status < 0) {
                fprintf(rep, "| %g | %ld | FAIL at t = %.6g | | %ld | | | %ld | %ld | | | %ld | | "
                             "| %.2f | |\n",
                        rtols[k], m->steps, o.t, m->failed, m->res, m_nofd, m->jac, m->scd);
            } else {
                fprintf(rep, "| %g | %ld | %ld |", rtols[k], m->steps, o.steps);
                ratio(rep, o.steps, m->steps);
                fprintf(rep, " %ld | %ld |", m->failed, failed);
                ratio(rep, failed, m->failed);
                fprintf(rep, " %ld | %ld | %ld |", m->res, m_nofd, o.res);
                if (d->mf == 22 && m->res > 0 && m_nofd > 0)
                    fprintf(rep, " %.2f (%.2f) |", (double)o.res / (double)m->res,
                            (double)o.res / (double)m_nofd);
                else
                    ratio(rep, o.res, m->res);
                fprintf(rep, " %ld | %ld |", m->jac, o.jac);
                ratio(rep, o.jac, m->jac);
                fprintf(rep, " %.2f | %.2f |\n", m->scd, sc.scd);
            }
            bench_run_free(&o);
        }
        if (header) fprintf(rep, "\n");
    }
    if (!any)
        fprintf(rep, "No run: none of crank, pump, transamp, chemakzo, nand, pendulum2 at a "
                     "tolerance of the drivers' sweep (1e-2 .. 1e-10 in steps of sqrt(10)).\n\n");
    if (c) bench_file_close(&bf);
    return fails;
}
