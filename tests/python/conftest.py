"""Real outputs of every study for the reader's tests, written once per session
by the nltopo binary ($NLTOPO; ctest sets it, else <repo>/build/nltopo) at
tiny sizes (a 5-cell lattice, short runs: a few seconds in all)."""
import os
import shlex
import subprocess
import sys
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(REPO / "python"))

# Open MPI as the suite runs it (tests/CMakeLists.txt MPI_ENV), for a run outside ctest
MPI_ENV = {"OMPI_ALLOW_RUN_AS_ROOT": "1", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1", "OMPI_MCA_rmaps_base_oversubscribe": "1",
           "OMPI_MCA_pml": "ob1", "OMPI_MCA_btl": "self,vader", "OMPI_MCA_ess_singleton_isolated": "1",
           "NLTOPO_SCHEMA_CHECK": "1"}

# The forced scenes' burst shortened (5 periods wide, centred 3 widths in) so E* is reached in 300 time units.
BURST = ["-force_tau_periods", "5", "-force_t0_taus", "3", "-sim_t_final", "300"]
WP_CONFIGS = " -sim_ts_type rk -sim_ts_rtol 1e-6 -sim_ts_atol 1e-6, -sim_ts_type symsplit -sim_ts_dt 0.1"

# name: (options file or None, command-line arguments); the output is <name>.h5
RUNS = {
    "linear": ("linear.opts", ["-lattice_cells", "5", "-linear_gamma_list", "-1:1:5"]),
    "simulate": ("simulate.opts", ["-lattice_cells", "5", "-sim_progress", "0"] + BURST),
    "simulate_stride": ("simulate.opts", ["-lattice_cells", "5", "-sim_progress", "0", "-sim_store_u_stride", "3"] + BURST),
    # -floquet and bifurcation location along the insulated branch: Hamiltonian-Hopf, Krein, branch point, resonances
    "fep": ("fep.opts", ["-cont_branch", "insulated", "-lattice_cells", "5", "-cont_energy_max", "300", "-cont_verbose", "0"]),
    # -cont_codim2: the energy maximum of mode 0 of the 1-cell lattice (N = 6) followed in -lattice_cubic (E Gamma = const)
    "codim2": (None, ["-study", "continuation", "-lattice_cells", "1", "-cont_branch", "0", "-floquet", "-cont_energy_max", "1000",
                      "-cont_omega_max", "0.9692", "-cont_verbose", "0", "-cont_codim2", "0:fold@0.9685", "-cont_codim2_parameter", "lattice_cubic",
                      "-cont_codim2_min", "0.3", "-cont_codim2_max", "0.8", "-cont_codim2_verbose", "0"]),
    # the five branches without Floquet multipliers, to low energy
    "fep_plain": ("fep.opts", ["-lattice_cells", "5", "-floquet", "0", "-cont_energy_max", "1e-2", "-cont_verbose", "0"]),
    # the matrix-free leading multipliers: stable "not decided", instability "not computed"
    "fep_mf": ("fep.opts", ["-cont_branch", "insulated", "-lattice_cells", "5", "-cont_energy_max", "1e-3", "-cont_verbose", "0",
                            "-floquet_mf", "-floquet_mf_dense_max", "0"]),
    "sweep": ("sweep_quick.opts", ["-lattice_cells", "5", "-sweep_omega_n", "3", "-sweep_energy_n", "2", "-sweep_lyapunov"] + BURST),
    "zak": ("zak.opts", ["-lattice_cells", "11", "-zak_energy_list", "0.01,0.1"] + BURST),
    "perturb": ("perturb.opts", ["-lattice_cells", "5", "-perturb_delta_list", "0,0.05", "-perturb_ensemble", "2",
                                 "-perturb_energy_list", "0.1"] + BURST),
    "stability": ("stability.opts", ["-lattice_cells", "5", "-stability_omega", "1.7320508075688772,2.5",
                                     "-stability_periods", "50", "-stability_sample_periods", "1", "-sim_progress", "0"]),
    # two sizes, the dense Floquet route, one energy window
    "floquet_scaling": (None, ["-study", "floquet_scaling", "-scaling_cells", "3,5", "-cont_energy_max", "1", "-scaling_energy_windows", "0,1",
                               "-cont_verbose", "0"]),
    # one size, one curve (the first onset of N = 22 near gamma 0.4), one check branch
    "stabilitymap": ("stabilitymap.opts", ["-smap_cells", "5", "-smap_check", "0.405", "-cont_energy_max", "0.63", "-cont_codim2_min", "0.39",
                                           "-cont_codim2_max", "0.41", "-smap_raster_p", "5", "-smap_raster_energy", "5"]),
    "workprecision": ("workprecision.opts", ["-lattice_cells", "5", "-wp_repeats", "1", "-wp_twins", "1",
                                             "-wp_configs", WP_CONFIGS] + BURST),
}

STUDY = {"linear": "linear", "simulate": "simulate", "simulate_stride": "simulate", "fep": "continuation", "codim2": "continuation",
         "fep_plain": "continuation", "fep_mf": "continuation", "sweep": "sweep", "zak": "zak", "perturb": "perturb", "stability": "stability",
         "floquet_scaling": "floquet_scaling", "stabilitymap": "stabilitymap", "workprecision": "workprecision"}


def nltopo_binary():
    b = os.environ.get("NLTOPO") or str(REPO / "build" / "nltopo")
    if not os.access(b, os.X_OK):
        pytest.exit(f"no nltopo binary at {b}: set NLTOPO=<build>/nltopo", returncode=2)
    return b


def given_options(name, output):
    """The options the run was given, as PETSc holds them (key without "-", value; "" for a flag)."""
    opts_file, args = RUNS[name]
    tokens = []
    if opts_file:
        for line in (REPO / "options" / opts_file).read_text().splitlines():
            line = line.split("#", 1)[0].strip()
            if line:
                tokens += shlex.split(line)
    tokens += args + ["-output", output]
    out, i = {}, 0
    while i < len(tokens):
        key = tokens[i][1:]
        i += 1
        value = ""
        if i < len(tokens) and not (tokens[i].startswith("-") and tokens[i][1:2].isalpha()):
            value = tokens[i]
            i += 1
        out[key] = value
    return out


@pytest.fixture(scope="session")
def outputs(tmp_path_factory):
    """{name: path} of the real outputs, written once."""
    d = tmp_path_factory.mktemp("nltopo_outputs")
    env = dict(os.environ)
    for k, v in MPI_ENV.items():
        env.setdefault(k, v)
    binary = nltopo_binary()
    paths = {}
    for name, (opts_file, args) in RUNS.items():
        path = d / f"{name}.h5"
        cmd = [binary] + (["-options_file", str(REPO / "options" / opts_file)] if opts_file else []) + args + ["-output", str(path)]
        p = subprocess.run(cmd, cwd=d, env=env, capture_output=True, text=True)
        assert p.returncode == 0 and path.exists(), f"{' '.join(cmd)} failed ({p.returncode}):\n{p.stdout[-2000:]}\n{p.stderr[-2000:]}"
        paths[name] = path
    return paths


@pytest.fixture(scope="session")
def runs(outputs):
    import nltopo
    opened = {name: nltopo.open(path) for name, path in outputs.items()}
    yield opened
    for r in opened.values():
        r.close()
