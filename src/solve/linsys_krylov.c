/* Newton-Krylov products and near-field preconditioner (see linsys_krylov.h). */
#include "solve/linsys_krylov.h"

#include "base/util.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

int rs_krylov_create(rs_krylov *k, const rs_model *m, int band, int band_y)
{
  memset(k, 0, sizeof *k);
  k->m = m;
  k->band = band;
  k->band_y = band_y;
  k->ylink = m->el.dim == 3 && m->lay.ncomp == 2 && band_y == 0 && m->lay.nextra == 0 &&
             band <= RS_YLINK_MAX_BAND;
  const int neq = m->lay.neq;
  k->cap = rs_model_jac_capacity(m, band, band_y);
  k->near.rowptr = malloc(((size_t)neq + 1) * sizeof *k->near.rowptr);
  k->near.col = malloc((size_t)k->cap * sizeof *k->near.col);
  k->near.val = malloc((size_t)k->cap * sizeof *k->near.val);
  k->near.cap = k->cap;
  k->rp_old = calloc((size_t)neq + 1, sizeof *k->rp_old);
  k->sig_factored = malloc((size_t)m->lay.n * sizeof *k->sig_factored);
  k->y_ev = malloc((size_t)neq * sizeof *k->y_ev);
  k->yp_ev = malloc((size_t)neq * sizeof *k->yp_ev);
  if (!k->near.rowptr || !k->near.col || !k->near.val || !k->rp_old || !k->sig_factored ||
      !k->y_ev || !k->yp_ev || rs_work_create(&k->w, m) != RS_OK ||
      rs_work_create_kinematics(&k->wlin, m) != RS_OK) {
    rs_krylov_free(k);
    return RS_ERR_INTERNAL;
  }
  return RS_OK;
}

static void part_free(rs_klu_part *p)
{
  if (p->num) klu_l_free_numeric(&p->num, &p->common);
  if (p->sym) klu_l_free_symbolic(&p->sym, &p->common);
  if (!p->borrowed) {
    free(p->rowptr);
    free(p->col);
    free(p->val);
  }
  free(p->idx);
  free(p->x);
  memset(p, 0, sizeof *p);
}

static void parts_free(rs_krylov *k)
{
  for (int q = 0; q < k->nparts; q++) part_free(&k->part[q]);
  free(k->part);
  free(k->refresh);
  free(k->ready);
  free(k->lane_todo);
  k->lane_todo = NULL;
  if (k->lanes_on) rs_lanes_free(&k->lanes);
  k->lanes_on = 0;
  k->part = NULL;
  k->refresh = NULL;
  k->ready = NULL;
  k->nparts = 0;
}

void rs_krylov_free(rs_krylov *k)
{
  parts_free(k);
  rs_ylink_free(&k->yl);
  rs_work_free(&k->w);
  rs_work_free(&k->wlin);
  free(k->near.rowptr);
  free(k->near.col);
  free(k->near.val);
  free(k->rp_old);
  free(k->sig_factored);
  free(k->y_ev);
  free(k->yp_ev);
  memset(k, 0, sizeof *k);
}

const char *rs_krylov_error(const rs_krylov *k) { return k->w.msg.text; }

/* The near field's active-set signature of cell i: its branches, and whether its yield
 * rows pin the traction (the pattern of its local Jacobian follows from these). */
static unsigned char cell_signature(const rs_law_out *o)
{
  return (unsigned char)(o->branch | (o->pins_p ? 0x80 : 0));
}

/* Whether the factored near field may serve at (cj, velocity): reuse on, a factorisation
 * at hand and not declared stale, cj + V/dx (the iteration matrix is r times a sum of
 * terms in cj and in V/dx) within the reuse ratio of the factorisation's, and at most
 * reuse_cells cells on other branches than then (rs_krylov_set_reuse). Each such cell
 * perturbs the preconditioner locally, whatever the grid's size, so the bound is a count. */
