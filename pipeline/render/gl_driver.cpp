#include "pipeline/render/gl_driver.hpp"

#include <dlfcn.h>
#include <link.h>

#include <mutex>
#include <set>

namespace ligsim::render {

std::vector<std::string> loaded_gl_drivers()
{
  std::vector<std::string> drivers;
  dl_iterate_phdr(
      [](dl_phdr_info* module, size_t, void* found) {
        const std::string path = module->dlpi_name ? module->dlpi_name : "";
        const std::string suffix = "_dri.so";
        if (path.size() > suffix.size() &&
            path.compare(path.size() - suffix.size(), suffix.size(), suffix) == 0)
          static_cast<std::vector<std::string>*>(found)->push_back(path);
        return 0;
      },
      &drivers);
  return drivers;
}

void keep_gl_drivers_loaded()
{
  static std::mutex mutex;
  static std::set<std::string> kept;
  const std::lock_guard<std::mutex> lock(mutex);
  // Outside dl_iterate_phdr, which holds the loader's lock. The handle is never closed: that
  // reference, and RTLD_NODELETE, are the point.
  for (const std::string& driver : loaded_gl_drivers())
    if (kept.insert(driver).second)
      dlopen(driver.c_str(), RTLD_LAZY | RTLD_NOLOAD | RTLD_NODELETE);
}

} // namespace ligsim::render
