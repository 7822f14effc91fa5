# options/fep_long.opts (matrix-free shooting with the linear-lattice
# preconditioner) on shortened lattices: the insulated branch of N = 1002 on 2
# ranks equals the dense-Jacobian branch of N = 102 (the localized mode barely
# feels the lattice end) with GMRES iterations per Newton step that do not grow
# with N; the matrix-free Floquet multipliers of the N = 102 branch are on the
# unit circle where the dense route calls the orbits stable.
source "$(dirname "$0")/common.bash"
common=(-cont_energy_max 3 -cont_verbose 0 -cont_max_change 0.2)
run1 -options_file "$SRC/options/fep.opts" -cont_branch insulated -floquet 0 "${common[@]}" -output dense.h5 > dense.txt
run1 -options_file "$SRC/options/fep_long.opts" -lattice_cells 25 -floquet 0 "${common[@]}" -output mf102.h5 > mf102.txt
run2 -options_file "$SRC/options/fep_long.opts" -lattice_cells 250 -floquet 0 "${common[@]}" -output mf1002.h5 > mf1002.txt
run1 -options_file "$SRC/options/fep_long.opts" -lattice_cells 25 -cont_energy_max 0.01 -cont_verbose 0 -output floquet.h5 > floquet.txt
$PY - <<'PYEOF'
import h5py, numpy as np
g = lambda f: h5py.File(f, "r")["continuation/insulated"]
D, A, B, F = g("dense.h5"), g("mf102.h5"), g("mf1002.h5"), g("floquet.h5")
for X in (A, B):
    assert X.attrs["reached_energy_max"] == 1
    # same orbits as the dense route: compare the points of equal energy (the step control is the same)
    ed, wd = D["energy"][:], D["omega"][:]
    matched = 0
    for e, w in zip(X["energy"][:], X["omega"][:]):
        k = np.argmin(np.abs(ed - e))
        if abs(ed[k] - e) < 1e-6 * e:
            assert abs(w - wd[k]) < 1e-6 * wd[k], (e, w, wd[k])
            matched += 1
    assert matched >= 20, matched
    per_newton = X.attrs["krylov_iterations"] / X["newton_its"][:].sum()
    assert per_newton < 20, per_newton
    print("mf branch:", len(X["energy"]), "points,", matched, "equal to the dense N = 102 branch to 1e-6; GMRES per Newton step", round(per_newton, 1))
ka, kb = A.attrs["krylov_iterations"], B.attrs["krylov_iterations"]
assert kb <= 1.2 * ka + 10, (ka, kb)   # N = 1002 needs no more Krylov iterations than N = 102
mm = F["max_modulus"][:]
assert F["multipliers_re"].shape == (len(mm), 2)
assert np.all(np.abs(mm - 1) < 1e-4) and np.all(F["stable"][:] == 1), mm
print("matrix-free Floquet, E <= 0.01: max |mu| - 1 =", np.abs(mm - 1).max())
PYEOF
$PY "$SRC/src/plots/plot_fep.py" floquet.h5 floquet.png > /dev/null
test -s floquet.png
