# Resume and overwrite rules (docs/errors.md "Resume rules"), at 1 and 2
# ranks: -sweep_resume / -cont_resume refuse a file written with other physics
# or numerics with one line naming the first differing option, and accept
# bookkeeping and extent changes; a fresh run refuses to replace the output of
# another study or of other options (the file is left byte for byte as it was)
# unless -output_overwrite is given; the same scene may be re-run into its file.
source "$(dirname "$0")/common.bash"
LIMIT=120

for np in 1 2; do
  if [ "$np" -eq 1 ]; then RUN=(timeout "$LIMIT" "$NLTOPO"); else RUN=(timeout "$LIMIT" "$MPIEXEC" -q -n 2 "$NLTOPO"); fi
  ok() { "${RUN[@]}" "$@" -options_left > ok.txt 2> ok.err || { cat ok.err; echo "FAILED (np $np): $*"; exit 1; }; }
  refused() { # refused <pattern> <file that must stay unchanged> nltopo args...
    local pattern=$1 keep=$2 rc=0
    shift 2
    cp "$keep" keep.copy
    "${RUN[@]}" "$@" > no.txt 2> no.err || rc=$?
    [ "$rc" -ne 0 ] && [ "$rc" -ne 124 ] || { cat no.err; echo "FAILED (np $np, exit $rc): $*"; exit 1; }
    [ "$(grep -c . no.err)" -eq 1 ] && grep -q -- "$pattern" no.err || { cat no.err; echo "FAILED (np $np): not one line naming '$pattern'"; exit 1; }
    cmp -s "$keep" keep.copy || { echo "FAILED (np $np): $keep was changed"; exit 1; }
    if ls ./*.tmp.* > /dev/null 2>&1; then echo "FAILED (np $np): temporary left: $(ls ./*.tmp.*)"; exit 1; fi
    echo "ok (np $np): $(cat no.err)"
  }
  study_of() { $PY "$CHECKS/resume_safety.py" study "$1"; }

  # -sweep_resume
  SW=(-study sweep -sweep_omega_n 2 -sweep_energy_n 2 -sweep_energy_min 1e-3 -sweep_energy_max 1e-2 -sim_t_final 300)
  ok "${SW[@]}" -output sw$np.h5
  refused "-sweep_resume sw$np.h5 was written without -force_tau_periods (now 20)" sw$np.h5 "${SW[@]}" -force_tau_periods 20 -sweep_resume -output sw$np.h5
  refused "-sweep_resume sw$np.h5 was written without -sim_ts_type (now cn)" sw$np.h5 "${SW[@]}" -sim_ts_type cn -sweep_resume -output sw$np.h5
  refused "-sweep_resume sw$np.h5 was written without -lattice_cubic (now 1)" sw$np.h5 "${SW[@]}" -lattice_cubic 1 -sweep_resume -output sw$np.h5
  refused "-sweep_resume sw$np.h5 was written with -sweep_energy_max 1e-2 (now 0.1)" sw$np.h5 "${SW[@]}" -sweep_energy_max 0.1 -sweep_resume -output sw$np.h5
  # bookkeeping differs, and a value written another way (1e-2 = 0.01): accepted
  ok "${SW[@]}" -sweep_energy_max 0.01 -sweep_progress 0 -sweep_checkpoint 100 -sweep_resume -output sw$np.h5
  grep -q "resuming sw$np.h5: 4 of 4 points done" ok.txt

  # -cont_resume
  CO=(-study continuation -lattice_layout interface -lattice_cells 5 -lattice_cubic 0.5 -cont_energy_max 1e-4 -cont_max_points 3 -cont_verbose 0)
  ok "${CO[@]}" -output co$np.h5
  refused "-cont_resume co$np.h5 was written with -lattice_cubic 0.5 (now 2)" co$np.h5 "${CO[@]}" -lattice_cubic 2 -cont_resume co$np.h5 -output res$np.h5
  refused "-cont_resume co$np.h5 was written without -nnm_steps_per_period (now 64)" co$np.h5 "${CO[@]}" -nnm_steps_per_period 64 -cont_resume co$np.h5 -output res$np.h5
  refused "-cont_resume co$np.h5 was written without -lattice_gamma (now 0.3)" co$np.h5 "${CO[@]}" -lattice_gamma 0.3 -cont_resume co$np.h5 -output res$np.h5
  refused "-cont_resume sw$np.h5 was written by -study sweep (now continuation)" sw$np.h5 "${CO[@]}" -cont_resume sw$np.h5 -output res$np.h5
  # a code default changed since the file was written: its effective -nnm_ts_type rk (the default before symsplit)
  cp co$np.h5 old$np.h5
  $PY "$CHECKS/resume_safety.py" code_default_changed old$np.h5
  refused "-cont_resume old$np.h5 was written with -nnm_ts_type rk, the default then (now symsplit)" old$np.h5 "${CO[@]}" -cont_resume old$np.h5 -output res$np.h5
  # a file of another output format (version 0: written before format_version existed)
  cp co$np.h5 v0$np.h5
  $PY "$CHECKS/resume_safety.py" format_version_0 v0$np.h5
  refused "-cont_resume v0$np.h5 has format_version 0 (this nltopo writes 1)" v0$np.h5 "${CO[@]}" -cont_resume v0$np.h5 -output res$np.h5
  [ ! -e res$np.h5 ] || { echo "FAILED: a refused resume wrote its -output"; exit 1; }
  # extent (-cont_energy_max, -cont_max_points) and diagnostics may change; into the same file
  ok "${CO[@]}" -lattice_cubic 5e-1 -cont_energy_max 2e-4 -cont_max_points 6 -nnm_snes_converged_reason -cont_resume co$np.h5 -output co$np.h5
  grep -q "stored tangent and step" ok.txt
  $PY "$CHECKS/resume_safety.py" resumed co$np.h5

  # overwrite: another study's complete output, then the same study with other options
  ok -study linear -output lin$np.h5
  refused "-output lin$np.h5 holds the complete output of -study linear (this run: -study simulate); choose another -output or give -output_overwrite" lin$np.h5 \
    -study simulate -sim_t_final 50 -output lin$np.h5
  ok -study linear -output lin$np.h5 # the same scene again
  refused "-output lin$np.h5 holds the complete output of a run without -lattice_cells (now 10)" lin$np.h5 -study linear -lattice_cells 10 -output lin$np.h5
  refused "-output co$np.h5 holds the complete output of a run with -cont_energy_max 2e-4 (now 1e-4)" co$np.h5 "${CO[@]}" -output co$np.h5
  ok -study simulate -sim_t_final 50 -output lin$np.h5 -output_overwrite
  [ "$(study_of lin$np.h5)" = simulate ] || { echo "FAILED: -output_overwrite did not replace lin$np.h5"; exit 1; }
  # a file that is not an nltopo output is replaced as before
  echo "not hdf5" > plain$np.h5
  ok -study linear -output plain$np.h5
  [ "$(study_of plain$np.h5)" = linear ]
done
# Issue 34, class 7: a resume state that is not finite (NaN or inf in any
# stored array of a continuation checkpoint, a sweep file or a sweep journal)
# is refused in one line, before any work, and the file is left as it was;
# NaN where a run writes it (a Floquet multiplier not computed, a sweep's kcorr
# or mcr_error) is accepted. Every array at 1 rank, a few at 2 ranks (the
# refusal is rank 0's read, made collective).
CO=(-study continuation -lattice_layout interface -lattice_cells 5 -lattice_cubic 0.5 -cont_energy_max 1e-4 -cont_max_points 3 -cont_verbose 0)
SW=(-study sweep -sweep_omega_n 2 -sweep_energy_n 2 -sweep_energy_min 1e-3 -sweep_energy_max 1e-2 -sim_t_final 300)
timeout "$LIMIT" "$NLTOPO" "${CO[@]}" -floquet -output cf.h5 > /dev/null
timeout "$LIMIT" "$NLTOPO" "${SW[@]}" -output sf.h5 > /dev/null
ARRAYS="z0 energy omega period mcr shape_corr beta newton_its krylov_its next_tangent next_ds multipliers_re multipliers_im max_modulus det_error"
FIELDS="mcr t_off nl_ratio amplitude energy_final seconds mcr_spread kcorr mcr_error"
# every corrupted copy at once (one Python start): cf_<array>_<value>.h5, sf_<field>_<value>.h5, jbad_<field>_<value>.h5 (+ .journal.0)
$PY "$CHECKS/resume_safety.py" corrupt cf.h5 continuation/insulated $(for a in $ARRAYS; do echo "$a=nan $a=inf $a=-inf"; done) period=-1
$PY "$CHECKS/resume_safety.py" corrupt sf.h5 sweep $(for f in $FIELDS; do echo "$f=nan $f=inf $f=-inf"; done)
$PY "$CHECKS/resume_safety.py" journal sf.h5 $(for f in $FIELDS; do echo "$f=nan $f=inf $f=-inf"; done)
for np in 1 2; do
  if [ "$np" -eq 1 ]; then RUN=(timeout "$LIMIT" "$NLTOPO"); else RUN=(timeout "$LIMIT" "$MPIEXEC" -q -n 2 "$NLTOPO"); fi
  refused_corrupt() { # refused_corrupt <pattern> <file> nltopo args...: one line, nothing written, the file unchanged
    local pattern=$1 keep=$2 rc=0
    shift 2
    cp "$keep" keep.copy
    rm -f out.h5
    "${RUN[@]}" "$@" > no.txt 2> no.err || rc=$?
    [ "$rc" -ne 0 ] && [ "$rc" -ne 124 ] || { cat no.err; echo "FAILED (np $np, exit $rc): $*"; exit 1; }
    [ "$(grep -c . no.err)" -eq 1 ] && grep -q -- "$pattern" no.err || { cat no.err; echo "FAILED (np $np): not one line naming '$pattern'"; exit 1; }
    cmp -s "$keep" keep.copy || { echo "FAILED (np $np): $keep was changed"; exit 1; }
    [ ! -e out.h5 ] && ! ls ./*.tmp.* > /dev/null 2>&1 || { echo "FAILED (np $np): output or temporary left"; exit 1; }
  }
  if [ "$np" -eq 1 ]; then VALUES="nan inf"; else ARRAYS="z0 next_tangent" VALUES="nan -inf" FIELDS="kcorr"; fi
  for a in $ARRAYS; do
    for v in $VALUES; do
      case $a in multipliers_* | max_modulus | det_error) [ "$v" != nan ] || continue ;; esac # NaN: not computed, accepted (below)
      refused_corrupt "-cont_resume cf_${a}_$v.h5: /continuation/insulated/$a holds $v" cf_${a}_$v.h5 \
        "${CO[@]}" -floquet -cont_max_points 5 -cont_resume cf_${a}_$v.h5 -output out.h5
    done
  done
  ok "${CO[@]}" -floquet -cont_max_points 5 -cont_resume cf_multipliers_re_nan.h5 -output out.h5
  refused_corrupt "period holds -1 at point 2, not a period" cf_period_-1.h5 "${CO[@]}" -floquet -cont_max_points 5 -cont_resume cf_period_-1.h5 -output out.h5
  for f in $FIELDS; do
    for v in $VALUES; do
      case $f in kcorr | mcr_error) [ "$v" != nan ] && what="$f = $v" || what= ;; *) what="$f = $v" ;; esac
      if [ -n "$what" ]; then
        refused_corrupt "-sweep_resume: sf_${f}_$v.h5 holds $what" sf_${f}_$v.h5 "${SW[@]}" -sweep_resume -output sf_${f}_$v.h5
        refused_corrupt "sweep journal jbad_${f}_$v.h5.journal.0, line 1: $what" jbad_${f}_$v.h5 "${SW[@]}" -sweep_resume -output jbad_${f}_$v.h5
      else # NaN where a sweep writes it
        cp sf_${f}_$v.h5 b.h5
        ok "${SW[@]}" -sweep_resume -output b.h5
        cp jbad_${f}_$v.h5 b.h5
        cp jbad_${f}_$v.h5.journal.0 b.h5.journal.0
        ok "${SW[@]}" -sweep_resume -output b.h5
        grep -q "4 of 4 points done (1 from journals)" ok.txt
      fi
    done
  done
  echo "ok (np $np): corrupted resume states refused in one line"
done

# Partial and failed runs (docs/errors.md): an error found at the end of a run
# (NLTOPO_TEST_LATE_ERROR=1, the test hook: after the computation, before the
# output is written) leaves nothing behind: no -output, partial output,
# journal, temporary or lock; a failing re-run over a complete result leaves
# it byte for byte; a failing resume leaves the partial output it continued.
# A fresh run next to a partial output is refused (it would replace it) unless
# it resumes it or is given -output_overwrite.
for np in 1 2; do
  if [ "$np" -eq 1 ]; then RUN=(timeout "$LIMIT" "$NLTOPO"); else RUN=(timeout "$LIMIT" "$MPIEXEC" -q -n 2 "$NLTOPO"); fi
  late() { # late <output> nltopo args...: fails at the end with the hook's one line
    local out=$1 rc=0
    shift
    NLTOPO_TEST_LATE_ERROR=1 "${RUN[@]}" "$@" -output "$out" -options_left > late.txt 2> late.err || rc=$?
    [ "$rc" -ne 0 ] && [ "$rc" -ne 124 ] && [ "$(grep -c . late.err)" -eq 1 ] && grep -q "NLTOPO_TEST_LATE_ERROR=1: an error after the computation" late.err ||
      { cat late.err; echo "FAILED (np $np, exit $rc): $*"; exit 1; }
  }
  left_only() { # left_only <output> [files...]: next to <output> exactly these files
    local out=$1 want have
    shift
    want=$(printf '%s\n' "$@" | sort | grep . || true)
    have=$(ls -d "$out" "$out".* 2> /dev/null | sort || true)
    [ "$have" = "$want" ] || { echo "FAILED (np $np): next to $out: '$have', expected '$want'"; exit 1; }
  }
  SWL=(-study sweep -sweep_omega_n 2 -sweep_energy_n 2 -sweep_energy_min 1e-3 -sweep_energy_max 1e-2 -sim_t_final 300 -sweep_checkpoint 1e-9)
  COL=(-study continuation -lattice_layout interface -lattice_cells 5 -lattice_cubic 0.5 -cont_energy_max 1e-4 -cont_max_points 3 -cont_verbose 0
       -cont_checkpoint_seconds 1e-9)
  # fresh runs that checkpoint, failing at the end: nothing left
  late lsw$np.h5 "${SWL[@]}"
  grep -q "points written\|computed\|nltopo sweep" late.txt
  left_only lsw$np.h5
  late lco$np.h5 "${COL[@]}"
  grep -q "checkpoint: 3 points written to lco$np.h5.partial.h5" late.txt || { cat late.txt; echo "FAILED: no checkpoint before the late error"; exit 1; }
  left_only lco$np.h5
  # an error found only at the end without the hook (here an option unused by the run's solvers): the same
  rc=0
  "${RUN[@]}" "${SWL[@]}" -sim_mat_type aij -output lnat$np.h5 > nat.txt 2> nat.err || rc=$?
  [ "$rc" -ne 0 ] && [ "$rc" -ne 124 ] && [ "$(grep -c . nat.err)" -eq 1 ] || { cat nat.err; echo "FAILED (np $np, exit $rc): -sim_mat_type aij"; exit 1; }
  left_only lnat$np.h5
  # the same scenes re-run over their complete results, failing at the end: the results unchanged
  ok "${SWL[@]}" -output lsw$np.h5
  ok "${COL[@]}" -output lco$np.h5
  cp lsw$np.h5 lsw.copy
  cp lco$np.h5 lco.copy
  late lsw$np.h5 "${SWL[@]}"
  late lco$np.h5 "${COL[@]}"
  cmp lsw$np.h5 lsw.copy && cmp lco$np.h5 lco.copy || { echo "FAILED (np $np): a failed re-run changed a complete result"; exit 1; }
  left_only lsw$np.h5 lsw$np.h5
  left_only lco$np.h5 lco$np.h5
  # a partial output next to -output (here: the complete sweep as a partial one): a fresh run is refused
  cp lsw$np.h5 lsw$np.h5.partial.h5
  refused "-output lsw$np.h5: lsw$np.h5.partial.h5 holds the partial output (complete = 0) of an earlier run; continue it with -sweep_resume, or remove it or give -output_overwrite to start afresh" \
    lsw$np.h5.partial.h5 "${SWL[@]}" -output lsw$np.h5
  cp lco$np.h5 lco$np.h5.partial.h5
  refused "continue it with -cont_resume lco$np.h5.partial.h5, or remove it" lco$np.h5.partial.h5 "${COL[@]}" -output lco$np.h5
  # a resume of it failing at the end leaves it (the sweep's rewritten with the same points)
  late lsw$np.h5 "${SWL[@]}" -sweep_resume
  grep -q "resuming lsw$np.h5.partial.h5: 4 of 4 points done" late.txt
  [ "$($PY "$CHECKS/signals.py" done_points lsw$np.h5.partial.h5)" -eq 4 ] || { echo "FAILED (np $np): the failed resume lost points"; exit 1; }
  late lco$np.h5 "${COL[@]}" -cont_resume lco$np.h5.partial.h5
  cmp lco$np.h5.partial.h5 lco.copy || { echo "FAILED (np $np): the failed resume changed its partial output"; exit 1; }
  left_only lsw$np.h5 lsw$np.h5 lsw$np.h5.partial.h5
  left_only lco$np.h5 lco$np.h5 lco$np.h5.partial.h5
  # resumed to the end: the complete output replaces the partial one; -output_overwrite discards it
  ok "${SWL[@]}" -sweep_resume -output lsw$np.h5
  left_only lsw$np.h5 lsw$np.h5
  ok "${COL[@]}" -output_overwrite -output lco$np.h5
  left_only lco$np.h5 lco$np.h5
  echo "ok (np $np): late errors leave nothing and destroy nothing; partial outputs are resumed or refused"
done
echo "resume safety scene OK"
