# -help lists every option of the studies with its help text: nltopo's own
# listing first (the study's own block first, values, no "(None)"), the
# solver options of PETSc and SLEPc with -help petsc.
source "$(dirname "$0")/common.bash"
"$NLTOPO" -help -study simulate -sim_t_final 1 -output h.h5 > help_sim.txt
"$NLTOPO" -help -study linear -output h2.h5 > help_lin.txt
for opt in -study -output -lattice_k -lattice_gamma -lattice_gamma0 -lattice_cubic -lattice_cells -lattice_layout \
           -force_profile -force_omega -force_energy -force_amplitude -force_amplitude_safety -force_amplitude_retries -force_tau_periods \
           -force_t0_taus -force_site -force_mode_index -sim_t_final -sim_sample_dt -sim_store_u -sim_progress; do
  grep -qE -- "$opt[ :]" help_sim.txt || { echo "missing in -help: $opt"; exit 1; }
done
head -1 help_sim.txt | grep -q "^nltopo -study simulate: its options" || { head -3 help_sim.txt; echo "-help does not begin with nltopo's options"; exit 1; }
! grep -q "(None)" help_sim.txt || { echo "-help prints (None)"; exit 1; }
sed -n 3p help_sim.txt | grep -q -- "(-sim_\*):" || { sed -n 1,4p help_sim.txt; echo "-help: the study's own block is not first"; exit 1; }
grep -q -- "-sim_t_final <1>" help_sim.txt || { echo "-help does not show the value this run would use"; exit 1; }
grep -q -- "-sim_ts_\*" help_sim.txt || { echo "-help does not name the solver prefix -sim_ts_*"; exit 1; }
"$NLTOPO" -help petsc -study simulate -sim_t_final 1 -output h.h5 > help_petsc.txt
grep -q -- "-sim_ts_type" help_petsc.txt || { echo "-help petsc does not list -sim_ts_type"; exit 1; }
"$NLTOPO" -version > version.txt
grep -qE "^nltopo .+" version.txt && grep -q "format_version" version.txt && grep -q "CITATION.cff" version.txt || { cat version.txt; echo "-version"; exit 1; }
grep -q -- "-linear_eps_\*" help_lin.txt || { echo "-help does not name -linear_eps_*"; exit 1; }
for opt in -linear_dense_max -linear_nev -linear_target_offset -linear_nq -linear_gamma_list; do
  grep -qE -- "$opt[ :]" help_lin.txt || { echo "missing in -help: $opt"; exit 1; }
done
"$NLTOPO" -help -study sweep -sweep_omega_n 1 -sweep_energy_n 1 -sim_t_final 1 -output h3.h5 > help_sweep.txt
for opt in -sweep_omega_min -sweep_omega_max -sweep_omega_n -sweep_omega_spacing -sweep_omega_list -sweep_energy_min -sweep_energy_max \
           -sweep_energy_n -sweep_resume -sweep_kcorr -sweep_checkpoint -sweep_progress -sweep_shard -sweep_refine_from -sweep_refine_mcr -sweep_refine_max_points -kcorr_nc -kcorr_seed -kcorr_sample_dt -kcorr_record \
           -kcorr_lags -kcorr_rms_fraction -kcorr_site_stride -lattice_perturbation -lattice_delta -lattice_seed; do
  grep -qE -- "$opt[ :]" help_sweep.txt || { echo "missing in -help: $opt"; exit 1; }
done
"$NLTOPO" -help -study zak -zak_energy_list 0.01 -sim_t_final 300 -lattice_cells 4 -output h4.h5 > help_zak.txt
for opt in -zak_energy_min -zak_windows -zak_samples_per_period -zak_theta_tol; do
  grep -qE -- "$opt[ :]" help_zak.txt || { echo "missing in -help: $opt"; exit 1; }
done
"$NLTOPO" -help -study continuation -lattice_cells 5 -lattice_layout interface -nnm_jacobian mf -floquet -floquet_mf -cont_energy_max 1e-4 -cont_max_points 2 -output h5.h5 > help_cont.txt
for opt in -nnm_jacobian -nnm_mf_pc -nnm_mf_pc_parametric_weight -nnm_orbit_rtol -nnm_start_dense_max -floquet -floquet_mf -floquet_mf_nev -floquet_mf_which -floquet_mf_circle_tol -floquet_mf_deflate -floquet_mf_dense_max -floquet_tol \
           -cont_energy_max -cont_max_change -cont_mcr_min -cont_checkpoint_seconds -cont_resume -cont_bifurcations -cont_bif_tol -cont_bif_max_probes \
           -cont_bif_angle_tol -cont_bif_bulk -cont_bif_passes -cont_bif_resonance_order -cont_switch -cont_switch_step \
           -cont_codim2 -cont_codim2_parameter -cont_codim2_min -cont_codim2_max -cont_codim2_step -cont_codim2_max_points; do
  grep -qE -- "$opt[ :]" help_cont.txt || { echo "missing in -help: $opt"; exit 1; }
done
# nltopo alone prints usage (every study, where the docs are), writes nothing and exits 0
"$NLTOPO" > usage.txt
for s in linear simulate continuation sweep zak perturb workprecision stability merge; do
  grep -qE "^  $s +[A-Za-z]" usage.txt || { cat usage.txt; echo "usage does not list -study $s"; exit 1; }
done
grep -q "docs/options.md" usage.txt
[ -z "$(ls ./*.h5 ./*.tmp.* 2> /dev/null | grep -v '^./h[0-9]*.h5$')" ] || { ls; echo "nltopo alone wrote a file"; exit 1; }
# docs/options.md is the binary's options reference, and the JSON form names the same options
"$NLTOPO" -option_tables md > options.md
diff -u "$SRC/docs/options.md" options.md > options.diff || { head -40 options.diff; echo "docs/options.md is stale: build/nltopo -option_tables md > docs/options.md"; exit 1; }
"$NLTOPO" -output_schema md > outputs.md
diff -u "$SRC/docs/outputs.md" outputs.md > outputs.diff || { head -40 outputs.diff; echo "docs/outputs.md is stale: build/nltopo -output_schema md > docs/outputs.md"; exit 1; }
"$NLTOPO" -option_tables json > options.json
$PY - <<'PYEOF'
import json, re
rows = json.load(open("options.json"))
md = set(re.findall(r"^\| `(-[a-z0-9_]+)` \|", open("options.md").read(), re.M))
names = [r["name"] for r in rows]
assert len(names) == len(set(names)), "an option declared twice"
assert set(names) == md and len(md) >= 120, (len(md), set(names) ^ md)
for r in rows:
    assert r["class"] in ("physics", "extent", "bookkeeping") and r["help"], r["name"]
    if r["type"] in ("real", "int", "real list"):
        lo, hi = r["min"], r["max"]
        assert lo is None or hi is None or lo <= hi, r["name"]
print("options reference OK:", len(rows), "options")
PYEOF
echo "help OK"
