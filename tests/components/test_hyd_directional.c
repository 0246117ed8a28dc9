/* 4/3 proportional directional valve (hyd_directional) on a bench of pressure sources, the
 * equilibrium of each circuit found by bgr_static, against the manufacturer's data and hand
 * calculations:
 *   - rated point: at u = +1 (and -1) and the rated drop dp_n across the open edges, each edge
 *     passes q_n + G_l dp_n;
 *   - symmetry: u -> -u with the pressures at A and B swapped swaps the flows at A and B;
 *   - series P -> A -> load -> B -> T at supply p_s through a laminar load G_L, against the
 *     turbulent orifice series p_s = 2 (Q / (K_t a))^2 + Q / G_L, K_t = q_n / sqrt(dp_n),
 *     a = u (critically centred): a quadratic in Q;
 *   - zero command: a critically centred valve passes its leakage G_l dp only (within the
 *     opening's stated smoothing residue eps ln 2 q_n sqrt(dp / dp_n) per edge); an underlapped
 *     one holds closed A and B at p_s / 2 and passes the centre flow 2 q_n (u0 / (1 + u0))
 *     sqrt(p_s / (2 dp_n));
 *   - the regime of the two spool switches; the analytic Jacobian in the switches' bands;
 *   - misuse: parameters out of range refused with messages naming the path and parameter, a
 *     command that names no unknown reported by bgr_compile. */
#include "bgr_analysis.h"
#include "bondgraph/param_check.h"
#include "cmptest.h"
#include "hyd_directional.h"
#include "hyd_source.h"
#include "hyd_valve.h"
#include "sig_sources.h"

static const double QN = 100.0 / 60000, DPN = 35e5; /* 100 l/min at 35 bar per edge */

/* How a port is held on the bench. */
enum { HOLD_PRESSURE, HOLD_CLOSED, HOLD_LOAD };

/* The valve with command u and ports P, T, A, B held at p[k] (HOLD_PRESSURE) or closed (flow
 * 0); HOLD_LOAD at A joins A to B through a laminar restriction G_L (B's hold is then ignored).
 * Solved for its equilibrium; q[k] receives the flow into the valve at each port, pout[k] the
 * pressure there. Returns the bgr_static status (< 0 also when building failed). */
static int bench(const hyd_directional_spec *vs, double u, const double *p, const int *hold,
                 double GL, double *q, double *pout, int *regime)
{
    static const char *const port[4] = {"P", "T", "A", "B"};
    bgr_model *m = bgr_model_create("vb");
    int cmd = sig_constant(m, 0, "command", u, SIG_VALUE);
    int v = hyd_directional_valve(m, 0, "valve", (bgr_ref){BGR_OWN, cmd, 0}, vs);
    char nm[32], path[64];
    for (int k = 0; k < 4; k++) {
        if (k == 3 && hold[2] == HOLD_LOAD) break;
        snprintf(nm, sizeof nm, "hold_%s", port[k]);
        int h;
        if (k == 2 && hold[2] == HOLD_LOAD) {
            h = hyd_leakage(m, 0, "load", GL);
            B(m, "b_A", v, 2, h, 0); /* power from the valve's A into the load, out at B */
            B(m, "b_B", h, 1, v, 3);
            continue;
        }
        h = hold[k] == HOLD_CLOSED ? hyd_flow_source(m, 0, nm, 0.0) : hyd_tank(m, 0, nm, p[k]);
        snprintf(nm, sizeof nm, "b_%s", port[k]);
        B(m, nm, h, 0, v, k);
    }
    if (!compile_ok(m, "valve bench")) {
        bgr_model_free(&m);
        return -100;
    }
    bg_error err = {0};
    int st = bgr_static(m, NULL, 0.0, NULL, &err);
    if (st != BG_OK) tap_diag("bench: %s", err.message);
    const double *y = bgr_y0(m);
    for (int k = 0; k < 4; k++) {
        /* the bond at A of a load ends at the load: the flow into the valve is -f */
        double sg = k == 2 && hold[2] == HOLD_LOAD ? -1.0 : 1.0;
        snprintf(path, sizeof path, "vb/b_%s/f", port[k]);
        q[k] = sg * at(y, V(m, path));
        snprintf(path, sizeof path, "vb/b_%s/e", port[k]);
        pout[k] = at(y, V(m, path));
    }
    if (regime) {
        int r[4] = {-1, -1, -1, -1};
        bgr_regimes(m, y, r);
        *regime = r[0];
    }
    bgr_model_free(&m);
    return st;
}

