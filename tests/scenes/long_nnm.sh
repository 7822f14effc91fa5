# options/fep_long.opts (matrix-free inexact-Newton shooting with the
# averaged-stiffness preconditioner) on shortened lattices: the insulated branch
# of N = 102 and of N = 1002 on 2 ranks lie on the dense-Jacobian branch of
# N = 102 (the localized mode barely feels the lattice end) with GMRES
# iterations per Newton step that do not grow with N; the matrix-free Floquet
# multipliers of the N = 102 branch (trivial pair deflated) lead with the
# left-end edge mode's pair, b = (mu + 1/mu)/2 = cos(2 pi sqrt(3) / omega): that
# mode (omega = sqrt(3), model.md "Trap") lies where the orbit's amplitude is
# ~1e-9, so its multipliers are the linear ones, and up to E ~ 1 its b is the
# largest nontrivial |b| (N = 102 dense spectra).
source "$(dirname "$0")/common.bash"
common=(-cont_energy_max 3 -cont_verbose 0 -cont_max_change 0.2)
# the dense reference with small steps, past E = 3 (the mf branches' last step may overshoot it by ~40 %):
# interpolated to the mf points (their steps differ: inexact Newton)
# (1-rank runs two at a time: run1 ... & then wait for it, which fails the scene if the run failed)
TMPDIR=$(own_tmpdir) run1 -options_file "$SRC/options/fep.opts" -cont_branch insulated -floquet 0 -cont_energy_max 5 -cont_verbose 0 -cont_max_change 0.04 -output dense.h5 > dense.txt &
dense=$!
run1 -options_file "$SRC/options/fep_long.opts" -lattice_cells 25 -floquet 0 "${common[@]}" -output mf102.h5 > mf102.txt
run2 -options_file "$SRC/options/fep_long.opts" -lattice_cells 250 -floquet 0 "${common[@]}" -output mf1002.h5 > mf1002.txt
# the matrix-free route (forced at this N by -floquet_mf_dense_max 0; the critical selection, not the
# localized route fep_long.opts takes), with enough eigensolver restarts that every multiplier converges
run1 -options_file "$SRC/options/fep_long.opts" -lattice_cells 25 -cont_energy_max 1 -cont_verbose 0 -cont_max_change 0.2 -floquet_mf_eps_max_it 40 -floquet_mf_dense_max 0 -floquet_mf_which critical -output floquet.h5 > floquet.txt
wait $dense
# issue 20's check at N = 102: fep_long.opts as shipped to E = 20 (2N = 204 <= -floquet_mf_dense_max: the
# dense leading pairs) on 2 ranks, against the full dense analysis (-floquet_mf 0: every multiplier, SLEPc) and
# against the matrix-free route on the same branch
long20=(-options_file "$SRC/options/fep_long.opts" -lattice_cells 25 -cont_energy_max 20 -cont_checkpoint_seconds 0)
run2 "${long20[@]}" -output lead20.h5 > lead20.txt
TMPDIR=$(own_tmpdir) run1 "${long20[@]}" -floquet_mf 0 -output dense20.h5 > dense20.txt &
dense20=$!
run1 "${long20[@]}" -floquet_mf_dense_max 0 -floquet_mf_which critical -output mf20.h5 > mf20.txt
wait $dense20
# Krylov-Schur on M (largest) with these settings called a spurious |mu| = 306.9 converged at E = 1.86
# (benchmarks/README.md); the true-residual check must keep it from becoming an "unstable" verdict
TMPDIR=$(own_tmpdir) run1 "${long20[@]}" -cont_energy_max 2 -floquet_mf_dense_max 0 -floquet_mf_which largest -floquet_mf_eps_ncv 60 -floquet_mf_eps_max_it 30 -output largest.h5 > largest.txt &
largest=$!
# the localized route (-floquet_mf_which localized, fep_long.opts' own, forced at N = 202 by -floquet_mf_dense_max 0):
# a verdict at every orbit, at 1 and 2 ranks (N = 202, not 402: the same verdicts at every orbit, in half the time;
# the route's N-independence is benchmarks/README.md "Issue 35", its dense agreement unit_tests "[localized]")
loc=(-options_file "$SRC/options/fep_long.opts" -lattice_cells 50 -cont_energy_max 1 -cont_verbose 0 -cont_checkpoint_seconds 0 -floquet_mf_dense_max 0)
run1 "${loc[@]}" -output loc1.h5 > loc1.txt
wait $largest
run2 "${loc[@]}" -output loc2.h5 > loc2.txt
$PY "$CHECKS/long_nnm.py" localized
# -cont_resume on 2 ranks: the E <= 1 branch above, continued to E = 3 (with
# the numerics it was computed with: a resume refuses others), without the
# multipliers (-floquet 0: their options then do not count)
run2 -options_file "$SRC/options/fep_long.opts" -lattice_cells 25 -floquet 0 "${common[@]}" -cont_resume floquet.h5 -output resumed.h5 > resumed.txt
grep -q "resumed after point" resumed.txt
$PY "$CHECKS/long_nnm.py" branches
# -cont_resume of -floquet_mf files written before the verdicts (no floquet_route, krein or instability;
# stable = 1 meant only max |mu| <= 1 + tol): made from mf20.h5 by removing what the old files lacked
$PY "$CHECKS/long_nnm.py" make_old_files
# (at 1 rank: what is read is the old file's columns; a resume at 2 ranks is resumed.h5's above)
run1 "${long20[@]}" -cont_energy_max 30 -floquet_mf_dense_max 0 -floquet_mf_which critical -cont_resume old_mf.h5 -output resumed_mf.h5 > resumed_mf.txt
if run1 "${long20[@]}" -cont_energy_max 30 -cont_resume old_mf_noopt.h5 -output mixed.h5 > mixed.txt 2>&1; then echo "resume across routes not refused"; exit 1; fi
grep -q "computed by the matrix-free route, this run would take the dense one" mixed.txt && test ! -e mixed.h5
$PY "$CHECKS/long_nnm.py" old_file_resumed
$PY "$SRC/tests/scenes/plot_check.py" "$SRC/src/plots/plot_fep.py" floquet.h5 floquet.png > /dev/null
$PY "$SRC/tests/scenes/plot_check.py" "$SRC/src/plots/plot_floquet.py" floquet.h5 multipliers.png > /dev/null
# the figure tells the verdicts apart: matrix-free orbits are "unresolved", the dense leading pairs' unstable ones have classes
$PY "$SRC/tests/scenes/plot_check.py" "$SRC/src/plots/plot_floquet.py" mf20.h5 mf20.png > mf20_plot.txt
grep -qE "orbits by class: unresolved \(verdict_reason says why\) [0-9]+$" mf20_plot.txt
$PY "$SRC/tests/scenes/plot_check.py" "$SRC/src/plots/plot_floquet.py" lead20.h5 lead20.png > lead20_plot.txt
grep -qE "orbits by class: stable [0-9]+, unstable-extended B-B 2, unstable-localized B-E 1$" lead20_plot.txt   # the three quadruplets (full analysis: B-E, B-B, B-B)
test -s floquet.png
