// LIGGGHTS 3.8 contact model `pair_style gran model thornton_yin tangential thornton_yin`: the
// Thornton-Yin law of plugin/core (docs/theory.md) in LIGGGHTS's model framework. The normal
// model evaluates the whole contact (JKR normal force and Thornton's tangential law are one law:
// the tangential stiffness and the sliding limit follow P + 2Pc), through the adapter
// thornton_yin_contact.h: in its own pair loop (pair_loop, run by the pair style of
// thornton_yin_register.cpp in place of LIGGGHTS's) the contacts gathered into batches and run in
// SIMD lanes as in the LAMMPS pair; where the run needs LIGGGHTS's loop (liggghts_loop_feature),
// one at a time as that loop hands them over (the same bits either way, one atom type). The
// tangential model only names the pairing, and any other pairing is refused
// (thornton_yin_register.cpp). Material data as LIGGGHTS reads them, from fix property/global:
// youngsModulus and poissonsRatio (peratomtype), coefficientFriction and interfaceEnergy (Gamma
// per surface, J/m^2; peratomtypepair), optional dampingRatioNormal and dampingRatioTangential
// (peratomtypepair, default 0).
// docs/pair_thornton_yin.md, "LIGGGHTS".
//
// Included from the style_*_model.h files CMake writes (cmake/Liggghts.cmake), as LIGGGHTS's
// Make.sh includes its own models: with NORMAL_MODEL defined it declares the model's id.
#ifdef NORMAL_MODEL
NORMAL_MODEL(THORNTON_YIN, thornton_yin, 31)
#elif defined(TANGENTIAL_MODEL)
TANGENTIAL_MODEL(TANGENTIAL_THORNTON_YIN, thornton_yin, 31)
#else
#ifndef TYLIGGGHTS_NORMAL_MODEL_THORNTON_YIN_H
#define TYLIGGGHTS_NORMAL_MODEL_THORNTON_YIN_H

#include "contact_models.h"
#include "normal_model_base.h"
#include "tangential_model_base.h"

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "fix_property_global.h"
#include "force.h"
#include "modify.h"
#include "neigh_list.h"
#include "neighbor.h"
#include "pair_gran.h"
#include "update.h"

#include "law_domain.hpp"
#include "thornton_yin_contact.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace LIGGGHTS {
namespace ContactModels {

  class ContactModelBase;

