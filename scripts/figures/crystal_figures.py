#!/usr/bin/python3
"""Seed 002's Figs. 2-9 (and issue #14's Hertz confinement figure) as PNG from the files `granwave figures crystal` wrote into OUT_DIR.

Plots only: every number comes from granwave's analysis (study files and crystal_figures_data.h5);
nothing is measured here. Usage: /usr/bin/python3 crystal_figures.py OUT_DIR
"""
import os
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def members(path):
    """Study file -> (dict name -> column array, profile list)."""
    with h5py.File(path, "r") as f:
        names = [n.decode() if isinstance(n, bytes) else n for n in f["/members/value_names"][()]]
        vals = f["/members/values"][()]
        off = f["/members/profile_offset"][()]
        prof = f["/members/profile"][()]
        extra = {}
        if "/damping" in f:
            extra = {k: f["/damping/" + k][()] for k in ("gamma_star", "t_gamma_star", "ratio_t_gamma_t_c")}
            extra["t_c"] = f["/damping"].attrs["t_c"]
        extra["positions"] = f["/study/positions"][()]
    cols = {n: vals[:, i] for i, n in enumerate(names)}
    profiles = [prof[off[i]:off[i + 1]] for i in range(len(off) - 1)]
    return cols, profiles, extra


def group(f, g):
    d = f[g]
    out = {k: d[k][()] for k in ("time", "z_over_l0", "sigma_over_sigma0")}
    out["layers"] = {k: d["layers/" + k][()] for k in d["layers"]}
    disp = d["dispersion"]
    out["disp"] = {k: disp[k][()] for k in disp}
    out.update({k: d.attrs[k] for k in d.attrs})
    if "lattice" in d:  # lattice dynamics with rotations of the same packing (issue 15)
        lat = d["lattice"]
        out["lattice"] = {k: lat[k][()] for k in lat}
        out["lattice"]["kind"] = [x.decode() if isinstance(x, bytes) else x for x in out["lattice"]["kind"]]
    if "dispersion_window" in d:  # the spectrum before the front reaches the far end (no reflection)
        win = d["dispersion_window"]
        out["window"] = {k: win[k][()] for k in win}
        out["window"].update({k: win.attrs[k] for k in win.attrs})
    return out


DOF = ["u_x", "u_y", "u_z", "theta_x", "theta_y", "theta_z"]


def lattice_lines(ax, g):
    """Overlay the lattice branches: the ones this drive excites in red, solid where the group
    velocity is >= 0 (energy from the source towards +z; in granwave's transform a wave travelling
    to +z sits at k > 0), dotted where it is < 0; the others thin and grey. Free rotations
    (omega = 0, no tangential spring) are left out. Returns the largest frequency drawn in red."""
    lat = g.get("lattice")
    if lat is None:
        return 0.0
    l0 = g["l0"]
    kl = lat["k"] * l0
    top = 0.0
    for b in range(lat["omega"].shape[0]):
        w, vg = lat["omega"][b], lat["group_velocity"][b]
        if lat["kind"][b] == "free rotation":
            continue
        name = f"lattice {DOF[lat['dominant'][b]]} ({lat['kind'][b]})"
        if lat["excited"][b]:
            top = max(top, w.max())
            fwd = np.where(vg >= 0, w, np.nan)
            bwd = np.where(vg < 0, w, np.nan)
            ax.plot(kl, fwd, "r-", lw=0.9, label=name + ", v_g > 0")
            ax.plot(kl, bwd, "r:", lw=0.9)
        else:
            ax.plot(kl, w, "-", color="0.6", lw=0.5, label=None)
    return top


def traces(ax, g, zs, style="-", label_suffix=""):
    for z in zs:
        idx = np.where(np.isclose(g["z_over_l0"], z))[0]
        if len(idx):
            ax.plot(g["time"] * 1e3, g["sigma_over_sigma0"][:, idx[0]], style, lw=1, label=f"z/l0 = {z:g}{label_suffix}")


def spectrum(ax, g, title, ref_omega0=None, ref_label=None):
    d = g["disp"]
    if "spectrum" not in d:
        return
    # The reflection-free window when the run has one (the front reached the far end earlier).
    src = g.get("window", d)
    F = src["spectrum"]
    k, w = src["k_axis"], src["omega_axis"]
    l0 = g["l0"]
    ax.pcolormesh(k * l0, w, np.log10(F / F.max() + 1e-12), shading="auto", cmap="Greys", vmin=-4, vmax=0)
    kk = np.linspace(0, np.pi / l0, 200)
    ax.plot(kk * l0, g["omega0"] * np.sin(kk * l0 / 2), "c--", lw=0.8, label=f"sine fit omega_0 = {g['omega0']:.0f} 1/s")
    ax.plot(d["k"] * l0, d["omega_max"], "c.", ms=2, label="omega_max(k), phi = 4")
    if ref_omega0 is not None:
        ax.plot(kk * l0, ref_omega0 * np.sin(kk * l0 / 2), "b--", lw=1, label=ref_label)
    top = lattice_lines(ax, g)
    ax.set_xlabel("k l0  (F = sum u exp(-i omega t + i k z): a wave to +z at k > 0)")
    ax.set_ylabel("omega (1/s)")
    ax.set_xlim(-np.pi, np.pi)
    ax.set_ylim(0, max(1.3 * max(g["omega0"], ref_omega0 or 0), 1.1 * top))
    if "window" in g:
        title += f"  (t <= {g['window']['t_max'] * 1e3:.2f} ms)"
    ax.set_title(title, fontsize=9)
    ax.legend(fontsize=6, loc="upper left")


