/* ----------------------------------------------------------------------
   fix cell/servo: the cell. What the servo measures every step (the contact stress, the
   affine stiffness and contact statistics from the pair's tallies), and how the cell deforms:
   h <- exp(L dt) h about the fixed box centre with the atoms remapped affinely, L the
   upper-triangular velocity gradient of the commanded strain rates (docs/theory.md §5.1,
   §10.1-10.2), tilts flipped past half a box length as fix deform's 'flip yes' does (§10.3).
   The kinematics are plugin/core/cell_kinematics.hpp; this file moves LAMMPS's box.
------------------------------------------------------------------------- */

#include "fix_cell_servo.h"
#include "cell_tally.h"

#include "cell_stiffness.hpp"

#include "atom.h"
#include "compute.h"
#include "domain.h"
#include "error.h"
#include "irregular.h"
#include "neighbor.h"
#include "update.h"

#include <cmath>

using namespace LAMMPS_NS;

/* ----------------------------------------------------------------------
   what the servo needs every step: stress (compression positive) from the pair virial,
   affine stiffness and contact statistics from the pair tallies
------------------------------------------------------------------------- */

void FixCellServo::measure()
{
  if (measured_step == update->ntimestep) return;
  pressure->compute_vector();
  pressure->addstep(update->ntimestep + 1);
  // LAMMPS's pressure tensor xx yy zz xy xz yz is the compression-positive stress (Voigt6)
  for (int k = 0; k < 6; ++k) stress(k) = pressure->vector[k];

  pair->refresh_cell_tallies();
  CellTallies total;
  MPI_Allreduce(const_cast<double *>(pair->cell_tallies().sum), total.sum, CellTallies::SIZE,
                MPI_DOUBLE, MPI_SUM, world);
  for (int k = 0; k < tycore::AffineStiffnessSums::size; ++k)
    stiffness_sums[k] = total.sum[CellTallies::STIFFNESS + k];
  contacts = total.sum[CellTallies::CONTACTS];
  sliding = total.sum[CellTallies::SLIDING];
  force_sum = total.sum[CellTallies::FORCE];
  measured_step = update->ntimestep;
}

double FixCellServo::cell_volume() const
{
  return domain->xprd * domain->yprd * domain->zprd;    // det h of the upper-triangular cell
}

Eigen::Matrix3d FixCellServo::cell_matrix() const
{
  return tycore::cell_matrix_from_lammps(domain->h);
}

// the natural strains of the axes from the reference edges (docs/theory.md §10.4)
Eigen::Vector3d FixCellServo::principal_strain() const
{
  return strain.axial(cell_matrix());
}

tycore::CellMeasurementOf<6> FixCellServo::cell_measurement() const
{
  tycore::CellMeasurementOf<6> cell;
  const double volume = cell_volume();
  cell.stress = stress;
  cell.stiffness.setZero();
  cell.stiffness.topLeftCorner<3, 3>() = tycore::affine_stiffness(stiffness_sums, volume);
  if (domain->triclinic) {    // the shear entries are tallied on a triclinic cell only
    tycore::AffineStiffnessSums sums;
    std::copy(stiffness_sums, stiffness_sums + sums.size, sums.sum.begin());
    const tycore::Matrix6d full = sums.stiffness(volume);
    cell.stiffness.rightCols<3>() = full.rightCols<3>();
    cell.stiffness.bottomRows<3>() = full.bottomRows<3>();
  }
  cell.strain = strain.voigt(cell_matrix());
  return cell;
}

/* ----------------------------------------------------------------------
   the stiffness entries the servo uses (model only what the programme needs): C_IJ of a held
   stress I and a component J that the servo moves or the programme strains (the response it
   inverts and the feed-forward, docs/theory.md §6.2, §11.2). Drained simple shear holds
   sigma_jj alone while it strains gamma_ij: C_jj and C_j,ij, two of the 21. An orthogonal cell
   has the principal block; the other programmes of a triclinic cell take all 21 (f_ID[I][J]).
------------------------------------------------------------------------- */

unsigned FixCellServo::stiffness_entries() const
{
  if (!domain->triclinic) return CellTallies::PRINCIPAL_ENTRIES;
  if (mode != Mode::SHEAR) return CellTallies::ALL_ENTRIES;
  const tycore::MixedControl6 c =
      tycore::DrainedSimpleShear{plane, shear_rate, normal_target}.control();
  unsigned entries = 0;
  for (int k = 0; k < c.actuator_count; ++k)
    for (int I = 0; I < 6; ++I)
      for (int J = 0; J < 6; ++J)
        if (c.stress_rows(k, I) != 0.0 &&
            (c.prescribed_strain_rate(J) != 0.0 || c.actuators.row(J).any()))
          entries |= 1u << tycore::AffineStiffnessSums::index(I, J);
  return entries;
}