static int factor_current(const rs_krylov *k, const rs_inputs *in, double cj)
{
  if (!(k->reuse_ratio > 1.0) || k->nparts == 0 || !k->ready[0] || k->stale) return 0;
  const double s = cj + fabs(in->velocity) / k->m->grid.dx;
  if (!(s <= k->reuse_ratio * k->rate_factored && k->rate_factored <= k->reuse_ratio * s)) return 0;
  int changed = 0;
  for (int i = 0; i < k->m->lay.n; i++)
    if (cell_signature(&k->w.law[i]) != k->sig_factored[i]) changed++;
  return changed <= k->reuse_cells;
}

/* KLU's options for a part. No row scaling: the rows are scaled already (r gives the
 * traction rows a unit diagonal), and KLU's scaling costs time. Nor KLU's check of the
 * input (scale 0 still checks every refactorisation's matrix; our assembly builds sorted
 * rows without duplicates): bitwise the same results, less time. */
static int part_defaults(rs_klu_part *p)
{
  if (!klu_l_defaults(&p->common)) return RS_ERR_INTERNAL;
  p->common.scale = -1;
  return RS_OK;
}

/* The parts the near field is factored in: in 3D with a band along x only and no unknowns
 * beyond the cells' (a prescribed force couples every traction) one per line of cells
 * along x (the unknowns of the cells of row iy, in their global order), which the near
 * field does not couple to each other; else the whole matrix. Per line, KLU orders each on
 * its own (the results agree with the whole matrix's to roundoff), the line Gauss-Seidel
 * takes the lines by colour, two threads take the halves iy < ny/2 and iy >= ny/2 of the
 * grid (solver.threads: 2, grids from SPLIT_MIN_UNKNOWNS unknowns), and a set-up refactors
 * only the lines whose cells changed branch (setup_linearised). */
enum { SPLIT_MIN_UNKNOWNS = 4000 };
static int line_parts(rs_krylov *k)
{
  const rs_model *m = k->m;
  const rs_layout *L = &m->lay;
  const int64_t neq = L->neq, *rp = k->near.rowptr, *ci = k->near.col;
  if (!(m->el.dim == 3 && k->band_y == 0 && L->nextra == 0 && k->ylink && m->grid.ny >= 2))
    return 0;
  const int nx = m->grid.nx, ny = m->grid.ny, n = L->n;
  int *owner = malloc((size_t)neq * sizeof *owner);
  int64_t *loc = malloc((size_t)neq * sizeof *loc), *count = calloc((size_t)ny, sizeof *count),
          *nnz = calloc((size_t)ny, sizeof *nnz);
  k->part = calloc((size_t)ny, sizeof *k->part);
  k->refresh = calloc((size_t)ny, 1);
  int ok = owner && loc && count && nnz && k->part && k->refresh;
  if (ok) k->nparts = ny;
  for (int64_t g = 0; ok && g < neq; g++) {
    owner[g] = (int)((g % n) / nx);
    loc[g] = count[owner[g]]++;
  }
  for (int64_t r = 0; ok && r < neq; r++) {
    nnz[owner[r]] += rp[r + 1] - rp[r];
    for (int64_t e = rp[r]; e < rp[r + 1] && ok; e++) ok = owner[ci[e]] == owner[r];
  }
  for (int q = 0; ok && q < ny; q++) {
    rs_klu_part *p = &k->part[q];
    const int64_t nz = nnz[q] > 0 ? nnz[q] : 1;
    p->n = count[q];
    p->idx = malloc(((size_t)p->n + 1) * sizeof *p->idx);
    p->rowptr = malloc(((size_t)p->n + 1) * sizeof *p->rowptr);
    p->col = malloc((size_t)nz * sizeof *p->col);
    p->val = malloc((size_t)nz * sizeof *p->val);
    p->x = malloc(((size_t)p->n + 1) * sizeof *p->x);
    ok = p->idx && p->rowptr && p->col && p->val && p->x && part_defaults(p) == RS_OK;
    if (ok) p->rowptr[0] = 0;
  }
  /* the rows of each line in global order (one pass over the matrix) */
  for (int q = 0; ok && q < ny; q++) count[q] = 0;
  for (int64_t r = 0; ok && r < neq; r++) {
    rs_klu_part *p = &k->part[owner[r]];
    const int64_t i = count[owner[r]]++, e0 = p->rowptr[i];
    p->idx[i] = r;
    for (int64_t e = rp[r]; e < rp[r + 1]; e++) p->col[e0 + e - rp[r]] = loc[ci[e]];
    p->rowptr[i + 1] = e0 + rp[r + 1] - rp[r];
  }
  free(owner);
  free(loc);
  free(count);
  free(nnz);
  if (!ok) {
    parts_free(k);
    return 0;
  }
  k->nsplit = rs_threads(m->par.threads) >= 2 && neq >= SPLIT_MIN_UNKNOWNS ? 2 : 1;
  return ny;
}

