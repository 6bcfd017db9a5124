"""The paper's assembly (SI): five sizes from 0.135 to 0.4 mm, number mean 0.26 mm, 3620
spheres in a 4.3 mm periodic cube at a solid fraction of ca. 0.5, the density scaled by 1e12
(docs/specimen.md)."""

D_MIN = 0.135e-3          # smallest diameter [m]
D_MAX = 0.4e-3            # largest diameter [m]
D_MEAN = 0.26e-3          # number-mean diameter [m]
N_SIZES = 5
N_PAPER = 3620            # number of spheres
L_PAPER = 4.3e-3          # side of the periodic cube [m]
PHI_PAPER = 0.5           # "solid fraction ca. 0.5"
DENSITY = 2650e12         # 2650 kg/m^3 scaled by 1e12 (paper)

SCALES = {"paper": N_PAPER, "quick": 500}
