#!/usr/bin/python3
"""Seeded option fuzzer for nltopo (docs/testing.md, docs/errors.md).

Every case runs one study on a small base scene (about a second of work) with
1-3 of nltopo's own options set to a random value drawn from the option's type
and range, an extreme (0, -1, 2^31, 1e300, 1e-300, ...), a wrong type ("abc",
"1.5" for an integer, "", ",,"), or a non-finite number, at 1 or 2 ranks
(alternating), under a timeout. A case passes when the run either

  * exits 0 with a complete output (HDF5 root attribute complete = 1), no
    temporary <out>.tmp.* and no sweep journal left, or
  * exits non-zero with exactly one non-empty line on stderr (both ranks),
    "nltopo: error: ...", and no output, temporary or journal left;
    when the case has a single mutation and it is a non-finite or unparsable
    value, the line must name that option;

and never hangs, dies of a signal, aborts, calls MPI_Abort or prints a PETSc
traceback. Unparsable and non-finite values must never be accepted.

About 40 % of the cases also get an input family (input_family): the option
names in mixed case, the mutations in an options file (plain, nested, on a
pipe, or mutated: a byte-order mark, a word after a value, two options on a
line, a missing nested file, files that include each other), a stray word on
the command line or in PETSC_OPTIONS, or only the stray words' legitimate
look-alikes; a mutated file or a stray word must be refused with a line
naming it, a look-alike never called stray, and no copy of a piped file left.

Run policy (tests/scenes/fuzz.sh): CI runs 30 cases with a fixed seed and 30
with a fresh random seed it prints; the opt-in long run (ctest -L long) 500.

A second family, concurrent runs on one output (--concurrent N cases, seeded
by the same --seed; rerun one with --only-concurrent CASE), starts two runs of
different scenes into one -output a random moment apart: at most one exits 0,
with its own complete result, the other stops with one line, and nothing but
the output is left (run_concurrent_case).

The option table below is nltopo's own options with a type and a range that
keeps an accepted run small; the fuzzer checks it against the option tables
the binary declares (nltopo -option_tables json: names, types, enum choices,
ranges) and against the -help listing of every study (which options each
study reads), so an option added to nltopo without an entry here fails the
test (add it with its type and range).

Usage: fuzz.py NLTOPO WORKDIR [--cases N] [--seed S] [--jobs J] [--only CASE]
                               [--timeout SEC] [--mpiexec MPIEXEC] [--resume-cases N]

Then --resume-cases cases (default 16) of corrupted resume states
(corrupted_resume_cases: NaN and inf in the stored arrays of a continuation
checkpoint, a sweep and a sweep journal).
A failure prints its case number and the full command; "--only CASE" (same
--seed) reruns just that case.
"""
import argparse
import glob
import json
import os
import random
import re
import shlex
import shutil
import signal
import subprocess
import sys
import threading
import time
from concurrent.futures import ThreadPoolExecutor

STUDIES = ["linear", "simulate", "continuation", "sweep", "zak", "perturb", "stability", "workprecision"]

# A forced burst of a few periods on a tiny lattice: every forced study stays ~1 s.
FAST_BURST = ["-sim_t_final", "50", "-force_tau_periods", "2", "-force_t0_taus", "1"]
BASE = {
    "linear": ["-lattice_cells", "5", "-linear_nq", "8"],
    "simulate": ["-lattice_cells", "5", "-force_site", "12", "-sim_progress", "0"] + FAST_BURST,
    "continuation": ["-lattice_cells", "5", "-cont_branch", "insulated", "-cont_energy_max", "1e-3", "-cont_max_points", "3",
                     "-cont_verbose", "0", "-nnm_steps_per_period", "32"],
    "sweep": ["-lattice_cells", "5", "-force_site", "12", "-sweep_omega_n", "2", "-sweep_energy_n", "1", "-sweep_energy_min", "0.1",
              "-sweep_energy_max", "0.1", "-sweep_progress", "0", "-kcorr_record", "50", "-kcorr_nc", "4"] + FAST_BURST,
    "zak": ["-lattice_cells", "5", "-zak_energy_list", "0.01", "-sim_t_final", "100", "-force_tau_periods", "2", "-force_t0_taus", "1"],
    "perturb": ["-lattice_cells", "5", "-perturb_delta_list", "0,0.05", "-perturb_ensemble", "2", "-perturb_energy_list", "1e-3",
                "-cont_verbose", "0", "-nnm_steps_per_period", "32"] + FAST_BURST,
    "stability": ["-lattice_cells", "5", "-stability_omega", "1.75", "-stability_periods", "20", "-stability_sample_periods", "2",
                  "-cont_verbose", "0", "-nnm_steps_per_period", "32"],
    "workprecision": ["-lattice_cells", "5", "-force_site", "12", "-wp_configs", " -sim_ts_type symsplit -sim_ts_dt 0.2", "-wp_repeats", "1",
                      "-wp_twins", "1", "-wp_reference_tol", "1e-8", "-wp_reference_tol_min", "1e-9"] + FAST_BURST,
}

