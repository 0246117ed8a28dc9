/* What the program reads from a built crane (crane_model.h): the solver's problem, the
 * reference's breakpoints, the output quantities, energies and power, the model statistics
 * with the nominal scales by quantity, and the geometry of the 3-D output. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "crane_model_impl.h"
#include "mech_axial.h"
#include "mech_beam.h"
#include "mech_body.h"
#include "mech_parts.h"

int crane_dae_problem(crane *c, dae_problem *p)
{
    if (!c || !p) return BG_ERR_ARGUMENT;
    int r = bgr_dae_problem(c->m, p);
    if (r == BG_OK && !c->s.nominal_scales) p->nominal = NULL;
    return r;
}

bgr_model *crane_model(crane *c)
{
    return c ? c->m : NULL;
}

double crane_tie_length(const crane *c)
{
    return c->s.ties ? c->tie_L0 : 0.0;
}

const crane_scene *crane_get_scene(const crane *c)
{
    return c ? &c->s : NULL;
}

int crane_energy(const crane *c, const double *y, double *kinetic, double *potential,
                 double *elastic)
{
    const bgr_model *m = c->m;
    double T = 0, V = 0, U = 0, t, v;
    int bodies[MAXEL + 3], nb = 0, st = BG_OK;
    bodies[nb++] = c->platform;
    if (c->n > 0)
        for (int k = 0; k <= c->n; k++)
            bodies[nb++] = c->nodes[k];
    else
        bodies[nb++] = c->boom;
    for (int k = 0; k < nb && st == BG_OK; k++)
        if ((st = mech_body_energy(m, bodies[k], y, &t, &v)) == BG_OK) T += t, V += v;
    if (c->s.rope && st == BG_OK && (st = mech_point_mass_energy(m, c->load, y, &t, &v)) == BG_OK)
        T += t, V += v;
    if (c->s.counterweight && st == BG_OK &&
        (st = mech_point_mass_energy(m, c->cw, y, &t, &v)) == BG_OK)
        T += t, V += v;
    for (int k = 0; k < c->n; k++)
        U += mech_beam_energy(m, c->elems[k], y);
    for (int k = 0; k < c->nties; k++)
        U += mech_axial_energy(m, c->tie[k], y);
    if (c->s.rope) U += mech_axial_energy(m, c->rope, y);
    *kinetic = T;
    *potential = V;
    *elastic = U;
    return st;
}

double crane_dissipation(const crane *c, const double *y)
{
    double P = 0;
    for (int k = 0; k < c->n; k++)
        P += mech_beam_dissipation(c->m, c->elems[k], y);
    for (int k = 0; k < c->nties; k++)
        P += mech_axial_dissipation(c->m, c->tie[k], y);
    if (c->s.rope) P += mech_axial_dissipation(c->m, c->rope, y);
    return P;
}

double crane_drive_power(const crane *c, const double *y)
{
    int e = bgr_ref_var(c->m, (bgr_ref){BGR_EFFORT, c->drive_bond, 0});
    int f = bgr_ref_var(c->m, (bgr_ref){BGR_FLOW, c->drive_bond, 0});
    return e >= 0 && f >= 0 ? y[e] * y[f] : NAN;
}

int crane_breakpoints(const crane *c, double *t, int max)
{
    return bgr_breakpoints(c->m, 0.0, c->s.t_end, t, max);
}

const char *const crane_output_names[CRANE_NOUT] = {"t [s]",
                                                    "theta [rad]",
                                                    "theta_ref [rad]",
                                                    "omega [rad/s]",
                                                    "omega_ref [rad/s]",
                                                    "omega_err [rad/s]",
                                                    "alpha_err [rad/s^2]",
                                                    "tip_x [m]",
                                                    "tip_y [m]",
                                                    "tip_z [m]",
                                                    "tip_defl_1 [m]",
                                                    "tip_defl_2 [m]",
                                                    "load_x [m]",
                                                    "load_y [m]",
                                                    "load_z [m]",
                                                    "rope_force [N]",
                                                    "pump_x [-]",
                                                    "p_high [Pa]",
                                                    "p_low [Pa]",
                                                    "constraint_drift [m]"};

int crane_output_index(const char *key)
{
    if (!key) return -1;
    size_t n = strlen(key);
    for (int i = 0; i < CRANE_NOUT; i++) {
        const char *nm = crane_output_names[i];
        if (nm && !strncmp(nm, key, n) && (nm[n] == '\0' || nm[n] == ' ')) return i;
    }
    return -1;
}

void crane_outputs(const crane *c, double t, const double *y, const double *yp, double *out)
{
    const crane_scene *s = &c->s;
    double tip[3], foot[3], hinge[3];
    out[0] = t;
    out[1] = y[c->v_theta];
    out[2] = y[c->v_theta_ref];
    out[3] = y[c->v_omega];
    out[4] = y[c->v_omega_ref];
    /* errors ref - value; the acceleration: the measured one (paper's PID law) or omega' */
    out[5] = y[c->v_omega_ref] - y[c->v_omega];
    out[6] = y[c->v_alpha_ref] - (c->v_alpha >= 0 ? y[c->v_alpha] : yp[c->v_omega]);
    boom_ends(c, y, tip, foot);
    memcpy(out + 7, tip, sizeof tip);
    /* deflection: the tip turned back by the platform's angle (about the axis through A)
     * against the static tip, along the boom's transverse directions */
    double th = y[c->v_theta], cs = cos(th), sn = sin(th), d[3];
    const double *A = s->joint_A;
    d[0] = A[0] + cs * (tip[0] - A[0]) + sn * (tip[1] - A[1]) - c->tip0[0];
    d[1] = A[1] - sn * (tip[0] - A[0]) + cs * (tip[1] - A[1]) - c->tip0[1];
    d[2] = tip[2] - c->tip0[2];
    out[10] = mech_dot(d, c->e2);
    out[11] = mech_dot(d, c->e3);
    for (int i = 0; i < 3; i++)
        out[12 + i] = c->v_load >= 0 ? y[c->v_load + i] : NAN;
    out[15] = s->rope ? mech_axial_tension(c->m, c->rope, y) : NAN;
    out[16] = c->v_x >= 0 ? y[c->v_x] : NAN;
    out[17] = c->v_ph >= 0 ? y[c->v_ph] : NAN;
    out[18] = c->v_pl >= 0 ? y[c->v_pl] : NAN;
    /* the hinge's position mismatch: B on the platform against the boom's foot */
    double rB[3];
    sub3(s->boom_foot, s->platform_com, rB);
    body_point(y, c->v_plat_x, c->v_plat_q, rB, hinge);
    sub3(hinge, foot, d);
    out[19] = sqrt(mech_dot(d, d));
}

