# -help lists every option of the studies with its help text.
source "$(dirname "$0")/common.bash"
"$NLTOPO" -help -study simulate -sim_t_final 1 -output h.h5 > help_sim.txt
"$NLTOPO" -help -study linear -output h2.h5 > help_lin.txt
for opt in -study -output -lattice_k -lattice_gamma -lattice_gamma0 -lattice_cubic -lattice_cells -lattice_layout \
           -force_profile -force_omega -force_energy -force_amplitude -force_amplitude_safety -force_amplitude_retries -force_tau_periods \
           -force_t0_taus -force_site -force_mode_index -sim_t_final -sim_sample_dt -sim_store_u -sim_progress -sim_ts_type; do
  grep -qE -- "$opt[ :]" help_sim.txt || { echo "missing in -help: $opt"; exit 1; }
done
for opt in -linear_dense_max -linear_nev -linear_target_offset -linear_nq -linear_eps_type; do
  grep -qE -- "$opt[ :]" help_lin.txt || { echo "missing in -help: $opt"; exit 1; }
done
echo "help OK"
