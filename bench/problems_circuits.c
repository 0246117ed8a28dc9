/* The IVP Test Set's circuits (problems_impl.h: bpi_pump, bpi_transamp, bpi_nand; listed by
 * bp_testset_get): the charge pump, the transistor amplifier and the NAND gate, written anew from
 * the published equations (docs/testset.md), with their initial values and references. */
#include "problems_impl.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* ==== pump: the charge pump of M. Guenther, G. Denk and U. Feldmann (How models for MOS
 * transistors reflect charge distribution effects, Preprint 1745, TH Darmstadt 1995), IVP Test
 * Set "pump", as defined in J. Cash's MEBDFI driver (pumpi.f, docs/testset.md). Unknowns: the
 * charges y1..y5 (gate, capacitor CS, source, capacitor CD, drain), the voltages y6..y8 (gate,
 * source and drain nodes) and the current y9 through the input source:
 *   y1' + y9 = 0,  y2' + y3' = 0,  y4' + y5' = 0,
 *   0 = y6 - Vin(t),
 *   0 = QG(V) - y1,  0 = CS y7 - y2,  0 = QS(V) - y3,  0 = CD y8 - y4,  0 = QD(V) - y5,
 * with V = (y6, y6 - y7, y6 - y8) = (gate-bulk, gate-source, gate-drain voltages) of the MOS
 * transistor's charge model (qgate, qsrc, qdrain of pumpi.f; the rows as in its RESID). y9
 * enters no algebraic row: it is fixed by the derivative of QG(V) - y1 = 0,
 * i.e. index 2; y6..y8 are index 1 (docs/testset.md: y9 index 2). Vin is a trapezoidal pulse of
 * period 120 ns with kinks at 50, 60, 110 and 120 ns in each period: 40 kinks in [0, 1200 ns],
 * the last one at tend, so 39 breakpoints inside the interval plus t_stop = tend. */
#define PU_CAPD 0.40e-12
#define PU_CAPS 1.60e-12
#define PU_VT0 0.20
#define PU_GAMMA 0.035
#define PU_PHI 1.010
#define PU_COX 4.0e-12
#define PU_VHIGH 20.0
#define PU_PERIOD 120.0e-9

static double pump_vin(double t)
{
    double d = fmod(t, PU_PERIOD);
    if (d < 50.0e-9) return 0.0;
    if (d < 60.0e-9) return (d - 50.0e-9) * 0.10e9 * PU_VHIGH;
    if (d < 110.0e-9) return PU_VHIGH;
    return (PU_PERIOD - d) * 0.10e9 * PU_VHIGH;
}

enum { PU_QGATE, PU_QSRC, PU_QDRAIN };

/* The MOS charges of pumpi.f (qgate, qsrc, qdrain) at (vgb, vgs, vgd) and their partial
 * derivatives d[0..2] with respect to vgb, vgs, vgd. Source and drain are exchanged when
 * vgs <= vgd. NaN when phi - ubs < 0 (outside the model, as the source's sqrt). */
static double pump_charge(int which, double vgb, double vgs, double vgd, double d[3])
{
    int swap = vgs - vgd <= 0.0;
    double ugs = swap ? vgd : vgs, ugd = swap ? vgs : vgd, ugb = vgb;
    double ubs = ugs - ugb;
    double vfb = PU_VT0 - PU_GAMMA * sqrt(PU_PHI) - PU_PHI;
    double sq = sqrt(PU_PHI - ubs);
    double vte = PU_VT0 + PU_GAMMA * (sq - sqrt(PU_PHI));
    double q = 0.0, gb = 0.0, gs = 0.0, gd = 0.0; /* partials by ugb, ugs, ugd */
    if (ugb <= vfb) {
        if (which == PU_QGATE) {
            q = PU_COX * (ugb - vfb);
            gb = PU_COX;
        }
    } else if (ugs <= vte) {
        if (which == PU_QGATE) {
            double r = sqrt(PU_GAMMA * PU_GAMMA / 4.0 + ugb - vfb);
            q = PU_COX * PU_GAMMA * (r - PU_GAMMA / 2.0);
            gb = PU_COX * PU_GAMMA / (2.0 * r);
        }
    } else {
        /* vte depends on ubs = ugs - ugb */
        double dvs = -PU_GAMMA / (2.0 * sq), dvb = PU_GAMMA / (2.0 * sq);
        double b = ugs - vte, bs = 1.0 - dvs, bb = -dvb; /* ugst */
        int on = which == PU_QGATE ? ugd > vte : ugd >= vte;
        double a = on ? ugd - vte : 0.0; /* ugdt */
        double as = on ? -dvs : 0.0, ab = on ? -dvb : 0.0, ad = on ? 1.0 : 0.0;
        double sab = a + b;
        double S = a + b - a * b / sab;
        double Sa = 1.0 - b * b / (sab * sab), Sb = 1.0 - a * a / (sab * sab);
        double Ss = Sa * as + Sb * bs, Sbk = Sa * ab + Sb * bb, Sd = Sa * ad;
        if (which == PU_QGATE) {
            q = PU_COX * (2.0 / 3.0 * S + PU_GAMMA * sq);
            gs = PU_COX * (2.0 / 3.0 * Ss - PU_GAMMA / (2.0 * sq));
            gb = PU_COX * (2.0 / 3.0 * Sbk + PU_GAMMA / (2.0 * sq));
            gd = PU_COX * 2.0 / 3.0 * Sd;
        } else {
            q = -PU_COX / 3.0 * S;
            gs = -PU_COX / 3.0 * Ss;
            gb = -PU_COX / 3.0 * Sbk;
            gd = -PU_COX / 3.0 * Sd;
        }
    }
    if (d) {
        d[0] = gb;
        d[1] = swap ? gd : gs;
        d[2] = swap ? gs : gd;
    }
    return q;
}

