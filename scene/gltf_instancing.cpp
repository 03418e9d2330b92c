// EXT_mesh_gpu_instancing: a node's TRANSLATION, ROTATION and SCALE accessors place its mesh once
// per element. Each element becomes a child SceneNode of the node (so an animation of the node
// moves every copy) carrying the element's transform, and one Instance: the BLAS is still one
// per mesh, the copies are TLAS instances like those of any other shared mesh.
#include <cmath>

#include "core/log.h"
#include "scene/gltf_internal.h"

namespace rayster::scene::gltf {

Result<std::vector<SceneNode>> gpuInstances(const tinygltf::Model& model, const tinygltf::Node& node, size_t index,
                                            const std::string& file) {
  std::vector<SceneNode> out;
  auto it = node.extensions.find("EXT_mesh_gpu_instancing");
  if (it == node.extensions.end()) return out;
  const std::string path = fmt::format("nodes[{}].extensions.EXT_mesh_gpu_instancing", index);
  if (!it->second.IsObject() || !it->second.Has("attributes") || !it->second.Get("attributes").IsObject())
    return bad(file, "{}.attributes is required (an object)", path);
  const tinygltf::Value& attributes = it->second.Get("attributes");
  auto accessorOf = [&](const char* name) -> Result<int> {
    if (!attributes.Has(name)) return -1;
    const tinygltf::Value& v = attributes.Get(name);
    if (!v.IsInt() || v.GetNumberAsInt() < 0 || size_t(v.GetNumberAsInt()) >= model.accessors.size())
      return bad(file, "{}.attributes.{} names no accessor", path, name);
    return v.GetNumberAsInt();
  };
  Result<int> t = accessorOf("TRANSLATION"), r = accessorOf("ROTATION"), s = accessorOf("SCALE");
  if (!t) return t.error();
  if (!r) return r.error();
  if (!s) return s.error();
  std::vector<glm::vec3> translations, scales;
  std::vector<glm::vec4> rotations;
  size_t count = 0;
  bool first = true;
  auto checkCount = [&](size_t n, const char* name) -> Status {
    if (!first && n != count) return bad(file, "{}.attributes.{} has {} elements, the others {}", path, name, n, count);
    count = n, first = false;
    return okStatus();
  };
  if (*t >= 0) {
    auto v = readVec3(model, *t, file);
    if (!v) return v.error();
    translations = std::move(*v);
    RAYSTER_TRY(checkCount(translations.size(), "TRANSLATION"));
  }
  if (*r >= 0) {
    auto v = readVec4(model, *r, file);
    if (!v) return v.error();
    rotations = std::move(*v);
    RAYSTER_TRY(checkCount(rotations.size(), "ROTATION"));
  }
  if (*s >= 0) {
    auto v = readVec3(model, *s, file);
    if (!v) return v.error();
    scales = std::move(*v);
    RAYSTER_TRY(checkCount(scales.size(), "SCALE"));
  }
  if (first)  // only custom attributes (_ID, …): nothing places copies, the node draws its mesh once
    return out;
  out.resize(count);
  for (size_t i = 0; i < count; ++i) {
    SceneNode& n = out[i];
    n.name = fmt::format("{}#{}", node.name.empty() ? fmt::format("node{}", index) : node.name, i);
    if (!translations.empty()) n.translation = translations[i];
    if (!scales.empty()) n.scale = scales[i];
    if (!rotations.empty()) {
      const glm::vec4 q = rotations[i];  // x, y, z, w as glTF stores it
      glm::quat rotation(q.w, q.x, q.y, q.z);
      const float length = glm::length(rotation);
      if (!(length > 0.0f) || !std::isfinite(length)) return bad(file, "{}: ROTATION {} is not a rotation", path, i);
      n.rotation = rotation / length;
    }
    const glm::mat4 m = n.parentFromNode();
    for (int c = 0; c < 4; ++c)
      for (int k = 0; k < 4; ++k)
        if (!std::isfinite(m[c][k])) return bad(file, "{}: instance {} has a non-finite transform", path, i);
  }
  return out;
}

}  // namespace rayster::scene::gltf