/* The lines iy0 <= iy < iy1 of half h of the grid when T threads take its halves. */
static void half_lines(int ny, int T, int h, int *iy0, int *iy1)
{
  *iy0 = h == 0 ? 0 : ny / 2;
  *iy1 = h == T - 1 ? ny : ny / 2;
}

/* A line's values from the assembled near field. */
static void part_values(const rs_krylov *k, rs_klu_part *p)
{
  const int64_t *rp = k->near.rowptr;
  for (int64_t i = 0; i < p->n; i++)
    memcpy(p->val + p->rowptr[i], k->near.val + rp[p->idx[i]],
           (size_t)(p->rowptr[i + 1] - p->rowptr[i]) * sizeof *p->val);
}

/* The lines side by side (linsys_lanes.h): groups by half of the grid (the threads) and
 * parity (the sweep's colours), the pivot order from the middle line's values. Where that
 * fails the lines keep KLU alone. */
static void lanes_create(rs_krylov *k)
{
  const int ny = k->m->grid.ny, T = k->nsplit, n = (int)k->part[0].n;
  for (int q = 0; q < k->nparts; q++)
    if (k->part[q].n != n) return;
  rs_lane_line *lines = malloc((size_t)ny * sizeof *lines);
  const double **values = malloc((size_t)ny * sizeof *values);
  int *order = malloc((size_t)ny * sizeof *order);
  unsigned char *first = calloc((size_t)ny, 1);
  if (lines && values && order && first) {
    for (int q = 0; q < ny; q++) {
      lines[q] = (rs_lane_line){k->part[q].rowptr, k->part[q].col, k->part[q].idx};
      values[q] = k->part[q].val;
    }
    part_values(k, &k->part[ny / 2]);
    int m = 0, groups = 0;
    for (int h = 0; h < T; h++)
      for (int c = 0; c < 2; c++) {
        int iy0, iy1;
        half_lines(ny, T, h, &iy0, &iy1);
        k->gfirst[h][c] = groups;
        int in_run = 0;
        for (int iy = iy0 + ((iy0 & 1) != c); iy < iy1; iy += 2, in_run++) {
          first[m] = in_run == 0;
          order[m++] = iy;
          if (in_run % RS_LANES == 0) groups++;
        }
        k->gfirst[h][c + 1] = groups;
      }
    k->lanes_on =
        rs_lanes_create(&k->lanes, n, ny, lines, values, ny / 2, order, m, first) == RS_OK;
    if (k->lanes_on) {
      k->lane_todo = malloc((size_t)k->lanes.ngroups * sizeof *k->lane_todo);
      if (!k->lane_todo) {
        rs_lanes_free(&k->lanes);
        k->lanes_on = 0;
      }
    }
  }
  free(values);
  free(lines);
  free(order);
  free(first);
}