/* i .. i + k - 1 into idx at *m (i < 0: the part is missing, nothing). */
static void add_run(int *idx, int *m, int i, int k)
{
    for (int j = 0; i >= 0 && j < k && *m < CRANE_MAX_OUTPUT_UNKNOWNS; j++)
        idx[(*m)++] = i + j;
}

int crane_output_unknowns(const crane *c, int *idx)
{
    if (!c || !idx) return 0;
    int m = 0;
    const int one[] = {c->v_theta, c->v_theta_ref, c->v_omega, c->v_omega_ref, c->v_alpha_ref,
                       c->v_alpha,  c->v_x,         c->v_ph,    c->v_pl};
    for (size_t k = 0; k < sizeof one / sizeof *one; k++)
        add_run(idx, &m, one[k], 1);
    /* boom_ends: the tip and foot nodes, or the rigid boom's position and orientation */
    add_run(idx, &m, c->v_tip, 3);
    if (c->n > 0)
        add_run(idx, &m, c->v_node0, 3);
    else
        add_run(idx, &m, c->v_tipq, 4);
    add_run(idx, &m, c->v_plat_x, 3);
    add_run(idx, &m, c->v_plat_q, 4);
    add_run(idx, &m, c->v_load, 3);
    if (c->s.rope) { /* T(L, L'): the stretch vector d, the velocities at A and B */
        const bgr_element *el = bgr_element_get(c->m, c->rope);
        add_run(idx, &m, bgr_sv(el, 0), 3);
        for (int k = 0; k < 2; k++)
            add_run(idx, &m, bgr_fv(el, c->m, k, 0), 3);
    }
    return m;
}