# name: (type, lo, hi, extra) -- lo..hi is the range random in-range draws come
# from: one that keeps an accepted run small, not the option's allowed range.
# type: real, int, bool, enum (extra: choices), reals / strings (lists; extra:
# choices for strings), path.
T = {
    "lattice_k": ("real", 0.5, 2.0), "lattice_gamma": ("real", -0.6, 0.6), "lattice_gamma0": ("real", 0.0, 2.0),
    "lattice_cubic": ("real", -1.0, 1.0), "lattice_cells": ("int", 2, 10),
    "lattice_layout": ("enum", 0, 0, ["interface", "left", "right"]),
    "lattice_perturbation": ("enum", 0, 0, ["none", "chiral", "achiral"]),
    "lattice_delta": ("real", 0.0, 0.3), "lattice_seed": ("int", 0, 1000), "lattice_damping": ("real", 0.0, 0.2),
    "linear_dense_max": ("int", 0, 60), "linear_nev": ("int", 1, 8), "linear_target_offset": ("real", 1e-8, 0.05),
    "linear_nq": ("int", 4, 40), "linear_gamma_list": ("enum", 0, 0, ["-1:1:5", "-0.5:0.5:3", "0:1:2", "-1:0:4"]),
    "force_profile": ("enum", 0, 0, ["site", "mode", "none", "exponential"]),
    "force_omega": ("real", 0.5, 3.0), "force_energy": ("real", 1e-3, 1.0), "force_amplitude": ("real", 0.0, 2.0),
    "force_amplitude_safety": ("real", 0.5, 4.0), "force_amplitude_retries": ("int", 0, 8),
    "force_tau_periods": ("real", 1.0, 4.0), "force_t0_taus": ("real", 0.0, 2.0), "force_site": ("int", 1, 22),
    "force_mode_index": ("int", 0, 21),
    "sim_t_final": ("real", 10.0, 100.0), "sim_sample_dt": ("real", 0.0, 5.0), "sim_progress": ("real", 0.0, 5.0),
    "sim_store_u": ("bool",), "sim_store_u_stride": ("int", 1, 5),
    "sweep_omega_min": ("real", 0.8, 2.6), "sweep_omega_max": ("real", 0.8, 2.6), "sweep_omega_n": ("int", 1, 3),
    "sweep_omega_spacing": ("enum", 0, 0, ["linear", "log"]), "sweep_omega_list": ("reals", 0.8, 2.6),
    "sweep_energy_min": ("real", 1e-3, 1.0), "sweep_energy_max": ("real", 1e-3, 1.0), "sweep_energy_n": ("int", 1, 2),
    "sweep_energy_spacing": ("enum", 0, 0, ["linear", "log"]), "sweep_energy_list": ("reals", 1e-3, 1.0),
    "sweep_resume": ("bool",), "sweep_kcorr": ("bool",), "sweep_checkpoint": ("real", 0.1, 10.0), "sweep_progress": ("real", 0.0, 5.0),
    "sweep_shard": ("enum", 0, 0, ["0/1", "0/2", "1/2"]), "merge_inputs": ("strings", 0, 0, ["no_such_file.h5", "no_such_file.h5,other.h5"]),
    "kcorr_nc": ("int", 1, 16), "kcorr_seed": ("int", 0, 1000), "kcorr_sample_dt": ("real", 0.0, 2.0),
    "kcorr_rms_fraction": ("real", 0.0, 1.0), "kcorr_record": ("real", 10.0, 100.0), "kcorr_lags": ("int", 3, 20),
    "kcorr_site_stride": ("int", 1, 5),
    "zak_energy_min": ("real", 1e-3, 0.1), "zak_energy_max": ("real", 1e-3, 0.1), "zak_energy_n": ("int", 1, 2),
    "zak_energy_spacing": ("enum", 0, 0, ["linear", "log"]), "zak_energy_list": ("reals", 1e-3, 0.1),
    "zak_windows": ("int", 1, 4), "zak_samples_per_period": ("int", 4, 32), "zak_theta_tol": ("real", 0.1, 3.0),
    "perturb_delta_list": ("reals", 0.0, 0.3), "perturb_kinds": ("strings", 0, 0, ["chiral", "achiral"]),
    "perturb_ensemble": ("int", 1, 3), "perturb_seed": ("int", 0, 1000),
    "perturb_energy_min": ("real", 1e-4, 1e-3), "perturb_energy_max": ("real", 1e-4, 1e-3), "perturb_energy_n": ("int", 1, 2),
    "perturb_energy_spacing": ("enum", 0, 0, ["linear", "log"]), "perturb_energy_list": ("reals", 1e-4, 1e-3),
    "perturb_fep": ("path",),
    "stability_omega": ("reals", 1.733, 1.8), "stability_periods": ("int", 2, 40), "stability_sample_periods": ("int", 1, 5),
    "stability_perturbation": ("real", 0.0, 0.1), "stability_seed": ("int", 0, 1000), "stability_corr_min": ("real", 0.1, 1.0),
    "stability_growth_periods": ("int", 0, 10), "stability_growth_perturbation": ("real", 1e-10, 1e-6),
    "cont_energy_min": ("real", 1e-6, 1e-4), "cont_energy_max": ("real", 1e-4, 1e-2), "cont_max_points": ("int", 1, 5),
    "cont_omega_max": ("real", 0.0, 2.5), "cont_mcr_min": ("real", 0.0, 0.5), "cont_max_change": ("real", 0.01, 0.5),
    "cont_ds_min": ("real", 1e-12, 1e-6), "cont_newton_target": ("int", 1, 8), "cont_interaction_corr": ("real", 0.0, 1.0),
    "cont_verbose": ("bool",), "cont_progress": ("real", 0.0, 5.0), "cont_checkpoint_seconds": ("real", 0.0, 5.0), "cont_resume": ("path",),
    "cont_bifurcations": ("bool",), "cont_bif_tol": ("real", 1e-9, 1e-4), "cont_bif_max_probes": ("int", 1, 20),
    "cont_bif_angle_tol": ("real", 0.01, 0.5), "cont_bif_bulk": ("bool",),
    "cont_bif_passes": ("bool",), "cont_bif_resonance_order": ("int", 0, 5),
    "cont_switch": ("enum", 0, 0, ["insulated:0", "insulated:1", "insulated", "optical_top:x"]), "cont_switch_step": ("real", 1e-3, 0.1),
    "cont_codim2": ("enum", 0, 0, ["insulated:fold@1.9", "insulated:1@2", "insulated:pd@2", "insulated:bp@2", "insulated:4@2", "insulated", "optical_top:fold@x"]),
    "cont_codim2_parameter": ("enum", 0, 0, ["lattice_gamma", "lattice_k", "lattice_cubic"]),
    "cont_codim2_min": ("real", -1.0, 0.4), "cont_codim2_max": ("real", 0.4, 2.0), "cont_codim2_step": ("real", 1e-3, 0.1),
    "cont_codim2_step_min": ("real", 1e-8, 1e-4), "cont_codim2_step_max": ("real", 0.05, 0.5), "cont_codim2_max_points": ("int", 1, 5),
    "cont_codim2_tol": ("real", 1e-12, 1e-6), "cont_codim2_test_tol": ("real", 1e-9, 1e-4), "cont_codim2_verbose": ("bool",),
    "cont_codim2_energy_min": ("real", 0.0, 0.5), "cont_codim2_energy_max": ("real", 1.0, 100.0),
    "smap_cells": ("reals", 1, 5), "smap_branch": ("enum", 0, 0, ["insulated", "interface", "mode0", "nope"]),
    "smap_kinds": ("reals", 1, 5), "smap_classes": ("reals", 1, 3), "smap_check": ("reals", 0.1, 0.8), "smap_raster_p": ("int", 2, 50), "smap_raster_energy": ("int", 2, 50),
    "smap_energy_min": ("real", 1e-3, 1.0), "smap_max_curves": ("int", 1, 5), "smap_same_curve_rtol": ("real", 1e-6, 0.1),
    "smap_seed_checks": ("bool",), "smap_group_size": ("int", 1, 3),
    "cont_branch": ("strings", 0, 0, ["insulated", "interface", "acoustic_top", "optical_bottom", "optical_top", "mode3", "7"]),
    "nnm_steps_per_period": ("int", 8, 64), "nnm_monodromy": ("enum", 0, 0, ["variational", "tsforward"]),
    "nnm_jacobian": ("enum", 0, 0, ["dense", "mf"]), "nnm_start_dense_max": ("int", 0, 100),
    "nnm_mf_pc": ("enum", 0, 0, ["none", "linear", "averaged", "parametric"]), "nnm_mf_pc_parametric_weight": ("real", 0.1, 1.0),
    "nnm_orbit_rtol": ("real", 0.0, 1e-3),
    "floquet": ("bool",), "floquet_mf": ("bool",), "floquet_tol": ("real", 1e-9, 1e-3), "floquet_krein_tol": ("real", 1e-9, 1e-3),
    "floquet_edge_sites": ("int", 0, 10), "floquet_edge_weight": ("real", 0.55, 0.95), "floquet_mf_nev": ("int", 1, 4),
    "floquet_mf_which": ("enum", 0, 0, ["largest", "critical", "localized"]), "floquet_mf_circle_tol": ("real", 1e-12, 1e-6),
    "floquet_confirm_periods": ("int", 1, 5), "floquet_confirm_rtol": ("real", 0.01, 0.5),
    "floquet_loc_window": ("int", 1, 10), "floquet_loc_ramp": ("int", 1, 10), "floquet_loc_pad": ("int", -1, 3),
    "floquet_loc_damping": ("real", 0.1, 2.0), "floquet_loc_resolve": ("bool",), "floquet_loc_check": ("bool",),
    "floquet_loc_exterior": ("bool",), "floquet_loc_exterior_cells": ("int", 4, 30), "floquet_loc_exterior_tol": ("real", 1e-14, 1e-8),
    "floquet_loc_exterior_arc": ("real", 0.0, 0.5),
    "floquet_mf_deflate": ("bool",), "floquet_mf_dense_max": ("int", 0, 4096),
    "sim_dt_quartic_energy": ("real", 0.0, 10.0),
    "sweep_mcr_tol": ("real", 0.0, 0.1), "sweep_mcr_levels": ("int", 0, 2), "sweep_mcr_twins": ("int", 1, 3),
    "sweep_mcr_twin_eps": ("real", 1e-12, 1e-6), "sweep_mcr_dt_phase": ("real", 0.0, 1.0), "sweep_mcr_dt_energy": ("real", 0.0, 100.0),
    "sweep_group_size": ("int", 1, 2), "sweep_lyapunov": ("bool",), "sweep_lyapunov_renorm": ("real", 1.0, 50.0), "sweep_lyapunov_efolds": ("real", 1.0, 50.0),
    "sweep_refine_from": ("path",), "sweep_refine_mcr": ("real", 1e-3, 0.5), "sweep_refine_kcorr": ("real", 0.01, 1.0),
    "sweep_refine_ratio": ("real", 0.1, 5.0), "sweep_refine_max_points": ("int", 0, 20),
    "wp_configs": ("strings", 0, 0, [" -sim_ts_type symsplit -sim_ts_dt 0.2", " -sim_ts_type rk -sim_ts_rtol 1e-6 -sim_ts_atol 1e-6",
                                      " -sim_ts_type rkn -sim_ts_rtol 1e-6 -sim_ts_atol 1e-6"]),
    "wp_reference": ("strings", 0, 0, [" -sim_ts_type rkn -sim_ts_rkn_scheme dep1210", " -sim_ts_type rkn -sim_ts_rkn_scheme dep86"]),
    "wp_scene": ("enum", 0, 0, ["simulate", "shooting"]),
    "wp_reference_tol": ("real", 1e-9, 1e-7), "wp_reference_tol_min": ("real", 1e-10, 1e-9), "wp_reference_dt_max": ("real", 0.05, 1.0),
    "wp_reference_agreement": ("real", 1e-9, 1e-3), "wp_repeats": ("int", 1, 2), "wp_twins": ("int", 1, 2), "wp_twin_eps": ("real", 1e-12, 1e-6), "wp_target": ("real", 0.0, 1e-3),
}
NOT_FUZZED = {"study", "output"}  # the scene itself
RAW = {"wp_configs"}  # read outside the option tables (longer than a string row holds: src/studies/workprecision.cpp)

