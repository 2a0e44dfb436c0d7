// Opens the OpenImageIO plugin module (liberpt_oiio.so) on first use, once per process.
// It is looked for where the build put it, then beside the running executable.
#include <dlfcn.h>
#include <unistd.h>

#include <filesystem>
#include <mutex>

#include "image_formats.h"
#include "oiio/oiio_module.h"

namespace erpt::image_formats {

namespace {

struct LoadedModule {
  const OiioModuleApi* api = nullptr;
  std::string error;
};

const LoadedModule& oiioModule() {
  static LoadedModule loaded;
  static std::once_flag once;
  std::call_once(once, [] {
    std::vector<std::string> candidates{ERPT_OIIO_MODULE_PATH};
    std::error_code ec;
    const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
    if (!ec) candidates.push_back((exe.parent_path() / "liberpt_oiio.so").string());
    // Beside the library this code is in: an installed Python package carries both files
    // (scripts/install-python.sh), and the build directory may be gone.
    Dl_info self{};
    if (dladdr(reinterpret_cast<const void*>(&oiioModule), &self) && self.dli_fname)
      candidates.push_back((std::filesystem::path(self.dli_fname).parent_path() / "liberpt_oiio.so").string());
    std::string errors;
    for (const std::string& path : candidates) {
      void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
      if (!handle) {
        errors += (errors.empty() ? "" : "; ") + std::string(dlerror());
        continue;
      }
      auto entry = reinterpret_cast<const OiioModuleApi* (*)()>(dlsym(handle, "erptOiioModule"));
      const OiioModuleApi* api = entry ? entry() : nullptr;
      if (api && api->version == kOiioModuleVersion) {
        loaded.api = api;
        return;
      }
      errors += (errors.empty() ? "" : "; ") + path + " is not this version's OpenImageIO module";
      dlclose(handle);
    }
    loaded.error = "the OpenImageIO module cannot be loaded (" + errors + ")";
  });
  return loaded;
}

}  // namespace

bool readWithOiio(const std::string& path, RgbImage& image, bool& isSrgb, std::string& error) {
  const LoadedModule& m = oiioModule();
  if (!m.api) {
    error = m.error;
    return false;
  }
  return m.api->read(path.c_str(), image, isSrgb, error);
}

bool writeWithOiio(const std::string& path, int width, int height, bool isFloat, const void* pixels, std::string& error) {
  const LoadedModule& m = oiioModule();
  if (!m.api) {
    error = m.error;
    return false;
  }
  return m.api->write(path.c_str(), width, height, isFloat, pixels, error);
}

}  // namespace erpt::image_formats