static void test_rated(void)
{
    hyd_directional_spec vs = {.flow_rated = QN, .dp_rated = DPN, .leakage = 2e-13};
    const int hold[4] = {HOLD_PRESSURE, HOLD_PRESSURE, HOLD_PRESSURE, HOLD_PRESSURE};
    const double want = QN + vs.leakage * DPN;
    double q[4], pr[4];
    /* u = +1: P->A and B->T at dp_n each (p_A = p_T = 0, p_P = p_B = dp_n); P->B, A->T at 0 */
    const double p1[4] = {DPN, 0, 0, DPN};
    int st = bench(&vs, 1.0, p1, hold, 0, q, pr, NULL);
    tap_ok(st == BG_OK, "rated, u = +1: solved");
    tap_close(q[0], want, 1e-12, 0, "rated, u = +1: P->A passes q_n + G_l dp_n = %.9g m^3/s", want);
    tap_close(-q[2], want, 1e-12, 0, "rated, u = +1: out of A, q_n + G_l dp_n");
    tap_close(q[3], want, 1e-12, 0, "rated, u = +1: B->T passes q_n + G_l dp_n");
    tap_close(-q[1], want, 1e-12, 0, "rated, u = +1: into the tank, q_n + G_l dp_n");
    /* u = -1: P->B and A->T */
    const double p2[4] = {DPN, 0, DPN, 0};
    st = bench(&vs, -1.0, p2, hold, 0, q, pr, NULL);
    tap_ok(st == BG_OK && fabs(q[0] - want) < 1e-12 * want && fabs(q[3] + want) < 1e-12 * want &&
               fabs(q[2] - want) < 1e-12 * want,
           "rated, u = -1: P->B and A->T pass q_n + G_l dp_n (%.9g, %.9g, %.9g m^3/s)", q[0], -q[3],
           q[2]);
}

static void test_symmetry(void)
{
    hyd_directional_spec vs = {
        .flow_rated = QN, .dp_rated = DPN, .underlap = 0.05, .leakage = 3e-13};
    const int hold[4] = {HOLD_PRESSURE, HOLD_PRESSURE, HOLD_PRESSURE, HOLD_PRESSURE};
    const double pp[4] = {2e7, 1e5, 1.2e7, 4e6}, pm[4] = {2e7, 1e5, 4e6, 1.2e7};
    double qp[4], qm[4], pr[4];
    int a = bench(&vs, 0.37, pp, hold, 0, qp, pr, NULL);
    int b = bench(&vs, -0.37, pm, hold, 0, qm, pr, NULL);
    double err =
        fabs(qp[0] - qm[0]) + fabs(qp[1] - qm[1]) + fabs(qp[2] - qm[3]) + fabs(qp[3] - qm[2]);
    tap_ok(a == BG_OK && b == BG_OK && err < 1e-12 * fabs(qp[0]),
           "symmetry: u = +-0.37 with p_A, p_B swapped swaps q_A and q_B (q_P %.9g, %.9g; q_A "
           "%.9g = q_B %.9g; error %.3g)",
           qp[0], qm[0], qp[2], qm[3], err);
    tap_ok(qp[2] < 0 && qp[3] > 0, "symmetry: u > 0 feeds A and drains B");
}