/* A new pattern: the parts and KLU's symbolic analysis of each. */
static int analyse(rs_krylov *k)
{
  parts_free(k);
  k->nsplit = 1;
  if (!line_parts(k)) {
    k->ylink = 0; /* the whole matrix: no lines of their own */
    k->part = calloc(1, sizeof *k->part);
    k->refresh = calloc(1, 1);
    if (!k->part || !k->refresh) return RS_ERR_INTERNAL;
    k->nparts = 1;
    rs_klu_part *p = &k->part[0];
    if (part_defaults(p) != RS_OK) return RS_ERR_INTERNAL;
    p->n = k->m->lay.neq;
    p->rowptr = k->near.rowptr; /* borrowed: the whole matrix (idx NULL) */
    p->col = k->near.col;
    p->val = k->near.val;
    p->borrowed = 1;
  }
  k->ready = calloc((size_t)k->nparts, 1);
  if (!k->ready) return RS_ERR_INTERNAL;
  for (int q = 0; q < k->nparts; q++) {
    rs_klu_part *p = &k->part[q];
    p->sym = klu_l_analyze(p->n, p->rowptr, p->col, &p->common);
    if (!p->sym) return RS_ERR_SOLVER;
  }
  if (k->nparts > 1) lanes_create(k);
  return RS_OK;
}

/* Same pattern: refactor with the pivot order of the last factorisation; a new
 * factorisation (partial pivoting) if that meets a zero pivot or a pivot so small
 * (diagonal of U, relative) that the preconditioner would be poor. Rows change between
 * band rows and unit rows with the contact regimes, so the old order is not always
 * good. */
static int factor_part(rs_klu_part *p, int same)
{
  if (same && p->num && klu_l_refactor(p->rowptr, p->col, p->val, p->sym, p->num, &p->common) &&
      p->common.status == KLU_OK && klu_l_rcond(p->sym, p->num, &p->common) &&
      p->common.rcond > 1e-8)
    return RS_OK;
  if (p->num) klu_l_free_numeric(&p->num, &p->common);
  p->num = klu_l_factor(p->rowptr, p->col, p->val, p->sym, &p->common);
  return p->num && p->common.status == KLU_OK ? RS_OK : RS_ERR_SOLVER;
}

static int same_inputs(const rs_inputs *a, const rs_inputs *b)
{
  return a->t == b->t && a->velocity == b->velocity && a->creepage == b->creepage &&
         a->lateral_creepage == b->lateral_creepage && a->spin == b->spin &&
         a->shift_velocity == b->shift_velocity && a->load == b->load && a->force == b->force &&
         a->force_y == b->force_y && a->load_rate == b->load_rate &&
         a->force_rate == b->force_rate && a->force_y_rate == b->force_y_rate &&
         a->linear == b->linear && a->newton == b->newton;
}

int rs_krylov_residual(rs_krylov *k, const rs_inputs *in, const double *y, const double *yp,
                       double cj, double *F)
{
  const size_t bytes = (size_t)k->m->lay.neq * sizeof *y;
  k->ev_valid = k->w_at_ev = 0;
  const int status = rs_model_linearise_residual(k->m, &k->w, in, y, yp, cj, F);
  if (status != RS_OK) return status;
  k->w_at_ev = 1;
  memcpy(k->y_ev, y, bytes);
  memcpy(k->yp_ev, yp, bytes);
  k->cj_ev = cj;
  k->in_ev = *in;
  k->ev_valid = 1;
  return RS_OK;
}

/* Whether (in, y, yp, cj) is the point of the last rs_krylov_residual. */
static int at_evaluated_point(const rs_krylov *k, const rs_inputs *in, const double *y,
                              const double *yp, double cj)
{
  const size_t bytes = (size_t)k->m->lay.neq * sizeof *y;
  return k->cj_ev == cj && same_inputs(&k->in_ev, in) && !memcmp(k->y_ev, y, bytes) &&
         !memcmp(k->yp_ev, yp, bytes);
}

const rs_work *rs_krylov_evaluated_at(const rs_krylov *k, const rs_inputs *in, const double *y,
                                      const double *yp, double cj)
{
  return k->w_at_ev && at_evaluated_point(k, in, y, yp, cj) ? &k->w : NULL;
}

