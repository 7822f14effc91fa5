#pragma once
// The stability verdict of one orbit, the same vocabulary for every Floquet
// route (docs/long-lattices.md "Verdicts"):
//   stable                         the dense route: every multiplier within 1 + -floquet_tol
//   unstable-localized(mu, class)  a multiplier beyond 1 + delta whose eigenvector carries
//                                  weight at the interface (Localisation class B-E or E-E)
//   unstable-extended(mu, class)   the same with an extended eigenvector (class B-B)
//   stable-to(delta)               nothing beyond 1 + delta, delta what the route resolved
//   unresolved(reason, bound)      otherwise (never a silent NaN)
// An unstable-* verdict is confirmed after the fact: the eigenvector is
// integrated k periods by the tangent flow and |M^k v| must match |mu|^k |v|
// (ConfirmGrowth); a failed confirmation makes the orbit unresolved.
#include "orbits/flow.hpp"
#include "stability/floquet.hpp"
#include <limits>
#include <string>

namespace nltopo {

// The integer codes written as `verdict` (io/schema.hpp codes::kVerdict).
enum class Verdict : PetscInt { Stable = 0, UnstableLocalized = 1, UnstableExtended = 2, StableTo = 3, Unresolved = 4 };
const char *VerdictName(Verdict v); // "stable", "unstable-localized", ...

struct OrbitVerdict {
  Verdict code = Verdict::Unresolved;
  // stable: -floquet_tol; stable-to: delta; unstable-*: |mu| - 1; unresolved:
  // the largest |mu| - 1 the route could not exclude (+inf when it has no bound).
  PetscReal bound = std::numeric_limits<PetscReal>::infinity();
  PetscInt cls = 0;               // unstable-*: the eigenvector's class (Localisation: 1 B-B, 2 B-E, 3 E-E); 0 otherwise
  PetscReal mu_re = 0, mu_im = 0; // unstable-*: the multiplier (|mu| > 1 member, upper half plane)
  PetscReal efold = std::numeric_limits<PetscReal>::infinity(); // unstable-*: e-folding time of the growth in periods, 1 / ln|mu|
  PetscReal confirmed_rate = 0;     // unstable-*: ln(|M^k v| / |v|) / k measured by ConfirmGrowth
  bool whole_lattice_vector = false; // the localized route: its eigenvector is the whole finite lattice's (the exterior route), not the damped window's
  std::string reason;               // one line: how the route reached the verdict
};

// Whether an eigenvector with edge share w carries weight at the interface:
// its class (Localisation) is B-E or E-E, i.e. w >= 1 - -floquet_edge_weight.
inline bool Localised(const FloquetOptions &o, PetscReal w) { return Localisation(o, w) >= 2; }

// stable (the dense route) at -floquet_tol tol; stable-to(delta); unresolved(reason, bound).
OrbitVerdict StableVerdict(PetscReal tol, const std::string &reason);
OrbitVerdict StableToVerdict(PetscReal delta, const std::string &reason);
OrbitVerdict UnresolvedVerdict(PetscReal bound, const std::string &reason);
// One line: "unstable-localized(|mu| = 1.0042360, B-E, e-folding 237 periods)", "stable-to(1.0e-03)", ...
std::string VerdictLabel(const OrbitVerdict &v);

// An unstable verdict for multiplier mu with eigenvector class cls, before confirmation.
OrbitVerdict UnstableVerdict(std::complex<PetscReal> mu, PetscInt cls, const std::string &reason);

// Confirms an unstable verdict: integrates v = vr + i vi (state layout; vi
// may be null for a real multiplier) k periods with the tangent flow at the
// orbit (z0, T, beta) and compares ln(|M^k v| / |v|) / k with ln|mu|. A
// failure turns the verdict into unresolved, naming both rates. k and the
// tolerance: -floquet_confirm_periods, -floquet_confirm_rtol. Collective.
// window (optional): natural sites window[0]..window[1]; the norm is then
// taken on their (u, v) entries only (a localized mode that radiates into the
// band: the window holds the mode, the rest the outgoing wave).
PetscErrorCode ConfirmGrowth(PeriodicFlow &flow, Vec z0, PetscReal T, PetscReal beta, Vec vr, Vec vi, const FloquetOptions &o, OrbitVerdict *v,
                             const PetscInt *window = nullptr);

// The dense route's verdict (all 2N multipliers known): stable within
// -floquet_tol, else unstable-* for the most unstable multiplier mu with its
// eigenvector's class cls (< 1: no eigenvector, unresolved), confirmed by
// ConfirmGrowth on its eigenvector (vr, vi). Collective.
PetscErrorCode DenseVerdict(PeriodicFlow &flow, Vec z0, PetscReal T, PetscReal beta, const FloquetOptions &o, bool stable, PetscReal max_modulus,
                            std::complex<PetscReal> mu, PetscInt cls, Vec vr, Vec vi, OrbitVerdict *v);

} // namespace nltopo