static int pump_res(void *user, double t, const double *y, const double *yp, double *F)
{
    (void)user;
    double vgb = y[5], vgs = y[5] - y[6], vgd = y[5] - y[7];
    F[0] = yp[0] + y[8];
    F[1] = yp[1] + yp[2];
    F[2] = yp[3] + yp[4];
    F[3] = y[5] - pump_vin(t);
    F[4] = pump_charge(PU_QGATE, vgb, vgs, vgd, NULL) - y[0];
    F[5] = PU_CAPS * y[6] - y[1];
    F[6] = pump_charge(PU_QSRC, vgb, vgs, vgd, NULL) - y[2];
    F[7] = PU_CAPD * y[7] - y[3];
    F[8] = pump_charge(PU_QDRAIN, vgb, vgs, vgd, NULL) - y[4];
    for (int i = 4; i < 9; i += 2)
        if (isnan(F[i])) return 1; /* outside the transistor model: cut the step */
    return 0;
}

static int pump_jac(void *user, double t, const double *y, const double *yp, sp_csc *Jy,
                    sp_csc *Jyp)
{
    (void)user, (void)t, (void)yp;
    double vgb = y[5], vgs = y[5] - y[6], vgd = y[5] - y[7], d[3];
    sp_csc_zero(Jy);
    sp_csc_zero(Jyp);
    bpi_set(Jy, 0, 8, 1.0);
    bpi_set(Jy, 3, 5, 1.0);
    static const int rows[3] = {4, 6, 8}, kinds[3] = {PU_QGATE, PU_QSRC, PU_QDRAIN};
    for (int k = 0; k < 3; k++) {
        if (isnan(pump_charge(kinds[k], vgb, vgs, vgd, d))) return 1;
        /* chain rule through V = (y6, y6 - y7, y6 - y8) */
        bpi_set(Jy, rows[k], 5, d[0] + d[1] + d[2]);
        bpi_set(Jy, rows[k], 6, -d[1]);
        bpi_set(Jy, rows[k], 7, -d[2]);
    }
    bpi_set(Jy, 4, 0, -1.0);
    bpi_set(Jy, 5, 1, -1.0);
    bpi_set(Jy, 5, 6, PU_CAPS);
    bpi_set(Jy, 6, 2, -1.0);
    bpi_set(Jy, 7, 3, -1.0);
    bpi_set(Jy, 7, 7, PU_CAPD);
    bpi_set(Jy, 8, 4, -1.0);
    bpi_set(Jyp, 0, 0, 1.0);
    bpi_set(Jyp, 1, 1, 1.0);
    bpi_set(Jyp, 1, 2, 1.0);
    bpi_set(Jyp, 2, 3, 1.0);
    bpi_set(Jyp, 2, 4, 1.0);
    return 0;
}

static int pump_patterns(sp_csc **jy, sp_csc **jyp)
{
    static const int iy[][2] = {{0, 8}, {3, 5}, {4, 0}, {4, 5}, {4, 6}, {4, 7},
                                {5, 1}, {5, 6}, {6, 2}, {6, 5}, {6, 6}, {6, 7},
                                {7, 3}, {7, 7}, {8, 4}, {8, 5}, {8, 6}, {8, 7}};
    static const int iyp[][2] = {{0, 0}, {1, 1}, {1, 2}, {2, 3}, {2, 4}};
    return bpi_patterns_pair(9, iy, 18, iyp, 5, jy, jyp);
}

/* ==== transamp: the transistor amplifier of E. Hairer, Ch. Lubich and M. Roche (The Numerical
 * Solution of DAEs by Runge-Kutta Methods, LNM 1409, 1989), IVP Test Set "transamp"
 * (deTestSet Ex_transistor.f, ex_transistor.R; Cash's transi.f): node voltages y1..y8,
 *   M y' = f(t, y),  M = [-C1 C1; C1 -C1] (+) [-C2] (+) [-C3 C3; C3 -C3] (+) [-C4] (+) [-C5 C5; C5
 * -C5] (rank 5), Ub = 6, UF = 0.026, alpha = 0.99, beta = 1e-6, R0 = 1000, R1..R9 = 9000, Ck = k *
 * 1e-6, input Ue(t) = 0.1 sin(200 pi t). Every voltage has its derivative in some row, so all eight
 * are differential; the index-1 structure sits in the three capacitor pairs. The source's rows 1, 4
 * and 7 are replaced here by the sums of rows (1, 2), (4, 5) and (7, 8) (a nonsingular row
 * operation, the same equations): the current balances -(f1 + f2) = 0,
 * -(f4 + f5) = 0, -(f7 + f8) = 0 contain no derivative, and written so they are the algebraic rows
 * they are, which consistent initialisation differentiates (with the source's rows, dF/dy' is
 * singular in rows that all contain y'). */
#define TA_UB 6.0
#define TA_UF 0.026
#define TA_ALPHA 0.99
#define TA_BETA 1.0e-6
#define TA_R0 1000.0
#define TA_RK 9000.0 /* R1 .. R9 */
#define TA_PI 3.1415926535897931

static const double ta_c[5] = {1.0e-6, 2.0e-6, 3.0e-6, 4.0e-6, 5.0e-6};

