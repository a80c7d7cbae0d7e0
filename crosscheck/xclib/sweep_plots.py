"""A crosscheck sweep's figures (matplotlib, PNG): peaks against position, speeds against the swept
parameter, the rolling sweep's zone-edge frequency."""
from __future__ import annotations

STYLES = {"granwave": ("k", "-", "o"), "yade": ("tab:orange", "--", "s"), "liggghts": ("tab:blue", ":", "^"),
          "lammps": ("tab:red", "-.", "v")}


def _plt():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


def plot_damping(points, codes, positions, path):
    plt = _plt()
    n = len(points)
    fig, axes = plt.subplots(1, n, figsize=(3.2 * n, 3.4), sharey=True, squeeze=False)
    for ax, p in zip(axes[0], points):
        for c in codes:
            col, ls, mk = STYLES.get(c, ("gray", "-", "x"))
            ys = [p["peaks"].get(c, {}).get(z) for z in positions]
            xs = [z for z, y in zip(positions, ys) if y is not None]
            ax.plot(xs, [y for y in ys if y is not None], color=col, ls=ls, marker=mk, ms=5, label=c)
        ax.set_title("gamma_0 = %g kg/s" % p["gamma"], fontsize=9)
        ax.set_xlabel("z / l0")
    axes[0][0].set_ylabel("first-peak sigma_zz - sigma_zz(0) (Pa)")
    axes[0][0].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)


def plot_speeds(ax, pts, codes, xkey, theory_of, theory_label):
    """First-peak (filled) and half-peak (open) speeds of each code against p[xkey], and the theory's line."""
    x = [p[xkey] for p in pts]
    for c in codes:
        col, ls, mk = STYLES.get(c, ("gray", "-", "x"))
        for which, mfc in (("peak", col), ("half", "none")):
            ys = [p["speeds"].get(c, {}).get(which) for p in pts]
            xx = [xi for xi, y in zip(x, ys) if y is not None]
            ax.plot(xx, [y for y in ys if y is not None], color=col, ls=ls, marker=mk, mfc=mfc, ms=6,
                    label="%s (%s)" % (c, "first peak" if which == "peak" else "half peak"))
    th = [(p[xkey], theory_of(p)) for p in pts if theory_of(p) is not None]
    if th:
        ax.plot([t[0] for t in th], [t[1] for t in th], color="tab:green", lw=2, alpha=0.6, label=theory_label)
    ax.set_ylabel("front speed (m/s)")


def plot_friction(points, codes, modes, path):
    plt = _plt()
    fig, axes = plt.subplots(1, len(modes), figsize=(5.5 * len(modes), 4), squeeze=False)
    for ax, mode in zip(axes[0], modes):
        plot_speeds(ax, [p for p in points if p["mode"] == mode], codes, "kt_over_k", lambda p: p["theory"],
                     "granwave theory (eq. 10, affine kt)")
        ax.set_title("%s wave" % mode)
        ax.set_xlabel("kt / k")
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)


def plot_rolling(points, codes, modes, positions, path, on_velocity=False):
    """Speeds against k_r/k_t (per mode, with the lattice's long-wave speed), S first peaks against k_r/k_t
    per position (of the layer velocity when `on_velocity`), and the S ridge's zone-edge frequency against
    the branch's."""
    plt = _plt()
    fig, axes = plt.subplots(1, len(modes) + 2, figsize=(4.6 * (len(modes) + 2), 4), squeeze=False)
    axes = axes[0]
    for ax, mode in zip(axes, modes):
        key = "V_sz" if mode == "S" else "V_pz"
        plot_speeds(ax, [p for p in points if p["mode"] == mode], codes, "kr_over_kt", lambda p: p["theory"].get(key),
                     "lattice long-wave speed")
        ax.set_xscale("log")
        ax.set_title("%s wave" % mode)
        ax.set_xlabel("k_r / k_t")
        ax.legend(fontsize=6)
    mode = "S" if "S" in modes else modes[0]
    pts = [p for p in points if p["mode"] == mode]
    x = [p["kr_over_kt"] for p in pts]
    ax = axes[len(modes)]
    for c in codes:
        col, ls, mk = STYLES.get(c, ("gray", "-", "x"))
        for z in positions:
            ys = [p["peaks"].get(c, {}).get(z) for p in pts]
            xx = [xi for xi, y in zip(x, ys) if y is not None]
            ax.plot(xx, [abs(y) for y in ys if y is not None], color=col, ls=ls, marker=mk, ms=5,
                    label="%s z/l0 = %g" % (c, z))
    ax.set_xscale("log")
    ax.set_title("%s first peak" % mode)
    ax.set_xlabel("k_r / k_t")
    ax.set_ylabel("|first peak| (%s)" % ("layer velocity, m/s" if on_velocity and mode == "S" else "Pa"))
    ax.legend(fontsize=6)
    ax = axes[len(modes) + 1]
    key = "zone_edge_u_x" if mode == "S" else "zone_edge_u_z"
    th = [(p["kr_over_kt"], p["theory"].get(key)) for p in pts if p["theory"].get(key)]
    if th:
        ax.plot([t[0] for t in th], [t[1] for t in th], color="tab:green", lw=2, alpha=0.6,
                label="lattice: zone-edge translation")
    ac = [(p["kr_over_kt"], p["theory"].get("zone_edge_acoustic_u_x")) for p in pts
          if mode == "S" and p["theory"].get("zone_edge_acoustic_u_x")]
    if ac:
        ax.plot([t[0] for t in ac], [t[1] for t in ac], color="tab:purple", lw=1.5, ls="--", alpha=0.7,
                label="lattice: acoustic S branch at pi/l0")
    for c in codes:
        col, ls, mk = STYLES.get(c, ("gray", "-", "x"))
        ys = [p["ridges"].get(c, {}).get("zone_edge") for p in pts]
        xx = [xi for xi, y in zip(x, ys) if y is not None]
        ax.plot(xx, [y for y in ys if y is not None], color=col, ls=ls, marker=mk, ms=5, label=c)
    ax.set_xscale("log")
    ax.set_title("%s ridge at k = pi/l0" % mode)
    ax.set_xlabel("k_r / k_t")
    ax.set_ylabel("omega (1/s)")
    ax.legend(fontsize=6)
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)