static void test_series(void)
{
    /* dp_l = 1e-3 dp_n: the orifice is within (dp_l / dp)^2 / 4 of the turbulent law */
    hyd_directional_spec vs = {.flow_rated = QN, .dp_rated = DPN, .dp_laminar = 1e-3 * DPN};
    const int hold[4] = {HOLD_PRESSURE, HOLD_PRESSURE, HOLD_LOAD, HOLD_LOAD};
    const double ps = 1.5e7, pT = 2e5, u = 0.5, GL = 1e-9, p[4] = {ps, pT, 0, 0};
    double q[4], pr[4];
    int st = bench(&vs, u, p, hold, GL, q, pr, NULL);
    /* p_s - p_T = 2 (Q / (K_t a))^2 + Q / G_L */
    double Kt = QN / sqrt(DPN), al = 2 / (Kt * u * Kt * u), dp = ps - pT;
    double Q = (-1 / GL + sqrt(1 / (GL * GL) + 4 * al * dp)) / (2 * al);
    double dpe = (Q / (Kt * u)) * (Q / (Kt * u)), bound = 0.25 * pow(1e-3 * DPN / dpe, 2) + 0.25e-6;
    tap_ok(st == BG_OK && fabs(q[0] - Q) <= 2 * bound * Q + 1e-12 * Q,
           "series P->A->load->B->T: Q = %.9g m^3/s, the orifice series gives %.9g (rel. %.2g, "
           "bound %.2g)",
           q[0], Q, fabs(q[0] / Q - 1), 2 * bound);
    tap_close(pr[2] - pr[3], Q / GL, 2 * bound + 1e-12, 0,
              "series: the load's drop Q / G_L = %.6g Pa; each edge drops %.6g Pa", Q / GL, dpe);
    tap_close(-q[1], q[0], 1e-12, 0, "series: all of it returns to the tank");
}

static void test_centre(void)
{
    const double ps = 1e7, pc[4] = {ps, 0, 0.5 * ps, 0.5 * ps};
    const int hold[4] = {HOLD_PRESSURE, HOLD_PRESSURE, HOLD_PRESSURE, HOLD_PRESSURE};
    double q[4], pr[4];
    /* critically centred with leakage: leakage only, plus the opening's residue */
    hyd_directional_spec vs = {
        .flow_rated = QN, .dp_rated = DPN, .leakage = 8e-13, .spool_smoothing = 1e-5};
    int rg = -1;
    int st = bench(&vs, 0.0, pc, hold, 0, q, pr, &rg);
    double leak = 2 * vs.leakage * 0.5 * ps;
    double resid = 2 * 1e-5 * log(2.0) * QN * sqrt(0.5 * ps / DPN) * 1.01;
    tap_ok(st == BG_OK && fabs(q[0] - leak) <= resid && resid < 1e-2 * leak,
           "centre, critically centred: q_P = %.6g m^3/s, leakage 2 G_l (p_s / 2) = %.6g (within "
           "the smoothing residue %.3g)",
           q[0], leak, resid);
    tap_ok(rg == 4 * 2 + 2, "centre: both switches in their band, regime %d (4*2 + 2)", rg);
    hyd_directional_spec tight = {.flow_rated = QN, .dp_rated = DPN, .spool_smoothing = 1e-5};
    st = bench(&tight, 0.0, pc, hold, 0, q, pr, NULL);
    tap_ok(st == BG_OK && fabs(q[0]) <= resid,
           "centre, no leakage: q_P = %.3g m^3/s, only the residue (<= %.3g)", q[0], resid);
    /* underlap: A and B closed settle at p_s / 2; centre flow through P->A->T and P->B->T */
    hyd_directional_spec ul = {
        .flow_rated = QN, .dp_rated = DPN, .underlap = 0.04, .dp_laminar = 1e-3 * DPN};
    const int holdc[4] = {HOLD_PRESSURE, HOLD_PRESSURE, HOLD_CLOSED, HOLD_CLOSED};
    st = bench(&ul, 0.0, pc, holdc, 0, q, pr, NULL);
    double a0 = 0.04 / 1.04, Qc = 2 * QN * a0 * sqrt(0.5 * ps / DPN);
    double b2 = 0.25 * pow(1e-3 * DPN / (0.5 * ps), 2) + 0.25 * 1e-6;
    tap_ok(st == BG_OK && fabs(pr[2] - 0.5 * ps) < 1e-9 * ps && fabs(pr[3] - 0.5 * ps) < 1e-9 * ps,
           "underlap 4 %%: closed A and B held at p_s / 2 = %g Pa (%.9g, %.9g)", 0.5 * ps, pr[2],
           pr[3]);
    tap_ok(fabs(q[0] - Qc) <= 2 * b2 * Qc,
           "underlap 4 %%: centre flow 2 q_n u0/(1+u0) sqrt(p_s/(2 dp_n)) = %.9g m^3/s (%.9g, "
           "bound %.2g)",
           Qc, q[0], 2 * b2);
    /* the regimes at full command: u = +1 opens one pair fully, the other is off */
    hyd_directional_spec plain = {.flow_rated = QN, .dp_rated = DPN};
    int rp = -1, rm = -1;
    bench(&plain, 1.0, pc, hold, 0, q, pr, &rp);
    bench(&plain, -1.0, pc, hold, 0, q, pr, &rm);
    tap_ok(rp == 12 && rm == 3, "regime: u = +1 gives 4*3 + 0 = %d, u = -1 gives 0 + 3 = %d", rp,
           rm);
}

