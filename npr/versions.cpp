#include "npr/versions.h"

#include <embree3/rtcore.h>

#include <OpenMesh/Core/System/config.h>
#include <nanoflann.hpp>
#include <string>

namespace sylva {

namespace {

// The loaded Embree's version, from a device made for the purpose (MMmmpp, e.g. 31305).
std::string embree_version() {
  RTCDevice device = rtcNewDevice(nullptr);
  if (device == nullptr) return "unavailable: no Embree device";
  const long v = static_cast<long>(rtcGetDeviceProperty(device, RTC_DEVICE_PROPERTY_VERSION));
  rtcReleaseDevice(device);
  return std::to_string(v / 10000) + "." + std::to_string(v / 100 % 100) + "." +
         std::to_string(v % 100);
}

// OpenMesh's OM_VERSION is 0xMMmmpp, nanoflann's NANOFLANN_VERSION 0xMmp.
std::string hex_version(int v, int bits) {
  const int mask = (1 << bits) - 1;
  return std::to_string(v >> (2 * bits)) + "." + std::to_string((v >> bits) & mask) + "." +
         std::to_string(v & mask);
}

}  // namespace

std::vector<LibraryVersion> npr_library_versions() {
  return {{"Embree", embree_version()},
          {"OpenMesh", hex_version(OM_VERSION, 8) + " (build)"},
          {"nanoflann", hex_version(NANOFLANN_VERSION, 4) + " (build)"},
          {"OpenMP", "spec " + std::to_string(_OPENMP) + " (build)"}};
}

}  // namespace sylva
