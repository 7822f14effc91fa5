# Bad input (README.md "Error contract"): every case at 1 and 2 ranks, under a
# timeout, must end with exactly one line on stderr (both ranks together)
# naming the option, value or file, a non-zero exit, and neither the output
# file nor a temporary left behind.
source "$(dirname "$0")/common.bash"
fail() { echo "FAILED: $*" >&2; exit 1; }
cases=0
check_one() { # check_one <np> <pattern> <output file> nltopo args...
  local np=$1 pattern=$2 out=$3; shift 3
  set +e
  if [ "$np" = 1 ]; then timeout 120 "$NLTOPO" "$@" -output "$out" > stdout.txt 2> stderr.txt
  else timeout 120 "$MPIEXEC" -q -n "$np" "$NLTOPO" "$@" -output "$out" > stdout.txt 2> stderr.txt; fi
  local rc=$?
  set -e
  [ $rc -ne 124 ] || fail "hang (timeout) at $np rank(s) for: $*"
  [ $rc -ne 0 ] || fail "exit 0 at $np rank(s) for: $*"
  [ "$(grep -c . stderr.txt)" -eq 1 ] || { cat stderr.txt; fail "not a one-line error at $np rank(s) for: $*"; }
  grep -q -- "$pattern" stderr.txt || { cat stderr.txt; fail "error does not name '$pattern' at $np rank(s) for: $*"; }
  ! grep -q "\.c:[0-9]" stderr.txt || { cat stderr.txt; fail "a source path in the message for: $*"; }
  [ ! -f "$out" ] || fail "output left behind at $np rank(s) for: $*"
  ls -d "$out".tmp.* "$out".journal.* > /dev/null 2>&1 && fail "temporary left behind at $np rank(s) for: $*"
  return 0
}
expect_error() { # expect_error <pattern> <output file> nltopo args...
  local pattern=$1 out=$2; shift 2
  check_one 1 "$pattern" "$out" "$@"
  check_one 2 "$pattern" "$out" "$@"
  cases=$((cases + 1))
  echo "ok: $(cat stderr.txt)"
}
S="-study simulate -sim_t_final 5"
C="-study continuation -lattice_cells 5 -cont_energy_max 1e-4 -cont_max_points 3 -cont_verbose 0"
W="-study sweep -sweep_omega_n 2 -sweep_energy_n 1 -sim_t_final 20"

# -study workprecision: configurations hold integrator options only, each used by its run
P="-study workprecision -sim_t_final 5 -wp_twins 1 -wp_repeats 1"
expect_error "-lattice_k is not an integrator option" o.h5 $P -wp_configs " -sim_ts_type rk -lattice_k 2"
expect_error "-sim_ts_symsplit_scheme was not used by that run" o.h5 $P -wp_configs " -sim_ts_type rk -sim_ts_symsplit_scheme bm4"
expect_error "-wp_configs has no value" o.h5 $P -wp_configs "-sim_ts_type rk"
expect_error "-wp_repeats" o.h5 $P -wp_repeats 0
expect_error "leave out -sim_ts_rtol" o.h5 $P -wp_reference " -sim_ts_type rkn -sim_ts_rtol 1e-9"

expect_error "-sweep_mcr_tol needs a fixed-step integrator" o.h5 $W -sweep_mcr_tol 1e-3 -sim_ts_type rk
expect_error "-sweep_mcr_tol" o.h5 $W -sweep_mcr_tol 2