int crane_stats_print(const crane *c, FILE *f)
{
    bgr_stats st;
    int rc = bgr_get_stats(c->m, &st);
    if (rc != BG_OK) return rc;
    fprintf(f, "%-34s %10s %10s\n", "model statistics", "this", "paper");
    fprintf(f, "%-34s %10d %10d\n", "equations (= unknowns)", st.equations, 3544);
    fprintf(f, "%-34s %10d %10d\n", "partial derivative matrix nnz", st.nnz_dy, 11303);
    fprintf(f, "%-34s %10d %10d\n", "time-rate matrix nnz", st.nnz_dyp, 438);
    fprintf(f, "%-34s %10d\n", "differential", st.differential);
    fprintf(f, "%-34s %10d\n", "algebraic (index 1)", st.algebraic);
    fprintf(f, "%-34s %10d\n", "algebraic (index 2)", st.index2);
    fprintf(f, "%-34s %10d\n", "elements", st.elements);
    fprintf(f, "%-34s %10d\n", "bonds", st.bonds);
    fprintf(f, "%-34s %10d\n", "components", st.components);
    fprintf(f, "%-34s %10d\n", "boom beam elements", c->n);
    /* unknowns by part (the first path segment under the model; bonds between parts together) */
    enum { MAXPART = 64 };
    char part[MAXPART][48];
    int cnt[MAXPART][3] = {{0}}, np = 0;
    const int *kinds = bgr_kinds(c->m);
    for (int i = 0; i < bgr_n(c->m); i++) {
        const char *nm = bgr_var_name(c->m, i), *a = nm ? strchr(nm, '/') : NULL;
        char key[48] = "(other)";
        if (a) {
            size_t len = strcspn(a + 1, "/");
            if (strncmp(a + 1, "b_", 2) == 0)
                strcpy(key, "(bonds between parts)");
            else
                snprintf(key, sizeof key, "%.*s", (int)(len < 47 ? len : 47), a + 1);
        }
        int k = 0;
        while (k < np && strcmp(part[k], key) != 0)
            k++;
        if (k == np) {
            if (np == MAXPART)
                k = np - 1; /* the last row collects the rest */
            else
                strcpy(part[np++], key);
        }
        cnt[k][kinds[i]]++;
    }
    fprintf(f, "\n%-34s %10s %10s %10s\n", "unknowns by part", "diff", "alg", "index 2");
    for (int k = 0; k < np; k++)
        fprintf(f, "%-34s %10d %10d %10d\n", part[k], cnt[k][0], cnt[k][1], cnt[k][2]);
    /* the nominal scales by quantity (scene [solver] nominal_scales) */
    enum { MAXDOM = 16 };
    const char *dom[MAXDOM];
    int nd = 0, dcnt[MAXDOM] = {0};
    double dmin[MAXDOM], dmax[MAXDOM];
    const double *nom = bgr_nominals(c->m);
    for (int i = 0; nom && i < bgr_n(c->m); i++) {
        const char *d = crane_domain_of(bgr_var_name(c->m, i));
        int k = 0;
        while (k < nd && strcmp(dom[k], d) != 0)
            k++;
        if (k == nd) {
            if (nd == MAXDOM) continue; /* the classification has fewer quantities */
            dom[nd] = d;
            dmin[nd] = dmax[nd] = nom[i];
            nd++;
        }
        dcnt[k]++;
        dmin[k] = fmin(dmin[k], nom[i]);
        dmax[k] = fmax(dmax[k], nom[i]);
    }
    fprintf(f, "\n%-34s %10s %10s %10s\n", "nominal scales by quantity", "unknowns", "min", "max");
    for (int k = 0; k < nd; k++)
        fprintf(f, "%-34s %10d %10.3g %10.3g\n", dom[k], dcnt[k], dmin[k], dmax[k]);
    fprintf(f,
            "(the absolute tolerance of an unknown is atol times its nominal scale; scene "
            "[solver] nominal_scales = %s)\n",
            c->s.nominal_scales ? "true" : "false: all 1");
    return BG_OK;
}