OWN = re.compile(r"^(lattice_|force_|sim_|sweep_|kcorr_|zak_|perturb_|stability_|cont_|nnm_|floquet|linear_|wp_)")
SOLVER = re.compile(r"^(sim_|nnm_start_|nnm_|linear_|floquet_mf_|floquet_)(ts|snes|ksp|pc|eps|st|bv|ds|rg|fn|mat|dm|tao|sf)_")

EXTREME_REAL = ["0", "-1", "-0.5", "1e300", "-1e300", "1e-300", "2147483648", "1e20", "4.9e-324", "-1e-300"]
EXTREME_INT = ["0", "-1", "-2147483648", "2147483647", "2147483648", "99999999999", "1000000000", "-7"]
GARBAGE_REAL = ["abc", "1.2.3", "1e", "--1", "0x1p", "1,5", "one", "1e5x"]
GARBAGE_INT = ["abc", "1.5", "1e3", "0x10", "2.0", "7abc", "one"]
NONFINITE = ["nan", "inf", "-inf", "NaN", "Infinity", "1e999"]


def fmt(x):
    return repr(float(x)) if isinstance(x, float) else str(x)


def draw_in_range(rng, typ):
    kind = typ[0]
    if kind == "real":
        lo, hi = typ[1], typ[2]
        if lo > 0 and hi / lo > 100 and rng.random() < 0.7:  # log-uniform over decades
            return "%.6g" % (lo * (hi / lo) ** rng.random())
        return "%.6g" % rng.uniform(lo, hi)
    if kind == "int":
        return str(rng.randint(typ[1], typ[2]))
    if kind == "bool":
        return rng.choice(["0", "1", "true", "false", "yes", "no"])
    if kind == "enum":
        return rng.choice(typ[3])
    if kind == "reals":
        return ",".join("%.6g" % rng.uniform(typ[1], typ[2]) for _ in range(rng.randint(1, 3)))
    if kind == "strings":
        return ",".join(rng.sample(typ[3], rng.randint(1, min(2, len(typ[3])))))
    if kind == "path":
        return "no_such_file.h5"
    raise ValueError(kind)


