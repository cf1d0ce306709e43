/* RS_BLAS=mkl: MKL's sequential threading layer, chosen before its first call (the function
 * takes precedence over MKL_THREADING_LAYER). rollsim calls LAPACK from several of its own
 * OpenMP threads (GNU's runtime) at once; MKL's default Intel layer brings a second OpenMP
 * runtime that does not know them, and concurrent factorisations then fail (DLASWP parameter
 * errors, crashes in cases/friction_memory.yaml). Sequential MKL is what the default build's
 * serial OpenBLAS is. Compiled into the executable, librollsim.so and every program linking
 * rollsim_lib (CMakeLists.txt, RS_BLAS). */
int MKL_Set_Threading_Layer(int code);    /* mkl_service.h */
enum { RS_MKL_THREADING_SEQUENTIAL = 1 }; /* mkl_service.h: MKL_THREADING_SEQUENTIAL */

__attribute__((constructor)) static void rs_mkl_sequential(void)
{
  MKL_Set_Threading_Layer(RS_MKL_THREADING_SEQUENTIAL);
}
