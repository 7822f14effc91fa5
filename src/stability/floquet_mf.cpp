#include "stability/floquet_mf.hpp"
#include "core/log.hpp"
#include <algorithm>
#include <cmath>
#include <numeric>
#include <slepceps.h>

namespace nltopo {

static PetscErrorCode ShellMult(Mat M, Vec x, Vec y)
{
  MonodromyShell *s;
  PetscFunctionBeginUser;
  PetscCall(MatShellGetContext(M, &s));
  PetscCall(s->Mult(x, y));
  PetscFunctionReturn(0);
}

PetscErrorCode MonodromyShell::Create(PeriodicFlow &flow, Vec z0, PetscReal T, PetscReal beta)
{
  PetscInt n, nloc;
  PetscFunctionBeginUser;
  flow_ = &flow, z0_ = z0, T_ = T, beta_ = beta;
  PetscCall(VecGetSize(z0, &n));
  PetscCall(VecGetLocalSize(z0, &nloc));
  PetscCall(VecDuplicate(z0, zT_.out()));
  PetscCall(MatCreateShell(PetscObjectComm((PetscObject)z0), nloc, nloc, n, n, this, M_.out()));
  PetscCall(MatShellSetOperation(M_, MATOP_MULT, (void (*)(void))ShellMult));
  PetscFunctionReturn(0);
}

PetscErrorCode MonodromyShell::Mult(Vec x, Vec y)
{
  PetscFunctionBeginUser;
  PetscCall(flow_->IntegrateWithTangent(z0_, T_, beta_, x, 0.0, zT_, y));
  products_++;
  PetscFunctionReturn(0);
}

PetscErrorCode FloquetLeading(PeriodicFlow &flow, Vec z0, PetscReal T, PetscReal beta, PetscInt nev, LeadingMultipliers *r)
{
  MonodromyShell shell;
  OwnedEPS eps;
  PetscInt nconv;
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(Log().floquet, 0, 0, 0, 0));
  PetscCall(shell.Create(flow, z0, T, beta));
  PetscCall(EPSCreate(PetscObjectComm((PetscObject)z0), eps.out()));
  PetscCall(EPSSetOptionsPrefix(eps, "floquet_mf_"));
  PetscCall(EPSSetOperators(eps, shell.Get(), NULL));
  PetscCall(EPSSetProblemType(eps, EPS_NHEP));
  PetscCall(EPSSetType(eps, EPSKRYLOVSCHUR));
  PetscCall(EPSSetWhichEigenpairs(eps, EPS_LARGEST_MAGNITUDE));
  PetscCall(EPSSetDimensions(eps, nev, PETSC_DEFAULT, PETSC_DEFAULT));
  PetscCall(EPSSetTolerances(eps, 1e-10, PETSC_DEFAULT));
  PetscCall(EPSSetFromOptions(eps));
  PetscCall(EPSSolve(eps));
  PetscCall(EPSGetConverged(eps, &nconv));
  PetscCheck(nconv >= nev, PetscObjectComm((PetscObject)z0), PETSC_ERR_NOT_CONVERGED,
             "matrix-free Floquet: %" PetscInt_FMT " of %" PetscInt_FMT " multipliers converged (-floquet_mf_eps_max_it, -floquet_mf_eps_ncv)", nconv, nev);
  r->re.resize(nev), r->im.resize(nev);
  for (PetscInt i = 0; i < nev; i++) PetscCall(EPSGetEigenvalue(eps, i, &r->re[i], &r->im[i]));
  r->products = shell.Products();
  PetscCall(PetscLogEventEnd(Log().floquet, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

} // namespace nltopo