static int setup_linearised(rs_krylov *k, const rs_inputs *in, double cj);

int rs_krylov_setup(rs_krylov *k, const rs_inputs *in, const double *y, const double *yp, double cj)
{
  /* J v needs the local laws at this point, whatever becomes of the factorisation: those
   * of the last residual if it was evaluated here (bitwise the same), else evaluated now:
   * one model evaluation less per Newton iteration. */
  const int evaluated = k->ev_valid && at_evaluated_point(k, in, y, yp, cj);
  k->ev_valid = 0;
  if (!evaluated) k->w_at_ev = 0;
  int status = evaluated ? RS_OK : rs_model_linearise(k->m, &k->w, in, y, yp, cj);
  if (status == RS_OK) status = setup_linearised(k, in, cj);
  /* the line Gauss-Seidel's couplings of this linearisation, gathered once for the solves
   * (each read the cells' local laws and the kernel's entries before) */
  if (status == RS_OK && k->ylink && k->nparts > 1)
    status = rs_model_near_ylink_prepare(k->m, &k->w, in, cj, k->band, &k->yl);
  return status;
}

/* refresh[q]: whether part q is to be refactored: all of them, or those not factored yet or
 * with a cell on another branch than at their factorisation (a line's cells; the whole
 * matrix's). */
static void mark_refresh(rs_krylov *k, int all)
{
  const int nx = k->m->grid.nx, lines = k->nparts > 1;
  for (int q = 0; q < k->nparts; q++) {
    const int i0 = lines ? q * nx : 0, i1 = lines ? i0 + nx : k->m->lay.n;
    int changed = all || !k->ready[q];
    for (int i = i0; i < i1 && !changed; i++)
      changed = cell_signature(&k->w.law[i]) != k->sig_factored[i];
    k->refresh[q] = (unsigned char)changed;
  }
}

/* A hash of the pattern's columns (FNV-1a steps on whole column indices, four interleaved
 * streams): whether a whole assembly kept the pattern of the last analysis, with the row
 * pointers compared in full, instead of a copy of the columns (8 bytes per entry); a
 * collision could only make the preconditioner
 * poor (the factors on another pattern), never J v or a result. */
static uint64_t columns_hash(const int64_t *ci, int64_t nnz)
{
  const uint64_t prime = 1099511628211ull;
  uint64_t h[4] = {14695981039346656037ull, 1ull, 2ull, 3ull};
  int64_t e = 0;
  for (; e + 4 <= nnz; e += 4)
    for (int j = 0; j < 4; j++) h[j] = (h[j] ^ (uint64_t)ci[e + j]) * prime;
  for (; e < nnz; e++) h[0] = (h[0] ^ (uint64_t)ci[e]) * prime;
  return ((h[0] * prime ^ h[1]) * prime ^ h[2]) * prime ^ h[3];
}

