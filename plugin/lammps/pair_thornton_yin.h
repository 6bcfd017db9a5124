/* -*- c++ -*- ----------------------------------------------------------
   pair_style thornton/yin: JKR adhesive elastic spheres with Thornton's tangential law
   (Thornton & Yin 1991; Thornton 1991; Thornton & Randall 1988).
   The contact physics lives in plugin/core (tycore); this class is the LAMMPS plumbing:
   neighbor loop, contact history, affine relative velocity, energy and virial tallies.
------------------------------------------------------------------------- */

#ifndef LMP_PAIR_THORNTON_YIN_H
#define LMP_PAIR_THORNTON_YIN_H

#include "cell_tally.h"
#include "lammps_compat.h"

#include "affine_stiffness_entries.hpp"
#include "contact_batch.hpp"
#include "contact_geometry.hpp"

#include <array>
#include <memory>
#include <utility>
#include <vector>

namespace LAMMPS_NS {

class PairThorntonYin : public tylmp_compat::PairWithHistory, public CellTallySource {
 public:
  PairThorntonYin(class LAMMPS *);
  ~PairThorntonYin() override;

  void compute(int, int) override;
  void settings(int, char **) override;
  void coeff(int, char **) override;
  void init_style() override;
  double init_one(int, int) override;
  void write_restart(FILE *) override;
  void read_restart(FILE *) override;
  void write_restart_settings(FILE *) override;
  void read_restart_settings(FILE *) override;
  double single(int, int, int, int, double, double, double, double &) override;
  void transfer_contact_history(const double *, double *) override;
  double memory_usage() override;
  void *extract(const char *, int &) override;
  int pack_reverse_comm(int, int, double *) override;
  void unpack_reverse_comm(int, int *, double *) override;

  // the sums for fix cell/servo (cell_tally.h)
  unsigned request_cell_tallies(unsigned entries) override;
  const CellTallies &cell_tallies() const override { return tallies; }
  const double *contact_count() const override { return atom_contacts; }

  // indices of pvector (cumulative energies, J; read with compute pair thornton/yin)
  enum { DISSIPATION_FRICTION, DISSIPATION_BREAK, DISSIPATION_DAMPING, N_PVECTOR };
  // indices of svector (single(), for compute pair/local p1 ... p8)
  enum {
    S_NORMAL_FORCE,
    S_TANGENTIAL_FORCE,
    S_CONTACT_RADIUS,
    S_OVERLAP,
    S_SLIDING,
    S_PEELING,
    S_PULL_OFF_FORCE,
    S_BREAK_OVERLAP,
    N_SVECTOR
  };

  // one contact as of the last force evaluation, kept while a compute thornton/yin/... exists
  // (docs/compute_thornton_yin_contacts.md): each contact once over all ranks
  struct ContactRecord {
    double id_i, id_j;                 // atom IDs
    double normal_force[3];            // P n on atom i, viscous normal damping included
    double tangential_force[3];        // on atom i, viscous tangential damping included
    double branch[3];                  // x_i - x_j (the virial's branch vector)
    double P;                          // normal force (repulsive > 0), = n . normal_force
    double overlap, contact_radius;    // delta, a
    double sliding, peeling;           // 1 or 0
    int mask;                          // mask_i & mask_j: both atoms in a group
  };
  const std::vector<ContactRecord> &contact_records() const { return records; }
  bigint contact_record_step() const { return record_step; }
  int contacts_recorded() const { return record_contacts; }

  // fraction of the Rayleigh time above which init() warns (docs/theory.md §4.1)
  static constexpr double RAYLEIGH_WARN_FRACTION = 0.3;
  // a0/R* above which init() warns that the contact is large before any load (a << R*)
  static constexpr double A0_WARN_FRACTION = 0.1;

 protected:
  // per type: material as given by pair_coeff I I
  double *youngs, *poisson;
  int *material_set;
  // per type pair (mixed for I != J unless given explicitly)
  double **E_star, **G_star, **friction, **surface_energy;
  double **cut;
  tycore::PairConstants *pair_constants;    // [i * (ntypes + 1) + j], set by init_one

  double **damp_n, **damp_t;    // damping ratios beta_n, beta_t; 0 = off
  int adhesive, damped;         // chosen once per compute()
  tycore::Isa isa;              // build of the batch law (settings)
  double *maxrad_type;          // largest radius per type (init_style)

  class FixNeighHistory *fix_history;
  int neighprev;
  double dt;

