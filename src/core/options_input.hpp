#pragma once
// The options as PETSc reads them (docs/errors.md "The command line and
// options files"). PETSc builds its database from PETSC_OPTIONS, the petscrc
// files, the command line and the options files these name. What it would
// drop silently (a stray argument), report with a traceback (a syntax error
// in an options file), recurse on until the stack overflows (files that
// include each other) or hang on (ranks given different options) is found
// first and refused in one line:
// - main calls PreflightArguments before SlepcInitialize. It compares the
//   ranks' command lines, reads a file on a pipe (or /dev/stdin) once into a
//   temporary regular file that PETSc then reads instead, and, with PETSc
//   started for the check alone, reads the arguments and every file on rank 0
//   with PETSc's own reader (PetscOptionsInsert) into a throw-away database;
// - RunStudyFromOptions calls CheckOptionsAgree first: every rank's database
//   is the same (a hash of all of it, compared across ranks).
#include <petscsys.h>
#include <string>
#include <vector>

namespace nltopo {

// Before PETSc starts (MPI has): false, after rank 0 printed one line, when
// the options cannot be read as given. May replace an -options_file argument
// of rank 0 by a temporary copy (a pipe's content); main removes the copies
// once PETSc has read them (RemoveSpooledOptionsFiles).
bool PreflightArguments(int argc, char **argv);
void RemoveSpooledOptionsFiles();

// The pieces, each returning the error line without "nltopo: error: " ("" if
// none); usable with PETSc started (the in-process tests).
// A word that is neither an option nor an option's value, by the rules of
// PetscOptionsInsertArgs (args: the command line without the program name)
// and of PetscOptionsInsertString (text: PETSC_OPTIONS).
std::string StrayArgument(const std::vector<std::string> &args);
std::string StrayInOptionsString(const std::string &text, const char *where);
// Collective on comm: rank 0 checks the options files named by argv,
// PETSC_OPTIONS and the petscrc files (readable, no directory, no include
// cycle, not nested deeper than 32), then reads everything with PETSc's
// reader and checks the database for -lattice_Gamma; every rank gets the line.
std::string CheckOptionsSources(MPI_Comm comm, int argc, char **argv);
// Collective on comm: whether some rank was started with other arguments than rank 0's.
std::string ArgumentsDifferAcrossRanks(MPI_Comm comm, int argc, char **argv);

// Collective: every rank's options database is the same (PETSc reads the
// command line on each rank; a launch that gives ranks different options
// would otherwise hang or compute different things).
PetscErrorCode CheckOptionsAgree(MPI_Comm comm);

} // namespace nltopo
