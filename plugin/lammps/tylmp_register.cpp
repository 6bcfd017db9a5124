// Registration of all tylmp styles into a running LAMMPS.
//
// Debian's LAMMPS has no PLUGIN package, so the styles are inserted directly into the
// public creator maps (Force::pair_map, Modify::fix_map, Modify::compute_map) by
// tylmp_register(), which python/tylmp/__init__.py calls through ctypes. lammpsplugin_init()
// offers the same styles to `plugin load` in LAMMPS builds of the same version that have
// PLUGIN.

#include "tylmp_styles.h"

#include "error.h"
#include "force.h"
#include "lammps.h"
#include "lammpsplugin.h"
#include "modify.h"
#include "version.h"

#include <string>

using namespace LAMMPS_NS;

// Only the entry points below leave the library (CMake builds it with hidden visibility):
// LAMMPS 4 Feb 2025 has a built-in LAMMPS_NS::FixDampingCundall, and an exported class of the
// same name would be bound to the other library's constructor and virtual table.
#define TYLMP_EXPORT __attribute__((visibility("default")))
#define TYLMP_STRINGIFY2(x) #x
#define TYLMP_STRINGIFY(x) TYLMP_STRINGIFY2(x)

// The LAMMPS version (YYYYMMDD) this library is compiled against: a build runs only in that
// LAMMPS (class layouts and virtual tables differ between versions). The tag is also a string
// in the file, which python/tylmp/__init__.py reads before loading the library.
extern "C" TYLMP_EXPORT const char tylmp_lammps_version_tag[] =
    "tylmp-lammps-version=" TYLMP_STRINGIFY(TYLMP_LAMMPS_VERSION);

extern "C" TYLMP_EXPORT int tylmp_lammps_version()
{
  return TYLMP_LAMMPS_VERSION;
}

namespace {

template <typename T> Pair *create_pair(LAMMPS *lmp)
{
  return new T(lmp);
}
template <typename T> Fix *create_fix(LAMMPS *lmp, int narg, char **arg)
{
  return new T(lmp, narg, arg);
}
template <typename T> Compute *create_compute(LAMMPS *lmp, int narg, char **arg)
{
  return new T(lmp, narg, arg);
}
template <typename T> void *plugin_pair(void *lmp)
{
  return new T((LAMMPS *) lmp);
}
template <typename T> void *plugin_with_args(void *lmp, int narg, char **arg)
{
  return new T((LAMMPS *) lmp, narg, arg);
}

}    // namespace

extern "C" TYLMP_EXPORT int tylmp_register(void *handle)
{
  auto lmp = static_cast<LAMMPS *>(handle);
  // (num_ver sits at the same place in the LAMMPS class of every supported version)
  if (lmp->num_ver != TYLMP_LAMMPS_VERSION) return -1;
  int count = 0;
#define TYLMP_PAIR(style_name, Class)                        \
  (*lmp->force->pair_map)[style_name] = &create_pair<Class>; \
  ++count;
#define TYLMP_FIX(style_name, Class)                        \
  (*lmp->modify->fix_map)[style_name] = &create_fix<Class>; \
  ++count;
#define TYLMP_COMPUTE(style_name, Class)                            \
  (*lmp->modify->compute_map)[style_name] = &create_compute<Class>; \
  ++count;
  TYLMP_STYLE_LIST
#undef TYLMP_PAIR
#undef TYLMP_FIX
#undef TYLMP_COMPUTE
  return count;
}

extern "C" TYLMP_EXPORT void lammpsplugin_init(void *lmp, void *handle, void *regfunc)
{
  auto reg = (lammpsplugin_regfunc) regfunc;
  auto host = static_cast<LAMMPS *>(lmp);
  if (host->num_ver != TYLMP_LAMMPS_VERSION)
    host->error->all(FLERR,
                     std::string("plugin load: this tylmp library was built for LAMMPS ") +
                         LAMMPS_VERSION + " (" TYLMP_STRINGIFY(TYLMP_LAMMPS_VERSION) "), " +
                         "not for this LAMMPS " + host->version + ": build tylmp " +
                         "against this LAMMPS (README, Install) and load that build");
  lammpsplugin_t plugin;
  plugin.version = LAMMPS_VERSION;
  plugin.author = "tylmp developers";
  plugin.handle = handle;
#define TYLMP_PLUGIN(kind, style_name, member, factory_type, factory) \
  plugin.style = kind;                                                \
  plugin.name = style_name;                                           \
  plugin.info = "tylmp " kind " " style_name;                         \
  plugin.creator.member = (factory_type *) &factory;                  \
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
