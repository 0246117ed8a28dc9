/* The kinds of unknowns under a frame's motion (bgr_declare_frame, bgr_model.h) and the
 * generator of a steadily rotating frame built from them (bgr_frame_rotation,
 * bgr_analysis.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bgr_analysis.h"
#include "bgr_model_impl.h"

int bgr_declare_frame(bgr_element *el, bgr_model *m, int kind, const int *vars)
{
    const char *w = "bgr_declare_frame";
    if (!m) return BG_ERR_ARGUMENT;
    if (!el || el->id < 0 || el->id >= m->nel || m->el[el->id] != el)
        return bgri_fail(m, BG_ERR_ARGUMENT, w, "the element is not one of model %s",
                         m->comp[0].path);
    if (!m->compiling)
        return bgri_fail(m, BG_ERR_STATE, w,
                         "element %s/%s: %s is called only from the element's declare() during "
                         "bgr_compile",
                         m->comp[el->comp].path, el->name, w);
    int len = kind == BGR_FRAME_QUATERNION ? 4 : 3;
    if ((kind != BGR_FRAME_VECTOR && kind != BGR_FRAME_POSITION && kind != BGR_FRAME_QUATERNION) ||
        !vars)
        return bgri_fail(m, BG_ERR_ARGUMENT, "bgr_compile",
                         "element %s/%s declares a frame kind %d%s: expected BGR_FRAME_VECTOR, "
                         "BGR_FRAME_POSITION or BGR_FRAME_QUATERNION with its unknowns",
                         m->comp[el->comp].path, el->name, kind, vars ? "" : " without unknowns");
    for (int i = 0; i < len; i++)
        if (vars[i] < 0 || vars[i] >= m->n)
            return bgri_fail(m, BG_ERR_ARGUMENT, "bgr_compile",
                             "element %s/%s declares the frame kind of variable %d: out of range "
                             "(0 .. %d)",
                             m->comp[el->comp].path, el->name, vars[i], m->n - 1);
    if (!m->fkind && !(m->fkind = calloc((size_t)m->n + 1, sizeof *m->fkind)))
        return bgri_fail(m, BG_ERR_MEMORY, "bgr_compile", "out of memory");
    /* the same group again: nothing to add; any overlap with another: refused (fkind: the
     * group of each unknown, + 1) */
    int g0 = m->fkind[vars[0]] - 1, same = g0 >= 0 && m->fgroup[g0][0] == kind, any = 0;
    for (int i = 0; i < len; i++) {
        any |= m->fkind[vars[i]] != 0;
        same = same && m->fkind[vars[i]] == g0 + 1 && m->fgroup[g0][1 + i] == vars[i];
    }
    if (same) return BG_OK;
    if (any)
        return bgri_fail(m, BG_ERR_ARGUMENT, "bgr_compile",
                         "element %s/%s declares a frame kind for %s, which another declaration "
                         "puts in a different group or kind",
                         m->comp[el->comp].path, el->name, m->vname[vars[0]]);
    if (m->nfgroup == m->capfgroup) {
        int cap = m->capfgroup ? 2 * m->capfgroup : 16;
        int(*ng)[5] = realloc(m->fgroup, (size_t)cap * sizeof *ng);
        if (!ng) return bgri_fail(m, BG_ERR_MEMORY, "bgr_compile", "out of memory");
        m->fgroup = ng;
        m->capfgroup = cap;
    }
    int *G = m->fgroup[m->nfgroup++];
    G[0] = kind;
    G[4] = -1;
    for (int i = 0; i < len; i++) {
        G[1 + i] = vars[i];
        m->fkind[vars[i]] = m->nfgroup;
    }
    return BG_OK;
}

int bgr_frame_rotation(const bgr_model *m, const double *axis, double rate, const double *point,
                       sp_csc **S, double *c)
{
    const char *w = "bgr_frame_rotation";
    if (S) *S = NULL;
    if (!m) return BG_ERR_ARGUMENT;
    int st = bgri_need_compiled(m, w);
    if (st != BG_OK) return st;
    if (!S || !axis) return bgri_fail_c(m, BG_ERR_ARGUMENT, w, "%s is NULL", !S ? "S" : "axis");
    double a = 0;
    for (int i = 0; i < 3; i++)
        a += axis[i] * axis[i];
    a = sqrt(a);
    if (!(a > 0 && isfinite(a)) || !isfinite(rate) ||
        (point && !(isfinite(point[0]) && isfinite(point[1]) && isfinite(point[2]))))
        return bgri_fail_c(m, BG_ERR_ARGUMENT, w,
                           "the axis must be finite and nonzero, the rate and the point finite "
                           "(axis (%g, %g, %g), rate %g)",
                           axis[0], axis[1], axis[2], rate);
    double W[3] = {rate * axis[0] / a, rate * axis[1] / a, rate * axis[2] / a};
    /* Omega x v = K v, K the skew matrix of Omega; q' = (0, Omega/2) (x) q = L q */
    const double K[3][3] = {{0, -W[2], W[1]}, {W[2], 0, -W[0]}, {-W[1], W[0], 0}};
    const double h[3] = {0.5 * W[0], 0.5 * W[1], 0.5 * W[2]};
    const double L[4][4] = {{0, -h[0], -h[1], -h[2]},
                            {h[0], 0, -h[2], h[1]},
                            {h[1], h[2], 0, -h[0]},
                            {h[2], -h[1], h[0], 0}};
    sp_builder *B = sp_builder_create(m->n, m->n, 9 * m->nfgroup);
    if (!B) return bgri_fail_c(m, BG_ERR_MEMORY, w, "out of memory");
    if (c) memset(c, 0, (size_t)m->n * sizeof *c);
    int ok = 1;
    for (int g = 0; g < m->nfgroup && ok; g++) {
        const int *G = m->fgroup[g];
        if (G[0] == BGR_FRAME_QUATERNION) {
            for (int i = 0; i < 4 && ok; i++)
                for (int j = 0; j < 4 && ok; j++)
                    if (L[i][j] != 0) ok = sp_builder_add(B, G[1 + i], G[1 + j], L[i][j]) >= 0;
            continue;
        }
        for (int i = 0; i < 3 && ok; i++)
            for (int j = 0; j < 3 && ok; j++)
                if (K[i][j] != 0) ok = sp_builder_add(B, G[1 + i], G[1 + j], K[i][j]) >= 0;
        /* a point: x' = Omega x (x - p) = K x - K p */
        if (G[0] == BGR_FRAME_POSITION && c && point)
            for (int i = 0; i < 3; i++)
                c[G[1 + i]] = -(K[i][0] * point[0] + K[i][1] * point[1] + K[i][2] * point[2]);
    }
    *S = ok ? sp_builder_finish(B, NULL) : NULL;
    sp_builder_free(&B);
    if (!*S) return bgri_fail_c(m, BG_ERR_MEMORY, w, "out of memory");
    return BG_OK;
}