def mutate(rng, name):
    """One option setting: (args, class). class says what the contract demands."""
    typ = T[name]
    kind = typ[0]
    r = rng.random()
    opt = "-" + name
    if r < 0.45:
        return [opt, draw_in_range(rng, typ)], "in_range"
    if r < 0.65:  # extremes
        if kind == "real":
            return [opt, rng.choice(EXTREME_REAL)], "extreme"
        if kind == "int":
            return [opt, rng.choice(EXTREME_INT)], "extreme"
        if kind == "reals":
            return [opt, rng.choice(["0", "-1", "1e300", "1e-300", "0,1", "-1,1", ",".join(["1"] * 70), "1e300,1"])], "extreme"
        if kind == "strings":
            return [opt, rng.choice(["insulated,insulated", ",".join(["chiral"] * 40), "mode999", "-1", "mode-1"])], "extreme"
        if kind == "bool":
            return [opt], "in_range"  # a bare flag means true
        if kind == "path":
            return [opt, rng.choice(["", "/", "/dev/null", "no/such/dir/f.h5"])], "extreme"
        return [opt, rng.choice(typ[3]).upper()], "extreme"
    if r < 0.85:  # wrong type
        if kind == "real":
            return [opt, rng.choice(GARBAGE_REAL)], "garbage"
        if kind == "int":
            return [opt, rng.choice(GARBAGE_INT)], "garbage"
        if kind == "reals":
            return [opt, rng.choice(["abc", "1,abc", "1;2", "1 2"])], "garbage"
        if kind == "bool":
            return [opt, rng.choice(["maybe", "2", "-1", "abc"])], "garbage"
        if kind in ("enum", "strings"):
            return [opt, rng.choice(["nope", "1.5", "abc"])], "garbage"
        return [opt, "abc"], "extreme"
    if r < 0.93:  # empty: an empty argument, a bare option, an empty list
        choice = rng.choice(["empty", "bare", "commas"])
        if choice == "empty":
            return [opt, ""], "empty"
        if choice == "bare":
            return [opt], "empty"
        return [opt, rng.choice([",,", ",", ", ,"])], "empty"
    if kind in ("real", "int", "reals"):
        v = rng.choice(NONFINITE)
        if kind == "reals" and rng.random() < 0.5:
            v = "1," + v
        return [opt, v], "nonfinite"
    return [opt, draw_in_range(rng, typ)], "in_range"


def study_options(nltopo):
    """nltopo's own options of every study, from its -help listing."""
    out = {}
    for s in STUDIES:
        p = subprocess.run([nltopo, "-study", s, "-help"], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, timeout=120)
        text = p.stdout.decode(errors="replace")
        names = set()
        for line in text.splitlines():
            m = re.match(r"^  -([a-z][a-z0-9_]*)", line)
            if m and OWN.match(m.group(1)) and not SOLVER.match(m.group(1)):
                names.add(m.group(1))
        if p.returncode != 0 or not names:
            raise SystemExit("fuzz: %s -study %s -help failed (exit %d):\n%s" % (nltopo, s, p.returncode, text[-2000:]))
        out[s] = sorted(names)
    return out


# The fuzz table's kind for each type of nltopo's option tables (nltopo -option_tables json).
KINDS = {"real": {"real"}, "int": {"int"}, "bool": {"bool"}, "enum": {"enum"}, "real list": {"reals"},
         "string": {"path", "enum", "strings"}, "string list": {"strings", "enum"}}


def check_table(nltopo):
    """T against the options nltopo declares: the same names, kinds that fit the declared types, the
    declared choices of every enum, and in-range draws inside each declared range. Returns problems."""
    p = subprocess.run([nltopo, "-option_tables", "json"], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, timeout=120)
    if p.returncode != 0:
        return ["%s -option_tables json failed (exit %d): %s" % (nltopo, p.returncode, p.stdout.decode(errors="replace")[-500:])]
    declared = {r["name"][1:]: r for r in json.loads(p.stdout.decode())}
    problems = []
    for name, typ in sorted(T.items()):
        r = declared.get(name)
        if r is None and name in RAW:
            continue
        if r is None:
            problems.append("-%s: in the fuzz table, not declared by nltopo" % name)
            continue
        if typ[0] not in KINDS[r["type"]]:
            problems.append("-%s: fuzz kind %s, declared %s" % (name, typ[0], r["type"]))
        if r["type"] == "enum" and sorted(typ[3]) != sorted(r["choices"]):
            problems.append("-%s: fuzz choices %s, declared %s" % (name, typ[3], r["choices"]))
        if typ[0] in ("real", "int", "reals") and r["type"] != "string":
            lo, hi = r.get("min"), r.get("max")
            if (lo is not None and typ[1] < lo) or (hi is not None and typ[2] > hi):
                problems.append("-%s: fuzz draws %g..%g, declared range %s..%s" % (name, typ[1], typ[2], lo, hi))
    return problems


# ---------------------------------------------------------------------------
# Input families (issue 34): how the options reach nltopo, not their values.
# A case may get one (input_family): its option names in mixed case (PETSc's
# names are case-insensitive, so the contract is the plain case's); its
# mutations in an options file, possibly mutated (a byte-order mark, a word
# after a value, two options on a line, a missing nested file, files that
# include each other: each an error naming the file), nested, or read from a
# pipe (/dev/stdin, or /dev/fd/N at 1 rank); a stray word on the command line
# or in PETSC_OPTIONS (an error), or only its legitimate look-alikes
# (negative numbers, values that begin with a space: never called stray).
# The case then carries: muts_in_argv, files {name: bytes}, argv_pre (before the mutations), argv_extra,
# env_extra, stdin / fd_pipe (bytes), and what the run must print:
# expect_error (a substring of the one line) or never (a substring it must not hold).

INPUT_FAMILY_SHARE = 0.4


def mixed_case(rng, name):
    """-lattice_k as -Lattice_K, -LATTICE_k, ...: some letter upper-case."""
    while True:
        s = "".join(c.upper() if c.isalpha() and rng.random() < 0.4 else c for c in name)
        if s != name or not any(c.isalpha() for c in name):
            return s


def file_line(args):
    """An options-file line for one mutation's arguments (a value with spaces, or empty, quoted)."""
    if len(args) == 1:
        return args[0]
    v = args[1]
    return "%s %s" % (args[0], '"%s"' % v if (v == "" or " " in v or "\t" in v) else v)


