# Makes the yade_periodic fixture: 2000 frictionless spheres, radii uniform in r0 (1 +- 0.15)
# (makeCloud's rRelFuzz), compressed in a periodic cell by PeriTriaxController to an isotropic
# stress of 1e5 Pa, relaxed until the unbalanced force is small, then written by yade.export.text
# (one "x y z r" line per sphere, 6 significant digits, positions unwrapped: YADE keeps them so).
# The cell (the box the importer needs, since the text has none) is printed to the log and written
# to cell.txt. Run: yade -n -x make.py > log.txt 2>&1
# log.txt is of a run started with maxUnbalanced=1e-4 whose bound was raised to 0.02 and then 0.05
# at iteration ~26500-27776 through YADE's TCP prompt (the unbalanced force halved only every 5000
# iterations on a loaded machine; the tracebacks at the end are that prompt's closed connection).
from yade import pack, export
import math

N, r0, fuzz = 2000, 5e-4, 0.15
vs = N * 4.0 / 3.0 * math.pi * r0**3 * (1 + fuzz**2)        # E[r^3] = r0^3 (1 + fuzz^2), r uniform in r0 (1 +- fuzz)
L = (vs / 0.25)**(1.0 / 3.0)                                # start at solid fraction ~ 0.25
O.periodic = True
O.cell.setBox(L, L, L)
mat = O.materials.append(FrictMat(young=1e8, poisson=0.3, frictionAngle=0.0, density=2500))
sp = pack.SpherePack()
n = sp.makeCloud((0, 0, 0), (L, L, L), rMean=r0, rRelFuzz=fuzz, num=N, periodic=True, seed=11)
sp.toSimulation(material=mat)
print('makeCloud placed', n, 'spheres in a cell of', L)

def compacted():
    print('goal reached at iter', O.iter, 'stress', triax.stress, 'unbalanced', unbalancedForce())
    O.pause()

O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb()]),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()],
                    [Law2_ScGeom_FrictPhys_CundallStrack()]),
    PeriTriaxController(label='triax', goal=(-1e5, -1e5, -1e5), stressMask=7, dynCell=True,
                        maxStrainRate=(20, 20, 20), maxUnbalanced=0.05, relStressTol=1e-3,
                        doneHook='compacted()'),
    NewtonIntegrator(damping=0.4),
    PyRunner(command='print(O.iter, triax.stress, unbalancedForce(), porosity())', iterPeriod=5000),
]
O.dt = 0.5 * PWaveTimeStep()
O.run(300000, True)
h = O.cell.hSize
print('cell hSize', [[h[i, j] for j in range(3)] for i in range(3)])
vol = sum(4.0 / 3.0 * math.pi * b.shape.radius**3 for b in O.bodies)
print('solid fraction', vol / O.cell.volume, 'iter', O.iter, 'unbalanced', unbalancedForce())
print('mean coordination', avgNumInteractions())
export.text('packing.txt')
with open('cell.txt', 'w') as f:
    f.write('# periodic cell of packing.txt: lo (0 0 0), hi:\n%.12g %.12g %.12g\n' % (h[0, 0], h[1, 1], h[2, 2]))
