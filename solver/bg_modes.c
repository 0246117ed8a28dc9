/* Linearisation and modes: the reduced dense eigenproblem and the shift-invert window by ARPACK
 * (the method and its reasons are in bg_modes.h); the dense method is in bg_modes_dense.c. */
#include "bg_modes.h"

#include <complex.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bg_jaceval.h"
#include "bg_modes_impl.h"

#include <klu.h>

#ifdef BG_HAVE_ARPACK
#include <arpack.h>
#endif

const char *dae_mode_kind_name(int kind)
{
    switch (kind) {
    case DAE_MODE_ELASTIC:
        return "elastic";
    case DAE_MODE_RIGID:
        return "rigid";
    case DAE_MODE_CONSTRAINT:
        return "constraint";
    default:
        return "unknown";
    }
}

int dae_modes_options_default(dae_modes_options *o)
{
    if (!o) return BG_ERR_ARGUMENT;
    memset(o, 0, sizeof *o);
    o->method = DAE_MODES_AUTO;
    o->dense_max = 1200;
    o->sigma = 0;
    o->nev = 20;
    o->ncv = 0;
    o->tol = 1e-10;
    o->maxiter = 500;
    o->zero_tol = 1e-6;
    o->inf_tol = 1e-9;
    o->linsol = LS_KLU;
    o->frozen = 0;
    o->frame = NULL;
    o->jacobian = DAE_MODES_JAC_AUTO;
    return BG_OK;
}

void dae_modes_free(dae_modes **mp)
{
    if (!mp || !*mp) return;
    dae_modes *m = *mp;
    free(m->dif);
    free(m->nominal);
    free(m->modes);
    free(m->vre);
    free(m->vim);
    free(m);
    *mp = NULL;
}

int dae_modes_count(const dae_modes *m)
{
    return m ? m->nmodes : 0;
}

const dae_mode *dae_modes_get(const dae_modes *m, int k)
{
    return m && k >= 0 && k < m->nmodes ? &m->modes[k] : NULL;
}

int dae_modes_info(const dae_modes *m, int *elastic, int *rigid, int *constraint, double *sigma,
                   int *d, int *method)
{
    if (!m) return BG_ERR_ARGUMENT;
    if (elastic) *elastic = m->counts[0];
    if (rigid) *rigid = m->counts[1];
    if (constraint) *constraint = m->counts[2];
    if (sigma) *sigma = m->sigma;
    if (d) *d = m->d;
    if (method) *method = m->method;
    return BG_OK;
}

int dae_modes_vector(const dae_modes *m, int k, double *re, double *im)
{
    if (!m || k < 0 || k >= m->nmodes || !re) return BG_ERR_ARGUMENT;
    memcpy(re, m->vre + (size_t)k * m->n, (size_t)m->n * sizeof *re);
    if (im) memcpy(im, m->vim + (size_t)k * m->n, (size_t)m->n * sizeof *im);
    return BG_OK;
}

double mode_nominal(const dae_modes *m, int i)
{
    return m->nominal ? m->nominal[i] : 1.0;
}

static const char *mlabel(const dae_modes *m, int i, char *buf, size_t size)
{
    if (m->names && m->names[i]) return m->names[i];
    snprintf(buf, size, "y[%d]", i);
    return buf;
}

/* Squared weighted amplitude of unknown i in mode k. */
static double amp2(const dae_modes *m, int k, int i)
{
    double a = m->vre[(size_t)k * m->n + i], b = m->vim[(size_t)k * m->n + i],
           s = mode_nominal(m, i);
    return (a * a + b * b) / (s * s);
}

double dae_modes_share(const dae_modes *m, int k, const char *prefix)
{
    if (!m || k < 0 || k >= m->nmodes || !prefix) return NAN;
    double tot = 0, in = 0;
    size_t lp = strlen(prefix);
    char nb[32];
    for (int j = 0; j < m->d; j++) {
        int i = m->dif[j];
        double a = amp2(m, k, i);
        tot += a;
        if (!strncmp(mlabel(m, i, nb, sizeof nb), prefix, lp)) in += a;
    }
    return tot > 0 ? in / tot : NAN;
}

/* Length of the first depth segments of name. */
static size_t prefix_len(const char *name, int depth)
{
    if (depth < 1) return strlen(name);
    const char *q = name;
    for (int k = 0; k < depth; k++) {
        const char *s = strchr(q, '/');
        if (!s) return strlen(name);
        q = s + 1;
    }
    return (size_t)(q - name - 1);
}

