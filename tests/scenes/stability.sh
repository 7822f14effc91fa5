# The stability study on three insulated-branch orbits for 3000 periods (one
# invocation, about 20 s): the linear limit sqrt(3) and omega = 2.2 (E ~ 100,
# inside the stable window 1.941..2.331 of docs/studies/continuation.md) must be
# Floquet-stable AND persist; omega = 2.5 (E ~ 270, past the E-E instability
# that starts at omega 2.43) must be Floquet-unstable through a real multiplier,
# its perturbation must grow at the Floquet rate, and the standing wave must
# be lost within 3000 periods; a perturbation of 1e-8 along its unstable eigenvector, run
# beside the orbit (-stability_growth_periods), grows at ln|mu| per period.
source "$(dirname "$0")/common.bash"
run1 -options_file "$SRC/options/stability.opts" -stability_omega 1.7320508075688772,2.2,2.5 -stability_periods 3000 \
     -stability_sample_periods 1 -stability_growth_periods 40 -sim_progress 0 -output st.h5 | tee out.txt
$PY "$CHECKS/stability.py" three_orbits
$PY "$SRC/tests/scenes/plot_check.py" "$SRC/src/plots/plot_stability.py" st.h5 st.png
# Issue 34, class 8: a frequency between the linear one and the branch's first orbit
# (cells 5: the first orbit, at E = 1e-5, has omega 1.7354) is that orbit, said on
# stderr and in the file (omega_replaced = 1); one below the linear frequency is refused.
run1 -study stability -lattice_cells 5 -stability_omega 1.7320508075688772,1.75 -stability_periods 20 -stability_sample_periods 2 -output sl.h5 \
  > sl.txt 2> sl.err
[ "$(grep -c . sl.err)" -eq 1 ] && grep -q "^nltopo: warning: -stability_omega 1.73205081 lies between the linear frequency 1.73205081 and the branch's first orbit" sl.err \
  || { cat sl.err; echo "FAILED: no one-line warning for the replaced frequency"; exit 1; }
$PY "$CHECKS/stability.py" replaced