  template <> class NormalModel<THORNTON_YIN> : public NormalModelBase {
   public:
    NormalModel(LAMMPS *lmp, IContactHistorySetup *hsetup, class ContactModelBase *c) :
        NormalModelBase(lmp, hsetup, c), batch(new tycore::ContactBatch{}),
        pair_gran(dynamic_cast<PairGran *>(hsetup))
    {
      history_offset = hsetup->add_history_value(tyliggghts::history_names[0],
                                                 tyliggghts::history_newton_flag(0));
      for (int k = 1; k < tyliggghts::history_size; ++k)
        hsetup->add_history_value(tyliggghts::history_names[k], tyliggghts::history_newton_flag(k));
      if (c->is_wall())
        error->all(FLERR,
                   "model thornton_yin: walls (fix wall/gran) are not supported; the law "
                   "is for sphere-sphere contacts");
      constructed() = this;
    }
    ~NormalModel()
    {
      if (constructed() == this) constructed() = nullptr;
    }

    // the model last constructed: the pair style of this law (ThorntonYinPair,
    // thornton_yin_register.cpp) constructs it with its ContactModel and takes it from here
    static NormalModel *&constructed()
    {
      static NormalModel *model = nullptr;
      return model;
    }

    void registerSettings(Settings &) {}
    void postSettings(IContactHistorySetup *, ContactModelBase *) {}
    double stressStrainExponent() { return 1.5; }

    // LIGGGHTS's pair loop (PairStyles::Granular::compute_force), where it runs, hands the model
    // one contact at a time (surfacesIntersect, surfacesClose) and reads the contact's ForceData
    // right after the call
    void beginPass(SurfacesIntersectData &, ForceData &, ForceData &) {}
    void endPass(SurfacesIntersectData &, ForceData &, ForceData &) {}

    // material pairs from fix property/global, checked; the contact distance for tension
    void connectToProperties(PropertyRegistry &registry)
    {
      const int ntypes = registry.max_type();
      owned_values.clear();
      const char *caller = "model thornton_yin";
      const double *E = values("youngsModulus", "peratomtype", ntypes, 0, caller, true);
      const double *nu = values("poissonsRatio", "peratomtype", ntypes, 0, caller, true);
      const double *mu =
          values("coefficientFriction", "peratomtypepair", ntypes, ntypes, caller, true);
      const double *Gamma =
          values("interfaceEnergy", "peratomtypepair", ntypes, ntypes, caller, true);
      const double *beta_n =
          values("dampingRatioNormal", "peratomtypepair", ntypes, ntypes, caller, false);
      const double *beta_t =
          values("dampingRatioTangential", "peratomtypepair", ntypes, ntypes, caller, false);
      for (int t = 0; t < ntypes; ++t) {
        check(E[t], "youngsModulus", t + 1, -1, E[t] > 0.0, "> 0");
        check(nu[t], "poissonsRatio", t + 1, -1, nu[t] > -1.0 && nu[t] < 0.5, "in (-1, 0.5)");
      }
      const auto pair = [&](const double *m, int i, int j) {
        return m ? m[i * ntypes + j] : 0.0;
      };
      ntypes_ = ntypes;
      constants.assign((ntypes + 1) * (ntypes + 1), tycore::PairConstants{});
      damping.assign((ntypes + 1) * (ntypes + 1), tycore::BatchParameters{});
      adhesive = damped = false;
      for (int i = 0; i < ntypes; ++i)
        for (int j = 0; j < ntypes; ++j) {
          struct {
            const double *m;
            const char *name;
          } const table[] = {{mu, "coefficientFriction"},
                             {Gamma, "interfaceEnergy"},
                             {beta_n, "dampingRatioNormal"},
                             {beta_t, "dampingRatioTangential"}};
          for (const auto &entry : table) {
            if (!entry.m) continue;
            const double value = pair(entry.m, i, j);
            check(value, entry.name, i + 1, j + 1, value >= 0.0, ">= 0");
            if (value != pair(entry.m, j, i))
              fail(std::string(entry.name) + " must be symmetric: entry " + std::to_string(i + 1) +
                   " " + std::to_string(j + 1) + " = " + number(value) + ", " +
                   std::to_string(j + 1) + " " + std::to_string(i + 1) + " = " +
                   number(pair(entry.m, j, i)));
          }
          const tycore::PairCoefficients c{
              tycore::effective_modulus(E[i], nu[i], E[j], nu[j]),
              tycore::effective_shear_modulus(E[i], nu[i], E[j], nu[j]), pair(mu, i, j),
              pair(Gamma, i, j)};
          constants[(i + 1) * (ntypes + 1) + j + 1] = tycore::pair_constants(c);
          damping[(i + 1) * (ntypes + 1) + j + 1].beta_n = pair(beta_n, i, j);
          damping[(i + 1) * (ntypes + 1) + j + 1].beta_t = pair(beta_t, i, j);
          adhesive = adhesive || c.Gamma > 0.0;
          damped = damped || pair(beta_n, i, j) > 0.0 || pair(beta_t, i, j) > 0.0;
        }
      check_radii_and_range(ntypes);
    }

    void surfacesIntersect(SurfacesIntersectData &sidata, ForceData &i_forces, ForceData &j_forces)
    {
      if (!sidata.contact_history) return;
      contact(sidata, i_forces, j_forces);
    }

    // not overlapping, within the contact distance: a touched contact in tension (delta_f < delta
    // < 0) keeps its force until it breaks; an untouched one has none (before delta = 0)
    void surfacesClose(SurfacesCloseData &scdata, ForceData &i_forces, ForceData &j_forces)
    {
      if (!scdata.contact_history || !scdata.contact_flags) return;
      // an untouched pair starts at delta >= 0, as in the LAMMPS pair (rsq <= radsum^2)
      if (!(*scdata.contact_flags & CONTACT_NORMAL_MODEL) &&
          scdata.rsq > scdata.radsum * scdata.radsum)
        return;
      contact(scdata, i_forces, j_forces);
      scdata.has_force_update = true;
    }

    // What in this force evaluation needs LIGGGHTS's own pair loop (Granular::compute_force)
    // rather than pair_loop, named for the user; nullptr: nothing. Contact relaxation and the
    // history copy of fix insert/stream/predefined are no-ops in Debian's LIGGGHTS 3.8 (its
    // fix_relax_contacts.h and fix_insert_stream_predefined.h are stubs: the factor is 1, the
    // copy does nothing), in its loop as in ours
    const char *liggghts_loop_feature(PairGran &pg) const
    {
      if (pg.cpl() || !pg.computeflag()) return "compute pair/gran/local";
      if (pg.storeContactForces()) return "contact forces stored per contact (requested by a fix)";
      if (pg.storeContactForcesStress())
        return "contact forces stored for a stress (fix continuum/weighted)";
      if (pg.store_sum_normal_force())
        return "the sum of normal forces (fix property/atom sum_normal_force_)";
      if (pg.storeSumDelta()) return "multi-contact radii (fix multicontact/halfspace)";
      if (atom->shapetype_flag) return "non-spherical particles (atom style convex)";
      return nullptr;
    }

    // LIGGGHTS's pair loop for this law alone, in place of Granular::compute_force where
    // liggghts_loop_feature finds nothing (ThorntonYinPair, thornton_yin_register.cpp): the pairs
    // that loop hands the model, in its order, gathered into batches (one per type pair) that run
    // in SIMD lanes as in the LAMMPS pair, each contact's force and torques then added as that
    // loop adds them (run_batch), without its per-pair contact record and calls. A pair is the
    // law's when it overlaps (rsq < radsum^2: LIGGGHTS's surfacesIntersect) or, within the
    // contact distance (surfacesClose), was touched before or touches (delta = 0). With one atom
    // type the forces are summed in LIGGGHTS's order, the same bits; with several, the batches
    // of the type pairs interleave, the sums in another order (round-off)
    void pair_loop(PairGran &pg)
    {
      step = pg.shearupdate() != 0;
      if (batches.size() != constants.size()) batches.resize(constants.size());
      if (damped)
        pair_loop_of<true>(pg);
      else
        pair_loop_of<false>(pg);
      for (auto &bt : batches)
        if (bt && bt->n) run_batch(*bt);
    }

   private:
    int history_offset = 0;
    int ntypes_ = 0;
    std::vector<tycore::PairConstants> constants;
    std::vector<tycore::BatchParameters> damping;    // beta_n, beta_t per type pair
    bool adhesive = false, damped = false;
    std::unique_ptr<tycore::ContactBatch> batch;    // one lane: a contact at a time
    std::vector<std::vector<double>> owned_values;

    // the gathered contacts of one type pair: lanes of the core's batch, and where each lane's
    // results go
    struct Batch {
      tycore::ContactBatch b;
      int n = 0;
      int pair = 0;    // index of the type pair in constants, damping
      int i[tycore::batch_lanes], j[tycore::batch_lanes];
      int *flags[tycore::batch_lanes];
      double *history[tycore::batch_lanes];
    };
    PairGran *pair_gran;    // the pair style: its virial and energy tallies
    bool step = true;       // this pass advances the contacts (not the setup pass)
    std::vector<std::unique_ptr<Batch>> batches;    // per type pair, made at its first contact
    const tycore::Isa isa = tycore::best_isa();

    static std::string number(double x)
    {
      char buf[64];
      std::snprintf(buf, sizeof buf, "%.6g", x);
      return buf;
    }

    void fail(const std::string &what)
    {
      const std::string message = "pair gran model thornton_yin: " + what;    // alive in the call
      error->all(FLERR, message.c_str());
    }

    void check(double value, const char *name, int i, int j, bool in_range, const char *range)
    {
      if (std::isfinite(value) && in_range) return;
      fail(std::string(name) + " of type " + std::to_string(i) +
           (j > 0 ? " " + std::to_string(j) : std::string()) + " must be finite and " + range +
           " (fix property/global " + name + "), got " + number(value));
    }

    // the values of fix property/global `name` (row-major for a matrix), or nullptr when an
    // optional one is absent
    const double *values(const char *name, const char *kind, int n1, int n2, const char *caller,
                         bool required)
    {
      FixPropertyGlobal *fix = static_cast<FixPropertyGlobal *>(
          modify->find_fix_property(name, "property/global", kind, n1, n2, caller, false));
      if (!fix) {
        if (!required) return nullptr;
        fail(std::string("needs 'fix ID all property/global ") + name + " " + kind + " ...' (" +
             std::to_string(n1) + (n2 ? "x" + std::to_string(n2) : std::string()) + " values for " +
             std::to_string(n1) + " atom types)");
      }
      owned_values.emplace_back();
      std::vector<double> &v = owned_values.back();
      for (int i = 0; i < n1; ++i)
        if (n2 == 0)
          v.push_back(fix->compute_vector(i));
        else
          for (int j = 0; j < n2; ++j) v.push_back(fix->compute_array(i, j));
      return v.data();
    }

    // per type the largest radius; the law's domain for each pair (plugin/core/law_domain.hpp,
    // as the LAMMPS pair checks it) and the contact distance that keeps a tensile contact's
    // partner within reach of surfacesClose until the break overlap delta_f (docs/theory.md §1.2)
    void check_radii_and_range(int ntypes)
    {
      std::vector<double> local(ntypes + 1, 0.0), largest(ntypes + 1, 0.0);
      double smallest_local = 1e300, smallest = 0.0;
      for (int i = 0; i < atom->nlocal; ++i) {
        const int t = atom->type[i];
        if (t >= 1 && t <= ntypes) local[t] = std::max(local[t], atom->radius[i]);
        smallest_local = std::min(smallest_local, atom->radius[i]);
      }
      MPI_Allreduce(local.data(), largest.data(), ntypes + 1, MPI_DOUBLE, MPI_MAX, world);
      MPI_Allreduce(&smallest_local, &smallest, 1, MPI_DOUBLE, MPI_MIN, world);
      if (!(smallest > 0.0 && smallest < 1e300))
        fail("needs the spheres (with radius > 0) before the run: the range of tensile contacts "
             "(the contact distance) is set from their radii");
      double factor = 1.0;
      for (int i = 1; i <= ntypes; ++i)
        for (int j = 1; j <= ntypes; ++j) {
          if (largest[i] <= 0.0 || largest[j] <= 0.0) continue;
          const tycore::PairCoefficients &c = constants[i * (ntypes + 1) + j].c;
          const double R = tycore::effective_radius(largest[i], largest[j]);
          if (!(tycore::zero_load_radius_ratio(c, R) < 1.0))
            fail("types " + std::to_string(i) + " " + std::to_string(j) +
                 ": the JKR zero-load contact radius a0 is not smaller than R* = " + number(R) +
                 ", so the contact law (a << R*) does not apply; interfaceEnergy must be below "
                 "E* R*/(9 pi) = " +
                 number(c.E_star * R / (9.0 * tycore::jkr::pi)));
          const tycore::LawDomainFault fault =
              tycore::law_domain_fault(c, R, std::min(largest[i], largest[j]));
          if (fault.quantity)
            fail("types " + std::to_string(i) + " " + std::to_string(j) + ": the " +
                 fault.quantity + " of the contact law is not finite at overlap " +
                 number(fault.delta) +
                 ": the material values are far outside what the law can "
                 "represent");
          // LIGGGHTS evaluates a separated pair only within the contact distance: a touched
          // pair must not leave it in one step before the law has seen it beyond delta_f (its
          // flag and history would stay, Gamma = 0 included), so the range is |delta_f| plus the
          // skin, what no pair moves in a step without a dangerous neighbour build
          const double delta_f = tycore::jkr::break_overlap(R, c.E_star, c.Gamma);
          factor = std::max(factor, 1.0 + (neighbor->skin - delta_f) / (2.0 * smallest));
        }
      neighbor->register_contact_dist_factor(factor);
    }

    // the law on lanes 0 .. n-1 of b, its geometry computed
    void evaluate(tycore::ContactBatch &b, int n, int pair, bool step, tycore::Isa law_isa)
    {
      const tycore::PairConstants &k = constants[pair];
      tycore::BatchParameters p = damping[pair];
      p.dt = update->dt;
      if (adhesive) {
        if (damped)
          tyliggghts::evaluate_contacts<true, true>(b, n, k, p, step, law_isa);
        else
          tyliggghts::evaluate_contacts<true, false>(b, n, k, p, step, law_isa);
      } else {
        if (damped)
          tyliggghts::evaluate_contacts<false, true>(b, n, k, p, step, law_isa);
        else
          tyliggghts::evaluate_contacts<false, false>(b, n, k, p, step, law_isa);
      }
    }

    void overlap_fault(int i, int j, double delta)
    {
      fail("atoms " + std::to_string(atom->tag[i]) + " " + std::to_string(atom->tag[j]) +
           ": overlap " + number(delta) +
           " is not finite or exceeds the smaller radius (the "
           "law and the explicit step have failed: the timestep is too large or a position "
           "is not finite)");
    }

    // lane l after the law: a broken contact is forgotten (false); otherwise its flag and history
    // are stored and add(f, lever_i, lever_j) given its force on i and the levers of its
    // moment (the torque on i is -lever_i moment, on j -lever_j moment)
    template <class Add>
    bool lane_result(const tycore::ContactBatch &b, int l, int i, int j, int *flags,
                     double *history, Add add)
    {
      if (b.broken[l] != 0.0) {    // separated at the break overlap: the contact is forgotten
        *flags &= ~CONTACT_NORMAL_MODEL;
        for (int m = 0; m < tyliggghts::history_size; ++m) history[m] = 0.0;
        return false;
      }
      *flags |= CONTACT_NORMAL_MODEL;
      tycore::store_history(b, l, history);
      const double f[3] = {b.force[0][l], b.force[1][l], b.force[2][l]};
      if (!(std::fabs(f[0] + f[1] + f[2]) <= std::numeric_limits<double>::max()))
        fail("atoms " + std::to_string(atom->tag[i]) + " " + std::to_string(atom->tag[j]) +
             ": the contact force is not finite (a velocity, spin or history value is not)");
      // the tangential force acts at the contact point: levers r - delta/2
      const double delta = b.delta[l];
      add(f, b.r_i[l] - 0.5 * delta, b.r_j[l] - 0.5 * delta);
      return true;
    }

    // the batch of type pair `pair` (itype (ntypes + 1) + jtype), made at its first contact
    Batch &batch_of(int pair)
    {
      std::unique_ptr<Batch> &slot = batches[pair];
      if (!slot) {
        slot.reset(new Batch{});
        slot->pair = pair;
      }
      return *slot;
    }

    // contact i-j (del = x_i - x_j, rsq = |del|^2; its flags and this model's history) into
    // batch bt; the batch runs when full. Damped: the masses too
    template <bool Damped>
    void gather_into(Batch &bt, int i, int j, const double del[3], double rsq, int *flags,
                     double *history)
    {
      const int l = bt.n;
      const tycore::SphereState si{atom->v[i], atom->omega[i], atom->radius[i], atom->rmass[i]};
      const tycore::SphereState sj{atom->v[j], atom->omega[j], atom->radius[j], atom->rmass[j]};
      tycore::gather_contact<Damped>(bt.b, l, del, rsq, si, sj, !(*flags & CONTACT_NORMAL_MODEL));
      tycore::load_history(bt.b, l, history);
      bt.history[l] = history;
      bt.i[l] = i, bt.j[l] = j;
      bt.flags[l] = flags;
      if (++bt.n == tycore::batch_lanes) run_batch(bt);
    }

    // pair_loop's walk over LIGGGHTS's neighbour list and its contact history (fix
    // contacthistory: per neighbour a flag and dnum values, this model's from history_offset)
    template <bool Damped> void pair_loop_of(PairGran &pg)
    {
      double **x = atom->x;
      const double *radius = atom->radius;
      const int *type = atom->type;
      const int inum = pg.list->inum;
      const int *ilist = pg.list->ilist, *numneigh = pg.list->numneigh;
      int **firstneigh = pg.list->firstneigh;
      int **firstflags = pg.listgranhistory->firstneigh;
      double **firsthistory = pg.listgranhistory->firstdouble;
      const int dnum = pg.dnum();
      const double close = neighbor->contactDistanceFactor * neighbor->contactDistanceFactor;
      for (int ii = 0; ii < inum; ++ii) {
        const int i = ilist[ii];
        const double xi[3] = {x[i][0], x[i][1], x[i][2]};
        const double radi = radius[i];
        std::unique_ptr<Batch> *batch_of_j = &batches[type[i] * (ntypes_ + 1)];
        int *flags = firstflags[i];
        double *history = firsthistory[i] + history_offset;
        const int *jlist = firstneigh[i];
        const int jnum = numneigh[i];
        for (int jj = 0; jj < jnum; ++jj) {
          const int j = jlist[jj] & NEIGHMASK;
          const double del[3] = {xi[0] - x[j][0], xi[1] - x[j][1], xi[2] - x[j][2]};
          const double rsq = del[0] * del[0] + del[1] * del[1] + del[2] * del[2];
          const double radsum = radi + radius[j];
          // LIGGGHTS's tests, in its arithmetic: apart, the model's only within the contact
          // distance, touched before or at delta = 0
          if (!(rsq < radsum * radsum) &&
              !(rsq < close * radsum * radsum &&
                ((flags[jj] & CONTACT_NORMAL_MODEL) || rsq <= radsum * radsum)))
            continue;
          Batch *bt = batch_of_j[type[j]].get();
          if (!bt) bt = &batch_of(type[i] * (ntypes_ + 1) + type[j]);
          gather_into<Damped>(*bt, i, j, del, rsq, &flags[jj], history + dnum * jj);
        }
      }
    }

    // the law on a batch, then each contact's force and torques added as LIGGGHTS's loop adds
    // a contact's ForceData (Granular::force_update, its relaxation factor 1 in Debian's
    // LIGGGHTS; newton off: j's share only when j is owned) and tallied as its virial
    // (ev_tally_xyz), contact after contact
    void run_batch(Batch &bt)
    {
      const int n = bt.n;
      bt.n = 0;
      tycore::ContactBatch &b = bt.b;
      const tycore::AffineGradient none{};
      const bool valid = damped ? tycore::batch_geometry<false, true>(b, n, none, isa)
                                : tycore::batch_geometry<false, false>(b, n, none, isa);
      if (!valid)
        for (int l = 0; l < n; ++l)
          if (!tycore::overlap_valid(b, l)) overlap_fault(bt.i[l], bt.j[l], b.delta[l]);
      evaluate(b, n, bt.pair, step, isa);
      double **f = atom->f, **torque = atom->torque;
      const int nlocal = atom->nlocal;
      const int newton_pair = force->newton_pair;
      const bool tally = pair_gran->evflag;
      for (int l = 0; l < n; ++l) {
        const int i = bt.i[l], j = bt.j[l];
        const auto add = [&](const double *F, double lever_i, double lever_j) {
          for (int a = 0; a < 3; ++a) {
            f[i][a] += F[a];
            torque[i][a] -= lever_i * b.moment[a][l];
          }
          if (newton_pair || j < nlocal)
            for (int a = 0; a < 3; ++a) {
              f[j][a] -= F[a];
              torque[j][a] -= lever_j * b.moment[a][l];
            }
          if (tally)
            pair_gran->ev_tally_xyz(i, j, nlocal, newton_pair, 0.0, 0.0, F[0], F[1], F[2],
                                    b.del[0][l], b.del[1][l], b.del[2][l]);
        };
        lane_result(b, l, i, j, bt.flags[l], bt.history[l], add);
      }
    }

    // one contact, in the scalar build, its forces into i_forces and j_forces for the loop
    void contact(SurfacesCloseData &d, ForceData &i_forces, ForceData &j_forces)
    {
      const int i = d.i, j = d.j;
      if (!d.computeflag) return;
      const bool first_touch = !(*d.contact_flags & CONTACT_NORMAL_MODEL);
      double *history = &d.contact_history[history_offset];
      tycore::ContactBatch &b = *batch;
      const tycore::SphereState si{atom->v[i], atom->omega[i], atom->radius[i], atom->rmass[i]};
      const tycore::SphereState sj{atom->v[j], atom->omega[j], atom->radius[j], atom->rmass[j]};
      tycore::gather_contact<true>(b, 0, d.delta, d.rsq, si, sj, first_touch);
      tycore::contact_geometry<false, true>(b, 0, tycore::AffineGradient{});
      if (!tycore::overlap_valid(b, 0)) overlap_fault(i, j, b.delta[0]);
      tycore::load_history(b, 0, history);
      evaluate(b, 1, d.itype * (ntypes_ + 1) + d.jtype, d.shearupdate != 0, tycore::Isa::scalar);
      const auto add = [&](const double *F, double lever_i, double lever_j) {
        for (int a = 0; a < 3; ++a) {
          i_forces.delta_F[a] += F[a];
          j_forces.delta_F[a] -= F[a];
          i_forces.delta_torque[a] -= lever_i * b.moment[a][0];
          j_forces.delta_torque[a] -= lever_j * b.moment[a][0];
        }
      };
      lane_result(b, 0, i, j, d.contact_flags, history, add);
    }
  };

  // The pairing's name: the whole law runs in NormalModel<THORNTON_YIN>
  template <> class TangentialModel<TANGENTIAL_THORNTON_YIN> : public TangentialModelBase {
   public:
    TangentialModel(LAMMPS *lmp, IContactHistorySetup *hsetup, class ContactModelBase *c) :
        TangentialModelBase(lmp, hsetup, c)
    {
    }
    void registerSettings(Settings &) {}
    void postSettings(IContactHistorySetup *, ContactModelBase *) {}
    void connectToProperties(PropertyRegistry &) {}
    void surfacesIntersect(const SurfacesIntersectData &, ForceData &, ForceData &) {}
    void surfacesClose(SurfacesCloseData &, ForceData &, ForceData &) {}
    void beginPass(SurfacesIntersectData &, ForceData &, ForceData &) {}
    void endPass(SurfacesIntersectData &, ForceData &, ForceData &) {}
  };

}    // namespace ContactModels
}    // namespace LIGGGHTS

#endif
#endif