def options_file_family(rng, case):
    lines = [file_line(a) for a, _ in case["muts"]]
    if rng.random() < 0.5:  # what PETSc ignores: comments, blank lines, tabs, CR LF
        lines.insert(rng.randint(0, len(lines)), "# a comment line")
        lines.append("")
    sep = "\r\n" if rng.random() < 0.2 else "\n"
    kind = rng.choice(["plain", "plain", "nested", "pipe", "bom", "trailing", "two", "missing", "cycle"])
    extra = dict(family="file:" + kind, muts_in_argv=False, files={}, argv_extra=[])
    body = sep.join(lines) + sep
    if kind == "bom":
        body = "\ufeff" + body
        extra["expect_error"] = "byte-order mark"
    elif kind == "trailing":
        body += "-lattice_k 1 %s%s" % (rng.choice(["!", "x", "2", "! comment"]), sep)
        extra["expect_error"] = "scene.opts line"
    elif kind == "two":
        body += "-lattice_k 1 -lattice_gamma 0.5" + sep
        extra["expect_error"] = "two options on one line"
    elif kind == "missing":
        body += "-options_file gone.opts" + sep
        extra["expect_error"] = "cannot read options file gone.opts"
    elif kind == "cycle":
        body += "-options_file other.opts" + sep
        extra["files"]["other.opts"] = ("-lattice_k 1" + sep + "-options_file scene.opts" + sep).encode()
        extra["expect_error"] = "include each other"
    if kind == "nested":
        extra["files"]["scene.opts"] = ("-options_file inner.opts" + sep).encode()
        extra["files"]["inner.opts"] = body.encode()
        extra["argv_extra"] = ["-options_file", "scene.opts"]
    elif kind == "pipe":
        if case["ranks"] == 1 and rng.random() < 0.5:
            extra["fd_pipe"] = body.encode()  # -options_file /dev/fd/N, as the shell's <(...)
        else:
            extra["stdin"] = body.encode()
            extra["argv_extra"] = ["-options_file", "/dev/stdin"]
    else:
        extra["files"]["scene.opts"] = body.encode()
        extra["argv_extra"] = ["-options_file", "scene.opts"]
    return extra


def stray_family(rng, case):
    """A stray word after a complete option (an error), or only look-alikes that are values."""
    # The look-alikes go before the mutations (argv_pre): PETSc keeps an option's last value, so after them a
    # look-alike would replace a mutated -lattice_cubic (a garbage value then never read; seed 1795778297 case 292).
    look_alikes = ["-lattice_cubic", rng.choice(["-0.25", "-.5", "-1e-3", "-0"])]
    if rng.random() < 0.5:
        return dict(family="stray:look-alike", argv_pre=look_alikes, never="is neither an option")
    word = rng.choice(["1", "0.5", "x", ",", "extra.opts", "-1", "1,2"])
    return dict(family="stray:argv", argv_pre=look_alikes, argv_extra=["-lattice_k", "1", word], expect_error="is neither an option nor an option's value")


def env_family(rng, case):
    """PETSC_OPTIONS: a backslash-escaped space (a stray word), or values PETSc reads as written."""
    if rng.random() < 0.5:
        return dict(family="env:stray", env_extra={"PETSC_OPTIONS": "-lattice_k 1\\ 2"}, expect_error="PETSC_OPTIONS")
    return dict(family="env:plain", env_extra={"PETSC_OPTIONS": rng.choice(["-lattice_cubic -0.5", '-lattice_cubic "-0.25"'])}, never="PETSC_OPTIONS")


def input_family(rng, case):
    """None for most cases; otherwise one family's fields (see above)."""
    if rng.random() >= INPUT_FAMILY_SHARE:
        return {}
    kind = rng.choice(["case", "file", "file", "stray", "env"])
    if kind == "case":
        muts = [([mixed_case(rng, a[0])] + a[1:], c) for a, c in case["muts"]]
        return dict(family="case", muts=muts)
    if kind == "file":
        return options_file_family(rng, case)
    if kind == "stray":
        return stray_family(rng, case)
    return env_family(rng, case)


def input_setup(case, d):
    """Writes the case's files into its directory; the arguments, environment, stdin and fds of its run."""
    for name, data in case.get("files", {}).items():
        with open(os.path.join(d, name), "wb") as f:
            f.write(data)
    argv = list(case.get("argv_extra", []))
    env = dict(os.environ, TMPDIR=d)  # a leftover copy of a piped file shows in the case directory
    env.update(case.get("env_extra", {}))
    fds = ()
    if "fd_pipe" in case:
        r, w = os.pipe()
        os.write(w, case["fd_pipe"])  # a few hundred bytes: within the pipe's buffer
        os.close(w)
        fds = (r,)
        argv += ["-options_file", "/dev/fd/%d" % r]
    return argv, env, case.get("stdin"), fds


def input_problems(case, d, rc, lines):
    """What an input family demands beyond the common contract."""
    problems = []
    left = sorted(f for f in os.listdir(d) if f.startswith("nltopo-options-"))
    if left:
        problems.append("left behind: %s" % " ".join(left))
    want, never = case.get("expect_error"), case.get("never")
    if rc == 0 and want:
        problems.append("%s: exit 0, expected an error naming '%s'" % (case.get("family"), want))
    elif rc is not None and rc > 0 and lines:
        if want and want not in lines[0]:
            problems.append("%s: the error does not name '%s'" % (case.get("family"), want))
        if never and never in lines[0]:
            problems.append("%s: a legitimate form refused: %s" % (case.get("family"), lines[0]))
    return problems


def make_case(seed, i, options):
    rng = random.Random("%d:%d" % (seed, i))
    study = STUDIES[i % len(STUDIES)]
    ranks = 1 + i % 2  # 7 studies: each study alternates between 1 and 2 ranks too
    names = rng.sample(options[study], rng.randint(1, 3))
    muts = [mutate(rng, n) for n in names]
    case = dict(i=i, study=study, ranks=ranks, names=names, muts=muts)
    case.update(input_family(rng, case))  # how the options reach nltopo (issue 34)
    return case


CRASH = re.compile(r"PETSC ERROR|MPI_ABORT|MPI_Abort|Caught signal|Segmentation|Aborted|core dumped|terminate called|"
                   r"mpiexec noticed|exited on signal|mpiexec has exited|Assertion|double free|corrupted|std::bad_alloc")