/* ------------------------------------------------------------ geometry ---- */

_Static_assert(CRANE_MAX_NODES == MAXEL + 1, "crane_geom holds every boom node");

/* A point given in the platform frame, global at the state y. */
static void platform_point(const crane *c, const double *y, const double *r, double *p)
{
    double rc[3];
    sub3(r, c->s.platform_com, rc);
    body_point(y, c->v_plat_x, c->v_plat_q, rc, p);
}

/* Boom node k at the state y: a beam node's centre, or the rigid boom's foot (0) and tip (1). */
static void boom_node(const crane *c, const double *y, int k, double *p)
{
    if (c->n > 0)
        memcpy(p, y + mech_body_var(c->m, c->nodes[k], 'x'), 3 * sizeof *p);
    else
        body_point(y, c->v_tip, c->v_tipq, k ? c->tip_r : c->foot_r, p);
}

static void unit3(double *a)
{
    double n = sqrt(mech_dot(a, a));
    if (n > 0)
        for (int i = 0; i < 3; i++)
            a[i] /= n;
}

int crane_geometry(const crane *c, double t, const double *y, const double *yp, crane_geom *g)
{
    if (!c || !y || !g) return BG_ERR_ARGUMENT;
    (void)yp;
    const crane_scene *s = &c->s;
    const double *y0 = bgr_y0(c->m), *A = s->joint_A;
    memset(g, 0, sizeof *g);
    g->t = t;
    g->theta = y[c->v_theta];
    g->omega = y[c->v_omega];
    memcpy(g->platform_x, y + c->v_plat_x, sizeof g->platform_x);
    mech_quat_R(y + c->v_plat_q, g->platform_R, NULL);
    memcpy(g->joint_A, A, sizeof g->joint_A);
    /* the platform: deck, hinge, gantry (platform frame, then carried along) */
    double lo[3], hi[3], p[3];
    memcpy(lo, A, sizeof lo);
    memcpy(hi, A, sizeof hi);
    g->ngantry = c->nties == 2 ? 2 : 1;
    for (int k = 0; k < 3 + g->ngantry; k++) {
        if (k == 2 && !s->counterweight) continue;
        if (k < 3)
            memcpy(p, k == 0 ? s->boom_foot : k == 1 ? s->gantry_top : s->cw_pos, sizeof p);
        else
            gantry_point(s, k - 3, c->nties, p);
        for (int i = 0; i < 2; i++)
            lo[i] = fmin(lo[i], p[i] - 1), hi[i] = fmax(hi[i], p[i] + 1);
    }
    const double corner[4][2] = {{lo[0], lo[1]}, {hi[0], lo[1]}, {hi[0], hi[1]}, {lo[0], hi[1]}};
    for (int k = 0; k < 4; k++) {
        double r[3] = {corner[k][0], corner[k][1], A[2]};
        platform_point(c, y, r, g->deck[k]);
    }
    platform_point(c, y, s->boom_foot, g->hinge);
    platform_point(c, y, s->gantry_top, g->gantry_top);
    for (int k = 0; k < g->ngantry; k++) {
        gantry_point(s, k, c->nties, p);
        platform_point(c, y, p, g->gantry[k]);
        p[2] = A[2];
        platform_point(c, y, p, g->gantry_base[k]);
    }
    /* the boom: nodes and their displacements from the start carried round by theta */
    double cs = cos(g->theta), sn = sin(g->theta), e2[3], e3[3];
    e2[0] = cs * c->e2[0] - sn * c->e2[1], e2[1] = sn * c->e2[0] + cs * c->e2[1], e2[2] = c->e2[2];
    e3[0] = cs * c->e3[0] - sn * c->e3[1], e3[1] = sn * c->e3[0] + cs * c->e3[1], e3[2] = c->e3[2];
    g->beam = c->n > 0;
    g->nodes = c->n > 0 ? c->n + 1 : 2;
    for (int k = 0; k < g->nodes; k++) {
        double p0[3], r[3], *d = g->defl[k];
        boom_node(c, y, k, g->node[k]);
        boom_node(c, y0, k, p0);
        r[0] = A[0] + cs * (p0[0] - A[0]) - sn * (p0[1] - A[1]);
        r[1] = A[1] + sn * (p0[0] - A[0]) + cs * (p0[1] - A[1]);
        r[2] = p0[2];
        sub3(g->node[k], r, d);
        g->defl_luff[k] = mech_dot(d, e2);
        g->defl_side[k] = mech_dot(d, e3);
    }
    /* section loads: element k's port loads (F_a, M_a, F_b, M_b) act on the element */
    for (int k = 0; k < c->n; k++) {
        double L[12];
        if (mech_beam_loads(c->m, c->elems[k], y, 0, L) != BG_OK) return BG_ERR_ARGUMENT;
        for (int i = 0; i < 3; i++) {
            g->force[k][i] -= L[i], g->moment[k][i] -= L[3 + i];
            g->force[k + 1][i] += L[6 + i], g->moment[k + 1][i] += L[9 + i];
        }
    }
    for (int k = 0; k < g->nodes && g->beam; k++) {
        double b1[3], b2[3], b3[3], w = k > 0 && k < c->n ? 0.5 : 1.0;
        sub3(g->node[k < c->n ? k + 1 : k], g->node[k > 0 ? k - 1 : k], b1);
        unit3(b1);
        for (int i = 0; i < 3; i++)
            b2[i] = e2[i] - mech_dot(e2, b1) * b1[i];
        unit3(b2);
        mech_cross(b1, b2, b3);
        if (mech_dot(b3, e3) < 0)
            for (int i = 0; i < 3; i++)
                b3[i] = -b3[i];
        for (int i = 0; i < 3; i++)
            g->force[k][i] *= w, g->moment[k][i] *= w;
        const double *b[3] = {b1, b2, b3};
        for (int i = 0; i < 3; i++) {
            g->force_local[k][i] = mech_dot(g->force[k], b[i]);
            g->moment_local[k][i] = mech_dot(g->moment[k], b[i]);
        }
    }
    /* ties, rope and load, counterweight, drive */
    g->nties = c->nties;
    for (int k = 0; k < c->nties; k++)
        g->tie_tension[k] = mech_axial_tension(c->m, c->tie[k], y);
    g->rope = s->rope;
    if (s->rope) {
        memcpy(g->load, y + c->v_load, sizeof g->load);
        g->load_mass = s->load_mass;
        g->rope_tension = mech_axial_tension(c->m, c->rope, y);
    }
    g->counterweight = s->counterweight;
    if (s->counterweight) {
        int v = bgr_ref_var(c->m, (bgr_ref){BGR_STATE, c->cw, 0});
        if (v < 0) return BG_ERR_ARGUMENT;
        memcpy(g->cw, y + v, sizeof g->cw);
        g->cw_mass = s->cw_mass;
    }
    g->pump_x = c->v_x >= 0 ? y[c->v_x] : NAN;
    g->p_high = c->v_ph >= 0 ? y[c->v_ph] : NAN;
    g->p_low = c->v_pl >= 0 ? y[c->v_pl] : NAN;
    return BG_OK;
}