int dae_modes_describe(const dae_modes *m, int k, int depth, int ngroups, int top, char *buf,
                       size_t size)
{
    if (!m || k < 0 || k >= m->nmodes || (!buf && size > 0)) return BG_ERR_ARGUMENT;
    enum { MAXG = 256 };
    const char *gname[MAXG];
    size_t glen[MAXG];
    double gsum[MAXG], tot = 0;
    int ng = 0;
    char nb[32];
    for (int j = 0; j < m->d; j++) {
        int i = m->dif[j];
        double a = amp2(m, k, i);
        tot += a;
        const char *nm = mlabel(m, i, nb, sizeof nb);
        if (nm == nb) continue; /* unnamed */
        size_t l = prefix_len(nm, depth);
        int g = 0;
        while (g < ng && !(glen[g] == l && !strncmp(gname[g], nm, l)))
            g++;
        if (g == ng) {
            if (ng == MAXG) continue;
            gname[ng] = nm, glen[ng] = l, gsum[ng] = 0, ng++;
        }
        gsum[g] += a;
    }
    size_t len = 0;
#define PUT(...)                                                                                   \
    do {                                                                                           \
        char nobuf_[1];                                                                            \
        int w_ = snprintf(buf ? buf + (len < size ? len : size) : nobuf_,                          \
                          buf && len < size ? size - len : 0, __VA_ARGS__);                        \
        if (w_ > 0) len += (size_t)w_;                                                             \
    } while (0)
    if (size) buf[0] = '\0';
    /* groups above 1 %, largest first */
    for (int shown = 0; shown < ngroups && tot > 0; shown++) {
        int b = -1;
        for (int g = 0; g < ng; g++)
            if (gsum[g] >= 0 && (b < 0 || gsum[g] > gsum[b])) b = g;
        if (b < 0 || gsum[b] < 0.01 * tot) break;
        PUT("%s%.*s %.0f%%", shown ? ", " : "", (int)glen[b], gname[b], 100 * gsum[b] / tot);
        gsum[b] = -1;
    }
    /* leading unknowns */
    if (top > 0) {
        enum { MAXT = 16 };
        int idx[MAXT], nt = 0;
        if (top > MAXT) top = MAXT;
        for (int j = 0; j < m->d; j++) {
            int i = m->dif[j];
            double a = amp2(m, k, i);
            int pos = nt;
            while (pos > 0 && amp2(m, k, idx[pos - 1]) < a)
                pos--;
            if (pos >= top) continue;
            if (nt < top) nt++;
            memmove(idx + pos + 1, idx + pos, (size_t)(nt - 1 - pos) * sizeof *idx);
            idx[pos] = i;
        }
        PUT("%s", len ? " |" : "|");
        for (int t = 0; t < nt; t++)
            PUT(" %s", mlabel(m, idx[t], nb, sizeof nb));
    }
#undef PUT
    return (int)len;
}

/* ------------------------------------------------------------------ shared ---- */

double mode_frob(const sp_csc *A)
{
    double s = 0;
    for (int p = 0; p < A->nnz; p++)
        s += A->val[p] * A->val[p];
    return sqrt(s);
}

/* Factor B + sigma A, moving sigma off an eigenvalue if needed (three tries). */
int mode_factor_shift(mctx *c, double *sigma)
{
    int st = BG_OK;
    for (int tries = 0; tries < 4; tries++) {
        sp_union_combine(c->u, c->J.Jy, 1.0, c->J.Jyp, *sigma);
        st = ls_factor(c->ls, c->u->M);
        if (st != BG_ERR_SINGULAR) break;
        *sigma *= 1.6180339887;
    }
    if (st == BG_ERR_SINGULAR) {
        char nb[256];
        return bg_error_raise(c->err, st, "dae_modes_compute",
                              "B + sigma A is singular for four shifts up to %g: nothing "
                              "determines %s (the model has no unique linearisation there)",
                              *sigma, bg_var_label(c->p, ls_singular_col(c->ls), nb, sizeof nb));
    }
    if (st != BG_OK)
        return bg_error_raise(c->err, st, "dae_modes_compute", "factorization: %s",
                              ls_get_error(c->ls)->message);
    return BG_OK;
}

