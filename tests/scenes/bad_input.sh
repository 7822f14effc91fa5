# Bad input (docs/errors.md "The error contract"): every case at 1 and 2 ranks, under a
# timeout, must end with exactly one line on stderr (both ranks together)
# naming the option, value or file, a non-zero exit, and neither the output
# file nor a temporary left behind. The cases here need a process: argv
# preflight, files, runs that fail after work, write faults. The options
# refused in option checking are tested in-process, at 1 and 2 ranks, by
# tests/unit/test_bad_options.cpp (the same contract).
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
  for f in "$out".tmp.* "$out".journal.* "$out".lock "$out".partial.h5; do # (an unmatched glob stays as itself)
    [ ! -e "$f" ] || fail "$f left behind at $np rank(s) for: $*"
  done
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

# argv preflight (before PETSc starts; one line from the first rank only)
expect_error "-options_file $WORK/missing.opts" o.h5 -options_file "$WORK/missing.opts"
expect_error "-lattice_cubic" o.h5 -study linear -lattice_Gamma 0.5
# a fixed step scaled so short that the run could never end (found by the fuzzer: a hang at 2 ranks)
expect_error "needs 2.5e+76 steps for -sim_t_final 5.: more than 1e+12" o.h5 $S -sim_ts_type symsplit -sim_ts_dt 0.2 -sim_dt_quartic_energy 1e-300
# a run names its study (nltopo alone prints usage: the help scene)
expect_error "no -study given (one of: linear, simulate, continuation, sweep, zak, perturb, workprecision, stability, floquet_scaling, stabilitymap, merge)" o.h5 -lattice_cells 5
# the output file
expect_error "-output $WORK/no/such/dir/x.h5" "$WORK/no/such/dir/x.h5" -study linear
mkdir -p adir.h5
expect_error "-output $WORK/adir.h5: is a directory" "$WORK/adir.h5" -study linear -lattice_cells 5
# options found unused after the run, at the end-of-run audit: the closest known option is named, the temporary removed
expect_error "did you mean -sim_ts_rtol?" o.h5 $S -sim_ts_rtoll 1e-6
expect_error "-sim_ts_rk_type 5dp: not used by this run" o.h5 $S -sim_ts_type euler -sim_ts_dt 0.1 -sim_ts_rk_type 5dp
expect_error "unknown option -bogus" o.h5 -study linear -lattice_cells 5 -bogus 1
# -study workprecision: each configuration's options used by its run
expect_error "-sim_ts_symsplit_scheme was not used by that run" o.h5 -study workprecision -sim_t_final 5 -wp_twins 1 -wp_repeats 1 -wp_configs " -sim_ts_type rk -sim_ts_symsplit_scheme bm4"
# -cont_switch events, known after the branch is continued
expect_error "-cont_switch insulated:5: branch insulated has 0 located events" o.h5 $C -floquet -cont_switch insulated:5
# switching follows branch points and period doublings only (event 0 of the N = 22 insulated branch: a Hamiltonian-Hopf onset at E 0.62)
expect_error "-cont_switch insulated:0: that event is a Hamiltonian-Hopf (opposite signatures); branch switching follows branch points (kind 2) and period doublings (kind 3)" o.h5 -study continuation -lattice_cells 5 -cont_energy_max 1 -cont_verbose 0 -floquet -cont_switch insulated:0
# -cont_codim2: malformed, a kind that bounds no region of stability (4, 6), a branch not continued, outside its bounds (before any branch is computed); an event the branch lacks
expect_error "-cont_codim2 insulated:fold: expected <branch>:<kind>@<omega>" o.h5 $C -floquet -cont_codim2 insulated:fold
expect_error "-cont_codim2 insulated:4@2: kinds 4 (Krein collision, a pass) and 6 (internal resonance) are not boundaries of stability" o.h5 $C -floquet -cont_codim2 insulated:4@2
expect_error "-cont_codim2 interface:fold@2: no branch interface among -cont_branch" o.h5 $C -floquet -cont_codim2 interface:fold@2
expect_error "-cont_codim2 insulated_bp3_plus:pd@2: no branch insulated_bp3_plus among -cont_branch or the families of -cont_switch" o.h5 $C -floquet -cont_codim2 insulated_bp3_plus:pd@2
expect_error "-cont_codim2 insulated:fold@2: the run's -lattice_gamma 0.4 lies outside \\[-cont_codim2_min 0.5" o.h5 $C -floquet -cont_codim2 insulated:fold@2 -cont_codim2_min 0.5
expect_error "-cont_codim2 needs -cont_bifurcations" o.h5 $C -cont_codim2 insulated:fold@2
expect_error "-cont_codim2 insulated:fold@2: branch insulated has no energy folds among its 0 located events" o.h5 $C -floquet -cont_codim2 insulated:fold@2
# resource guard: the estimate is named before the dense Jacobian is allocated
expect_error "dense shooting Jacobian .* more than this machine's" o.h5 -study continuation -lattice_cells 100000
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
[ "$cases" -ge 20 ] || fail "only $cases bad-input cases"
echo "bad input OK: $cases cases, each at 1 and 2 ranks (the write faults also at 3)"

