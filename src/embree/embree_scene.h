// An Embree scene on the process's Embree device: what the renderer
// (pictures) and the printability check (sculpture) build their ray and collision queries
// on. Header-only and in no layer's folder, so that both layers share it without one
// depending on the other; each links Embree itself. Internal to the library.
#pragma once

#include "meander/error.h"
#include "meander/mesh.h"

#include <embree3/rtcore.h>

#include <memory>
#include <span>
#include <string>
#include <string_view>

namespace meander {

class EmbreeScene {
public:
  // A scene on the process's one device; `user` names the caller if Embree cannot start.
  EmbreeScene(std::string_view user, RTCSceneFlags flags, RTCBuildQuality quality) : user_(user) {
    device_.reset(shared_device());
    if (!device_) throw Error(user_ + ": cannot start Embree (error " + std::to_string(rtcGetDeviceError(nullptr)) + ")");
    rtcRetainDevice(device());
    scene_.reset(rtcNewScene(device()));
    rtcSetSceneFlags(scene(), flags);
    rtcSetSceneBuildQuality(scene(), quality);
  }

  RTCDevice device() const { return device_.get(); }
  RTCScene scene() const { return scene_.get(); }

  // Commits `geometry`, attaches it and lets the scene hold the only reference to it.
  // Returns its geometry id.
  unsigned attach(RTCGeometry geometry) {
    rtcCommitGeometry(geometry);
    const unsigned id = rtcAttachGeometry(scene(), geometry);
    rtcReleaseGeometry(geometry);
    return id;
  }

  // Builds the scene's tree, after every geometry is attached.
  void commit() {
    rtcCommitScene(scene());
    throw_if_failed();
  }

  // Throws Error if an Embree call on the device failed since the last check (a tree
  // that could not be built, for want of memory, would otherwise find nothing).
  void throw_if_failed() const {
    if (const RTCError error = rtcGetDeviceError(device()); error != RTC_ERROR_NONE)
      throw Error(user_ + ": Embree failed (error " + std::to_string(int(error)) + ")");
  }

private:
  // Made once and kept for the process: a device costs far more to make than a small
  // scene (a brute-force check of 180,000 two-triangle meshes spent its time there), and
  // rtcCollide takes two scenes of one device. Errors are kept per thread on it.
  static RTCDevice shared_device() {
    static const RTCDevice device = rtcNewDevice(nullptr);
    return device;
  }

  struct DeviceRelease {
    void operator()(RTCDevice d) const { rtcReleaseDevice(d); }
  };
  struct SceneRelease {
    void operator()(RTCScene s) const { rtcReleaseScene(s); }
  };
  std::string user_;
  std::unique_ptr<RTCDeviceTy, DeviceRelease> device_; // declared before the scene, released after it
  std::unique_ptr<RTCSceneTy, SceneRelease> scene_;
};

// Gives a triangle geometry its vertices: a copy in a buffer of Embree's, which pads it as
// its vector loads need (a shared buffer of Vec3 would end 4 bytes short).
inline void set_vertices(RTCGeometry geometry, std::span<const Vec3> positions) {
  auto* vertices = static_cast<float*>(
      rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), positions.size()));
  for (size_t v = 0; v < positions.size(); ++v) {
    vertices[3 * v] = positions[v].x;
    vertices[3 * v + 1] = positions[v].y;
    vertices[3 * v + 2] = positions[v].z;
  }
}

} // namespace meander