/* Appends a mode with its vector (complex zr + i zi, n values; scaled here). */
int mode_add(dae_modes *M, double re, double im, int kind, double rcond, const double *zr,
             const double *zi, double residual)
{
    if (M->nmodes == M->cap) {
        int cap = M->cap ? 2 * M->cap : 64;
        dae_mode *nm = realloc(M->modes, (size_t)cap * sizeof *nm);
        if (!nm) return BG_ERR_MEMORY;
        M->modes = nm;
        double *a = realloc(M->vre, (size_t)cap * M->n * sizeof *a);
        if (!a) return BG_ERR_MEMORY;
        M->vre = a;
        double *b = realloc(M->vim, (size_t)cap * M->n * sizeof *b);
        if (!b) return BG_ERR_MEMORY;
        M->vim = b;
        M->cap = cap;
    }
    dae_mode *md = &M->modes[M->nmodes];
    md->re = re;
    md->im = im;
    md->kind = kind;
    md->rcond = rcond;
    md->residual = residual;
    double mag = hypot(re, im);
    if (isinf(re) || isinf(im)) {
        md->freq_hz = INFINITY;
        md->damping = NAN;
    } else {
        md->freq_hz = mag / MODE_TWO_PI;
        md->damping = mag > 0 ? -re / mag : NAN;
    }
    /* scale: largest weighted amplitude among the differential unknowns 1, that entry real */
    double best = -1;
    int ib = 0;
    for (int j = 0; j < M->d; j++) {
        int i = M->dif[j];
        double s = mode_nominal(M, i);
        double a = hypot(zr[i], zi ? zi[i] : 0) / s;
        if (a > best) best = a, ib = i;
    }
    double complex f = 1.0;
    if (best > 0) {
        double complex zb = zr[ib] + I * (zi ? zi[ib] : 0);
        double s = mode_nominal(M, ib);
        f = conj(zb) / (cabs(zb) * cabs(zb)) * s;
    }
    double *vr = M->vre + (size_t)M->nmodes * M->n, *vi = M->vim + (size_t)M->nmodes * M->n;
    for (int i = 0; i < M->n; i++) {
        double complex z = (zr[i] + I * (zi ? zi[i] : 0)) * f;
        vr[i] = creal(z);
        vi[i] = cimag(z);
    }
    M->counts[kind]++;
    M->nmodes++;
    return BG_OK;
}

/* ||(s A + B) z|| / ((|s| ||A|| + ||B||) ||z||) for complex s and z; NaN at infinity. */
double mode_pencil_residual(mctx *c, double complex s, const double *zr, const double *zi)
{
    int n = c->M->n;
    if (!isfinite(creal(s)) || !isfinite(cimag(s))) return NAN;
    double *ar = c->w1, *br = c->w2;
    double num = 0, zz = 0;
    /* real part: Re(s) A zr - Im(s) A zi + B zr; imaginary: Im(s) A zr + Re(s) A zi + B zi */
    for (int part = 0; part < 2; part++) {
        const double *x = part == 0 ? zr : zi, *y = part == 0 ? zi : zr;
        double sg = part == 0 ? -1.0 : 1.0;
        sp_matvec(c->J.Jyp, creal(s), x, 0.0, ar);
        sp_matvec(c->J.Jyp, sg * cimag(s), y, 1.0, ar);
        sp_matvec(c->J.Jy, 1.0, x, 0.0, br);
        for (int i = 0; i < n; i++)
            num += (ar[i] + br[i]) * (ar[i] + br[i]);
    }
    for (int i = 0; i < n; i++)
        zz += zr[i] * zr[i] + zi[i] * zi[i];
    double den = (cabs(s) * c->normA + c->normB) * sqrt(zz);
    return den > 0 ? sqrt(num) / den : NAN;
}

/* Sorts the modes: elastic by frequency, then rigid, then constraint (by |s|). */
static int mode_order(const dae_mode *a, const dae_mode *b)
{
    if (a->kind != b->kind) return a->kind - b->kind;
    double fa = a->freq_hz, fb = b->freq_hz;
    return (fa > fb) - (fa < fb);
}

void mode_sort(dae_modes *M)
{
    /* insertion sort carrying the vectors (a few hundred modes) */
    size_t n = (size_t)M->n;
    double *tr = malloc(n * sizeof *tr), *ti = malloc(n * sizeof *ti);
    if (!tr || !ti) {
        free(tr);
        free(ti);
        return;
    }
    for (int i = 1; i < M->nmodes; i++) {
        dae_mode key = M->modes[i];
        memcpy(tr, M->vre + i * n, n * sizeof *tr);
        memcpy(ti, M->vim + i * n, n * sizeof *ti);
        int j = i - 1;
        while (j >= 0 && mode_order(&M->modes[j], &key) > 0) {
            M->modes[j + 1] = M->modes[j];
            memcpy(M->vre + (j + 1) * n, M->vre + j * n, n * sizeof *tr);
            memcpy(M->vim + (j + 1) * n, M->vim + j * n, n * sizeof *ti);
            j--;
        }
        M->modes[j + 1] = key;
        memcpy(M->vre + (j + 1) * n, tr, n * sizeof *tr);
        memcpy(M->vim + (j + 1) * n, ti, n * sizeof *ti);
    }
    free(tr);
    free(ti);
}

