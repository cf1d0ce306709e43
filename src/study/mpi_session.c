/* The MPI session (study/mpi_session.h): Open MPI (Debian) when built with RS_HAVE_MPI. */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "study/mpi_session.h"

#ifdef RS_HAVE_MPI
#include <mpi.h>
#ifdef _OPENMP
#include <omp.h>
#endif

/* Environment variables a launcher sets: Open MPI's mpirun, MPICH/Hydra and Slurm's PMI(x). */
static int under_launcher(void)
{
  static const char *const vars[] = {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK", NULL};
  for (int i = 0; vars[i]; i++)
    if (getenv(vars[i])) return 1;
  return 0;
}

int rs_mpi_start(rs_mpi *mpi, int *argc, char ***argv)
{
  memset(mpi, 0, sizeof *mpi);
  mpi->size = 1;
  if (!under_launcher()) return 0;
  if (MPI_Init(argc, argv) != MPI_SUCCESS) {
    fprintf(stderr, "rollsim: MPI_Init failed\n");
    return -1;
  }
  mpi->initialised = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &mpi->rank);
  MPI_Comm_size(MPI_COMM_WORLD, &mpi->size);
#ifdef _OPENMP
  /* the ranks share the cores: one thread each (util.h, rs_threads) */
  if (mpi->size > 1) omp_set_num_threads(1);
#endif
  return 0;
}

void rs_mpi_finish(rs_mpi *mpi)
{
  if (mpi->initialised) MPI_Finalize();
  mpi->initialised = 0;
}

void rs_mpi_abort(const rs_mpi *mpi, int code)
{
  if (mpi->initialised) MPI_Abort(MPI_COMM_WORLD, code);
}

int rs_mpi_send_doubles(const double *buf, int n, int to, int tag)
{
  return MPI_Send(buf, n, MPI_DOUBLE, to, tag, MPI_COMM_WORLD) == MPI_SUCCESS ? 0 : -1;
}

int rs_mpi_send_text(const char *text, int to, int tag)
{
  return MPI_Send(text, (int)strlen(text) + 1, MPI_CHAR, to, tag, MPI_COMM_WORLD) == MPI_SUCCESS
             ? 0
             : -1;
}

int rs_mpi_recv_doubles(double *buf, int cap, int from, int tag, int *src, int *got_tag, int *n)
{
  MPI_Status st;
  if (MPI_Recv(buf, cap, MPI_DOUBLE, from < 0 ? MPI_ANY_SOURCE : from, tag < 0 ? MPI_ANY_TAG : tag,
               MPI_COMM_WORLD, &st) != MPI_SUCCESS)
    return -1;
  if (src) *src = st.MPI_SOURCE;
  if (got_tag) *got_tag = st.MPI_TAG;
  if (n) MPI_Get_count(&st, MPI_DOUBLE, n);
  return 0;
}

int rs_mpi_recv_text(char *buf, int cap, int from, int tag, int *src)
{
  MPI_Status st;
  if (MPI_Recv(buf, cap, MPI_CHAR, from < 0 ? MPI_ANY_SOURCE : from, tag < 0 ? MPI_ANY_TAG : tag,
               MPI_COMM_WORLD, &st) != MPI_SUCCESS)
    return -1;
  int n = 0;
  MPI_Get_count(&st, MPI_CHAR, &n);
  buf[n > 0 && n <= cap ? n - 1 : 0] = '\0';
  if (src) *src = st.MPI_SOURCE;
  return 0;
}

int rs_mpi_probe(int *src, int *tag)
{
  int flag = 0;
  MPI_Status st;
  MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &st);
  if (flag) {
    *src = st.MPI_SOURCE;
    *tag = st.MPI_TAG;
  }
  return flag;
}

int rs_mpi_wait(int *src, int *tag)
{
  MPI_Status st;
  if (MPI_Probe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &st) != MPI_SUCCESS) return -1;
  *src = st.MPI_SOURCE;
  *tag = st.MPI_TAG;
  return 0;
}

#else /* serial build */

int rs_mpi_start(rs_mpi *mpi, int *argc, char ***argv)
{
  (void)argc;
  (void)argv;
  memset(mpi, 0, sizeof *mpi);
  mpi->size = 1;
  return 0;
}
void rs_mpi_finish(rs_mpi *mpi) { mpi->initialised = 0; }
void rs_mpi_abort(const rs_mpi *mpi, int code)
{
  (void)mpi;
  (void)code;
}
int rs_mpi_send_doubles(const double *buf, int n, int to, int tag)
{
  (void)buf, (void)n, (void)to, (void)tag;
  return -1;
}
int rs_mpi_send_text(const char *text, int to, int tag)
{
  (void)text, (void)to, (void)tag;
  return -1;
}
int rs_mpi_recv_doubles(double *buf, int cap, int from, int tag, int *src, int *got_tag, int *n)
{
  (void)buf, (void)cap, (void)from, (void)tag, (void)src, (void)got_tag, (void)n;
  return -1;
}
int rs_mpi_recv_text(char *buf, int cap, int from, int tag, int *src)
{
  (void)buf, (void)cap, (void)from, (void)tag, (void)src;
  return -1;
}
int rs_mpi_probe(int *src, int *tag)
{
  (void)src, (void)tag;
  return 0;
}
int rs_mpi_wait(int *src, int *tag)
{
  (void)src, (void)tag;
  return -1;
}
#endif