/* ----------------------------------------------------------------------
   the cell deforms at the next step's post_integrate, before its forces (see end_of_step)
------------------------------------------------------------------------- */

void FixCellServo::post_integrate()
{
  change_box(memory.last_strain_rate);
}

// domain->h_rate = L h, with which the pair reads L back as h_rate h^-1 (docs/theory.md §5.1,
// §10.1); an orthogonal cell has only the diagonal, h_rate_k = -eps_dot_k l_k
void FixCellServo::set_box_rate(const tycore::Vector6d &rate, const Eigen::Matrix3d &h)
{
  if (domain->triclinic) {
    const std::array<double, 6> h_rate = tycore::lammps_h_rate(tycore::velocity_gradient(rate), h);
    for (int k = 0; k < 6; ++k) domain->h_rate[k] = h_rate[k];
  } else {
    for (int k = 0; k < 3; ++k) domain->h_rate[k] = -rate(k) * h(k, k);
  }
  for (int k = 0; k < 3; ++k) domain->h_ratelo[k] = -0.5 * domain->h_rate[k];
}

/* ----------------------------------------------------------------------
   h <- exp(L dt) h about the fixed box centre, atoms remapped affinely; a tilt past half its
   box length is flipped in pre_exchange of this step (a neighbor list rebuild is forced)
------------------------------------------------------------------------- */

void FixCellServo::change_box(const tycore::Vector6d &rate)
{
  domain->x2lamda(atom->nlocal);

  const double dt = update->dt;
  const Eigen::Matrix3d L = tycore::velocity_gradient(rate);
  const Eigen::Matrix3d next = tycore::advance_cell(cell_matrix(), L, dt);
  for (int k = 0; k < 3; ++k) {
    // (for an orthogonal cell next(k, k) = l_k exp(-eps_dot_k dt), the edge update of
    // docs/theory.md §5.1)
    const double length = next(k, k);
    if (length < 2.0 * neighbor->cutneighmax)
      error->all(FLERR, "fix cell/servo: cell edge {} = {:.4g} has shrunk below twice the "
                 "neighbor cutoff ({:.4g}); use a larger specimen or a smaller skin",
                 tycore::axis_name(k), length, 2.0 * neighbor->cutneighmax);
    const double centre = 0.5 * (domain->boxlo[k] + domain->boxhi[k]);
    domain->boxlo[k] = centre - 0.5 * length;
    domain->boxhi[k] = centre + 0.5 * length;
  }
  if (domain->triclinic) {
    domain->xy = next(0, 1);
    domain->xz = next(0, 2);
    domain->yz = next(1, 2);
    strain.advance(L, dt);
  }
  domain->set_global_box();
  domain->set_local_box();
  domain->lamda2x(atom->nlocal);
  set_box_rate(rate, next);    // (next, not boxhi - boxlo, which differs by round-off)

  if (domain->triclinic) {
    pending_flip = tycore::tilt_flip_of(cell_matrix());
    if (pending_flip.any()) next_reneighbor = update->ntimestep;
  }
}

/* ----------------------------------------------------------------------
   a tilt flip (docs/theory.md §10.3), as fix deform's pre_exchange: the equivalent cell
   h M, image flags by Domain::image_flip, atoms remapped into the new cell and migrated;
   h_rate = L h M so that the pair reads the same L. The cumulative strain does not change.
------------------------------------------------------------------------- */

void FixCellServo::pre_exchange()
{
  if (!pending_flip.any()) return;
  const Eigen::Matrix3d flipped = tycore::flipped_cell(cell_matrix(), pending_flip);
  domain->xy = flipped(0, 1);
  domain->xz = flipped(0, 2);
  domain->yz = flipped(1, 2);
  domain->set_global_box();
  domain->set_local_box();
  // b' = b + m a, c' = c + p b + n a with (m, n, p) = LAMMPS's (flipxy, flipxz, flipyz)
  domain->image_flip(pending_flip.xy, pending_flip.xz, pending_flip.yz);
  double **x = atom->x;
  imageint *image = atom->image;
  for (int i = 0; i < atom->nlocal; ++i) domain->remap(x[i], image[i]);
  domain->x2lamda(atom->nlocal);
  irregular->migrate_atoms();
  domain->lamda2x(atom->nlocal);
  set_box_rate(memory.last_strain_rate, flipped);
  pending_flip = {};
}