def run_case(case, args, workroot):
    d = os.path.join(workroot, "c%04d" % case["i"])
    shutil.rmtree(d, ignore_errors=True)
    os.makedirs(d)
    out = "out.h5"
    cmd = ["-study", case["study"]] + BASE[case["study"]] + case.get("argv_pre", [])
    for a, _ in case["muts"]:
        cmd += a if case.get("muts_in_argv", True) else []
    extra_argv, env, stdin, fds = input_setup(case, d)
    cmd += extra_argv + ["-output", out]
    full = ([args.mpiexec, "-q", "-n", "2"] if case["ranks"] == 2 else []) + [args.nltopo] + cmd
    t0 = time.time()
    p = subprocess.Popen(full, cwd=d, stdout=subprocess.PIPE, stderr=subprocess.PIPE, start_new_session=True, env=env,
                         stdin=subprocess.PIPE if stdin is not None else subprocess.DEVNULL, pass_fds=fds)
    for fd in fds:
        os.close(fd)
    try:
        so, se = p.communicate(input=stdin, timeout=args.timeout)
        hung = False
    except subprocess.TimeoutExpired:
        hung = True
        try:
            os.killpg(p.pid, signal.SIGKILL)  # the whole session: mpiexec and its ranks
        except ProcessLookupError:
            pass
        so, se = p.communicate()
    rc = None if hung else p.returncode
    so, se = so.decode(errors="replace"), se.decode(errors="replace")
    dt = time.time() - t0
    problems = []
    left = sorted(f for f in os.listdir(d) if f.startswith(out) and f != out)
    lines = [l for l in se.splitlines() if l.strip()]
    classes = [c for _, c in case["muts"]]
    if hung:
        problems.append("hang: no exit within %g s" % args.timeout)
    elif rc < 0 or rc >= 128:
        problems.append("crash: exit status %d (signal)" % rc)
    if CRASH.search(se):
        problems.append("crash: stderr shows a signal, abort or PETSc traceback")
    if left:
        problems.append("left behind: %s" % " ".join(left))
    if not hung and rc == 0:
        if not os.path.exists(os.path.join(d, out)):
            problems.append("exit 0 without %s" % out)
        else:
            try:
                import h5py
                with h5py.File(os.path.join(d, out), "r") as f:
                    if int(f.attrs.get("complete", -1)) != 1:
                        problems.append("exit 0 with root attribute complete = %s" % f.attrs.get("complete"))
            except Exception as e:  # noqa: BLE001
                problems.append("exit 0 with an unreadable %s: %s" % (out, e))
        for c, (a, _) in zip(classes, case["muts"]):
            if c in ("garbage", "nonfinite"):
                problems.append("accepted a %s value: %s" % (c, " ".join(shlex.quote(x) for x in a)))
    elif not hung and rc > 0:
        if os.path.exists(os.path.join(d, out)):
            problems.append("exit %d but %s exists" % (rc, out))
        if len(lines) != 1 or not lines[0].startswith("nltopo: error: "):
            problems.append("not a one-line 'nltopo: error:' message (%d non-empty stderr lines)" % len(lines))
        elif len(case["muts"]) == 1 and classes[0] in ("garbage", "nonfinite") and not case.get("expect_error"):  # a mutated file is named first
            if "-" + case["names"][0] not in lines[0].lower():
                problems.append("the error does not name -%s" % case["names"][0])
    problems += input_problems(case, d, rc, lines)
    if not problems:
        shutil.rmtree(d, ignore_errors=True)
    verdict = "ok" if rc == 0 else ("error" if rc is not None else "hang")
    return dict(case=case, problems=problems, rc=rc, seconds=dt, stderr=se, stdout=so, cmd=full, verdict=verdict,
                first=lines[0] if lines else "")


# Issue 34, class 7: corrupted resume states. A continuation checkpoint and a
# sweep (complete, from the base scenes) get one stored value set to NaN, inf
# or -inf (a random array and position: every dataset of the branch, the
# sweep's per-point datasets and axes, or a line of a sweep journal left by a
# killed run), and the run resumes from it. It must end (no hang), refuse in
# one line without an output and leave the resumed file as it was, or
# complete; inf and -inf, which no run writes, must be refused.
# Columns where a run writes +inf (a verdict's bound without a bound, the e-folding time of a non-growing orbit).
INF_WRITTEN = {"verdict_bound", "verdict_efold"}
RESUME_BASE = {
    "continuation": BASE["continuation"] + ["-floquet"],
    "sweep": BASE["sweep"],
}


def sweep_point_fields(nltopo):
    """The per-point (ne x no) fields of /sweep in the journal's order (reals, then ints; not done), from
    the binary's output schema (-output_schema md)."""
    md = subprocess.run([nltopo, "-output_schema", "md"], stdout=subprocess.PIPE, check=True).stdout.decode()
    part = md.split("### `/sweep`", 1)[1].split("###", 1)[0]
    rows = re.findall(r"^\| `([a-z_]+)` \| dataset \| (real|int) \| ne x no \|", part, re.M)
    return [n for n, t in rows if t == "real"], [n for n, t in rows if t == "int" and n != "done"]


