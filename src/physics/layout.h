/* Where the unknowns of the DAE live in the state vector y (and the equations in the
 * residual F: row k belongs to unknown k). Per cell I of n cells: the tangential
 * traction p (ncomp components: 1 in 2D, 2 in 3D), the plastic displacement difference
 * u_pl (ncomp), the accumulated plastic deformation u*, with friction memory the
 * coefficient of friction mu (docs/model.md §11); then the extra unknowns (force-controlled
 * creepages). Blocks by quantity and component, cells inside a block:
 *   y = [ p_0 | (p_1) | upl_0 | (upl_1) | ustar | (mu) | extras ]
 * (2D: [ p | upl | ustar ( | mu ) ( | xi ) ], neq = 3 n (+ n) (+ 1)). Without memory the
 * layout is that of the memoryless model, index for index. */
#ifndef ROLLSIM_LAYOUT_H
#define ROLLSIM_LAYOUT_H

typedef struct rs_layout {
  int n;      /* cells */
  int ncomp;  /* tangential components per cell */
  int nextra; /* extra unknowns: prescribed-force creepages (0, 1 in 2D, 2 in 3D) */
  int memory; /* 1: a friction-memory state mu per cell */
  int ncell;  /* unknowns per cell: 2 ncomp + 1 (+ 1 with memory) */
  int neq;    /* ncell n + nextra */
} rs_layout;

static inline rs_layout rs_layout_make(int n, int ncomp, int nextra, int memory)
{
  const int ncell = 2 * ncomp + 1 + (memory ? 1 : 0);
  return (rs_layout){.n = n,
                     .ncomp = ncomp,
                     .nextra = nextra,
                     .memory = memory ? 1 : 0,
                     .ncell = ncell,
                     .neq = ncell * n + nextra};
}

/* Index of component c of the traction of cell I. */
static inline int rs_at_p(const rs_layout *L, int c, int I) { return c * L->n + I; }
/* Index of component c of the plastic displacement of cell I. */
static inline int rs_at_upl(const rs_layout *L, int c, int I) { return (L->ncomp + c) * L->n + I; }
/* Index of the accumulated plastic deformation of cell I. */
static inline int rs_at_ustar(const rs_layout *L, int I) { return 2 * L->ncomp * L->n + I; }
/* Index of the friction-memory state mu of cell I (only with L->memory). */
static inline int rs_at_mu(const rs_layout *L, int I) { return (2 * L->ncomp + 1) * L->n + I; }
/* Index of extra unknown k. */
static inline int rs_at_extra(const rs_layout *L, int k) { return L->ncell * L->n + k; }

#endif
