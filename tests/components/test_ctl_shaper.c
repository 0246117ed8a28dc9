/* Input shapers (ctl_shaper.h) against closed forms.
 *
 * The impulses of ZV and ZVD (Singer and Seering 1990): amplitudes summing to 1, spaced by half
 * the damped period. The residual vibration: linear oscillators s'' + 2 z w0 s' + w0^2 s = -a(t)
 * (a pendulum of natural frequency w0 under the acceleration a of its suspension point), driven
 * by the acceleration of a trapezoidal velocity reference, unshaped and shaped, run by the
 * solver from a model file. After the reference has ended the oscillation's amplitude
 * A = sqrt(s^2 + (s' / w0)^2) (undamped) is constant; the shaped one, over the unshaped one, is
 * V = |cos(pi w0 / (2 w_d))| for an undamped ZV shaper designed at w_d (the two impulses'
 * responses, a half design period apart, summed): 0 at w_d = w0, cos(0.4 pi) = 0.309017 when
 * the shaper is designed 25 % too high. A damped oscillator (z = 0.1) with a ZVD shaper at its
 * own frequency and damping: no residual either. */
#include "ctl_shaper.h"
#include "ctltest.h"

#define PI 3.14159265358979323846

static void test_impulses(void)
{
    double A[3], t[3];
    int n = ctl_shaper_impulses(CTL_SHAPER_ZV, 0.5, 0.0, A, t);
    tap_ok(n == 2 && fabs(A[0] - 0.5) < 1e-15 && fabs(A[1] - 0.5) < 1e-15 && t[0] == 0 &&
               fabs(t[1] - 1.0) < 1e-15,
           "ZV undamped at 0.5 Hz: [1/2, 1/2] at [0, 1 s] (got %d: %g %g at %g %g)", n, A[0], A[1],
           t[0], t[1]);
    /* damped: K = exp(-z pi / sqrt(1 - z^2)), the period 1 / (f sqrt(1 - z^2)) */
    double z = 0.2, s = sqrt(1 - z * z), K = exp(-z * PI / s);
    n = ctl_shaper_impulses(CTL_SHAPER_ZVD, 1.0, z, A, t);
    double d = (1 + K) * (1 + K);
    tap_ok(n == 3 && fabs(A[0] - 1 / d) < 1e-15 && fabs(A[1] - 2 * K / d) < 1e-15 &&
               fabs(A[2] - K * K / d) < 1e-15 && fabs(t[2] - 1 / s) < 1e-14 &&
               fabs(A[0] + A[1] + A[2] - 1) < 1e-15,
           "ZVD at 1 Hz, z = 0.2: amplitudes [1, 2K, K^2] / (1 + K)^2, last at the damped period");
    /* V of the undamped ZV against |cos(pi w / (2 w_d))| across a range of mistuning */
    ctl_shaper_impulses(CTL_SHAPER_ZV, 1.0, 0.0, A, t);
    double worst = 0;
    for (int k = 0; k <= 40; k++) {
        double w = 2 * PI * (0.5 + 0.025 * k);
        worst = fmax(worst, fabs(ctl_shaper_vibration(2, A, t, w, 0.0) -
                                 fabs(cos(PI * w / (2 * 2 * PI)))));
    }
    tap_ok(worst < 1e-14, "ZV's V(w) equals |cos(pi w / (2 w_d))| for w / w_d in [0.5, 1.5] (%.1e)",
           worst);
    n = ctl_shaper_impulses(CTL_SHAPER_ZVD, 0.3, 0.15, A, t);
    double v0 = ctl_shaper_vibration(n, A, t, 2 * PI * 0.3, 0.15);
    tap_ok(v0 < 1e-14, "ZVD: V = 0 at its design mode (%.1e)", v0);
    tap_ok(ctl_shaper_impulses(CTL_SHAPER_ZV, 0.0, 0.0, A, t) == BG_ERR_ARGUMENT &&
               ctl_shaper_impulses(CTL_SHAPER_ZV, 1.0, 1.0, A, t) == BG_ERR_ARGUMENT &&
               ctl_shaper_impulses((ctl_shaper_kind)7, 1.0, 0.0, A, t) == BG_ERR_ARGUMENT,
           "a frequency of 0, a damping of 1 or an unknown kind are refused");
}

/* one oscillator block: reference `ref` (its rate is the acceleration), pendulum `name` */
#define OSC(name, ref, k, c)                                                                       \
    "  f_" name ": {type: sig.gain, input: " ref ".y, gain: -1}\n"                                 \
    "  e_" name ": {type: bg.Se_signal, signal: f_" name ".y}\n"                                   \
    "  m_" name ": {type: bg.I, mass: 1}\n"                                                        \
    "  k_" name ": {type: bg.C, stiffness: " k "}\n"                                               \
    "  r_" name ": {type: bg.R, resistance: " c "}\n"                                              \
    "  j_" name ": {type: bg.one, ports: [e, m, k, r]}\n"
