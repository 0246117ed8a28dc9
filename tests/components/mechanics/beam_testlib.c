/* What the beam elements' tests share (beam_testlib.h). */
#include "beam_testlib.h"

#include <math.h>
#include <stdio.h>

#include "bgr_elements.h"
#include "mech_body.h"
#include "mech_parts.h"

static const double PI = 3.14159265358979323846;

bgr_model *bt_cantilever(const mech_section *section, int element, int n, double L, const double *g,
                         double Px, double P, int *nodes, int *elems)
{
    const double p0[3] = {0, 0, 0}, p1[3] = {L, 0, 0}, up[3] = {0, 0, 1};
    int extra[65];
    for (int k = 0; k <= n; k++)
        extra[k] = k == 0 || k == n;
    mech_section sec = *section;
    sec.element = element;
    bgr_model *m = bgr_model_create("cant");
    mech_beam_chain(m, 0, "beam", n, p0, p1, up, &sec, g, extra, NULL, nodes, elems);
    int clamp = mech_support(m, 0, "clamp", 6);
    bgr_bond(m, 0, "b_clamp", 6, bgr_port_of(m, clamp, 0),
             mech_beam_chain_port(m, nodes, n, extra, 0, 0), NULL, NULL);
    double load[6] = {Px, 0, -P, 0, 0, 0};
    int src = bgr_Se(m, 0, "tip_load", 6, load);
    bgr_bond(m, 0, "b_load", 6, bgr_port_of(m, src, 0),
             mech_beam_chain_port(m, nodes, n, extra, n, 0), NULL, NULL);
    if (bgr_compile(m) != BG_OK) {
        printf("# cantilever: %s\n", bgr_model_error(m)->message); /* a TAP comment */
        bgr_model_free(&m);
        return NULL;
    }
    mech_beam_chain_set(m, nodes, n, p0, p1);
    return m;
}

/* by Newton from its asymptote (n + 1/2) pi */
double bt_clamped_free_root(int n)
{
    double b = n == 0 ? 1.9 : (n + 0.5) * PI;
    for (int it = 0; it < 50; it++)
        b -= (cos(b) * cosh(b) + 1) / (cos(b) * sinh(b) - sin(b) * cosh(b));
    return b;
}

/* 3-point Gauss-Legendre on 400 panels */
double bt_slope_ratio(double b)
{
    const double gx[3] = {-sqrt(0.6), 0, sqrt(0.6)}, gw[3] = {5.0 / 9, 8.0 / 9, 5.0 / 9};
    double s = (cosh(b) + cos(b)) / (sinh(b) + sin(b)), num = 0, den = 0;
    for (int p = 0; p < 400; p++)
        for (int g = 0; g < 3; g++) {
            double x = b * (p + 0.5 + 0.5 * gx[g]) / 400;
            double ph = cosh(x) - cos(x) - s * (sinh(x) - sin(x));
            double dp = b * (sinh(x) + sin(x) - s * (cosh(x) - cos(x)));
            num += gw[g] * dp * dp;
            den += gw[g] * ph * ph;
        }
    return num / den;
}

double bt_total_energy(const bgr_model *m, const int *nodes, const int *elems, int n,
                       const double *y)
{
    double E = 0;
    for (int k = 0; k <= n; k++) {
        double T, V;
        mech_body_energy(m, nodes[k], y, &T, &V);
        E += T;
    }
    for (int k = 0; k < n; k++)
        E += mech_beam_energy(m, elems[k], y) + mech_beam_kinetic(m, elems[k], y);
    return E;
}
