/* Kalker's linear theory of rolling contact (full adhesion, vanishing creepages):
 * creepage and spin coefficients of an elliptic contact, by interpolation in Kalker's
 * published table (docs/verification.md 10).
 *
 * Source of the numbers. Kalker 1967 (thesis, Delft) computed them; they are tabulated in
 * Kalker 1990, "Three-dimensional elastic bodies in rolling contact", Kluwer, Appendix E,
 * Table E.3, and reproduced in Johnson 1985, "Contact Mechanics", Table 8.1. The values
 * typed in kalker.c were taken from the transcription of Table E.3 in the open-source
 * CONTACT program of Vollebregt & Kalker (github.com/eve70a/CONTACT, src/m_hertz.f90,
 * subroutine linrol, commit 6a9d48e) and cross-checked entry by entry against a second
 * transcription in the same project (src/usetab_table.f90, commit a6799ce). They agree
 * except C23 at a/b = 0.8, nu = 0.25, given as 1.15 in the second copy and 1.25 in the
 * first; 1.25 is taken, as the row sequence 1.03, 1.14, [.], 1.36, 1.47 (and the
 * columns at nu = 0 and 0.5, steps of 0.10-0.11) requires. A copy of Johnson's or
 * Kalker's printed table was not available here for a third check. C11 = C22 at nu = 0
 * holds in every row (the kernel is isotropic in x-y at nu = 0), and every column is
 * smooth; both are asserted in test_kalker.
 *
 * C33 (the spin-moment coefficient) is given for a <= b only, the half of Table E.3 whose
 * values were at hand (Kalker 1990, Table E.3, a/b = 0.1 ... 1.0). Neither transcription
 * above carries that column, and no printed copy was available to type it from, so every
 * entry was checked against an independent computation instead: rollsim's own spin moment
 * M_z(phi) of an elastic ellipse in full adhesion on 64^2 and 128^2 cells, extrapolated to
 * zero cell size with the scheme's first order, agrees with each of the 30 entries to within
 * 1 % (bench/kalker_coefficients prints the comparison, with C11, C22 and C23 at every node
 * of the table; docs/verification.md 10). For a > b no value could be checked that way
 * against a source, so C33 is NaN there.
 *
 * Laws and sign conventions (Kalker 1990 §2.2 / Johnson 1985 §8.4), G the combined
 * shear modulus, a the semi-axis along the rolling direction x, b across it:
 *   F_x = -G a b C11 xi
 *   F_y = -G a b (C22 eta + sqrt(a b) C23 phi)
 *   M_z =  G (a b)^(3/2) (C23 eta - sqrt(a b) C33 phi)
 * with F the tangential force exerted on body 1 and M_z its moment about the contact
 * centre. All C_ij > 0.
 *
 * Mapping to rollsim (docs/model.md §1, §10). rollsim's conventions are Kalker's: the rigid
 * slip w = (xi - phi y, eta + phi x), p the traction on body 1, F = sum p dx dy,
 * M_z = sum (x p_y - y p_x) dx dy, rolling along +x with material entering at the
 * leading edge x = +a. So the laws apply unchanged: xi < 0 gives F_x > 0 (docs/model.md §1).
 * The signs of the coupling terms depend on the rolling direction; with rollsim's they
 * are the ones above: in full adhesion the steady slip vanishes, du/dx = w (v_s = V w -
 * V du/dx), and with the local law p ~ u of Kalker's simplified theory (enough for signs)
 * the traction-free leading edge has u = 0, so u_y(x) = eta (x - a) + phi (x^2 - a^2)/2,
 * which is <= 0 inside the patch for eta, phi > 0: F_y < 0 from both (C22, C23 > 0), and
 * M_z = Int x p_y ~ Int x eta (x - a) > 0 (+C23 eta); the spin term of M_z,
 * Int -y p_x ~ phi Int y^2 (x - a) < 0 (-C33 phi). Rolling the other way (leading edge
 * at x = -a) would flip the signs of both C23 terms. */
#ifndef ROLLSIM_KALKER_H
#define ROLLSIM_KALKER_H

#include "base/status.h"

/* Kalker's creepage coefficients (dimensionless). */
typedef struct rs_kalker {
  double c11; /* longitudinal creepage xi -> F_x */
  double c22; /* lateral creepage eta -> F_y */
  double c23; /* spin -> F_y and lateral creepage -> M_z */
  double c33; /* spin -> M_z; NaN for a > b (not tabulated here) */
} rs_kalker;

/* The table: rows of a/b = 0.1, 0.2, ..., 1.0 and then b/a = 0.9, 0.8, ..., 0.1
 * (a/b = 1/0.9 ... 10), at nu = 0, 0.25, 0.5. */
#define RS_KALKER_ROWS     19
#define RS_KALKER_NUS      3
/* C33's rows: a/b = 0.1, ..., 1.0. */
#define RS_KALKER_C33_ROWS 10

/* The semi-axis ratio a/b of table row `row` (0..RS_KALKER_ROWS-1). */
double rs_kalker_row_ratio(int row);
/* The tabulated value of coefficient `which` (0: C11, 1: C22, 2: C23, 3: C33) at a row and
 * nu = 0.25 nu_index (nu_index 0..2); C33 is NaN in the rows a > b. */
double rs_kalker_table(int which, int row, int nu_index);

/* Coefficients for the semi-axis ratio a/b in [0.1, 10] and nu in [0, 0.5]: monotone
 * piecewise-cubic Hermite interpolation (Fritsch & Butland 1984, harmonic-mean slopes) in
 * s = a/b (a <= b) or s = 2 - b/a (a > b), nodes every 0.1 of s from 0.1 to 1.9 (s and its
 * derivative continuous at a = b), then in nu through the three nu columns. Each is
 * monotone between nodes and returns the table values exactly at nodes. Outside the
 * table: RS_ERR_INPUT. */
int rs_kalker_coefficients(double a_over_b, double poisson_ratio, rs_kalker *c, rs_msg *msg);

/* The linear-theory forces on body 1 for creepages xi, eta and spin phi (1/mm):
 * F_x = -G a b C11 xi, F_y = -G a b (C22 eta + sqrt(a b) C23 phi) (N), and, if mz is not
 * NULL, M_z = G (a b)^(3/2) (C23 eta - sqrt(a b) C33 phi) (N mm; NaN for a > b with spin). */
void rs_kalker_forces(const rs_kalker *c, double shear_modulus, double a, double b, double xi,
                      double eta, double phi, double *fx, double *fy, double *mz);

#endif
