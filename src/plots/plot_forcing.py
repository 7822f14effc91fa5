#!/usr/bin/python3
"""The forcing profile of a -study sweep (the paper's Fig. 8a-b, for
-force_profile exponential), from /sweep/force_eta and /sweep/insulated_mode:
(a) eta_n per site, signed, with the linear insulated mode phi_n it was
    fitted to;
(b) |eta_n| and |phi_n| on a log scale with the fitted envelope
    a e^{b |n - m|} (force_exp_a, force_exp_b) through every site and the
    spec's decay -k2/k1 per cell, i.e. b = ln(k2/k1)/2 per site.
Sites are 1-based as in model.md; m = N/2 is the interface site of the
interface layout (N = 4 Nc + 2, m = 2 Nc + 1).
usage: plot_forcing.py sweep.h5 [out.png]"""
import sys
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
import nltopo_plot


def load(path):
    """/sweep of a -study sweep file with its forcing profile."""
    s = nltopo_plot.open_run(path).sweep
    if "force_eta" not in s:
        sys.exit(f"plot_forcing.py: {path} has no /sweep/force_eta (a sweep written by an older nltopo)")
    return s




def figure(s):
    eta = s.force_eta
    phi = s.insulated_mode if "insulated_mode" in s else None
    return draw(s, eta, phi)


def draw(s, eta, phi):
    N = len(eta)
    n = np.arange(1, N + 1)
    on = eta != 0
    fig, ax = plt.subplots(1, 2, figsize=(13, 4.6))

    # (a) the profile and the mode, signed
    ax[0].vlines(n[on], 0, eta[on], color=nltopo_plot.EVEN, lw=1.2)
    ax[0].plot(n[on], eta[on], "o", color=nltopo_plot.EVEN, ms=4, label=r"forcing profile $\eta_n$")
    if phi is not None:
        ax[0].plot(n, phi, "-", color="k", lw=0.8, label=r"linear insulated mode $\phi_n$")
    ax[0].axhline(0, color="0.6", lw=0.6)
    ax[0].set(xlabel="site n", ylabel=r"$\eta_n$, $\phi_n$")
    ax[0].set_title(r"(a) the forcing profile: $\eta_n = a\,e^{b|n-m|}(-1)^{n/2}$ on the even sites", fontsize=10)
    ax[0].legend(fontsize=8, loc="upper left")

    # (b) the envelopes on a log scale
    ax[1].semilogy(n[on], np.abs(eta[on]), "o", color=nltopo_plot.EVEN, ms=5, mfc="none", label=r"$|\eta_n|$")
    if phi is not None:
        floor = 1e-12 * np.abs(phi).max()  # the odd sites (zero) and round-off off the log axis
        big = np.abs(phi) > floor
        ax[1].semilogy(n[big], np.abs(phi[big]), ".", color="k", ms=4, label=r"$|\phi_n|$ (linear insulated mode)")
    title = "(b) the exponential envelope"
    if "force_exp_b" in s:
        a, b = float(s.force_exp_a), float(s.force_exp_b)
        m = N // 2
        x = np.linspace(1, N, 4 * N)
        ax[1].semilogy(x, a * np.exp(b * np.abs(x - m)), "-", color="tab:blue", lw=1, label=rf"fit $a\,e^{{b|n-m|}}$: a = {a:.4f}, b = {b:.4f}")
        title += rf"; the paper's $\gamma$ = 0.4: b = ln(3/7)/2 = {0.5 * np.log(3 / 7):.4f}"
    ax[1].set(xlabel="site n", ylabel=r"$|\eta_n|$, $|\phi_n|$")
    ax[1].set_title(title, fontsize=10)
    ax[1].legend(fontsize=8, loc="lower center")
    fig.tight_layout()
    return fig


if __name__ == "__main__":
    nltopo_plot.main_one_file(__doc__, "sweep", "forcing", load, figure, dpi=110)