/* Every partial derivative, near both switches (a wide smoothing and the command in it) and
 * past them, with the bonds of both orientations. */
static void test_jacobian(void)
{
    const double us[3] = {0.03, -0.6, 1.1};
    for (int k = 0; k < 3; k++) {
        hyd_directional_spec vs = {.flow_rated = 1.3,
                                   .dp_rated = 0.9,
                                   .underlap = 0.02,
                                   .leakage = 0.2,
                                   .dp_laminar = 0.3,
                                   .spool_smoothing = 0.05};
        bgr_model *m = bgr_model_create("jac");
        int cmd = sig_constant(m, 0, "command", us[k], SIG_VALUE);
        int v = hyd_directional_valve(m, 0, "valve", (bgr_ref){BGR_OWN, cmd, 0}, &vs);
        int h[4];
        const char *nm[4] = {"sP", "sT", "sA", "sB"};
        for (int i = 0; i < 4; i++)
            h[i] = hyd_tank(m, 0, nm[i], 0.1 * i);
        B(m, "bP", h[0], 0, v, 0);
        B(m, "bT", v, 1, h[1], 0); /* reversed */
        B(m, "bA", v, 2, h[2], 0); /* reversed */
        B(m, "bB", h[3], 0, v, 3);
        if (!compile_ok(m, "jacobian")) {
            bgr_model_free(&m);
            continue;
        }
        int n = bgr_n(m);
        double *y = calloc((size_t)n, sizeof *y), *yp = calloc((size_t)n, sizeof *yp);
        random_point(n, NULL, 31 + (uint64_t)k, y, yp);
        int vu = V(m, "jac/command/value");
        if (vu >= 0) y[vu] = us[k];
        char what[64];
        snprintf(what, sizeof what, "directional valve at u = %g", us[k]);
        check_jac(m, 0.0, y, yp, 1e-6, what);
        free(y);
        free(yp);
        bgr_model_free(&m);
    }
}

/* The valve with spec field which (0 .. 5 in the order of hyd_directional_spec) replaced by x;
 * which < 0: valid. */
