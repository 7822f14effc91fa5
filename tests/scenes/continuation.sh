# options/fep.opts at low energy: the five branches start at their linear
# frequencies, the file follows outputs.md, 1 and 2 ranks agree; the FEP plot draws.
source "$(dirname "$0")/common.bash"
short="-cont_energy_max 2e-4 -cont_verbose 0"
run1 -options_file "$SRC/options/linear.opts" -output lin.h5 > /dev/null
run1 -options_file "$SRC/options/fep.opts" $short -output fep1.h5 | tee out1.txt
run2 -options_file "$SRC/options/fep.opts" $short -output fep2.h5 > out2.txt
$PY "$SRC/tests/scenes/plot_check.py" "$SRC/src/plots/plot_fep.py" fep1.h5 fep.png
$PY "$SRC/tests/scenes/plot_check.py" "$SRC/src/plots/plot_floquet.py" fep1.h5 floquet.png
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
    # fep.opts shoots with the symplectic splitting: det M = 1 to rounding (Liouville), on 1 and 2 ranks
    for h in (b, g["continuation/" + name]):
        assert h["det_error"].shape == (n,) and h["det_error"][:].max() < 1e-12, (name, h["det_error"][:].max())
    c = g["continuation/" + name]
    assert c["energy"].shape == (n,), name
    assert np.abs(c["omega"][:] - b["omega"][:]).max() < 1e-9, name
    print(name, "starts at", b["omega"][0], "linear", w_lin)
print("continuation scene OK")
PYEOF
# -cont_mcr_min stops the insulated branch where it delocalizes: at N = 102 its
# MCR (0.345 for the linear mode) falls below 0.3 only as omega nears the
# optical band bottom (sqrt(3.8) = 1.94936), the paper's E ~ 12 threshold.
run1 -options_file "$SRC/options/fep.opts" -cont_branch insulated -floquet 0 -cont_energy_max 100 -cont_mcr_min 0.3 -cont_verbose 0 -output mcr.h5 > mcr.txt
$PY - <<'PYEOF'
import h5py, numpy as np
b = h5py.File("mcr.h5", "r")["continuation/insulated"]
m, w, e = b["mcr"][:], b["omega"][:], b["energy"][:]
reason = b.attrs["stop_reason"]
reason = reason.decode() if isinstance(reason, bytes) else reason
assert "-cont_mcr_min" in reason and b.attrs["reached_energy_max"] == 0, reason
assert m[-1] < 0.3 and np.all(m[:-1] >= 0.3), m
assert 1.93 < w[-1] < np.sqrt(3.8) + 0.01 and 8 < e[-1] < 13, (w[-1], e[-1])
print("-cont_mcr_min: stopped at E = %.3g, omega %.5f, MCR %.3f" % (e[-1], w[-1], m[-1]))
PYEOF
# -cont_checkpoint_seconds: a run killed mid-branch (SIGKILL, no clean-up)
# leaves a readable -output file with the points so far, consistent across
# datasets and marked complete = 0; finished runs are marked complete = 1.
"$NLTOPO" -options_file "$SRC/options/fep_long.opts" -lattice_cells 25 -cont_energy_max 100 -cont_checkpoint_seconds 1e-9 -output ck.h5 > ck.txt 2>&1 &
pid=$!
for i in $(seq 1 240); do
  sleep 0.25
  [ "$(grep -c 'checkpoint:' ck.txt || true)" -ge 3 ] && break
done
kill -9 $pid
wait $pid || true
grep -q "checkpoint:" ck.txt
$PY - <<'PYEOF'
import h5py
f = h5py.File("ck.h5", "r")
assert f.attrs["complete"] == 0
b = f["continuation/insulated"]
n = b.attrs["points"]
assert n >= 3 and b["energy"].shape == (n,) and b["z0"].shape == (n, 204) and b["multipliers_re"].shape == (n, 1) and b["stable"].shape == (n,)
reason = b.attrs["stop_reason"]
assert "checkpoint" in (reason.decode() if isinstance(reason, bytes) else reason)
assert h5py.File("fep1.h5", "r").attrs["complete"] == 1 and h5py.File("mcr.h5", "r").attrs["complete"] == 1
print("checkpoint of a killed run:", n, "points, complete = 0")
PYEOF
# The same at 2 ranks (collective checkpoint writes), run to its end: every
# checkpoint is replaced by the final file, complete = 1, no temporary left.
run2 -options_file "$SRC/options/fep_long.opts" -lattice_cells 25 -cont_energy_max 0.01 -cont_verbose 0 -cont_checkpoint_seconds 1e-9 -output ck2.h5 > ck2.txt
[ "$(grep -c 'checkpoint:' ck2.txt)" -ge 5 ]
if ls ck2.h5.tmp.* > /dev/null 2>&1; then echo "a temporary file was left behind"; exit 1; fi
$PY - <<'PYEOF'
import h5py
f = h5py.File("ck2.h5", "r")
b = f["continuation/insulated"]
assert f.attrs["complete"] == 1 and b.attrs["reached_energy_max"] == 1 and b["multipliers_re"].shape == (b.attrs["points"], 1)
print("2-rank checkpoints, then the complete file:", b.attrs["points"], "points")
PYEOF
