/* Linearisation and modes: the reduced dense eigenproblem and the shift-invert window by ARPACK
 * (the method and its reasons are in bg_modes.h). */
#include "bg_modes.h"

#include <complex.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bg_jaceval.h"

#include <klu.h>

#ifdef BG_HAVE_ARPACK
#include <arpack.h>
#endif

/* LAPACK, Fortran calling convention with the hidden lengths of character arguments. */
void dgeevx_(const char *balanc, const char *jobvl, const char *jobvr, const char *sense,
             const int *n, double *a, const int *lda, double *wr, double *wi, double *vl,
             const int *ldvl, double *vr, const int *ldvr, int *ilo, int *ihi, double *scale,
             double *abnrm, double *rconde, double *rcondv, double *work, const int *lwork,
             int *iwork, int *info, size_t l1, size_t l2, size_t l3, size_t l4);

static const double TWO_PI = 6.283185307179586476925286766559;

struct dae_modes {
    const dae_problem *p;       /* during dae_modes_compute only */
    const char *const *names;   /* the problem's names (NULL: "y[i]") */
    double *nominal;            /* copy of the problem's nominal magnitudes (NULL: 1) */
    int n, d, method;
    int *dif;         /* the d differential unknowns */
    double sigma;
    int nmodes, cap;
    dae_mode *modes;
    double *vre, *vim; /* n per mode */
    int counts[3];
};

