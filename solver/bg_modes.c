/* Linearisation and modes: the reduced dense eigenproblem and the shift-invert window by ARPACK
 * (the method and its reasons are in bg_modes.h). */
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

/* LAPACK, Fortran calling convention with the hidden lengths of character arguments. */
void dgeevx_(const char *balanc, const char *jobvl, const char *jobvr, const char *sense,
             const int *n, double *a, const int *lda, double *wr, double *wi, double *vl,
             const int *ldvl, double *vr, const int *ldvr, int *ilo, int *ihi, double *scale,
             double *abnrm, double *rconde, double *rcondv, double *work, const int *lwork,
             int *iwork, int *info, size_t l1, size_t l2, size_t l3, size_t l4);

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
                dgesvd_("N", "N", &d, &d, A, &d, sv, NULL, &one, NULL, &one, work, &lwork, &info, 1,
                        1);
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
    if ((st = mode_factor_shift(c, &sigma)) != BG_OK) return st;
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
    if (!pos || !C || !C0 || !rigid || !blk || !wr || !wi || !VL || !VR || !scale || !rce || !rcv ||
        !zr || !zi || !iwork) {
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
                            "LAPACK dgeevx failed (info %d) on the %d x %d reduced matrix", info, d,
                            d);
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
        double res = mode_pencil_residual(c, s, zr, zi);
        double re = creal(s), im = cimag(s);
        if (isinf(re)) re = INFINITY, im = 0;
        if ((st = mode_add(M, re, im, kind, rce[j], zr, zi, res)) != BG_OK) {
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
static int check_args(const dae_problem *p, const dae_modes_options *o, double t,
                      const double *y, const double *yp, bg_error *err)
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
        st = modes_dense(&c);
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
