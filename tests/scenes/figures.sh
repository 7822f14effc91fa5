# figures/make_all.sh, every figure of the paper (README.md "Figures of the
# paper"), at its tiny test size: each figure's runs finish, every PNG is
# written and drawn through plot_check.py (data in every panel, limits that
# cover it, axis labels, legends that name the series), and the timing table
# lists every figure and the total. The panels drawn beside the studies' own
# results: Fig. 5a-b's simulate runs repeat zak runs exactly and show the
# linear phases at the lowest E*; Fig. 8a-b's profile is the exponential fit
# the sweep ran with. NLTOPO_FIG_SIZE=small (the default of make_all.sh,
# ~2.5 min) or paper (~5.5 min, beyond this test's TIMEOUT: run make_all.sh
# itself) runs the real sizes instead:
#   NLTOPO_FIG_SIZE=small ctest -R scene_figures
source "$(dirname "$0")/common.bash"
SIZE=${NLTOPO_FIG_SIZE:-test}
if ! FIG_SIZE=$SIZE FIG_OUT="$WORK/out" NLTOPO="$NLTOPO" bash "$SRC/figures/make_all.sh"; then
  for log in out/logs/*.log; do echo "--- $log (end)"; tail -15 "$log"; done
  exit 1
fi
cat out/timings.md
pngs=(fig2_linear_modes fig3_fep fig4ab_floquet fig4c_stability fig5ab_zak_runs fig5cd_zak fig6_sweep fig7_time_histories fig8ab_forcing
  fig8c_exponential fig9_perturb)
for png in "${pngs[@]}"; do
  [ -s "out/$png.png" ] || { echo "make_all.sh wrote no out/$png.png"; exit 1; }
done
# every figure was drawn through plot_check.py: one "limits cover them" line per panel
for n in 2 3 4 5 6 7 8 9; do
  panels=$(grep -c "limits cover them" "out/logs/fig$n.log" || true)
  [ "$panels" -ge 2 ] || { echo "figure $n: plot_check.py checked $panels panels"; cat "out/logs/fig$n.log"; exit 1; }
  grep -q "^| $n | .* | ok |$" out/timings.md || { echo "figure $n missing from timings.md"; exit 1; }
done
grep -q '^| \*\*total\*\* |.*| 0 failed |$' out/timings.md
# the panels drawn from runs the zak study does not store (5a-b) and from the profile the sweep writes (8a-b)
for script in plot_zak_runs plot_forcing; do
  panels=$(grep -c "^$script.py: panel .*limits cover them" out/logs/fig*.log | awk -F: '{ s += $2 } END { print s }')
  [ "$panels" -eq 2 ] || { echo "$script.py: plot_check.py checked $panels panels, expected (a) and (b)"; exit 1; }
done
$PY - "$SRC/src/plots" <<'PYEOF'
import glob
import sys
import h5py
import numpy as np
sys.path.insert(0, sys.argv[1])
import nltopo_plot
# Fig. 5a-b: each simulate run repeats a zak run: its E* on the zak grid, the same
# MCR, and the plot's dimer phases over the zak windows give the zak window medians
z = h5py.File("out/data/zak.h5", "r")["zak"]
runs = sorted(glob.glob("out/data/zak_run_*.h5"))
assert len(runs) >= 4, runs
low = {}
for name in runs:
    S = h5py.File(name, "r")["simulate"]
    edge = "0" if S.attrs["omega_ext"] == z.attrs["omega0"] else "pi"
    assert S.attrs["omega_ext"] == z.attrs["omega" + edge], name
    k = int(np.flatnonzero(z["energy"][:] == S.attrs["energy_star"])[0])  # exactly a grid energy
    mcr_zak = z["mcr" + edge][k]
    assert abs(S.attrs["mcr"] - mcr_zak) <= 1e-9 * mcr_zak, (name, S.attrs["mcr"], mcr_zak)
    t, u, w = S["t"][:], S["u"][:], S.attrs["omega_ext"]
    zwin = z["phi%s_window_median" % edge][k]
    wins = nltopo_plot.zak_windows(t, S.attrs["t_off"], int(z.attrs["samples_per_period"]), len(zwin))
    med = [np.median(nltopo_plot.dimer_phases(t[i], u[i], w)) for i in wins]
    assert np.allclose(med, zwin, rtol=0, atol=1e-6), (name, med, zwin)
    if k == 0:
        low[edge] = med[-1]
print("fig 5a-b: %d runs repeat the zak runs (MCR to 1e-9, window medians to 1e-6); lowest E*: phi_0 = %.4f, phi_pi = %.4f" % (len(runs), low["0"], low["pi"]))
assert abs(low["0"]) < 0.1 and abs(low["pi"] - np.pi) < 0.1, low  # in phase at mu = 0, out of phase at mu = pi
# Fig. 8a-b: the profile the exponential sweep ran with: a e^{b |n - m|} (-1)^{n/2} on the
# even sites (1-based n, m = N/2), b = ln(k2/k1)/2 at the defaults, equal to the linear insulated mode there
s = h5py.File("out/data/sweep_exponential.h5", "r")["sweep"]
eta, phi = s["force_eta"][:], s["insulated_mode"][:]
a, b = s.attrs["force_exp_a"], s.attrs["force_exp_b"]
N = len(eta)
n = np.arange(1, N + 1)
even = n % 2 == 0
assert not eta[~even].any()
assert np.allclose(eta[even], a * np.exp(b * np.abs(n[even] - N // 2)) * (-1.0) ** (n[even] // 2), rtol=1e-12, atol=0)
assert abs(b - 0.5 * np.log(3 / 7)) < 1e-8, b
assert np.abs(eta - phi).max() < 1e-6 * np.abs(phi).max(), np.abs(eta - phi).max()
print("fig 8a-b: eta on the %d even sites, a = %.6f, b = %.6f, max |eta - phi| = %.2g" % (even.sum(), a, b, np.abs(eta - phi).max()))
PYEOF
# a figure that fails is reported (its row, the exit status) and the others go on
set +e
FIG_SIZE=$SIZE FIG_OUT="$WORK/bad" FIG_ONLY="2 1" NLTOPO="$NLTOPO" bash "$SRC/figures/make_all.sh" > bad.txt 2>&1
rc=$?
set -e
cat bad.txt
[ $rc -eq 1 ] && [ -s bad/fig2_linear_modes.png ] && grep -q "no figure 1" bad.txt || { echo "make_all.sh with an unknown figure: exit $rc"; exit 1; }
echo "figures scene OK ($SIZE)"
