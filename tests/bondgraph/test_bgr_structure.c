/* bgr_check_structure against models whose structural rank is known by hand:
 *   - two flow sources on one 1-junction with a resistor: the junction's flows are set twice
 *     (Sf1, Sf2 and the junction's two flow equalities: 4 equations, 3 flows) and the two
 *     sources' efforts appear only in the junction's effort sum: rank deficient by 1;
 *   - one flow source and a resistor on the junction: regular (0). */
#include <string.h>

#include "bgr_elements.h"
#include "bgr_model.h"
#include "tap.h"

static bgr_model *junction(int sources)
{
    bgr_model *m = bgr_model_create("j");
    double v = 1;
    int j = bgr_one(m, 0, "one", sources + 1, 1);
    int r = bgr_R(m, 0, "r", 1, 2.0);
    for (int k = 0; k < sources; k++) {
        char nm[16], bn[16];
        snprintf(nm, sizeof nm, "sf%d", k);
        snprintf(bn, sizeof bn, "b%d", k);
        int s = bgr_Sf(m, 0, nm, 1, &v);
        bgr_bond(m, 0, bn, 1, bgr_port_of(m, s, 0), bgr_port_of(m, j, k), NULL, NULL);
    }
    bgr_bond(m, 0, "br", 1, bgr_port_of(m, j, sources), bgr_port_of(m, r, 0), NULL, NULL);
    return m;
}

int main(void)
{
    char rep[1024];
    bgr_model *m = junction(1);
    tap_ok(bgr_check_structure(m, rep, sizeof rep) == BG_ERR_STATE, "before compiling: BG_ERR_STATE");
    tap_ok(bgr_compile(m) == BG_OK, "one source and a resistor compile");
    tap_ok(bgr_check_structure(m, rep, sizeof rep) == 0, "and are structurally regular");
    bgr_model_free(&m);
    m = junction(2);
    tap_ok(bgr_compile(m) == BG_OK, "two flow sources on a 1-junction compile (%s)",
           bgr_model_error(m)->message);
    int d = bgr_check_structure(m, rep, sizeof rep);
    tap_ok(d == 1, "structural rank deficient by 1 (got %d)", d);
    tap_ok(strstr(rep, "equations j/") && strstr(rep, "unknowns j/"),
           "the report names an equation and an unknown by path: %s", rep);
    tap_ok(bgr_check_structure(NULL, rep, sizeof rep) == BG_ERR_ARGUMENT, "NULL model refused");
    bgr_model_free(&m);
    return tap_done();
}
