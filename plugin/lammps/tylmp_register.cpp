// Registration of all tylmp styles into a running LAMMPS.
//
// Debian's LAMMPS has no PLUGIN package, so the styles are inserted directly into the
// public creator maps (Force::pair_map, Modify::fix_map, Modify::compute_map) by tylmp_register(), which
// python/tylmp/__init__.py calls through ctypes. lammpsplugin_init() offers the same
// styles to `plugin load` in LAMMPS builds of the same version that have PLUGIN.

#include "tylmp_styles.h"

#include "force.h"
#include "lammps.h"
#include "lammpsplugin.h"
#include "modify.h"
#include "version.h"

using namespace LAMMPS_NS;

namespace {

template <typename T> Pair *create_pair(LAMMPS *lmp) { return new T(lmp); }
template <typename T> Fix *create_fix(LAMMPS *lmp, int narg, char **arg)
{
  return new T(lmp, narg, arg);
}
template <typename T> Compute *create_compute(LAMMPS *lmp, int narg, char **arg)
{
  return new T(lmp, narg, arg);
}
template <typename T> void *plugin_pair(void *lmp) { return new T((LAMMPS *) lmp); }
template <typename T> void *plugin_with_args(void *lmp, int narg, char **arg)
{
  return new T((LAMMPS *) lmp, narg, arg);
}

}    // namespace

extern "C" int tylmp_register(void *handle)
{
  auto lmp = static_cast<LAMMPS *>(handle);
  int count = 0;
#define TYLMP_PAIR(style_name, Class) \
  (*lmp->force->pair_map)[style_name] = &create_pair<Class>; \
  ++count;
#define TYLMP_FIX(style_name, Class) \
  (*lmp->modify->fix_map)[style_name] = &create_fix<Class>; \
  ++count;
#define TYLMP_COMPUTE(style_name, Class) \
  (*lmp->modify->compute_map)[style_name] = &create_compute<Class>; \
  ++count;
  TYLMP_STYLE_LIST
#undef TYLMP_PAIR
#undef TYLMP_FIX
#undef TYLMP_COMPUTE
  return count;
}

extern "C" void lammpsplugin_init(void *lmp, void *handle, void *regfunc)
{
  auto reg = (lammpsplugin_regfunc) regfunc;
  lammpsplugin_t plugin;
  plugin.version = LAMMPS_VERSION;
  plugin.author = "tylmp developers";
  plugin.handle = handle;
#define TYLMP_PLUGIN(kind, style_name, member, factory_type, factory) \
  plugin.style = kind; \
  plugin.name = style_name; \
  plugin.info = "tylmp " kind " " style_name; \
  plugin.creator.member = (factory_type *) &factory; \
  (*reg)(&plugin, lmp);
#define TYLMP_PAIR(style_name, Class) \
  TYLMP_PLUGIN("pair", style_name, v1, lammpsplugin_factory1, plugin_pair<Class>)
#define TYLMP_FIX(style_name, Class) \
  TYLMP_PLUGIN("fix", style_name, v2, lammpsplugin_factory2, plugin_with_args<Class>)
#define TYLMP_COMPUTE(style_name, Class) \
  TYLMP_PLUGIN("compute", style_name, v2, lammpsplugin_factory2, plugin_with_args<Class>)
  TYLMP_STYLE_LIST
#undef TYLMP_PAIR
#undef TYLMP_FIX
#undef TYLMP_COMPUTE
#undef TYLMP_PLUGIN
}