def corrupted_resume_cases(args, n):
    """n cases of the family above (seeded by --seed), run on the thread pool; returns the results."""
    import h5py
    import numpy as np
    root = os.path.join(args.work, "resume")
    shutil.rmtree(root, ignore_errors=True)
    os.makedirs(root)
    for study, opts in RESUME_BASE.items():
        subprocess.run([args.nltopo, "-study", study] + opts + ["-output", study + ".h5"], cwd=root, stdout=subprocess.DEVNULL, check=True)
    reals, ints = sweep_point_fields(args.nltopo)
    with h5py.File(os.path.join(root, "continuation.h5"), "r") as f:
        branch = sorted(k for k, d in f["continuation/insulated"].items() if isinstance(d, h5py.Dataset) and d.size > 0 and d.dtype.kind == "f")  # an int holds no NaN
    cases = []
    for i in range(n):
        rng = random.Random("%d:resume:%d" % (args.seed, i))
        kind = rng.choice(["continuation", "sweep", "journal"])
        name = rng.choice(branch if kind == "continuation" else reals + (["omega", "energy"] if kind == "sweep" else []))
        cases.append(dict(i=i, kind=kind, name=name, value=rng.choice(["nan", "inf", "-inf"]), ranks=1 + i % 2, pick=rng.random()))

    def one(c):
        d = os.path.join(root, "r%03d" % c["i"])
        shutil.rmtree(d, ignore_errors=True)
        os.makedirs(d)
        study = "continuation" if c["kind"] == "continuation" else "sweep"
        target = os.path.join(d, "in.h5")
        shutil.copyfile(os.path.join(root, study + ".h5"), target)
        v = float(c["value"])
        with h5py.File(target, "r+") as f:
            if c["kind"] == "journal":  # point k taken out of the file (done = 0) and journaled with the value
                g = f["sweep"]
                k = int(c["pick"] * g["done"].size)
                cell = np.unravel_index(k, g["done"].shape)
                text = lambda x: x.hex() if np.isfinite(x) else str(x)  # noqa: E731
                line = [str(k)] + [text(v if r == c["name"] else float(g[r][cell])) for r in reals] + [str(int(g[x][cell])) for x in ints]
                done = g["done"][...]
                done[cell] = 0
                g["done"][...] = done
                with open(target + ".journal.0", "w") as j:
                    j.write(" ".join(line) + "\n")
            else:
                ds = f[("continuation/insulated/" if study == "continuation" else "sweep/") + c["name"]]
                a = ds[...]
                a.flat[int(c["pick"] * a.size)] = v
                ds[...] = a
        before = open(target, "rb").read()
        cmd = ["-study", study] + RESUME_BASE[study] + (["-cont_max_points", "5", "-cont_resume", "in.h5", "-output", "out.h5"]
                                                         if study == "continuation" else ["-sweep_resume", "-output", "in.h5"])
        full = ([args.mpiexec, "-q", "-n", "2"] if c["ranks"] == 2 else []) + [args.nltopo] + cmd
        p = subprocess.Popen(full, cwd=d, stdout=subprocess.PIPE, stderr=subprocess.PIPE, start_new_session=True)
        try:
            so, se = p.communicate(timeout=args.timeout)
            rc = p.returncode
        except subprocess.TimeoutExpired:
            os.killpg(p.pid, signal.SIGKILL)
            so, se = p.communicate()
            rc = None
        se = se.decode(errors="replace")
        lines = [l for l in se.splitlines() if l.strip() and not MPI_NOISE.search(l)]  # (see MPI_NOISE)
        out = os.path.join(d, "out.h5" if study == "continuation" else "in.h5")
        problems = []
        if rc is None:
            problems.append("hang: no exit within %g s" % args.timeout)
        elif rc < 0 or rc >= 128 or CRASH.search(se):
            problems.append("crash (exit %s)" % rc)
        elif rc == 0:
            if c["value"] != "nan" and not (c["value"] == "inf" and c["name"] in INF_WRITTEN):
                problems.append("accepted %s, which no run writes" % c["value"])
            with h5py.File(out, "r") as f:
                if int(f.attrs.get("complete", -1)) != 1:
                    problems.append("exit 0 without a complete output")
        else:
            if len(lines) != 1 or not lines[0].startswith("nltopo: error: "):
                problems.append("not a one-line 'nltopo: error:' message (%d lines)" % len(lines))
            if study == "continuation" and os.path.exists(out):
                problems.append("refused, but out.h5 was written")
            if open(target, "rb").read() != before:
                problems.append("refused, but the resumed file was changed")
        if any(x.startswith("out.h5.tmp") or x.startswith("in.h5.tmp") for x in os.listdir(d)):
            problems.append("temporary left")
        if not problems:
            shutil.rmtree(d, ignore_errors=True)
        return dict(case=c, problems=problems, rc=rc, first=lines[0] if lines else "", cmd=full, dir=d)

    with ThreadPoolExecutor(max_workers=max(1, args.jobs)) as ex:
        results = list(ex.map(one, cases))
    for r in results:
        c = r["case"]
        if args.verbose or r["problems"]:
            print("resume case %d np%d %s %s = %s: exit %s | %s" % (c["i"], c["ranks"], c["kind"], c["name"], c["value"], r["rc"], r["first"]))
        if r["problems"]:
            print("FAIL resume case %d (--seed %d): %s\n  in %s: %s" % (c["i"], args.seed, "; ".join(r["problems"]), r["dir"],
                                                                      " ".join(shlex.quote(x) for x in r["cmd"])))
    n_bad = sum(1 for r in results if r["problems"])
    print("fuzz: %d corrupted resume states (%d refused with one line), %d failed" % (len(results), sum(1 for r in results if r["rc"] not in (0, None)), n_bad))
    return n_bad


# Concurrent runs on one output (docs/errors.md "One run per output"): two runs
# of different scenes (another study, or the same study with another
# -lattice_cubic) into one -output, the second started a random 0-0.6 s
# after the first, each at 1 or 2 ranks. At most one exits 0, and the file
# is then complete and that run's (its study and -lattice_cubic). Every other
# run stops with one 'nltopo: error:' line (another run holds the output, or
# an earlier result of another scene is there). Nothing beside the file is
# left (lock, temporary, partial output, journal), and no run hangs or crashes.
CONCURRENT_STUDIES = ["simulate", "sweep", "continuation", "linear", "zak", "stability"]
MPI_NOISE = re.compile(r"mca_sharedfp_sm_component_file_query")  # Open MPI singletons sharing a session directory


def make_concurrent_case(seed, i):
    rng = random.Random("%d:concurrent:%d" % (seed, i))
    cubic = rng.choice([0.1, 0.2, 0.3, 0.4])
    runs = [(rng.choice(CONCURRENT_STUDIES), rng.randint(1, 2), c) for c in (cubic, cubic + 0.05)]
    return dict(i=i, runs=runs, delay=rng.uniform(0.0, 0.6))


def run_concurrent_case(case, args, workroot):
    d = os.path.join(workroot, "k%04d" % case["i"])
    shutil.rmtree(d, ignore_errors=True)
    os.makedirs(d)
    out, cmds, procs = "out.h5", [], []
    t0 = time.time()
    for k, (study, ranks, cubic) in enumerate(case["runs"]):
        if k:
            time.sleep(case["delay"])
        cmd = ([args.mpiexec, "-q", "-n", "2"] if ranks == 2 else []) + [args.nltopo, "-study", study] + BASE[study] + \
            ["-lattice_cubic", repr(cubic), "-output", out]
        cmds.append(cmd)
        procs.append(subprocess.Popen(cmd, cwd=d, stdout=subprocess.PIPE, stderr=subprocess.PIPE, start_new_session=True))
    results, problems = [], []
    for k, p in enumerate(procs):
        try:
            so, se = p.communicate(timeout=max(1.0, args.timeout - (time.time() - t0)))
            rc = p.returncode
        except subprocess.TimeoutExpired:
            try:
                os.killpg(p.pid, signal.SIGKILL)
            except ProcessLookupError:
                pass
            so, se = p.communicate()
            rc = None
            problems.append("run %d: hang: no exit within %g s" % (k, args.timeout))
        se = se.decode(errors="replace")
        lines = [l for l in se.splitlines() if l.strip() and not MPI_NOISE.search(l)]
        results.append((rc, lines))
        if rc is not None and (rc < 0 or rc >= 128):
            problems.append("run %d: crash: exit status %d (signal)" % (k, rc))
        if CRASH.search(se):
            problems.append("run %d: crash: stderr shows a signal, abort or PETSc traceback" % k)
        if rc is not None and 0 < rc < 128 and (len(lines) != 1 or not lines[0].startswith("nltopo: error: ")):
            problems.append("run %d: exit %d without one 'nltopo: error:' line (%d lines)" % (k, rc, len(lines)))
    winners = [k for k, (rc, _) in enumerate(results) if rc == 0]
    path = os.path.join(d, out)
    if len(winners) > 1:
        problems.append("both runs exited 0 into one -output")
    elif winners:
        study, _, cubic = case["runs"][winners[0]]
        try:
            import h5py
            with h5py.File(path, "r") as f:
                got = f.attrs["options"]
                got = (got.decode() if isinstance(got, bytes) else str(got)) + " "
                st = f.attrs["study"]
                st = st.decode() if isinstance(st, bytes) else str(st)
                if int(f.attrs["complete"]) != 1 or st != study or ("-lattice_cubic %r " % cubic) not in got:
                    problems.append("run %d exited 0 but %s is not its complete result (study %s, complete %s)" % (winners[0], out, st, f.attrs["complete"]))
        except Exception as e:  # noqa: BLE001
            problems.append("run %d exited 0 without a readable %s: %s" % (winners[0], out, e))
    elif os.path.exists(path):
        problems.append("no run exited 0 but %s exists" % out)
    left = sorted(f for f in os.listdir(d) if f.startswith(out) and f != out)
    if left:
        problems.append("left behind: %s" % " ".join(left))
    if not problems:
        shutil.rmtree(d, ignore_errors=True)
    return dict(case=case, problems=problems, cmds=cmds, results=results, seconds=time.time() - t0)