  // box of the last compute, to check that domain->h_rate explains the box change
  double box_h[6];
  bigint box_step;
  int box_from_setup;
  int box_rate_warned;
  void check_box_rate();
  // error path of the contact loop, out of line: an overlap beyond the law's validity or a
  // non-finite quantity (NaN/inf position, velocity, ... of atom i or j, or the contact force)
  __attribute__((noinline, cold)) void contact_fault(int i, int j, double delta, bool force);

  int record_contacts;    // a compute thornton/yin/... exists (init_style)
  std::vector<ContactRecord> records;
  bigint record_step;
  struct Batch;
  __attribute__((noinline)) void record_contact(const Batch &, int lane, double Fn,
                                                const double fs[3]);

  int tally_cell;
  // which stiffness entries the tallies make, and how (request_cell_tallies): the principal
  // block contact by contact, or one of its entries per batch lane; and none, one or all 15
  // entries with a shear component per lane. Each shape has its own branch-free summation.
  bool principal_by_contact;
  int lane_principal;    // the principal entry summed per lane (virial order), -1 none
  int lane_shear;        // the shear entry (0..14) summed per lane, ALL_SHEAR all, -1 none
  static constexpr int ALL_SHEAR = tycore::affine_shear_size;
  unsigned lane_entries;    // the entries summed per lane (AffineStiffnessSums bits)
  CellTallies tallies;
  // per batch lane, the entries of lane_entries (summed over the lanes into tallies after the
  // force evaluation)
  alignas(64) double stiffness_lanes[6 + tycore::affine_shear_size][tycore::batch_lanes];
  void tally_principal_lane(const Batch &, int n);
  template <int K> __attribute__((noinline)) void tally_shear_lane(const Batch &, int n);
  using ShearLaneTally = void (PairThorntonYin::*)(const Batch &, int);
  template <std::size_t... K>
  static std::array<ShearLaneTally, sizeof...(K)> shear_lane_tallies(std::index_sequence<K...>);
  static ShearLaneTally shear_lane_tally(int k);
  double *atom_contacts;    // per atom (local after reverse communication)
  int nmax_count;

  void allocate();
  bool sub_style_of(const char *style) const;    // a sub-style of pair_style STYLE
  bool handles(int i, int j) const;              // type pair computed by this pair
  void check_hybrid_outputs();
  void mix_pair(int, int);
  void check_break_against_skin();
  void check_timestep_against_rayleigh();
  void check_law_domain(int, int, double, double, bool);
  double largest_radius(int) const;
  double affine_velocity_gradient(double L[3][3]) const;

  // contacts of one material pair on their way through tycore::advance_batch: the batch and
  // where each lane's contact lives (atoms, history slot, share of the tallies)
  struct Batch {
    tycore::ContactBatch b;
    const tycore::PairConstants *constants;
    tycore::BatchParameters p;
    int n;
    int i[tycore::batch_lanes], j[tycore::batch_lanes];
    int *touch[tycore::batch_lanes];
    double *slot[tycore::batch_lanes];
    double share[tycore::batch_lanes];
  };
  // one batch per type pair i <= j (advance_batch takes one material pair), made on first use
  // (make_batch); batch_of_types[itype * (ntypes + 1) + jtype] points to it from either order.
  // With one type the contacts reach the atoms in neighbour-list order, with several the forces
  // on an atom add in another order (the same to round-off)
  std::vector<std::unique_ptr<Batch>> batches;
  std::vector<Batch *> batch_of_types;
  bool batch_energy;    // this evaluation's batches fill the stored energy
  void begin_batches(bool energy);
  Batch *make_batch(int itype, int jtype);
  tycore::BatchParameters batch_parameters(int itype, int jtype) const;

  // one force evaluation: a step or the setup pass (no history increment), the cell's
  // velocity gradient, the dissipated energies summed over the contacts
  struct Sweep {
    bool step;
    bool affine;    // the box deforms: the contacts' affine velocity gradient.L (x_i - x_j)
    tycore::AffineGradient gradient;
    double friction = 0.0, breaks = 0.0, damping = 0.0;
  };

  template <bool ADHESIVE, bool DAMPED> void eval(int eflag, int vflag);
  // BY_CONTACT: the principal stiffness block is summed contact by contact
  // (principal_by_contact)
  template <bool ADHESIVE, bool DAMPED, bool BY_CONTACT> void run_batch(Batch &, Sweep &);
  __attribute__((noinline, cold)) void report_overlap(const Batch &, int n);
  template <bool DAMPED> void scatter(const Batch &, int n, Sweep &);
  template <bool BY_CONTACT> void tally_batch(const Batch &, int n);
  void begin_tallies();
  void end_tallies();
};

}    // namespace LAMMPS_NS

#endif
