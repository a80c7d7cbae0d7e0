# Writes start.data for make.liggghts: 2000 spheres at random centres in a periodic box at solid
# fraction 0.15, radii uniform in r0 (1 +- 0.15), density 2500 kg/m^3 (atom_style granular rows:
# id type diameter density x y z). Run: /usr/bin/python3 start.py
import math
import random

N, r0, fuzz, phi0 = 2000, 5e-4, 0.15, 0.15
rng = random.Random(2024)
radii = [r0 * (1 - fuzz + 2 * fuzz * rng.random()) for _ in range(N)]
L = (sum(4 / 3 * math.pi * r**3 for r in radii) / phi0) ** (1 / 3)
with open("start.data", "w") as f:
    f.write("start of the liggghts_periodic fixture (start.py)\n\n%d atoms\n1 atom types\n\n" % N)
    for ax in "xyz":
        f.write("0 %.12g %slo %shi\n" % (L, ax, ax))
    f.write("\nAtoms\n\n")
    for i, r in enumerate(radii):
        f.write("%d 1 %.12g 2500 %.12g %.12g %.12g\n" % (i + 1, 2 * r, rng.random() * L, rng.random() * L, rng.random() * L))
print("box", L)
