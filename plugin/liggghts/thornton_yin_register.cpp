// Registers `pair_style gran model thornton_yin tangential thornton_yin` into Debian's unmodified
// libliggghts.so.3 when this library is loaded (a static initialiser, as LIGGGHTS's own
// granular_styles.h registers its models): the model names into the contact model factory, the
// pair style of the pairing (ThorntonYinPair: LIGGGHTS's Granular with the model's own pair
// loop) into the granular pair style factory. Any other pairing with
// thornton_yin (another tangential, normal, cohesion or rolling model) is registered as an
// error that names what to write instead.
// the include order of LIGGGHTS's granular_styles.h: contact_models.h defines our model classes
// where it includes the style_*_model.h lists (normal_model_thornton_yin.h)
// clang-format off
#include "comm.h"
#include "error.h"
#include "fix_insert_stream.h"
#include "granular_pair_style.h"
#include "contact_models.h"
#include "pair_gran_base.h"
// clang-format on

#include <cstdio>
#include <string>

namespace {

using namespace LIGGGHTS;
using namespace LIGGGHTS::ContactModels;

typedef GranStyle<THORNTON_YIN, TANGENTIAL_THORNTON_YIN, COHESION_OFF, ROLLING_OFF, SURFACE_DEFAULT>
    ThorntonYinStyle;
typedef PairStyles::Granular<ContactModel<ThorntonYinStyle>> LiggghtsLoop;
typedef NormalModel<THORNTON_YIN> ThorntonYinModel;

// The pair style of the pairing: LIGGGHTS's Granular with this model (settings, properties,
// history, restart as for any LIGGGHTS model), whose force evaluation is the model's own pair
// loop (ThorntonYinModel::pair_loop) unless the run uses a feature that needs LIGGGHTS's loop
// (ThorntonYinModel::liggghts_loop_feature; the model then runs in that loop, named once in
// the log). docs/pair_thornton_yin.md, "LIGGGHTS"
class ThorntonYinPair : public LiggghtsLoop {
 public:
  ThorntonYinPair(LAMMPS_NS::LAMMPS *lmp, LAMMPS_NS::PairGran *parent, int64_t hash) :
      LiggghtsLoop(lmp, parent, hash), lmp_(lmp), model(ThorntonYinModel::constructed())
  {
    if (!model) lmp->error->all(FLERR, "pair gran model thornton_yin: the model was not made");
  }

  void compute_force(LAMMPS_NS::PairGran *pg, int eflag, int vflag, int addflag) override
  {
    const char *feature = model->liggghts_loop_feature(*pg);
    if (feature != noted) note(feature);
    if (feature) {
      LiggghtsLoop::compute_force(pg, eflag, vflag, addflag);
      return;
    }
    if (eflag || vflag)    // as LIGGGHTS's loop starts
      pg->ev_setup(eflag, vflag);
    else
      pg->evflag = pg->vflag_fdotr = 0;
    model->pair_loop(*pg);
  }

 private:
  LAMMPS_NS::LAMMPS *lmp_;
  ThorntonYinModel *model;
  const char *noted = nullptr;    // the feature last named

  void note(const char *feature)
  {
    noted = feature;
    if (lmp_->comm->me != 0) return;
    const std::string line = feature
        ? std::string("pair gran model thornton_yin: LIGGGHTS's pair loop evaluates the "
                      "contacts, for ") +
            feature + " (the model's own loop is faster)\n"
        : std::string("pair gran model thornton_yin: the model's own pair loop "
                      "evaluates the contacts\n");
    for (FILE *out : {lmp_->screen, lmp_->logfile})
      if (out) std::fputs(line.c_str(), out);
  }
};

PairStyles::IGranularPairStyle *create_pair(LAMMPS_NS::LAMMPS *lmp, LAMMPS_NS::PairGran *parent,
                                            int64_t hash)
{
  return new ThorntonYinPair(lmp, parent, hash);
}

PairStyles::IGranularPairStyle *refuse_pairing(LAMMPS_NS::LAMMPS *lmp, LAMMPS_NS::PairGran *,
                                               int64_t)
{
  lmp->error->all(FLERR,
                  "pair gran: thornton_yin is one law, normal and tangential together, "
                  "with no cohesion or rolling_friction model: write 'pair_style gran model "
                  "thornton_yin tangential thornton_yin' (adhesion is the law's own, "
                  "fix property/global interfaceEnergy)");
  return nullptr;
}

int64_t hash_of(int normal, int tangential, int cohesion, int rolling)
{
  return Utils::generate_gran_hashcode(normal, tangential, cohesion, rolling, SURFACE_DEFAULT);
}

struct RegisterThorntonYin {
  RegisterThorntonYin()
  {
    ContactModels::Factory &models = ContactModels::Factory::instance();
    models.addNormalModel("thornton_yin", THORNTON_YIN);
    models.addTangentialModel("thornton_yin", TANGENTIAL_THORNTON_YIN);
    PairStyles::Factory &pairs = PairStyles::Factory::instance();
    pairs.addStyle("gran", ThorntonYinStyle::HASHCODE, &create_pair);
    // the hash has 6 bits per model: every other pairing that names thornton_yin
    for (int id = 0; id < 64; ++id) {
      if (id != TANGENTIAL_THORNTON_YIN)
        pairs.addStyle("gran", hash_of(THORNTON_YIN, id, COHESION_OFF, ROLLING_OFF),
                       &refuse_pairing);
      if (id != THORNTON_YIN)
        pairs.addStyle("gran", hash_of(id, TANGENTIAL_THORNTON_YIN, COHESION_OFF, ROLLING_OFF),
                       &refuse_pairing);
      if (id != COHESION_OFF)
        pairs.addStyle("gran", hash_of(THORNTON_YIN, TANGENTIAL_THORNTON_YIN, id, ROLLING_OFF),
                       &refuse_pairing);
      if (id != ROLLING_OFF)
        pairs.addStyle("gran", hash_of(THORNTON_YIN, TANGENTIAL_THORNTON_YIN, COHESION_OFF, id),
                       &refuse_pairing);
    }
  }
};

const RegisterThorntonYin register_thornton_yin;

}    // namespace