static void transamp_f(double t, const double *y, double *f)
{
    double ue = 0.1 * sin(200.0 * TA_PI * t);
    double fac1 = TA_BETA * (exp((y[1] - y[2]) / TA_UF) - 1.0);
    double fac2 = TA_BETA * (exp((y[4] - y[5]) / TA_UF) - 1.0);
    f[0] = (y[0] - ue) / TA_R0;
    f[1] = y[1] / TA_RK + (y[1] - TA_UB) / TA_RK + (1.0 - TA_ALPHA) * fac1;
    f[2] = y[2] / TA_RK - fac1;
    f[3] = (y[3] - TA_UB) / TA_RK + TA_ALPHA * fac1;
    f[4] = y[4] / TA_RK + (y[4] - TA_UB) / TA_RK + (1.0 - TA_ALPHA) * fac2;
    f[5] = y[5] / TA_RK - fac2;
    f[6] = (y[6] - TA_UB) / TA_RK + TA_ALPHA * fac2;
    f[7] = y[7] / TA_RK;
}

static int transamp_res(void *user, double t, const double *y, const double *yp, double *F)
{
    (void)user;
    double f[8];
    transamp_f(t, y, f);
    double c1 = ta_c[0], c3 = ta_c[2], c5 = ta_c[4];
    F[0] = -(f[0] + f[1]);
    F[1] = c1 * (yp[0] - yp[1]) - f[1];
    F[2] = -ta_c[1] * yp[2] - f[2];
    F[3] = -(f[3] + f[4]);
    F[4] = c3 * (yp[3] - yp[4]) - f[4];
    F[5] = -ta_c[3] * yp[5] - f[5];
    F[6] = -(f[6] + f[7]);
    F[7] = c5 * (yp[6] - yp[7]) - f[7];
    return 0;
}

/* df/dy as a dense row-major 8 x 8 array */
static void transamp_dfdy(const double *y, double *J)
{
    double e1 = TA_BETA * exp((y[1] - y[2]) / TA_UF) / TA_UF;
    double e2 = TA_BETA * exp((y[4] - y[5]) / TA_UF) / TA_UF;
    memset(J, 0, 64 * sizeof *J);
    J[0 * 8 + 0] = 1.0 / TA_R0;
    J[1 * 8 + 1] = 2.0 / TA_RK + (1.0 - TA_ALPHA) * e1;
    J[1 * 8 + 2] = -(1.0 - TA_ALPHA) * e1;
    J[2 * 8 + 1] = -e1;
    J[2 * 8 + 2] = 1.0 / TA_RK + e1;
    J[3 * 8 + 1] = TA_ALPHA * e1;
    J[3 * 8 + 2] = -TA_ALPHA * e1;
    J[3 * 8 + 3] = 1.0 / TA_RK;
    J[4 * 8 + 4] = 2.0 / TA_RK + (1.0 - TA_ALPHA) * e2;
    J[4 * 8 + 5] = -(1.0 - TA_ALPHA) * e2;
    J[5 * 8 + 4] = -e2;
    J[5 * 8 + 5] = 1.0 / TA_RK + e2;
    J[6 * 8 + 4] = TA_ALPHA * e2;
    J[6 * 8 + 5] = -TA_ALPHA * e2;
    J[6 * 8 + 6] = 1.0 / TA_RK;
    J[7 * 8 + 7] = 1.0 / TA_RK;
}

static int transamp_jac(void *user, double t, const double *y, const double *yp, sp_csc *Jy,
                        sp_csc *Jyp)
{
    (void)user, (void)t, (void)yp;
    double J[64], D[64];
    transamp_dfdy(y, J);
    /* F = T (M y' - f) with T the row operation above */
    for (int j = 0; j < 8; j++) {
        D[0 * 8 + j] = -(J[0 * 8 + j] + J[1 * 8 + j]);
        D[3 * 8 + j] = -(J[3 * 8 + j] + J[4 * 8 + j]);
        D[6 * 8 + j] = -(J[6 * 8 + j] + J[7 * 8 + j]);
        static const int plain[5] = {1, 2, 4, 5, 7};
        for (int k = 0; k < 5; k++)
            D[plain[k] * 8 + j] = -J[plain[k] * 8 + j];
    }
    bpi_fill_from_dense(Jy, D, 8);
    sp_csc_zero(Jyp);
    bpi_set(Jyp, 1, 0, ta_c[0]);
    bpi_set(Jyp, 1, 1, -ta_c[0]);
    bpi_set(Jyp, 2, 2, -ta_c[1]);
    bpi_set(Jyp, 4, 3, ta_c[2]);
    bpi_set(Jyp, 4, 4, -ta_c[2]);
    bpi_set(Jyp, 5, 5, -ta_c[3]);
    bpi_set(Jyp, 7, 6, ta_c[4]);
    bpi_set(Jyp, 7, 7, -ta_c[4]);
    return 0;
}

static int transamp_patterns(sp_csc **jy, sp_csc **jyp)
{
    static const int iy[][2] = {{0, 0}, {0, 1}, {0, 2}, {1, 1}, {1, 2}, {2, 1}, {2, 2},
                                {3, 1}, {3, 2}, {3, 3}, {3, 4}, {3, 5}, {4, 4}, {4, 5},
                                {5, 4}, {5, 5}, {6, 4}, {6, 5}, {6, 6}, {6, 7}, {7, 7}};
    static const int iyp[][2] = {{1, 0}, {1, 1}, {2, 2}, {4, 3}, {4, 4}, {5, 5}, {7, 6}, {7, 7}};
    return bpi_patterns_pair(8, iy, 21, iyp, 8, jy, jyp);
}