# Unknown options and the resource guards the options decide: refused before
# any set-up, at 1 and 2 ranks; -log_view shows no stage but the Main Stage.
for args in "-study simulate -lattice_cells 25000 -forc_energy 0.5" "-study continuation -lattice_cells 100000"; do
  for np in 1 2; do
    check_one "$np" "unknown option -forc_energy\|dense shooting Jacobian" o.h5 $args -log_view
    grep -q "Main Stage" stdout.txt || fail "no -log_view at $np rank(s) for: $args"
    ! grep -qE "^ +[0-9]+: +(Setup|Solve|Write):" stdout.txt || fail "a stage beyond the Main Stage entered at $np rank(s) for: $args"
  done
  echo "ok (Main Stage only): $(cat stderr.txt)"
done

# The command line and options files as PETSc reads them (core/options_input.hpp):
# a syntax problem is one line naming the file and line, an include cycle
# ends, a stray word is an error, at 1 and 2 ranks.
printf -- '-options_file cyc_b.opts\n' > cyc_a.opts
printf -- '-lattice_k 1\n-options_file cyc_a.opts\n' > cyc_b.opts
expect_error "options file cyc_b.opts line 2: options files include each other (cyc_a.opts -> cyc_b.opts -> cyc_a.opts)" o.h5 -options_file cyc_a.opts
printf '\xef\xbb\xbf-study linear\n' > bom.opts
expect_error "options file bom.opts line 1: the file starts with a UTF-8 byte-order mark" o.h5 -options_file bom.opts
printf -- '-study linear\n-options_file gone.opts\n' > nest.opts
expect_error "options file nest.opts line 2: cannot read options file gone.opts: No such file or directory" o.h5 -options_file nest.opts
printf -- '-study linear -lattice_cells 5\n' > two.opts
expect_error "options file two.opts line 1: two options on one line" o.h5 -options_file two.opts
expect_error "command line: '1' is neither an option nor an option's value (after -sweep_energy_list 0.1,)" o.h5 $W -sweep_energy_list 0.1, 1
PETSC_OPTIONS='-output my\ file.h5' expect_error "PETSC_OPTIONS: 'file.h5' is neither an option nor an option's value" o.h5 -study linear -lattice_cells 5
PETSC_OPTIONS='-options_file gone.opts' expect_error "PETSC_OPTIONS: cannot read options file gone.opts" o.h5 -study linear -lattice_cells 5
# a file on a pipe is read once, whole (it was drained, and the run used the default lattice)
"$NLTOPO" -options_file <(printf -- '-study linear\n-lattice_cells 7\n') -output pipe1.h5 > stdout.txt 2> stderr.txt || { cat stderr.txt; fail "an options file on a pipe"; }
grep -q "Nc = 7" stdout.txt || fail "an options file on a pipe was not read"
printf -- '-study linear\n-lattice_cells 7\n' | "$MPIEXEC" -q -n 2 "$NLTOPO" -options_file /dev/stdin -output pipe2.h5 > stdout.txt 2> stderr.txt || { cat stderr.txt; fail "-options_file /dev/stdin at 2 ranks"; }
grep -q "Nc = 7" stdout.txt || fail "-options_file /dev/stdin at 2 ranks was not read"
! ls "${TMPDIR:-/tmp}"/nltopo-options-* > /dev/null 2>&1 || fail "the copy of a piped options file was left behind"
echo "ok: options files on a pipe and /dev/stdin, at 1 and 2 ranks"
# ranks started with different options: one line, no hang, no file
set +e
timeout 60 "$MPIEXEC" -q -n 1 "$NLTOPO" $S -output mpmd.h5 : -n 1 "$NLTOPO" $S -output mpmd.h5 -force_omega abc > stdout.txt 2> stderr.txt
rc=$?
set -e
[ $rc -ne 124 ] || fail "hang: ranks started with different options"
[ $rc -ne 0 ] && [ "$(grep -c . stderr.txt)" -eq 1 ] && grep -q "rank 1 was started with other options than rank 0" stderr.txt || { cat stderr.txt; fail "ranks started with different options"; }
! ls mpmd.h5* > /dev/null 2>&1 || fail "ranks started with different options left a file"
echo "ok: $(cat stderr.txt)"
