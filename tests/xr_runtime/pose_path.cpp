#include "pose_path.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <stdexcept>
#include <string>

#include <nlohmann/json.hpp>

namespace ddish::xr_runtime {

namespace {

using nlohmann::json;

constexpr float kDegree = 0.017453292519943295f;

XrVector3f vec3(const json& j, const std::string& what) {
  if (!j.is_array() || j.size() != 3) throw std::runtime_error(what + " must be [x, y, z]");
  return {j[0].get<float>(), j[1].get<float>(), j[2].get<float>()};
}

XrQuaternionf quat(const json& j, const std::string& what) {
  if (!j.is_array() || j.size() != 4) throw std::runtime_error(what + " must be [x, y, z, w]");
  XrQuaternionf q{j[0].get<float>(), j[1].get<float>(), j[2].get<float>(), j[3].get<float>()};
  const float n = std::sqrt(q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w);
  if (!(n > 1e-6f)) throw std::runtime_error(what + " is not a rotation");
  return {q.x / n, q.y / n, q.z / n, q.w / n};
}

XrFovf fov_deg(const json& j, const std::string& what) {
  XrFovf f{j.at("left").get<float>() * kDegree, j.at("right").get<float>() * kDegree,
           j.at("up").get<float>() * kDegree, j.at("down").get<float>() * kDegree};
  if (!(f.angleLeft < f.angleRight && f.angleDown < f.angleUp))
    throw std::runtime_error(what + " needs left < right and down < up");
  return f;
}

XrQuaternionf nlerp(XrQuaternionf a, XrQuaternionf b, float t) {
  const float dot = a.x * b.x + a.y * b.y + a.z * b.z + a.w * b.w;
  const float s = dot < 0.0f ? -1.0f : 1.0f;  // the shorter way round
  XrQuaternionf q{a.x + t * (s * b.x - a.x), a.y + t * (s * b.y - a.y), a.z + t * (s * b.z - a.z),
                  a.w + t * (s * b.w - a.w)};
  const float n = std::sqrt(q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w);
  return {q.x / n, q.y / n, q.z / n, q.w / n};
}

XrVector3f rotate(const XrQuaternionf& q, const XrVector3f& v) {
  // v' = v + 2 w (u x v) + 2 u x (u x v), u = (x, y, z)
  const XrVector3f u{q.x, q.y, q.z};
  const XrVector3f c{u.y * v.z - u.z * v.y, u.z * v.x - u.x * v.z, u.x * v.y - u.y * v.x};
  const XrVector3f cc{u.y * c.z - u.z * c.y, u.z * c.x - u.x * c.z, u.x * c.y - u.y * c.x};
  return {v.x + 2.0f * (q.w * c.x + cc.x), v.y + 2.0f * (q.w * c.y + cc.y),
          v.z + 2.0f * (q.w * c.z + cc.z)};
}

}  // namespace

Script Script::load(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read the pose script " + path.string());
  Script s;
  try {
    const json j = json::parse(in);
    s.eye_width = j.value("eye_width", s.eye_width);
    s.eye_height = j.value("eye_height", s.eye_height);
    s.ipd = j.value("ipd", s.ipd);
    s.display_hz = j.value("display_hz", s.display_hz);
    s.synchronized_frames = j.value("synchronized_frames", s.synchronized_frames);
    s.record_images = j.value("record_images", s.record_images);
    if (j.contains("stop_after")) s.stop_after = j["stop_after"].get<int>();
    if (j.contains("loss_after")) s.loss_after = j["loss_after"].get<int>();
    if (j.contains("fov_deg")) {
      s.fov[0] = fov_deg(j["fov_deg"].at("left"), "fov_deg.left");
      s.fov[1] = fov_deg(j["fov_deg"].at("right"), "fov_deg.right");
    }
    for (const json& k : j.value("keys", json::array())) {
      PoseKey key;
      key.frame = k.at("frame").get<int>();
      if (k.contains("position")) key.position = vec3(k["position"], "position");
      if (k.contains("orientation")) key.orientation = quat(k["orientation"], "orientation");
      if (k.contains("display_hz")) key.display_hz = k["display_hz"].get<double>();
      if (!s.keys.empty() && key.frame <= s.keys.back().frame)
        throw std::runtime_error("keys must have increasing frames");
      s.keys.push_back(key);
    }
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error("pose script " + path.string() + ": " + e.what());
  } catch (const std::runtime_error& e) {
    throw std::runtime_error("pose script " + path.string() + ": " + e.what());
  }
  if (s.eye_width < 1 || s.eye_height < 1 || s.eye_width > 4096 || s.eye_height > 4096 ||
      !(s.ipd >= 0.0f) || !(s.display_hz > 0.0) || s.synchronized_frames < 0)
    throw std::runtime_error("pose script " + path.string() +
                             ": eye size 1..4096, ipd >= 0, display_hz > 0, synchronized_frames >= 0");
  for (const PoseKey& k : s.keys)
    if (k.display_hz && !(*k.display_hz > 0.0))
      throw std::runtime_error("pose script " + path.string() + ": display_hz must be positive");
  return s;
}

XrPosef Script::head(int frame) const {
  if (keys.empty()) return {{0.0f, 0.0f, 0.0f, 1.0f}, {0.0f, 0.0f, 0.0f}};
  if (frame <= keys.front().frame) return {keys.front().orientation, keys.front().position};
  if (frame >= keys.back().frame) return {keys.back().orientation, keys.back().position};
  const auto next = std::upper_bound(keys.begin(), keys.end(), frame,
                                     [](int f, const PoseKey& k) { return f < k.frame; });
  const PoseKey& b = *next;
  const PoseKey& a = *(next - 1);
  const float t = float(frame - a.frame) / float(b.frame - a.frame);
  const XrVector3f p{a.position.x + t * (b.position.x - a.position.x),
                     a.position.y + t * (b.position.y - a.position.y),
                     a.position.z + t * (b.position.z - a.position.z)};
  return {nlerp(a.orientation, b.orientation, t), p};
}

XrDuration Script::period_ns(int frame) const {
  double hz = display_hz;
  for (const PoseKey& k : keys)
    if (k.frame <= frame && k.display_hz) hz = *k.display_hz;
  return static_cast<XrDuration>(std::llround(1e9 / hz));
}

XrPosef eye_pose(const XrPosef& head, float ipd, int eye) {
  const float side = eye == 0 ? -0.5f : 0.5f;
  const XrVector3f offset = rotate(head.orientation, {side * ipd, 0.0f, 0.0f});
  return {head.orientation,
          {head.position.x + offset.x, head.position.y + offset.y, head.position.z + offset.z}};
}

}  // namespace ddish::xr_runtime
