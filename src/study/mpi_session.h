/* Private to the drivers: the MPI session of a process. MPI is initialised only when the
 * process was started by an MPI launcher (mpirun/mpiexec/srun set OMPI_COMM_WORLD_SIZE,
 * PMI_SIZE or PMIX_RANK); otherwise, and in builds without MPI (-DRS_MPI=OFF), the
 * process is rank 0 of 1 and nothing of MPI is touched. */
#ifndef ROLLSIM_MPI_SESSION_H
#define ROLLSIM_MPI_SESSION_H

#include <stddef.h>

typedef struct rs_mpi {
  int rank, size;
  int initialised; /* MPI_Init was called (MPI_Finalize due) */
} rs_mpi;

/* Start MPI under a launcher. Returns 0, or -1 when MPI_Init failed (message printed). */
int rs_mpi_start(rs_mpi *mpi, int *argc, char ***argv);
void rs_mpi_finish(rs_mpi *mpi);
/* Stop every rank at once (an internal error on one of them). */
void rs_mpi_abort(const rs_mpi *mpi, int code);

/* Point-to-point messages (no-ops returning -1 without MPI). Tags are small integers. */
int rs_mpi_send_doubles(const double *buf, int n, int to, int tag);
int rs_mpi_send_text(const char *text, int to, int tag);
/* Receive from anyone (from < 0) or one rank, any tag (tag < 0) or one; the sender and
 * tag are returned; *n the number of doubles (or bytes for text, NUL-terminated). */
int rs_mpi_recv_doubles(double *buf, int cap, int from, int tag, int *src, int *got_tag, int *n);
int rs_mpi_recv_text(char *buf, int cap, int from, int tag, int *src);
/* A message waiting (nonblocking)? Its sender and tag. */
int rs_mpi_probe(int *src, int *tag);
/* Block until a message is there: its sender and tag. */
int rs_mpi_wait(int *src, int *tag);

#endif