/* ------------------------------------------------------------------- entry ---- */

/* The message of an option out of range: its name, its value and the range it must be in. */
static int out_of_range(bg_error *err, const char *field, double value, const char *range)
{
    return bg_error_raise(err, BG_ERR_ARGUMENT, "dae_modes_compute",
                          "modes options out of range: %s = %g, it must be %s", field, value,
                          range);
}

/* Every check of dae_modes_compute's options and data, in one place: each option against its
 * range (one test per field; the message names the field, its value and the range), then t,
 * the problem's nominal magnitudes and the state (bg_check_nominal, bg_check_state: the
 * integrator's rules and words; a NaN there would reach the factorization as a matrix entry).
 * The ranges are those the methods need: a method of dae_modes_method, counts >= 1 (ncv 0: the
 * default), tolerances >= 0 (NaN refused), a finite shift. BG_OK or the status. */
static int check_args(const dae_problem *p, const dae_modes_options *o, double t, const double *y,
                      const double *yp, bg_error *err)
{
    const char *w = "dae_modes_compute";
    if (o->method < DAE_MODES_AUTO || o->method > DAE_MODES_SPARSE)
        return out_of_range(err, "method", o->method,
                            "a dae_modes_method: 0 (AUTO), 1 (DENSE) or 2 (SPARSE)");
    if (o->dense_max < 1) return out_of_range(err, "dense_max", o->dense_max, ">= 1");
    if (!isfinite(o->sigma)) return out_of_range(err, "sigma", o->sigma, "finite");
    if (o->nev < 1) return out_of_range(err, "nev", o->nev, ">= 1");
    if (o->ncv < 0) return out_of_range(err, "ncv", o->ncv, ">= 0 (0: the default)");
    if (!(o->tol >= 0 && isfinite(o->tol))) return out_of_range(err, "tol", o->tol, ">= 0, finite");
    if (o->maxiter < 1) return out_of_range(err, "maxiter", o->maxiter, ">= 1");
    /* relative tolerances: 1 or more would call every mode rigid (zero_tol) or a constraint
     * (inf_tol) */
    if (!(o->zero_tol >= 0 && o->zero_tol < 1))
        return out_of_range(err, "zero_tol", o->zero_tol, "in [0, 1)");
    if (!(o->inf_tol >= 0 && o->inf_tol < 1))
        return out_of_range(err, "inf_tol", o->inf_tol, "in [0, 1)");
    if (o->linsol != LS_KLU && o->linsol != LS_DENSE)
        return out_of_range(err, "linsol", (double)o->linsol,
                            "a linear solver: 0 (LS_KLU) or 1 (LS_DENSE)");
    if (o->frozen != 0 && o->frozen != 1)
        return out_of_range(err, "frozen", (double)o->frozen, "0 or 1");
    if (o->jacobian < DAE_MODES_JAC_AUTO || o->jacobian > DAE_MODES_JAC_DIFFERENCES)
        return out_of_range(err, "jacobian", (double)o->jacobian,
                            "0 (AUTO), 1 (PROBLEM) or 2 (DIFFERENCES)");
    if (!isfinite(t)) return bg_error_raise(err, BG_ERR_ARGUMENT, w, "t is not finite");
    if (p->n < 1) return BG_OK; /* bg_jaceval_init refuses it */
    int st = bg_check_nominal(p, w, err);
    if (st == BG_OK) st = bg_check_state(p, y, "value", BG_ERR_NONFINITE, w, err);
    if (st == BG_OK && yp) st = bg_check_state(p, yp, "derivative", BG_ERR_NONFINITE, w, err);
    return st;
}

