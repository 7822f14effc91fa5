# options/simulate.opts: a paper-default forced run; outputs.md /simulate; MCR equal on 1 and 2 ranks to 1e-8.
source "$(dirname "$0")/common.bash"
run1 -options_file "$SRC/options/simulate.opts" -output sim1.h5 | tee out1.txt
run2 -options_file "$SRC/options/simulate.opts" -output sim2.h5 | tee out2.txt
$PY "$CHECKS/simulate.py" paper
# Strongly nonlinear E* = 10: the linear amplitude rule misses E* (the lattice
# detunes), the rescaling finds an S that reaches it inside the burst.
run1 -options_file "$SRC/options/simulate.opts" -force_energy 10 -sim_store_u 0 -output sim10.h5 > out10.txt
$PY "$CHECKS/simulate.py" strong
# Damping (-lattice_damping c, an effect): simulate honours it with an rk
# type. After the cut-off exp(-2 c (t - t_off)) <= E(t) / E* <= about
# exp(-c (t - t_off)) (the virial bound, checks/simulate.py damped); 1 and 2
# ranks agree.
run1 -options_file "$SRC/options/simulate.opts" -sim_ts_type rk -sim_store_u 0 -sim_t_final 600 -lattice_damping 0.01 -output simd1.h5 > outd1.txt
run2 -options_file "$SRC/options/simulate.opts" -sim_ts_type rk -sim_store_u 0 -sim_t_final 600 -lattice_damping 0.01 -output simd2.h5 > outd2.txt
$PY "$CHECKS/simulate.py" damped
