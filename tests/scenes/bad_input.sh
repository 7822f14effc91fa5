# Bad input: one line naming the option/file/time, non-zero exit, no HDF5 file left behind.
source "$(dirname "$0")/common.bash"
fail() { echo "FAILED: $*" >&2; exit 1; }
expect_error() { # expect_error <pattern> <output file> nltopo args...
  local pattern=$1 out=$2; shift 2
  set +e
  "$NLTOPO" "$@" -output "$out" > stdout.txt 2> stderr.txt
  local rc=$?
  set -e
  [ $rc -ne 0 ] || fail "exit 0 for: $*"
  [ "$(grep -c . stderr.txt)" -eq 1 ] || { cat stderr.txt; fail "not a one-line error for: $*"; }
  grep -q -- "$pattern" stderr.txt || { cat stderr.txt; fail "error does not name '$pattern' for: $*"; }
  ls "$out"* > /dev/null 2>&1 && fail "output left behind for: $*"
  echo "ok: $(cat stderr.txt)"
}
expect_error "unknown -study nope" o1.h5 -study nope
expect_error "-lattice_cells" o2.h5 -study linear -lattice_cells 0
expect_error "-lattice_k" o3.h5 -study linear -lattice_k -1
expect_error "-lattice_gamma0" o4.h5 -study simulate -lattice_gamma0 -0.5
expect_error "-lattice_gamma " o5.h5 -study linear -lattice_gamma 1.2
expect_error "-options_file $WORK/missing.opts" o6.h5 -options_file "$WORK/missing.opts"
expect_error "-output $WORK/no/such/dir/x.h5" "$WORK/no/such/dir/x.h5" -study linear
expect_error "-force_energy" o8.h5 -study simulate -force_energy -1
expect_error "-lattice_cubic" o9.h5 -study linear -lattice_Gamma 0.5
expect_error "-nnm_mf_pc_parametric_weight 0" o11.h5 -study continuation -lattice_cells 5 -nnm_jacobian mf -nnm_mf_pc parametric -nnm_mf_pc_parametric_weight 0
expect_error "-nnm_orbit_rtol -1" o14.h5 -study continuation -lattice_cells 5 -nnm_orbit_rtol -1
"$NLTOPO" -study continuation -lattice_layout interface -lattice_cells 5 -cont_energy_max 1e-4 -cont_max_points 3 -cont_verbose 0 -output small.h5 > /dev/null
expect_error "-cont_resume $WORK/small.h5" o12.h5 -study continuation -lattice_layout interface -lattice_cells 6 -cont_energy_max 1e-4 -cont_resume "$WORK/small.h5"
expect_error "-cont_resume $WORK/missing.h5" o13.h5 -study continuation -lattice_layout interface -lattice_cells 6 -cont_resume "$WORK/missing.h5"
# a diverging integration (softening cubic, large burst): the time is named, no file is left
expect_error "non-finite state at t = " o10.h5 -study simulate -lattice_cubic -50 -force_amplitude 5 -force_energy 1e6 \
  -sim_ts_type basicsymplectic -sim_ts_basicsymplectic_type 2 -sim_ts_dt 0.05 -sim_t_final 300
echo "bad input OK"
