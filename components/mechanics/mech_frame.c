/* The kinds of the mechanical unknowns under a frame's motion (mech_frame.h). */
#include "mech_frame.h"

int mech_frame_group(bgr_element *el, bgr_model *m, int kind, int var)
{
    int v[4] = {var, var + 1, var + 2, var + 3};
    return bgr_declare_frame(el, m, kind, v);
}

int mech_frame_ports(bgr_element *el, bgr_model *m)
{
    int st = BG_OK;
    for (int k = 0; k < el->nports && st == BG_OK; k++) {
        int d = bgr_port_dim(el, m, k);
        if (d != 3 && d != 6) continue;
        for (int i = 0; i < d && st == BG_OK; i += 3) {
            int e = bgr_ev(el, m, k, i), f = bgr_fv(el, m, k, i);
            if (e >= 0) st = mech_frame_group(el, m, BGR_FRAME_VECTOR, e);
            if (f >= 0 && st == BG_OK) st = mech_frame_group(el, m, BGR_FRAME_VECTOR, f);
        }
    }
    return st;
}