/* ==== nand: the NAND gate of G. Denk and M. Guenther (IVP Test Set "nand",
 * deTestSet Ex_nand.f, ex_nand.R): the network equation C(y) y' = f(t, y) of 14 node
 * potentials with a voltage-dependent, nonsingular capacitance matrix (index 0, written
 * implicitly), MOS transistors of Shichman-Hodges type (drain current IDS, pn-junction currents
 * IBS/IBD, junction capacitance CBDBS) and two pulse inputs V1 (delay 5, rise 5, high 5, fall 5,
 * period 20) and V2 (delay 15, rise 5, high 15, fall 5, period 40), t in [0, 80]. The inputs'
 * kinks (every 5 time units) are the breakpoints; V1', V2' jump there and enter f. Faithful to
 * the source also where it looks odd: the enhancement transistor's beta is 1.748e-3 for
 * VDS > 0 but 1.748e-4 for VDS < 0, and CBDBS uses CBD for both junctions. A transistor evaluated
 * with phi - VBS < 0 (sqrt of a negative number) is a recoverable failure (the source's
 * ierr = -1). */
#define ND_RGS 4.0
#define ND_RGD 4.0
#define ND_RBS 10.0
#define ND_RBD 10.0
#define ND_CGS 0.6e-4
#define ND_CGD 0.6e-4
#define ND_CBD 2.4e-5
#define ND_C9 0.5e-4
#define ND_DELTA 0.2e-1
#define ND_CURIS 1.0e-14
#define ND_VTH 25.85
#define ND_VDD 5.0
#define ND_VBB -2.5
#define ND_PHIB 0.87

/* Pulse between 0 and 5 (nandPULSE with LOW = 0, HIGH = 5, T1 = T3 = 5) and its derivative. */
static void nand_pulse(double t, double delay, double t2, double period, double *v, double *vd)
{
    double tm = fmod(t, period), t1 = 5.0, t3 = 5.0, high = 5.0;
    if (tm > delay + t1 + t2 + t3) {
        *v = 0.0, *vd = 0.0;
    } else if (tm > delay + t1 + t2) {
        *v = high / t3 * (delay + t1 + t2 + t3 - tm), *vd = -high / t3;
    } else if (tm > delay + t1) {
        *v = high, *vd = 0.0;
    } else if (tm > delay) {
        *v = high / t1 * (tm - delay), *vd = high / t1;
    } else {
        *v = 0.0, *vd = 0.0;
    }
}

/* Junction current (IBS = IBD of the source) and its derivative. */
static double nand_ib(double v, double *d)
{
    if (v <= 0.0) {
        double e = exp(v / ND_VTH);
        if (d) *d = -ND_CURIS / ND_VTH * e;
        return -ND_CURIS * (e - 1.0);
    }
    if (d) *d = 0.0;
    return 0.0;
}

/* Junction capacitance CBDBS and its derivative. */
static double nand_cb(double v, double *d)
{
    if (v <= 0.0) {
        double r = sqrt(1.0 - v / ND_PHIB);
        if (d) *d = ND_CBD * 0.5 / (ND_PHIB * r * r * r);
        return ND_CBD / r;
    }
    if (d) *d = ND_CBD / (2.0 * ND_PHIB);
    return ND_CBD * (1.0 + v / (2.0 * ND_PHIB));
}

/* Drain current IDS(ned, vds, vgs, vbs, vgd, vbd) (nandIDS, nandGDSP, nandGDSM) and its partial
 * derivatives d[0..4] by the five arguments. Returns 1 (d untouched) where the source sets
 * ierr = -1, else 0. */
static int nand_ids(int ned, double vds, double vgs, double vbs, double vgd, double vbd,
                    double *ids, double d[5])
{
    double vt0, cg, phi, beta;
    d[0] = d[1] = d[2] = d[3] = d[4] = 0.0;
    *ids = 0.0;
    /* VDS = 0 gives IDS = 0 in the source; the VDS > 0 branch gives 0 there too and, for the
     * derivatives, the limit from VDS > 0 (from both sides for the depletion type) */
    int pos = vds >= 0.0;
    if (ned == 1) { /* depletion type */
        vt0 = -2.43, cg = 0.2, phi = 1.28, beta = 5.35e-4;
    } else { /* enhancement type; beta differs between the two branches in the source */
        vt0 = 0.2, cg = 0.035, phi = 1.01, beta = pos ? 1.748e-3 : 1.748e-4;
    }
    double vb = pos ? vbs : vbd, vg = pos ? vgs : vgd;
    if (phi - vb < 0.0) return vds == 0.0 ? 0 : 1;
    double sq = sqrt(phi - vb);
    double vte = vt0 + cg * (sq - sqrt(phi));
    double u = vg - vte, du_vb = cg / (2.0 * sq); /* du/dvg = 1 */
    double di_u = 0.0, di_vds = 0.0;
    if (u <= 0.0) return 0;
    if (pos) {
        double g = 1.0 + ND_DELTA * vds;
        if (u <= vds) {
            *ids = -beta * u * u * g;
            di_u = -2.0 * beta * u * g;
            di_vds = -beta * u * u * ND_DELTA;
        } else {
            *ids = -beta * vds * (2.0 * u - vds) * g;
            di_u = -2.0 * beta * vds * g;
            di_vds = -beta * ((2.0 * u - 2.0 * vds) * g + ND_DELTA * vds * (2.0 * u - vds));
        }
        d[0] = di_vds, d[1] = di_u, d[2] = di_u * du_vb;
    } else {
        double g = 1.0 - ND_DELTA * vds;
        if (u <= -vds) {
            *ids = beta * u * u * g;
            di_u = 2.0 * beta * u * g;
            di_vds = -beta * u * u * ND_DELTA;
        } else {
            *ids = -beta * vds * (2.0 * u + vds) * g;
            di_u = -2.0 * beta * vds * g;
            di_vds = -beta * ((2.0 * u + 2.0 * vds) * g - ND_DELTA * vds * (2.0 * u + vds));
        }
        d[0] = di_vds, d[3] = di_u, d[4] = di_u * du_vb;
    }
    return 0;
}

