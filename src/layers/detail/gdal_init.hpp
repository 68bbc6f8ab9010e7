#pragma once
// Registers GDAL's drivers once per process.
#include <gdal_priv.h>

#include <mutex>

namespace tw::detail {

inline void ensure_gdal_registered() {
  static std::once_flag once;
  std::call_once(once, [] { GDALAllRegister(); });
}

}  // namespace tw::detail
