#!/usr/bin/python3
"""A cost model of one step of a 10^7-particle crystal on 64-1024 MPI ranks (issue 16 item 3):
granwave's slab decomposition along z against LAMMPS' 3-D domain decomposition of the same crystal.

  /usr/bin/python3 bench/mpi_model.py [--latency 2e-6] [--bandwidth 10e9] [--friction]
      [--sample-every 5] [--markdown]

The interconnect is stated, not measured: --latency (alpha, s per message, MPI small-message
latency of an InfiniBand-class network) and --bandwidth (B, bytes/s per link and direction).
Everything else comes from measurements on this machine (docs/benchmarks.md, bench_crystal,
bench/side_by_side.py, bench/mpi_crystal.py) and from the code (message sizes):

granwave, slab of nl/R layers per rank, h = 1 halo layer (docs/design.md §2.8), per step:
  compute     (N/R) (t_p + t_s / every)      t_p: ns per particle-step of one rank's share;
                                             t_s: ns per particle of one sample's observers
  duplicates  4 n_xy t_c                     the contacts to the layer below, evaluated by both ranks
  halo        2 (alpha + 8 f n_xy / B)       two MPI_Sendrecv; f = 6 doubles (x, v), 9 with omega
  trigger     ceil(log2 R) alpha             MPI_Allreduce MAX of the largest displacement
  per sample  6 ceil(log2 R) alpha + (4 + 6) 8 nl / B   (every --sample-every steps)
              the energies' per-layer values to every rank (Allgather of the counts, Allgatherv),
              the layer rows to rank 0 (Gather of the counts, Gatherv), the coordination counts
              (Allgather of the counts and of the values)
LAMMPS, R sub-boxes of N/R particles (cubes where the crystal allows), newton on, per step:
  compute     (N/R) t_p,LAMMPS
  ghosts      rho ((L + 2 r_c)^3 - L^3) for a cube of side L = (N / (R rho))^(1/3), r_c = d + skin
              (the deck's skin 0.2 a); a slab-shaped box when the crystal is thinner than L
  comm        12 alpha + ghosts (72 + 48) / B  forward x, v, omega (comm_modify vel yes, 6 swaps)
              and reverse f, torque (newton on, 6 swaps)
Not modelled (both codes): load imbalance, neighbour-list rebuilds (none in these wave runs),
output beyond the per-sample messages, memory bandwidth contention between ranks of one node.
"""
import argparse
import math

D = 1.0  # lengths in diameters
RHO = math.sqrt(2.0)  # FCC particles per d^3 (d' = d (1 - 1e-3) taken as d)

# Measured on this machine, one thread (docs/benchmarks.md; bench_crystal passes alone):
# ns per particle-step by particles per rank (small: cache-resident, large: 320 000 particles),
# ns per contact evaluation.
GRANWAVE = {False: dict(t_small=37.0, t_large=56.6, t_c=3.4), True: dict(t_small=97.0, t_large=149.0, t_c=11.5)}
# One sample's observers (layer stress, coordination, energies) per particle, 4 x 4 x 200 crystal:
# (97 + 26 + 31 + 12 + 13) us / 3200 (bench_crystal "sample:", with friction).
T_SAMPLE = 56.0
# LAMMPS 29 Sep 2021, gran/hooke (frictionless) and gran/hooke/history (kt = k), one process:
# CPU time per particle-step of the whole run (bench/side_by_side.py, docs/benchmarks.md).
LAMMPS = {False: 252.0, True: 392.0}
# cells = [nx, ny, layers] as in a case file: nx ny particles per layer, layers l0 = d/sqrt(2) apart.
SHAPES = [("column 50 x 50 x 4000", 50 * 50, 4000), ("block 224 x 224 x 200", 224 * 224, 200)]


def granwave_step(n, n_xy, nl, R, fr, a, B, every):
    g = GRANWAVE[fr]
    per_rank = n / R
    t_p = g["t_small"] if per_rank <= 40000 else g["t_large"]
    comp = per_rank * (t_p + T_SAMPLE / every) * 1e-9
    if R == 1:
        return comp, comp, 0.0
    f = 9 if fr else 6
    comm = 4 * n_xy * g["t_c"] * 1e-9 + 2 * (a + 8 * f * n_xy / B) + math.ceil(math.log2(R)) * a
    comm += (6 * math.ceil(math.log2(R)) * a + (4 + 6) * 8 * nl / B) / every
    return comp + comm, comp, comm


def lammps_step(n, n_xy, nl, R, fr, a, B):
    comp = n / R * LAMMPS[fr] * 1e-9
    if R == 1:
        return comp, comp, 0.0
    r_c = D + 0.1 * D  # 2a + skin 0.2 a = d + 0.1 d
    v = n / (R * RHO)
    side = v ** (1.0 / 3.0)
    height = nl * D / math.sqrt(2.0)
    width = math.sqrt(n_xy) * D
    if side > height or side > width:  # a thin crystal: boxes as flat as it is
        hz = min(height, side)
        hx = math.sqrt(v / hz)
        ghosts = RHO * ((hx + 2 * r_c) ** 2 * (hz + (2 * r_c if hz < height else 0.0)) - hx * hx * hz)
    else:
        ghosts = RHO * ((side + 2 * r_c) ** 3 - side ** 3)
    comm = 12 * a + ghosts * (72 + 48) / B
    return comp + comm, comp, comm


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--latency", type=float, default=2e-6)
    ap.add_argument("--bandwidth", type=float, default=10e9)
    ap.add_argument("--friction", action="store_true")
    ap.add_argument("--sample-every", type=int, default=5)
    ap.add_argument("--markdown", action="store_true")
    a = ap.parse_args()
    fr = a.friction
    print("10^7 particles, %s; interconnect: latency %.3g us, bandwidth %.3g GB/s; a sample every %d steps" %
          ("kt = k (friction)" if fr else "frictionless", a.latency * 1e6, a.bandwidth / 1e9, a.sample_every))
    print("\n| crystal (cells) | R | granwave slabs: ms/step (of it comm.) | compute share | particle-steps/s | "
          "LAMMPS 3-D: ms/step (comm.) | compute share | particle-steps/s | granwave / LAMMPS |")
    print("|---|---|---|---|---|---|---|---|---|")
    for name, n_xy, nl in SHAPES:
        n = n_xy * nl
        for R in (64, 128, 256, 512, 1024):
            lt, _, lc = lammps_step(n, n_xy, nl, R, fr, a.latency, a.bandwidth)
            lcol = "%.3f (%.3f) | %.0f %% | %.2e" % (lt * 1e3, lc * 1e3, 100 * (lt - lc) / lt, n / lt)
            if R > nl:
                print("| %s | %d | more ranks than layers: refused | | | %s | |" % (name, R, lcol))
                continue
            gt, _, gc = granwave_step(n, n_xy, nl, R, fr, a.latency, a.bandwidth, a.sample_every)
            print("| %s | %d | %.3f (%.3f) | %.0f %% | %.2e | %s | %.1fx |" %
                  (name, R, gt * 1e3, gc * 1e3, 100 * (gt - gc) / gt, n / gt, lcol, lt / gt))


if __name__ == "__main__":
    main()