def main(out):
    data = h5py.File(os.path.join(out, "crystal_figures_data.h5"), "r")
    p0, damped, fig4 = group(data, "p0"), group(data, "p_damped"), group(data, "fig4")
    pf, s0, skt2, poly = group(data, "p0_friction"), group(data, "s0"), group(data, "s_kt2"), group(data, "poly_max")
    poly_max = data.attrs["poly_max"]
    zs = list(p0["z_over_l0"])

    fig, ax = plt.subplots(figsize=(6, 4))
    traces(ax, p0, zs)
    ax.set_xlabel("t (ms)"); ax.set_ylabel("sigma_zz / sigma_zz^0"); ax.set_title("Fig. 2: P wave, no damping"); ax.legend(fontsize=8)
    fig.tight_layout(); fig.savefig(os.path.join(out, "fig2.png"), dpi=120); plt.close(fig)

    fig, ax = plt.subplots(figsize=(6, 4))
    two = [z for z in zs if z in (10, 80)] if 80 in zs else zs[:2]
    traces(ax, p0, two, "--", " (gamma_0 = 0)")
    traces(ax, damped, two, "-", " (gamma_0 = 0.1 kg/s)")
    ax.set_xlabel("t (ms)"); ax.set_ylabel("sigma_zz / sigma_zz^0"); ax.set_title("Fig. 3 (left)"); ax.legend(fontsize=7)
    fig.tight_layout(); fig.savefig(os.path.join(out, "fig3_left.png"), dpi=120); plt.close(fig)

    cols, _, extra = members(os.path.join(out, "crystal_damping.h5"))
    g = cols["value"]
    order = np.argsort(g)
    fig, ax = plt.subplots(figsize=(6, 4))
    gplot = np.where(g > 0, g, np.min(g[g > 0]) / 10)  # gamma_0 = 0 drawn one decade left of the grid
    for k, z in enumerate(extra["positions"]):
        ax.semilogx(gplot[order], cols[f"amp_z{int(z)}"][order], "o-", ms=3, label=f"z/l0 = {z:g}")
        ax.axvline(extra["gamma_star"][k], color="C%d" % k, lw=0.5, ls=":")
    gs = cols["m_ij"][0] / (2 * extra["t_c"])
    ax.axvline(gs, color="k", lw=1, ls="--", label="t_gamma = 2 t_c")
    ax.set_xlabel("gamma_0 (kg/s)  [leftmost point: gamma_0 = 0]"); ax.set_ylabel("first peak |sigma - sigma_0| / sigma_0")
    ax.set_title("Fig. 3 (right): strongest decay (dotted) vs t_gamma = 2 t_c"); ax.legend(fontsize=7)
    fig.tight_layout(); fig.savefig(os.path.join(out, "fig3_right.png"), dpi=120); plt.close(fig)

    fig, ax = plt.subplots(figsize=(6, 4))
    L = fig4["layers"]
    ax.errorbar(L["z_over_l0"], L["local_speed"], yerr=L["local_speed_error"], fmt=".", ms=3, lw=0.5, label="local speed (5 layers)")
    ax.axhline(fig4["v_first_peak"], ls="--", color="k", label=f"V_p1 = {fig4['v_first_peak']:.1f} m/s")
    ax.axhline(fig4["theory_v"], ls="-", color="r", label=f"V_pz (eq. 10) = {fig4['theory_v']:.2f} m/s")
    ax.set_ylim(180, 235); ax.set_xlabel("z / l0"); ax.set_ylabel("V_p (m/s)"); ax.set_title("Fig. 4"); ax.legend(fontsize=8)
    fig.tight_layout(); fig.savefig(os.path.join(out, "fig4.png"), dpi=120); plt.close(fig)

    for name, gg, t in (("fig5_p.png", pf, "Fig. 5: P wave"), ("fig5_s.png", s0, "Fig. 5: S wave")):
        fig, ax = plt.subplots(figsize=(6, 4)); spectrum(ax, gg, t)
        fig.tight_layout(); fig.savefig(os.path.join(out, name), dpi=120); plt.close(fig)

    cols, _, _ = members(os.path.join(out, "crystal_friction.h5"))
    fig, ax = plt.subplots(figsize=(6, 4))
    for mode, mk in ((0.0, "P"), (1.0, "S")):
        sel = cols["mode_s"] == mode
        x = cols["value"][sel]
        o = np.argsort(x)
        ax.errorbar(x[o], cols["v_first_peak"][sel][o], yerr=cols["v_first_peak_err"][sel][o], fmt="o", ms=4, label=f"{mk}: first peak")
        ax.errorbar(x[o], cols["v_half_peak"][sel][o], yerr=cols["v_half_peak_err"][sel][o], fmt="s", mfc="none", ms=4, label=f"{mk}: half peak")
        ax.plot(x[o], cols["theory_v"][sel][o], "--", lw=1, label=f"{mk}: eq. (10) (no rotations)")
        if "theory_v_lattice" in cols:
            ax.plot(x[o], cols["theory_v_lattice"][sel][o], "-", lw=1, label=f"{mk}: lattice with rotations")
    ax.set_xlabel("kt / k"); ax.set_ylabel("V (m/s)"); ax.set_title("Fig. 6 (mu = 0.5)"); ax.legend(fontsize=6)
    fig.tight_layout(); fig.savefig(os.path.join(out, "fig6.png"), dpi=120); plt.close(fig)

    fig, ax = plt.subplots(figsize=(6, 4))
    spectrum(ax, skt2, "Fig. 7: S wave, kt/k = 2", pf["omega0"], "P fit, frictionless")
    fig.tight_layout(); fig.savefig(os.path.join(out, "fig7.png"), dpi=120); plt.close(fig)

    fig, ax = plt.subplots(figsize=(6, 4))
    traces(ax, p0, zs, "--", " mono")
    traces(ax, poly, zs, "-", f" Delta a = {poly_max:g} delta")
    ax.set_xlabel("t (ms)"); ax.set_ylabel("sigma_zz / sigma_zz^0"); ax.set_title("Fig. 8"); ax.legend(fontsize=7)
    fig.tight_layout(); fig.savefig(os.path.join(out, "fig8.png"), dpi=120); plt.close(fig)

    cols, _, _ = members(os.path.join(out, "crystal_poly.h5"))
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(11, 4))
    x = np.concatenate([[0.0], cols["value"]])
    vf = np.concatenate([[pf["v_first_peak"]], cols["v_first_peak"]])
    vh = np.concatenate([[pf["v_half_peak"]], cols["v_half_peak"]])
    th = np.concatenate([[pf["theory_v"]], cols["theory_v"]])
    a1.plot(x, vf, "o", label="first peak"); a1.plot(x, vh, "s", mfc="none", label="half peak"); a1.plot(x, th, "-", label="eq. (10), relaxed network")
    a1.set_xlabel("Delta a / delta"); a1.set_ylabel("V_p (m/s)"); a1.set_title("Fig. 9 (left)"); a1.legend(fontsize=8)
    spectrum(a2, poly, f"Fig. 9 (right): Delta a = {poly_max:g} delta", pf["omega0"], "monodisperse P fit")
    fig.tight_layout(); fig.savefig(os.path.join(out, "fig9.png"), dpi=120); plt.close(fig)

    # Issue #14: Hertz-Mindlin speeds against the confinement, with the theory lines (eq. (10) for
    # P, the lattice with rotations for S) and the fitted exponents of the study file.
    path = os.path.join(out, "hertz_pressure.h5")
    if os.path.exists(path):
        cols, _, _ = members(path)
        with h5py.File(path, "r") as f:
            fits = {m: dict(f["/pressure/" + m].attrs) for m in f["/pressure"]}
        fig, (a1, a2) = plt.subplots(1, 2, figsize=(11, 4))
        for mode, mk, c in ((0.0, "P", "C0"), (1.0, "S", "C1")):
            sel = cols["mode_s"] == mode
            if not np.any(sel):
                continue
            o = np.argsort(cols["value"][sel])
            d0, p0s = cols["value"][sel][o], cols["sigma0"][sel][o]
            v, th = cols["v_half_peak"][sel][o], (cols["theory_v_lattice"] if mk == "S" else cols["theory_v"])[sel][o]
            fd, fp = fits[mk]["exponent_delta"], fits[mk]["exponent_pressure"]
            a1.loglog(d0, v, "o", color=c, label=f"{mk}: half peak, n = {fd:.4f}")
            a1.loglog(d0, th, "-", color=c, lw=1, label=f"{mk}: " + ("lattice with rotations" if mk == "S" else "eq. (10)"))
            a2.loglog(p0s, v, "o", color=c, label=f"{mk}: half peak, n = {fp:.4f}")
            a2.loglog(p0s, th, "-", color=c, lw=1, label=f"{mk}: theory")
            a2.loglog(p0s, v[0] * (p0s / p0s[0]) ** (1.0 / 6.0), ":", color="k", lw=0.8)
        a1.set_xlabel("static overlap delta_0 / d"); a1.set_ylabel("V (m/s)")
        a1.set_title("Hertz-Mindlin FCC: V ~ delta_0^(1/4)"); a1.legend(fontsize=7)
        a2.set_xlabel("prestress sigma_zz^0 (Pa)"); a2.set_ylabel("V (m/s)")
        a2.set_title("V ~ p^(1/6) (dotted: slope 1/6)"); a2.legend(fontsize=7)
        fig.tight_layout(); fig.savefig(os.path.join(out, "hertz_pressure.png"), dpi=120); plt.close(fig)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else "."))