const char *dae_mode_kind_name(int kind)
{
    switch (kind) {
    case DAE_MODE_ELASTIC: return "elastic";
    case DAE_MODE_RIGID: return "rigid";
    case DAE_MODE_CONSTRAINT: return "constraint";
    default: return "unknown";
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

static double nominal(const dae_modes *m, int i)
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
    double a = m->vre[(size_t)k * m->n + i], b = m->vim[(size_t)k * m->n + i], s = nominal(m, i);
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

typedef struct mctx {
    const dae_problem *p;
    const dae_modes_options *o;
    bg_jaceval J;
    sp_union *u;
    ls_solver *ls;
    dae_modes *M;
    double *w1, *w2; /* n each */
    double normA, normB;
    bg_error *err;
} mctx;

static double frob(const sp_csc *A)
{
    double s = 0;
    for (int p = 0; p < A->nnz; p++)
        s += A->val[p] * A->val[p];
    return sqrt(s);
}

/* Factor B + sigma A, moving sigma off an eigenvalue if needed (three tries). */
static int factor_shift(mctx *c, double *sigma)
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
static int add_mode(dae_modes *M, double re, double im, int kind, double rcond, const double *zr,
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
        md->freq_hz = mag / TWO_PI;
        md->damping = mag > 0 ? -re / mag : NAN;
    }
    /* scale: largest weighted amplitude among the differential unknowns 1, that entry real */
    double best = -1;
    int ib = 0;
    for (int j = 0; j < M->d; j++) {
        int i = M->dif[j];
        double s = nominal(M, i);
        double a = hypot(zr[i], zi ? zi[i] : 0) / s;
        if (a > best) best = a, ib = i;
    }
    double complex f = 1.0;
    if (best > 0) {
        double complex zb = zr[ib] + I * (zi ? zi[ib] : 0);
        double s = nominal(M, ib);
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
static double pencil_residual(mctx *c, double complex s, const double *zr, const double *zi)
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

static void sort_modes(dae_modes *M)
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

/* ------------------------------------------------------------------- dense ---- */

/* Which zero eigenvalues are defective (Jordan chains: rigid motions) and which semisimple
 * (invariants: constraint modes). The zero eigenvalues of X A are mu0 = 1/sigma; their algebraic
 * multiplicity m is the number of computed eigenvalues there, their geometric multiplicity g the
 * dimension of the null space of C - mu0 I (singular values below 1e-10 of the largest, LAPACK
 * dgesvd on a copy of C), and m - g Jordan chains of length 2 are the rigid motions. Rounding
 * splits a chain into a pair +-delta (or +-i delta) of nearly parallel eigenvectors: the m - g
 * pairs of eigenvectors at the smallest angles are the rigid ones. The reciprocal condition
 * numbers of the eigenvalues tell the same in isolation, but not inside a cluster of dozens of
 * semisimple zeros (the drift of every joint and member), where they fall to 1e-5 and where
 * computed eigenvectors can be nearly parallel too; the multiplicities decide. rigid[j] = 1 for
 * the eigenvalues (of wr, wi) that are rigid. */
void dgesvd_(const char *jobu, const char *jobvt, const int *m, const int *n, double *a,
             const int *lda, double *s, double *u, const int *ldu, double *vt, const int *ldvt,
             double *work, const int *lwork, int *info, size_t l1, size_t l2);

static double col_angle(const double *a, const double *b, int d)
{
    double ab = 0, aa = 0, bb = 0;
    for (int i = 0; i < d; i++)
        ab += a[i] * b[i], aa += a[i] * a[i], bb += b[i] * b[i];
    if (!(aa > 0 && bb > 0)) return 0;
    double c = fabs(ab) / sqrt(aa * bb);
    return c >= 1 ? 0 : sqrt(1 - c * c);
}

static int rigid_analysis(const double *C0, const double *VR, const double *wr, const double *wi,
                          int d, double sigma, double zero_tol, int *rigid)
{
    if (d < 1) return BG_OK;
    int *zero = calloc((size_t)d, sizeof *zero), m = 0;
    if (!zero) return BG_ERR_MEMORY;
    for (int j = 0; j < d; j++) {
        rigid[j] = 0;
        double complex mu = wr[j] + I * wi[j];
        if (cabs(mu) > 0 && cabs(sigma - 1.0 / mu) <= zero_tol * fabs(sigma)) zero[j] = 1, m++;
    }
    /* candidate pairs: complex pairs at zero (real and imaginary parts), and real pairs */
    typedef struct pair {
        int a, b;
        double angle;
    } pair;
    int np = 0, cap = 16;
    pair *P = malloc((size_t)cap * sizeof *P);
    int st = BG_OK;
    for (int j = 0; j < d && P; j++) {
        if (!zero[j] || wi[j] < 0) continue;
        for (int k = j + 1; k < d; k++) {
            if (!(wi[j] > 0 ? k == j + 1 : zero[k] && wi[k] == 0)) continue;
            double ang = col_angle(VR + (size_t)j * d, VR + (size_t)k * d, d);
            if (ang >= 1e-4) continue;
            if (np == cap) {
                pair *q = realloc(P, 2 * (size_t)cap * sizeof *q);
                if (!q) {
                    free(P);
                    P = NULL;
                    break;
                }
                P = q, cap *= 2;
            }
            P[np++] = (pair){j, k, ang};
        }
    }
    if (!P) st = BG_ERR_MEMORY;
    if (st == BG_OK && np > 0) { /* the geometric multiplicity */
        double *A = malloc((size_t)d * d * sizeof *A), *sv = malloc((size_t)d * sizeof *sv), wq;
        int info = 0, lwork = -1, one = 1;
        if (!A || !sv) {
            st = BG_ERR_MEMORY;
        } else {
            memcpy(A, C0, (size_t)d * d * sizeof *A);
            for (int i = 0; i < d; i++)
                A[(size_t)i * d + i] -= 1.0 / sigma;
            dgesvd_("N", "N", &d, &d, A, &d, sv, NULL, &one, NULL, &one, &wq, &lwork, &info, 1, 1);
            lwork = info == 0 ? (int)wq : 5 * d;
            double *work = malloc((size_t)lwork * sizeof *work);
            if (!work) {
                st = BG_ERR_MEMORY;
            } else {
                memcpy(A, C0, (size_t)d * d * sizeof *A);
                for (int i = 0; i < d; i++)
                    A[(size_t)i * d + i] -= 1.0 / sigma;
                dgesvd_("N", "N", &d, &d, A, &d, sv, NULL, &one, NULL, &one, work, &lwork, &info,
                        1, 1);
                free(work);
                int g = 0;
                for (int i = 0; info == 0 && i < d; i++)
                    g += sv[i] <= 1e-10 * sv[0];
                int chains = info == 0 ? m - g : 0;
                /* the pairs at the smallest angles, each eigenvalue once */
                for (int c = 0; c < chains; c++) {
                    int best = -1;
                    for (int q = 0; q < np; q++)
                        if (!rigid[P[q].a] && !rigid[P[q].b] &&
                            (best < 0 || P[q].angle < P[best].angle))
                            best = q;
                    if (best < 0) break;
                    rigid[P[best].a] = rigid[P[best].b] = 1;
                }
            }
        }
        free(A);
        free(sv);
    }
    free(P);
    free(zero);
    return st;
}

static int modes_dense(mctx *c)
{
    dae_modes *M = c->M;
    const dae_modes_options *o = c->o;
    const int n = M->n, d = M->d;
    const sp_csc *A = c->J.Jyp;
    int st;
    if (n < 1 || d < 1) return BG_OK;
    double sigma = o->sigma > 0 ? o->sigma : (o->sigma < 0 ? o->sigma : 1.0);
    if ((st = factor_shift(c, &sigma)) != BG_OK) return st;
    M->sigma = sigma;
    int *pos = malloc((size_t)n * sizeof *pos); /* position among the differential unknowns */
    double *C = malloc((size_t)d * d * sizeof *C), *C0 = malloc((size_t)d * d * sizeof *C0);
    int *rigid = malloc((size_t)d * sizeof *rigid);
    const int nb = 32;
    double *blk = malloc((size_t)n * nb * sizeof *blk);
    double *wr = malloc((size_t)d * sizeof *wr), *wi = malloc((size_t)d * sizeof *wi);
    double *VL = malloc((size_t)d * d * sizeof *VL), *VR = malloc((size_t)d * d * sizeof *VR);
    double *scale = malloc((size_t)d * sizeof *scale), *rce = malloc((size_t)d * sizeof *rce);
    double *rcv = malloc((size_t)d * sizeof *rcv);
    double *zr = malloc((size_t)n * sizeof *zr), *zi = malloc((size_t)n * sizeof *zi);
    double *work = NULL;
    int *iwork = malloc((size_t)(2 * d + 2) * sizeof *iwork);
    if (!pos || !C || !C0 || !rigid || !blk || !wr || !wi || !VL || !VR || !scale || !rce || !rcv || !zr || !zi ||
        !iwork) {
        st = bg_error_raise(c->err, BG_ERR_MEMORY, "dae_modes_compute", "out of memory");
        goto done;
    }
    for (int i = 0; i < n; i++)
        pos[i] = -1;
    for (int j = 0; j < d; j++)
        pos[M->dif[j]] = j;
    /* C = P_d^T (B + sigma A)^-1 A_d, nb columns at a time */
    for (int j0 = 0; j0 < d; j0 += nb) {
        int nc = d - j0 < nb ? d - j0 : nb;
        memset(blk, 0, (size_t)n * nc * sizeof *blk);
        for (int k = 0; k < nc; k++) {
            int col = M->dif[j0 + k];
            for (int p = A->colptr[col]; p < A->colptr[col + 1]; p++)
                blk[(size_t)k * n + A->rowind[p]] = A->val[p];
        }
        if ((st = ls_solve(c->ls, blk, nc)) != BG_OK) {
            st = bg_error_raise(c->err, st, "dae_modes_compute", "solve: %s",
                                ls_get_error(c->ls)->message);
            goto done;
        }
        for (int k = 0; k < nc; k++)
            for (int j = 0; j < d; j++)
                C[(size_t)(j0 + k) * d + j] = blk[(size_t)k * n + M->dif[j]];
    }
    memcpy(C0, C, (size_t)d * d * sizeof *C0); /* dgeevx overwrites C */
    int ilo, ihi, info = 0, lwork = -1;
    double abnrm, wq;
    dgeevx_("B", "V", "V", "E", &d, C, &d, wr, wi, VL, &d, VR, &d, &ilo, &ihi, scale, &abnrm, rce,
            rcv, &wq, &lwork, iwork, &info, 1, 1, 1, 1);
    lwork = info == 0 ? (int)wq : d * (d + 6);
    if (lwork < d * (d + 6)) lwork = d * (d + 6);
    work = malloc((size_t)lwork * sizeof *work);
    if (!work) {
        st = bg_error_raise(c->err, BG_ERR_MEMORY, "dae_modes_compute", "out of memory");
        goto done;
    }
    dgeevx_("B", "V", "V", "E", &d, C, &d, wr, wi, VL, &d, VR, &d, &ilo, &ihi, scale, &abnrm, rce,
            rcv, work, &lwork, iwork, &info, 1, 1, 1, 1);
    if (info != 0) {
        st = bg_error_raise(c->err, BG_ERR_LIBRARY, "dae_modes_compute",
                            "LAPACK dgeevx failed (info %d) on the %d x %d reduced matrix", info,
                            d, d);
        goto done;
    }
    double mumax = 0;
    for (int j = 0; j < d; j++)
        mumax = fmax(mumax, hypot(wr[j], wi[j]));
    if ((st = rigid_analysis(C0, VR, wr, wi, d, sigma, o->zero_tol, rigid)) != BG_OK) {
        st = bg_error_raise(c->err, st, "dae_modes_compute", "out of memory");
        goto done;
    }
    double *ur = blk, *ui = blk + n; /* A_d u, real and imaginary, then z */
    for (int j = 0; j < d; j++) {
        if (wi[j] < 0) continue; /* the conjugate of the previous one */
        double complex mu = wr[j] + I * wi[j];
        const double *vr = VR + (size_t)j * d, *vi = wi[j] > 0 ? VR + (size_t)(j + 1) * d : NULL;
        int kind;
        double complex s;
        if (cabs(mu) <= o->inf_tol * mumax) {
            kind = DAE_MODE_CONSTRAINT;
            s = INFINITY;
        } else {
            s = sigma - 1.0 / mu;
            if (cabs(s) <= o->zero_tol * fabs(sigma))
                kind = rigid[j] ? DAE_MODE_RIGID : DAE_MODE_CONSTRAINT;
            else
                kind = DAE_MODE_ELASTIC;
        }
        /* z = X A_d u */
        memset(ur, 0, 2 * (size_t)n * sizeof *ur);
        for (int k = 0; k < d; k++) {
            int col = M->dif[k];
            for (int p = A->colptr[col]; p < A->colptr[col + 1]; p++) {
                ur[A->rowind[p]] += A->val[p] * vr[k];
                if (vi) ui[A->rowind[p]] += A->val[p] * vi[k];
            }
        }
        if ((st = ls_solve(c->ls, ur, vi ? 2 : 1)) != BG_OK) goto done;
        if (kind == DAE_MODE_CONSTRAINT && isinf(creal(s))) {
            /* at infinity: the differential part of the eigenvector of C itself */
            memset(ur, 0, 2 * (size_t)n * sizeof *ur);
            for (int k = 0; k < d; k++) {
                ur[M->dif[k]] = vr[k];
                if (vi) ui[M->dif[k]] = vi[k];
            }
        }
        memcpy(zr, ur, (size_t)n * sizeof *zr);
        if (vi)
            memcpy(zi, ui, (size_t)n * sizeof *zi);
        else
            memset(zi, 0, (size_t)n * sizeof *zi);
        double res = pencil_residual(c, s, zr, zi);
        double re = creal(s), im = cimag(s);
        if (isinf(re)) re = INFINITY, im = 0;
        if ((st = add_mode(M, re, im, kind, rce[j], zr, zi, res)) != BG_OK) {
            st = bg_error_raise(c->err, st, "dae_modes_compute", "out of memory");
            goto done;
        }
    }
    st = BG_OK;
done:
    free(pos);
    free(C);
    free(C0);
    free(rigid);
    free(blk);
    free(wr);
    free(wi);
    free(VL);
    free(VR);
    free(scale);
    free(rce);
    free(rcv);
    free(zr);
    free(zi);
    free(work);
    free(iwork);
    return st;
}

/* ------------------------------------------------------------------ sparse ---- */

#ifdef BG_HAVE_ARPACK
/* y = (X A - sigma (X A)^2) x, X = (B + sigma A)^-1 (factored). */
static int apply_op(mctx *c, double sigma, const double *x, double *y)
{
    int n = c->M->n, st;
    double *u = c->w1, *w = c->w2;
    sp_matvec(c->J.Jyp, 1.0, x, 0.0, u);
    if ((st = ls_solve(c->ls, u, 1)) != BG_OK) return st;
    sp_matvec(c->J.Jyp, 1.0, u, 0.0, w);
    if ((st = ls_solve(c->ls, w, 1)) != BG_OK) return st;
    for (int i = 0; i < n; i++)
        y[i] = u[i] - sigma * w[i];
    return BG_OK;
}

/* Rayleigh-quotient iteration on one mode in complex arithmetic (KLU's complex LU of s A + B on
 * the union pattern): the window's eigenvalues come from -s/(sigma - s)^2 through solves with
 * B + sigma A, whose rounding along the model's drift directions (small singular values
 * sigma |A|) limits them to a relative 1e-4 on the crane with 512 elements; a solve with the
 * shift at the mode itself does not have that weakness. Two factorizations per mode. */
typedef struct refiner {
    klu_common common;
    klu_symbolic *sym;
    double *Ax, *rhs, *z; /* interleaved complex: 2 nnz, 2 n, 2 n */
} refiner;

static void refiner_free(refiner *R)
{
    if (R->sym) klu_free_symbolic(&R->sym, &R->common);
    free(R->Ax);
    free(R->rhs);
    free(R->z);
    memset(R, 0, sizeof *R);
}

static int refiner_init(mctx *c, refiner *R)
{
    memset(R, 0, sizeof *R);
    const sp_csc *P = c->u->M;
    int n = c->M->n;
    klu_defaults(&R->common);
    R->common.ordering = 1; /* COLAMD, as bg_linsol.c */
    R->sym = klu_analyze(n, P->colptr, P->rowind, &R->common);
    R->Ax = malloc(2 * (size_t)(P->nnz > 0 ? P->nnz : 1) * sizeof *R->Ax);
    R->rhs = malloc(2 * (size_t)n * sizeof *R->rhs);
    R->z = malloc(2 * (size_t)n * sizeof *R->z);
    if (!R->sym || !R->Ax || !R->rhs || !R->z) {
        refiner_free(R);
        return BG_ERR_MEMORY;
    }
    return BG_OK;
}

/* rhs = A z (complex, interleaved) */
static void cplx_matvec(const sp_csc *A, const double *z, double *y)
{
    memset(y, 0, 2 * (size_t)A->nrow * sizeof *y);
    for (int j = 0; j < A->ncol; j++)
        for (int p = A->colptr[j]; p < A->colptr[j + 1]; p++) {
            y[2 * A->rowind[p]] += A->val[p] * z[2 * j];
            y[2 * A->rowind[p] + 1] += A->val[p] * z[2 * j + 1];
        }
}

/* Refines s, zr, zi in place; 0 if it improved them, else the inputs are kept. */
static int refine_mode(mctx *c, refiner *R, double complex *s, double *zr, double *zi)
{
    const sp_csc *P = c->u->M;
    const sp_union *u = c->u;
    int n = c->M->n;
    double complex s0 = *s;
    for (int i = 0; i < n; i++)
        R->z[2 * i] = zr[i], R->z[2 * i + 1] = zi[i];
    int improved = 0;
    for (int it = 0; it < 3; it++) {
        memset(R->Ax, 0, 2 * (size_t)P->nnz * sizeof *R->Ax);
        for (int p = 0; p < c->J.Jy->nnz; p++)
            R->Ax[2 * u->map_a[p]] += c->J.Jy->val[p];
        for (int p = 0; p < c->J.Jyp->nnz; p++) {
            R->Ax[2 * u->map_b[p]] += creal(s0) * c->J.Jyp->val[p];
            R->Ax[2 * u->map_b[p] + 1] += cimag(s0) * c->J.Jyp->val[p];
        }
        klu_numeric *num = klu_z_factor(P->colptr, P->rowind, R->Ax, R->sym, &R->common);
        if (!num) break; /* s0 is an eigenvalue to working precision: keep it */
        double complex nu = 0, zz = 0;
        for (int k = 0; k < 2; k++) { /* two steps of inverse iteration at this shift */
            cplx_matvec(c->J.Jyp, R->z, R->rhs);
            if (!klu_z_solve(R->sym, num, n, 1, R->rhs, &R->common)) break;
            /* nu = z^H y / z^H z ~ 1 / (s0 - s) */
            nu = 0, zz = 0;
            double big = 0;
            for (int i = 0; i < n; i++) {
                double complex zi_ = R->z[2 * i] + I * R->z[2 * i + 1];
                double complex yi = R->rhs[2 * i] + I * R->rhs[2 * i + 1];
                nu += conj(zi_) * yi;
                zz += conj(zi_) * zi_;
                big = fmax(big, cabs(yi));
            }
            if (!(big > 0) || !isfinite(big)) break;
            for (int i = 0; i < 2 * n; i++)
                R->z[i] = R->rhs[i] / big;
            nu /= big;
            zz /= big;
        }
        klu_z_free_numeric(&num, &R->common);
        if (!(cabs(nu) > 0) || !isfinite(cabs(nu))) break;
        double complex s1 = s0 - zz / nu;
        double step = cabs(s1 - s0);
        s0 = s1;
        improved = 1;
        if (step <= 1e-13 * cabs(s0)) break;
    }
    if (!improved) return 1;
    double *tr = c->w1, *ti = c->w2;
    /* keep the refined pair only if its residual is smaller */
    double *nr = malloc(2 * (size_t)n * sizeof *nr);
    if (!nr) return 1;
    for (int i = 0; i < n; i++)
        nr[i] = R->z[2 * i], nr[n + i] = R->z[2 * i + 1];
    (void)tr;
    (void)ti;
    double e_old = pencil_residual(c, *s, zr, zi), e_new = pencil_residual(c, s0, nr, nr + n);
    int ok = e_new <= e_old || !isfinite(e_old);
    if (ok) {
        *s = s0;
        memcpy(zr, nr, (size_t)n * sizeof *zr);
        memcpy(zi, nr + n, (size_t)n * sizeof *zi);
    }
    free(nr);
    return ok ? 0 : 1;
}

typedef struct found {
    double complex s;
    double res;
    double *zr, *zi;
} found;

/* One ARPACK run at shift sigma: the elastic modes it finds into f (at most cap, vectors
 * allocated), their count into *nf. BG_OK, DAE_CONV_FAIL (some converged) or an error. */
static int arpack_run(mctx *c, double sigma, int nev_a, found *f, int cap, int *nf, int *iters)
{
    dae_modes *M = c->M;
    const dae_modes_options *o = c->o;
    const int n = M->n;
    *nf = 0;
    if (n < 1) return BG_OK;
    int ncv = o->ncv > 0 ? o->ncv : (2 * nev_a + 1 > nev_a + 20 ? 2 * nev_a + 1 : nev_a + 20);
    if (ncv > n) ncv = n;
    if (nev_a > ncv - 2) nev_a = ncv - 2;
    if (nev_a < 1)
        return bg_error_raise(c->err, BG_ERR_ARGUMENT, "dae_modes_compute",
                              "the model is too small for the sparse method (n = %d)", n);
    int lworkl = 3 * ncv * ncv + 6 * ncv, st = BG_OK;
    double *resid = malloc((size_t)n * sizeof *resid), *V = malloc((size_t)n * ncv * sizeof *V);
    double *workd = malloc(3 * (size_t)n * sizeof *workd);
    double *workl = malloc((size_t)lworkl * sizeof *workl);
    double *dr = malloc((size_t)(nev_a + 1) * sizeof *dr), *di = malloc((size_t)(nev_a + 1) * sizeof *di);
    double *Z = malloc((size_t)n * (nev_a + 1) * sizeof *Z);
    double *workev = malloc(3 * (size_t)ncv * sizeof *workev);
    int *select = calloc((size_t)ncv, sizeof *select);
    if (!resid || !V || !workd || !workl || !dr || !di || !Z || !workev || !select) {
        st = bg_error_raise(c->err, BG_ERR_MEMORY, "dae_modes_compute", "out of memory");
        goto done;
    }
    /* a start vector of the model's scale: the nominal magnitudes with a deterministic pattern */
    for (int i = 0; i < n; i++) {
        unsigned h = (unsigned)i * 2654435761u;
        resid[i] = ((double)(h >> 8) / 16777216.0 - 0.5) * nominal(M, i);
    }
    int ipntr[14] = {0}, iparam[11] = {0}, ido = 0, info = 1;
    iparam[0] = 1;
    iparam[2] = o->maxiter;
    iparam[6] = 1;
    for (;;) {
        dnaupd_c(&ido, "I", n, "LM", nev_a, o->tol, resid, ncv, V, n, iparam, ipntr, workd, workl,
                 lworkl, &info);
        if (ido == -1 || ido == 1) {
            if ((st = apply_op(c, sigma, workd + ipntr[0] - 1, workd + ipntr[1] - 1)) != BG_OK) {
                st = bg_error_raise(c->err, st, "dae_modes_compute", "solve: %s",
                                    ls_get_error(c->ls)->message);
                goto done;
            }
            continue;
        }
        break;
    }
    *iters = iparam[2];
    if (info < 0) {
        st = bg_error_raise(c->err, BG_ERR_LIBRARY, "dae_modes_compute",
                            "ARPACK dnaupd failed (info %d)", info);
        goto done;
    }
    int conv_fail = info == 1;
    int nconv = iparam[4];
    if (nconv < 1) {
        st = bg_error_raise(c->err, DAE_CONV_FAIL, "dae_modes_compute",
                            "ARPACK found no eigenvalue within %d restarts", o->maxiter);
        goto done;
    }
    int rinfo = 0;
    dneupd_c(1, "A", select, dr, di, Z, n, 0.0, 0.0, workev, "I", n, "LM", nev_a, o->tol, resid,
             ncv, V, n, iparam, ipntr, workd, workl, lworkl, &rinfo);
    if (rinfo != 0) {
        st = bg_error_raise(c->err, BG_ERR_LIBRARY, "dae_modes_compute",
                            "ARPACK dneupd failed (info %d)", rinfo);
        goto done;
    }
    nconv = iparam[4];
    double thmax = 0;
    for (int j = 0; j < nconv; j++)
        thmax = fmax(thmax, hypot(dr[j], di[j]));
    double *ti = calloc((size_t)n, sizeof *ti);
    if (!ti) {
        st = bg_error_raise(c->err, BG_ERR_MEMORY, "dae_modes_compute", "out of memory");
        goto done;
    }
    for (int j = 0; j < nconv && *nf < cap; j++) {
        double complex th = dr[j] + I * di[j];
        const double *zr = Z + (size_t)j * n, *zi = NULL;
        int conj_pair = 0;
        if (di[j] != 0) {
            if (j + 1 >= nconv) break;
            zi = Z + (size_t)(j + 1) * n;
            conj_pair = 1;
        }
        if (cabs(th) > 1e-12 * thmax) {
            /* s from theta: theta s^2 - (2 sigma theta - 1) s + theta sigma^2 = 0; the root with
             * the smaller pencil residual on this vector */
            double complex bq = -(2 * sigma * th - 1.0), disc = csqrt(bq * bq - 4 * th * th * sigma * sigma);
            double complex r1 = (-bq + disc) / (2 * th), r2 = (-bq - disc) / (2 * th);
            double e1 = pencil_residual(c, r1, zr, zi ? zi : ti);
            double e2 = pencil_residual(c, r2, zr, zi ? zi : ti);
            double complex s = e1 <= e2 ? r1 : r2;
            double res = fmin(e1, e2);
            int flip = cimag(s) < 0;
            found *fd = &f[*nf];
            fd->zr = malloc((size_t)n * sizeof *fd->zr);
            fd->zi = malloc((size_t)n * sizeof *fd->zi);
            if (!fd->zr || !fd->zi) {
                free(fd->zr);
                free(fd->zi);
                free(ti);
                st = bg_error_raise(c->err, BG_ERR_MEMORY, "dae_modes_compute", "out of memory");
                goto done;
            }
            memcpy(fd->zr, zr, (size_t)n * sizeof *zr);
            for (int i = 0; i < n; i++)
                fd->zi[i] = zi ? (flip ? -zi[i] : zi[i]) : 0.0;
            fd->s = flip ? conj(s) : s;
            fd->res = res;
            (*nf)++;
        }
        if (conj_pair) j++;
    }
    free(ti);
    st = conv_fail ? DAE_CONV_FAIL : BG_OK;
done:
    free(resid);
    free(V);
    free(workd);
    free(workl);
    free(dr);
    free(di);
    free(Z);
    free(workev);
    free(select);
    return st;
}
#endif

#ifdef BG_HAVE_ARPACK
/* The window: the nev eigenvalues nearest i wc by complex shift-invert, OP = (B + i wc A)^-1 A
 * (KLU's complex LU, ARPACK znaupd/zneupd): mu = 1 / (i wc - s). Zero modes are at distance wc
 * from the shift, so every mode in the disc |s - i wc| < wc comes before them, and a mode's
 * conjugate is farther than the mode. The found modes go to f as in arpack_run. */
static int arpack_window(mctx *c, refiner *R, double wc, int nev, found *f, int cap, int *nf)
{
    dae_modes *M = c->M;
    const dae_modes_options *o = c->o;
    const sp_csc *P = c->u->M;
    const sp_union *u = c->u;
    const int n = M->n;
    *nf = 0;
    if (n < 1) return BG_OK;
    int ncv = o->ncv > 0 ? o->ncv : (2 * nev + 1 > nev + 20 ? 2 * nev + 1 : nev + 20);
    if (ncv > n) ncv = n;
    if (nev > ncv - 2) nev = ncv - 2;
    if (nev < 1)
        return bg_error_raise(c->err, BG_ERR_ARGUMENT, "dae_modes_compute",
                              "the model is too small for the sparse method (n = %d)", n);
    memset(R->Ax, 0, 2 * (size_t)P->nnz * sizeof *R->Ax);
    for (int p = 0; p < c->J.Jy->nnz; p++)
        R->Ax[2 * u->map_a[p]] += c->J.Jy->val[p];
    for (int p = 0; p < c->J.Jyp->nnz; p++)
        R->Ax[2 * u->map_b[p] + 1] += wc * c->J.Jyp->val[p];
    klu_numeric *num = klu_z_factor(P->colptr, P->rowind, R->Ax, R->sym, &R->common);
    if (!num)
        return bg_error_raise(c->err, BG_ERR_SINGULAR, "dae_modes_compute",
                              "B + i %g A is singular (KLU status %d): an eigenvalue at the "
                              "window's centre; move it",
                              wc, R->common.status);
    int lworkl = 3 * ncv * ncv + 5 * ncv, st = BG_OK;
    double complex *resid = malloc((size_t)n * sizeof *resid);
    double complex *V = malloc((size_t)n * ncv * sizeof *V);
    double complex *workd = malloc(3 * (size_t)n * sizeof *workd);
    double complex *workl = malloc((size_t)lworkl * sizeof *workl);
    double complex *dv = malloc((size_t)(nev + 1) * sizeof *dv);
    double complex *Z = malloc((size_t)n * (nev + 1) * sizeof *Z);
    double complex *workev = malloc(2 * (size_t)ncv * sizeof *workev);
    double *rwork = malloc((size_t)ncv * sizeof *rwork);
    int *select = calloc((size_t)ncv, sizeof *select);
    double *zr = malloc((size_t)n * sizeof *zr), *zi = malloc((size_t)n * sizeof *zi);
    if (!resid || !V || !workd || !workl || !dv || !Z || !workev || !rwork || !select || !zr ||
        !zi) {
        st = bg_error_raise(c->err, BG_ERR_MEMORY, "dae_modes_compute", "out of memory");
        goto done;
    }
    for (int i = 0; i < n; i++) {
        unsigned h = (unsigned)i * 2654435761u;
        resid[i] = ((double)(h >> 8) / 16777216.0 - 0.5) * nominal(M, i);
    }
    int ipntr[14] = {0}, iparam[11] = {0}, ido = 0, info = 1;
    iparam[0] = 1;
    iparam[2] = o->maxiter;
    iparam[6] = 1;
    for (;;) {
        znaupd_c(&ido, "I", n, "LM", nev, o->tol, resid, ncv, V, n, iparam, ipntr, workd, workl,
                 lworkl, rwork, &info);
        if (ido != -1 && ido != 1) break;
        const double complex *x = workd + ipntr[0] - 1;
        double complex *y = workd + ipntr[1] - 1;
        cplx_matvec(c->J.Jyp, (const double *)x, (double *)y);
        if (!klu_z_solve(R->sym, num, n, 1, (double *)y, &R->common)) {
            st = bg_error_raise(c->err, BG_ERR_LIBRARY, "dae_modes_compute",
                                "complex solve failed (KLU status %d)", R->common.status);
            goto done;
        }
    }
    if (info < 0) {
        st = bg_error_raise(c->err, BG_ERR_LIBRARY, "dae_modes_compute",
                            "ARPACK znaupd failed (info %d)", info);
        goto done;
    }
    int conv_fail = info == 1;
    if (iparam[4] < 1) {
        st = bg_error_raise(c->err, DAE_CONV_FAIL, "dae_modes_compute",
                            "ARPACK found no eigenvalue within %d restarts", o->maxiter);
        goto done;
    }
    int rinfo = 0;
    zneupd_c(1, "A", select, dv, Z, n, 0.0, workev, "I", n, "LM", nev, o->tol, resid, ncv, V, n,
             iparam, ipntr, workd, workl, lworkl, rwork, &rinfo);
    if (rinfo != 0) {
        st = bg_error_raise(c->err, BG_ERR_LIBRARY, "dae_modes_compute",
                            "ARPACK zneupd failed (info %d)", rinfo);
        goto done;
    }
    int nconv = iparam[4];
    for (int j = 0; j < nconv && *nf < cap; j++) {
        if (!(cabs(dv[j]) * wc > 1e-10)) continue; /* at infinity */
        double complex s = I * wc - 1.0 / dv[j];
        int flip = cimag(s) < 0;
        for (int i = 0; i < n; i++) {
            double complex z = Z[(size_t)j * n + i];
            zr[i] = creal(z);
            zi[i] = flip ? -cimag(z) : cimag(z);
        }
        if (flip) s = conj(s);
        int dup = 0;
        for (int k = 0; k < *nf; k++)
            if (cabs(f[k].s - s) <= 1e-8 * cabs(s)) dup = 1;
        if (dup) continue;
        found *fd = &f[*nf];
        fd->zr = malloc((size_t)n * sizeof *fd->zr);
        fd->zi = malloc((size_t)n * sizeof *fd->zi);
        if (!fd->zr || !fd->zi) {
            free(fd->zr);
            free(fd->zi);
            st = bg_error_raise(c->err, BG_ERR_MEMORY, "dae_modes_compute", "out of memory");
            goto done;
        }
        memcpy(fd->zr, zr, (size_t)n * sizeof *zr);
        memcpy(fd->zi, zi, (size_t)n * sizeof *zi);
        fd->s = s;
        fd->res = pencil_residual(c, s, zr, zi);
        (*nf)++;
    }
    st = conv_fail ? DAE_CONV_FAIL : BG_OK;
done:
    klu_z_free_numeric(&num, &R->common);
    free(resid);
    free(V);
    free(workd);
    free(workl);
    free(dv);
    free(Z);
    free(workev);
    free(rwork);
    free(select);
    free(zr);
    free(zi);
    return st;
}
#endif

static int modes_sparse(mctx *c)
{
#ifndef BG_HAVE_ARPACK
    return bg_error_raise(c->err, BG_ERR_LIBRARY, "dae_modes_compute",
                          "the sparse method needs ARPACK, and the library was built without it "
                          "(Debian: libarpack2-dev); use DAE_MODES_DENSE (%d differential "
                          "unknowns)",
                          c->M->d);
#else
    dae_modes *M = c->M;
    const dae_modes_options *o = c->o;
    int nev = o->nev, auto_sigma = !(o->sigma > 0), st = BG_OK;
    double sigma = auto_sigma ? 1.0 : o->sigma;
    int cap = 2 * nev + 2;
    found *f = calloc((size_t)cap, sizeof *f);
    if (!f) return bg_error_raise(c->err, BG_ERR_MEMORY, "dae_modes_compute", "out of memory");
    int nf = 0;
    refiner R;
    if (refiner_init(c, &R) != BG_OK) {
        free(f);
        return bg_error_raise(c->err, BG_ERR_MEMORY, "dae_modes_compute", "out of memory");
    }
    if (!auto_sigma) { /* a window around the frequency sigma (complex shift) */
        st = arpack_window(c, &R, sigma, nev, f, cap, &nf);
        nev = nf;
    }
    for (int round = 0; auto_sigma && round < 6; round++) {
        for (int k = 0; k < nf; k++)
            free(f[k].zr), free(f[k].zi);
        nf = 0;
        if ((st = factor_shift(c, &sigma)) != BG_OK) break;
        int iters = 0;
        st = arpack_run(c, sigma, 2 * nev, f, cap, &nf, &iters);
        if (st != BG_OK && st != DAE_CONV_FAIL) break;
        if (!auto_sigma || nf == 0) break;
        /* the lowest nev: sigma^2 <= |s_1| |s_nev| */
        double lo = INFINITY, w[256];
        int nw = 0;
        for (int k = 0; k < nf && nw < 256; k++)
            w[nw++] = cabs(f[k].s);
        for (int a = 1; a < nw; a++) /* sort */
            for (int b = a; b > 0 && w[b - 1] > w[b]; b--) {
                double t = w[b];
                w[b] = w[b - 1];
                w[b - 1] = t;
            }
        lo = w[0];
        double hi = w[(nw < nev ? nw : nev) - 1];
        if (sigma * sigma <= 0.9 * lo * hi) break;
        sigma = 0.5 * sqrt(lo * hi);
    }
    M->sigma = sigma;
    int keep = st == BG_OK || st == DAE_CONV_FAIL;
    if (keep && nf > 0) { /* accurate eigenvalues: Rayleigh-quotient iteration per mode */
        {
            for (int k = 0; k < nf; k++) {
                double complex sk = f[k].s;
                if (refine_mode(c, &R, &sk, f[k].zr, f[k].zi) == 0) {
                    if (cimag(sk) < 0) { /* the conjugate, with its vector */
                        sk = conj(sk);
                        for (int i = 0; i < M->n; i++)
                            f[k].zi[i] = -f[k].zi[i];
                    }
                    f[k].s = sk;
                    f[k].res = pencil_residual(c, sk, f[k].zr, f[k].zi);
                }
            }
        }
    }
    refiner_free(&R);
    /* the same mode found twice (a window's copies converge to one eigenvalue when refined):
     * the one with the larger residual goes */
    for (int k = 0; k < nf; k++)
        for (int j = 0; j < nf; j++)
            if (j != k && f[j].zr && f[k].zr && cabs(f[j].s - f[k].s) <= 1e-8 * cabs(f[k].s) &&
                (f[j].res < f[k].res || (f[j].res == f[k].res && j < k))) {
                free(f[k].zr), free(f[k].zi);
                f[k].zr = f[k].zi = NULL;
                f[k].s = INFINITY;
                break;
            }
    /* keep the nev lowest (auto) or all found (window) */
    for (int k = 0; keep && k < nf; k++) {
        if (!f[k].zr) continue;
        int rank = 0;
        for (int j = 0; j < nf; j++)
            if (cabs(f[j].s) < cabs(f[k].s) || (cabs(f[j].s) == cabs(f[k].s) && j < k)) rank++;
        if (auto_sigma && rank >= nev) continue;
        int e = add_mode(M, creal(f[k].s), cimag(f[k].s), DAE_MODE_ELASTIC, NAN, f[k].zr, f[k].zi,
                         f[k].res);
        if (e != BG_OK) {
            st = bg_error_raise(c->err, e, "dae_modes_compute", "out of memory");
            break;
        }
    }
    if (st == DAE_CONV_FAIL)
        bg_error_raise(c->err, st, "dae_modes_compute",
                       "ARPACK did not converge within %d restarts: %d modes returned",
                       o->maxiter, M->nmodes);
    for (int k = 0; k < nf; k++)
        free(f[k].zr), free(f[k].zi);
    free(f);
    return st;
#endif
}

/* ------------------------------------------------------------------- entry ---- */

int dae_modes_compute(const dae_problem *p, double t, const double *y, const double *yp,
                      const dae_modes_options *opt, dae_modes **out, bg_error *err)
{
    const char *where = "dae_modes_compute";
    if (out) *out = NULL;
    if (!p || !y || !out)
        return bg_error_raise(err, BG_ERR_ARGUMENT, where, "%s is NULL",
                              !p ? "the problem" : !y ? "y" : "out");
    dae_modes_options od;
    if (!opt) dae_modes_options_default(&od);
    const dae_modes_options *o = opt ? opt : &od;
    if (o->method < DAE_MODES_AUTO || o->method > DAE_MODES_SPARSE || o->dense_max < 1 ||
        !isfinite(o->sigma) || o->nev < 1 || o->ncv < 0 || !(o->tol >= 0) || o->maxiter < 1 ||
        !(o->zero_tol >= 0) || !(o->inf_tol >= 0) ||
        (o->linsol != LS_KLU && o->linsol != LS_DENSE))
        return bg_error_raise(err, BG_ERR_ARGUMENT, where, "modes options out of range");
    if (!isfinite(t)) return bg_error_raise(err, BG_ERR_ARGUMENT, where, "t is not finite");
    mctx c;
    memset(&c, 0, sizeof c);
    c.p = p;
    c.o = o;
    c.err = err;
    int st = bg_jaceval_init(&c.J, p, err);
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
    c.normA = frob(c.J.Jyp);
    c.normB = frob(c.J.Jy);
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
    if (method == DAE_MODES_AUTO) method = M->d <= o->dense_max ? DAE_MODES_DENSE : DAE_MODES_SPARSE;
    M->method = method;
    if (M->d == 0) {
        st = BG_OK; /* no differential unknowns: no finite modes */
    } else if (method == DAE_MODES_DENSE) {
        st = modes_dense(&c);
    } else {
        st = modes_sparse(&c);
    }
    if (st == BG_OK || st == DAE_CONV_FAIL) sort_modes(M);
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
