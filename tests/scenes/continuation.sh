# options/fep.opts at low energy: the five branches start at their linear
# frequencies, the file follows outputs.md, 1 and 2 ranks agree; the FEP plot draws.
source "$(dirname "$0")/common.bash"
short="-cont_energy_max 2e-4 -cont_verbose 0"
run1 -options_file "$SRC/options/linear.opts" -output lin.h5 > /dev/null
run1 -options_file "$SRC/options/fep.opts" $short -output fep1.h5 | tee out1.txt
run2 -options_file "$SRC/options/fep.opts" $short -output fep2.h5 > out2.txt
$PY "$SRC/src/plots/plot_fep.py" fep1.h5 fep.png
$PY - <<'PYEOF'
import h5py, numpy as np
lin = h5py.File("lin.h5", "r")["linear"].attrs
f, g = h5py.File("fep1.h5", "r"), h5py.File("fep2.h5", "r")
assert f.attrs["study"] in (b"continuation", "continuation")
N = 102
expect = {"insulated": lin["insulated_omega"], "interface": lin["interface_omega"], "acoustic_top": lin["acoustic_top"],
          "optical_bottom": lin["optical_bottom"], "optical_top": lin["optical_top"]}
for name, w_lin in expect.items():
    b = f["continuation/" + name]
    n = b["energy"].shape[0]
    for d in ("energy", "omega", "period", "mcr", "newton_its"):
        assert b[d].shape == (n,), (name, d)
    assert b["z0"].shape == (n, 2 * N)
    assert b.attrs["reached_energy_max"] == 1, name
    assert abs(b["energy"][0] - 1e-5) < 1e-11
    assert abs(b["omega"][0] - w_lin) < 1e-6 * w_lin, (name, b["omega"][0], w_lin)
    assert np.allclose(b["period"][:] * b["omega"][:], 2 * np.pi)
    for d in ("multipliers_re", "multipliers_im", "krein"):
        assert b[d].shape == (n, 2 * N), (name, d)
    assert b["krein"].dtype.kind == "i" and b["stable"].dtype.kind == "i" and b["instability"].dtype.kind == "i"
    assert b["stable"][0] == 1 and abs(b["max_modulus"][0] - 1) < 1e-6, name   # the linear limit is stable
    c = g["continuation/" + name]
    assert c["energy"].shape == (n,), name
    assert np.abs(c["omega"][:] - b["omega"][:]).max() < 1e-9, name
    print(name, "starts at", b["omega"][0], "linear", w_lin)
print("continuation scene OK")
PYEOF