/* The set-up once w holds the linearisation at the point. */
static int setup_linearised(rs_krylov *k, const rs_inputs *in, double cj)
{
  const rs_model *m = k->m;
  const int neq = m->lay.neq;
  k->in = *in;
  k->cj = cj;
  k->setups++;
  if (factor_current(k, in, cj)) {
    k->reuses++;
    return RS_OK;
  }
  /* Lines: only those with cells on other branches than at their own factorisation are
   * assembled and refactored, when the others may serve (reuse on, the same cj + V/dx, not
   * declared stale, the same pattern); their values then lag as in a set-up kept whole. */
  const double rate = cj + fabs(in->velocity) / m->grid.dx;
  int all = !(k->reuse_ratio > 1.0) || k->stale || rate != k->rate_factored || k->nparts < 2;
  k->stale = 0;
  k->rate_factored = rate;
  const int nx = m->grid.nx;
  int lines = k->nparts > 1;
  int64_t *rp = k->near.rowptr;
  int status = RS_ERR_SOLVER, same = 1;
  /* The changed lines' rows only, on the pattern of the last assembly. Lines exist in 3D
   * only, where a row's columns follow from its length (rs_model_jacobian_assemble: fixed
   * columns, fewer only in the traction rows of exterior cells), and the assembly checks
   * each row's length. The columns themselves are not checked again: they could only make
   * the preconditioner, not J v, wrong, and the check costs time at every set-up. */
  if (!all) {
    mark_refresh(k, 0);
    status = rs_model_jacobian_assemble_lines(m, &k->w, in, cj, k->band, k->band_y, k->refresh,
                                              &k->near);
  }
  if (status != RS_OK) { /* the whole matrix */
    status = rs_model_jacobian_assemble(m, &k->w, in, cj, k->band, k->band_y, &k->near);
    if (status != RS_OK) return status;
    const int64_t nnz = rp[neq];
    const uint64_t ci_hash = columns_hash(k->near.col, nnz);
    same = k->nparts > 0 && nnz == k->nnz_old && ci_hash == k->ci_hash &&
           !memcmp(rp, k->rp_old, ((size_t)neq + 1) * sizeof *rp);
    if (!same) {
      memcpy(k->rp_old, rp, ((size_t)neq + 1) * sizeof *rp);
      k->ci_hash = ci_hash;
      k->nnz_old = nnz;
      status = analyse(k);
      k->analyses++;
      if (status != RS_OK) return status;
      all = 1;
      lines = k->nparts > 1;
    }
    mark_refresh(k, all);
  }
  for (int q = 0; q < k->nparts; q++) {
    const int i0 = lines ? q * nx : 0, i1 = lines ? i0 + nx : m->lay.n;
    for (int i = i0; i < i1 && k->refresh[q]; i++)
      k->sig_factored[i] = cell_signature(&k->w.law[i]);
  }
  k->factorizations++;
  int failed = 0;
  if (lines && k->lanes_on) {
    const rs_lanes *ln = &k->lanes;
    /* the groups with a line to refresh, refactored side by side in batches of at most
     * RS_LANES_BATCH, as many batches for each thread, of sizes as equal as they go */
    int ntodo = 0;
    for (int g = 0; g < ln->ngroups; g++) {
      int any = 0;
      for (int l = 0; l < RS_LANES; l++) {
        const int q = ln->group[g].line[l];
        any |= q >= 0 && k->refresh[q];
      }
      if (any) k->lane_todo[ntodo++] = g;
    }
    const int T = k->nsplit;
    int nbatch = (ntodo + RS_LANES_BATCH - 1) / RS_LANES_BATCH;
    if (nbatch % T && ntodo >= T) nbatch += T - nbatch % T;
#pragma omp parallel for num_threads(T) schedule(static) reduction(+ : failed)
    for (int b = 0; b < nbatch; b++) {
      const int t0 = (int)((int64_t)b * ntodo / nbatch),
                t1 = (int)((int64_t)(b + 1) * ntodo / nbatch);
      const int *batch = k->lane_todo + t0;
      if (t1 > t0) rs_lanes_refactor(&k->lanes, batch, t1 - t0, k->near.val, rp, k->refresh);
      for (int j = 0; j < t1 - t0; j++) {
        const rs_lane_group *gr = &ln->group[batch[j]];
        for (int l = 0; l < RS_LANES; l++) {
          const int q = gr->line[l];
          if (q < 0 || !k->refresh[q]) continue;
          if (gr->ok[l]) {
            k->ready[q] = 1;
            continue;
          }
          rs_klu_part *p = &k->part[q]; /* its pivots did not hold: KLU on its own values */
          part_values(k, p);
          k->ready[q] = factor_part(p, same && p->num) == RS_OK;
          failed += !k->ready[q];
        }
      }
    }
  } else if (lines) {
#pragma omp parallel for num_threads(k->nsplit) schedule(static) reduction(+ : failed)
    for (int q = 0; q < k->nparts; q++) { /* each line's values from the assembled rows */
      rs_klu_part *p = &k->part[q];
      if (!k->refresh[q]) continue;
      part_values(k, p);
      k->ready[q] = factor_part(p, same && p->num) == RS_OK;
      failed += !k->ready[q];
    }
  } else {
    k->ready[0] = factor_part(&k->part[0], same) == RS_OK;
    failed = !k->ready[0];
  }
  return failed ? RS_ERR_SOLVER : RS_OK;
}

