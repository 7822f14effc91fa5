#include "studies/sweep_store.hpp"
#include "io/input.hpp"
#include <cstring>
#include <dirent.h>

namespace nltopo {

const SweepRealField kSweepRealFields[7] = {{"mcr", &SweepPoint::mcr},         {"t_off", &SweepPoint::t_off},
                                            {"kcorr", &SweepPoint::kcorr},     {"nl_ratio", &SweepPoint::nl_ratio},
                                            {"amplitude", &SweepPoint::amplitude}, {"energy_final", &SweepPoint::energy_final},
                                            {"seconds", &SweepPoint::seconds}};
const SweepIntField kSweepIntFields[5] = {{"reached", &SweepPoint::reached}, {"rescalings", &SweepPoint::rescalings}, {"rhs_evals", &SweepPoint::rhs},
                                          {"steps", &SweepPoint::steps},     {"failed", &SweepPoint::failed}};

PetscInt SweepGrid::Done() const
{
  PetscInt n = 0;
  for (PetscInt d : done) n += d;
  return n;
}

void SweepGrid::Reset(const std::vector<PetscReal> &w, const std::vector<PetscReal> &e)
{
  omega = w;
  energy = e;
  pts.assign(Size(), SweepPoint());
  done.assign(Size(), 0);
}

PetscErrorCode SweepGrid::Load(const std::string &path)
{
  std::vector<PetscReal> w, e, v;
  std::vector<PetscInt> iv;
  PetscFunctionBeginUser;
  PetscCall(ReadDoubles(path, "/sweep/omega", &w));
  PetscCall(ReadDoubles(path, "/sweep/energy", &e));
  PetscCheck(w == omega && e == energy, PETSC_COMM_SELF, PETSC_ERR_USER,
             "-sweep_resume: the grid stored in %s (%zu x %zu) differs from the -sweep_* axes (%zu x %zu)", path.c_str(), e.size(), w.size(),
             energy.size(), omega.size());
  auto doubles = [&](const char *name, PetscReal SweepPoint::*field) -> PetscErrorCode {
    PetscFunctionBeginUser;
    PetscCall(ReadDoubles(path, (std::string("/sweep/") + name).c_str(), &v));
    PetscCheck(v.size() == Size(), PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "-sweep_resume: /sweep/%s in %s has the wrong size", name, path.c_str());
    for (size_t i = 0; i < v.size(); i++) pts[i].*field = v[i];
    PetscFunctionReturn(0);
  };
  auto ints = [&](const char *name, PetscInt SweepPoint::*field) -> PetscErrorCode {
    PetscFunctionBeginUser;
    PetscCall(ReadInts(path, (std::string("/sweep/") + name).c_str(), &iv));
    PetscCheck(iv.size() == Size(), PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "-sweep_resume: /sweep/%s in %s has the wrong size", name, path.c_str());
    for (size_t i = 0; i < iv.size(); i++) pts[i].*field = iv[i];
    PetscFunctionReturn(0);
  };
  for (const auto &f : kSweepRealFields) PetscCall(doubles(f.name, f.field));
  for (const auto &f : kSweepIntFields) PetscCall(ints(f.name, f.field));
  PetscCall(ReadInts(path, "/sweep/done", &done));
  PetscCheck(done.size() == Size(), PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "-sweep_resume: /sweep/done in %s has the wrong size", path.c_str());
  PetscFunctionReturn(0);
}

std::vector<std::string> JournalFiles(const std::string &path)
{
  const size_t slash = path.find_last_of('/');
  const std::string dir = slash == std::string::npos ? "." : path.substr(0, slash + 1);
  const std::string prefix = (slash == std::string::npos ? path : path.substr(slash + 1)) + ".journal.";
  std::vector<std::string> files;
  if (DIR *d = opendir(dir.c_str())) {
    while (dirent *e = readdir(d))
      if (!std::strncmp(e->d_name, prefix.c_str(), prefix.size())) files.push_back((slash == std::string::npos ? "" : dir) + e->d_name);
    closedir(d);
  }
  return files;
}

// Line format: index mcr t_off kcorr nl_ratio amplitude energy_final seconds reached rescalings rhs steps failed
PetscErrorCode SweepGrid::MergeJournals(const std::string &path, PetscInt *lines)
{
  PetscFunctionBeginUser;
  *lines = 0;
  for (const std::string &name : JournalFiles(path)) {
    FILE *f = std::fopen(name.c_str(), "r");
    if (!f) continue;
    char buf[1024];
    while (std::fgets(buf, sizeof(buf), f)) {
      if (!std::strchr(buf, '\n')) break; // a line cut by a kill: ignored, the point is recomputed
      long idx, reached, resc, rhs, steps, failed;
      SweepPoint p;
      double v[7];
      if (std::sscanf(buf, "%ld %la %la %la %la %la %la %la %ld %ld %ld %ld %ld", &idx, &v[0], &v[1], &v[2], &v[3], &v[4], &v[5], &v[6], &reached, &resc, &rhs,
                      &steps, &failed) != 13 || idx < 0 || (size_t)idx >= Size())
        continue;
      p.mcr = v[0], p.t_off = v[1], p.kcorr = v[2], p.nl_ratio = v[3], p.amplitude = v[4], p.energy_final = v[5], p.seconds = v[6];
      p.reached = reached, p.rescalings = resc, p.rhs = rhs, p.steps = steps, p.failed = failed;
      pts[idx] = p;
      done[idx] = 1;
      (*lines)++;
    }
    std::fclose(f);
  }
  PetscFunctionReturn(0);
}

PetscErrorCode Journal::Open(const std::string &path, PetscMPIInt rank)
{
  PetscFunctionBeginUser;
  const std::string name = path + ".journal." + std::to_string(rank);
  f_ = std::fopen(name.c_str(), "a");
  PetscCheck(f_, PETSC_COMM_SELF, PETSC_ERR_FILE_OPEN, "cannot write the sweep journal %s next to -output", name.c_str());
  PetscFunctionReturn(0);
}

PetscErrorCode Journal::Append(size_t index, const SweepPoint &p)
{
  PetscFunctionBeginUser;
  std::fprintf(f_, "%zu %a %a %a %a %a %a %a %ld %ld %ld %ld %ld\n", index, (double)p.mcr, (double)p.t_off, (double)p.kcorr, (double)p.nl_ratio, (double)p.amplitude,
               (double)p.energy_final, (double)p.seconds, (long)p.reached, (long)p.rescalings, (long)p.rhs, (long)p.steps, (long)p.failed);
  PetscCheck(std::fflush(f_) == 0, PETSC_COMM_SELF, PETSC_ERR_FILE_WRITE, "cannot write the sweep journal (disk full?)");
  PetscFunctionReturn(0);
}

void Journal::Close()
{
  if (f_) std::fclose(f_);
  f_ = nullptr;
}

} // namespace nltopo
