#pragma once
// What makes two runs "the same computation": the options of the writing run
// are stored in every output (root attribute `options`, PetscOptionsGetAll);
// a resume and an overwrite compare them with this run's (docs/errors.md
// "Resume rules").
//
// The rule: only options with a prefix that sets the physics or the numerics
// are compared: the prefixes every study registers with its contract
// (studies/registry.hpp: its own, e.g. -wp_, and its components', e.g.
// -lattice_, -force_, -sim_, -nnm_, -cont_, -floquet, -linear_); within those,
//  - bookkeeping is never compared: -cont_resume, -sweep_resume,
//    -cont_checkpoint_seconds, -sweep_checkpoint, -sweep_progress, -sweep_shard,
//    -sim_progress, -cont_verbose, and every option whose name contains
//    "monitor", "_view" or "converged_reason";
//  - the extent of a run (how far it goes, what it stores) is compared for an
//    overwrite but not for a resume, which may extend it: -cont_energy_max,
//    -cont_max_points, -cont_omega_max, -cont_mcr_min, -cont_branch,
//    -sim_store_u, -sim_store_u_stride, -sim_sample_dt;
//  - everything else must be equal. Values are equal as numbers when both
//    read as numbers (1e-2 = 0.01), as booleans for true/false/yes/no/on/off
//    (a bare flag is true), else as strings (lists element by element).
//    An option given on one side only is a difference, except where nltopo
//    itself sets the default into the database (-nnm_start_pc_svd_zero_sing 1e-9).
// A resume without -floquet ignores the -floquet* options: the multipliers
// post-process each orbit and never feed back into the branch.
#include <petscsys.h>
#include <functional>
#include <string>
#include <vector>

namespace nltopo {

enum class OptionRule { Resume, Overwrite };

// What a run was given (root attribute options: PetscOptionsGetAll's text)
// and the effective values it used, defaults included (root attribute
// effective_options, core/effective_options.hpp; "" in files written before
// it existed).
struct RunRecord {
  std::string given, effective;
};
// This run's record so far.
RunRecord ThisRunRecord();

// The first difference (in option-name order) between the options a file was
// written with and this run's, as "with -x 2 (now 1)", "with -x 2 (now not
// given)" or "without -x (now 1)"; empty when they agree under the rule. An
// option given on neither side compares by its effective values where both
// records have one: "with -nnm_ts_type rk, the default then (now symsplit)".
std::string FirstOptionDifference(const RunRecord &file, const RunRecord &run, OptionRule rule);

// -sweep_resume / -cont_resume: the file must be an nltopo output of `study`
// whose options agree with this run's under OptionRule::Resume; otherwise one
// line, e.g. "-cont_resume x.h5 was written with -lattice_cubic 2 (now 1)".
// what names the option ("-cont_resume"). A missing file passes (the caller
// reports it). Collective (rank 0 reads).
PetscErrorCode CheckResumeOptions(MPI_Comm comm, const std::string &file, const char *study, const char *what);

// A fresh run never silently replaces another run's output: if path is an
// nltopo output (root attribute study) of another study, or of options that
// differ under OptionRule::Overwrite, it is an error unless overwrite is set.
// Collective (rank 0 reads).
PetscErrorCode CheckOverwrite(MPI_Comm comm, const std::string &path, const char *study, PetscBool overwrite);

// Whether a and b name the same file (same inode when both exist, else the same string).
bool SameFile(const std::string &a, const std::string &b);

} // namespace nltopo