# the study, the lattice and the files
expect_error "unknown -study nope" o.h5 -study nope
expect_error "-lattice_cells" o.h5 -study linear -lattice_cells 0
expect_error "-lattice_k" o.h5 -study linear -lattice_k -1
expect_error "-lattice_gamma0" o.h5 $S -lattice_gamma0 -0.5
expect_error "-lattice_gamma " o.h5 -study linear -lattice_gamma 1.2
expect_error "-options_file $WORK/missing.opts" o.h5 -options_file "$WORK/missing.opts"
expect_error "-output $WORK/no/such/dir/x.h5" "$WORK/no/such/dir/x.h5" -study linear
mkdir -p adir.h5
expect_error "-output $WORK/adir.h5: is a directory" "$WORK/adir.h5" -study linear -lattice_cells 5
expect_error "-force_energy" o.h5 $S -force_energy -1
expect_error "-lattice_cubic" o.h5 -study linear -lattice_Gamma 0.5
# damping (an effect): refused by the studies that need a conservative lattice and by the integrators of u'' = a(t, u)
expect_error "-lattice_damping must lie in" o.h5 $S -lattice_damping -1
expect_error "-study continuation needs a conservative lattice; -lattice_damping 0.1 adds" o.h5 $C -lattice_damping 0.1
expect_error "-study linear (the normal modes of K) needs a conservative lattice; -lattice_damping 0.1" o.h5 -study linear -lattice_cells 5 -lattice_damping 0.1
expect_error "-study stability needs a conservative lattice; -lattice_damping 0.2" o.h5 -study stability -lattice_cells 5 -lattice_damping 0.2
expect_error "-sim_ts_type rkn integrates u'' = a(t, u); -lattice_damping 0.1" o.h5 $S -lattice_damping 0.1 -sim_ts_type rkn
expect_error "-sim_ts_type symsplit integrates u'' = a(t, u); -lattice_damping 0.1" o.h5 $S -lattice_damping 0.1 -sim_ts_type symsplit -sim_ts_dt 0.1
expect_error "-lattice_layout" o.h5 -study linear -lattice_layout sideways
expect_error "-force_profile" o.h5 $S -force_profile sideways
# misspelt, foreign and unused options: the closest known option is named
expect_error "did you mean -force_omega?" o.h5 $S -force_omgea 2.0
expect_error "did you mean -sim_t_final?" o.h5 $S -sim_tfinal 3
expect_error "did you mean -sim_ts_rtol?" o.h5 $S -sim_ts_rtoll 1e-6
expect_error "-sweep_omega_n 3: not an option of -study simulate (it belongs to -study sweep)" o.h5 $S -sweep_omega_n 3
expect_error "-nnm_orbit_rtol 0.1: not an option of -study simulate" o.h5 $S -nnm_orbit_rtol 0.1
expect_error "-sim_ts_rk_type 5dp: not used by this run" o.h5 $S -sim_ts_type euler -sim_ts_dt 0.1 -sim_ts_rk_type 5dp
# another TS type's own option is refused before any work (the sweep would otherwise fail after its last point)
expect_error "-sim_ts_rk_type 5dp: not used by this run (-sim_ts_type is symsplit; the option belongs to -sim_ts_type rk)" o.h5 $W -sim_ts_type symsplit -sim_ts_dt 0.1 -sim_ts_rk_type 5dp
expect_error "-nnm_ts_rk_type 5dp: not used by this run (-nnm_ts_type is symsplit, the default; the option belongs to -nnm_ts_type rk)" o.h5 $C -nnm_ts_rk_type 5dp
expect_error "-nnm_monodromy tsforward needs -nnm_ts_type rk (forward sensitivities); the default -nnm_ts_type is symsplit, whose tangent map is its own" o.h5 $C -nnm_monodromy tsforward
expect_error "unknown option -bogus" o.h5 -study linear -lattice_cells 5 -bogus 1
# options a study sets itself are refused, not read and overwritten
expect_error "-sim_progress is set by -study sweep" o.h5 $W -sim_progress 1
expect_error "-sim_sample_dt is set by -study zak" o.h5 -study zak -zak_energy_list 0.01 -sim_t_final 300 -lattice_cells 4 -sim_sample_dt 0.5
expect_error "-sim_t_final is set by -study stability" o.h5 -study stability -lattice_cells 5 -sim_t_final 10
expect_error "-sim_progress is set by -study perturb" o.h5 -study perturb -lattice_cells 5 -sim_progress 1
expect_error "-force_omega is set by" o.h5 $W -force_omega 2
# values: garbage, NaN, inf, wrong types
expect_error "-force_omega abc: not a real number" o.h5 $S -force_omega abc
expect_error "-lattice_cells 2.5: not an integer" o.h5 -study linear -lattice_cells 2.5
expect_error "-sim_store_u maybe: not a boolean" o.h5 $S -sim_store_u maybe
expect_error "-sim_ts_type foo" o.h5 $S -sim_ts_type foo
expect_error "-kcorr_record must lie in (0, 1e6], got inf" o.h5 $W -sweep_kcorr -kcorr_record inf
expect_error "-floquet_tol must lie in (0, 1), got inf" o.h5 $C -floquet -floquet_tol inf
expect_error "-sim_t_final must lie in \[1e-6, 1e9\], got nan" o.h5 -study simulate -sim_t_final nan
expect_error "-force_omega must lie in \[1e-6, 1e3\], got -inf" o.h5 $S -force_omega -inf
expect_error "-sweep_energy_list: values must lie in \[1e-12, 1e+12\], got nan" o.h5 $W -sweep_energy_list 1,nan
expect_error "-sim_ts_rtol 1e999: the value must be a finite number" o.h5 $S -sim_ts_rtol 1e999
expect_error "-linear_bv_orthog_eta inf: the value must be a finite number" o.h5 -study linear -lattice_cells 5 -linear_bv_orthog_eta inf
# values PETSc would silently drop or wrap: a missing value, an integer beyond 32 bits
expect_error "-lattice_k: no value given" o.h5 -study linear -lattice_cells 5 -lattice_k ""
expect_error "-perturb_delta_list: no value given" o.h5 -study perturb -lattice_cells 5 -perturb_delta_list
expect_error "-lattice_cells 4294967301: out of the integer range" o.h5 -study linear -lattice_cells 4294967301
expect_error "-sim_ts_max_steps 99999999999: out of the integer range" o.h5 $S -sim_ts_max_steps 99999999999
# ranges
expect_error "-linear_nq" o.h5 -study linear -lattice_cells 5 -linear_nq 2
# -linear_gamma_list min:max:n (the topological transition)
L="-study linear -lattice_cells 5"
expect_error "-linear_gamma_list 0.5:1: expected min:max:n" o.h5 $L -linear_gamma_list 0.5:1
expect_error "-linear_gamma_list abc: expected min:max:n" o.h5 $L -linear_gamma_list abc
expect_error "-linear_gamma_list -1:1:2.5: expected min:max:n" o.h5 $L -linear_gamma_list -1:1:2.5
expect_error "-linear_gamma_list -1:1:1: n must lie in \[2, 100000\]" o.h5 $L -linear_gamma_list -1:1:1
expect_error "-linear_gamma_list -1.5:1:5: min and max must satisfy -1 <= min < max <= 1" o.h5 $L -linear_gamma_list -1.5:1:5
expect_error "-linear_gamma_list 0.5:0.5:3: min and max must satisfy" o.h5 $L -linear_gamma_list 0.5:0.5:3
expect_error "-linear_gamma_list nan:1:3: min and max must satisfy" o.h5 $L -linear_gamma_list nan:1:3
expect_error "-linear_gamma_list -1:1:3 needs all N eigenfrequencies: N = 22 exceeds -linear_dense_max 10" o.h5 $L -linear_dense_max 10 -linear_gamma_list -1:1:3
expect_error "-linear_gamma_list -1:1:3: not an option of -study simulate (it belongs to -study linear)" o.h5 $S -linear_gamma_list -1:1:3
expect_error "-kcorr_nc" o.h5 $W -sweep_kcorr -kcorr_nc 0
expect_error "-zak_theta_tol" o.h5 -study zak -zak_energy_list 0.01 -sim_t_final 300 -lattice_cells 4 -zak_theta_tol 4
expect_error "-stability_periods" o.h5 -study stability -lattice_cells 5 -stability_periods 0
expect_error "-cont_checkpoint_seconds" o.h5 $C -cont_checkpoint_seconds -1
expect_error "-cont_bifurcations needs -floquet without -floquet_mf" o.h5 $C -cont_bifurcations
expect_error "-cont_bifurcations needs -floquet without -floquet_mf" o.h5 $C -floquet -floquet_mf -cont_bifurcations 1
expect_error "-floquet_mf_dense_max must lie in \[0, 20000\], got -1" o.h5 $C -floquet -floquet_mf -floquet_mf_dense_max -1
expect_error "-cont_bif_tol must lie in \[1e-14, 1e-2\], got 0." o.h5 $C -floquet -cont_bif_tol 0
expect_error "-cont_bif_angle_tol must lie in (0, 1), got 2." o.h5 $C -floquet -cont_bif_angle_tol 2
expect_error "-cont_bif_resonance_order must lie in \[0, 12\], got 13" o.h5 $C -floquet -cont_bif_resonance_order 13
expect_error "-cont_switch insulated: expected <branch>:<event index>" o.h5 $C -floquet -cont_switch insulated
expect_error "-cont_switch insulated:x: expected <branch>:<event index>" o.h5 $C -floquet -cont_switch insulated:x
expect_error "-cont_switch needs -cont_bifurcations" o.h5 $C -cont_switch insulated:0
expect_error "-cont_switch optical_top:0: no branch optical_top among -cont_branch" o.h5 $C -floquet -cont_switch optical_top:0
expect_error "-cont_switch insulated:5: branch insulated has 0 located events" o.h5 $C -floquet -cont_switch insulated:5
expect_error "-cont_switch_step must lie in (0, 1), got 0." o.h5 $C -floquet -cont_switch_step 0
expect_error "-cont_switch insulated:3: given twice" o.h5 $C -floquet -cont_switch insulated:3,insulated:3
# a switched family's events: only that of another -cont_switch (a period doubling's family has no _plus/_minus)
expect_error "-cont_switch insulated_bp3_plus:2: no branch insulated_bp3_plus among -cont_branch or the families of the other -cont_switch events" o.h5 $C -floquet -cont_switch insulated_bp3_plus:2
expect_error "-cont_switch insulated_pd3_minus:1: no branch insulated_pd3_minus among" o.h5 $C -floquet -cont_switch insulated:3,insulated_pd3_minus:1
# switching follows branch points and period doublings only (event 0 of the N = 22 insulated branch: a Hamiltonian-Hopf onset at E 0.62)
expect_error "-cont_switch insulated:0: that event is a Hamiltonian-Hopf (opposite signatures); branch switching follows branch points (kind 2) and period doublings (kind 3)" o.h5 -study continuation -lattice_cells 5 -cont_energy_max 1 -cont_verbose 0 -floquet -cont_switch insulated:0
expect_error "-sim_store_u_stride" o.h5 $S -sim_store_u_stride 0
expect_error "-nnm_mf_pc_parametric_weight 0" o.h5 -study continuation -lattice_cells 5 -nnm_jacobian mf -nnm_mf_pc parametric -nnm_mf_pc_parametric_weight 0
expect_error "-nnm_orbit_rtol -1" o.h5 -study continuation -lattice_cells 5 -nnm_orbit_rtol -1
# resource guard: the estimate is named before anything is allocated
expect_error "-lattice_cells must lie in 1..2500000, got 20000000" o.h5 -study simulate -lattice_cells 20000000 -sim_t_final 1000
expect_error "-linear_dense_max must lie in \[0, 10000\], got 1000000" o.h5 -study linear -lattice_cells 40000 -linear_dense_max 1000000
expect_error "dense shooting Jacobian .* more than this machine's" o.h5 -study continuation -lattice_cells 100000
expect_error "-sim_store_u: .* more than 2.5e8 values" o.h5 -study simulate -lattice_cells 100000 -sim_store_u -sim_sample_dt 0.01 -sim_t_final 1000
# files that cannot be read: missing, truncated, not HDF5, another lattice
"$NLTOPO" $C -lattice_layout interface -output small.h5 > /dev/null
head -c 3000 small.h5 > truncated.h5
head -c 5000 /dev/urandom > garbage.h5
expect_error "-cont_resume $WORK/small.h5" o.h5 $C -lattice_layout interface -lattice_cells 6 -cont_resume "$WORK/small.h5"
expect_error "-cont_resume $WORK/missing.h5" o.h5 $C -cont_resume "$WORK/missing.h5"
expect_error "-cont_resume $WORK/truncated.h5" o.h5 $C -cont_resume "$WORK/truncated.h5"
expect_error "-cont_resume $WORK/garbage.h5" o.h5 $C -cont_resume "$WORK/garbage.h5"
expect_error "-perturb_fep $WORK/missing.h5" o.h5 -study perturb -lattice_cells 5 -perturb_fep "$WORK/missing.h5"
expect_error "-perturb_fep $WORK/garbage.h5" o.h5 -study perturb -lattice_cells 5 -perturb_fep "$WORK/garbage.h5"
expect_error "-sweep_resume: no sweep file" o.h5 $W -sweep_resume
# a diverging integration (softening cubic, large burst): the time is named, no file is left
expect_error "non-finite state at t = " o.h5 -study simulate -lattice_cubic -50 -force_amplitude 5 -force_energy 1e6 \
  -sim_ts_type basicsymplectic -sim_ts_basicsymplectic_type 2 -sim_ts_dt 0.05 -sim_t_final 300