/* The three transistors' IDS arguments (vds, vgs, vbs, vgd, vbd), each y[a] - y[b] + off, where
 * a = -1 stands for the gate's input voltage and b = -1 for nothing. */
typedef struct nd_arg {
    int a, b;
    double off;
} nd_arg;

static const nd_arg nd_tr[3][5] = {
    /* rows 1, 2: IDS(1, y2-y1, y5-y1, y3-y5, y5-y2, y4-VDD) */
    {{1, 0, 0}, {4, 0, 0}, {2, 4, 0}, {4, 1, 0}, {3, -1, -ND_VDD}},
    /* rows 6, 7: IDS(2, y7-y6, V1-y6, y8-y10, V1-y7, y9-y5) */
    {{6, 5, 0}, {-1, 5, 0}, {7, 9, 0}, {-1, 6, 0}, {8, 4, 0}},
    /* rows 11, 12: IDS(2, y12-y11, V2-y11, y13, V2-y12, y14-y10) */
    {{11, 10, 0}, {-1, 10, 0}, {12, -1, 0}, {-1, 11, 0}, {13, 9, 0}}};

/* Transistor k's current at y with input vin; with D != NULL, s times its derivative by y is
 * added to row r of D (row-major 14 x 14). Returns 1 where the model is undefined. */
static int nand_transistor(int k, const double *y, double vin, double *ids, double *D, int r,
                           double s)
{
    double a[5], d[5];
    for (int i = 0; i < 5; i++) {
        nd_arg g = nd_tr[k][i];
        a[i] = (g.a >= 0 ? y[g.a] : vin) - (g.b >= 0 ? y[g.b] : 0.0) + g.off;
    }
    if (nand_ids(k == 0 ? 1 : 2, a[0], a[1], a[2], a[3], a[4], ids, d)) return 1;
    if (D)
        for (int i = 0; i < 5; i++) {
            if (nd_tr[k][i].a >= 0) D[r * 14 + nd_tr[k][i].a] += s * d[i];
            if (nd_tr[k][i].b >= 0) D[r * 14 + nd_tr[k][i].b] -= s * d[i];
        }
    return 0;
}

/* f(t, y) of the network equation; with D != NULL, D -= df/dy (row-major 14 x 14). */
static int nand_f(double t, const double *y, double *f, double *D)
{
    double v1, v1d, v2, v2d, i1, i2, i3, g;
    nand_pulse(t, 5.0, 5.0, 20.0, &v1, &v1d);
    nand_pulse(t, 15.0, 15.0, 40.0, &v2, &v2d);
    if (nand_transistor(0, y, 0.0, &i1, NULL, 0, 0) || nand_transistor(1, y, v1, &i2, NULL, 0, 0) ||
        nand_transistor(2, y, v2, &i3, NULL, 0, 0))
        return 1;
    double ib35 = nand_ib(y[2] - y[4], NULL), ib4 = nand_ib(y[3] - ND_VDD, NULL);
    double ib95 = nand_ib(y[8] - y[4], NULL), ib810 = nand_ib(y[7] - y[9], NULL);
    double ib1410 = nand_ib(y[13] - y[9], NULL), ib13 = nand_ib(y[12], NULL);
    f[0] = -(y[0] - y[4]) / ND_RGS - i1;
    f[1] = -(y[1] - ND_VDD) / ND_RGD + i1;
    f[2] = -(y[2] - ND_VBB) / ND_RBS + ib35;
    f[3] = -(y[3] - ND_VBB) / ND_RBD + ib4;
    f[4] = -(y[4] - y[0]) / ND_RGS - ib35 - (y[4] - y[6]) / ND_RGD - ib95;
    f[5] = ND_CGS * v1d - (y[5] - y[9]) / ND_RGS - i2;
    f[6] = ND_CGD * v1d - (y[6] - y[4]) / ND_RGD + i2;
    f[7] = -(y[7] - ND_VBB) / ND_RBS + ib810;
    f[8] = -(y[8] - ND_VBB) / ND_RBD + ib95;
    f[9] = -(y[9] - y[5]) / ND_RGS - ib810 - (y[9] - y[11]) / ND_RGD - ib1410;
    f[10] = ND_CGS * v2d - y[10] / ND_RGS - i3;
    f[11] = ND_CGD * v2d - (y[11] - y[9]) / ND_RGD + i3;
    f[12] = -(y[12] - ND_VBB) / ND_RBS + ib13;
    f[13] = -(y[13] - ND_VBB) / ND_RBD + ib1410;
    if (!D) return 0;
        /* D -= df/dy: linear terms first (their negatives) */
#define DM(i, j, v) D[(i)*14 + (j)] -= (v)
    DM(0, 0, -1.0 / ND_RGS), DM(0, 4, 1.0 / ND_RGS);
    DM(1, 1, -1.0 / ND_RGD);
    DM(2, 2, -1.0 / ND_RBS);
    DM(3, 3, -1.0 / ND_RBD);
    DM(4, 4, -1.0 / ND_RGS - 1.0 / ND_RGD), DM(4, 0, 1.0 / ND_RGS), DM(4, 6, 1.0 / ND_RGD);
    DM(5, 5, -1.0 / ND_RGS), DM(5, 9, 1.0 / ND_RGS);
    DM(6, 6, -1.0 / ND_RGD), DM(6, 4, 1.0 / ND_RGD);
    DM(7, 7, -1.0 / ND_RBS);
    DM(8, 8, -1.0 / ND_RBD);
    DM(9, 9, -1.0 / ND_RGS - 1.0 / ND_RGD), DM(9, 5, 1.0 / ND_RGS), DM(9, 11, 1.0 / ND_RGD);
    DM(10, 10, -1.0 / ND_RGS);
    DM(11, 11, -1.0 / ND_RGD), DM(11, 9, 1.0 / ND_RGD);
    DM(12, 12, -1.0 / ND_RBS);
    DM(13, 13, -1.0 / ND_RBD);
    /* junction currents */
    nand_ib(y[2] - y[4], &g); /* f2 +, f4 - */
    DM(2, 2, g), DM(2, 4, -g), DM(4, 2, -g), DM(4, 4, g);
    nand_ib(y[3] - ND_VDD, &g);
    DM(3, 3, g);
    nand_ib(y[8] - y[4], &g); /* f4 -, f8 + */
    DM(4, 8, -g), DM(4, 4, g), DM(8, 8, g), DM(8, 4, -g);
    nand_ib(y[7] - y[9], &g); /* f7 +, f9 - */
    DM(7, 7, g), DM(7, 9, -g), DM(9, 7, -g), DM(9, 9, g);
    nand_ib(y[13] - y[9], &g); /* f9 -, f13 + */
    DM(9, 13, -g), DM(9, 9, g), DM(13, 13, g), DM(13, 9, -g);
    nand_ib(y[12], &g);
    DM(12, 12, g);
#undef DM
    /* transistors: f0 -= i1, f1 += i1, f5 -= i2, f6 += i2, f10 -= i3, f11 += i3; D -= df/dy */
    nand_transistor(0, y, 0.0, &i1, D, 0, 1.0);
    nand_transistor(0, y, 0.0, &i1, D, 1, -1.0);
    nand_transistor(1, y, v1, &i2, D, 5, 1.0);
    nand_transistor(1, y, v1, &i2, D, 6, -1.0);
    nand_transistor(2, y, v2, &i3, D, 10, 1.0);
    nand_transistor(2, y, v2, &i3, D, 11, -1.0);
    return 0;
}

