/* Private: the lines of the 3D near-field preconditioner (linsys_krylov.h) factored and
 * solved side by side, RS_LANES lines at a time, one line per lane of a vector.
 *
 * Every line has the same unknowns (the cells of a row of the grid, in the same local
 * order), so the union of the lines' patterns is one pattern, which KLU orders and factors
 * once (a representative line, partial pivoting); every line is then refactored on that
 * pattern with that pivot order and solved with it, the lines of a group in the lanes of
 * one vector: an entry of L or U costs one vector operation for RS_LANES lines, where KLU's
 * own triangular solves spend about ten scalar instructions per entry and are bound by that
 * count. KLU's own choice of pivots on these lines is its ordering's diagonal (the pivot
 * sequence of each line follows from its pattern alone), so one order serves the lines;
 * the union adds about a fifth more entries. A line
 * whose pivots the common order does not suit (the smallest |u_kk| below 1e-8 of the
 * largest, KLU's own test for reusing an order) is marked and left to the caller (KLU with
 * partial pivoting on its own pattern). The entries the union adds to a line are zeros:
 * the factors are those of the line's own matrix up to roundoff. The solves read the factors in
 * single precision (rs_lanes_solve); the factorisation itself is in double. */
#ifndef ROLLSIM_LINSYS_LANES_H
#define ROLLSIM_LINSYS_LANES_H

#include <stdint.h>

enum { RS_LANES = 4, RS_LANES_BATCH = 4 };
typedef double rs_lane_vec __attribute__((vector_size(RS_LANES * sizeof(double))));
/* the solves' factors: single precision (see rs_lanes_solve) */
typedef float rs_lane_vecf __attribute__((vector_size(RS_LANES * sizeof(float))));

/* One line's matrix as the caller holds it: local CSR (n unknowns), and the global index
 * of each local unknown. */
typedef struct rs_lane_line {
  const int64_t *rowptr, *col, *idx;
} rs_lane_line;

typedef struct rs_lane_group {
  int line[RS_LANES];         /* the caller's line of each lane, -1: unused */
  unsigned char ok[RS_LANES]; /* the lane's factors hold (else the caller solves that line) */
  rs_lane_vec *ax;            /* A on the common pattern (CSC), lane by lane */
  rs_lane_vec *lx, *ud;       /* L below the diagonal by columns; ud: 1 / u_kk */
  rs_lane_vecf *lr, *ux;      /* for the solves: L by rows (lrp), U above it by rows (urp) */
  rs_lane_vec *w;             /* work of the refactorisation and the solve */
  int *gin, *gout;            /* n x RS_LANES: global index of pivot row / column k */
} rs_lane_group;

typedef struct rs_lanes {
  int n, nlines;
  int64_t *ap, *ai;       /* common pattern, CSC */
  int **amap;             /* per line: the CSC position of each of its CSR entries */
  int64_t *amap_len;      /* entries of each line */
  rs_lane_line *lines;    /* the caller's lines (their arrays stay the caller's) */
  int *q, *prow, *pinv;   /* column and row of pivot step k; pivot step of row i */
  int *lp, *li, *up, *ui; /* L, U without the diagonal, by columns in pivot order */
  /* The same by rows, for the solves: row k of L its columns ascending, row k of U its
   * columns descending (the order in which the column-oriented solves update an unknown);
   * lperm / uperm: the row-ordered position of each column-ordered entry */
  int *lrp, *lrc, *lperm, *urp, *urc, *uperm;
  int ngroups;
  rs_lane_group *group;
} rs_lanes;

/* The common pattern of nlines lines of n unknowns, its ordering and pivot order (KLU, the
 * line rep's values), and the groups: lines listed in order[0..norder-1], cut into groups
 * of RS_LANES where first_of_group marks a forced start. RS_OK, or an error (then the
 * caller keeps its own factorisations). */
int rs_lanes_create(rs_lanes *s, int n, int nlines, const rs_lane_line *lines,
                    const double *const *values, int rep, const int *order, int norder,
                    const unsigned char *first_of_group);
void rs_lanes_free(rs_lanes *s);
/* The lanes of the m groups groups[0..m-1] (1 <= m <= RS_LANES_BATCH) refactored side by side
 * from the matrix the lines' rows come from (CSR values gval, row pointers grp: line q's
 * row i is the first entries of row idx[i] there); refresh[line] says which lines' values
 * changed (the others' stay as last scattered). Sets ok[]. */
void rs_lanes_refactor(rs_lanes *s, const int *groups, int m, const double *gval,
                       const int64_t *grp, const unsigned char *refresh);
/* v <- the solves of the lines whose factors hold (global indices) of the m groups
 * groups[0..m-1], 1 <= m <= RS_LANES_BATCH, solved side by side. */
void rs_lanes_solve(const rs_lanes *s, const int *groups, int m, double *v);

#endif