# Faults while writing, at 1, 2 and 3 ranks: a full filesystem (a 256 kB tmpfs,
# when this user may mount one) and the output directory removed mid-run.
if mkdir -p small_fs && mount -t tmpfs -o size=256k tmpfs small_fs 2> /dev/null; then
  trap 'umount "$WORK/small_fs" 2> /dev/null || true' EXIT
  for np in 1 2 3; do check_one "$np" "cannot write -output $WORK/small_fs/x.h5: needs about" "$WORK/small_fs/x.h5" -study simulate -sim_t_final 400; done
  cases=$((cases + 1))
  echo "ok: $(cat stderr.txt)"
else
  echo "skipped: disk-full case (cannot mount a tmpfs here)"
fi
for np in 1 2 3; do
  rm -rf vanish && mkdir -p vanish/d
  set +e
  # 2-9 s of run on an idle machine (3 ranks share 2 cores); the directory
  # goes as soon as the run has opened its temporary there
  tf=$(case $np in 1) echo 30000 ;; 2) echo 3000 ;; *) echo 1000 ;; esac)
  timeout 120 "$MPIEXEC" -q -n $np "$NLTOPO" -study simulate -sim_t_final $tf -sim_store_u 0 -output "$WORK/vanish/d/x.h5" > stdout.txt 2> stderr.txt &
  pid=$!
  for _ in $(seq 200); do ls vanish/d/x.h5.tmp.* > /dev/null 2>&1 && break; sleep 0.05; done
  rm -rf vanish/d
  wait $pid
  rc=$?
  set -e
  [ $rc -ne 124 ] || fail "hang at $np rank(s) after the output directory vanished"
  [ $rc -ne 0 ] || fail "exit 0 at $np rank(s) after the output directory vanished"
  [ "$(grep -c . stderr.txt)" -eq 1 ] && grep -q "cannot write -output $WORK/vanish/d/x.h5" stderr.txt || { cat stderr.txt; fail "vanished directory at $np rank(s)"; }
done
cases=$((cases + 1))
echo "ok: $(cat stderr.txt)"
[ "$cases" -ge 40 ] || fail "only $cases bad-input cases"
echo "bad input OK: $cases cases, each at 1 and 2 ranks (the write faults also at 3)"