static int mk_valve(bgr_model *m, bgr_comp c, const char *name, int which, double x)
{
    hyd_directional_spec s = {.flow_rated = QN,
                              .dp_rated = DPN,
                              .underlap = 0.02,
                              .leakage = 1e-13,
                              .dp_laminar = 1e4,
                              .spool_smoothing = 1e-3};
    double *f[6] = {&s.flow_rated, &s.dp_rated,   &s.underlap,
                    &s.leakage,    &s.dp_laminar, &s.spool_smoothing};
    if (which >= 0) *f[which] = x;
    return hyd_directional_valve(m, c, name, (bgr_ref){BGR_OWN, 0, 0}, &s);
}

static void test_param_checks(void)
{
    const double inf = INFINITY, nan = NAN;
    const char *POS = "expected a finite number > 0", *NNEG = "expected a finite number >= 0";
    const pc_case cases[] = {
        {"hyd_directional_valve", mk_valve, 0, 0.0, "flow_rated = 0", POS},
        {"hyd_directional_valve", mk_valve, 0, nan, "flow_rated = nan", POS},
        {"hyd_directional_valve", mk_valve, 1, -35e5, "dp_rated = -3.5e+06", POS},
        {"hyd_directional_valve", mk_valve, 1, inf, "dp_rated = inf", POS},
        {"hyd_directional_valve", mk_valve, 2, -0.01, "underlap = -0.01", NNEG},
        {"hyd_directional_valve", mk_valve, 2, 0.6, "underlap = 0.6", "expected 0 .. 0.5"},
        {"hyd_directional_valve", mk_valve, 3, -1e-12, "leakage = -1e-12", NNEG},
        {"hyd_directional_valve", mk_valve, 4, -1.0, "dp_laminar = -1", NNEG},
        {"hyd_directional_valve", mk_valve, 4, 4e6, "dp_laminar = 4e+06",
         "expected > 0 and <= dp_rated = 3.5e+06"},
        {"hyd_directional_valve", mk_valve, 5, nan, "spool_smoothing = nan", NNEG},
        {"hyd_directional_valve", mk_valve, 5, 0.2, "spool_smoothing = 0.2",
         "expected > 0 and <= 0.1"},
    };
    const int n = (int)(sizeof cases / sizeof cases[0]);
    bgr_model *m = bgr_model_create("params");
    bgr_comp c = bgr_component(m, 0, "drive");
    int cmd = sig_constant(m, 0, "command", 0.5, SIG_VALUE);
    int passed = pc_run(m, c, "valve", cases, n);
    tap_diag("%d of %d refusals as required", passed, n);
    int st = hyd_directional_valve(m, c, "nospec", (bgr_ref){BGR_OWN, cmd, 0}, NULL);
    tap_ok(st == BG_ERR_ARGUMENT && strstr(bgr_model_error(m)->message, "params/drive/nospec") &&
               strstr(bgr_model_error(m)->message, "spec = NULL"),
           "spec NULL refused: %s", bgr_model_error(m)->message);
    bgr_model_free(&m);

    /* a command that names no unknown: reported by bgr_compile */
    hyd_directional_spec vs = {.flow_rated = QN, .dp_rated = DPN};
    m = bgr_model_create("nocmd");
    int v = hyd_directional_valve(m, 0, "valve", (bgr_ref){BGR_OWN, 99, 0}, &vs);
    const char *nm[4] = {"sP", "sT", "sA", "sB"};
    for (int i = 0; i < 4; i++)
        B(m, nm[i], hyd_tank(m, 0, nm[i], 0.0), 0, v, i);
    st = bgr_compile(m);
    tap_ok(st == BG_ERR_ARGUMENT && strstr(bgr_model_error(m)->message, "valve") &&
               strstr(bgr_model_error(m)->message, "command refers to no unknown"),
           "a command that names no unknown: bgr_compile says %s", bgr_model_error(m)->message);
    bgr_model_free(&m);
}

int main(void)
{
    test_rated();
    test_symmetry();
    test_series();
    test_centre();
    test_jacobian();
    test_param_checks();
    return tap_done();
}
