#pragma once
// In-process runs of the nltopo driver's code path (RunStudyFromOptions) on a
// command line that must be refused: the options database holds only that
// command line (a pushed database; the test binary's own is restored after),
// the one-line error handler is pushed and this process's stderr is captured,
// as the shell saw it. Used by test_bad_options.cpp.
#include "core/errors.hpp"
#include "io/output.hpp"
#include "studies/registry.hpp"
#include "studies/study.hpp"
#include "helpers.hpp"
#include <cstdio>
#include <cstdlib>
#include <dirent.h>
#include <string>
#include <unistd.h>
#include <vector>

namespace nltopo::test {

// Splits a command line at spaces; '...' quotes one argument (which may be
// empty or hold spaces), as the shell would.
inline std::vector<std::string> SplitArgs(const std::string &line)
{
  std::vector<std::string> args;
  size_t i = 0;
  while (i < line.size()) {
    if (line[i] == ' ') {
      i++;
      continue;
    }
    if (line[i] == '\'') {
      const size_t end = line.find('\'', i + 1);
      args.push_back(line.substr(i + 1, end - i - 1));
      i = end + 1;
      continue;
    }
    const size_t end = std::min(line.find(' ', i), line.size());
    args.push_back(line.substr(i, end - i));
    i = end;
  }
  return args;
}

// The options of a command line, read the way PETSc reads argv
// (PetscOptionsInsertArgs): a key takes the next word as its value unless that
// word is a key too.
inline PetscErrorCode InsertArgs(PetscOptions db, const std::vector<std::string> &args)
{
  PetscFunctionBeginUser;
  for (size_t i = 0; i < args.size();) {
    PetscBool key, next_key = PETSC_TRUE;
    PetscCall(PetscOptionsValidKey(args[i].c_str(), &key));
    if (!key) {
      i++;
      continue;
    }
    if (i + 1 < args.size()) PetscCall(PetscOptionsValidKey(args[i + 1].c_str(), &next_key));
    PetscCall(PetscOptionsSetValue(db, args[i].c_str(), next_key ? NULL : args[i + 1].c_str()));
    i += next_key ? 1 : 2;
  }
  PetscFunctionReturn(0);
}

// What one refused run left: its error code, what it printed on stderr (this
// rank's), and the files in its output directory afterwards.
struct Refusal {
  PetscErrorCode code = 0;
  std::string err;
  std::vector<std::string> files;
  std::vector<std::string> unused; // the options its database holds unused at the end (what -options_left lists)
  double seconds = 0;              // the run's wall time (RunStudyFromOptions)
  int setups = 0;                  // how many times it entered a study's Setup stage
};

inline std::vector<std::string> DirEntries(const std::string &dir)
{
  std::vector<std::string> names;
  if (DIR *d = opendir(dir.c_str())) {
    while (const dirent *e = readdir(d))
      if (std::string(e->d_name) != "." && std::string(e->d_name) != "..") names.push_back(e->d_name);
    closedir(d);
  }
  return names;
}

// A fresh directory for the outputs, the same path on every rank.
inline std::string SharedTempDir()
{
  char path[256] = "";
  if (!Rank()) {
    std::snprintf(path, sizeof(path), "%s/nltopo_bad_options_XXXXXX", std::getenv("TMPDIR") ? std::getenv("TMPDIR") : "/tmp");
    if (!mkdtemp(path)) path[0] = 0;
  }
  MPI_Bcast(path, sizeof(path), MPI_CHAR, 0, PETSC_COMM_WORLD);
  return path;
}

// Runs the driver on args + "-output <dir>/o.h5" (dir empty before).
inline Refusal RunRefused(const std::vector<std::string> &args, const std::string &dir)
{
  Refusal r;
  PetscOptions db;
  PCHK(PetscOptionsCreate(&db));
  std::vector<std::string> all = args;
  all.push_back("-output");
  all.push_back(dir + "/o.h5");
  PCHK(InsertArgs(db, all));
  PCHK(PetscOptionsPush(db));
  std::fflush(stderr);
  const int saved = dup(2);
  std::FILE *tmp = std::tmpfile();
  REQUIRE(tmp);
  dup2(fileno(tmp), 2);
  PetscPushErrorHandler(OneLineErrorHandler, NULL);
  const int setups = SetupStagesEntered();
  const double t0 = MPI_Wtime();
  r.code = RunStudyFromOptions(PETSC_COMM_WORLD);
  r.seconds = MPI_Wtime() - t0;
  r.setups = SetupStagesEntered() - setups;
  PetscPopErrorHandler();
  std::fflush(stderr);
  dup2(saved, 2);
  close(saved);
  std::rewind(tmp);
  char buf[4096];
  size_t n;
  while ((n = std::fread(buf, 1, sizeof(buf), tmp)) > 0) r.err.append(buf, n);
  std::fclose(tmp);
  {
    PetscInt n;
    char **names, **values;
    PCHK(PetscOptionsLeftGet(db, &n, &names, &values));
    for (PetscInt i = 0; i < n; i++) r.unused.push_back(names[i]);
    PCHK(PetscOptionsLeftRestore(db, &n, &names, &values));
  }
  PCHK(PetscOptionsPop());
  PCHK(PetscOptionsDestroy(&db));
  // What a refused run may have set for the process: nothing of it may reach the next test.
  PCHK(SetCommitGuard(nullptr));
  SetOutputContext(nullptr);
  MPI_Barrier(PETSC_COMM_WORLD);
  r.files = DirEntries(dir);
  return r;
}

} // namespace nltopo::test