#define OSC_BONDS(name)                                                                            \
    "  - {from: e_" name ".p, to: j_" name ".e}\n"                                                 \
    "  - {from: j_" name ".m, to: m_" name ".p}\n"                                                 \
    "  - {from: j_" name ".k, to: k_" name ".p}\n"                                                 \
    "  - {from: j_" name ".r, to: r_" name ".p}\n"
#define OSC_OUT(name) "  s_" name ": k_" name ".q\n  v_" name ": m_" name ".p\n"

static const char *model =
    "format: bgsim 1\n"
    "name: pend\n"
    "parameters:\n"
    "  w0: 1.3\n"
    "  z: 0.1\n"
    "  f0: w0 / (2 * pi)\n"
    "components:\n"
    "  plain: {type: sig.pwl, times: [0, 1, 4, 5], values: [0, 1, 1, 0], output: rate}\n"
    "  zv: {type: ctl.shaper, times: [0, 1, 4, 5], values: [0, 1, 1, 0], frequency: f0, "
    "output: rate}\n"
    "  zv_high: {type: ctl.shaper, times: [0, 1, 4, 5], values: [0, 1, 1, 0], "
    "frequency: 1.25 * f0, output: rate}\n"
    "  zvd: {type: ctl.shaper, times: [0, 1, 4, 5], values: [0, 1, 1, 0], frequency: f0, "
    "damping: z, shaper: zvd, output: rate}\n" OSC("u", "plain", "w0^2", "0")
        OSC("a", "zv", "w0^2", "0") OSC("b", "zv_high", "w0^2", "0")
            OSC("du", "plain", "w0^2", "2 * z * w0") OSC("dd", "zvd", "w0^2", "2 * z * w0")
    "bonds:\n" OSC_BONDS("u") OSC_BONDS("a") OSC_BONDS("b") OSC_BONDS("du") OSC_BONDS("dd")
    "outputs:\n" OSC_OUT("u") OSC_OUT("a") OSC_OUT("b") OSC_OUT("du") OSC_OUT("dd");

/* the oscillator's amplitude: |s + i s' / w_d| scaled to the damped motion's envelope */
static double amp(const ctl_run *r, const char *nm, double w0, double z)
{
    char s[16], v[16];
    snprintf(s, sizeof s, "s_%s", nm);
    snprintf(v, sizeof v, "v_%s", nm);
    double q = cr_out(r, s), p = cr_out(r, v), wd = w0 * sqrt(1 - z * z);
    /* q = C e^(-z w0 t) cos(wd t + phi): q' + z w0 q = -C wd e^(..) sin(..) */
    return hypot(q, (p + z * w0 * q) / wd);
}

static void test_residual(void)
{
    const double w0 = 1.3, z = 0.1;
    ctl_run r;
    if (!tap_ok(cr_open(&r, model, 1e-10, 1e-12), "pendulums under shaped references load")) {
        cr_close(&r);
        return;
    }
    /* the ZVD's reference ends at 5 + 2 pi / w_d = 9.86 s; amplitudes at 12 s and 15 s */
    int ok = cr_to(&r, 12.0);
    double au = amp(&r, "u", w0, 0), aa = amp(&r, "a", w0, 0), ab = amp(&r, "b", w0, 0);
    double adu = amp(&r, "du", w0, z), add = amp(&r, "dd", w0, z);
    ok = ok && cr_to(&r, 15.0);
    double au2 = amp(&r, "u", w0, 0);
    tap_ok(ok && au > 0.1 && fabs(au2 - au) < 1e-7 * au,
           "unshaped: a residual oscillation of constant amplitude %.6f (at 15 s: %.6f)", au, au2);
    tap_ok(aa < 1e-6 * au, "ZV at the pendulum's frequency: residual %.2e of the unshaped (0)",
           aa / au);
    double V = fabs(cos(PI * 1.0 / (2 * 1.25)));
    tap_ok(fabs(ab / au - V) < 1e-6,
           "ZV designed 25 %% too high: residual ratio %.8f, closed form cos(0.4 pi) = %.8f",
           ab / au, V);
    tap_ok(add < 1e-6 * adu, "ZVD at the damped pendulum's mode (z = 0.1): residual %.2e of the "
                             "unshaped",
           add / adu);
    cr_close(&r);
}

int main(void)
{
    test_impulses();
    test_residual();
    return tap_done();
}