int dae_modes_compute(const dae_problem *p, double t, const double *y, const double *yp,
                      const dae_modes_options *opt, dae_modes **out, bg_error *err)
{
    const char *where = "dae_modes_compute";
    if (out) *out = NULL;
    if (!p || !y || !out)
        return bg_error_raise(err, BG_ERR_ARGUMENT, where, "%s is NULL",
                              !p   ? "the problem"
                              : !y ? "y"
                                   : "out");
    dae_modes_options od;
    if (!opt) dae_modes_options_default(&od);
    const dae_modes_options *o = opt ? opt : &od;
    int st = check_args(p, o, t, y, yp, err);
    if (st != BG_OK) return st;
    if (o->frame && p->n >= 1 && p->res) return mode_in_frame(p, t, y, yp, o, out, err);
    dae_problem pdiff;
    if (o->jacobian == DAE_MODES_JAC_DIFFERENCES && p->jac) { /* the residual's differences */
        pdiff = *p;
        pdiff.jac = NULL;
        p = &pdiff;
    }
    mctx c;
    memset(&c, 0, sizeof c);
    c.p = p;
    c.o = o;
    c.err = err;
    st = bg_jaceval_init(&c.J, p, err);
    if (st != BG_OK) return st;
    int n = p->n;
    dae_modes *M = calloc(1, sizeof *M);
    double *ypz = yp ? NULL : calloc((size_t)n, sizeof *ypz);
    c.w1 = malloc((size_t)n * sizeof *c.w1);
    c.w2 = malloc((size_t)n * sizeof *c.w2);
    c.u = sp_union_create(c.J.Jy, c.J.Jyp);
    if (!M || (!yp && !ypz) || !c.w1 || !c.w2 || !c.u) {
        st = bg_error_raise(err, BG_ERR_MEMORY, where, "out of memory");
        goto done;
    }
    M->p = p;
    M->n = n;
    M->names = p->names;
    if (p->nominal) {
        M->nominal = malloc((size_t)n * sizeof *M->nominal);
        if (!M->nominal) {
            st = bg_error_raise(err, BG_ERR_MEMORY, where, "out of memory");
            goto done;
        }
        memcpy(M->nominal, p->nominal, (size_t)n * sizeof *M->nominal);
    }
    c.M = M;
    st = bg_jaceval_eval(&c.J, t, y, yp ? yp : ypz, NULL);
    if (st != 0) {
        st = bg_error_raise(err, BG_ERR_CALLBACK, where,
                            "the Jacobian could not be evaluated (status %d)", st);
        goto done;
    }
    if (yp && !o->frozen) { /* a moving state: its pencil must hold along the motion */
        double ratio;
        int row;
        st = bg_jaceval_steadiness(&c.J, t, y, yp, NULL, &ratio, &row);
        if (st != 0) {
            st = bg_error_raise(err, BG_ERR_CALLBACK, where,
                                "the residual could not be evaluated along the motion (status "
                                "%d)",
                                st);
            goto done;
        }
        if (ratio > MODES_STEADY_TOL) {
            char eb[256], vb[256];
            int fast = mode_fastest(p, y, yp);
            st = bg_error_raise(err, BG_ERR_ARGUMENT, where,
                                "the state is moving and not steady: %s changes along the motion "
                                "(%.3g of its terms; the fastest unknown is %s), so the "
                                "linearisation has no constant coefficients and its modes are "
                                "not those of small motions about the state (a structure "
                                "spinning in the inertial frame: linearise it in a co-moving "
                                "frame, options.frame; options.frozen = 1 gives the frozen "
                                "pencil's modes anyway)",
                                bg_eq_label(p, row, eb, sizeof eb), ratio,
                                bg_var_label(p, fast, vb, sizeof vb));
            goto done;
        }
    }
    c.normA = mode_frob(c.J.Jyp);
    c.normB = mode_frob(c.J.Jy);
    /* differential unknowns: the columns of dF/dy' with a nonzero value */
    M->dif = malloc((size_t)n * sizeof *M->dif);
    if (!M->dif) {
        st = bg_error_raise(err, BG_ERR_MEMORY, where, "out of memory");
        goto done;
    }
    for (int j = 0; j < n; j++) {
        int nz = 0;
        for (int q = c.J.Jyp->colptr[j]; q < c.J.Jyp->colptr[j + 1]; q++)
            nz |= c.J.Jyp->val[q] != 0;
        if (nz) M->dif[M->d++] = j;
    }
    c.ls = ls_create(o->linsol, c.u->M, err);
    if (!c.ls) {
        st = err && err->status < 0 ? err->status : BG_ERR_LIBRARY;
        goto done;
    }
    int method = o->method;
    if (method == DAE_MODES_AUTO)
        method = M->d <= o->dense_max ? DAE_MODES_DENSE : DAE_MODES_SPARSE;
    M->method = method;
    if (M->d == 0) {
        st = BG_OK; /* no differential unknowns: no finite modes */
    } else if (method == DAE_MODES_DENSE) {
        st = mode_dense(&c);
    } else {
        st = mode_sparse(&c);
    }
    if (st == BG_OK || st == DAE_CONV_FAIL) mode_sort(M);
done:
    if (st == BG_OK || st == DAE_CONV_FAIL) {
        M->p = NULL;
        *out = M;
    } else {
        dae_modes_free(&M);
    }
    free(ypz);
    free(c.w1);
    free(c.w2);
    sp_union_free(&c.u);
    ls_free(&c.ls);
    bg_jaceval_free(&c.J);
    return st;
}