def concurrent_cases(args, ids):
    """The concurrent-runs family; returns the failed results."""
    failed = []
    for i in ids:
        r = run_concurrent_case(make_concurrent_case(args.seed, i), args, args.work)
        c = r["case"]
        if args.verbose or r["problems"]:
            print("concurrent case %d: %s, delay %.2f s: exits %s %5.1fs | %s" % (
                i, " + ".join("%s np%d cubic %g" % x for x in c["runs"]), c["delay"], [rc for rc, _ in r["results"]], r["seconds"],
                " | ".join(l[0] for _, l in r["results"] if l)))
        if r["problems"]:
            failed.append(r)
            print("FAIL concurrent case %d (--seed %d --only-concurrent %d): %s" % (i, args.seed, i, "; ".join(r["problems"])))
            for cmd, (rc, lines) in zip(r["cmds"], r["results"]):
                print("  command (exit %s): %s" % (rc, " ".join(shlex.quote(x) for x in cmd)))
                for l in lines[:6]:
                    print("  stderr: " + l)
        sys.stdout.flush()
    return failed


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("nltopo")
    ap.add_argument("work")
    ap.add_argument("--cases", type=int, default=30)
    ap.add_argument("--seed", type=int, default=20261122)
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--only", type=int, default=None)
    ap.add_argument("--timeout", type=float, default=60)
    ap.add_argument("--mpiexec", default=os.environ.get("MPIEXEC", "mpiexec"))
    ap.add_argument("--verbose", action="store_true")
    ap.add_argument("--resume-cases", type=int, default=16, help="cases of the corrupted-resume-state family (0: none)")
    ap.add_argument("--concurrent", type=int, default=6, help="cases of the concurrent-runs family")
    ap.add_argument("--only-concurrent", type=int, default=None)
    args = ap.parse_args()
    args.nltopo = os.path.abspath(args.nltopo)
    args.work = os.path.abspath(args.work)  # the cases' TMPDIR
    os.makedirs(args.work, exist_ok=True)
    t0 = time.time()
    problems = check_table(args.nltopo)
    if problems:
        print("fuzz: the fuzz table (tests/fuzz/fuzz.py T) disagrees with nltopo's option tables:\n  " + "\n  ".join(problems))
        return 1
    options = study_options(args.nltopo)
    missing = sorted({n for s in options.values() for n in s} - set(T) - NOT_FUZZED)
    if missing:
        print("fuzz: options without an entry in the fuzz table (tests/fuzz/fuzz.py T): " + " ".join("-" + m for m in missing))
        return 1
    for s in options:
        options[s] = [n for n in options[s] if n not in NOT_FUZZED]
    if args.only_concurrent is not None:
        return 1 if concurrent_cases(args, [args.only_concurrent]) else 0
    ids = [args.only] if args.only is not None else list(range(args.cases))
    cases = [make_case(args.seed, i, options) for i in ids]
    lock = threading.Lock()
    results = []

    def one(c):
        r = run_case(c, args, args.work)
        with lock:
            results.append(r)
            if args.verbose or r["problems"]:
                print("case %d %s np%d %s %-5s %5.1fs %s | %s" % (c["i"], c["study"], c["ranks"], c.get("family", "values"), r["verdict"], r["seconds"],
                      " ".join(" ".join(a) if len(a) == 1 else "%s %r" % (a[0], a[1]) for a, _ in c["muts"]), r["first"]))
                sys.stdout.flush()
        return r

    with ThreadPoolExecutor(max_workers=max(1, args.jobs)) as ex:
        list(ex.map(one, cases))
    results.sort(key=lambda r: r["case"]["i"])
    failed = [r for r in results if r["problems"]]
    for r in failed:
        c = r["case"]
        print("FAIL case %d (--seed %d --only %d): %s" % (c["i"], args.seed, c["i"], "; ".join(r["problems"])))
        print("  command: " + " ".join(shlex.quote(x) for x in r["cmd"]))
        for l in r["stderr"].splitlines()[:12]:
            print("  stderr: " + l)
    cfailed = []
    if args.only is None and args.concurrent > 0:
        t1 = time.time()
        cfailed = concurrent_cases(args, list(range(args.concurrent)))
        print("fuzz: %d concurrent-runs cases, seed %d, %.0f s: %d passed, %d failed" % (args.concurrent, args.seed, time.time() - t1,
                                                                                     args.concurrent - len(cfailed), len(cfailed)))
    n_ok = sum(1 for r in results if r["verdict"] == "ok")
    n_err = sum(1 for r in results if r["verdict"] == "error")
    print("fuzz: %d cases (%d completed, %d refused with one line), seed %d, %.0f s" % (len(results), n_ok, n_err, args.seed, time.time() - t0))
    print("fuzz: %d passed, %d failed" % (len(results) - len(failed), len(failed)))
    resume_failed = corrupted_resume_cases(args, args.resume_cases) if args.only is None and args.resume_cases > 0 else 0
    return 1 if failed or cfailed or resume_failed else 0


if __name__ == "__main__":
    sys.exit(main())
