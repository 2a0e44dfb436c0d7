// Each integrator's own data, held by type: RenderSettings and RenderStats carry what every
// integrator shares, and an integrator's settings and statistics structs (ErptSettings,
// PmcStats, ...) live here, declared in the integrator's own header. A struct not set yet
// reads as its defaults; copying the holder copies the structs (a sub-render's changes stay
// its own).
#pragma once

#include <any>
#include <map>
#include <typeindex>

namespace erpt {

class PerIntegrator {
 public:
  template <class T>
  T& get() {
    auto it = values_.find(std::type_index(typeid(T)));
    if (it == values_.end()) it = values_.emplace(std::type_index(typeid(T)), std::any(T{})).first;
    return *std::any_cast<T>(&it->second);
  }
  template <class T>
  const T& get() const {
    const auto it = values_.find(std::type_index(typeid(T)));
    if (it == values_.end()) {
      static const T defaults{};
      return defaults;
    }
    return *std::any_cast<T>(&it->second);
  }

 private:
  std::map<std::type_index, std::any> values_;
};

}  // namespace erpt