/* C(y) y' for the capacitance matrix of the source (subroutine CAP); with Dy != NULL, adds
 * d(C(y) y')/dy to Dy, with Dyp != NULL stores C(y) (both row-major 14 x 14). */
static void nand_cap(const double *y, const double *yp, double *cy, double *Dy, double *Dyp)
{
    double g35, g4, g95, g810, g1410, g13;
    double c35 = nand_cb(y[2] - y[4], &g35), c4 = nand_cb(y[3] - ND_VDD, &g4);
    double c95 = nand_cb(y[8] - y[4], &g95), c810 = nand_cb(y[7] - y[9], &g810);
    double c1410 = nand_cb(y[13] - y[9], &g1410), c13 = nand_cb(y[12], &g13);
    cy[0] = ND_CGS * (yp[0] - yp[4]);
    cy[1] = ND_CGD * (yp[1] - yp[4]);
    cy[2] = c35 * (yp[2] - yp[4]);
    cy[3] = c4 * yp[3];
    cy[4] = -ND_CGS * yp[0] - ND_CGD * yp[1] + c35 * (yp[4] - yp[2]) + c95 * (yp[4] - yp[8]) +
            (ND_CGS + ND_CGD + ND_C9) * yp[4];
    cy[5] = ND_CGS * yp[5];
    cy[6] = ND_CGD * yp[6];
    cy[7] = c810 * (yp[7] - yp[9]);
    cy[8] = c95 * (yp[8] - yp[4]);
    cy[9] = c810 * (yp[9] - yp[7]) + c1410 * (yp[9] - yp[13]) + ND_C9 * yp[9];
    cy[10] = ND_CGS * yp[10];
    cy[11] = ND_CGD * yp[11];
    cy[12] = c13 * yp[12];
    cy[13] = c1410 * (yp[13] - yp[9]);
    if (Dy) {
#define DA(i, j, v) Dy[(i)*14 + (j)] += (v)
        double a = g35 * (yp[2] - yp[4]); /* d c35 / d(y3 - y5) times (y3' - y5') */
        DA(2, 2, a), DA(2, 4, -a), DA(4, 2, -a), DA(4, 4, a);
        DA(3, 3, g4 * yp[3]);
        a = g95 * (yp[4] - yp[8]); /* row 4: c95 (y5' - y9'), c95 = CB(y9 - y5) */
        DA(4, 8, a), DA(4, 4, -a);
        a = g95 * (yp[8] - yp[4]);
        DA(8, 8, a), DA(8, 4, -a);
        a = g810 * (yp[7] - yp[9]);
        DA(7, 7, a), DA(7, 9, -a), DA(9, 7, -a), DA(9, 9, a);
        a = g1410 * (yp[9] - yp[13]); /* row 9: c1410 (y10' - y14'), c1410 = CB(y14 - y10) */
        DA(9, 13, a), DA(9, 9, -a);
        a = g1410 * (yp[13] - yp[9]);
        DA(13, 13, a), DA(13, 9, -a);
        DA(12, 12, g13 * yp[12]);
#undef DA
    }
    if (Dyp) {
        memset(Dyp, 0, 196 * sizeof *Dyp);
#define DP(i, j, v) Dyp[(i)*14 + (j)] = (v)
        DP(0, 0, ND_CGS), DP(0, 4, -ND_CGS);
        DP(1, 1, ND_CGD), DP(1, 4, -ND_CGD);
        DP(2, 2, c35), DP(2, 4, -c35);
        DP(3, 3, c4);
        DP(4, 0, -ND_CGS), DP(4, 1, -ND_CGD), DP(4, 2, -c35), DP(4, 8, -c95);
        DP(4, 4, ND_CGS + ND_CGD + c35 + c95 + ND_C9);
        DP(5, 5, ND_CGS);
        DP(6, 6, ND_CGD);
        DP(7, 7, c810), DP(7, 9, -c810);
        DP(8, 4, -c95), DP(8, 8, c95);
        DP(9, 7, -c810), DP(9, 13, -c1410), DP(9, 9, c810 + c1410 + ND_C9);
        DP(10, 10, ND_CGS);
        DP(11, 11, ND_CGD);
        DP(12, 12, c13);
        DP(13, 9, -c1410), DP(13, 13, c1410);
#undef DP
    }
}

