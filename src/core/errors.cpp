#include "core/errors.hpp"
#include <cstdio>
#include <cstdlib>
#include <cerrno>
#include <cstring>
#include <strings.h>
#include <unistd.h>

namespace nltopo {

static bool interrupt_reported = false;

bool InterruptReported() { return interrupt_reported; }

PetscErrorCode OneLineErrorHandler(MPI_Comm comm, int line, const char *fun, const char *file, PetscErrorCode n, PetscErrorType p,
                                   const char *mess, void *ctx)
{
  if (p != PETSC_ERROR_INITIAL) return n;
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  if (rank) return n; // collective errors print once
  if (n == PETSC_ERR_SIG) { // a stop signal (core/signals.hpp): silent on the way out, then the study's one line
    if (mess && mess[0] && mess[0] != ' ') {
      std::fprintf(stderr, "nltopo: %s\n", mess);
      std::fflush(stderr);
      interrupt_reported = true;
    }
    return n;
  }
  const char *text = NULL;
  PetscErrorMessage(n, &text, NULL);
  const bool user = n == PETSC_ERR_USER || n == PETSC_ERR_FILE_OPEN || n == PETSC_ERR_FILE_WRITE || n == PETSC_ERR_FP || n == PETSC_ERR_NOT_CONVERGED;
  if (user) std::fprintf(stderr, "nltopo: error: %s\n", mess && mess[0] ? mess : text);
  else std::fprintf(stderr, "nltopo: error: %s: %s [%s, %s:%d]\n", text ? text : "PETSc error", mess ? mess : "", fun, file, line);
  std::fflush(stderr);
  return n;
}

PetscErrorCode RejectGivenOptions(MPI_Comm comm, std::initializer_list<const char *> names, const char *set_by)
{
  PetscFunctionBeginUser;
  for (const char *name : names) {
    PetscBool set;
    PetscCall(PetscOptionsHasName(NULL, NULL, name, &set));
    PetscCheck(!set, comm, PETSC_ERR_USER, "%s is set by %s; remove it", name, set_by);
  }
  PetscFunctionReturn(0);
}

PetscErrorCode FailTogether(MPI_Comm comm, PetscErrorCode code, const char *msg)
{
  PetscMPIInt rank, size, first, who;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  first = code ? rank : size;
  PetscCallMPI(MPI_Allreduce(&first, &who, 1, MPI_INT, MPI_MIN, comm));
  if (who == size) PetscFunctionReturn(0);
  int c = (int)code;
  char buf[1024] = "";
  if (rank == who) PetscCall(PetscStrncpy(buf, msg ? msg : "", sizeof(buf)));
  PetscCallMPI(MPI_Bcast(&c, 1, MPI_INT, who, comm));
  PetscCallMPI(MPI_Bcast(buf, sizeof(buf), MPI_CHAR, who, comm));
  SETERRQ(comm, (PetscErrorCode)c, "%s", buf);
}

static bool CaseTrap(const char *token, const char *where)
{
  // Any spelling of -lattice_gamma with an upper-case letter (-lattice_Gamma, -LATTICE_GAMMA, ...)
  if (strcasecmp(token, "-lattice_gamma") || !std::strcmp(token, "-lattice_gamma")) return false;
  std::fprintf(stderr, "nltopo: error: %s: %s is the same option as -lattice_gamma (PETSc option names are case-insensitive); set the cubic coefficient with -lattice_cubic\n", where, token);
  return true;
}

bool PreflightArguments(int argc, char **argv)
{
  for (int i = 1; i < argc; i++) {
    if (CaseTrap(argv[i], "command line")) return false;
    if (std::strcmp(argv[i], "-options_file")) continue;
    if (i + 1 >= argc) {
      std::fprintf(stderr, "nltopo: error: -options_file needs a file name\n");
      return false;
    }
    std::FILE *f = std::fopen(argv[i + 1], "r");
    if (!f) {
      std::fprintf(stderr, "nltopo: error: cannot read -options_file %s: %s\n", argv[i + 1], std::strerror(errno));
      return false;
    }
    char line[4096], tok[4096];
    bool bad = false;
    while (!bad && std::fgets(line, sizeof(line), f))
      if (std::sscanf(line, " %4095s", tok) == 1) bad = CaseTrap(tok, argv[i + 1]);
    std::fclose(f);
    if (bad) return false;
  }
  if (const char *env = std::getenv("PETSC_OPTIONS")) {
    char tok[4096];
    int n = 0;
    for (const char *p = env; std::sscanf(p, " %4095s%n", tok, &n) == 1; p += n)
      if (CaseTrap(tok, "PETSC_OPTIONS")) return false;
  }
  return true;
}

} // namespace nltopo
