#include "core/errors.hpp"
#include <cstdio>
#include <cerrno>
#include <cstring>
#include <unistd.h>

namespace nltopo {

PetscErrorCode OneLineErrorHandler(MPI_Comm comm, int line, const char *fun, const char *file, PetscErrorCode n, PetscErrorType p,
                                   const char *mess, void *ctx)
{
  if (p != PETSC_ERROR_INITIAL) return n;
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  if (rank) return n; // collective errors print once
  const char *text = NULL;
  PetscErrorMessage(n, &text, NULL);
  const bool user = n == PETSC_ERR_USER || n == PETSC_ERR_FILE_OPEN || n == PETSC_ERR_FILE_WRITE || n == PETSC_ERR_FP || n == PETSC_ERR_NOT_CONVERGED;
  if (user) std::fprintf(stderr, "nltopo: error: %s\n", mess && mess[0] ? mess : text);
  else std::fprintf(stderr, "nltopo: error: %s: %s [%s, %s:%d]\n", text ? text : "PETSc error", mess ? mess : "", fun, file, line);
  std::fflush(stderr);
  return n;
}

bool OptionsFilesReadable(int argc, char **argv)
{
  for (int i = 1; i < argc; i++) {
    if (std::strcmp(argv[i], "-options_file")) continue;
    if (i + 1 >= argc) {
      std::fprintf(stderr, "nltopo: error: -options_file needs a file name\n");
      return false;
    }
    if (access(argv[i + 1], R_OK)) {
      std::fprintf(stderr, "nltopo: error: cannot read -options_file %s: %s\n", argv[i + 1], std::strerror(errno));
      return false;
    }
  }
  return true;
}

} // namespace nltopo