static int nand_res(void *user, double t, const double *y, const double *yp, double *F)
{
    (void)user;
    double f[14], cy[14];
    if (nand_f(t, y, f, NULL)) return 1;
    nand_cap(y, yp, cy, NULL, NULL);
    for (int i = 0; i < 14; i++)
        F[i] = cy[i] - f[i];
    return 0;
}

static int nand_jac(void *user, double t, const double *y, const double *yp, sp_csc *Jy,
                    sp_csc *Jyp)
{
    (void)user;
    double f[14], cy[14], Dy[196], Dyp[196];
    memset(Dy, 0, sizeof Dy);
    if (nand_f(t, y, f, Dy)) return 1;
    nand_cap(y, yp, cy, Dy, Dyp);
    bpi_fill_from_dense(Jy, Dy, 14);
    bpi_fill_from_dense(Jyp, Dyp, 14);
    return 0;
}

static int nand_patterns(sp_csc **jy, sp_csc **jyp)
{
    static const int iyp[][2] = {{0, 0},   {0, 4},   {1, 1},   {1, 4},  {2, 2},  {2, 4}, {3, 3},
                                 {4, 0},   {4, 1},   {4, 2},   {4, 4},  {4, 8},  {5, 5}, {6, 6},
                                 {7, 7},   {7, 9},   {8, 4},   {8, 8},  {9, 7},  {9, 9}, {9, 13},
                                 {10, 10}, {11, 11}, {12, 12}, {13, 9}, {13, 13}};
    /* rows: f's dependence (resistors, junctions, transistors) and that of C(y) y' */
    static const int rows[14][7] = {{0, 1, 2, 3, 4, -1},
                                    {0, 1, 2, 3, 4, -1},
                                    {2, 4, -1},
                                    {3, -1},
                                    {0, 2, 4, 6, 8, -1},
                                    {4, 5, 6, 7, 8, 9, -1},
                                    {4, 5, 6, 7, 8, 9, -1},
                                    {7, 9, -1},
                                    {4, 8, -1},
                                    {5, 7, 9, 11, 13, -1},
                                    {9, 10, 11, 12, 13, -1},
                                    {9, 10, 11, 12, 13, -1},
                                    {12, -1},
                                    {9, 13, -1}};
    int iy[14 * 7][2], ny = 0;
    for (int i = 0; i < 14; i++)
        for (int k = 0; k < 7 && rows[i][k] >= 0; k++) {
            iy[ny][0] = i;
            iy[ny][1] = rows[i][k];
            ny++;
        }
    return bpi_patterns_pair(14, (const int(*)[2])iy, ny, iyp, 26, jy, jyp);
}

/* ---- initial values, kinds, names, references ---- */

/* pump: y1 = QG(0, 0, 0), y3 = QS(0, 0, 0) = 0, y5 = QD(0, 0, 0) = 0, the rest 0, y' = 0
 * (pumpi.f INIT); consistent because Vin = 0 on [0, 50 ns]. */
static const double pump_y0[] = {1.2628004298767594e-13, 0, 0, 0, 0, 0, 0, 0, 0};
static const double pump_yp0[9] = {0};
static const int pump_kind[] = {DAE_DIFF, DAE_DIFF, DAE_DIFF, DAE_DIFF, DAE_DIFF,
                                DAE_ALG,  DAE_ALG,  DAE_ALG,  DAE_ALG2};
static const char *const pump_names[] = {"qgate", "qcs",  "qsrc",   "qcd", "qdrain",
                                         "vgate", "vsrc", "vdrain", "iin"};
/* GAMD in quadruple precision, quoted in SciMLBenchmarks charge_pump.jmd (docs/testset.md). The
 * PSIDE (tol 2e-8) values of pumpi.f agree in y1 to 16 digits; their y9 differs by 6e-6 relative
 * (docs/testset.md: y9 is good to about 5 digits). */
static const double pump_yref[] = {0.126280042987675933170893e-12, 0, 0, 0, 0, 0, 0, 0,
                                   0.152255686815577679043511e-3};
static const unsigned char pump_scored[] = {1, 1, 1, 1, 1, 1, 1, 1, 0};
/* the kinks of Vin at 50, 60, 110, 120 ns + k 120 ns inside (0, 1200 ns) (pumpi.f T(1..39));
 * the 40th, 1200 ns, is tend */
static const double pump_bp[] = {
    50e-9,  60e-9,  110e-9,  120e-9,  170e-9,  180e-9,  230e-9,  240e-9,  290e-9, 300e-9,
    350e-9, 360e-9, 410e-9,  420e-9,  470e-9,  480e-9,  530e-9,  540e-9,  590e-9, 600e-9,
    650e-9, 660e-9, 710e-9,  720e-9,  770e-9,  780e-9,  830e-9,  840e-9,  890e-9, 900e-9,
    950e-9, 960e-9, 1010e-9, 1020e-9, 1070e-9, 1080e-9, 1130e-9, 1140e-9, 1190e-9};

