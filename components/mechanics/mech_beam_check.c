/* The beam element's argument checks (mech_beam_impl.h), shared with the chain builder so that
 * both refuse with the same messages before anything is built. */
#include <math.h>
#include <string.h>

#include "mech_beam_impl.h"

/* BG_OK if the section obeys the rules of mech_beam.h (where: the constructor), else the
 * refusal naming the field. */
int mech_beam_bad_section_(bgr_model *m, bgr_comp c, const char *name, const char *w,
                           const mech_section *s)
{
    if (!s) return bgr_refuse(m, c, name, w, "the section is NULL");
    if (bgr_check_value(m, c, name, w, "section.E", s->E, BGR_POSITIVE) ||
        bgr_check_value(m, c, name, w, "section.G", s->G, BGR_POSITIVE) ||
        bgr_check_value(m, c, name, w, "section.A", s->A, BGR_POSITIVE) ||
        bgr_check_value(m, c, name, w, "section.Iy", s->Iy, BGR_POSITIVE) ||
        bgr_check_value(m, c, name, w, "section.Iz", s->Iz, BGR_POSITIVE) ||
        bgr_check_value(m, c, name, w, "section.J", s->J, BGR_POSITIVE) ||
        bgr_check_value(m, c, name, w, "section.rho", s->rho, BGR_NONNEGATIVE) ||
        bgr_check_value(m, c, name, w, "section.kappa", s->kappa, BGR_NONNEGATIVE) ||
        bgr_check_value(m, c, name, w, "section.beta", s->beta, BGR_NONNEGATIVE))
        return BG_ERR_ARGUMENT;
    if (s->element != MECH_BEAM_LUMPED && s->element != MECH_BEAM_CONSISTENT &&
        s->element != MECH_BEAM_QUARTIC)
        return bgr_refuse(m, c, name, w,
                          "section.element = %d, expected MECH_BEAM_LUMPED (0), "
                          "MECH_BEAM_CONSISTENT (1) or MECH_BEAM_QUARTIC (2)",
                          s->element);
    return BG_OK;
}

/* BG_OK if E0 is a finite right-handed orthonormal frame (to 1e-9), else the refusal. */
int mech_beam_bad_frame_(bgr_model *m, bgr_comp c, const char *name, const char *w, const double *E0)
{
    if (!E0) return bgr_refuse(m, c, name, w, "the initial frame E0 is NULL");
    if (bgr_check_values(m, c, name, w, "E0", E0, 9, BGR_FINITE)) return BG_ERR_ARGUMENT;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            double d = mech_dot(E0 + 3 * i, E0 + 3 * j) - (i == j);
            if (!(fabs(d) <= 1e-9))
                return bgr_refuse(m, c, name, w,
                                  "E0's columns %d and %d have the product %g, expected an "
                                  "orthonormal frame (column products 1 and 0 to 1e-9)",
                                  i, j, d + (i == j));
        }
    double e3[3];
    mech_cross(E0, E0 + 3, e3);
    if (!(mech_dot(e3, E0 + 6) > 0))
        return bgr_refuse(m, c, name, w, "E0 is left-handed, expected e3 = e1 x e2");
    return BG_OK;
}

/* BG_OK if node is a rigid body (mech_body) of m, else the refusal naming param. */
int mech_beam_bad_node_(bgr_model *m, bgr_comp c, const char *name, const char *w, const char *param,
                    int node)
{
    bgr_element *b = bgr_element_get(m, node);
    if (b && b->nstates == 13 && !strcmp(b->cls->type, "body")) return BG_OK;
    return bgr_refuse(m, c, name, w, "%s = %d, expected the element id of a rigid body (mech_body)",
                      param, node);
}