void rs_krylov_set_reuse(rs_krylov *k, double ratio, int max_cells)
{
  k->reuse_ratio = ratio;
  k->reuse_cells = max_cells;
}

void rs_krylov_invalidate(rs_krylov *k) { k->stale = 1; }

int rs_krylov_times(rs_krylov *k, const double *v, double *Jv)
{
  k->products++;
  return rs_model_jv(k->m, &k->w, &k->wlin, &k->in, k->cj, v, Jv);
}

/* KLU holds the transpose (CSR read as CSC): tsolve applies the inverse of P. */
static int solve_part(rs_klu_part *p, double *v)
{
  if (!p->num) return RS_ERR_SOLVER;
  if (p->borrowed)
    return klu_l_tsolve(p->sym, p->num, p->n, 1, v, &p->common) ? RS_OK : RS_ERR_SOLVER;
  for (int64_t i = 0; i < p->n; i++) p->x[i] = v[p->idx[i]];
  if (!klu_l_tsolve(p->sym, p->num, p->n, 1, p->x, &p->common)) return RS_ERR_SOLVER;
  for (int64_t i = 0; i < p->n; i++) v[p->idx[i]] = p->x[i];
  return RS_OK;
}

int rs_krylov_psolve(rs_krylov *k, double *v)
{
  if (k->nparts == 1) return solve_part(&k->part[0], v);
  if (k->nparts < 2) return RS_ERR_SOLVER;
  const int T = k->nsplit, ny = k->m->grid.ny;
  int failed = 0;
#pragma omp parallel num_threads(T) reduction(+ : failed)
  {
    const int tid = rs_thread_num(), nth = rs_thread_count();
    for (int c = 0; c < 2; c++) {
      if (c > 0) { /* the odd lines' right-hand side: their couplings to the even lines */
#pragma omp barrier
        for (int h = tid; h < T; h += nth) {
          int iy0, iy1;
          half_lines(ny, T, h, &iy0, &iy1);
          rs_model_near_ylink_apply(k->m, &k->yl, h, 1, iy0, iy1, v, v);
        }
      }
      for (int h = tid; h < T; h += nth) {
        if (k->lanes_on) {
          /* side by side in batches of sizes as equal as they go */
          const int g0 = k->gfirst[h][c], count = k->gfirst[h][c + 1] - g0;
          const int nbatch = (count + RS_LANES_BATCH - 1) / RS_LANES_BATCH;
          for (int b = 0; b < nbatch; b++) {
            int batch[RS_LANES_BATCH], m = 0;
            for (int g = g0 + b * count / nbatch; g < g0 + (b + 1) * count / nbatch; g++)
              batch[m++] = g;
            rs_lanes_solve(&k->lanes, batch, m, v);
            for (int j = 0; j < m; j++) {
              const rs_lane_group *gr = &k->lanes.group[batch[j]];
              for (int l = 0; l < RS_LANES; l++)
                if (gr->line[l] >= 0 && !gr->ok[l])
                  failed += solve_part(&k->part[gr->line[l]], v) != RS_OK;
            }
          }
        } else {
          int iy0, iy1;
          half_lines(ny, T, h, &iy0, &iy1);
          for (int iy = iy0 + ((iy0 & 1) != c); iy < iy1; iy += 2)
            failed += solve_part(&k->part[iy], v) != RS_OK;
        }
      }
    }
  }
  return failed ? RS_ERR_SOLVER : RS_OK;
}
