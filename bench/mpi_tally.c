/* Counts each rank's MPI traffic through the MPI profiling interface (MPI standard, ch. 15:
 * every MPI_X is also PMPI_X, so a library loaded first can wrap the calls of an unchanged
 * binary). Point-to-point sends are counted as messages and bytes, collectives as calls. At
 * MPI_Finalize each rank appends one line to the file named by MPI_TALLY_FILE:
 *
 *   rank R sends N bytes B allreduce A collectives C
 *
 * Build and use (bench/run_halo.sh does both):
 *   mpicc -O2 -shared -fPIC -o libmpi_tally.so bench/mpi_tally.c
 *   MPI_TALLY_FILE=t.txt mpirun -x LD_PRELOAD=./libmpi_tally.so -x MPI_TALLY_FILE -np 4 perifem deck.yaml
 * Counts include the set-up's traffic; the per-step traffic is the difference of two runs that
 * differ only in their number of steps. */
#include <mpi.h>
#include <stdio.h>
#include <stdlib.h>

static long long sends, send_bytes, allreduces, collectives;

static void count_send(int count, MPI_Datatype type) {
  int size = 0;
  PMPI_Type_size(type, &size);
  sends++;
  send_bytes += (long long)count * size;
}

int MPI_Send(const void *buf, int count, MPI_Datatype type, int dest, int tag, MPI_Comm comm) {
  count_send(count, type);
  return PMPI_Send(buf, count, type, dest, tag, comm);
}

int MPI_Isend(const void *buf, int count, MPI_Datatype type, int dest, int tag, MPI_Comm comm, MPI_Request *req) {
  count_send(count, type);
  return PMPI_Isend(buf, count, type, dest, tag, comm, req);
}

int MPI_Allreduce(const void *in, void *out, int count, MPI_Datatype type, MPI_Op op, MPI_Comm comm) {
  allreduces++;
  return PMPI_Allreduce(in, out, count, type, op, comm);
}

int MPI_Barrier(MPI_Comm comm) {
  collectives++;
  return PMPI_Barrier(comm);
}

int MPI_Bcast(void *buf, int count, MPI_Datatype type, int root, MPI_Comm comm) {
  collectives++;
  return PMPI_Bcast(buf, count, type, root, comm);
}

int MPI_Gather(const void *s, int sc, MPI_Datatype st, void *r, int rc, MPI_Datatype rt, int root, MPI_Comm comm) {
  collectives++;
  return PMPI_Gather(s, sc, st, r, rc, rt, root, comm);
}

int MPI_Gatherv(const void *s, int sc, MPI_Datatype st, void *r, const int *rc, const int *displs, MPI_Datatype rt,
                int root, MPI_Comm comm) {
  collectives++;
  return PMPI_Gatherv(s, sc, st, r, rc, displs, rt, root, comm);
}

int MPI_Allgather(const void *s, int sc, MPI_Datatype st, void *r, int rc, MPI_Datatype rt, MPI_Comm comm) {
  collectives++;
  return PMPI_Allgather(s, sc, st, r, rc, rt, comm);
}

int MPI_Allgatherv(const void *s, int sc, MPI_Datatype st, void *r, const int *rc, const int *displs, MPI_Datatype rt,
                   MPI_Comm comm) {
  collectives++;
  return PMPI_Allgatherv(s, sc, st, r, rc, displs, rt, comm);
}

int MPI_Alltoall(const void *s, int sc, MPI_Datatype st, void *r, int rc, MPI_Datatype rt, MPI_Comm comm) {
  collectives++;
  return PMPI_Alltoall(s, sc, st, r, rc, rt, comm);
}

int MPI_Alltoallv(const void *s, const int *sc, const int *sd, MPI_Datatype st, void *r, const int *rc, const int *rd,
                  MPI_Datatype rt, MPI_Comm comm) {
  collectives++;
  return PMPI_Alltoallv(s, sc, sd, st, r, rc, rd, rt, comm);
}

int MPI_Finalize(void) {
  int rank = 0;
  PMPI_Comm_rank(MPI_COMM_WORLD, &rank);
  const char *path = getenv("MPI_TALLY_FILE");
  FILE *f = path ? fopen(path, "a") : NULL;
  if (f) {
    fprintf(f, "rank %d sends %lld bytes %lld allreduce %lld collectives %lld\n", rank, sends, send_bytes, allreduces,
            collectives);
    fclose(f);
  }
  return PMPI_Finalize();
}