/* transamp: y0 from ex_transistor.R (Ub = 6, R1 = R2, R5 = R6: (0, 3, 3, 6, 3, 3, 6, 0), which
 * satisfies the three current balances exactly); y0' consistent (ours): the five rows with y'
 * and the time derivatives of the three balances solved in 80-bit arithmetic. ex_transistor.R's
 * dyini (51.338775, ..., -24.9757667, ..., -10.00564453) agrees to 1e-5..1e-3 only. */
static const double transamp_y0[] = {0.0, 3.0, 3.0, 6.0, 3.0, 3.0, 6.0, 0.0};
static const double transamp_yp0[] = {51.339276517180721, 51.339276517180735,  -166.66666666666666,
                                      -24.97032851540634, -24.970328515406322, -83.333333333333329,
                                      -10.00027640245634, -10.000276402456338};
static const int transamp_kind[] = {DAE_DIFF, DAE_DIFF, DAE_DIFF, DAE_DIFF,
                                    DAE_DIFF, DAE_DIFF, DAE_DIFF, DAE_DIFF};
static const char *const transamp_names[] = {"U1", "U2", "U3", "U4", "U5", "U6", "U7", "U8"};
/* transsoln in deTestSet src/Ex_transistor.f (docs/testset.md): PSIDE, Cray C90,
 * rtol = atol = 1e-14. */
static const double transamp_yref[] = {-0.5562145012262709e-002, 0.3006522471903042e+001,
                                       0.2849958788608128e+001,  0.2926422536206241e+001,
                                       0.2704617865010554e+001,  0.2761837778393145e+001,
                                       0.4770927631616772e+001,  0.1236995868091548e+001};

/* nand: y0 of ex_nand.R. Its y0' = 0 leaves |F| = 5e-15 (the junction leakage currents, CURIS =
 * 1e-14); y0' = C(y0)^-1 f(0, y0) (ours, 80-bit elimination) is consistent (index 0: every y0 is
 * consistent with its own y0'). */
static const double nand_y0[] = {5.0,    5.0,    ND_VBB,  ND_VBB, 5.0,     3.62385, 5.0,
                                 ND_VBB, ND_VBB, 3.62385, 0.0,    3.62385, ND_VBB,  ND_VBB};
static const double nand_yp0[] = {-3.0788122750122969e-27,
                                  -3.0788122750122969e-27,
                                  3.2547127901527181e-10,
                                  3.2547127901527181e-10,
                                  -3.0788122750122969e-27,
                                  0,
                                  0,
                                  2.4918638241775561e-10,
                                  3.2547127901527181e-10,
                                  -1.1233134888883567e-27,
                                  0,
                                  0,
                                  7.5594827694643552e-11,
                                  2.4918638241775561e-10};
static const int nand_kind[14] = {DAE_DIFF, DAE_DIFF, DAE_DIFF, DAE_DIFF, DAE_DIFF,
                                  DAE_DIFF, DAE_DIFF, DAE_DIFF, DAE_DIFF, DAE_DIFF,
                                  DAE_DIFF, DAE_DIFF, DAE_DIFF, DAE_DIFF};
static const char *const nand_names[] = {"y1", "y2", "y3",  "y4",  "y5",  "y6",  "y7",
                                         "y8", "y9", "y10", "y11", "y12", "y13", "y14"};
/* nandsoln in deTestSet src/Ex_nand.f (docs/testset.md): PSIDE, Cray C90, rtol = atol = 1e-16. */
static const double nand_yref[] = {
    0.4971088699385777e+1,  0.4999752103929311e+1,  -0.2499998781491227e+1, -0.2499999999999975e+1,
    0.4970837023296724e+1,  -0.2091214032073855e+0, 0.4970593243278363e+1,  -0.2500077409198803e+1,
    -0.2499998781491227e+1, -0.2090289583878100e+0, -0.2399999999966269e-3, -0.2091214032073855e+0,
    -0.2499999999999991e+1, -0.2500077409198803e+1};
/* docs/testset.md: the test set scores y5 only */
static const unsigned char nand_scored[] = {0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0};
/* the kinks of V1 (every 5) and V2 (15, 20, 35, 40 mod 40) inside (0, 80) */
static const double nand_bp[] = {5, 10, 15, 20, 25, 30, 35, 40, 45, 50, 55, 60, 65, 70, 75};

/* ---- the problems ---- */

const bp_problem bpi_pump = {.name = "pump",
                             .title = "charge pump, index 2 (IVP Test Set pump, pumpi.f)",
                             .n = 9,
                             .t0 = 0.0,
                             .tend = 1.2e-6,
                             BP_PARTS(pump),
                             .yref = pump_yref,
                             .ref_source = "GAMD quadruple precision (docs/testset.md)",
                             .scored = pump_scored,
                             .nbreakpoints = 39,
                             .breakpoints = pump_bp};

const bp_problem bpi_transamp = {
    .name = "transamp",
    .title = "transistor amplifier, index 1 (IVP Test Set transamp)",
    .n = 8,
    .t0 = 0.0,
    .tend = 0.2,
    BP_PARTS(transamp),
    .yref = transamp_yref,
    .ref_source = "deTestSet Ex_transistor.f transsoln, PSIDE 1e-14 (docs/testset.md)"};

const bp_problem bpi_nand = {.name = "nand",
                             .title = "NAND gate, C(y) y' = f (IVP Test Set nand)",
                             .n = 14,
                             .t0 = 0.0,
                             .tend = 80.0,
                             BP_PARTS(nand),
                             .yref = nand_yref,
                             .ref_source =
                                 "deTestSet Ex_nand.f nandsoln, PSIDE 1e-16 (docs/testset.md)",
                             .scored = nand_scored,
                             .nbreakpoints = 15,
                             .breakpoints = nand_bp};
